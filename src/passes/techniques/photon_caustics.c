/* photon_caustics: Hu & Qin §3. A photon buffer is rendered from the light
 * (§3.1): each of its pixels on a refractor (or mirror) follows the light
 * through the object (the two-sided lookup of §2.1 in the light's view)
 * and onto the impostor of the receiver it reaches (§2.2, with the
 * iterative correction of Fig. 16), and stores (u, v, k) and its flux.
 * The photons are accumulated into one caustic texture per receiver on
 * the GPU (no read-back) and filtered with
 *   c(u, v) = s * sum p(u + i, v + j) sqrt(1 + 2k^2 - (i^2 + j^2))   (§3.2),
 * normalised so that s = 1 keeps the photons' energy: the texture holds
 * irradiance. Caustic mapping (§3.3) projects it back onto the receivers
 * seen by the camera, with a shadow-map-like test against the impostor's
 * depth, into a screen-space irradiance `shade` adds. A static scene (light
 * and objects unchanged) reuses the photon buffer and caustic textures (§4);
 * only the mapping is redone, and the textures rebuilt from the buffer when
 * the camera moved (their box is where it may see the photons land). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "graph/temporal.h"
#include "scene/light_view.h"
#include "passes/helpers/caustic_coverage.h"
#include "passes/blocks/impostors.h"
#include "passes/helpers/shadow_inputs.h"
#include "scene/scene.h"

/* per receiver in the PhotonWindows buffer: the box (lo.x, lo.y, hi.x, hi.y)
 * and the count of the photons the camera may see, and the box of all of
 * them (shaders/photon_caustics/window.glsl) */
#define PHOTON_WINDOW_STRIDE 9

/* The C mirror of PhotonParams (shaders/photon_caustics/window.glsl,
 * std140): the caustic textures' and the mapping's values for one frame,
 * uploaded in one call (issue 54). */
struct photon_params {
    int32_t fit, texture;
    float footprint;
    int32_t k;
    float s, fixed_point, bias;
    int32_t pixel_samples;
};
#define PHOTON_PARAM(field, name) {name, offsetof(struct photon_params, field)}
static const struct gl_block_member photon_params_members[] = {
    PHOTON_PARAM(fit, "u_fit"), PHOTON_PARAM(texture, "u_texture"), PHOTON_PARAM(footprint, "u_footprint"),
    PHOTON_PARAM(k, "u_k"), PHOTON_PARAM(s, "u_s"), PHOTON_PARAM(fixed_point, "u_fixed_point"),
    PHOTON_PARAM(bias, "u_bias"), PHOTON_PARAM(pixel_samples, "u_pixel_samples"),
};
#undef PHOTON_PARAM

struct photon_state {
    struct gl_param_block params; /* PhotonParams, this frame's */
    struct caustic_coverage dark_check; /* what it left dark under glass, measured once */
    const struct impostor_set *impostors; /* the impostors block's, this frame */
    struct gl_framebuffer light_fb[2], photon_fb, map_fb;
    struct gl_texture light_normal[2], light_depth[2]; /* front, back as seen from the light */
    struct gl_texture light_material[2];              /* absorption or tint, and the material kind */
    struct gl_texture photons, photon_flux;           /* the photon buffer: (u, v, k, valid), flux */
    struct gl_texture counts;                         /* r32ui array, 3 layers per receiver */
    struct gl_texture caustics;                       /* rgba32f array, one layer per receiver */
    int buffer, texture, receivers;
    bool valid;
    uint64_t key;      /* what the photon buffer was made from (pass_frame_key) */
    uint64_t view_key; /* and the caustic textures: that and the camera (their box is what it may see) */
    mat4 light_view_proj, light_inverse;
    float fixed_point; /* flux -> integer count scale */
    GLuint windows;    /* SSBO: per receiver, the box its photons landed in (window.glsl) */
    GLuint cover;      /* SSBO: the light-view texels the specular objects cover (cover.comp) */
    float coverage;    /* the narrowed light view's share of the first one (0: not narrowed; the report) */
    struct temporal_history temporal; /* accumulate > 1: the irradiance of the last frames (issue 32) */
    /* accumulate > 1: the last frame's photon buffer and its grid's jitter,
     * and where the light moved on screen since (motion.comp) */
    struct gl_texture photons_previous, motion;
    float jitter[2], jitter_previous[2];
    bool previous_valid;
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
/* Choices of `mode`, in the order of its `choices`. */
enum { PHOTON_MODE_REFRACT, PHOTON_MODE_REFLECT };

enum photon_caustics_param {
    PHOTON_LIGHT,
    PHOTON_BUFFER,
    PHOTON_K,
    PHOTON_S,
    PHOTON_TEXTURE,
    PHOTON_ITERATIONS,
    PHOTON_BIAS,
    PHOTON_MODE,
    PHOTON_FOOTPRINT,
    PHOTON_FIT,
    PHOTON_PIXEL_SAMPLES,
    PHOTON_ACCUMULATE,
    PHOTON_SHADOW,
    PHOTON_IMPOSTORS,
    PHOTON_RECEIVERS,
    PHOTON_RECEIVER_DEPTH,
};

static const struct pass_param_desc params[] = {
    [PHOTON_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true, .help = "the light the photons come from"},
    [PHOTON_BUFFER] = {.name = "buffer", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 2048,
     .help = "photon buffer size (photons = buffer^2 at most), 64-512 in the paper"},
    [PHOTON_K] = {.name = "k", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 8,
     .help = "filter radius (§3.2; 0: none, the footprints spread the photons instead; docs/techniques/hu_qin.md)"},
    [PHOTON_S] = {.name = "s", .type = PASS_PARAM_NUMBER, .default_number = 1.0, .min = 0, .max = 1e6,
     .help = "filter scale; 1 keeps the photons' energy (irradiance)"},
    [PHOTON_TEXTURE] = {.name = "texture", .type = PASS_PARAM_INTEGER, .default_number = 512, .min = 16, .max = 4096,
     .help = "caustic texture size per receiver (over the box its photons landed in, with fit)"},
    [PHOTON_ITERATIONS] = {.name = "iterations", .type = PASS_PARAM_INTEGER, .default_number = 3, .min = 0, .max = 16,
     .help = "iterations of the impostor correction (Fig. 16); d_T (Fig. 9) iterates until the gap to the back "
             "surface closes, at most 8 steps"},
    [PHOTON_BIAS] = {.name = "bias", .type = PASS_PARAM_NUMBER, .default_number = 0.02, .min = 0, .max = 10,
     .help = "depth tolerance of the caustic mapping test, scene units"},
    [PHOTON_MODE] = {.name = "mode", .type = PASS_PARAM_ENUM, .default_string = "refract", .choices = "refract|reflect",
     .help = "follow the light refracted through glass, or reflected off it (Fig. 19, 26); mirrors always reflect"},
    [PHOTON_FOOTPRINT] = {.name = "footprint", .type = PASS_PARAM_NUMBER, .default_number = 16, .min = 0, .max = 64,
     .help = "spread each photon over the area its neighbours span on the receiver (a ray differential), at most this "
             "many texels from its landing point (4x where both neighbours agree the light is stretched smoothly); "
             "0 = a point per photon, the paper's (docs/techniques/hu_qin.md)"},
    [PHOTON_FIT] = {.name = "fit", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "each receiver's caustic texture covers the box its photons landed in, not the whole receiver "
             "(more texels where the caustic is; docs/techniques/hu_qin.md)"},
    [PHOTON_PIXEL_SAMPLES] = {.name = "pixel_samples", .type = PASS_PARAM_INTEGER, .default_number = 4, .min = 1, .max = 16,
     .help = "caustic lookups per pixel along each screen axis where its footprint spans more caustic texels "
             "(the pixel's mean light; 1: its centre; docs/techniques/hu_qin.md)"},
    [PHOTON_SHADOW] = SHADOW_PARAM_PANES("a photon"),
    [PHOTON_ACCUMULATE] = {.name = "accumulate", .type = PASS_PARAM_INTEGER, .default_number = 1, .min = 1, .max = 64,
     .help = "temporal accumulation: the photon grid moves by a sub-texel jitter every frame and the irradiance "
             "averages the last this many frames while the light and the geometry stay, half as many (at least 2; the "
             "history clipped to each pixel's neighbourhood) while they move; 1: none (docs/TEMPORAL.md)"},
    [PHOTON_IMPOSTORS] = {.name = "impostors", .type = PASS_PARAM_INPUT, .block = "impostors",
     .bundle = &IMPOSTOR_SET_RECORD, .default_output = "set",
     .help = "the receivers' impostors the caustic textures are made over (§3.2; an impostors pass's `set`): by "
             "default the graph adds one of `texture` texels, shared with refraction or layered_refraction where "
             "they want the same"},
    [PHOTON_RECEIVERS] = {.name = "receivers", .type = PASS_PARAM_INPUT, .block = "receivers",
     .default_output = "position",
     .help = "the camera's receivers the caustic textures are mapped onto (a receivers { position = true } pass's "
             "`position`, w = 1 + the object's id): by default the graph adds one, shared with the other caustics "
             "passes"},
    [PHOTON_RECEIVER_DEPTH] = {.name = "receiver_depth", .type = PASS_PARAM_INPUT, .default_beside = "receivers",
     .default_output = "depth", .help = "their depth, this pass's `depth` (by default beside `receivers`)"},
};

static bool photon_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "depth", GL_DEPTH_COMPONENT32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool photon_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct photon_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("PhotonParams", photon_params_members, struct photon_params);
    p->state = s;
    return gl_framebuffer_create(&s->light_fb[0], err) && gl_framebuffer_create(&s->light_fb[1], err) &&
           gl_framebuffer_create(&s->photon_fb, err) && gl_framebuffer_create(&s->map_fb, err);
}

static void release_textures(struct photon_state *s)
{
    for (int i = 0; i < 2; i++) {
        gl_texture_destroy(&s->light_normal[i]);
        gl_texture_destroy(&s->light_depth[i]);
        gl_texture_destroy(&s->light_material[i]);
    }
    gl_texture_destroy(&s->photons);
    gl_texture_destroy(&s->photon_flux);
    gl_texture_destroy(&s->photons_previous);
    gl_texture_destroy(&s->motion);
    s->previous_valid = false;
    gl_texture_destroy(&s->counts);
    gl_texture_destroy(&s->caustics);
}

static void photon_destroy(struct pass *p)
{
    struct photon_state *s = p->state;
    if (!s)
        return;
    release_textures(s);
    caustic_coverage_release(&s->dark_check);
    temporal_release(&s->temporal);
    for (int i = 0; i < 2; i++)
        gl_framebuffer_destroy(&s->light_fb[i]);
    gl_framebuffer_destroy(&s->photon_fb);
    gl_framebuffer_destroy(&s->map_fb);
    if (s->windows && gl_api_ready())
        gl.DeleteBuffers(1, &s->windows);
    if (s->cover && gl_api_ready())
        gl.DeleteBuffers(1, &s->cover);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

static bool specular_bounds(const struct scene *scene, vec3 *center, float *radius)
{
    vec3 lo, hi;
    if (!scene_role_bounds(scene, OBJECT_ROLE_SPECULAR, &lo, &hi))
        return false;
    *center = vec3_scale(vec3_add(lo, hi), 0.5f);
    *radius = fmaxf(0.5f * vec3_length(vec3_sub(hi, lo)), 1e-3f);
    return true;
}

static enum pass_need photon_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    vec3 c;
    float rad;
    if (!specular_bounds(f->scene, &c, &rad)) {
        snprintf(why, whylen, "left out: no refractive or reflective object makes caustics");
        return PASS_SKIP;
    }
    return PASS_RUN;
}

static bool ensure_textures(struct photon_state *s, int buffer, int texture, int receivers, struct error *err)
{
    if (s->buffer == buffer && s->texture == texture && s->receivers == receivers && s->photons.id)
        return true;
    release_textures(s);
    s->buffer = buffer;
    s->texture = texture;
    s->receivers = receivers;
    s->valid = false;
    for (int i = 0; i < 2; i++) {
        if (!gl_texture_create(&s->light_normal[i], GL_TEXTURE_2D, GL_RGBA32F, buffer, buffer, 1, err) ||
            !gl_texture_create(&s->light_material[i], GL_TEXTURE_2D, GL_RGBA32F, buffer, buffer, 1, err) ||
            !gl_texture_create(&s->light_depth[i], GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, buffer, buffer, 1, err))
            return false;
        const struct gl_texture *c[2] = {&s->light_normal[i], &s->light_material[i]};
        if (!gl_framebuffer_attach(&s->light_fb[i], c, NULL, 2, &s->light_depth[i], -1, err))
            return false;
    }
    if (!gl_texture_create(&s->photons, GL_TEXTURE_2D, GL_RGBA32F, buffer, buffer, 1, err) ||
        !gl_texture_create(&s->photon_flux, GL_TEXTURE_2D, GL_RGBA32F, buffer, buffer, 1, err) ||
        !gl_texture_create(&s->photons_previous, GL_TEXTURE_2D, GL_RGBA32F, buffer, buffer, 1, err))
        return false;
    const struct gl_texture *pc[2] = {&s->photons, &s->photon_flux};
    if (!gl_framebuffer_attach(&s->photon_fb, pc, NULL, 2, NULL, -1, err))
        return false;
    int layers = receivers > 0 ? receivers : 1;
    return gl_texture_create(&s->counts, GL_TEXTURE_2D_ARRAY, GL_R32UI, texture, texture, 3 * layers, err) &&
           gl_texture_create(&s->caustics, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, texture, texture, layers, err);
}

static void bind_impostors(struct photon_state *s, const struct gl_program *prog)
{
    gl_program_bind_storage(prog, "Impostors", s->impostors->ubo);
    gl_program_bind_storage(prog, "PhotonWindows", s->windows);
    gl_program_bind_texture(prog, "u_impostor_depth", s->impostors->depth.id);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_impostor_count"), s->impostors->count);
}

/* Front and back surfaces of the specular objects as the light sees them
 * (§2.1 in the light's view): normals, depths and materials. */
static bool draw_light_surfaces(struct photon_state *s, struct renderer *r, const struct scene *scene, int buffer,
                                struct error *err)
{
    struct gl_program *surf;
    if (!gl_program_get(&r->programs, "photon_caustics/light_surfaces.vert", "photon_caustics/light_surfaces.frag", NULL,
                        &surf, err))
        return false;
    gl.ProgramUniformMatrix4fv(surf->id, gl_program_uniform(surf, "u_light_view_proj"), 1, GL_FALSE,
                               s->light_view_proj.m);
    const float zero[4] = {0, 0, 0, 0};
    gl.Enable(GL_DEPTH_TEST);
    gl.Enable(GL_CULL_FACE);
    gl.Viewport(0, 0, buffer, buffer);
    for (int side = 0; side < 2; side++) {
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->light_fb[side].id);
        gl.ClearNamedFramebufferfv(s->light_fb[side].id, GL_COLOR, 0, zero);
        gl.ClearNamedFramebufferfv(s->light_fb[side].id, GL_COLOR, 1, zero);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.CullFace(side == 0 ? GL_BACK : GL_FRONT);
        renderer_draw_objects(r, scene, surf, DRAW_SPECULAR);
    }
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_DEPTH_TEST);
    return true;
}

/* Issue 8's "photon buffer that adapts to the refractors' projected area":
 * the light view first covers the specular objects' bounding sphere; the
 * texels they cover there are boxed (cover.comp, read back: four numbers),
 * and where the box leaves a tenth of the buffer or more unused along an
 * axis the view is narrowed to it (grown by two texels) and the surfaces are
 * drawn again. The bounding sphere is the one around the objects' box: a
 * lone glass ball covered a third of the view, a ball with a mirror teapot
 * beside it or a long dragon less. The photons' flux comes from the narrowed view's own texel
 * footprints (trace.frag), so the energy is unchanged. `jitter` (accumulating,
 * issue 32) then moves the grid by a sub-texel offset of the final view, and
 * the surfaces are drawn with it. */
static bool fit_light_view(struct photon_state *s, struct renderer *r, const struct scene *scene, int buffer, mat4 view,
                           mat4 jitter, mat4 *proj, struct error *err)
{
    if (!s->cover) {
        gl.CreateBuffers(1, &s->cover);
        gl.NamedBufferStorage(s->cover, 4 * sizeof(GLuint), NULL, GL_DYNAMIC_STORAGE_BIT);
    }
    struct gl_program *cover;
    if (!gl_program_get_compute(&r->programs, "photon_caustics/cover.comp", NULL, NULL, &cover, err))
        return false;
    GLuint box[4] = {(GLuint)buffer, (GLuint)buffer, 0u, 0u};
    gl.NamedBufferSubData(s->cover, 0, sizeof box, box);
    gl.UseProgram(cover->id);
    gl_program_bind_texture(cover, "u_front_depth", s->light_depth[0].id);
    gl_program_bind_texture(cover, "u_back_depth", s->light_depth[1].id);
    gl_program_bind_storage(cover, "Cover", s->cover);
    gl_program_dispatch(cover, buffer, buffer, 1, GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetNamedBufferSubData(s->cover, 0, sizeof box, box);
    s->coverage = 0.0f;
    bool jittered = jitter.m[12] != 0.0f || jitter.m[13] != 0.0f;
    if (box[0] > box[2] || box[1] > box[3])
        return true; /* nothing specular in view of the light */
    float lo[2], hi[2];
    bool narrow = false;
    for (int a = 0; a < 2; a++) {
        /* the box in normalized device coordinates, two texels wider each way */
        float t0 = fmaxf((float)box[a] - 2.0f, 0.0f), t1 = fminf((float)box[a + 2] + 3.0f, (float)buffer);
        lo[a] = 2.0f * t0 / (float)buffer - 1.0f;
        hi[a] = 2.0f * t1 / (float)buffer - 1.0f;
        narrow = narrow || (t1 - t0) < 0.9f * (float)buffer;
    }
    if (!narrow && !jittered)
        return true;
    if (!narrow) {
        /* the grid moved by its sub-texel offset only */
        *proj = mat4_mul(jitter, *proj);
        s->light_view_proj = mat4_mul(*proj, view);
        mat4_inverse(s->light_view_proj, &s->light_inverse);
        return draw_light_surfaces(s, r, scene, buffer, err);
    }
    s->coverage = ((hi[0] - lo[0]) * (hi[1] - lo[1])) / 4.0f;
    /* x' = (2 x - (hi + lo) w) / (hi - lo) on clip coordinates: the box to
     * [-1, 1], for a perspective view as for an orthographic one */
    mat4 m = mat4_identity();
    m.m[0] = 2.0f / (hi[0] - lo[0]);
    m.m[12] = -(hi[0] + lo[0]) / (hi[0] - lo[0]);
    m.m[5] = 2.0f / (hi[1] - lo[1]);
    m.m[13] = -(hi[1] + lo[1]) / (hi[1] - lo[1]);
    /* m acts on clip space: its last column adds w times the offset */
    *proj = mat4_mul(jitter, mat4_mul(m, *proj));
    s->light_view_proj = mat4_mul(*proj, view);
    mat4_inverse(s->light_view_proj, &s->light_inverse);
    return draw_light_surfaces(s, r, scene, buffer, err);
}

/* Issue 32: where the light moved on screen since the last frame, from the
 * photons of the same light-view texels then and now (motion.comp), for
 * temporal_accumulate to take the history from where the caustic was. */
static bool light_motion(struct photon_state *s, struct renderer *r, const struct pass_frame *f, int buffer,
                         const struct gl_texture *depth, struct error *err)
{
    if (s->motion.width != f->width || s->motion.height != f->height || !s->motion.id) {
        gl_texture_destroy(&s->motion);
        if (!gl_texture_create(&s->motion, GL_TEXTURE_2D_ARRAY, GL_R32I, f->width, f->height, 3, err))
            return false;
    }
    const GLint zero = 0;
    gl.ClearTexImage(s->motion.id, 0, GL_RED_INTEGER, GL_INT, &zero);
    struct gl_program *prog;
    if (!gl_program_get_compute(&r->programs, "photon_caustics/motion.comp", NULL, NULL, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    bind_impostors(s, prog);
    gl_program_bind_texture(prog, "u_photons", s->photons.id);
    gl_program_bind_texture(prog, "u_previous", s->photons_previous.id);
    gl_program_bind_texture(prog, "u_depth", depth->id);
    gl_program_bind_image(prog, "u_motion", s->motion.id, GL_TRUE, GL_READ_WRITE, GL_R32I);
    /* texel p sampled the unjittered grid at p - j (the jitter moves the
     * image by +j): last frame the same ray was at p + j_prev - j_now */
    gl.ProgramUniform2f(prog->id, gl_program_uniform(prog, "u_shift"), s->jitter_previous[0] - s->jitter[0],
                        s->jitter_previous[1] - s->jitter[1]);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_buffer"), buffer);
    gl_program_dispatch(prog, buffer, buffer, 1, GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return true;
}

/* §3.2: the photons into each receiver's caustic texture, over the box they
 * landed in (issue 8) where the camera may see them (issue 27; window.glsl,
 * bounds.comp): after a new photon buffer, and when the camera's view
 * changed. */
static bool build_caustic_textures(struct photon_state *s, struct renderer *r, int buffer, int texture,
                                   struct error *err)
{
    if (!s->windows) {
        gl.CreateBuffers(1, &s->windows);
        gl.NamedBufferStorage(s->windows, IMPOSTOR_MAX * PHOTON_WINDOW_STRIDE * sizeof(GLuint), NULL,
                              GL_DYNAMIC_STORAGE_BIT);
    }
    GLuint empty[IMPOSTOR_MAX * PHOTON_WINDOW_STRIDE];
    for (int i = 0; i < IMPOSTOR_MAX; i++) {
        GLuint *w = empty + PHOTON_WINDOW_STRIDE * i;
        w[0] = w[1] = w[5] = w[6] = 65535u; /* lo */
        w[2] = w[3] = w[7] = w[8] = 0u;     /* hi */
        w[4] = 0u;                          /* photons the camera may see */
    }
    gl.NamedBufferSubData(s->windows, 0, sizeof empty, empty);
    struct gl_program *bounds;
    if (!gl_program_get_compute(&r->programs, "photon_caustics/bounds.comp", NULL, NULL, &bounds, err))
        return false;
    gl.UseProgram(bounds->id);
    gl_program_bind_texture(bounds, "u_photons", s->photons.id);
    bind_impostors(s, bounds);
    if (!gl_param_block_bind(&s->params, bounds, err))
        return false;
    gl_program_dispatch(bounds, buffer, buffer, 1, GL_SHADER_STORAGE_BARRIER_BIT);
    const GLuint zero_u = 0;
    gl.ClearTexImage(s->counts.id, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero_u);
    struct gl_program *acc;
    if (!gl_program_get_compute(&r->programs, "photon_caustics/accumulate.comp", NULL, NULL, &acc, err))
        return false;
    gl.UseProgram(acc->id);
    gl_program_bind_texture(acc, "u_photons", s->photons.id);
    gl_program_bind_texture(acc, "u_flux", s->photon_flux.id);
    gl_program_bind_image(acc, "u_counts", s->counts.id, GL_TRUE, GL_READ_WRITE, GL_R32UI);
    if (!gl_param_block_bind(&s->params, acc, err))
        return false;
    gl_program_bind_storage(acc, "PhotonWindows", s->windows);
    gl_program_dispatch(acc, buffer, buffer, 1, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    struct gl_program *filt;
    if (!gl_program_get_compute(&r->programs, "photon_caustics/filter.comp", NULL, NULL, &filt, err))
        return false;
    gl.UseProgram(filt->id);
    bind_impostors(s, filt);
    gl_program_bind_image(filt, "u_counts", s->counts.id, GL_TRUE, GL_READ_ONLY, GL_R32UI);
    gl_program_bind_image(filt, "u_caustics", s->caustics.id, GL_TRUE, GL_WRITE_ONLY, GL_RGBA32F);
    if (!gl_param_block_bind(&s->params, filt, err))
        return false;
    gl_program_dispatch(filt, texture, texture, s->impostors->count,
                        GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return true;
}

/* §3.1: the photon buffer. One fullscreen draw traces every photon. */
static bool trace_photons(struct photon_state *s, struct pass *p, struct pass_frame *f, int light_index, int buffer,
                          float orad, struct error *err)
{
    struct renderer *r = f->renderer;
    int iterations = pass_int(p, PHOTON_ITERATIONS);
    const float zero[4] = {0, 0, 0, 0};
    struct gl_program *trace;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "photon_caustics/trace.frag", NULL, &trace, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->photon_fb.id);
    gl.ClearNamedFramebufferfv(s->photon_fb.id, GL_COLOR, 0, zero);
    gl.ClearNamedFramebufferfv(s->photon_fb.id, GL_COLOR, 1, zero);
    gl.UseProgram(trace->id);
    bind_impostors(s, trace);
    gl_program_bind_texture(trace, "u_front_normal", s->light_normal[0].id);
    gl_program_bind_texture(trace, "u_back_normal", s->light_normal[1].id);
    gl_program_bind_texture(trace, "u_front_depth", s->light_depth[0].id);
    gl_program_bind_texture(trace, "u_back_depth", s->light_depth[1].id);
    gl_program_bind_texture(trace, "u_front_material", s->light_material[0].id);
    shadow_inputs_bind(p, f, trace); /* the panes between the light and the glass (its pane filter) */
    gl.ProgramUniformMatrix4fv(trace->id, gl_program_uniform(trace, "u_light_view_proj"), 1, GL_FALSE,
                               s->light_view_proj.m);
    gl.ProgramUniformMatrix4fv(trace->id, gl_program_uniform(trace, "u_light_inverse"), 1, GL_FALSE,
                               s->light_inverse.m);
    gl.ProgramUniform1i(trace->id, gl_program_uniform(trace, "u_light"), light_index);
    gl.ProgramUniform1i(trace->id, gl_program_uniform(trace, "u_iterations"), iterations);
    gl.ProgramUniform1f(trace->id, gl_program_uniform(trace, "u_buffer"), (float)buffer);
    gl.ProgramUniform1f(trace->id, gl_program_uniform(trace, "u_reach"), 2.0f * orad);
    /* each photon reads the material it meets from the light-space
     * buffers (mirror or index of refraction, tint or absorption, water's
     * one interface): several specular objects may share the view */
    gl.ProgramUniform1i(trace->id, gl_program_uniform(trace, "u_reflect_glass"),
                        pass_choice(p, PHOTON_MODE) == PHOTON_MODE_REFLECT);
    gl.Viewport(0, 0, buffer, buffer);
    renderer_draw_fullscreen(r);
    return true;
}

/* Temporal accumulation (issue 32): this frame's irradiance averaged
 * with the history, which follows the light where it moved. */
static bool accumulate_frames(struct photon_state *s, struct pass *p, struct pass_frame *f, bool unchanged,
                              int accumulate, int buffer, struct graph_resource *irr, struct graph_resource *depth,
                              struct error *err)
{
    struct renderer *r = f->renderer;
    bool moving = !unchanged && s->previous_valid;
    if (moving && !light_motion(s, r, f, buffer, &depth->texture, err))
        return false;
    int held = 0;
    if (!temporal_accumulate(&s->temporal, r, f->snapshot, &irr->texture, &depth->texture, moving ? &s->motion : NULL,
                             unchanged, accumulate, &held, err))
        return false;
    /* this frame's photons are the next one's previous */
    gl.CopyImageSubData(s->photons.id, GL_TEXTURE_2D, 0, 0, 0, 0, s->photons_previous.id, GL_TEXTURE_2D, 0, 0, 0, 0,
                        buffer, buffer, 1);
    s->jitter_previous[0] = s->jitter[0];
    s->jitter_previous[1] = s->jitter[1];
    s->previous_valid = true;
    size_t used = strlen(p->report);
    if (used + 8 < sizeof p->report)
        snprintf(p->report + used, sizeof p->report - used, "; accumulated: %s", held == 0 ? "the history starts"
                 : s->temporal.still > 1 ? "the light and geometry still, frames averaged"
                                         : "the light or geometry moved, the history clipped");
    return true;
}

/* §3.3: the caustic textures mapped onto the receivers the camera sees
 * (the receivers block's positions, into the bound framebuffer). */
static bool map_caustics(struct photon_state *s, struct pass *p, struct pass_frame *f, struct error *err)
{
    struct renderer *r = f->renderer;
    struct gl_program *map;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "photon_caustics/map.frag", NULL, &map, err))
        return false;
    gl.UseProgram(map->id);
    bind_impostors(s, map);
    gl_program_bind_texture(map, "u_caustics", s->caustics.id);
    /* the diffuse surfaces only, as shade { specular = false } draws them: the
     * refraction passes and water_surface look up that image through the
     * glass or water, so a floor under water or behind glass needs its
     * caustics too (drawing the refractors' depth hid them: no caustics at
     * all under water seen from above) */
    gl_program_bind_texture(map, "u_receiver_position", pass_frame_input(p, f, "receivers")->texture.id);
    if (!gl_param_block_bind(&s->params, map, err))
        return false;
    for (int k = 0; k < s->impostors->count; k++) {
        char name[48];
        snprintf(name, sizeof name, "u_impostor_object[%d]", k);
        gl.ProgramUniform1i(map->id, gl_program_uniform(map, name), s->impostors->items[k].object->id);
    }
    renderer_draw_fullscreen(r);
    return true;
}

/* This frame's PhotonParams: the caustic textures' and the mapping's
 * values (the photons' fixed point as this light-side build, or the last,
 * made it). */
static bool upload_params(struct photon_state *s, const struct pass *p, int texture, struct error *err)
{
    const struct photon_params values = {
        .fit = pass_flag(p, PHOTON_FIT),
        .texture = texture,
        .footprint = (float)pass_real(p, PHOTON_FOOTPRINT),
        .k = pass_int(p, PHOTON_K),
        .s = (float)pass_real(p, PHOTON_S),
        .fixed_point = s->fixed_point,
        .bias = (float)pass_real(p, PHOTON_BIAS),
        .pixel_samples = pass_int(p, PHOTON_PIXEL_SAMPLES),
    };
    return gl_param_block_upload(&s->params, &values, err);
}

static bool photon_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct photon_state *s = p->state;
    struct renderer *r = f->renderer;
    struct light *light = pass_light_at(p, PHOTON_LIGHT);
    int light_index = renderer_light_slot(f->renderer, f->scene, light);
    if (light_index < 0)
        return error_set(err, "its light was never added to the scene (use scene:add(light))");
    /* the receivers' impostors: the impostors block's, made before this pass (§3.2) */
    s->impostors = pass_frame_record(p, f, "impostors", &IMPOSTOR_SET_RECORD);
    if (!s->impostors)
        return error_set(err, "its impostors ('%s') were not made this frame", pass_frame_input(p, f, "impostors")->name);
    vec3 oc = {0, 0, 0};
    float orad = 1.0f; /* photon_needed left the pass out when nothing is specular */
    specular_bounds(f->scene, &oc, &orad);
    int buffer = pass_int(p, PHOTON_BUFFER), texture = pass_int(p, PHOTON_TEXTURE);
    /* the light side depends on the light, the geometry and the parameters,
     * not on the camera (§4) */
    uint64_t key = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY);
    /* accumulating, every frame traces a jittered grid: nothing is reused */
    int accumulate = pass_int(p, PHOTON_ACCUMULATE);
    bool unchanged = pass_frame_reusable(f, s->valid, s->key, key);
    bool reuse = accumulate <= 1 && unchanged;
    if (accumulate <= 1) {
        temporal_reset(&s->temporal);
        s->previous_valid = false;
    }
    snprintf(p->report, sizeof p->report, "%s",
             reuse ? "the photon buffer and caustic textures reused (the light and the geometry did not change since "
                     "the last frame); the caustic mapping from the camera runs every frame"
                   : "photons traced from the light into new caustic textures");
    size_t used = strlen(p->report);
    if (!reuse) {
        if (!ensure_textures(s, buffer, texture, s->impostors->count, err))
            return false;
        /* The light's view of the refractors' bounding sphere (then narrowed
         * to what they cover, fit_light_view): wider margins than the
         * layers', and a light inside the sphere sees it at 69 degrees
         * either side. */
        static const struct light_view_margins margins = {
            .radius_scale = 1.0f, .eye_radii = 3.0f, .ortho_near_radii = 0.5f, .ortho_far_radii = 6.0f,
            .fov_scale = 1.05f, .near_scale = 0.5f, .far_radii = 2.0f, .inside_half_angle = 1.2f,
            .up_z_when_vertical = false,
        };
        struct light_view lv;
        light_view_fit(light->kind == LIGHT_DIRECTIONAL, light_center(light), light->direction, oc, orad, &margins, &lv);
        mat4 view = lv.view, proj = lv.proj;
        /* accumulating: the grid moved by this frame's sub-texel offset, in
         * clip space (as TAA jitters a camera's projection), after the
         * narrowing (fit_light_view), so that the narrowed view is the same
         * every frame and 16 frames' grids interleave into one 4 x 4 as dense */
        mat4 jitter = mat4_identity();
        if (accumulate > 1) {
            temporal_jitter(&s->temporal, &s->jitter[0], &s->jitter[1]);
            jitter.m[12] = 2.0f * s->jitter[0] / (float)buffer;
            jitter.m[13] = 2.0f * s->jitter[1] / (float)buffer;
        }
        s->light_view_proj = mat4_mul(proj, view);
        mat4_inverse(s->light_view_proj, &s->light_inverse);

        /* Front and back surfaces of the refractors from the light (§2.1, in
         * its view), the view then narrowed to the texels they cover. */
        if (!draw_light_surfaces(s, r, f->scene, buffer, err) ||
            !fit_light_view(s, r, f->scene, buffer, view, jitter, &proj, err))
            return false;

        if (!trace_photons(s, p, f, light_index, buffer, orad, err))
            return false;

        /* §3.2: accumulate into the caustic textures (fixed point: the
         * scale keeps even all the light in one texel below 2^31). */
        vec3 e = light->intensity;
        double total = light_view_flux_bound(fmaxf(e.x, fmaxf(e.y, e.z)), &proj);
        s->fixed_point = (float)(2.0e9 / fmax(total, 1e-20));
        s->valid = true;
        if (s->coverage > 0.0f && used + 8 < sizeof p->report)
            snprintf(p->report + used, sizeof p->report - used, " (the light's view narrowed to the specular objects' "
                     "box, %.0f%% of the area it first had)", 100.0 * s->coverage);
        s->key = key;
    }
    if (!upload_params(s, p, texture, err))
        return false;
    /* The caustic textures cover the box the photons landed in where the
     * camera may see them (bounds.comp), so a moved camera rebuilds them
     * from the photon buffer, which it does not change (§4). */
    uint64_t view_key = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY | PASS_DEPENDS_CAMERA);
    if (!reuse || (pass_flag(p, PHOTON_FIT) && view_key != s->view_key)) {
        if (reuse && used + 8 < sizeof p->report)
            snprintf(p->report + used, sizeof p->report - used, "; the caustic textures rebuilt for the camera's view");
        if (s->impostors->count > 0 && !build_caustic_textures(s, r, buffer, texture, err))
            return false;
        s->view_key = view_key;
    }

    /* §3.3: caustic mapping onto the receivers the camera sees. */
    struct graph_resource *irr = pass_frame_output(p, f, "irradiance"), *depth = pass_frame_output(p, f, "depth");
    const struct gl_texture *c[1] = {&irr->texture};
    if (!gl_framebuffer_attach(&s->map_fb, c, NULL, 1, &depth->texture, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->map_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    const float zero[4] = {0, 0, 0, 0};
    gl.ClearNamedFramebufferfv(s->map_fb.id, GL_COLOR, 0, zero);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    if (s->impostors->count == 0)
        return true;
    /* this pass's depth: the receivers' (what the mapping covered), which
     * the coverage check and the history's reprojection read */
    const struct graph_resource *receiver_depth = pass_frame_input(p, f, "receiver_depth");
    gl.CopyImageSubData(receiver_depth->texture.id, GL_TEXTURE_2D, 0, 0, 0, 0, depth->texture.id, GL_TEXTURE_2D, 0, 0, 0,
                        0, f->width, f->height, 1);
    if (!map_caustics(s, p, f, err))
        return false;
    /* the light's front depths and normals as the photons were last traced
     * (the view and projection in one matrix) */
    if (!caustic_coverage_check(&s->dark_check, p, f, &f->snapshot->lights[light_index],
                                &(struct caustic_coverage_view){.depth = s->light_depth[0].id,
                                                                .normal = s->light_normal[0].id,
                                                                .view = mat4_identity(), .proj = s->light_view_proj},
                                depth->texture.id, 0,
                                &irr->texture, "raise `buffer` (the photons' spacing)", err))
        return false;
    return accumulate <= 1 || accumulate_frames(s, p, f, unchanged, accumulate, buffer, irr, depth, err);
}

/* Photons refract at the interpolated normal, all of them: rough or
 * partly diffuse glass as smooth, clear glass. */
static const char *photon_caustics_leaves_out(const struct pass *p, const struct scene *scene, const struct object *o)
{
    if (object_is(o, OBJECT_ROLE_THIN))
        return shadow_inputs_pane_left_out(p, scene, o);
    return pass_refractor_left_out(o, true);
}

/* Its impostors: the receivers at the caustic textures' size, lit
 * through its shadow maps (the photons read their depth alone; lit alike,
 * a refraction pass's at the same size shares them). */
static bool photon_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    if (param == PHOTON_RECEIVERS) /* the mapping reads their positions */
        return pass_set_boolean(block, "position", true, err);
    if (param != PHOTON_IMPOSTORS)
        return true;
    return impostors_configure_block(block, pass_int(p, PHOTON_TEXTURE), 0, p, PHOTON_SHADOW, err);
}

const struct pass_desc photon_caustics_pass = {
    .configure_block = photon_configure_block,
    .technique = PASS_TECHNIQUE_CAUSTICS,
    .surface_caustics_only = true,
    .leaves_out = photon_caustics_leaves_out,
    .name = "photon_caustics",
    .summary = "Hu & Qin §3: photon buffer from the light, caustic textures per receiver, caustic mapping",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = photon_declare,
    .create = photon_create,
    .execute = photon_execute,
    .needed = photon_needed,
    .destroy = photon_destroy,
};
