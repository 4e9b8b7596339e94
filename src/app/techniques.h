/* A comparison scene's techniques (the `techniques` table a scene script
 * returns, docs/LUA_API.md): which scene parameters select each technique,
 * and the settings of its own parameters that `caustica bench --sweep
 * technique=all` and `caustica choose` measure. */
#ifndef CAUSTICA_TECHNIQUES_H
#define CAUSTICA_TECHNIQUES_H

#include <stdbool.h>

#include "app/session.h"
#include "core/error.h"

#define TECHNIQUES_MAX 16
#define TECHNIQUE_POINTS_MAX 16
#define TECHNIQUE_ASSIGNMENTS_MAX 8

/* One setting of a technique: "pass.param" (a pass parameter) or "param" (a
 * scene parameter) = value. Point 0 is always the technique's defaults. */
struct technique_point {
    int count;
    char keys[TECHNIQUE_ASSIGNMENTS_MAX][64];
    char values[TECHNIQUE_ASSIGNMENTS_MAX][64];
};

struct technique {
    char name[64];
    int set_count; /* the scene parameters that select it ({technique = name} by default) */
    char set_keys[4][64];
    char set_values[4][64];
    int point_count;
    struct technique_point points[TECHNIQUE_POINTS_MAX];
};

enum technique_metric { TECHNIQUE_METRIC_CAUSTIC, TECHNIQUE_METRIC_IMAGE };

struct technique_list {
    enum technique_metric metric; /* the error the comparison ranks by */
    int count;
    struct technique items[TECHNIQUES_MAX];
};

/* Reads the returned table's `techniques`; false (with a message naming the
 * script and what to write) when it is missing or malformed. */
bool techniques_read(const struct session *s, struct technique_list *out, struct error *err);
/* Keeps the techniques named in a comma list ("all": every one). */
bool techniques_select(struct technique_list *list, const char *names, struct error *err);
/* "caustics.buffer=512 caustics.k=1", or "defaults" for point 0. */
void technique_point_label(const struct technique_point *p, char *out, size_t size);
/* The inverse: a label back into its assignments (false when malformed). */
bool technique_point_parse(const char *label, struct technique_point *out);
/* Whether an assignment's key names a pass parameter ("pass.param"). */
bool technique_key_is_pass(const char *key);
/* True when `key` is one of the selecting parameters of any technique (they
 * choose the graph, not the scene: the ground truth ignores them). */
bool techniques_is_selector(const struct technique_list *list, const char *key);

#endif
