/* Textured diffuse surfaces in the reference: the same texels, filter,
 * texture transform and tangent frame as common/material.glsl. Where an
 * eye path knows its pixel's footprint (ref_footprint.c) a texture is
 * read through the mip level the rasterizer would choose there; elsewhere
 * (photons, shadow and glossy rays, a path beyond a rough bounce) at
 * level 0 (docs/LUA_API.md, Textures). */
#include <math.h>

#include "reference/ref_scene.h"

#include "core/optics.h"

/* The texture coordinates' change across and down one pixel (h's
 * footprint): the set's coordinates at the triangle's corners weighted by
 * the barycentrics' change. */
static void hit_uv_gradient(const struct ref_object *o, const struct ref_hit *h, int set, float duv[4])
{
    const uint32_t *tri = o->indices + (size_t)h->primitive * 3;
    const float *tc = o->texcoords[set];
    for (int c = 0; c < 2; c++) {
        double t0 = tc[tri[0] * 2 + (uint32_t)c], t1 = tc[tri[1] * 2 + (uint32_t)c], t2 = tc[tri[2] * 2 + (uint32_t)c];
        for (int k = 0; k < 2; k++)
            duv[2 * k + c] = (float)(h->dbary[2 * k] * (t1 - t0) + h->dbary[2 * k + 1] * (t2 - t0));
    }
}

/* A slot's texture at the hit: RGBA through the footprint's mip level
 * where the hit has one, else level 0 (texture_sample's filter). */
static void slot_rgba(const struct ref_object *o, const struct ref_hit *h, const struct texture_ref *ref, bool srgb,
                      float rgba[4])
{
    float uv[2];
    ref_object_uv(o, h->primitive, h->bary_u, h->bary_v, ref->texcoord, uv);
    if (h->footprint) {
        float duv[4];
        hit_uv_gradient(o, h, ref->texcoord, duv);
        texture_sample_grad(ref, uv, duv, srgb, rgba);
        return;
    }
    vec3 c = texture_sample(ref, uv, srgb);
    rgba[0] = c.x;
    rgba[1] = c.y;
    rgba[2] = c.z;
    rgba[3] = texture_sample_alpha(ref, uv);
}

static vec3 slot_rgb(const struct ref_object *o, const struct ref_hit *h, const struct texture_ref *ref, bool srgb)
{
    if (!h->footprint) { /* (photons, shadow and glossy rays: no alpha read beside it) */
        float uv[2];
        ref_object_uv(o, h->primitive, h->bary_u, h->bary_v, ref->texcoord, uv);
        return texture_sample(ref, uv, srgb);
    }
    float rgba[4];
    slot_rgba(o, h, ref, srgb, rgba);
    return vec3_make(rgba[0], rgba[1], rgba[2]);
}

static bool slot_active(const struct ref_object *o, const struct texture_ref *ref)
{
    return ref->texture && o->texcoords[ref->texcoord];
}

double ref_object_transmission(const struct ref_object *o, const struct ref_hit *h)
{
    const struct material *m = &o->material;
    double t = m->transmission;
    if (slot_active(o, &m->transmission_map)) {
        t *= slot_rgb(o, h, &m->transmission_map, false).x;
    }
    return t;
}


static dvec3 to_dvec3(vec3 v) { return dv(v.x, v.y, v.z); }

/* The normal map `ref` (the material's normal, or its clearcoat's) at the
 * hit, in the frame of material_normal(): t along increasing u on the
 * triangle (made perpendicular to n), b = n x t turned to the side of
 * decreasing v (a mirrored mapping: -(n x t)). */
static dvec3 mapped_normal(const struct ref_object *o, const struct ref_hit *h, const struct texture_ref *ref, dvec3 n)
{
    const uint32_t *tri = o->indices + (size_t)h->primitive * 3;
    const float *tc = o->texcoords[ref->texcoord];
    float uvs[3][2];
    dvec3 p[3];
    for (int k = 0; k < 3; k++) {
        const float *q = o->positions + tri[k] * 3;
        p[k] = dv(q[0], q[1], q[2]);
        float raw[2] = {tc[tri[k] * 2], tc[tri[k] * 2 + 1]};
        texture_ref_apply(ref, raw, uvs[k]);
    }
    /* dp = Pu du + Pv dv along the edges; Pu * det by Cramer's rule. */
    dvec3 e1 = dv_sub(p[1], p[0]), e2 = dv_sub(p[2], p[0]);
    double du1 = uvs[1][0] - uvs[0][0], dv1 = uvs[1][1] - uvs[0][1];
    double du2 = uvs[2][0] - uvs[0][0], dv2 = uvs[2][1] - uvs[0][1];
    double det = du1 * dv2 - dv1 * du2;
    dvec3 pu = dv_sub(dv_scale(e1, dv2), dv_scale(e2, dv1));
    dvec3 pv = dv_sub(dv_scale(e2, du1), dv_scale(e1, du2)); /* (dp/dv) * det */
    dvec3 t = dv_sub(pu, dv_scale(n, dv_dot(n, pu)));
    double len = sqrt(dv_dot(t, t));
    if (!(fabs(det) > 1e-20) || !(len > 1e-20 * fmax(fabs(det), 1e-20)) || !isfinite(len))
        return n; /* a triangle with no area in uv: no tangent frame */
    t = dv_scale(t, (det > 0 ? 1.0 : -1.0) / len);
    if (o->tangents) {
        /* the mesh's tangent, interpolated as the GPU does (by the model
         * matrix, then made perpendicular to n) */
        double w = 1.0 - h->bary_u - h->bary_v, tv[3];
        for (int k = 0; k < 3; k++)
            tv[k] = w * o->tangents[tri[0] * 4 + (uint32_t)k] + h->bary_u * o->tangents[tri[1] * 4 + (uint32_t)k] +
                    h->bary_v * o->tangents[tri[2] * 4 + (uint32_t)k];
        vec3 wt = mat4_transform_dir(o->model, vec3_make((float)tv[0], (float)tv[1], (float)tv[2]));
        dvec3 tw = dv(wt.x, wt.y, wt.z);
        tw = dv_sub(tw, dv_scale(n, dv_dot(n, tw)));
        if (dv_dot(tw, tw) > 1e-12)
            t = dv_normalize_or(tw, t);
    }
    dvec3 b = dv_cross(n, t);
    if (dv_dot(b, pv) * det > 0.0)
        b = dv_scale(b, -1.0); /* a mirrored mapping: v runs the other way round n */
    vec3 m = slot_rgb(o, h, ref, false);
    double s = ref->scale;
    dvec3 mapped = dv_add(dv_add(dv_scale(t, (m.x * 2.0 - 1.0) * s), dv_scale(b, (m.y * 2.0 - 1.0) * s)),
                          dv_scale(n, m.z * 2.0 - 1.0));
    return dv_normalize_or(mapped, n);
}

dvec3 ref_glass_tint(const struct ref_object *o, const struct ref_hit *h)
{
    const struct material *m = &o->material;
    dvec3 tint = to_dvec3(m->tint);
    if (slot_active(o, &m->base_color)) {
        tint = dv_mul(tint, to_dvec3(slot_rgb(o, h, &m->base_color, true)));
    }
    return tint;
}

dvec3 ref_interface_normal(const struct ref_object *o, const struct ref_hit *h, dvec3 n)
{
    return slot_active(o, &o->material.normal) ? mapped_normal(o, h, &o->material.normal, n) : n;
}

double ref_thin_surface(const struct ref_object *o, const struct ref_hit *h, dvec3 dir, dvec3 n, dvec3 *normal,
                        dvec3 *tint)
{
    const struct material *m = &o->material;
    double rgba[4];
    ref_object_color(o, h->primitive, h->bary_u, h->bary_v, rgba); /* COLOR_0 on thin glass, as on the GPU */
    *tint = dv_mul(ref_glass_tint(o, h), dv(rgba[0], rgba[1], rgba[2]));
    *normal = slot_active(o, &m->normal) ? mapped_normal(o, h, &m->normal, n) : n;
    double cos_i = fmin(fmax(-dv_dot(dir, *normal), 0.0), 1.0);
    return optics_fresnel_of(cos_i, 1.0 / m->ior, m->ideal);
}

void ref_surface_diffuse(const struct ref_scene *rs, const struct ref_hit *h, dvec3 n, struct ref_surface *out)
{
    const struct ref_object *o = &rs->objects[h->object];
    const struct material *m = &o->material;
    out->albedo = to_dvec3(m->color);
    out->emission = to_dvec3(m->emission);
    out->normal = n;
    out->pbr = false;
    out->occlusion = 1.0;
    if (!material_is_textured_surface(m))
        return; /* (thin glass's diffuse share: its base colour, textured, as on the GPU) */
    double color0[4];
    ref_object_color(o, h->primitive, h->bary_u, h->bary_v, color0);
    out->albedo = dv_mul(out->albedo, dv(color0[0], color0[1], color0[2]));
    if (slot_active(o, &m->base_color))
        out->albedo = dv_mul(out->albedo, to_dvec3(slot_rgb(o, h, &m->base_color, true)));
    if (slot_active(o, &m->emissive))
        out->emission = dv_mul(out->emission, to_dvec3(slot_rgb(o, h, &m->emissive, true)));
    if (slot_active(o, &m->normal))
        out->normal = mapped_normal(o, h, &m->normal, n);
    if (!m->pbr)
        return;
    /* material_brdf() and material_occlusion() of common/material.glsl */
    out->pbr = true;
    vec3 mr = vec3_make(1, 1, 1);
    if (slot_active(o, &m->metallic_roughness))
        mr = slot_rgb(o, h, &m->metallic_roughness, false);
    out->brdf = brdf_material_default(out->albedo.x, out->albedo.y, out->albedo.z,
                                      fmin(fmax(m->metallic * mr.z, 0.0), 1.0),
                                      fmin(fmax(m->roughness * mr.y, 0.0), 1.0));
    out->brdf.ior = m->ior;
    out->brdf.specular = m->specular;
    out->brdf.specular_color[0] = m->specular_color.x;
    out->brdf.specular_color[1] = m->specular_color.y;
    out->brdf.specular_color[2] = m->specular_color.z;
    /* KHR_materials_specular's textures (material_brdf): A and RGB (sRGB) */
    if (slot_active(o, &m->specular_map)) {
        float rgba[4];
        slot_rgba(o, h, &m->specular_map, false, rgba);
        out->brdf.specular *= rgba[3];
    }
    if (slot_active(o, &m->specular_color_map)) {
        vec3 c = slot_rgb(o, h, &m->specular_color_map, true);
        out->brdf.specular_color[0] *= c.x;
        out->brdf.specular_color[1] *= c.y;
        out->brdf.specular_color[2] *= c.z;
    }
    /* KHR_materials_clearcoat (material_brdf): R and G of its textures
     * (linear), its own normal map, else the geometry's normal n */
    out->brdf.clearcoat = m->clearcoat;
    out->brdf.clearcoat_roughness = m->clearcoat_roughness;
    if (m->clearcoat > 0.0f) {
        if (slot_active(o, &m->clearcoat_map)) {
            out->brdf.clearcoat *= slot_rgb(o, h, &m->clearcoat_map, false).x;
        }
        if (slot_active(o, &m->clearcoat_roughness_map)) {
            out->brdf.clearcoat_roughness *= slot_rgb(o, h, &m->clearcoat_roughness_map, false).y;
        }
        out->brdf.clearcoat = fmin(fmax(out->brdf.clearcoat, 0.0), 1.0);
        out->brdf.clearcoat_roughness = fmin(fmax(out->brdf.clearcoat_roughness, 0.0), 1.0);
        dvec3 nc = slot_active(o, &m->clearcoat_normal) ? mapped_normal(o, h, &m->clearcoat_normal, n) : n;
        out->brdf.clearcoat_normal[0] = nc.x;
        out->brdf.clearcoat_normal[1] = nc.y;
        out->brdf.clearcoat_normal[2] = nc.z;
    }
    if (slot_active(o, &m->occlusion)) {
        out->occlusion = 1.0 + m->occlusion_strength * (slot_rgb(o, h, &m->occlusion, false).x - 1.0);
    }
}
