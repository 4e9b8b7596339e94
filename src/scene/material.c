/* Materials: their kinds, the role each gives an object (the one
 * predicate passes, lint and the reference choose objects by), and the
 * references a material holds to its textures. */
#include <string.h>

#include "scene/scene.h"

const char *material_kind_name(enum material_kind kind)
{
    switch (kind) {
    case MATERIAL_DIFFUSE: return "diffuse";
    case MATERIAL_GLASS: return "glass";
    case MATERIAL_MIRROR: return "mirror";
    case MATERIAL_WATER: return "water";
    }
    return "?";
}

unsigned material_role(const struct material *m)
{
    switch (m->kind) {
    case MATERIAL_GLASS: return m->thin ? OBJECT_ROLE_THIN : OBJECT_ROLE_GLASS;
    case MATERIAL_WATER: return OBJECT_ROLE_WATER;
    case MATERIAL_MIRROR: return OBJECT_ROLE_MIRROR;
    case MATERIAL_DIFFUSE: break;
    }
    return OBJECT_ROLE_RECEIVER;
}

const char *object_role_name(unsigned role)
{
    switch (role) {
    case OBJECT_ROLE_GLASS: return "glass";
    case OBJECT_ROLE_WATER: return "water";
    case OBJECT_ROLE_MIRROR: return "mirror";
    case OBJECT_ROLE_RECEIVER: return "receiver";
    case OBJECT_ROLE_THIN: return "thin glass";
    default: return "object";
    }
}

bool material_is_textured_surface(const struct material *m)
{
    unsigned role = material_role(m);
    return role == OBJECT_ROLE_RECEIVER || role == OBJECT_ROLE_THIN;
}

void material_init(struct material *m, enum material_kind kind)
{
    memset(m, 0, sizeof *m);
    m->kind = kind;
    m->color = kind == MATERIAL_MIRROR ? vec3_make(1, 1, 1) : vec3_make(0.8f, 0.8f, 0.8f);
    m->ior = kind == MATERIAL_WATER ? 1.33f : 1.5f;
    m->alpha = 1.0f;
    m->transmission = 1.0f;
    m->tint = vec3_make(1, 1, 1);
    m->specular = 1.0f;
    m->specular_color = vec3_make(1, 1, 1);
    texture_ref_init(&m->base_color);
    texture_ref_init(&m->normal);
    texture_ref_init(&m->emissive);
    texture_ref_init(&m->transmission_map);
    texture_ref_init(&m->metallic_roughness);
    texture_ref_init(&m->occlusion);
    texture_ref_init(&m->specular_map);
    texture_ref_init(&m->specular_color_map);
    texture_ref_init(&m->thickness_map);
    texture_ref_init(&m->clearcoat_map);
    texture_ref_init(&m->clearcoat_roughness_map);
    texture_ref_init(&m->clearcoat_normal);
}

void material_texture_slots(const struct material *m, const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS],
                            bool srgb[MATERIAL_TEXTURE_SLOTS])
{
    const struct texture_ref *all[MATERIAL_TEXTURE_SLOTS] = {
        &m->base_color,    &m->normal,           &m->emissive,      &m->transmission_map,
        &m->metallic_roughness, &m->occlusion,   &m->specular_map,  &m->specular_color_map,
        &m->thickness_map, &m->clearcoat_map,    &m->clearcoat_roughness_map, &m->clearcoat_normal};
    for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++) {
        slots[k] = all[k];
        srgb[k] = all[k] == &m->base_color || all[k] == &m->emissive || all[k] == &m->specular_color_map;
    }
}

void material_assign(struct material *dst, const struct material *src)
{
    if (dst == src)
        return;
    const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS];
    bool srgb[MATERIAL_TEXTURE_SLOTS];
    material_texture_slots(src, slots, srgb);
    for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++)
        texture_retain(slots[k]->texture);
    material_release(dst);
    *dst = *src;
}

void material_release(struct material *m)
{
    const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS];
    bool srgb[MATERIAL_TEXTURE_SLOTS];
    material_texture_slots(m, slots, srgb);
    for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++)
        texture_destroy(slots[k]->texture);
    m->base_color.texture = m->normal.texture = m->emissive.texture = m->transmission_map.texture = NULL;
    m->metallic_roughness.texture = m->occlusion.texture = m->specular_map.texture = NULL;
    m->specular_color_map.texture = m->thickness_map.texture = m->clearcoat_map.texture = NULL;
    m->clearcoat_roughness_map.texture = m->clearcoat_normal.texture = NULL;
}

bool material_has_textures(const struct material *m)
{
    return m->base_color.texture || m->normal.texture || m->emissive.texture || m->transmission_map.texture;
}
