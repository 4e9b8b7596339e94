/* Temporal accumulation of a screen-space irradiance (temporal.h). */
#include "graph/temporal.h"

#include <string.h>

#include "graph/frame.h"
#include "graph/renderer.h"

void temporal_jitter(const struct temporal_history *h, float *dx, float *dy)
{
    /* the 4 x 4 ordered-dither matrix's cells in rank order: ranks 0-3 fall
     * in the four quarters, 0-15 in every cell */
    static const unsigned char order[16][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}, {1, 1}, {3, 3}, {3, 1}, {1, 3},
                                               {1, 0}, {3, 2}, {3, 0}, {1, 2}, {0, 1}, {2, 3}, {2, 1}, {0, 3}};
    int i = (int)(h->sequence % 16);
    *dx = ((float)order[i][0] + 0.5f) / 4.0f - 0.5f;
    *dy = ((float)order[i][1] + 0.5f) / 4.0f - 0.5f;
}

void temporal_reset(struct temporal_history *h)
{
    h->valid = false;
    h->still = 0;
}

void temporal_release(struct temporal_history *h)
{
    for (int i = 0; i < 2; i++) {
        gl_texture_destroy(&h->color[i]);
        gl_texture_destroy(&h->depth[i]);
    }
    gl_texture_destroy(&h->current);
    memset(h, 0, sizeof *h);
}

static bool ensure_size(struct temporal_history *h, int width, int height, struct error *err)
{
    if (h->width == width && h->height == height && h->current.id)
        return true;
    temporal_release(h);
    h->width = width;
    h->height = height;
    for (int i = 0; i < 2; i++)
        if (!gl_texture_create(&h->color[i], GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, err) ||
            !gl_texture_create(&h->depth[i], GL_TEXTURE_2D, GL_R32F, width, height, 1, err))
            return false;
    return gl_texture_create(&h->current, GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, err);
}

bool temporal_accumulate(struct temporal_history *h, struct renderer *r, const struct frame *frame,
                         const struct gl_texture *irradiance, const struct gl_texture *depth,
                         const struct gl_texture *motion, bool still, int frames, int *held, struct error *err)
{
    long sequence = h->sequence;
    if (!ensure_size(h, irradiance->width, irradiance->height, err))
        return false;
    h->sequence = sequence + 1;
    still = still && h->valid;
    int before = h->valid ? (still ? h->still : 1) : 0;
    if (held)
        *held = before;
    struct gl_program *prog;
    if (!gl_program_get_compute(&r->programs, "common/temporal.comp", NULL, NULL, &prog, err))
        return false;
    gl.CopyImageSubData(irradiance->id, GL_TEXTURE_2D, 0, 0, 0, 0, h->current.id, GL_TEXTURE_2D, 0, 0, 0, 0,
                        h->width, h->height, 1);
    int from = h->newest, to = 1 - h->newest;
    gl.UseProgram(prog->id);
    gl_program_bind_texture(prog, "u_current", h->current.id);
    gl_program_bind_texture(prog, "u_depth", depth->id);
    gl_program_bind_texture(prog, "u_history", h->color[from].id);
    gl_program_bind_texture(prog, "u_history_depth", h->depth[from].id);
    gl_program_bind_texture(prog, "u_motion", motion ? motion->id : 0);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_has_motion"), motion != NULL);
    gl_program_bind_image(prog, "u_out", irradiance->id, GL_FALSE, GL_WRITE_ONLY, GL_RGBA32F);
    gl_program_bind_image(prog, "u_out_history", h->color[to].id, GL_FALSE, GL_WRITE_ONLY, GL_RGBA32F);
    gl_program_bind_image(prog, "u_out_depth", h->depth[to].id, GL_FALSE, GL_WRITE_ONLY, GL_R32F);
    gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_inv_view_proj"), 1, GL_FALSE,
                               frame->inv_view_proj.m);
    gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_prev_view_proj"), 1, GL_FALSE, h->view_proj.m);
    gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_prev_inv_view_proj"), 1, GL_FALSE,
                               h->inv_view_proj.m);
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_eye"), frame->eye.x, frame->eye.y, frame->eye.z);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_valid"), h->valid && frames > 1);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_moved"), !still);
    bool camera_still = h->valid && memcmp(&h->view_proj, &frame->view_proj, sizeof h->view_proj) == 0;
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_settled"), still && camera_still);
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_frames"), (float)(frames < 1 ? 1 : frames));
    /* moving, half as many frames (at least 2): measured on the turning
     * ball (docs/TEMPORAL.md), a quarter lagged less but halved no flicker */
    int moved = frames / 2 > 2 ? frames / 2 : 2;
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_moved_frames"), (float)(moved < frames ? moved : frames));
    gl_program_dispatch(prog, h->width, h->height, 1,
                        GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    h->newest = to;
    h->valid = true;
    h->still = still ? h->still + 1 : 1;
    h->view_proj = frame->view_proj;
    h->inv_view_proj = frame->inv_view_proj;
    return true;
}
