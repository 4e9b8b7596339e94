/* Every pass the scripts can create, as `c.pass.<name>`. Adding a pass:
 * write src/passes/{techniques,blocks,helpers}/<name>.c with its
 * descriptor `<name>_pass` and add one X(<name>) line below (CMake builds
 * every .c file in those folders). */
#include <string.h>

#include "graph/pass.h"

/* One line per pass, in the order `caustica help passes` lists them. */
#define PASS_REGISTRY(X) \
    X(shadow_map) \
    X(shade) \
    X(environment) \
    X(fullscreen) \
    X(custom) \
    X(caustic_volumes) \
    X(water_surface) \
    X(glossy_reflection) \
    X(refraction) \
    X(photon_caustics) \
    X(layered_refraction) \
    X(layered_caustics) \
    X(illumination_textures) \
    X(sliced_refraction) \
    X(beam_caustics) \
    X(volume_light) \
    X(receivers) \
    X(depth_layers) \
    X(distance_map) \
    X(impostors) \
    CAUSTICA_EXTRA_PASSES(X) \
    /* end */

/* A build may register one pass of its own, appended to the list: the
 * test build of tests/cli/new_technique_test.sh compiles this file with
 * -DCAUSTICA_EXTRA_PASS=example_caustics (CMakeLists.txt). */
#ifdef CAUSTICA_EXTRA_PASS
#define CAUSTICA_APPLY(X, name) X(name) /* (expands the name before X pastes it) */
#define CAUSTICA_EXTRA_PASSES(X) CAUSTICA_APPLY(X, CAUSTICA_EXTRA_PASS)
#else
#define CAUSTICA_EXTRA_PASSES(X)
#endif

#define PASS_DECLARE(name) extern const struct pass_desc name##_pass;
PASS_REGISTRY(PASS_DECLARE)
#undef PASS_DECLARE

#define PASS_ENTRY(name) &name##_pass,
static const struct pass_desc *const registry[] = {PASS_REGISTRY(PASS_ENTRY)};
#undef PASS_ENTRY

int pass_registry_count(void) { return (int)(sizeof registry / sizeof registry[0]); }

const struct pass_desc *pass_registry_get(int index)
{
    return index >= 0 && index < pass_registry_count() ? registry[index] : NULL;
}

const char *pass_technique_name(enum pass_technique technique)
{
    switch (technique) {
    case PASS_TECHNIQUE_CAUSTICS: return "caustics";
    case PASS_TECHNIQUE_WATER_CAUSTICS: return "water_caustics";
    case PASS_TECHNIQUE_VIEW: return "view";
    case PASS_TECHNIQUE_WATER_VIEW: return "water_view";
    case PASS_TECHNIQUE_NONE: break;
    }
    return NULL;
}

const struct pass_desc *pass_registry_find(const char *name)
{
    for (int i = 0; i < pass_registry_count(); i++)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}
