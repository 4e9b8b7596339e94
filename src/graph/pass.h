/* A render pass: a descriptor (what `c.pass.<name>` creates, with its
 * parameters, inputs and outputs) and instances made from it by scripts.
 * A pass is one C file in src/passes plus shaders/<name>/; adding one means
 * writing the descriptor and listing it in pass_registry.c. */
#ifndef CAUSTICA_PASS_H
#define CAUSTICA_PASS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_texture.h"

struct renderer;
struct scene;
struct light;
struct pass;

enum pass_param_type {
    PASS_PARAM_NUMBER,
    PASS_PARAM_INTEGER,
    PASS_PARAM_BOOLEAN,
    PASS_PARAM_STRING,
    PASS_PARAM_ENUM,       /* a string from `choices` ("a|b|c") */
    PASS_PARAM_LIGHT,      /* a light of the scene */
    PASS_PARAM_OBJECT,     /* an object of the scene */
    PASS_PARAM_OBJECT_LIST,/* {object, ...}: objects of the scene */
    PASS_PARAM_INPUT,      /* "pass.output": a texture made by an earlier pass */
    PASS_PARAM_INPUT_LIST, /* one such name or a list of them */
    PASS_PARAM_COLOR,      /* {r, g, b[, a]} */
    PASS_PARAM_INPUT_MAP,  /* {slot = "pass.output", ...}: named inputs (user passes) */
    PASS_PARAM_OUTPUT_MAP, /* {name = "rgba32f", ...} or {"name", ...}: named outputs (user passes) */
    PASS_PARAM_UNIFORM_MAP,/* {name = number or {x, y[, z[, w]]}, ...} */
    PASS_PARAM_TABLE,      /* a Lua table kept by reference (custom passes) */
    PASS_PARAM_FUNCTION,   /* a Lua function kept by reference (custom passes) */
};

/* A record a resource carries (issue 54): a struct its producer owns,
 * named by one static descriptor per type, defined by the module that owns
 * the struct (LAYER_SET_RECORD in passes/helpers/layers.c, SHADOW_MAP_RECORD in
 * passes/helpers/shadow_inputs.c) and compared by pointer, never by its name.
 * A reader gets it through pass_frame_record, which graph_check has made
 * safe: a connected input is of the type its descriptor asks for. What the
 * reader gets is the producer's: valid from the producer's execute in this
 * frame until the producer's next execute or release; a reader uses it
 * within its own execute and keeps no pointer into it. */
struct record_type {
    const char *name; /* for messages, `help` and `info` ("layer_set") */
};

/* What a graph resource is: a texture the graph allocates (which may also
 * carry a record: a shadow map's light matrix), or a record alone (a
 * light's layer set), which has no texture. */
enum resource_kind { RESOURCE_TEXTURE, RESOURCE_RECORD };

struct pass_param_desc {
    const char *name;
    enum pass_param_type type;
    double default_number; /* number, integer, boolean (0/1) */
    double min, max;       /* number, integer: accepted range; an input list: max = the most items */
    int multiple;          /* integer: > 0, the value must be a multiple of it (checked here, once) */
    const char *default_string; /* string/enum default; NULL = none */
    const char *choices;   /* enum: "a|b|c" */
    bool required;
    bool is_path; /* string: a file path, resolved against the script's folder */
    /* input: when the script gives none, read output `default_output` of
     * the pass that makes input `default_beside` (refraction's depth is the
     * depth of the pass that made its colour). */
    const char *default_beside, *default_output;
    /* input: the building block (a registered pass, e.g. "receivers") the
     * graph adds and shares when the script names none (issue 26); its
     * parameters come from the reader's `configure_block`. */
    const char *block;
    /* input: the record alone it must be (&LAYER_SET_RECORD); NULL: a texture */
    const struct record_type *bundle;
    /* input (a texture): the record it must carry besides its texels
     * (&SHADOW_MAP_RECORD: a shadow map's light matrix), as its producer
     * declares it (pass_output_decl.record); checked with the graph, not
     * each frame */
    const struct record_type *record;
    /* boolean: building blocks that differ only in this are one block with
     * it on (the receivers' `position`: one G-buffer serves both readers) */
    bool merge_or;
    const char *help;
};

struct pass_value {
    bool set;
    double number;         /* number, integer, boolean (0/1), enum (index into choices) */
    char *string;          /* owned */
    struct light *light;   /* borrowed (Lua keeps it alive) */
    struct object *object; /* borrowed (Lua keeps it alive) */
    struct object **objects; /* an object list: a reference each (owned array) */
    int object_count;
    float color[4];
    char **list;           /* owned strings: an input list, or a map's values */
    char **keys;           /* owned strings: a map's keys (same count as list) */
    float (*vectors)[4];   /* uniform map values */
    int *vector_sizes;
    int list_count;
    int lua_ref;           /* table/function in the Lua registry, or -1 */
};

#define PASS_MAX_INPUTS 16
#define PASS_MAX_OUTPUTS 8
#define PASS_NAME_MAX 64
#define RESOURCE_NAME_MAX 160

struct pass_input_decl {
    char name[PASS_NAME_MAX];        /* the slot, e.g. "shadow" */
    char source[RESOURCE_NAME_MAX];  /* "pass.output" */
};

struct pass_output_decl {
    char name[PASS_NAME_MAX];
    enum resource_kind kind;
    /* RESOURCE_RECORD: the record's type (the producer points the
     * resource's `record` at one); RESOURCE_TEXTURE: the record it carries
     * besides its texels (pass_declare_output_record), or NULL */
    const struct record_type *record;
    GLenum format;
    GLenum target;   /* GL_TEXTURE_2D or GL_TEXTURE_CUBE_MAP */
    int width, height; /* 0: the frame's size */
};

/* A texture in the graph ("pass.output") and what its producer says about
 * it: a shadow map's light-space matrix, the light it belongs to. */
struct graph_resource {
    char name[RESOURCE_NAME_MAX];
    struct pass_output_decl decl; /* its kind and record type */
    struct gl_texture texture; /* a texture's (none for a record alone) */
    /* the record of decl.record's type, owned by its producer, which sets
     * it in its execute (NULL: not made this frame); read through
     * pass_frame_record */
    void *record;
    uint64_t version;          /* bumped each time its producer runs (what readers' reuse keys hold) */
    int producer;      /* index of the pass in the graph */
};

/* What a pass sees while it runs. */
struct frame;

struct pass_frame {
    struct renderer *renderer;
    struct scene *scene;
    const struct frame *snapshot; /* this frame's lights, matrices, objects (graph/frame.h) */
    int width, height;
    int frame;
    double time;
    struct graph_resource *inputs[PASS_MAX_INPUTS];   /* by declaration order, NULL if absent */
    struct graph_resource *outputs[PASS_MAX_OUTPUTS];
};

enum pass_need { PASS_RUN, PASS_REUSE, PASS_SKIP };

/* Reuse by version, the one key (issue 26): what a pass made something
 * from: its parameters (a light or object by identity and version), the
 * frame's size, and what `depends` names of the camera, the geometry, the
 * lights and its inputs' versions. The graph keys a whole pass's outputs
 * with it (descriptor's `depends` plus the inputs); a pass keys a part that
 * depends on less (photon_caustics' light-side textures: not the camera)
 * with the same function, mixing in values it computes (a centre, a range)
 * with pass_key_mix. */
uint64_t pass_frame_key(const struct pass *p, const struct pass_frame *f, unsigned depends);
uint64_t pass_key_mix(uint64_t key, const void *data, size_t size);
/* Whether what was made under `made_key` (when `made`) stands for `key`:
 * equal keys, and no visible geometry animates this frame (an animated
 * mesh changes without a version). */
bool pass_frame_reusable(const struct pass_frame *f, bool made, uint64_t made_key, uint64_t key);

/* The comparison a technique joins (issue 54), by what it plugs into: the
 * optics matrix lists every registered technique of a family (as "not
 * measured" until it is given bounds there), the comparison scenes add it
 * to `bench --sweep technique=all`, and `help` names its family. */
enum pass_technique {
    PASS_TECHNIQUE_NONE,           /* a building block, a script's own, a helper of the image */
    PASS_TECHNIQUE_CAUSTICS,       /* takes `light` (nothing else required) and makes `irradiance` for shade's
                                    * `caustics` */
    PASS_TECHNIQUE_WATER_CAUSTICS, /* the same, from the water surface its `water` names */
    PASS_TECHNIQUE_VIEW,           /* draws glass and water over `color` (with `depth`), nothing else required */
    PASS_TECHNIQUE_WATER_VIEW,     /* draws the water surface its `water` names over `color` */
};

/* "caustics", "water_caustics", "view", "water_view" (NULL for none). */
const char *pass_technique_name(enum pass_technique technique);

struct pass_desc {
    const char *name;
    const char *summary;
    enum pass_technique technique; /* the comparison it joins (PASS_TECHNIQUE_NONE: none) */
    const struct pass_param_desc *params;
    int param_count;
    /* Declares inputs and outputs from the parameter values. */
    bool (*declare)(struct pass *p, struct error *err);
    /* Allocates what does not depend on the frame (programs, framebuffers). */
    bool (*create)(struct pass *p, struct renderer *r, struct error *err);
    bool (*execute)(struct pass *p, struct pass_frame *f, struct error *err);
    /* Does this frame need the pass? REUSE keeps last frame's outputs.
     * NULL means it always runs. `why` explains a REUSE or SKIP. */
    enum pass_need (*needed)(struct pass *p, struct pass_frame *f, char *why, size_t whylen);
    void (*destroy)(struct pass *p);
    /* What of the scene the pass cannot handle: NULL where it handles
     * object o of `scene` as the scene stands (its camera, say), else what it leaves out, in
     * words ("no caustics through it: ..."). graph_lint prints one warning
     * per pass and object, so nothing renders dark without a line saying
     * why (issue 27). NULL: the pass handles every object. */
    const char *(*leaves_out)(const struct pass *p, const struct scene *scene, const struct object *o);
    /* A caustics pass that carries light through the refractors onto
     * surfaces only: in a scene with a participating medium, the light it
     * bends and the medium scatters (volume caustics, the shafts under a
     * glass ball in fog) is drawn by no pass unless one that makes them is
     * in the graph too (`volume_caustics`); graph_lint says so, naming the
     * refractors. */
    bool surface_caustics_only;
    /* Makes the light the refractors bend and a medium scatters (beam_caustics' inscatter). */
    bool volume_caustics;
    /* Shows what lies behind the glass it draws lit by its own lookups (a
     * distance map, impostors, slices), which carry no caustics: the
     * caustics passes' images are of the receivers the camera sees
     * directly. With the camera inside a refractor it draws, nothing it
     * shows has caustics (graph_lint says so). */
    bool behind_glass_without_caustics;
    /* Sets the parameters of the building block the graph adds for input
     * parameter `param` (one with `.block`): a depth-layer set for this
     * pass's light at its buffer size. NULL: the block's defaults. */
    bool (*configure_block)(const struct pass *p, int param, struct pass *block, struct error *err);
    /* Whether the pass reads the block of input parameter `param` (one with
     * `.block`) as its values stand: refraction reads the distance map only
     * for the lookups that use one, so the graph adds none for the others.
     * NULL: every block input is read. */
    bool (*reads_block)(const struct pass *p, int param);
    /* Which objects the pass draws into the image it makes (graph_lint's
     * "glass no pass draws"): a mask of OBJECT_ROLE_* (scene.h), or
     * PASS_DRAWS_ANYTHING. NULL: none (a pass that makes irradiance, depth
     * or layers). */
    unsigned (*draws)(const struct pass *p);
    /* The pass looks its `color` input up where rays leave the refractors
     * it draws, so an input that already shows them (shade { specular =
     * true }) shows them inside themselves: graph_lint warns. False for a
     * pass whose lookup steps over them (refraction's, sliced_refraction's:
     * measured within 0.8% and 0.04%). */
    bool color_behind_refractors;
    /* Reuse by version (issue 26): what of the frame the pass's outputs
     * depend on besides its parameters and inputs, a mask of PASS_DEPENDS_*.
     * The graph reuses last frame's outputs while none of it changed (and no
     * visible geometry animates). NULL: the pass decides (`needed`). */
    unsigned (*depends)(const struct pass *p);
};

#define PASS_DEPENDS_CAMERA 1u   /* the camera's view and projection */
#define PASS_DEPENDS_GEOMETRY 2u /* objects: added, removed, moved, shown, hidden, their materials */
#define PASS_DEPENDS_LIGHTS 4u   /* every light of the scene (a LIGHT parameter's own is always counted) */
#define PASS_DEPENDS_INPUTS 8u   /* its inputs' versions (the graph's key of a whole pass always has them) */

#define PASS_DRAWS_ANYTHING 0x100u /* the script's own (custom, fullscreen): may draw anything, not checked */

/* Named stages of one frame of a pass, timed with GL timestamps
 * (`--timings` prints them under the pass): pass_stage_begin, then
 * pass_stage_end("name") after each stage's commands. */
#define PASS_MAX_STAGES 12
struct pass_stages {
    int count;
    char names[PASS_MAX_STAGES][32];
    double ms[PASS_MAX_STAGES];
    GLuint queries[PASS_MAX_STAGES + 1];
};

struct pass {
    int references;            /* the Lua userdata's, and the graph's while it holds the pass */
    const struct pass_desc *desc;
    char name[PASS_NAME_MAX];  /* the name given to g:add */
    char origin[600];          /* "script.lua:12", where the script made it */
    struct pass_value *values; /* desc->param_count, owned */
    struct pass_input_decl inputs[PASS_MAX_INPUTS];
    int input_count;
    struct pass_output_decl outputs[PASS_MAX_OUTPUTS];
    int output_count;
    int declared_inputs;       /* inputs from the values; those after it were added by the graph */
    bool implicit;             /* a building block the graph added (not the script) */
    bool created;
    void *state;               /* owned by the pass's create/destroy */
    /* A pass that calls back into the script (custom): set by the bindings,
     * so that the pass needs nothing of the Lua layer above it. */
    bool (*script_run)(struct pass *p, struct pass_frame *f, struct error *err);
    void *script_state;        /* the bindings' (the lua_State) */
    struct pass_stages stages; /* the last frame's, empty for a pass that names none */
    char report[256];          /* a line about the last frame (beam counts, fill rate), printed by --timings */
};

void pass_stage_begin(struct pass *p);
void pass_stage_end(struct pass *p, const char *name);
/* Reads the stages' timestamps (after the frame: graph_execute calls it). */
void pass_stages_collect(struct pass *p);

/* Creation and release of instances (values filled by the Lua binding).
 * A light or object value holds a reference to it: set them with
 * pass_set_light / pass_set_object. */
struct pass *pass_create(const struct pass_desc *desc);
void pass_retain(struct pass *p);
/* Drops one reference; the last one destroys the pass's state and values. */
void pass_destroy(struct pass *p);
void pass_set_light(struct pass *p, int param, struct light *light);
void pass_set_object(struct pass *p, int param, struct object *object);
/* Replaces an object list (a reference to each); false when out of memory. */
bool pass_set_objects(struct pass *p, int param, struct object *const *objects, int count);

/* Setting parameters: the one place values are validated (type, finite,
 * integer, range, enum choice), used by the Lua bindings, `bench --sweep`
 * and the unit tests. False with "bad argument 'size' to 'shadow_map'
 * (0 is out of range 16..8192)" and the like. Enums are stored as their
 * index into `choices`. */
bool pass_set_number(struct pass *p, const char *name, double value, struct error *err);
bool pass_set_boolean(struct pass *p, const char *name, bool value, struct error *err);
bool pass_set_enum(struct pass *p, const char *name, const char *choice, struct error *err);
/* STRING and INPUT parameters (a path is stored as given: resolve it first). */
bool pass_set_string(struct pass *p, const char *name, const char *value, struct error *err);
/* By index: an input list (each item "pass.output", at most the
 * descriptor's max); a map (input and output maps: a string per key, the
 * source or the format; a uniform map: 1 to 4 finite numbers per key), in
 * the order given; a colour (finite). Each replaces the old value. */
bool pass_set_list(struct pass *p, int param, const char *const *items, int count, struct error *err);
bool pass_set_map(struct pass *p, int param, const char *const *keys, const char *const *values,
                  const float (*vectors)[4], const int *sizes, int count, struct error *err);
bool pass_set_color(struct pass *p, int param, vec3 color, struct error *err);

/* Reading them, by the parameter's index in the descriptor's `params`
 * (a pass names its indices with an enum and fills `params` with
 * designated initializers, so the two cannot drift apart): no lookup by
 * name and no cast in the frame loop. */
double pass_real(const struct pass *p, int param);
int pass_int(const struct pass *p, int param);
bool pass_flag(const struct pass *p, int param);
int pass_choice(const struct pass *p, int param); /* an enum's index into its choices */
const char *pass_text(const struct pass *p, int param); /* string/input, or its default (may be NULL) */
struct light *pass_light_at(const struct pass *p, int param);
struct object *pass_object_at(const struct pass *p, int param);

/* By name: for generic code (bindings, tools), not for passes. */
const struct pass_value *pass_value(const struct pass *p, const char *name);
int pass_param_index(const struct pass_desc *desc, const char *name);

/* Declares the pass's inputs and outputs from its values: every INPUT
 * parameter that is set (or has a default_beside) becomes an input slot of
 * its own name, then desc->declare adds the rest. Call after setting values. */
bool pass_declare(struct pass *p, struct error *err);

/* Used by declare(). */
bool pass_declare_input(struct pass *p, const char *slot, const char *source, struct error *err);
bool pass_declare_output(struct pass *p, const char *name, GLenum format, GLenum target, int width, int height,
                         struct error *err);
/* The same, for a texture that carries a record besides its texels
 * (&SHADOW_MAP_RECORD): inputs whose descriptor asks for that record
 * accept it, and no other texture. */
bool pass_declare_output_record(struct pass *p, const char *name, const struct record_type *record, GLenum format,
                                GLenum target, int width, int height, struct error *err);
/* A record alone (&LAYER_SET_RECORD), no texture: the pass owns it and
 * points its resource's `record` at it while it executes. */
bool pass_declare_bundle(struct pass *p, const char *name, const struct record_type *record, struct error *err);
/* Do two passes of one descriptor have the same values (lights and
 * objects by identity)? Booleans marked `merge_or` are ignored when
 * `ignore_merged`. For sharing building blocks. */
bool pass_values_equal(const struct pass *a, const struct pass *b, bool ignore_merged);
/* The resolved input for `slot` (NULL when the script gave none). */
struct graph_resource *pass_frame_input(const struct pass *p, struct pass_frame *f, const char *slot);
struct graph_resource *pass_frame_output(const struct pass *p, struct pass_frame *f, const char *name);
/* Input `slot`'s record, of `type` (NULL when the script gave none, or its
 * producer made none this frame: a shadow map of no light). graph_check
 * refused a connection of another type, so a mismatch here is a bug in
 * the pass's descriptor: NULL too, never another struct. */
void *pass_frame_record(const struct pass *p, struct pass_frame *f, const char *slot, const struct record_type *type);

/* The registry of descriptors (pass_registry.c). */
int pass_registry_count(void);
const struct pass_desc *pass_registry_get(int index);
const struct pass_desc *pass_registry_find(const char *name);

/* What a pass that treats every refractor as smooth, clear, whole glass
 * (and every mirror as smooth, flat and whole) leaves out of `o`: its
 * roughness, its diffuse share, its tint, its normal map, its alphaMode
 * holes or blending, for its leaves_out: `caustics` for a pass that carries
 * light through the glass, else for one that shows the view through it.
 * NULL when `o` has none of them or is neither glass nor a mirror. */
const char *pass_refractor_left_out(const struct object *o, bool caustics);

/* What a view technique that finds what lies behind a refractor's surfaces
 * (the image, a distance map, impostors, slices) leaves out of `o`: the
 * objects inside its solid glass or water (a pearl in a glass block, a
 * spoon in a glass of water), which only the reference sees through it;
 * then `other` (the pass's own reason, or NULL) after it. NULL when none
 * lies within (what lies in a hollow, as flowers in a vase, is behind its
 * inner surface and is found). For pass_desc.leaves_out. */
const char *pass_refractor_holds(const struct scene *scene, const struct object *o, const char *other);

#endif
