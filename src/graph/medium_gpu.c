/* The scene's participating medium on the GPU (see medium_gpu.h). */
#include <math.h>

#include "graph/medium_gpu.h"
#include "graph/renderer.h"

bool medium_gpu_present(const struct scene *scene)
{
    const struct medium *m = scene->medium;
    if (!m || m->max_density <= 0.0f)
        return false;
    vec3 t = vec3_add(m->sigma_s, m->sigma_a);
    return t.x > 0.0f || t.y > 0.0f || t.z > 0.0f;
}

static bool upload_grid(struct renderer *r, const struct medium *m, struct error *err)
{
    if (r->medium_density.id && r->medium_uploaded == m && r->medium_version == m->version &&
        r->medium_density.width == m->nx && r->medium_density.height == m->ny && r->medium_density.layers == m->nz)
        return true;
    gl_texture_destroy(&r->medium_density);
    r->medium_uploaded = NULL;
    if (!gl_texture_create(&r->medium_density, GL_TEXTURE_3D, GL_R32F, m->nx, m->ny, m->nz, err))
        return false;
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TextureSubImage3D(r->medium_density.id, 0, 0, 0, 0, m->nx, m->ny, m->nz, GL_RED, GL_FLOAT, m->grid);
    r->medium_uploaded = m;
    r->medium_version = m->version;
    return true;
}

bool medium_gpu_bind(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                     struct error *err)
{
    GLuint id = program->id;
    bool present = medium_gpu_present(scene);
    gl.ProgramUniform1i(id, gl_program_uniform(program, "u_medium"), present ? 1 : 0);
    if (!present) {
        gl_program_bind_texture(program, "u_medium_texture", 0);
        return true;
    }
    const struct medium *m = scene->medium;
    vec3 st = vec3_add(m->sigma_s, m->sigma_a);
    gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_lo"), m->box_min.x, m->box_min.y, m->box_min.z);
    gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_hi"), m->box_max.x, m->box_max.y, m->box_max.z);
    gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_sigma_s"), m->sigma_s.x, m->sigma_s.y, m->sigma_s.z);
    gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_sigma_t"), st.x, st.y, st.z);
    gl.ProgramUniform1f(id, gl_program_uniform(program, "u_medium_g"), m->g);
    gl.ProgramUniform1f(id, gl_program_uniform(program, "u_medium_density"), m->density);
    gl.ProgramUniform1i(id, gl_program_uniform(program, "u_medium_grid"), m->grid ? 1 : 0);
    if (m->grid) {
        if (!upload_grid(r, m, err))
            return false;
        /* Grid values sit on the corners of (n-1) cells spanning the box
         * (scene/medium.c): texel centres at the corners. */
        vec3 size = vec3_sub(m->box_max, m->box_min);
        float sx = (float)(m->nx - 1) / (float)m->nx / size.x, sy = (float)(m->ny - 1) / (float)m->ny / size.y,
              sz = (float)(m->nz - 1) / (float)m->nz / size.z;
        gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_grid_scale"), sx, sy, sz);
        gl.ProgramUniform3f(id, gl_program_uniform(program, "u_medium_grid_offset"),
                            0.5f / (float)m->nx - m->box_min.x * sx, 0.5f / (float)m->ny - m->box_min.y * sy,
                            0.5f / (float)m->nz - m->box_min.z * sz);
        gl_program_bind_texture(program, "u_medium_texture", r->medium_density.id);
    } else {
        gl_program_bind_texture(program, "u_medium_texture", 0); /* not sampled: a homogeneous medium */
    }
    return true;
}
