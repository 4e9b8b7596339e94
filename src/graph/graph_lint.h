/* Mistakes a graph can make that render without an error but give a wrong
 * image: a glass, water or mirror object that no pass draws (it shows as
 * whatever is behind it), and caustics added by `shade` where the same
 * light is not shadowed (the floor under the glass gets its light twice).
 * `info` lists them; render, record and run warn once per session. */
#ifndef CAUSTICA_GRAPH_LINT_H
#define CAUSTICA_GRAPH_LINT_H

#include "graph/graph.h"
#include "scene/scene.h"

#define GRAPH_LINT_MAX 8

/* Fills up to GRAPH_LINT_MAX sentences; returns how many. With a camera's
 * `view_proj` (may be NULL), objects outside its view are not reported. */
int graph_lint(const struct graph *g, const struct scene *scene, const mat4 *view_proj, char messages[][400], int max);
/* Whether a sentence of graph_lint's says a pass leaves something of the
 * scene undrawn (an object it cannot handle, caustics in a medium, the
 * caustics seen from inside a refractor): `choose` never picks a technique
 * whose graph says one (issues 27, 52). */
bool graph_lint_is_omission(const char *message);

#endif
