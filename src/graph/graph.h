/* The render graph: passes in the order the script added them, named
 * outputs "pass.output", one final image. Compiling checks the order,
 * leaves out passes that contribute nothing, and allocates textures;
 * executing runs what the frame needs and times each pass. */
#ifndef CAUSTICA_GRAPH_H
#define CAUSTICA_GRAPH_H

#include <stdbool.h>

#include "core/error.h"
#include "graph/pass.h"

struct renderer;
struct scene;

enum graph_pass_state { GRAPH_PASS_KEPT, GRAPH_PASS_PRUNED };

struct graph_entry {
    struct pass *pass;                     /* borrowed (Lua owns the pass) */
    enum graph_pass_state state;
    char reason[256];                      /* why it was left out */
    int input_resources[PASS_MAX_INPUTS];  /* indices into resources, -1 if none */
    int output_resources[PASS_MAX_OUTPUTS];
    /* last frame: what happened and how long it took */
    enum pass_need last_need;
    char last_why[256];
    double last_ms;
    long last_draws, last_triangles; /* object draws the pass made (renderer_draw_objects) */
    GLuint queries[2]; /* GL_TIMESTAMP before and after */
    uint64_t reuse_key; /* what its outputs were made from, for passes with `depends` */
    bool reuse_valid;   /* its outputs hold what reuse_key says (cleared by compile, skip, error) */
};

struct graph {
    struct graph_entry *entries;
    int count, capacity;
    char output[RESOURCE_NAME_MAX];
    char output_where[256]; /* "script.lua:12: " where the script named the output ("" when unknown) */
    bool executing;       /* inside graph_execute: frozen */
    /* compiled */
    bool compiled;
    struct graph_resource *resources; /* owned, with their textures */
    int resource_count;
    int output_resource;
    int width, height;
};

void graph_init(struct graph *g);
/* Releases textures, queries and the graph's references to its passes;
 * leaves it empty (safe to call twice). */
void graph_release(struct graph *g);
bool graph_add(struct graph *g, const char *name, struct pass *pass, struct error *err);
bool graph_set_output(struct graph *g, const char *name, struct error *err);
/* Order check and pruning only: no GL needed (used by tests and `info`). */
bool graph_check(struct graph *g, struct error *err);
/* graph_check, then textures at width x height and pass creation. */
bool graph_compile(struct graph *g, struct renderer *r, int width, int height, struct error *err);
/* Runs one frame (the renderer's frame set-up must have happened). */
bool graph_execute(struct graph *g, struct renderer *r, struct scene *scene, int frame, double time,
                   struct error *err);
struct graph_resource *graph_output(struct graph *g);
struct graph_resource *graph_find_resource(struct graph *g, const char *name);

#endif
