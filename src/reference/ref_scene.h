/* The reference renderer's copy of one frame: world-space triangles after
 * morphs and deformers (read back from the GPU buffers every pass draws),
 * the same camera, lights (the renderer's expanded light list), materials
 * and environment, in an Embree scene. */
#ifndef CAUSTICA_REF_SCENE_H
#define CAUSTICA_REF_SCENE_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include <embree3/rtcore.h>

#include "core/error.h"
#include "core/brdf.h"
#include "core/optics.h"
#include "core/shading.h"
#include "graph/renderer.h"
#include "scene/scene.h"

typedef struct { double x, y, z; } dvec3;

static inline dvec3 dv(double x, double y, double z) { return (dvec3){x, y, z}; }
static inline dvec3 dv_add(dvec3 a, dvec3 b) { return dv(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline dvec3 dv_sub(dvec3 a, dvec3 b) { return dv(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline dvec3 dv_scale(dvec3 a, double s) { return dv(a.x * s, a.y * s, a.z * s); }
static inline dvec3 dv_mul(dvec3 a, dvec3 b) { return dv(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline double dv_dot(dvec3 a, dvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline dvec3 dv_cross(dvec3 a, dvec3 b)
{
    return dv(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
dvec3 dv_normalize_or(dvec3 a, dvec3 fallback);

/* Mirror reflection of d about unit n. */
static inline dvec3 ref_reflect(dvec3 d, dvec3 n) { return dv_sub(d, dv_scale(n, 2.0 * dv_dot(d, n))); }

/* Snell refraction of unit d about unit n facing against d (eta = n_from /
 * n_to); false under total internal reflection, never a NaN. */
static inline bool ref_refract(dvec3 d, dvec3 n, double eta, dvec3 *t)
{
    const double dd[3] = {d.x, d.y, d.z}, nn[3] = {n.x, n.y, n.z};
    double tt[3];
    if (!optics_refract(dd, nn, eta, tt))
        return false;
    *t = dv(tt[0], tt[1], tt[2]);
    return true;
}

static inline bool ref_is_dielectric(const struct material *m)
{
    return (m->kind == MATERIAL_GLASS && !m->thin) || m->kind == MATERIAL_WATER;
}

/* The surfaces a path meets without being absorbed: glass, water, mirrors
 * and thin glass (the photons' targets, specular_step's surfaces). */
#define REF_SPECULAR_ROLES (OBJECT_ROLE_SPECULAR | OBJECT_ROLE_THIN)

struct ref_object {
    float *positions; /* world space, vertex_count * 3 (+ padding for Embree), owned */
    float *normals;   /* world space, owned */
    uint32_t *indices; /* borrowed from the mesh */
    const float *texcoords[2]; /* borrowed from the mesh (NULL where it has no such set) */
    const float *colors;       /* glTF's COLOR_0, borrowed from the mesh (NULL: white) */
    const float *tangents;     /* a normal map's tangents in the mesh's space, borrowed (NULL: none) */
    mat4 model;                /* the frame's model matrix: a tangent's world direction (common/object.vert) */
    size_t vertex_count, triangle_count;
    struct material material;
    /* Traced as the sphere the script made (c.mesh.sphere), not as its
     * triangles (issue 53): Embree finds which object a ray meets first,
     * the hit is solved again in double precision on the sphere, its
     * normal exact. The triangles stay for the photons' aim (ref_emit.c). */
    bool sphere;
    dvec3 sphere_center;
    double sphere_radius;
    double epsilon; /* ray offset from its surface, from its own size (ref_scene_offset) */
};

/* Texture coordinates `set` at barycentrics (u, v) of triangle `primitive`. */
void ref_object_uv(const struct ref_object *o, unsigned primitive, double u, double v, int set, float uv[2]);
/* COLOR_0 there, RGBA (white where the mesh has none), as the GPU
 * interpolates it (common/object.vert). */
void ref_object_color(const struct ref_object *o, unsigned primitive, double u, double v, double rgba[4]);
/* Is (u, v) of the triangle cut out (alphaMode MASK: the base colour's
 * alpha below the material's cutoff; BLEND: xi, uniform in [0, 1) per ray,
 * at or above that alpha)? Embree's filter asks, so that rays and shadow
 * rays pass through cut-outs as on the GPU (ref_scene.c). */
bool ref_object_cut_out(const struct ref_object *o, unsigned primitive, double u, double v, double xi);

struct ref_light {
    int kind;        /* 0 point, 1 directional, 2 spot (as in the frame uniforms) */
    dvec3 position, direction, intensity;
    double cos_outer, cos_inner;
    struct shading_light shading; /* the same, for core/shading.c (the GPU's lighting function's twin) */
};

struct ref_scene {
    RTCDevice device;
    RTCScene rtc;
    struct ref_object *objects;
    int object_count;
    unsigned *geometry_object; /* Embree geometry id -> object index */
    int geometry_count;
    struct ref_light lights[SCENE_MAX_GPU_LIGHTS];
    int light_count;
    mat4 inv_view_proj;
    dvec3 eye;
    bool ortho;        /* an orthographic camera: parallel rays from the near plane */
    double znear;
    const struct environment *environment; /* borrowed */
    dvec3 background, ambient;
    dvec3 bounds_lo, bounds_hi;
    double epsilon; /* ray offset, from the scene size (a diffuse point's shadow rays) */
    bool has_specular_bounds;
    bool has_thin;  /* thin-walled glass: shadow rays go through it (ref_scene_transmittance) */
    dvec3 specular_center; /* bounding sphere of the specular objects */
    double specular_radius;
};

struct ref_hit {
    double t;
    int object;
    unsigned primitive;
    dvec3 position;
    dvec3 geometric_normal; /* unit, outward (counter-clockwise winding) */
    dvec3 shading_normal;   /* unit, on the same side as the geometric normal */
    double bary_u, bary_v;  /* Embree's barycentrics: the hit is (1-u-v) p0 + u p1 + v p2 */
    /* The pixel's footprint where an eye path knows it (ref_footprint.c):
     * the barycentrics' change to the next pixel across (dbary[0], [1])
     * and down ([2], [3]), for the textures' mip level. false: textures
     * are read at level 0 (photons, shadow and glossy rays). */
    bool footprint;
    double dbary[4];
};

/* The share of a glass or water surface that is the interface at the hit
 * (material.transmission x its transmission texture's red channel); the
 * rest is diffuse of its colour. */
double ref_object_transmission(const struct ref_object *o, const struct ref_hit *h);

/* What a diffuse surface shows at a hit: albedo and emission (times their
 * textures) and the shading normal (a normal map applied to `n`, the
 * face-forward shading normal), as common/material.glsl computes them on
 * the GPU (ref_material.c). */
struct ref_surface {
    dvec3 albedo, emission, normal;
    /* glTF's metallic-roughness model (material.pbr): the BRDF's
     * parameters at the hit (textures read) and the occlusion (on the
     * ambient sky only); brdf.base_color is `albedo` */
    bool pbr;
    struct brdf_material brdf;
    double occlusion;
};
void ref_surface_diffuse(const struct ref_scene *rs, const struct ref_hit *h, dvec3 n, struct ref_surface *out);

/* The spot falloff the shaders use (smoothstep over the cone's edge) for
 * light leaving in unit direction `out`; 1 for other lights. */
double ref_light_spot(const struct ref_light *l, dvec3 out);

/* `tessellated`: trace every object's triangles, spheres too (reference
 * --tessellated: the shapes the GPU draws); else the spheres the script made
 * are traced as spheres where they can be (ref_scene.c's exact_sphere). */
bool ref_scene_build(struct ref_scene *rs, struct renderer *r, struct scene *scene, bool tessellated,
                     struct error *err);
void ref_scene_release(struct ref_scene *rs);
bool ref_scene_intersect(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax, struct ref_hit *hit);
/* How far off the surface of h a ray leaving it starts: the object's own
 * scale, at least the float precision of the point (Embree's rays are
 * float). */
double ref_scene_offset(const struct ref_scene *rs, const struct ref_hit *h);
bool ref_scene_occluded(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax);
/* What reaches origin from tmax along dir: 0 where an opaque surface (or
 * glass, whose light the photons carry) is in the way, else the product
 * of what each thin-walled pane on the way lets through, (1 - F) x tint x
 * transmission (its expectation: the diffuse share of a partly
 * transmissive pane blocks). Without thin glass, ref_scene_occluded. */
dvec3 ref_scene_transmittance(const struct ref_scene *rs, dvec3 origin, dvec3 dir, double tmax);
/* BLEND's coins (alphaMode BLEND: a surface kept per ray with probability
 * alpha) on this thread take `salt` from here on; ref_scene_blend_met says
 * whether a ray met such a surface since. */
void ref_scene_blend_begin(uint64_t salt);
bool ref_scene_blend_met(void);
/* Thin-walled glass where a ray along `dir` meets it: the shading normal
 * (n, on the ray's side, through the normal map), the tint (base colour x
 * baseColorTexture x COLOR_0), as common/thin_glass.frag reads them, and
 * the Fresnel reflectance it returns (from air into the pane's IOR). */
/* A glass or mirror surface's normal at the hit: the outward normal n
 * through its normal map where it has one (refraction's
 * interface_normal.glsl maps the same), else n. */
dvec3 ref_interface_normal(const struct ref_object *o, const struct ref_hit *h, dvec3 n);
double ref_thin_surface(const struct ref_object *o, const struct ref_hit *h, dvec3 dir, dvec3 n, dvec3 *normal,
                        dvec3 *tint);
/* Glass's tint at a hit: the base colour x baseColorTexture (glTF's
 * transmission tint per texel; refract.frag's glass_tint). */
dvec3 ref_glass_tint(const struct ref_object *o, const struct ref_hit *h);
dvec3 ref_scene_environment(const struct ref_scene *rs, dvec3 dir);
/* The primary ray through image point (px, py) (pixels, top-left origin). */
void ref_scene_camera_ray(const struct ref_scene *rs, double px, double py, int width, int height, dvec3 *origin,
                          dvec3 *dir);

#endif
