/* Shadow map inputs of a pass (see shadow_inputs.h). */
#include <stdio.h>
#include <string.h>

#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

const struct record_type SHADOW_MAP_RECORD = {"shadow_map"};

const char *shadow_inputs_pane_left_out(const struct pass *p, const struct object *o)
{
    if (!object_is(o, OBJECT_ROLE_THIN))
        return NULL;
    int k = pass_param_index(p->desc, "shadow");
    if (k >= 0 && p->values[k].set)
        return NULL; /* between the light and the glass, by the map's pane filter */
    return k >= 0 ? "the light that crosses this pane on its way to the glass is neither dimmed nor tinted in the "
                    "caustic: give the pass the light's shadow map (shadow = \"shadow.depth\"), whose pane filter "
                    "has it"
                  : "the light that crosses this pane on its way to the glass is neither dimmed nor tinted in the "
                    "caustic";
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
