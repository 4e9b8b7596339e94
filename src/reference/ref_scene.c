#include "reference/ref_scene.h"

#include "gl/gl_buffer.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

dvec3 dv_normalize_or(dvec3 a, dvec3 fallback)
{
    double len = sqrt(dv_dot(a, a));
    if (!(len > 1e-300) || !isfinite(len))
        return fallback;
    return dv_scale(a, 1.0 / len);
}

static dvec3 from_vec3(vec3 v) { return dv(v.x, v.y, v.z); }

/* Object-space vertices of this frame: the deformed GPU buffers when the
 * object morphs or deforms, else the mesh's own arrays. */
static bool frame_vertices(struct renderer *r, const struct object *o, float *pos, float *nrm, struct error *err)
{
    size_t bytes = o->mesh->vertex_count * 3 * sizeof(float);
    struct gpu_object *g = object_is_animated_geometry(o) ? mesh_cache_object(&r->meshes, o, err) : NULL;
    if (g && g->deformed_positions)
        return gl_buffer_read(g->deformed_positions, pos, bytes, err) &&
               gl_buffer_read(g->deformed_normals, nrm, bytes, err);
    memcpy(pos, o->mesh->positions, bytes);
    memcpy(nrm, o->mesh->normals, bytes);
    return true;
}

void ref_object_uv(const struct ref_object *o, unsigned primitive, double u, double v, int set, float uv[2])
{
    const uint32_t *tri = o->indices + (size_t)primitive * 3;
    const float *t = o->texcoords[set];
    double w = 1.0 - u - v;
    for (int k = 0; k < 2; k++)
        uv[k] = (float)(w * t[tri[0] * 2 + (uint32_t)k] + u * t[tri[1] * 2 + (uint32_t)k] +
                        v * t[tri[2] * 2 + (uint32_t)k]);
}

void ref_object_color(const struct ref_object *o, unsigned primitive, double u, double v, double rgba[4])
{
    if (!o->colors) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 1.0;
        return;
    }
    const uint32_t *tri = o->indices + (size_t)primitive * 3;
    double w = 1.0 - u - v;
    for (int k = 0; k < 4; k++)
        rgba[k] = w * o->colors[tri[0] * 4 + (uint32_t)k] + u * o->colors[tri[1] * 4 + (uint32_t)k] +
                  v * o->colors[tri[2] * 4 + (uint32_t)k];
}

bool ref_object_cut_out(const struct ref_object *o, unsigned primitive, double u, double v, double xi)
{
    const struct material *m = &o->material;
    if (!(m->alpha_cutoff > 0.0f || m->alpha_blend))
        return false;
    double rgba[4];
    ref_object_color(o, primitive, u, v, rgba);
    float a = m->alpha * (float)rgba[3];
    if (m->base_color.texture && o->texcoords[m->base_color.texcoord]) {
        float uv[2];
        ref_object_uv(o, primitive, u, v, m->base_color.texcoord, uv);
        a *= texture_sample_alpha(&m->base_color, uv);
    }
    return m->alpha_blend ? xi >= a : a < m->alpha_cutoff;
}

/* BLEND's coin per ray takes this thread's salt (an eye path's iteration
 * and pixel), so that a pixel-centre ray that is the same every iteration
 * still draws a new coin each one; and says it drew one (such a path is
 * not fixed: ref_sppm.c's trace_eye traces it again). */
static _Thread_local uint64_t blend_salt;
static _Thread_local bool blend_met;

void ref_scene_blend_begin(uint64_t salt)
{
    blend_salt = salt;
    blend_met = false;
}

bool ref_scene_blend_met(void) { return blend_met; }

/* Embree's filter for a surface with cut-outs: a hit in a cut-out is no
 * hit, for rays and shadow rays alike (common/material.glsl's
 * material_cut_out on the GPU). */
static void cut_out_filter(const struct RTCFilterFunctionNArguments *args)
{
    const struct ref_object *o = args->geometryUserPtr;
    /* RTCHitN's layout, as rtcore_ray.h's C++ accessors read it (structure
     * of arrays: Ng x, y, z, u, v, primID, each N wide) */
    const float *hit = (const float *)args->hit;
    const unsigned *hit_ids = (const unsigned *)args->hit;
    const float *ray = (const float *)args->ray; /* RTCRayN: org x, y, z, tnear, dir x, y, z, ... */
    unsigned n = args->N;
    for (unsigned i = 0; i < n; i++) {
        if (!args->valid[i])
            continue;
        /* BLEND's coin: a hash of the ray and the triangle, uniform over
         * rays (the filter has no generator of its own; the ray's origin and
         * direction are as random as the path that made them) */
        uint32_t words[9] = {hit_ids[5 * n + i], (uint32_t)blend_salt, (uint32_t)(blend_salt >> 32)};
        for (int k = 0; k < 3; k++) {
            memcpy(&words[3 + k], &ray[(unsigned)k * n + i], 4);
            memcpy(&words[6 + k], &ray[(unsigned)(4 + k) * n + i], 4);
        }
        blend_met = blend_met || o->material.alpha_blend;
        uint64_t h = 1469598103934665603ull;
        for (int k = 0; k < 9; k++) {
            h = (h ^ words[k]) * 1099511628211ull;
            h ^= h >> 29;
        }
        h *= 0xbf58476d1ce4e5b9ull;
        h ^= h >> 32;
        double xi = (double)(h >> 11) * (1.0 / 9007199254740992.0);
        if (ref_object_cut_out(o, hit_ids[5 * n + i], hit[3 * n + i], hit[4 * n + i], xi))
            args->valid[i] = 0;
    }
}

/* Lights exactly as the shaders see them: the frame snapshot's (linear
 * lights already split into their samples). */
static void copy_lights(struct ref_scene *rs, const struct frame *f)
{
    rs->light_count = f->light_count;
    for (int i = 0; i < rs->light_count; i++) {
        const struct frame_light *g = &f->lights[i];
        struct ref_light *l = &rs->lights[i];
        l->kind = g->kind == LIGHT_DIRECTIONAL ? 1 : g->kind == LIGHT_SPOT ? 2 : 0;
        l->position = from_vec3(g->position);
        l->direction = dv_normalize_or(from_vec3(g->direction), dv(0, -1, 0));
        l->intensity = from_vec3(g->intensity);
        l->cos_outer = g->cos_outer;
        l->cos_inner = g->cos_inner;
        l->shading = (struct shading_light){.kind = l->kind,
                                            .position = {l->position.x, l->position.y, l->position.z},
                                            .direction = {l->direction.x, l->direction.y, l->direction.z},
                                            .intensity = {l->intensity.x, l->intensity.y, l->intensity.z},
                                            .cos_outer = l->cos_outer,
                                            .cos_inner = l->cos_inner};
    }
}

/* Whether object `o`, placed by `model` this frame, is traced as the
 * sphere the script made (issue 53: the truth of the shape the scene names,
 * as POV-Ray traces it; the GPU's tessellation is then part of the GPU's
 * measured error). Only where nothing but the shape is read from its
 * triangles: glass, water or a mirror of one material with no texture and
 * no vertex colours, not deformed, and a model matrix that keeps a sphere
 * a sphere (rotation, translation and one scale). Its world centre and
 * radius. */
static bool exact_sphere(const struct object *o, mat4 model, dvec3 *center, double *radius)
{
    const struct mesh *m = o->mesh;
    if (!(m->sphere_radius > 0.0f) || m->colors || object_is_animated_geometry(o) ||
        !(material_role(&o->material) & REF_SPECULAR_ROLES) || o->material.alpha_cutoff > 0.0f ||
        o->material.alpha_blend)
        return false;
    const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS];
    bool srgb[MATERIAL_TEXTURE_SLOTS];
    material_texture_slots(&o->material, slots, srgb);
    for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++)
        if (slots[k]->texture)
            return false;
    dvec3 axis[3];
    for (int k = 0; k < 3; k++)
        axis[k] = from_vec3(mat4_transform_dir(model, vec3_make(k == 0, k == 1, k == 2)));
    double scale = sqrt(dv_dot(axis[0], axis[0]));
    if (!(scale > 0.0) || !isfinite(scale))
        return false;
    for (int k = 0; k < 3; k++) {
        if (fabs(sqrt(dv_dot(axis[k], axis[k])) - scale) > 1e-6 * scale ||
            fabs(dv_dot(axis[k], axis[(k + 1) % 3])) > 1e-6 * scale * scale)
            return false; /* an ellipsoid or a sheared sphere: its triangles */
    }
    *center = from_vec3(mat4_transform_point(model, vec3_make(0, 0, 0)));
    *radius = scale * (double)m->sphere_radius;
    return isfinite(center->x + center->y + center->z) && *radius > 0.0;
}

/* A sphere as an Embree geometry of the scene: a round point (Embree's
 * SPHERE_POINT), which finds the first sphere a ray meets; the hit is then
 * solved again in double precision (ref_scene_intersect). Its geometry
 * id, or RTC_INVALID_GEOMETRY_ID where this Embree has no points. */
static unsigned attach_sphere(struct ref_scene *rs, const struct ref_object *ro)
{
    if (!rtcGetDeviceProperty(rs->device, RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED))
        return RTC_INVALID_GEOMETRY_ID;
    RTCGeometry geom = rtcNewGeometry(rs->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    float *v = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1);
    if (!v) {
        rtcReleaseGeometry(geom);
        return RTC_INVALID_GEOMETRY_ID;
    }
    /* Embree intersects in single precision: a radius a little larger, so
     * that no ray the double-precision sphere takes slips past the float
     * one (the refined solve below decides the hit) */
    v[0] = (float)ro->sphere_center.x;
    v[1] = (float)ro->sphere_center.y;
    v[2] = (float)ro->sphere_center.z;
    v[3] = (float)(ro->sphere_radius * (1.0 + 1e-6));
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(rs->rtc, geom);
    rtcReleaseGeometry(geom);
    return id;
}

static unsigned attach_triangles(struct ref_scene *rs, struct ref_object *ro);

/* Object o (ro, its world vertices made) into the Embree scene: as its
 * sphere where exact_sphere allows and `tessellated` does not ask for the
 * triangles, else as its triangles. A sphere widens the scene's bounds and
 * the specular ones (bounds: lo, hi, specular lo, specular hi) to the
 * sphere's, which its inscribed vertices fall short of. Its geometry id. */
static unsigned attach_object(struct ref_scene *rs, struct ref_object *ro, const struct object *o, bool tessellated,
                              dvec3 bounds[4])
{
    unsigned id = RTC_INVALID_GEOMETRY_ID;
    ro->sphere = !tessellated && exact_sphere(o, ro->model, &ro->sphere_center, &ro->sphere_radius);
    if (ro->sphere && (id = attach_sphere(rs, ro)) == RTC_INVALID_GEOMETRY_ID)
        ro->sphere = false; /* an Embree built without points: the triangles */
    if (!ro->sphere)
        return attach_triangles(rs, ro);
    dvec3 r3 = dv(ro->sphere_radius, ro->sphere_radius, ro->sphere_radius);
    dvec3 a = dv_sub(ro->sphere_center, r3), b = dv_add(ro->sphere_center, r3);
    for (int k = 0; k < 4; k += 2) {
        bounds[k] = dv(fmin(bounds[k].x, a.x), fmin(bounds[k].y, a.y), fmin(bounds[k].z, a.z));
        bounds[k + 1] = dv(fmax(bounds[k + 1].x, b.x), fmax(bounds[k + 1].y, b.y), fmax(bounds[k + 1].z, b.z));
    }
    return id;
}

/* The object's triangles as an Embree geometry of the scene (its world
 * positions shared, not copied); a cut-out surface's filter skips the hits
 * its alpha removes. Its geometry id. */
static unsigned attach_triangles(struct ref_scene *rs, struct ref_object *ro)
{
    RTCGeometry geom = rtcNewGeometry(rs->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, ro->positions, 0, 3 * sizeof(float),
                               ro->vertex_count);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, ro->indices, 0, 3 * sizeof(uint32_t),
                               ro->triangle_count);
    if (ro->material.alpha_cutoff > 0.0f || ro->material.alpha_blend) {
        rtcSetGeometryUserData(geom, ro);
        rtcSetGeometryIntersectFilterFunction(geom, cut_out_filter);
        rtcSetGeometryOccludedFilterFunction(geom, cut_out_filter);
    }
    rtcCommitGeometry(geom);
    unsigned id = rtcAttachGeometry(rs->rtc, geom);
    rtcReleaseGeometry(geom);
    return id;
}

bool ref_scene_build(struct ref_scene *rs, struct renderer *r, struct scene *scene, bool tessellated,
                     struct error *err)
{
    memset(rs, 0, sizeof *rs);
    rs->device = rtcNewDevice(NULL);
    if (!rs->device)
        return error_set(err, "reference: Embree could not create a device (error %d)", (int)rtcGetDeviceError(NULL));
    rs->rtc = rtcNewScene(rs->device);
    rtcSetSceneBuildQuality(rs->rtc, RTC_BUILD_QUALITY_HIGH);
    /* Robust (watertight) traversal: rays through a shared edge must not slip between triangles. */
    rtcSetSceneFlags(rs->rtc, RTC_SCENE_FLAG_ROBUST);
    rs->objects = calloc((size_t)(scene->object_count + 1), sizeof *rs->objects);
    rs->geometry_object = calloc((size_t)(scene->object_count + 1), sizeof *rs->geometry_object);
    if (!rs->objects || !rs->geometry_object) {
        ref_scene_release(rs);
        return error_set(err, "reference: out of memory");
    }
    dvec3 lo = dv(INFINITY, INFINITY, INFINITY), hi = dv(-INFINITY, -INFINITY, -INFINITY);
    dvec3 slo = lo, shi = hi;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (!o->visible || o->mesh->index_count == 0)
            continue;
        /* the mip chains an eye path's footprint reads (ref_footprint.c),
         * made here, before the threads */
        const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS];
        bool srgb[MATERIAL_TEXTURE_SLOTS];
        material_texture_slots(&o->material, slots, srgb);
        for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++)
            if (slots[k]->texture && !texture_build_mips(slots[k]->texture, srgb[k], err)) {
                ref_scene_release(rs);
                return false;
            }
        struct ref_object *ro = &rs->objects[rs->object_count];
        size_t n = o->mesh->vertex_count;
        ro->positions = malloc((n * 3 + 4) * sizeof(float)); /* Embree reads 16 bytes past a vertex */
        ro->normals = malloc((n * 3 + 4) * sizeof(float));
        if (!ro->positions || !ro->normals) {
            free(ro->positions);
            free(ro->normals);
            ref_scene_release(rs);
            return error_set(err, "reference: out of memory for %zu vertices", n);
        }
        if (!frame_vertices(r, o, ro->positions, ro->normals, err)) {
            free(ro->positions);
            free(ro->normals);
            ref_scene_release(rs);
            return false;
        }
        /* The world and normal matrices of the frame snapshot. */
        const struct frame_object *fo = frame_object_of(&r->frame, o);
        mat4 model = fo ? fo->model : object_model_matrix(o), nm = fo ? fo->normal_matrix : mat4_identity();
        dvec3 olo = dv(INFINITY, INFINITY, INFINITY), ohi = dv(-INFINITY, -INFINITY, -INFINITY);
        for (size_t v = 0; v < n; v++) {
            float *p = ro->positions + v * 3, *q = ro->normals + v * 3;
            vec3 w = mat4_transform_point(model, vec3_make(p[0], p[1], p[2]));
            vec3 wn = vec3_normalize_or(mat4_transform_dir(nm, vec3_make(q[0], q[1], q[2])), vec3_make(0, 1, 0));
            if (!math_finite3(w))
                w = vec3_make(0, 0, 0); /* a deformer gone wrong: the GPU collapses it too */
            p[0] = w.x; p[1] = w.y; p[2] = w.z;
            q[0] = wn.x; q[1] = wn.y; q[2] = wn.z;
            dvec3 dw = from_vec3(w);
            olo = dv(fmin(olo.x, dw.x), fmin(olo.y, dw.y), fmin(olo.z, dw.z));
            ohi = dv(fmax(ohi.x, dw.x), fmax(ohi.y, dw.y), fmax(ohi.z, dw.z));
            lo = dv(fmin(lo.x, dw.x), fmin(lo.y, dw.y), fmin(lo.z, dw.z));
            hi = dv(fmax(hi.x, dw.x), fmax(hi.y, dw.y), fmax(hi.z, dw.z));
            if (material_role(&o->material) & REF_SPECULAR_ROLES) {
                slo = dv(fmin(slo.x, dw.x), fmin(slo.y, dw.y), fmin(slo.z, dw.z));
                shi = dv(fmax(shi.x, dw.x), fmax(shi.y, dw.y), fmax(shi.z, dw.z));
            }
        }
        ro->indices = o->mesh->indices;
        ro->texcoords[0] = o->mesh->texcoords[0];
        ro->texcoords[1] = o->mesh->texcoords[1];
        ro->colors = o->mesh->colors;
        ro->tangents = o->mesh->tangents;
        ro->model = model;
        ro->vertex_count = n;
        ro->triangle_count = o->mesh->index_count / 3;
        ro->material = o->material;
        /* The offset of a ray leaving this object's surface: from its own
         * size, not the scene's (a 40-unit floor made a glass ball of
         * radius 0.5 refract from 8e-4 off its surface: a bias of 0.35% in
         * its caustic 2.5 radii below, issue 53); never under the float
         * precision of where it lies (ref_scene_offset). */
        ro->epsilon = fmax(sqrt(dv_dot(dv_sub(ohi, olo), dv_sub(ohi, olo))), 1e-3) * 2e-5;
        dvec3 bounds[4] = {lo, hi, slo, shi};
        unsigned id = attach_object(rs, ro, o, tessellated, bounds);
        lo = bounds[0], hi = bounds[1], slo = bounds[2], shi = bounds[3];
        rs->geometry_object[id] = (unsigned)rs->object_count;
        rs->has_thin = rs->has_thin || ro->material.thin;
        rs->geometry_count = (int)id + 1;
        rs->object_count++;
    }
    rtcCommitScene(rs->rtc);
    if (rtcGetDeviceError(rs->device) != RTC_ERROR_NONE) {
        ref_scene_release(rs);
        return error_set(err, "reference: Embree failed to build the scene");
    }
    if (rs->object_count == 0)
        lo = hi = dv(0, 0, 0);
    rs->bounds_lo = lo;
    rs->bounds_hi = hi;
    double extent = sqrt(dv_dot(dv_sub(hi, lo), dv_sub(hi, lo)));
    rs->epsilon = fmax(extent, 1e-3) * 2e-5;
    rs->has_specular_bounds = slo.x <= shi.x;
    if (rs->has_specular_bounds) {
        rs->specular_center = dv_scale(dv_add(slo, shi), 0.5);
        rs->specular_radius = 0.5 * sqrt(dv_dot(dv_sub(shi, slo), dv_sub(shi, slo))) * 1.001 + rs->epsilon;
    }
    const struct frame *f = &r->frame;
    copy_lights(rs, f);
    rs->inv_view_proj = f->inv_view_proj;
    rs->eye = from_vec3(scene->camera.eye);
    rs->ortho = scene->camera.ortho_width > 0.0f;
    rs->znear = scene->camera.znear;
    rs->environment = scene->environment;
    rs->background = from_vec3(scene->background);
    rs->ambient = from_vec3(scene->ambient);
    return true;
}

void ref_scene_release(struct ref_scene *rs)
{
    for (int i = 0; i < rs->object_count; i++) {
        free(rs->objects[i].positions);
        free(rs->objects[i].normals);
    }
    free(rs->objects);
    free(rs->geometry_object);
    if (rs->rtc)
        rtcReleaseScene(rs->rtc);
    if (rs->device)
        rtcReleaseDevice(rs->device);
    memset(rs, 0, sizeof *rs);
}

double ref_scene_offset(const struct ref_scene *rs, const struct ref_hit *h)
{
    const dvec3 p = h->position;
    double far = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
    return fmax(rs->objects[h->object].epsilon, far * 1e-6);
}

/* A ray's hit on an exact sphere, which Embree found at about t_found:
 * the root of |origin + t dir - c|^2 = R^2 nearest it, solved in double
 * precision (the stable form of the quadratic), the point put back on the
 * sphere and its normal exact. A ray that grazes it so that the double
 * solve finds no root takes the point of closest approach. */
static bool sphere_hit(const struct ref_scene *rs, const struct ref_object *o, dvec3 origin, dvec3 dir,
                       double t_found, struct ref_hit *hit)
{
    dvec3 oc = dv_sub(origin, o->sphere_center);
    double a = dv_dot(dir, dir), b = dv_dot(oc, dir), r = o->sphere_radius;
    /* the discriminant from the ray's closest point (Hearn & Baker's
     * form: no cancellation of b^2 against a c for a far origin) */
    dvec3 perp = dv_sub(oc, dv_scale(dir, b / a));
    double disc = r * r - dv_dot(perp, perp);
    double t = -b / a;
    if (disc > 0.0) {
        double q = -b - copysign(sqrt(a * disc), b);
        double t0 = q / a, t1 = q != 0.0 ? (dv_dot(oc, oc) - r * r) / q : t0;
        if (t0 > t1) {
            double s = t0;
            t0 = t1;
            t1 = s;
        }
        t = fabs(t0 - t_found) <= fabs(t1 - t_found) ? t0 : t1;
    }
    if (!(t > 0.0) || !isfinite(t))
        t = t_found; /* a root behind the origin: Embree's, which is ahead of it */
    dvec3 p = dv_add(origin, dv_scale(dir, t));
    dvec3 n = dv_normalize_or(dv_sub(p, o->sphere_center), dv_scale(dir, -1.0));
    hit->t = t;
    hit->object = (int)(o - rs->objects);
    hit->primitive = 0; /* no triangle: nothing reads one of a sphere (exact_sphere) */
    hit->bary_u = hit->bary_v = 0.0;
    hit->footprint = false;
    hit->position = dv_add(o->sphere_center, dv_scale(n, r));
    hit->geometric_normal = n;
    hit->shading_normal = n;
    return true;
}

bool ref_scene_intersect(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax, struct ref_hit *hit)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = (float)origin.x;
    rh.ray.org_y = (float)origin.y;
    rh.ray.org_z = (float)origin.z;
    rh.ray.dir_x = (float)dir.x;
    rh.ray.dir_y = (float)dir.y;
    rh.ray.dir_z = (float)dir.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = (float)fmin(tmax, 3e38);
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rs->rtc, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return false;
    const struct ref_object *o = &rs->objects[rs->geometry_object[rh.hit.geomID]];
    if (o->sphere)
        return sphere_hit(rs, o, origin, dir, rh.ray.tfar, hit);
    const uint32_t *tri = o->indices + (size_t)rh.hit.primID * 3;
    const float *p0 = o->positions + tri[0] * 3, *p1 = o->positions + tri[1] * 3, *p2 = o->positions + tri[2] * 3;
    dvec3 a = dv(p0[0], p0[1], p0[2]), b = dv(p1[0], p1[1], p1[2]), c = dv(p2[0], p2[1], p2[2]);
    double u = rh.hit.u, v = rh.hit.v, w = 1.0 - u - v;
    hit->bary_u = u;
    hit->bary_v = v;
    hit->footprint = false;
    hit->t = rh.ray.tfar;
    hit->object = (int)rs->geometry_object[rh.hit.geomID];
    hit->primitive = rh.hit.primID;
    /* The hit point from the barycentrics is more precise than o + t d. */
    hit->position = dv_add(dv_add(dv_scale(a, w), dv_scale(b, u)), dv_scale(c, v));
    dvec3 ng = dv_cross(dv_sub(b, a), dv_sub(c, a));
    hit->geometric_normal = dv_normalize_or(ng, dv_scale(dir, -1.0));
    const float *n0 = o->normals + tri[0] * 3, *n1 = o->normals + tri[1] * 3, *n2 = o->normals + tri[2] * 3;
    dvec3 ns = dv(w * n0[0] + u * n1[0] + v * n2[0], w * n0[1] + u * n1[1] + v * n2[1], w * n0[2] + u * n1[2] + v * n2[2]);
    ns = dv_normalize_or(ns, hit->geometric_normal);
    if (dv_dot(ns, hit->geometric_normal) <= 0.0)
        ns = hit->geometric_normal; /* an interpolated normal that flipped: trust the triangle */
    hit->shading_normal = ns;
    return true;
}

bool ref_scene_occluded(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray;
    memset(&ray, 0, sizeof ray);
    ray.org_x = (float)origin.x;
    ray.org_y = (float)origin.y;
    ray.org_z = (float)origin.z;
    ray.dir_x = (float)dir.x;
    ray.dir_y = (float)dir.y;
    ray.dir_z = (float)dir.z;
    ray.tnear = 0.0f;
    ray.tfar = (float)fmin(tmax, 3e38);
    ray.mask = 0xffffffffu;
    rtcOccluded1(rs->rtc, &ctx, &ray);
    return ray.tfar < 0.0f;
}

dvec3 ref_scene_transmittance(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax)
{
    if (!rs->has_thin)
        return ref_scene_occluded(rs, origin, dir, tmax) ? dv(0, 0, 0) : dv(1, 1, 1);
    dvec3 through = dv(1, 1, 1);
    /* pane after pane (a bounded count: a ray grazing a mesh of panes) */
    for (int step = 0; step < 64; step++) {
        struct ref_hit h;
        if (!ref_scene_intersect(rs, origin, dir, tmax, &h))
            return through;
        const struct ref_object *o = &rs->objects[h.object];
        const struct material *m = &o->material;
        if (!m->thin)
            return dv(0, 0, 0);
        dvec3 ng = dv_dot(dir, h.geometric_normal) < 0.0 ? h.geometric_normal : dv_scale(h.geometric_normal, -1.0);
        dvec3 n0 = dv_dot(dir, h.shading_normal) < 0.0 ? h.shading_normal : dv_scale(h.shading_normal, -1.0);
        dvec3 n, tint;
        double pass = (1.0 - ref_thin_surface(o, &h, dir, n0, &n, &tint)) * ref_object_transmission(o, &h);
        through = dv_scale(dv_mul(through, tint), pass);
        if (!(dv_dot(through, through) > 0.0))
            return dv(0, 0, 0);
        /* on past the pane: what is left of the way */
        dvec3 next = dv_sub(h.position, dv_scale(ng, rs->epsilon));
        tmax -= dv_dot(dv_sub(next, origin), dir);
        origin = next;
        if (!(tmax > 0.0))
            return through;
    }
    return dv(0, 0, 0);
}

dvec3 ref_scene_environment(const struct ref_scene *rs, dvec3 dir)
{
    if (!rs->environment)
        return rs->background;
    vec3 c = environment_lookup(rs->environment, vec3_make((float)dir.x, (float)dir.y, (float)dir.z));
    return dv(c.x, c.y, c.z);
}

void ref_scene_camera_ray(const struct ref_scene *rs, double px, double py, int width, int height, dvec3 *origin,
                          dvec3 *dir)
{
    /* NDC of the image point (rows top to bottom), unprojected at the near
     * and far planes: the same rays the rasterizer samples at pixel centres. */
    double x = 2.0 * px / width - 1.0, y = 1.0 - 2.0 * py / height;
    vec3 a = mat4_transform_point(rs->inv_view_proj, vec3_make((float)x, (float)y, -1.0f));
    vec3 b = mat4_transform_point(rs->inv_view_proj, vec3_make((float)x, (float)y, 1.0f));
    *origin = dv(a.x, a.y, a.z); /* from the near plane, as the rasterizer clips */
    *dir = dv_normalize_or(dv(b.x - a.x, b.y - a.y, b.z - a.z), dv(0, 0, -1));
}

double ref_light_spot(const struct ref_light *l, dvec3 out)
{
    if (l->kind != 2)
        return 1.0;
    return shading_spot_falloff(dv_dot(out, l->direction), l->cos_outer, l->cos_inner);
}
