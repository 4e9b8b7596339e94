/* c.texture "file.png" | c.texture { file, wrap, filter, scale, offset,
 * rotation, texcoord } | c.texture.checker { size, a, b }: textures for
 * c.material.diffuse { color = tex, normal = tex, emission = tex }. A
 * Texture value holds the texels (shared, reference counted) and where a
 * material reads them (texcoord set and transform). */
#include <math.h>
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"

/* A Texture value: the reference, and the bytes charged against
 * --script-memory for it (its texels, when this value made the texture). */
struct l_texture {
    struct texture_ref ref;
    size_t charged;
};

static struct texture_ref *check_texture(lua_State *L, int idx)
{
    struct l_texture *u = luaL_checkudata(L, idx, TEXTURE_MT);
    if (!u->ref.texture)
        lscene_released(L, idx, "texture");
    return &u->ref;
}

const struct texture_ref *ltexture_test(lua_State *L, int idx)
{
    struct l_texture *u = luaL_testudata(L, idx, TEXTURE_MT);
    return u && u->ref.texture ? &u->ref : NULL;
}

void ltexture_push_ref(lua_State *L, const struct texture_ref *ref)
{
    struct l_texture *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->ref = *ref;
    u->charged = 0;
    texture_retain(u->ref.texture);
    luaL_setmetatable(L, TEXTURE_MT);
}

/* Takes the caller's reference to t, and charges its texels against
 * --script-memory (the decoders checked them against what was left before
 * allocating; a checker is small but counted all the same). */
static struct texture_ref *push_texture(lua_State *L, struct texture *t)
{
    struct error err;
    char what[600];
    snprintf(what, sizeof what, "texture '%.500s' (%dx%d)", t->name, t->width, t->height);
    if (!lua_host_charge(L, texture_bytes(t), what, &err)) {
        texture_destroy(t);
        lutil_error(L, "%s", err.message);
    }
    struct l_texture *u = lua_newuserdatauv(L, sizeof *u, 0);
    texture_ref_init(&u->ref);
    u->ref.texture = t;
    u->charged = texture_bytes(t);
    luaL_setmetatable(L, TEXTURE_MT);
    return &u->ref;
}

/* A pair {x, y} or one number for both. */
static void opt_pair(lua_State *L, int t, const char *field, float out[2])
{
    int type = lua_getfield(L, t, field);
    if (type == LUA_TNUMBER) {
        out[0] = out[1] = lutil_check_number(L, -1, "texture", field);
    } else if (type == LUA_TTABLE) {
        for (int i = 0; i < 2; i++) {
            lua_geti(L, -1, i + 1);
            if (lua_type(L, -1) != LUA_TNUMBER)
                lutil_field_error(L, "texture", field, "{x, y} numbers", -2);
            out[i] = lutil_check_number(L, -1, "texture", field);
            lua_pop(L, 1);
        }
    } else if (type != LUA_TNIL) {
        lutil_field_error(L, "texture", field, "number or {x, y}", -1);
    }
    lua_pop(L, 1);
}

static struct texture *load_file(lua_State *L, const char *rel)
{
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        lutil_error(L, "%s", err.message);
    unsigned long long left = lua_host_memory_left(L);
    struct texture *t = texture_load(path, left, &err);
    if (!t)
        lutil_error(L, "%s%s", err.message,
                    left && strstr(err.message, "more than the") ? " (what --script-memory leaves the script; raise it, "
                                                                   "0 = no limit)" : "");
    return t;
}

/* c.texture(path | options): the __call of the c.texture table (self at 1). */
static int texture_new(lua_State *L)
{
    if (lua_type(L, 2) == LUA_TSTRING) {
        push_texture(L, load_file(L, lua_tostring(L, 2)));
        return 1;
    }
    if (lua_type(L, 2) != LUA_TTABLE)
        return luaL_typeerror(L, 2, "file name or option table");
    static const char *const fields[] = {"file", "wrap", "filter", "scale", "offset", "rotation", "texcoord",
                                         "mipmaps", NULL};
    lutil_check_fields(L, 2, "texture", fields);
    static const char *const wraps[] = {"repeat", "clamp", "mirror", NULL};
    static const char *const filters[] = {"linear", "nearest", NULL};
    /* Everything is checked before the file is read. */
    int wrap = lutil_opt_option(L, 2, "texture", "wrap", wraps, 0);
    int filter = lutil_opt_option(L, 2, "texture", "filter", filters, 0);
    float scale[2] = {1, 1}, offset[2] = {0, 0}, rotation = 0;
    int texcoord = 0;
    bool mipmaps = true;
    opt_pair(L, 2, "scale", scale);
    opt_pair(L, 2, "offset", offset);
    lutil_opt_number(L, 2, "texture", "rotation", &rotation);
    lutil_opt_integer(L, 2, "texture", "texcoord", &texcoord);
    lutil_opt_boolean(L, 2, "texture", "mipmaps", &mipmaps);
    if (texcoord != 0 && texcoord != 1)
        return lutil_error(L, "bad argument 'texcoord' to 'texture' (0 or 1 expected, got %d)", texcoord);
    if (lua_getfield(L, 2, "file") != LUA_TSTRING)
        return lutil_field_error(L, "texture", "file", "file name (string)", -1);
    struct texture *t = load_file(L, lua_tostring(L, -1));
    lua_pop(L, 1);
    t->wrap_s = t->wrap_t = (enum texture_wrap)wrap;
    t->nearest = filter == 1;
    t->mipmaps = mipmaps;
    struct texture_ref *u = push_texture(L, t);
    u->texcoord = texcoord;
    /* KHR_texture_transform's order: T * R * S, rotation in radians
     * counter-clockwise in uv. */
    float c = cosf(rotation), s = sinf(rotation);
    u->transform[0] = c * scale[0];
    u->transform[1] = -s * scale[0];
    u->transform[2] = s * scale[1];
    u->transform[3] = c * scale[1];
    u->transform[4] = offset[0];
    u->transform[5] = offset[1];
    return 1;
}

/* c.texture.checker { size = 8, a = {1,1,1}, b = {0,0,0} } */
static int texture_checker(lua_State *L)
{
    int size = 8;
    vec3 a = vec3_make(0.9f, 0.9f, 0.9f), b = vec3_make(0.1f, 0.1f, 0.1f);
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"size", "a", "b", NULL};
        lutil_check_fields(L, 1, "checker", fields);
        lutil_opt_integer(L, 1, "checker", "size", &size);
        lutil_opt_color(L, 1, "checker", "a", &a);
        lutil_opt_color(L, 1, "checker", "b", &b);
    }
    struct error err;
    struct texture *t = texture_create_checker(size, a, b, &err);
    if (!t)
        return lutil_error(L, "%s", err.message);
    push_texture(L, t);
    return 1;
}

static int texture_gc(lua_State *L)
{
    struct l_texture *u = luaL_checkudata(L, 1, TEXTURE_MT);
    texture_destroy(u->ref.texture);
    u->ref.texture = NULL;
    lua_host_uncharge(L, u->charged);
    u->charged = 0;
    return 0;
}

static int texture_tostring(lua_State *L)
{
    const struct texture *t = ((struct l_texture *)luaL_checkudata(L, 1, TEXTURE_MT))->ref.texture;
    if (t)
        lua_pushfstring(L, "Texture(%s, %dx%d)", t->name, t->width, t->height);
    else
        lua_pushstring(L, "Texture(released)");
    return 1;
}

static int get_width(lua_State *L)
{
    lua_pushinteger(L, check_texture(L, 1)->texture->width);
    return 1;
}

static int get_height(lua_State *L)
{
    lua_pushinteger(L, check_texture(L, 1)->texture->height);
    return 1;
}

static int get_name(lua_State *L)
{
    lua_pushstring(L, check_texture(L, 1)->texture->name);
    return 1;
}

/* tex:sample(u, v): the linear colour the reference reads there (colour
 * slots are sRGB-decoded), for tests that check a texture against theory. */
static int texture_sample_at(lua_State *L)
{
    struct texture_ref *u = check_texture(L, 1);
    float uv[2] = {lutil_check_number(L, 2, "sample", "u"), lutil_check_number(L, 3, "sample", "v")};
    lutil_push_vec3(L, texture_sample(u, uv, true));
    return 1;
}

void ltexture_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__gc", texture_gc}, {"__tostring", texture_tostring}, {NULL, NULL}};
    static const luaL_Reg methods[] = {{"sample", texture_sample_at}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"width", get_width}, {"height", get_height}, {"name", get_name},
                                       {NULL, NULL}};
    lutil_class(L, TEXTURE_MT, "texture", meta, methods, getters, NULL);
    lua_newtable(L); /* c.texture: callable, with c.texture.checker */
    lua_pushcfunction(L, texture_checker);
    lua_setfield(L, -2, "checker");
    lua_newtable(L);
    lua_pushcfunction(L, texture_new);
    lua_setfield(L, -2, "__call");
    lua_setmetatable(L, -2);
    lua_setfield(L, -2, "texture");
}
