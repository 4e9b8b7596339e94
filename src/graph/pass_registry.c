/* Every pass the scripts can create, as `c.pass.<name>`. Adding a pass:
 * write src/passes/<name>.c with its descriptor and list it here. */
#include <string.h>

#include "graph/pass.h"

extern const struct pass_desc shadow_map_pass;
extern const struct pass_desc shade_pass;
extern const struct pass_desc environment_pass;
extern const struct pass_desc fullscreen_pass;
extern const struct pass_desc custom_pass;
extern const struct pass_desc caustic_volumes_pass;
extern const struct pass_desc water_surface_pass;
extern const struct pass_desc refraction_pass;
extern const struct pass_desc layered_refraction_pass;
extern const struct pass_desc layered_caustics_pass;
extern const struct pass_desc illumination_textures_pass;
extern const struct pass_desc sliced_refraction_pass;
extern const struct pass_desc photon_caustics_pass;
extern const struct pass_desc volume_light_pass;
extern const struct pass_desc beam_caustics_pass;
extern const struct pass_desc receivers_pass;
extern const struct pass_desc depth_layers_pass;

static const struct pass_desc *const registry[] = {
    &shadow_map_pass, &shade_pass, &environment_pass, &fullscreen_pass, &custom_pass, &caustic_volumes_pass,
    &water_surface_pass, &refraction_pass, &photon_caustics_pass, &layered_refraction_pass, &layered_caustics_pass, &illumination_textures_pass, &sliced_refraction_pass,
    &beam_caustics_pass, &volume_light_pass, &receivers_pass, &depth_layers_pass,
};

int pass_registry_count(void) { return (int)(sizeof registry / sizeof registry[0]); }

const struct pass_desc *pass_registry_get(int index)
{
    return index >= 0 && index < pass_registry_count() ? registry[index] : NULL;
}

const struct pass_desc *pass_registry_find(const char *name)
{
    for (int i = 0; i < pass_registry_count(); i++)
        if (strcmp(registry[i]->name, name) == 0)
            return registry[i];
    return NULL;
}
