#define _POSIX_C_SOURCE 200809L
/* caustica.scene: scenes, cameras, environments and quaternions, and the
 * module that gathers the other scene bindings (l_object.c, l_light.c,
 * l_material.c, l_medium.c). Assigning a field takes effect on the next
 * frame and bumps the owner's version. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"

struct l_camera { struct camera *cam; struct camera own; };
struct l_scene { struct scene scene; };

int lscene_released(lua_State *L, int idx, const char *what)
{
    return luaL_argerror(L, idx, lua_pushfstring(L, "this %s was already released", what));
}

/* ---- cameras --------------------------------------------------------- */

static struct camera *check_camera(lua_State *L)
{
    return ((struct l_camera *)luaL_checkudata(L, 1, CAMERA_MT))->cam;
}

/* near >= far leaves no depth range; checked once all fields are set. */
static void check_clip_range(lua_State *L, const struct camera *c)
{
    if (!(c->znear < c->zfar))
        lutil_error(L, "bad argument 'near' to 'camera' (near %g must be less than far %g)", (double)c->znear,
                    (double)c->zfar);
}

/* A live camera checks near < far on every assignment (a refused one
 * leaves it as it was); c.camera checks once all its fields are set
 * (uservalue 2 is true while it builds). */
static void camera_changed(lua_State *L, struct camera *c, const struct camera *before)
{
    if (!(c->znear < c->zfar) && lua_getiuservalue(L, 1, 2) != LUA_TBOOLEAN) {
        struct camera wanted = *c;
        *c = *before;
        check_clip_range(L, &wanted);
    }
    lua_pop(L, 1);
    c->version++;
}

static int set_vec(lua_State *L, size_t offset, const char *name)
{
    struct camera *c = check_camera(L);
    struct camera before = *c;
    *(vec3 *)((char *)c + offset) = lutil_check_vec3(L, 3, "camera", name);
    camera_changed(L, c, &before);
    return 0;
}

static int set_eye(lua_State *L) { return set_vec(L, offsetof(struct camera, eye), "eye"); }
static int set_target(lua_State *L) { return set_vec(L, offsetof(struct camera, target), "target"); }
static int set_up(lua_State *L) { return set_vec(L, offsetof(struct camera, up), "up"); }

static int set_fov(lua_State *L)
{
    struct camera *c = check_camera(L);
    struct camera before = *c;
    float x = lutil_check_number(L, 3, "camera", "fov");
    if (!(x > 0.5f && x < 179.5f))
        lutil_error(L, "bad argument 'fov' to 'camera' (degrees in (0.5, 179.5) expected, got %g)", (double)x);
    c->fov = x;
    camera_changed(L, c, &before);
    return 0;
}

static int set_distance(lua_State *L, float *field, const char *name)
{
    struct camera *c = check_camera(L);
    struct camera before = *c;
    float x = lutil_check_number(L, 3, "camera", name);
    if (!(x > 0.0f))
        lutil_error(L, "bad argument '%s' to 'camera' (a positive distance expected, got %g)", name, (double)x);
    *field = x;
    camera_changed(L, c, &before);
    return 0;
}

static int set_near(lua_State *L) { return set_distance(L, &check_camera(L)->znear, "near"); }
static int set_far(lua_State *L) { return set_distance(L, &check_camera(L)->zfar, "far"); }

/* ortho = { width = W } makes the camera orthographic, ortho = false
 * perspective again. */
static int set_ortho(lua_State *L)
{
    struct camera *c = check_camera(L);
    struct camera before = *c;
    float width = 0.0f;
    if (lua_istable(L, 3)) {
        static const char *const fields[] = {"width", NULL};
        lutil_check_fields(L, 3, "camera.ortho", fields);
        if (lua_getfield(L, 3, "width") == LUA_TNIL)
            lutil_error(L, "bad argument 'ortho' to 'camera' (a table { width = W } expected, and it has no width)");
        lua_pop(L, 1);
        lutil_opt_number(L, 3, "camera.ortho", "width", &width);
        if (!(width > 0.0f) || !isfinite(width))
            lutil_error(L, "bad argument 'width' to 'camera.ortho' (a positive width expected, got %g)", (double)width);
    } else if (!(lua_isboolean(L, 3) && !lua_toboolean(L, 3))) {
        return luaL_typeerror(L, 3, "table { width = W } or false");
    }
    c->ortho_width = width;
    camera_changed(L, c, &before);
    return 0;
}

static int get_ortho(lua_State *L)
{
    const struct camera *c = check_camera(L);
    if (!(c->ortho_width > 0.0f)) {
        lua_pushboolean(L, 0);
        return 1;
    }
    lua_createtable(L, 0, 1);
    lua_pushnumber(L, c->ortho_width);
    lua_setfield(L, -2, "width");
    return 1;
}

static int get_eye(lua_State *L)
{
    lutil_push_vec3(L, check_camera(L)->eye);
    return 1;
}

static int get_target(lua_State *L)
{
    lutil_push_vec3(L, check_camera(L)->target);
    return 1;
}

static int get_up(lua_State *L)
{
    lutil_push_vec3(L, check_camera(L)->up);
    return 1;
}

static int get_fov(lua_State *L)
{
    lua_pushnumber(L, check_camera(L)->fov);
    return 1;
}

static int get_near(lua_State *L)
{
    lua_pushnumber(L, check_camera(L)->znear);
    return 1;
}

static int get_far(lua_State *L)
{
    lua_pushnumber(L, check_camera(L)->zfar);
    return 1;
}

static const char *const camera_fields[] = {"eye", "target", "up", "fov", "near", "far", "ortho", NULL};

static int camera_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    lutil_check_fields(L, 1, "camera", camera_fields);
    /* uservalue 1: the scene a live view belongs to; 2: true while built */
    struct l_camera *u = lua_newuserdatauv(L, sizeof *u, 2);
    struct scene defaults;
    scene_init(&defaults);
    u->own = defaults.camera;
    u->cam = &u->own;
    luaL_setmetatable(L, CAMERA_MT);
    int idx = lua_gettop(L);
    lua_pushboolean(L, 1);
    lua_setiuservalue(L, idx, 2);
    lutil_assign_fields(L, idx, 1, camera_fields);
    lua_pushnil(L);
    lua_setiuservalue(L, idx, 2);
    check_clip_range(L, u->cam);
    lua_settop(L, idx);
    return 1;
}

/* ---- environments ---------------------------------------------------- */

static int cubemap_new(lua_State *L)
{
    const char *rel = luaL_checkstring(L, 1);
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return lutil_error(L, "%s", err.message);
    struct environment *env = environment_load(path, &err);
    if (!env)
        return lutil_error(L, "%s", err.message);
    struct l_environment *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->env = env;
    luaL_setmetatable(L, ENVIRONMENT_MT);
    return 1;
}

static int environment_gc(lua_State *L)
{
    struct l_environment *u = luaL_checkudata(L, 1, ENVIRONMENT_MT);
    environment_destroy(u->env);
    u->env = NULL;
    return 0;
}

/* ---- scenes ---------------------------------------------------------- */

static struct scene *check_scene(lua_State *L, int idx)
{
    return &((struct l_scene *)luaL_checkudata(L, idx, SCENE_MT))->scene;
}

struct scene *lua_host_to_scene(lua_State *L, int idx)
{
    struct l_scene *u = luaL_testudata(L, idx, SCENE_MT);
    return u ? &u->scene : NULL;
}

/* The scene's members table (uservalue 1) keeps what it holds alive. */
static void keep(lua_State *L, int scene_idx, const char *key, int value)
{
    lua_getiuservalue(L, scene_idx, 1);
    lua_pushstring(L, key);
    lua_pushvalue(L, value);
    lua_rawset(L, -3);
    lua_pop(L, 1);
}

static int set_camera(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    struct l_camera *c = luaL_testudata(L, 3, CAMERA_MT);
    if (!c)
        lutil_field_error(L, "scene", "camera", "camera (c.camera{...})", 3);
    uint64_t version = s->camera.version;
    s->camera = *c->cam;
    s->camera.version = version + 1;
    s->version++;
    return 0;
}

static int set_background(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    s->background = lutil_check_color(L, 3, "scene", "background");
    s->version++;
    return 0;
}

static int set_ambient(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    s->ambient = lutil_check_color(L, 3, "scene", "ambient");
    s->version++;
    return 0;
}

static int set_environment(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    struct l_environment *e = lua_isnil(L, 3) ? NULL : luaL_testudata(L, 3, ENVIRONMENT_MT);
    if (!lua_isnil(L, 3) && (!e || !e->env))
        lutil_field_error(L, "scene", "environment", "environment (c.cubemap \"folder\")", 3);
    scene_set_environment(s, e ? e->env : NULL);
    lua_pushvalue(L, 3);
    lua_setiuservalue(L, 1, 2);
    s->version++;
    return 0;
}

static int set_medium(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    struct l_medium *m = lua_isnil(L, 3) ? NULL : luaL_testudata(L, 3, MEDIUM_MT);
    if (!lua_isnil(L, 3) && (!m || !m->medium))
        lutil_field_error(L, "scene", "medium", "medium (c.medium{...})", 3);
    scene_set_medium(s, m ? m->medium : NULL);
    keep(L, 1, "medium", 3);
    s->version++;
    return 0;
}

static int get_camera(lua_State *L)
{
    /* A live view of the scene's camera. */
    struct scene *s = check_scene(L, 1);
    struct l_camera *c = lua_newuserdatauv(L, sizeof *c, 2);
    c->cam = &s->camera;
    luaL_setmetatable(L, CAMERA_MT);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, -2, 1);
    return 1;
}

static int get_background(lua_State *L)
{
    lutil_push_vec3(L, check_scene(L, 1)->background);
    return 1;
}

static int get_ambient(lua_State *L)
{
    lutil_push_vec3(L, check_scene(L, 1)->ambient);
    return 1;
}

static int get_environment(lua_State *L)
{
    check_scene(L, 1);
    lua_getiuservalue(L, 1, 2);
    return 1;
}

static int get_medium(lua_State *L)
{
    check_scene(L, 1);
    lua_getiuservalue(L, 1, 1);
    lua_getfield(L, -1, "medium");
    return 1;
}

static int get_object_count(lua_State *L)
{
    lua_pushinteger(L, check_scene(L, 1)->object_count);
    return 1;
}

static int get_light_count(lua_State *L)
{
    lua_pushinteger(L, check_scene(L, 1)->light_count);
    return 1;
}

static const char *const scene_fields[] = {"camera", "background", "ambient", "environment", "medium", NULL};

static int scene_new(lua_State *L)
{
    if (lua_isnoneornil(L, 1)) {
        lua_settop(L, 0);
        lua_newtable(L);
    }
    luaL_checktype(L, 1, LUA_TTABLE);
    lutil_check_fields(L, 1, "scene", scene_fields);
    struct l_scene *u = lua_newuserdatauv(L, sizeof *u, 2);
    scene_init(&u->scene);
    luaL_setmetatable(L, SCENE_MT);
    int idx = lua_gettop(L);
    lua_newtable(L); /* members kept alive: objects and lights */
    lua_setiuservalue(L, idx, 1);
    lutil_assign_fields(L, idx, 1, scene_fields);
    lua_settop(L, idx);
    return 1;
}

static int scene_gc(lua_State *L)
{
    scene_release(check_scene(L, 1));
    return 0;
}

static int scene_add(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    struct error err;
    bool ok;
    if (luaL_testudata(L, 2, OBJECT_MT))
        ok = scene_object_add(s, lobject_check(L, 2), &err);
    else if (luaL_testudata(L, 2, LIGHT_MT))
        ok = scene_light_add(s, llight_check(L, 2), &err);
    else
        return luaL_argerror(L, 2, lua_pushfstring(L, "object or light expected, got %s", luaL_typename(L, 2)));
    if (!ok)
        return lutil_error(L, "%s", err.message);
    lua_getiuservalue(L, 1, 1);
    lua_pushvalue(L, 2);
    lua_pushboolean(L, 1);
    lua_rawset(L, -3);
    lua_pop(L, 1);
    lua_pushvalue(L, 2);
    return 1;
}

static int scene_remove(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    if (luaL_testudata(L, 2, OBJECT_MT))
        scene_object_remove(s, lobject_check(L, 2));
    else if (luaL_testudata(L, 2, LIGHT_MT))
        scene_light_remove(s, llight_check(L, 2));
    else
        return luaL_argerror(L, 2, lua_pushfstring(L, "object or light expected, got %s", luaL_typename(L, 2)));
    lua_getiuservalue(L, 1, 1);
    lua_pushvalue(L, 2);
    lua_pushnil(L);
    lua_rawset(L, -3);
    return 0;
}

static int scene_tostring(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    lua_pushfstring(L, "Scene(%d objects, %d lights)", s->object_count, s->light_count);
    return 1;
}

/* ---- quaternions (plain tables) ------------------------------------- */

static int quat_axis_angle_l(lua_State *L)
{
    vec3 axis = lutil_check_vec3(L, 1, "axis_angle", "axis");
    float angle = lutil_check_number(L, 2, "axis_angle", "angle");
    lutil_push_quat(L, quat_axis_angle(axis, angle));
    return 1;
}

static int quat_mul_l(lua_State *L)
{
    quat a = lutil_check_quat(L, 1, "mul", "a"), b = lutil_check_quat(L, 2, "mul", "b");
    lutil_push_quat(L, quat_mul(a, b));
    return 1;
}

int luaopen_caustica_scene(lua_State *L)
{
    static const luaL_Reg camera_getters[] = {{"eye", get_eye}, {"target", get_target}, {"up", get_up},
                                              {"fov", get_fov}, {"near", get_near}, {"far", get_far},
                                              {"ortho", get_ortho}, {NULL, NULL}};
    static const luaL_Reg camera_setters[] = {{"eye", set_eye}, {"target", set_target}, {"up", set_up},
                                              {"fov", set_fov}, {"near", set_near}, {"far", set_far},
                                              {"ortho", set_ortho}, {NULL, NULL}};
    lutil_class(L, CAMERA_MT, "camera", NULL, NULL, camera_getters, camera_setters);
    static const luaL_Reg environment_meta[] = {{"__gc", environment_gc}, {NULL, NULL}};
    lutil_class(L, ENVIRONMENT_MT, "environment", environment_meta, NULL, NULL, NULL);
    static const luaL_Reg scene_meta[] = {{"__gc", scene_gc}, {"__tostring", scene_tostring}, {NULL, NULL}};
    static const luaL_Reg scene_methods[] = {{"add", scene_add}, {"remove", scene_remove}, {NULL, NULL}};
    static const luaL_Reg scene_getters[] = {{"camera", get_camera}, {"background", get_background},
                                             {"ambient", get_ambient}, {"environment", get_environment},
                                             {"medium", get_medium}, {"object_count", get_object_count},
                                             {"light_count", get_light_count}, {NULL, NULL}};
    static const luaL_Reg scene_setters[] = {{"camera", set_camera}, {"background", set_background},
                                             {"ambient", set_ambient}, {"environment", set_environment},
                                             {"medium", set_medium}, {NULL, NULL}};
    lutil_class(L, SCENE_MT, "scene", scene_meta, scene_methods, scene_getters, scene_setters);

    /* c.environment "sky.hdr" (one equirectangular .hdr or .pfm) and
     * c.cubemap "folder" (six faces) make the same thing: either takes either. */
    static const luaL_Reg top[] = {{"scene", scene_new}, {"camera", camera_new}, {"cubemap", cubemap_new},
                                   {"environment", cubemap_new}, {NULL, NULL}};
    luaL_newlib(L, top);
    lmesh_open(L);
    lobject_open(L);
    llight_open(L);
    lmaterial_open(L);
    lmaterials_open(L);
    lmedium_open(L);
    ltexture_open(L);
    lgltf_open(L);
    static const luaL_Reg quats[] = {{"axis_angle", quat_axis_angle_l}, {"mul", quat_mul_l}, {NULL, NULL}};
    luaL_newlib(L, quats);
    lua_setfield(L, -2, "quat");
    return 1;
}
