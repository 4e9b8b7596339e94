/* Shadow map inputs of a pass (see shadow_inputs.h). */
#include <stdio.h>
#include <string.h>

#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

const struct record_type SHADOW_MAP_RECORD = {"shadow_map"};

/* Does pane `o` lie beyond a specular object of the scene as `light` sees
 * them: its box's centre farther along the light's way than that object's,
 * and the two boxes' bounding spheres overlapping across it? Its number
 * (from 1), or 0. */
static int pane_beyond_specular(const struct scene *scene, const struct light *light, const struct object *o)
{
    vec3 plo, phi;
    object_world_bounds(o, &plo, &phi);
    vec3 pc = vec3_scale(vec3_add(plo, phi), 0.5f);
    float pr = 0.5f * vec3_length(vec3_sub(phi, plo));
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *s = scene->objects[i];
        if (!s->visible || !object_is(s, OBJECT_ROLE_SPECULAR))
            continue;
        vec3 lo, hi;
        object_world_bounds(s, &lo, &hi);
        vec3 c = vec3_scale(vec3_add(lo, hi), 0.5f);
        float r = 0.5f * vec3_length(vec3_sub(hi, lo));
        vec3 d = light->kind == LIGHT_DIRECTIONAL ? light->direction : vec3_sub(c, light_center(light));
        float len = vec3_length(d);
        if (!(len > 0.0f))
            continue;
        d = vec3_scale(d, 1.0f / len);
        vec3 between = vec3_sub(pc, c);
        float along = vec3_dot(between, d);
        vec3 across = vec3_sub(between, vec3_scale(d, along));
        if (along > 0.0f && vec3_length(across) < pr + r)
            return i + 1;
    }
    return 0;
}

const char *shadow_inputs_pane_left_out(const struct pass *p, const struct scene *scene, const struct object *o)
{
    if (!object_is(o, OBJECT_ROLE_THIN))
        return NULL;
    static char beyond[300]; /* (graph_lint copies it before the next call) */
    int l = pass_param_index(p->desc, "light");
    const struct light *light = l >= 0 && p->desc->params[l].type == PASS_PARAM_LIGHT ? pass_light_at(p, l) : NULL;
    int s = light ? pane_beyond_specular(scene, light, o) : 0;
    if (s) {
        snprintf(beyond, sizeof beyond,
                 "it lies beyond object %d (%s) as the light sees them: the caustic that reaches the receivers "
                 "through it is neither dimmed nor tinted by it (the reference's photons cross it)",
                 s, object_role_name(object_role(scene->objects[s - 1]) & OBJECT_ROLE_SPECULAR));
        return beyond;
    }
    int k = pass_param_index(p->desc, "shadow");
    if (k >= 0 && p->values[k].set)
        return NULL; /* between the light and the glass, by the map's pane filter */
    return k >= 0 ? "the light that crosses this pane on its way to the glass is neither dimmed nor tinted in the "
                    "caustic: give the pass the light's shadow map (shadow = \"shadow.depth\"), whose pane filter "
                    "has it"
                  : "the light that crosses this pane on its way to the glass is neither dimmed nor tinted in the "
                    "caustic";
}

bool shadow_inputs_give(struct pass *block, const struct pass *reader, int reader_shadow, struct error *err)
{
    const struct pass_value *shadow = reader_shadow >= 0 ? &reader->values[reader_shadow] : NULL;
    int param = pass_param_index(block->desc, "shadow");
    if (!shadow || !shadow->list_count)
        return true;
    if (param < 0)
        return error_set(err, "the block '%s' takes no shadow maps", block->desc->name);
    return pass_set_list(block, param, (const char *const *)shadow->list, shadow->list_count, err);
}

void shadow_inputs_bind(struct pass *p, struct pass_frame *f, const struct gl_program *prog)
{
    struct renderer *r = f->renderer;
    int nshadow = 0;
    for (int i = 0; i < SHADOW_INPUTS_MAX; i++) {
        char slot[32], name[64];
        snprintf(slot, sizeof slot, "shadow%d", i);
        struct graph_resource *sh = pass_frame_input(p, f, slot);
        if (!sh)
            continue;
        const struct shadow_record *made = pass_frame_record(p, f, slot, &SHADOW_MAP_RECORD);
        bool cube = sh->texture.target == GL_TEXTURE_CUBE_MAP;
        static const struct shadow_record none = {.matrix = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
                                                  .light_index = -1};
        const struct shadow_record *rec = made ? made : &none; /* none: a map of no light this frame */
        gl_program_bind_texture_at(prog, "u_shadow_2d", i, cube ? r->dummy_depth.id : sh->texture.id);
        gl_program_bind_texture_at(prog, "u_shadow_cubes", i, cube ? sh->texture.id : r->dummy_cube.id);
        gl_program_bind_texture_at(prog, "u_shadow_filter", i, rec->filter ? rec->filter : r->dummy_2d.id);
        int entries = rec->light_index >= 0 ? 1 : 0;
        for (int li = 0; li < f->scene->light_count && li < SCENE_MAX_GPU_LIGHTS; li++)
            if (r->frame.light_first[li] == rec->light_index)
                entries = r->frame.light_entries[li];
        snprintf(name, sizeof name, "u_shadow_first[%d]", nshadow);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, name), rec->light_index);
        snprintf(name, sizeof name, "u_shadow_count[%d]", nshadow);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, name), entries);
        snprintf(name, sizeof name, "u_shadow_cube[%d]", nshadow);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, name), cube ? 1 : 0);
        snprintf(name, sizeof name, "u_shadow_matrix[%d]", nshadow);
        gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, name), 1, GL_FALSE, rec->matrix.m);
        snprintf(name, sizeof name, "u_shadow_params[%d]", nshadow);
        gl.ProgramUniform4f(prog->id, gl_program_uniform(prog, name), rec->range, rec->bias,
                            1.0f / (float)sh->texture.width, rec->filter ? 1.0f : 0.0f);
        nshadow++;
    }
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_shadow_total"), nshadow);
}
