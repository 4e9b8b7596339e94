#include "graph/renderer.h"

#include "core/brdf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What stays bound for every pass, reserved in every program before the
 * first is built (common/frame.glsl); everything else a pass binds by name
 * (gl_program_bind_*). */
#define RENDERER_BINDING_FRAME 0
#define RENDERER_UNIT_ENVIRONMENT 0

bool renderer_create(struct renderer *r, const char *root, struct error *err)
{
    memset(r, 0, sizeof *r);
    snprintf(r->root, sizeof r->root, "%s", root);
    char shader_root[1100];
    snprintf(shader_root, sizeof shader_root, "%s/shaders", root);
    gl_program_cache_init(&r->programs, shader_root);
    if (!gl_program_cache_reserve(&r->programs, GL_SLOT_UNIFORM_BLOCK, "Frame", RENDERER_BINDING_FRAME, 1, err) ||
        !gl_program_cache_reserve(&r->programs, GL_SLOT_TEXTURE, "u_environment", RENDERER_UNIT_ENVIRONMENT, 1,
                                  err)) {
        gl_program_cache_destroy(&r->programs);
        return false;
    }
    mesh_cache_init(&r->meshes);
    texture_cache_init(&r->textures);
    gl.CreateBuffers(1, &r->frame_ubo);
    gl.NamedBufferStorage(r->frame_ubo, sizeof r->uniforms, NULL, GL_DYNAMIC_STORAGE_BIT);
    gl.CreateVertexArrays(1, &r->empty_vao);
    gl.GenQueries(2, r->deform_queries);
    /* Dummy textures stand in for optional inputs a script did not give. */
    if (!gl_texture_create(&r->dummy_2d, GL_TEXTURE_2D, GL_RGBA16F, 1, 1, 1, err) ||
        !gl_texture_create(&r->dummy_cube, GL_TEXTURE_CUBE_MAP, GL_RGBA16F, 1, 1, 6, err) ||
        !gl_texture_create(&r->dummy_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, 1, 1, 1, err) ||
        !gl_framebuffer_create(&r->present_fb, err)) {
        renderer_destroy(r);
        return false;
    }
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    gl.ClearTexImage(r->dummy_2d.id, 0, GL_RGBA, GL_FLOAT, zero);
    gl.ClearTexImage(r->dummy_cube.id, 0, GL_RGBA, GL_FLOAT, zero);
    gl.ClearTexImage(r->dummy_depth.id, 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
    return gl_check("renderer set-up", err);
}

void renderer_destroy(struct renderer *r)
{
    gl_program_cache_destroy(&r->programs);
    mesh_cache_release(&r->meshes);
    texture_cache_release(&r->textures);
    frame_release(&r->frame);
    if (gl_api_ready()) {
        if (r->frame_ubo)
            gl.DeleteBuffers(1, &r->frame_ubo);
        if (r->empty_vao)
            gl.DeleteVertexArrays(1, &r->empty_vao);
        if (r->deform_queries[0])
            gl.DeleteQueries(2, r->deform_queries);
    }
    gl_texture_destroy(&r->dummy_2d);
    gl_texture_destroy(&r->dummy_cube);
    gl_texture_destroy(&r->dummy_depth);
    gl_texture_destroy(&r->brdf_table);
    gl_texture_destroy(&r->present_texture);
    gl_texture_destroy(&r->environment);
    r->environment_serial = 0;
    gl_texture_destroy(&r->medium_density);
    r->medium_uploaded = NULL;
    r->medium_version = 0;
    gl_framebuffer_destroy(&r->present_fb);
    r->frame_ubo = r->empty_vao = 0;
    r->deform_queries[0] = r->deform_queries[1] = 0;
}

static void copy_mat(float *dst, mat4 m) { memcpy(dst, m.m, sizeof m.m); }

/* The uniform block's lights from the snapshot (kind as a float: 0 point,
 * 1 directional, 2 spot, as shaders/common/frame.glsl reads it). */
static void fill_lights(struct renderer *r, const struct frame *f)
{
    for (int n = 0; n < f->light_count; n++) {
        const struct frame_light *l = &f->lights[n];
        struct renderer_gpu_light *g = &r->uniforms.lights[n];
        float kind = l->kind == LIGHT_DIRECTIONAL ? 1.0f : l->kind == LIGHT_SPOT ? 2.0f : 0.0f;
        g->position[0] = l->position.x;
        g->position[1] = l->position.y;
        g->position[2] = l->position.z;
        g->position[3] = kind;
        g->direction[0] = l->direction.x;
        g->direction[1] = l->direction.y;
        g->direction[2] = l->direction.z;
        g->direction[3] = l->cos_outer;
        g->intensity[0] = l->intensity.x;
        g->intensity[1] = l->intensity.y;
        g->intensity[2] = l->intensity.z;
        g->intensity[3] = l->cos_inner;
    }
    r->uniforms.counts[0] = f->light_count;
}

/* The scene's environment as a cube map, uploaded when it is not the one
 * the renderer already holds (one at a time: scenes have one). */
static bool upload_environment(struct renderer *r, const struct environment *env, struct error *err)
{
    if (r->environment.id && r->environment_serial == env->serial)
        return true;
    gl_texture_destroy(&r->environment);
    r->environment_serial = 0;
    /* with its mipmaps: glTF's glossy surfaces read them (common/surface_light.glsl's environment_glossy) */
    if (!gl_texture_create_levels(&r->environment, GL_TEXTURE_CUBE_MAP, GL_RGBA16F, env->size, env->size, 6, 0, err))
        return false;
    float *rgba = malloc((size_t)env->size * (size_t)env->size * 4 * sizeof(float));
    if (!rgba)
        return error_set(err, "out of memory");
    for (int f = 0; f < 6; f++) {
        for (size_t i = 0; i < (size_t)env->size * (size_t)env->size; i++) {
            memcpy(rgba + i * 4, env->faces[f] + i * 3, 3 * sizeof(float));
            rgba[i * 4 + 3] = 1.0f;
        }
        /* Cube map faces are stored with their first row at the top of the
         * image as OpenGL expects (t grows downward in face space). */
        gl.TextureSubImage3D(r->environment.id, 0, 0, 0, f, env->size, env->size, 1, GL_RGBA, GL_FLOAT, rgba);
    }
    free(rgba);
    gl.GenerateTextureMipmap(r->environment.id);
    r->environment_serial = env->serial;
    return gl_check("uploading the environment", err);
}

bool renderer_begin_frame(struct renderer *r, struct scene *scene, int width, int height, int frame, double time,
                          struct error *err)
{
    if (!frame_build(&r->frame, scene, width, height, frame, time, err))
        return false;
    const struct frame *f = &r->frame;
    if (!mesh_cache_begin_frame(&r->meshes, scene, err))
        return false;
    texture_cache_begin_frame(&r->textures, scene);
    if (scene->environment && !upload_environment(r, scene->environment, err))
        return false;
    gl.QueryCounter(r->deform_queries[0], GL_TIMESTAMP);
    bool deformed = deform_update(r, scene, time, err);
    gl.QueryCounter(r->deform_queries[1], GL_TIMESTAMP);
    if (!deformed)
        return false;
    GLuint64 t0 = 0, t1 = 0;
    gl.GetQueryObjectui64v(r->deform_queries[0], GL_QUERY_RESULT, &t0);
    gl.GetQueryObjectui64v(r->deform_queries[1], GL_QUERY_RESULT, &t1);
    r->deform_ms = t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
    struct renderer_frame_uniforms *u = &r->uniforms;
    memset(u, 0, sizeof *u);
    copy_mat(u->view, f->view);
    copy_mat(u->proj, f->proj);
    copy_mat(u->view_proj, f->view_proj);
    copy_mat(u->inv_view_proj, f->inv_view_proj);
    u->camera_pos[0] = f->eye.x;
    u->camera_pos[1] = f->eye.y;
    u->camera_pos[2] = f->eye.z;
    u->camera_pos[3] = (float)time;
    u->viewport[0] = (float)width;
    u->viewport[1] = (float)height;
    u->viewport[2] = 1.0f / (float)width;
    u->viewport[3] = 1.0f / (float)height;
    u->background[0] = scene->background.x;
    u->background[1] = scene->background.y;
    u->background[2] = scene->background.z;
    u->background[3] = scene->environment ? 1.0f : 0.0f;
    u->ambient[0] = scene->ambient.x;
    u->ambient[1] = scene->ambient.y;
    u->ambient[2] = scene->ambient.z;
    u->counts[1] = frame;
    fill_lights(r, f);
    gl.NamedBufferSubData(r->frame_ubo, 0, sizeof *u, u);
    renderer_reset_state(r);
    /* The environment stays bound for every pass. */
    gl.BindTextureUnit(RENDERER_UNIT_ENVIRONMENT,
                       scene->environment ? r->environment.id : r->dummy_cube.id);
    return gl_check("frame set-up", err);
}

void renderer_reset_state(struct renderer *r)
{
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.DepthMask(GL_TRUE);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.DepthFunc(GL_LESS);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, RENDERER_BINDING_FRAME, r->frame_ubo);
    gl.UseProgram(0);
    gl.BindVertexArray(0);
}

/* The material's textures and the uniforms of
 * common/material.glsl (a program without them ignores the locations -1). */
/* base colour, normal, emissive, metallic-roughness, occlusion, specular, specular colour, clearcoat, clearcoat
 * roughness, clearcoat normal */
enum { MATERIAL_SLOTS = 10 };

struct material_locations {
    GLint set[MATERIAL_SLOTS], transform[MATERIAL_SLOTS * 2], normal_scale, alpha, alpha_cutoff, alpha_blend, single_sided;
    GLint transmission_set, transmission_transform[2];
    GLint thickness_set, thickness_transform[2];
    GLint metallic, roughness, ior, occlusion_strength, specular, specular_color;
    GLint clearcoat, clearcoat_roughness, clearcoat_normal_scale;
    /* the samplers' units (-1: not used), in the slots' order, then the
     * transmission, thickness and BRDF-table textures */
    int unit[MATERIAL_SLOTS], transmission_unit, thickness_unit, brdf_table_unit;
};

static const char *const material_samplers[MATERIAL_SLOTS] = {
    "u_base_color_texture", "u_normal_texture", "u_emissive_texture", "u_metallic_roughness_texture",
    "u_occlusion_texture", "u_specular_texture", "u_specular_color_texture", "u_clearcoat_texture",
    "u_clearcoat_roughness_texture", "u_clearcoat_normal_texture"};

static void material_locations_find(const struct gl_program *program, struct material_locations *loc)
{
    for (int s = 0; s < MATERIAL_SLOTS; s++)
        loc->unit[s] = gl_program_unit(program, GL_SLOT_TEXTURE, material_samplers[s]);
    loc->transmission_unit = gl_program_unit(program, GL_SLOT_TEXTURE, "u_transmission_texture");
    loc->thickness_unit = gl_program_unit(program, GL_SLOT_TEXTURE, "u_thickness_texture");
    loc->brdf_table_unit = gl_program_unit(program, GL_SLOT_TEXTURE, "u_brdf_table");
    for (int s = 0; s < MATERIAL_SLOTS; s++) {
        char name[64];
        snprintf(name, sizeof name, "u_texture_set[%d]", s);
        loc->set[s] = gl_program_uniform_optional(program, name);
    }
    for (int row = 0; row < MATERIAL_SLOTS * 2; row++) {
        char name[64];
        snprintf(name, sizeof name, "u_texture_transform[%d]", row);
        loc->transform[row] = gl_program_uniform_optional(program, name);
    }
    loc->normal_scale = gl_program_uniform_optional(program, "u_normal_scale");
    loc->alpha = gl_program_uniform_optional(program, "u_alpha");
    loc->alpha_cutoff = gl_program_uniform_optional(program, "u_alpha_cutoff");
    loc->single_sided = gl_program_uniform_optional(program, "u_single_sided");
    loc->alpha_blend = gl_program_uniform_optional(program, "u_alpha_blend");
    loc->transmission_set = gl_program_uniform_optional(program, "u_transmission_set");
    loc->transmission_transform[0] = gl_program_uniform_optional(program, "u_transmission_transform[0]");
    loc->transmission_transform[1] = gl_program_uniform_optional(program, "u_transmission_transform[1]");
    loc->thickness_set = gl_program_uniform_optional(program, "u_thickness_set");
    loc->thickness_transform[0] = gl_program_uniform_optional(program, "u_thickness_transform[0]");
    loc->thickness_transform[1] = gl_program_uniform_optional(program, "u_thickness_transform[1]");
    loc->metallic = gl_program_uniform_optional(program, "u_metallic");
    loc->roughness = gl_program_uniform_optional(program, "u_pbr_roughness");
    loc->ior = gl_program_uniform_optional(program, "u_pbr_ior");
    loc->occlusion_strength = gl_program_uniform_optional(program, "u_occlusion_strength");
    loc->specular = gl_program_uniform_optional(program, "u_specular");
    loc->specular_color = gl_program_uniform_optional(program, "u_specular_color");
    loc->clearcoat = gl_program_uniform_optional(program, "u_clearcoat");
    loc->clearcoat_roughness = gl_program_uniform_optional(program, "u_clearcoat_roughness");
    loc->clearcoat_normal_scale = gl_program_uniform_optional(program, "u_clearcoat_normal_scale");
}

/* The glTF BRDF's ambient table (core/brdf.h), read texel by texel by
 * common/brdf.glsl: uploaded once, when a glTF surface is first drawn. */
static GLuint brdf_table_texture(struct renderer *r)
{
    if (r->brdf_table.id)
        return r->brdf_table.id;
    struct error err;
    if (!gl_texture_create(&r->brdf_table, GL_TEXTURE_2D, GL_RGBA32F, BRDF_TABLE_SIZE, BRDF_TABLE_SIZE, 1, &err))
        return r->dummy_2d.id;
    const float *t = brdf_ambient_table();
    static float rgba[BRDF_TABLE_SIZE * BRDF_TABLE_SIZE * 4];
    for (int i = 0; i < BRDF_TABLE_SIZE * BRDF_TABLE_SIZE; i++) {
        rgba[i * 4] = t[i * 3], rgba[i * 4 + 1] = t[i * 3 + 1], rgba[i * 4 + 2] = t[i * 3 + 2];
        rgba[i * 4 + 3] = 0.0f;
    }
    gl.TextureSubImage2D(r->brdf_table.id, 0, 0, 0, BRDF_TABLE_SIZE, BRDF_TABLE_SIZE, GL_RGBA, GL_FLOAT, rgba);
    return r->brdf_table.id;
}

static void bind_material_textures(struct renderer *r, const struct gl_program *program,
                                   const struct material_locations *loc, const struct object *o)
{
    const struct texture_ref *slots[MATERIAL_SLOTS] = {&o->material.base_color, &o->material.normal,
                                                       &o->material.emissive, &o->material.metallic_roughness,
                                                       &o->material.occlusion, &o->material.specular_map,
                                                       &o->material.specular_color_map, &o->material.clearcoat_map,
                                                       &o->material.clearcoat_roughness_map,
                                                       &o->material.clearcoat_normal};
    /* Textures apply to diffuse surfaces only, in both renderers; a set the
     * mesh lacks reads nothing (the glTF loader refuses that case). (Glass:
     * its base colour texture, which tints it; glass and mirrors: their
     * normal map, which refraction maps, and the base colour's alpha where
     * it cuts or blends them.) */
    unsigned role = material_role(&o->material);
    bool cut = o->material.alpha_cutoff > 0.0f || o->material.alpha_blend;
    for (int s = 0; s < MATERIAL_SLOTS; s++) {
        const struct texture_ref *ref = slots[s];
        GLuint id = 0;
        struct error err;
        bool slot_used = material_is_textured_surface(&o->material) || (s == 0 && (role == OBJECT_ROLE_GLASS || cut)) ||
                         (s == 1 && (role == OBJECT_ROLE_GLASS || role == OBJECT_ROLE_MIRROR));
        bool on = ref->texture && slot_used && o->mesh->texcoords[ref->texcoord] &&
                  texture_cache_get(&r->textures, ref->texture, s == 0 || s == 2 || s == 6, &id, &err); /* colours are sRGB */
        gl_program_bind_texture_unit(loc->unit[s], on ? id : r->dummy_2d.id);
        gl.ProgramUniform1i(program->id, loc->set[s], on ? ref->texcoord + 1 : 0);
        const float *m = ref->transform;
        gl.ProgramUniform3f(program->id, loc->transform[s * 2], m[0], m[2], m[4]);
        gl.ProgramUniform3f(program->id, loc->transform[s * 2 + 1], m[1], m[3], m[5]);
    }
    gl.ProgramUniform1f(program->id, loc->normal_scale, o->material.normal.scale);
    bool pbr = o->material.pbr && material_role(&o->material) == OBJECT_ROLE_RECEIVER;
    gl.ProgramUniform1f(program->id, loc->metallic, o->material.metallic);
    gl.ProgramUniform1f(program->id, loc->roughness, o->material.roughness);
    gl.ProgramUniform1f(program->id, loc->ior, o->material.ior);
    gl.ProgramUniform1f(program->id, loc->occlusion_strength, o->material.occlusion_strength);
    gl.ProgramUniform1f(program->id, loc->specular, o->material.specular);
    gl.ProgramUniform3f(program->id, loc->specular_color, o->material.specular_color.x, o->material.specular_color.y,
                        o->material.specular_color.z);
    gl.ProgramUniform1f(program->id, loc->clearcoat, pbr ? o->material.clearcoat : 0.0f);
    gl.ProgramUniform1f(program->id, loc->clearcoat_roughness, o->material.clearcoat_roughness);
    gl.ProgramUniform1f(program->id, loc->clearcoat_normal_scale, o->material.clearcoat_normal.scale);
    if (pbr)
        gl_program_bind_texture_unit(loc->brdf_table_unit, brdf_table_texture(r));
    /* cut-outs and blending on every surface the loader gave them (glTF's
     * alphaMode: diffuse surfaces, glass and mirrors); single-sidedness on
     * diffuse surfaces and thin glass only */
    bool diffuse = material_is_textured_surface(&o->material);
    gl.ProgramUniform1f(program->id, loc->alpha, o->material.alpha);
    gl.ProgramUniform1f(program->id, loc->alpha_cutoff, o->material.alpha_cutoff);
    gl.ProgramUniform1i(program->id, loc->alpha_blend, o->material.alpha_blend);
    gl.ProgramUniform1i(program->id, loc->single_sided, diffuse && o->material.single_sided);
    /* glass's transmission texture (its red channel, linear), which refraction reads */
    const struct texture_ref *tm = &o->material.transmission_map;
    GLuint tid = 0;
    struct error err;
    bool tm_on = tm->texture && (material_role(&o->material) & (OBJECT_ROLE_REFRACTOR | OBJECT_ROLE_THIN)) &&
                 o->mesh->texcoords[tm->texcoord] && texture_cache_get(&r->textures, tm->texture, false, &tid, &err);
    gl_program_bind_texture_unit(loc->transmission_unit, tm_on ? tid : r->dummy_2d.id);
    gl.ProgramUniform1i(program->id, loc->transmission_set, tm_on ? tm->texcoord + 1 : 0);
    gl.ProgramUniform3f(program->id, loc->transmission_transform[0], tm->transform[0], tm->transform[2], tm->transform[4]);
    gl.ProgramUniform3f(program->id, loc->transmission_transform[1], tm->transform[1], tm->transform[3], tm->transform[5]);
    /* solid glass's thickness texture (its green channel, linear), which shade's one interface reads */
    if (loc->thickness_set < 0)
        return;
    const struct texture_ref *th = &o->material.thickness_map;
    GLuint thid = 0;
    bool th_on = th->texture && material_role(&o->material) == OBJECT_ROLE_GLASS && o->mesh->texcoords[th->texcoord] &&
                 texture_cache_get(&r->textures, th->texture, false, &thid, &err);
    gl_program_bind_texture_unit(loc->thickness_unit, th_on ? thid : r->dummy_2d.id);
    gl.ProgramUniform1i(program->id, loc->thickness_set, th_on ? th->texcoord + 1 : 0);
    gl.ProgramUniform3f(program->id, loc->thickness_transform[0], th->transform[0], th->transform[2], th->transform[4]);
    gl.ProgramUniform3f(program->id, loc->thickness_transform[1], th->transform[1], th->transform[3], th->transform[5]);
}

struct blended_object {
    int index;
    float distance;
};

static int farther_first(const void *a, const void *b)
{
    float da = ((const struct blended_object *)a)->distance, db = ((const struct blended_object *)b)->distance;
    return (da < db) - (da > db);
}

/* What renderer_draw_objects looks up in a program: found by name once per
 * link (gl_program_attached), not at every call (issue 54's look-ups a
 * frame). -1 where the program lacks it. */
struct draw_locations {
    struct material_locations material;
    GLint model, normal, role, color, ior, roughness, transmission, thickness, tint, ideal, emission, absorption,
        object_id, vertex_colors, tangents;
};

static const struct draw_locations *draw_locations_of(const struct gl_program *program)
{
    static struct draw_locations fallback; /* (out of memory: found again, into this) */
    bool made = false;
    struct draw_locations *d = gl_program_attached(program, sizeof *d, &made);
    if (d && !made)
        return d;
    if (!d)
        d = &fallback;
    material_locations_find(program, &d->material);
    d->model = gl_program_uniform_optional(program, "u_model");
    d->normal = gl_program_uniform_optional(program, "u_normal_matrix");
    d->role = gl_program_uniform_optional(program, "u_object_role");
    d->color = gl_program_uniform_optional(program, "u_color");
    d->ior = gl_program_uniform_optional(program, "u_ior");
    d->roughness = gl_program_uniform_optional(program, "u_roughness");
    d->transmission = gl_program_uniform_optional(program, "u_transmission");
    d->thickness = gl_program_uniform_optional(program, "u_thickness");
    d->tint = gl_program_uniform_optional(program, "u_tint");
    d->ideal = gl_program_uniform_optional(program, "u_ideal");
    d->emission = gl_program_uniform_optional(program, "u_emission");
    d->absorption = gl_program_uniform_optional(program, "u_absorption");
    d->object_id = gl_program_uniform_optional(program, "u_object_id");
    d->vertex_colors = gl_program_uniform_optional(program, "u_vertex_colors");
    d->tangents = gl_program_uniform_optional(program, "u_has_tangents");
    return d;
}

void renderer_draw_objects(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                           unsigned filter)
{
    const struct draw_locations *d = draw_locations_of(program);
    const struct material_locations *material_loc = &d->material;
    GLint loc_model = d->model, loc_normal = d->normal, loc_role = d->role, loc_color = d->color, loc_ior = d->ior;
    GLint loc_roughness = d->roughness, loc_transmission = d->transmission, loc_thickness = d->thickness;
    GLint loc_tint = d->tint, loc_ideal = d->ideal, loc_emission = d->emission, loc_abs = d->absorption;
    GLint loc_id = d->object_id, loc_vertex_colors = d->vertex_colors, loc_tangents = d->tangents;
    gl.UseProgram(program->id);
    /* DRAW_BLENDED: the blended surfaces back to front, by the distance
     * from the eye to each object's box centre (per object, not per
     * triangle), sorted once; out of memory, in scene order */
    int count = scene->object_count;
    struct blended_object *order = NULL;
    if ((filter & (DRAW_BLENDED | DRAW_THIN)) && (order = malloc((size_t)(count + 1) * sizeof *order))) {
        count = 0;
        for (int i = 0; i < scene->object_count; i++) {
            const struct object *o = scene->objects[i];
            if (!o->visible || !((filter & DRAW_BLENDED) ? o->material.alpha_blend : object_is(o, OBJECT_ROLE_THIN)))
                continue;
            vec3 lo, hi;
            object_world_bounds(o, &lo, &hi);
            order[count++] = (struct blended_object){
                i, vec3_length(vec3_sub(vec3_scale(vec3_add(lo, hi), 0.5f), r->frame.eye))};
        }
        qsort(order, (size_t)count, sizeof *order, farther_first);
    }
    for (int n = 0; n < count; n++) {
        struct object *o = scene->objects[order ? order[n].index : n];
        if (!o->visible)
            continue;
        if ((filter & DRAW_CASTERS) && !o->cast_shadows)
            continue;
        /* thin glass: drawn where asked for by name (shade blends it over
         * what lies behind; the shadow map's filter), or by DRAW_ALL */
        bool thin = object_is(o, OBJECT_ROLE_THIN);
        if (filter != DRAW_ALL && thin != ((filter & DRAW_THIN) != 0))
            continue;
        bool blended = o->material.alpha_blend;
        if (((filter & DRAW_OPAQUE) && blended) || ((filter & DRAW_BLENDED) && !blended))
            continue;
        bool pbr = o->material.pbr && material_role(&o->material) == OBJECT_ROLE_RECEIVER;
        if (((filter & DRAW_LAMBERT) && pbr) || ((filter & DRAW_PBR) && !pbr))
            continue;
        bool specular = object_is(o, OBJECT_ROLE_SPECULAR);
        if ((filter & DRAW_DIFFUSE) && specular)
            continue;
        if ((filter & DRAW_SPECULAR) && !specular)
            continue;
        const struct frame_object *fo = frame_object_of(&r->frame, o);
        if (!fo)
            continue; /* not in the scene this frame was built for */
        gl.ProgramUniformMatrix4fv(program->id, loc_model, 1, GL_FALSE, fo->model.m);
        gl.ProgramUniformMatrix4fv(program->id, loc_normal, 1, GL_FALSE, fo->normal_matrix.m);
        gl.ProgramUniform1i(program->id, loc_role, (GLint)material_role(&o->material)); /* common/roles.glsl */
        gl.ProgramUniform3f(program->id, loc_color, o->material.color.x, o->material.color.y, o->material.color.z);
        gl.ProgramUniform1f(program->id, loc_ior, o->material.ior);
        gl.ProgramUniform1f(program->id, loc_roughness, o->material.roughness);
        gl.ProgramUniform1f(program->id, loc_transmission, o->material.transmission);
        gl.ProgramUniform3f(program->id, loc_tint, o->material.tint.x, o->material.tint.y, o->material.tint.z);
        /* thicknessFactor is in the mesh's units: scaled by the object (its mean scale) */
        gl.ProgramUniform1f(program->id, loc_thickness,
                            o->material.thickness * (fabsf(o->scale.x) + fabsf(o->scale.y) + fabsf(o->scale.z)) / 3.0f);
        gl.ProgramUniform1f(program->id, loc_ideal, o->material.ideal ? 1.0f : 0.0f);
        gl.ProgramUniform3f(program->id, loc_emission, o->material.emission.x, o->material.emission.y,
                            o->material.emission.z);
        gl.ProgramUniform3f(program->id, loc_abs, o->material.absorption.x, o->material.absorption.y,
                            o->material.absorption.z);
        gl.ProgramUniform1i(program->id, loc_id, o->id);
        /* COLOR_0 on the surfaces whose base colour it multiplies (diffuse, as textures) */
        gl.ProgramUniform1i(program->id, loc_vertex_colors,
                            o->mesh->colors && material_is_textured_surface(&o->material));
        gl.ProgramUniform1i(program->id, loc_tangents, o->mesh->tangents != NULL);
        bind_material_textures(r, program, material_loc, o);
        struct error err;
        if (!mesh_cache_bind(&r->meshes, o, &err))
            continue; /* out of memory: the object is not drawn (mesh_cache_begin_frame said so first) */
        gl.DrawElements(GL_TRIANGLES, (GLsizei)o->mesh->index_count, GL_UNSIGNED_INT, NULL);
        r->draw_calls++;
        r->draw_triangles += (long)(o->mesh->index_count / 3);
    }
    free(order);
    gl.BindVertexArray(0);
}

static bool scene_has_pbr(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (o->visible && o->material.pbr && material_role(&o->material) == OBJECT_ROLE_RECEIVER)
            return true;
    }
    return false;
}

bool renderer_lit_programs(struct renderer *r, const struct scene *scene, const char *vert, const char *frag,
                           const char *defines, struct gl_program *progs[2], struct error *err)
{
    progs[0] = progs[1] = NULL;
    if (!gl_program_get(&r->programs, vert, frag, defines, &progs[0], err))
        return false;
    if (!scene_has_pbr(scene))
        return true;
    char variant[512];
    snprintf(variant, sizeof variant, "%s#define GLTF_BRDF\n", defines ? defines : "");
    return gl_program_get(&r->programs, vert, frag, variant, &progs[1], err);
}

void renderer_draw_lit(struct renderer *r, const struct scene *scene, const struct gl_program *plain,
                       const struct gl_program *pbr, unsigned filter)
{
    renderer_draw_objects(r, scene, plain, filter | (pbr ? DRAW_LAMBERT : 0));
    if (pbr)
        renderer_draw_objects(r, scene, pbr, filter | DRAW_PBR);
}

void renderer_draw_object(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                          struct object *object)
{
    struct scene only = *scene;
    struct object *list[1] = {object};
    only.objects = list;
    only.object_count = 1;
    renderer_draw_objects(r, &only, program, DRAW_ALL);
}

int renderer_light_slot(const struct renderer *r, const struct scene *scene, const struct light *light)
{
    int index = scene_light_index(scene, light);
    return index >= 0 && index < SCENE_MAX_GPU_LIGHTS ? r->frame.light_first[index] : -1;
}

void renderer_run_fullscreen(struct renderer *r, const struct gl_program *program, GLuint framebuffer, int width,
                             int height, const struct renderer_shader_input *inputs, int input_count,
                             const struct renderer_shader_uniform *uniforms, int uniform_count, double time)
{
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.Viewport(0, 0, width, height);
    gl.UseProgram(program->id);
    for (int i = 0; i < input_count && i < RENDERER_MAX_SHADER_INPUTS; i++)
        gl_program_bind_texture(program, inputs[i].sampler, inputs[i].texture);
    for (int i = 0; i < uniform_count; i++) {
        GLint loc = gl_program_uniform(program, uniforms[i].name);
        const float *v = uniforms[i].value;
        switch (uniforms[i].size) {
        case 1: gl.ProgramUniform1f(program->id, loc, v[0]); break;
        case 2: gl.ProgramUniform2f(program->id, loc, v[0], v[1]); break;
        case 3: gl.ProgramUniform3f(program->id, loc, v[0], v[1], v[2]); break;
        default: gl.ProgramUniform4f(program->id, loc, v[0], v[1], v[2], v[3]); break;
        }
    }
    /* a script's shader may not use the time */
    gl.ProgramUniform1f(program->id, gl_program_uniform_optional(program, "u_time"), (float)time);
    renderer_draw_fullscreen(r);
}

void renderer_draw_fullscreen(struct renderer *r)
{
    gl.BindVertexArray(r->empty_vao);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    gl.BindVertexArray(0);
}

bool renderer_draw_copy(struct renderer *r, GLuint framebuffer, int width, int height, GLuint texture,
                        struct error *err)
{
    struct gl_program *copy;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "common/copy.frag", NULL, &copy, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.Viewport(0, 0, width, height);
    gl.Disable(GL_DEPTH_TEST);
    gl.UseProgram(copy->id);
    gl_program_bind_texture(copy, "u_image", texture);
    renderer_draw_fullscreen(r);
    return true;
}

bool renderer_first_surface(struct renderer *r, const struct scene *scene, int width, int height, struct image *out,
                            struct error *err)
{
    struct gl_texture target = {0}, depth = {0};
    struct gl_framebuffer fb = {0};
    struct gl_program *prog;
    const struct gl_texture *colors[1] = {&target};
    bool ok = gl_program_get(&r->programs, "common/object.vert", "common/first_surface.frag", NULL, &prog, err) &&
              gl_texture_create(&target, GL_TEXTURE_2D, GL_RGBA32F, width, height, 1, err) &&
              gl_texture_create(&depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, width, height, 1, err) &&
              gl_framebuffer_create(&fb, err) && gl_framebuffer_attach(&fb, colors, NULL, 1, &depth, -1, err) &&
              image_create(out, width, height, err);
    if (ok) {
        renderer_reset_state(r);
        gl.BindFramebuffer(GL_FRAMEBUFFER, fb.id);
        gl.Viewport(0, 0, width, height);
        const float none[4] = {0, INFINITY, 0, 0}; /* no surface: no coverage, Z +inf, objectId 0 */
        gl_texture_clear(&target, none);
        gl.ClearDepth(1.0);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_LESS);
        gl.Disable(GL_CULL_FACE); /* a surface seen from behind is still the first one */
        renderer_draw_objects(r, scene, prog, DRAW_ALL);
        float *rgba = malloc((size_t)width * (size_t)height * 4 * sizeof(float));
        ok = rgba && gl_texture_read_rgba32f(&target, 0, rgba, err);
        if (!rgba)
            error_set(err, "out of memory");
        /* GL rows go bottom to top; `out` top to bottom */
        for (int y = 0; ok && y < height; y++)
            memcpy(out->rgba + (size_t)y * (size_t)width * 4, rgba + (size_t)(height - 1 - y) * (size_t)width * 4,
                   (size_t)width * 4 * sizeof(float));
        free(rgba);
        renderer_reset_state(r);
        if (!ok)
            image_destroy(out);
    }
    gl_framebuffer_destroy(&fb);
    gl_texture_destroy(&depth);
    gl_texture_destroy(&target);
    return ok;
}

bool tonemap_parse(const char *name, enum tonemap_operator *out)
{
    if (strcmp(name, "clamp") == 0)
        *out = TONEMAP_CLAMP;
    else if (strcmp(name, "reinhard") == 0)
        *out = TONEMAP_REINHARD;
    else if (strcmp(name, "aces") == 0)
        *out = TONEMAP_ACES;
    else
        return false;
    return true;
}

static bool tonemap_draw(struct renderer *r, const struct gl_texture *linear, float exposure,
                         enum tonemap_operator op, struct error *err)
{
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "tonemap/tonemap.frag", NULL, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_exposure"), exposure);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_operator"), (GLint)op);
    gl_program_bind_texture(prog, "u_image", linear->id);
    renderer_draw_fullscreen(r);
    return true;
}

static bool ensure_present_target(struct renderer *r, int w, int h, struct error *err)
{
    if (r->present_texture.id && r->present_texture.width == w && r->present_texture.height == h)
        return true;
    gl_texture_destroy(&r->present_texture);
    if (!gl_texture_create(&r->present_texture, GL_TEXTURE_2D, GL_RGBA8, w, h, 1, err))
        return false;
    const struct gl_texture *colors[1] = {&r->present_texture};
    return gl_framebuffer_attach(&r->present_fb, colors, NULL, 1, NULL, -1, err);
}

/* Tone maps `linear` into the 8-bit present target of its size. */
static bool tonemap_to_present(struct renderer *r, const struct gl_texture *linear, float exposure,
                               enum tonemap_operator op, struct error *err)
{
    renderer_reset_state(r);
    if (!ensure_present_target(r, linear->width, linear->height, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->present_fb.id);
    gl.Viewport(0, 0, linear->width, linear->height);
    return tonemap_draw(r, linear, exposure, op, err);
}

bool renderer_present_bytes(struct renderer *r, const struct gl_texture *linear, float exposure,
                            enum tonemap_operator op, uint8_t *rgba, struct error *err)
{
    int w = linear->width, h = linear->height;
    if (!tonemap_to_present(r, linear, exposure, op, err))
        return false;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r->present_fb.id);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    /* GL rows go bottom to top; images top to bottom. */
    size_t row = (size_t)w * 4;
    uint8_t *tmp = malloc(row);
    if (!tmp)
        return error_set(err, "out of memory");
    for (int y = 0; y < h / 2; y++) {
        memcpy(tmp, rgba + (size_t)y * row, row);
        memcpy(rgba + (size_t)y * row, rgba + (size_t)(h - 1 - y) * row, row);
        memcpy(rgba + (size_t)(h - 1 - y) * row, tmp, row);
    }
    free(tmp);
    return gl_check("presenting the image", err);
}

bool renderer_present_window(struct renderer *r, const struct gl_texture *linear, float exposure,
                             enum tonemap_operator op, int fb_width, int fb_height,
                             struct error *err)
{
    int w = linear->width, h = linear->height;
    if (!tonemap_to_present(r, linear, exposure, op, err))
        return false;
    /* Letterbox into the window, keeping the aspect ratio; at equal sizes
     * the blit copies pixels exactly. */
    float scale = fminf((float)fb_width / (float)w, (float)fb_height / (float)h);
    int dw = (int)lrintf((float)w * scale), dh = (int)lrintf((float)h * scale);
    int dx = (fb_width - dw) / 2, dy = (fb_height - dh) / 2;
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, fb_width, fb_height);
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    gl.BlitNamedFramebuffer(r->present_fb.id, 0, 0, 0, w, h, dx, dy, dx + dw, dy + dh, GL_COLOR_BUFFER_BIT,
                            dw == w && dh == h ? GL_NEAREST : GL_LINEAR);
    return gl_check("presenting to the window", err);
}
