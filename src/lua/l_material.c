/* c.material.diffuse / glass / mirror / water: materials as plain values
 * (an object keeps a copy; the textures a material names are shared). */
#include <math.h>
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"

/* emission = {r, g, b}: a radiance, so any finite value >= 0 (above 1 too). */
static void opt_emission(lua_State *L, int t, const char *fn, vec3 *out)
{
    lutil_opt_vec3(L, t, fn, "emission", out);
    if (!(out->x >= 0 && out->y >= 0 && out->z >= 0) || !isfinite(out->x + out->y + out->z))
        lutil_error(L, "bad argument 'emission' to '%s' (a radiance >= 0 per channel expected, got {%g, %g, %g})", fn,
                    (double)out->x, (double)out->y, (double)out->z);
}

/* field = a Texture: the slot reads it (one more reference, taken when the
 * material is pushed); the colour factor stays 1. */
static bool opt_texture(lua_State *L, int t, const char *field, struct texture_ref *slot)
{
    lua_getfield(L, t, field);
    const struct texture_ref *ref = ltexture_test(L, -1);
    if (ref)
        *slot = *ref;
    lua_pop(L, 1);
    return ref != NULL;
}

static int push_material(lua_State *L, enum material_kind kind, const char *fn)
{
    bool emissive = strcmp(fn, "emissive") == 0;
    struct material m;
    material_init(&m, kind);
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const diffuse_fields[] = {"color", "emission", "normal", "normal_scale", NULL};
        static const char *const mirror_fields[] = {"color", "roughness", "normal", "normal_scale", NULL};
        static const char *const emissive_fields[] = {"color", "strength", "albedo", NULL};
        static const char *const glass_fields[] = {"ior", "absorption", "fresnel", "roughness", "transmission",
                                                   "color", "tint", "thin", "normal", "normal_scale", NULL};
        static const char *const water_fields[] = {"ior", "absorption", "fresnel", "roughness", "transmission",
                                                   "color", "tint", NULL};
        lutil_check_fields(L, 1, fn, emissive ? emissive_fields : kind == MATERIAL_DIFFUSE ? diffuse_fields
                                     : kind == MATERIAL_MIRROR ? mirror_fields
                                     : kind == MATERIAL_WATER ? water_fields : glass_fields);
        if (emissive) {
            /* c.material.emissive { color, strength = 1, albedo = 0 }: a
             * diffuse surface that emits color x strength */
            float strength = 1.0f;
            vec3 color = vec3_make(1, 1, 1);
            lutil_opt_color(L, 1, fn, "color", &color);
            lutil_opt_number(L, 1, fn, "strength", &strength);
            if (!(strength >= 0.0f) || !isfinite(strength))
                return lutil_error(L, "bad argument 'strength' to '%s' (a number >= 0 expected, got %g)", fn,
                                   (double)strength);
            m.emission = vec3_scale(color, strength);
            m.color = vec3_make(0, 0, 0);
            lutil_opt_color(L, 1, fn, "albedo", &m.color);
        } else if (kind == MATERIAL_DIFFUSE && opt_texture(L, 1, "color", &m.base_color)) {
            m.color = vec3_make(1, 1, 1);
        } else {
            lutil_opt_color(L, 1, fn, "color", &m.color);
        }
        if (kind == MATERIAL_DIFFUSE && !emissive) {
            if (opt_texture(L, 1, "emission", &m.emissive))
                m.emission = vec3_make(1, 1, 1);
            else
                opt_emission(L, 1, fn, &m.emission);
        }
        /* a normal map: on diffuse surfaces, glass and mirrors */
        if (!emissive && kind != MATERIAL_WATER) {
            lua_getfield(L, 1, "normal");
            bool has_normal = !lua_isnil(L, -1);
            lua_pop(L, 1);
            if (has_normal && !opt_texture(L, 1, "normal", &m.normal))
                return lutil_field_error(L, fn, "normal", "texture (c.texture)", 1);
            float scale = 1.0f;
            lutil_opt_number(L, 1, fn, "normal_scale", &scale);
            m.normal.scale = scale;
        }
        lutil_opt_number(L, 1, fn, "ior", &m.ior);
        if (kind == MATERIAL_MIRROR) { /* mirror { roughness }: GGX, alpha = roughness^2 */
            lutil_opt_number(L, 1, fn, "roughness", &m.roughness);
            if (!(m.roughness >= 0.0f && m.roughness <= 1.0f))
                return lutil_error(L, "bad argument 'roughness' to '%s' (a number in [0, 1] expected, got %g)", fn,
                                   (double)m.roughness);
        }
        lutil_opt_color(L, 1, fn, "absorption", &m.absorption);
        if (kind == MATERIAL_GLASS || kind == MATERIAL_WATER) {
            bool fresnel = true;
            lutil_opt_boolean(L, 1, fn, "fresnel", &fresnel);
            m.ideal = !fresnel;
            lutil_opt_number(L, 1, fn, "roughness", &m.roughness);
            if (!(m.roughness >= 0.0f && m.roughness <= 1.0f))
                return lutil_error(L, "bad argument 'roughness' to '%s' (a number in [0, 1] expected, got %g)", fn,
                                   (double)m.roughness);
            lutil_opt_color(L, 1, fn, "tint", &m.tint);
            if (m.tint.x > 1.0f || m.tint.y > 1.0f || m.tint.z > 1.0f)
                return lutil_error(L, "bad argument 'tint' to '%s' (each channel in [0, 1]: a tint passes a share of "
                                   "the light, got {%g, %g, %g})", fn, (double)m.tint.x, (double)m.tint.y,
                                   (double)m.tint.z);
            /* thin = true: thin-walled glass, one surface light crosses
             * undeviated, (1 - F) x tint of it (glTF's glass without a volume) */
            if (kind == MATERIAL_GLASS)
                lutil_opt_boolean(L, 1, fn, "thin", &m.thin);
            lutil_opt_number(L, 1, fn, "transmission", &m.transmission);
            if (!(m.transmission >= 0.0f && m.transmission <= 1.0f))
                return lutil_error(L, "bad argument 'transmission' to '%s' (a number in [0, 1] expected, got %g)",
                                   fn, (double)m.transmission);
        }
    }
    if (!(m.ior > 0.0f) || !isfinite(m.ior))
        return lutil_error(L, "bad argument 'ior' to '%s' (a positive number expected, got %g)", fn, (double)m.ior);
    lmaterial_push(L, &m);
    return 1;
}

void lmaterial_push(lua_State *L, const struct material *m)
{
    struct material *u = lua_newuserdatauv(L, sizeof *u, 0);
    material_init(u, m->kind);
    luaL_setmetatable(L, MATERIAL_MT);
    material_assign(u, m);
}

static int material_gc(lua_State *L)
{
    material_release(luaL_checkudata(L, 1, MATERIAL_MT));
    return 0;
}

static int material_diffuse(lua_State *L) { return push_material(L, MATERIAL_DIFFUSE, "diffuse"); }
static int material_glass(lua_State *L) { return push_material(L, MATERIAL_GLASS, "glass"); }
static int material_emissive(lua_State *L) { return push_material(L, MATERIAL_DIFFUSE, "emissive"); }
static int material_mirror(lua_State *L) { return push_material(L, MATERIAL_MIRROR, "mirror"); }
static int material_water(lua_State *L) { return push_material(L, MATERIAL_WATER, "water"); }

static struct material *check_material(lua_State *L) { return luaL_checkudata(L, 1, MATERIAL_MT); }

static int get_kind(lua_State *L)
{
    lua_pushstring(L, material_kind_name(check_material(L)->kind));
    return 1;
}

static int get_color(lua_State *L)
{
    lutil_push_vec3(L, check_material(L)->color);
    return 1;
}

static int get_ior(lua_State *L)
{
    lua_pushnumber(L, check_material(L)->ior);
    return 1;
}

static int get_absorption(lua_State *L)
{
    lutil_push_vec3(L, check_material(L)->absorption);
    return 1;
}

static int get_emission(lua_State *L)
{
    lutil_push_vec3(L, check_material(L)->emission);
    return 1;
}

static int get_tint(lua_State *L)
{
    lutil_push_vec3(L, check_material(L)->tint);
    return 1;
}

static int get_transmission(lua_State *L)
{
    lua_pushnumber(L, check_material(L)->transmission);
    return 1;
}

static int get_roughness(lua_State *L)
{
    lua_pushnumber(L, check_material(L)->roughness);
    return 1;
}

static int get_fresnel(lua_State *L)
{
    lua_pushboolean(L, !check_material(L)->ideal);
    return 1;
}

static int get_thin(lua_State *L)
{
    lua_pushboolean(L, check_material(L)->thin);
    return 1;
}

/* The Texture a slot reads, or nil. */
static void push_texture_slot(lua_State *L, const struct texture_ref *slot)
{
    if (!slot->texture) {
        lua_pushnil(L);
        return;
    }
    ltexture_push_ref(L, slot);
}

static int get_texture(lua_State *L)
{
    push_texture_slot(L, &check_material(L)->base_color);
    return 1;
}

static int get_normal(lua_State *L)
{
    push_texture_slot(L, &check_material(L)->normal);
    return 1;
}

static int get_emission_texture(lua_State *L)
{
    push_texture_slot(L, &check_material(L)->emissive);
    return 1;
}

static int material_tostring(lua_State *L)
{
    lua_pushfstring(L, "Material(%s)", material_kind_name(check_material(L)->kind));
    return 1;
}

void lmaterial_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__tostring", material_tostring}, {"__gc", material_gc}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"kind", get_kind}, {"color", get_color}, {"ior", get_ior},
                                       {"absorption", get_absorption}, {"fresnel", get_fresnel},
                                       {"roughness", get_roughness}, {"transmission", get_transmission},
                                       {"tint", get_tint}, {"thin", get_thin},
                                       {"emission", get_emission}, {"texture", get_texture},
                                       {"normal", get_normal}, {"emission_texture", get_emission_texture},
                                       {NULL, NULL}};
    lutil_class(L, MATERIAL_MT, "material", meta, NULL, getters, NULL);
    static const luaL_Reg materials[] = {{"diffuse", material_diffuse}, {"glass", material_glass},
                                         {"mirror", material_mirror}, {"water", material_water},
                                         {"emissive", material_emissive}, {NULL, NULL}};
    luaL_newlib(L, materials);
    lua_setfield(L, -2, "material");
}
