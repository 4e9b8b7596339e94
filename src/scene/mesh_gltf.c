/* glTF files as meshes: the loader's arrays (io/gltf_shim.cpp), each
 * material the primitives name mapped onto caustica's (glass, mirror,
 * diffuse, emissive), and a file with several materials split into one
 * part per material (scene/mesh_parts.c). What a material asks for that
 * neither renderer draws is listed in its `ignored`, which `info` prints:
 * nothing is dropped in silence. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/gltf.h"
#include "scene/scene.h"

/* A glTF metal this smooth or smoother is drawn as a perfect mirror;
 * rougher, as a diffuse surface of its base colour (both said in
 * `ignored`). glTF's roughness is perceptual (alpha = roughness^2): at
 * 0.3 the lobe's alpha is 0.09, a few degrees, which a mirror stands for. */
#define GLTF_MIRROR_ROUGHNESS 0.3f
/* Below this the roughness is not worth a line. */
#define GLTF_SMOOTH_ROUGHNESS 0.05f

static void ignored_add(struct material *m, const char *fmt, ...)
{
    size_t used = strlen(m->ignored);
    if (used + 3 >= sizeof m->ignored)
        return;
    if (used) {
        memcpy(m->ignored + used, ", ", 3);
        used += 2;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m->ignored + used, sizeof m->ignored - used, fmt, ap);
    va_end(ap);
}

/* glTF's metal-roughness material onto caustica's kinds:
 * - transmission > 0 (and not a metal): glass with the file's IOR and
 *   KHR_materials_volume's attenuation as Beer-Lambert absorption,
 *   sigma = -ln(c) / d;
 * - metallic >= 0.5 and roughness at most GLTF_MIRROR_ROUGHNESS, by its
 *   factors or at every texel of its metallicRoughnessTexture: a mirror
 *   tinted by the base colour (it reflects the scene, which the BRDF's
 *   passes do not yet);
 * - otherwise a surface drawn by glTF's BRDF (material.pbr: metallic and
 *   roughness per texel, core/brdf.c), with the base colour, normal,
 *   emissive, metallicRoughness and occlusion textures, alphaMode MASK's
 *   cut-outs (material.alpha_cutoff) and BLEND's stochastic ones
 *   (material.alpha_blend). */
static void material_map(const struct gltf_material *g, bool smooth_metal_texture, struct material *m)
{
    snprintf(m->source, sizeof m->source, "%s", g->name);
    vec3 base = vec3_make(g->base_color[0], g->base_color[1], g->base_color[2]);
    bool metal = g->metallic >= 0.5f;
    m->color = base;
    m->ior = g->ior; /* validated by the loader */
    if (g->transmission > 0.0f && !metal) {
        m->kind = MATERIAL_GLASS;
        m->thickness = g->volume ? g->thickness : 0.0f;
        if (g->attenuation_distance > 0.0f) {
            const float *c = g->attenuation_color;
            float d = g->attenuation_distance;
            m->absorption = vec3_make(-logf(fmaxf(c[0], 1e-6f)) / d, -logf(fmaxf(c[1], 1e-6f)) / d,
                                      -logf(fmaxf(c[2], 1e-6f)) / d);
        }
        /* partial transmission: the rest of the surface is diffuse of the
         * base colour (the reference picks one per path, refraction blends) */
        m->transmission = g->transmission;
        /* rough transmission: the reference samples GGX microfacets, the
         * passes that can blur (refraction) do, the others say so */
        m->roughness = g->roughness > GLTF_SMOOTH_ROUGHNESS ? g->roughness : 0.0f;
        /* KHR_materials_transmission: the transmitted light is tinted by
         * the base colour. Once per way through (on entering), as the
         * samples' answer keys have it (AttenuationTest's Sample Color row:
         * base colour c = what attenuationColor c at thickness 1 lets
         * through once) */
        m->tint = vec3_min(base, vec3_make(1, 1, 1)); /* a tint passes a share, never more */
        /* glTF calls glass without a volume (or of thicknessFactor 0)
         * thin-walled: one surface that light crosses undeviated, tinted
         * by the base colour (x its texture, per texel) */
        m->thin = !g->volume || !(g->thickness > 0.0f);
        if (m->thin) {
            m->absorption = vec3_make(0, 0, 0); /* no volume to absorb over */
            if (m->roughness > 0.0f)
                ignored_add(m, "roughness %.2g on thin-walled glass (drawn smooth)", m->roughness);
            m->roughness = 0.0f;
        }
        if (g->metallic > 0.0f)
            ignored_add(m, "metallic %.2g", g->metallic);
        /* transmissionTexture: per texel, material.transmission_map */
    } else if (metal && g->roughness <= GLTF_MIRROR_ROUGHNESS &&
               (!g->metallic_roughness_texture.bytes || smooth_metal_texture)) {
        m->kind = MATERIAL_MIRROR;
        /* a rough mirror: the reference samples GGX microfacets, refraction's
         * scene lookup blurs its reflection, the other passes say so */
        m->roughness = g->roughness > GLTF_SMOOTH_ROUGHNESS ? g->roughness : 0.0f;
        if (g->transmission > 0.0f)
            ignored_add(m, "transmission %.2g (a metal does not transmit)", g->transmission);
        if (g->transmission_texture.bytes)
            ignored_add(m, "transmissionTexture (a metal does not transmit)");
    } else {
        m->kind = MATERIAL_DIFFUSE;
        m->pbr = true;
        m->metallic = g->metallic;
        m->roughness = g->roughness;
        m->occlusion_strength = g->occlusion_strength;
        m->specular = g->specular;
        m->specular_color = vec3_make(g->specular_color[0], g->specular_color[1], g->specular_color[2]);
        m->clearcoat = g->clearcoat;
        m->clearcoat_roughness = g->clearcoat_roughness;
        m->emission = vec3_make(g->emission[0], g->emission[1], g->emission[2]);
        if (metal && g->transmission > 0.0f)
            ignored_add(m, "transmission %.2g (a metal does not transmit; metallicFactor is 1 unless the file "
                           "says 0)", g->transmission);
    }
    if (g->thickness_texture.bytes && !(m->kind == MATERIAL_GLASS && !m->thin))
        ignored_add(m, "thicknessTexture (drawn on glass with a volume only)");
    if (!m->pbr && g->clearcoat > 0.0f)
        ignored_add(m, "KHR_materials_clearcoat (drawn on glTF's BRDF surfaces only, not on %s)",
                    m->kind == MATERIAL_MIRROR ? "smooth metals, drawn as mirrors" : "glass");
    if (m->kind != MATERIAL_DIFFUSE) {
        if (g->emission[0] > 0.0f || g->emission[1] > 0.0f || g->emission[2] > 0.0f)
            ignored_add(m, "emission (drawn on diffuse surfaces only)");
        if (g->base_color_texture.bytes && m->kind != MATERIAL_GLASS)
            ignored_add(m, g->alpha_mode != GLTF_ALPHA_OPAQUE
                               ? "baseColorTexture's colour (drawn on diffuse surfaces only; its alpha is read)"
                               : "baseColorTexture (drawn on diffuse surfaces only)");
        if (g->emissive_texture.bytes)
            ignored_add(m, "emissiveTexture (drawn on diffuse surfaces only)");
        if (g->occlusion_texture.bytes)
            ignored_add(m, "occlusionTexture (drawn on diffuse surfaces only)");
    }
    /* alphaMode on every kind: a crack cut out of a pane is a hole, and so
     * is one cut out of a mirror or of solid glass (the surface is not
     * there: a path through it meets what lies beyond, the glass's far
     * side included) */
    m->single_sided = (m->kind == MATERIAL_DIFFUSE || m->thin) && !g->double_sided;
    if (g->alpha_mode == GLTF_ALPHA_MASK) {
        m->alpha = g->alpha;
        m->alpha_cutoff = g->alpha_cutoff;
    } else if (g->alpha_mode == GLTF_ALPHA_BLEND) {
        m->alpha = g->alpha;
        m->alpha_blend = true;
    }
    if (g->unread[0])
        ignored_add(m, "%s", g->unread);
    if (g->unread_more)
        ignored_add(m, "and %d more extensions or attributes (too many to name)", g->unread_more);
}

/* The textures of a diffuse material (or glass's transmissionTexture),
 * decoded within what is left of the budget (`used` counts what the file's
 * textures took so far). */
static bool material_textures(const char *path, struct gltf_material *g, const struct mesh *whole,
                              unsigned long long budget, unsigned long long *used, struct material *m,
                              struct error *err)
{
    struct {
        struct gltf_texture *from;
        struct texture_ref *to;
    } slots[12] = {{&g->base_color_texture, &m->base_color},
                  {&g->normal_texture, &m->normal},
                  {&g->emissive_texture, &m->emissive},
                  {&g->metallic_roughness_texture, &m->metallic_roughness},
                  {&g->occlusion_texture, &m->occlusion},
                  {&g->transmission_texture, &m->transmission_map},
                  {&g->specular_texture, &m->specular_map},
                  {&g->specular_color_texture, &m->specular_color_map},
                  {&g->clearcoat_texture, &m->clearcoat_map},
                  {&g->clearcoat_roughness_texture, &m->clearcoat_roughness_map},
                  {&g->clearcoat_normal_texture, &m->clearcoat_normal},
                  {&g->thickness_texture, &m->thickness_map}};
    /* diffuse surfaces read all but the transmission (the specular and
     * clearcoat ones where glTF's BRDF draws them), glass its transmission and its base
     * colour (the tint per texel), its normal map (refraction and the
     * reference map it) and, solid, its thickness; mirrors their normal
     * map, and their base colour where its alpha cuts or blends them */
    bool glass = m->kind == MATERIAL_GLASS, mirror = m->kind == MATERIAL_MIRROR;
    if (!glass && !mirror && m->kind != MATERIAL_DIFFUSE)
        return true;
    for (int s = 0; s < 12; s++) {
        struct gltf_texture *gt = slots[s].from;
        bool read = mirror  ? s == 1 || (s == 0 && g->alpha_mode != GLTF_ALPHA_OPAQUE)
                    : glass ? s == 5 || s == 0 || s == 1 || (!m->thin && s == 11)
                            : s < 5 || (s >= 6 && s < 11 && m->pbr);
        if (!gt->bytes || !read)
            continue;
        if (!whole->texcoords[gt->texcoord])
            return error_set(err, "%s: material '%s': a texture reads TEXCOORD_%d, which no primitive has", path,
                             g->name, gt->texcoord);
        char name[700];
        snprintf(name, sizeof name, "%s %s", path, gt->name);
        if (budget && *used >= budget)
            return error_set(err, "%s: no memory left for its texture %s (its textures may take %.1f MB)", path,
                             gt->name, (double)budget / 1048576.0);
        struct texture *t = texture_decode(name, gt->bytes, gt->size, budget ? budget - *used : 0, err);
        if (!t)
            return false;
        *used += texture_bytes(t);
        t->wrap_s = (enum texture_wrap)gt->wrap_s;
        t->wrap_t = (enum texture_wrap)gt->wrap_t;
        t->nearest = gt->nearest;
        t->mipmaps = gt->mipmaps;
        struct texture_ref *ref = slots[s].to;
        ref->texture = t;
        ref->texcoord = gt->texcoord;
        memcpy(ref->transform, gt->transform, sizeof ref->transform);
        ref->scale = gt->scale;
    }
    return true;
}

/* glTF's metallicRoughnessTexture scales the factors per texel (G:
 * roughness, B: metallic). A surface drawn by the BRDF reads it per texel.
 * Glass, whose roughness the reference samples per material, takes the
 * texture's means (over its texels, linear), which `ignored` says: *means
 * holds (metallic, roughness) means, or (-1, -1) where not taken. Glass is
 * a transmissive material whose mean metallic (factor x mean B) is below
 * 0.5: a file that leaves metallicFactor at its default 1 and says 0 in the
 * texture (TransmissionRoughnessTest's tiles) is glass. A metal whose every
 * texel is a smooth metal (metallic x least B >= 0.5, roughness x greatest
 * G <= GLTF_MIRROR_ROUGHNESS) is a mirror, as by its factors alone: *mirror
 * says so (and the factors become the means). */
static bool metallic_roughness_means(const char *path, struct gltf_material *g, unsigned long long budget,
                                     unsigned long long used, float means[2], bool *mirror, struct error *err)
{
    means[0] = means[1] = -1.0f;
    *mirror = false;
    struct gltf_texture *gt = &g->metallic_roughness_texture;
    if (!gt->bytes || (g->metallic < 0.5f && !(g->transmission > 0.0f)))
        return true; /* (a dielectric of no transmission: drawn per texel without looking) */
    char name[700];
    snprintf(name, sizeof name, "%s %s", path, gt->name);
    if (budget && used >= budget)
        return error_set(err, "%s: no memory left for its texture %s (its textures may take %.1f MB)", path,
                         gt->name, (double)budget / 1048576.0);
    struct texture *t = texture_decode(name, gt->bytes, gt->size, budget ? budget - used : 0, err);
    if (!t)
        return false;
    double sum_g = 0.0, sum_b = 0.0;
    int least_b = 255, most_g = 0;
    size_t n = (size_t)t->width * (size_t)t->height;
    for (size_t i = 0; i < n; i++) {
        sum_g += t->texels[i * 4 + 1];
        sum_b += t->texels[i * 4 + 2];
        least_b = t->texels[i * 4 + 2] < least_b ? t->texels[i * 4 + 2] : least_b;
        most_g = t->texels[i * 4 + 1] > most_g ? t->texels[i * 4 + 1] : most_g;
    }
    texture_destroy(t);
    float mean_b = n ? (float)(sum_b / (255.0 * (double)n)) : 1.0f;
    float mean_g = n ? (float)(sum_g / (255.0 * (double)n)) : 1.0f;
    bool glass = g->transmission > 0.0f && g->metallic * mean_b < 0.5f;
    /* a transmissive metal (TransmissionTest's metal row: metal at most of
     * its texels, glass at a few) cannot be both per texel: its means decide,
     * as for glass */
    bool transmissive_metal = g->transmission > 0.0f && !glass;
    *mirror = !glass && (transmissive_metal ? g->metallic * mean_b >= 0.5f && g->roughness * mean_g <= GLTF_MIRROR_ROUGHNESS
                                            : g->metallic * (float)least_b / 255.0f >= 0.5f &&
                                                  g->roughness * (float)most_g / 255.0f <= GLTF_MIRROR_ROUGHNESS);
    if (!glass && !*mirror)
        return true; /* drawn per texel */
    means[0] = mean_b;
    means[1] = mean_g;
    g->metallic *= means[0];
    g->roughness *= means[1];
    return true;
}

/* The whole mesh from the loader's arrays (it takes them). */
static struct mesh *mesh_from_gltf(const char *path, struct gltf_mesh *g, struct error *err)
{
    struct mesh *m = mesh_create_from_arrays(path, g->positions, g->normals, g->vertex_count, g->indices,
                                             g->index_count, err);
    g->positions = g->normals = NULL;
    g->indices = NULL;
    if (!m)
        return NULL;
    m->texcoords[0] = g->texcoords[0];
    m->texcoords[1] = g->texcoords[1];
    g->texcoords[0] = g->texcoords[1] = NULL;
    m->colors = g->colors;
    g->colors = NULL;
    m->tangents = g->tangents;
    g->tangents = NULL;
    m->joints = g->joints;
    m->joint_weights = g->joint_weights;
    g->joints = g->joint_weights = NULL;
    for (size_t i = 0; m->joints && i < m->vertex_count * 4; i++)
        if (m->joint_weights[i] > 0.0f && (int)m->joints[i] + 1 > m->joint_count)
            m->joint_count = (int)m->joints[i] + 1;
    m->target_count = g->target_count;
    m->target_positions = g->target_positions;
    m->target_normals = g->target_normals;
    g->target_positions = g->target_normals = NULL;
    for (int t = 0; t < g->target_count; t++)
        m->default_weights[t] = g->weights[t];
    /* tangents for the normal maps of ranges whose file gave none */
    for (size_t r = 0; m->tangents && r < g->range_count; r++) {
        int slot = g->ranges[r].material;
        const struct gltf_material *gm = slot >= 0 && slot < g->material_count ? &g->materials[slot] : NULL;
        int set = gm && gm->normal_texture.bytes             ? gm->normal_texture.texcoord
                  : gm && gm->clearcoat_normal_texture.bytes ? gm->clearcoat_normal_texture.texcoord
                                                             : -1;
        if (set >= 0 && !mesh_make_tangents(m, g->ranges[r].first_index, g->ranges[r].index_count, set, err)) {
            mesh_destroy(m);
            return NULL;
        }
    }
    mesh_compute_bounds(m);
    return m;
}

/* One part per material, in the order the file first uses them. */
static bool mesh_split(const char *path, struct mesh *m, const struct gltf_mesh *g, const struct material *materials,
                       const int *slots, int slot_count, struct error *err)
{
    size_t *first = malloc(g->range_count * sizeof *first), *count = malloc(g->range_count * sizeof *count);
    m->parts = calloc((size_t)slot_count, sizeof *m->parts);
    if (!first || !count || !m->parts) {
        free(first);
        free(count);
        return error_set(err, "%s: out of memory", path);
    }
    bool ok = true;
    for (int p = 0; p < slot_count && ok; p++) {
        int n = 0;
        for (size_t r = 0; r < g->range_count; r++)
            if (g->ranges[r].material == slots[p]) {
                first[n] = g->ranges[r].first_index;
                count[n++] = g->ranges[r].index_count;
            }
        char name[600];
        snprintf(name, sizeof name, "%s [%s]", path,
                 slots[p] >= 0 ? g->materials[slots[p]].name : "no material");
        struct mesh *part = mesh_create_part(m, name, first, count, n, err);
        ok = part != NULL;
        if (ok) {
            m->parts[m->part_count++] = part;
            part->has_material = slots[p] >= 0;
            if (part->has_material) {
                material_assign(&part->material, &materials[slots[p]]);
                snprintf(part->material_name, sizeof part->material_name, "%s", g->materials[slots[p]].name);
            }
        }
    }
    free(first);
    free(count);
    return ok;
}

/* The mesh, its materials and parts from what the loader read (g, freed
 * here); `path` names it in messages. */
static struct mesh *mesh_build(const char *path, struct gltf_mesh g, unsigned long long texture_budget,
                               struct error *err)
{
    if (g.target_count > SCENE_MAX_MORPH_TARGETS) {
        error_set(err, "%s: %d morph targets, at most %d are supported", path, g.target_count,
                  SCENE_MAX_MORPH_TARGETS);
        gltf_mesh_free(&g);
        return NULL;
    }
    struct mesh *m = mesh_from_gltf(path, &g, err);
    struct material *materials = calloc((size_t)g.material_count + 1, sizeof *materials);
    /* the distinct material slots the ranges use, in first-use order (-1: none) */
    int *slots = malloc((g.range_count + 1) * sizeof *slots);
    int slot_count = 0;
    bool ok = m && materials && slots;
    if (m && !ok)
        error_set(err, "%s: out of memory", path);
    unsigned long long used = 0;
    for (int i = 0; ok && i < g.material_count; i++) {
        float means[2];
        bool smooth_metal = false;
        ok = metallic_roughness_means(path, &g.materials[i], texture_budget, used, means, &smooth_metal, err);
        if (!ok)
            break;
        material_init(&materials[i], MATERIAL_DIFFUSE);
        material_map(&g.materials[i], smooth_metal, &materials[i]);
        if (means[0] >= 0.0f)
            ignored_add(&materials[i], "metallicRoughnessTexture (its means taken: metallic x %.2g, roughness x %.2g)",
                        means[0], means[1]);
        ok = material_textures(path, &g.materials[i], m, texture_budget, &used, &materials[i], err);
    }
    for (size_t r = 0; ok && r < g.range_count; r++) {
        bool seen = false;
        for (int k = 0; k < slot_count; k++)
            seen = seen || slots[k] == g.ranges[r].material;
        if (!seen)
            slots[slot_count++] = g.ranges[r].material;
    }
    if (ok && slot_count > 1)
        ok = mesh_split(path, m, &g, materials, slots, slot_count, err);
    if (ok && slot_count >= 1 && slots[0] >= 0) {
        /* the mesh's own material: its only one, or its first part's (what
         * `object.material` reads on a group) */
        m->has_material = true;
        material_assign(&m->material, &materials[slots[0]]);
        if (m->part_count == 0)
            snprintf(m->material_name, sizeof m->material_name, "%s", g.materials[slots[0]].name);
    }
    for (int i = 0; materials && i < g.material_count; i++)
        material_release(&materials[i]);
    free(materials);
    free(slots);
    gltf_mesh_free(&g);
    if (!ok) {
        mesh_destroy(m);
        return NULL;
    }
    return m;
}

struct mesh *mesh_load_gltf(const char *path, unsigned long long texture_budget, struct error *err)
{
    struct gltf_mesh g;
    if (!gltf_load(path, &g, err))
        return NULL;
    return mesh_build(path, g, texture_budget, err);
}

struct mesh *mesh_load_gltf_mesh(const struct gltf_file *file, const char *path, int index,
                                 unsigned long long texture_budget, struct error *err)
{
    struct gltf_mesh g;
    if (!gltf_file_mesh(file, index, &g, err))
        return NULL;
    return mesh_build(path, g, texture_budget, err);
}
