/* Morph targets and deformers, evaluated once per frame on the GPU
 * (shaders/deform/deform.comp) into buffers that every pass draws from and
 * that the reference renderer reads back: one source of geometry. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_buffer.h"
#include "graph/renderer.h"
#include "scene/water.h"

bool deform_update(struct renderer *r, struct scene *scene, double time, struct error *err)
{
    bool any = false;
    for (int i = 0; i < scene->object_count; i++) {
        struct object *o = scene->objects[i];
        if (!object_is_animated_geometry(o))
            continue;
        struct gpu_object *g;
        bool created;
        if (!mesh_cache_deformed(&r->meshes, o, &g, &created, err))
            return false;
        if (created && o->water)
            o->water->dirty = true; /* new buffers: fill them */
        if (o->water) {
            /* The simulation runs on the CPU (its step is cheap and must be
             * exact for the tests); its heights go to the same buffers. */
            if (o->water->dirty) {
                size_t n = o->mesh->vertex_count;
                float *pos = malloc(n * 3 * sizeof(float)), *nrm = malloc(n * 3 * sizeof(float));
                if (!pos || !nrm) {
                    free(pos);
                    free(nrm);
                    return error_set(err, "out of memory for the water surface");
                }
                water_fill_vertices(o->water, pos, nrm);
                bool ok = gl_buffer_update(g->deformed_positions, pos, n * 3 * sizeof(float), err) &&
                          gl_buffer_update(g->deformed_normals, nrm, n * 3 * sizeof(float), err);
                free(pos);
                free(nrm);
                if (!ok)
                    return false;
                o->water->dirty = false;
            }
            continue;
        }
        char defines[8192];
        const char *origin = NULL;
        bool skinned = o->joint_matrix_count > 0 && o->mesh->joints;
        const char *skin = skinned ? "#define SKINNED 1\n" : "#define SKINNED 0\n";
        if (o->deform.kind == DEFORM_GLSL) {
            /* the skin's define after the script's GLSL: its lines keep the
             * numbers the error messages give (deform.lua:18 (deformer):3) */
            int n = snprintf(defines, sizeof defines, "#define DEFORM_KIND 2\n%s\n%s",
                             o->deform.glsl ? o->deform.glsl : "", skin);
            if (n < 0 || (size_t)n >= sizeof defines)
                return error_set(err, "%s: the deformer's GLSL is longer than %zu characters", o->deform.origin,
                                 sizeof defines - 64);
            origin = o->deform.origin;
        } else {
            snprintf(defines, sizeof defines, "%s#define DEFORM_KIND %d\n", skin, o->deform.kind == DEFORM_WAVE ? 1 : 0);
        }
        struct gl_program *prog;
        if (!gl_program_get_compute(&r->programs, "deform/deform.comp", defines, origin, &prog, err))
            return false;
        struct mesh *m = o->mesh;
        struct gpu_mesh *gm = mesh_cache_mesh(&r->meshes, m, err);
        if (!gm)
            return false;
        gl.UseProgram(prog->id);
        gl_program_bind_storage(prog, "BasePositions", gm->positions);
        gl_program_bind_storage(prog, "BaseNormals", gm->normals);
        gl_program_bind_storage(prog, "TargetPositions", m->target_count ? gm->target_positions : gm->positions);
        gl_program_bind_storage(prog, "TargetNormals", m->target_count ? gm->target_normals : gm->normals);
        gl_program_bind_storage(prog, "OutPositions", g->deformed_positions);
        gl_program_bind_storage(prog, "OutNormals", g->deformed_normals);
        if (skinned) {
            /* this frame's joint matrices, in a buffer of the object's that
             * grows with the skin */
            size_t bytes = (size_t)o->joint_matrix_count * 16 * sizeof(float);
            if (g->joint_capacity < o->joint_matrix_count) {
                gl_buffer_destroy(&g->joint_matrices);
                if (!gl_buffer_create(&g->joint_matrices, o->joint_matrices, bytes, GL_DYNAMIC_STORAGE_BIT, err))
                    return false;
                g->joint_capacity = o->joint_matrix_count;
            } else if (!gl_buffer_update(g->joint_matrices, o->joint_matrices, bytes, err)) {
                return false;
            }
            gl_program_bind_storage(prog, "Joints", gm->joints);
            gl_program_bind_storage(prog, "JointWeights", gm->joint_weights);
            gl_program_bind_storage(prog, "JointMatrices", g->joint_matrices);
            gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_joint_count"), o->joint_matrix_count);
        }
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_vertex_count"), (GLint)m->vertex_count);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_target_count"), m->target_count);
        for (int t = 0; t < SCENE_MAX_MORPH_TARGETS; t++) {
            char name[32];
            snprintf(name, sizeof name, "u_weights[%d]", t);
            gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, name), t < m->target_count ? o->morph_weights[t] : 0.0f);
        }
        gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_time"), (float)time);
        gl.ProgramUniform4f(prog->id, gl_program_uniform(prog, "u_wave"), o->deform.amplitude, o->deform.frequency,
                            o->deform.speed, 0.0f);
        vec3 d = vec3_normalize_or(o->deform.direction, vec3_make(1, 0, 0));
        gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_wave_direction"), d.x, d.y, d.z);
        vec3 ext = vec3_sub(m->bounds_max, m->bounds_min);
        float size = vec3_length(ext);
        gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_step"), 1e-3f * (size > 0 ? size : 1.0f));
        gl_program_dispatch(prog, (int)m->vertex_count, 1, 1, 0); /* (one barrier after them all) */
        any = true;
    }
    if (any)
        gl.MemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.UseProgram(0);
    return gl_check("morphs and deformers", err);
}
