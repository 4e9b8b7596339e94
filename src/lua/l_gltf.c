/* caustica.scene's `gltf.open`: a glTF file read as a scene (issue 51) —
 * its node tree, meshes, cameras, KHR_lights_punctual lights and
 * animations, as plain values a script (or lua/caustica/gltf.lua's
 * `c.gltf.load`, which makes objects, cameras and lights of them) reads:
 *
 *   local f = c.gltf.open("car.glb", { scene = "Main" })   -- or an index from 0
 *   f.name, f.nodes, f.cameras, f.lights, f.animations      -- tables, 1-based
 *   f:mesh(i)                                               -- glTF mesh i (from 1), in its own frame
 *   f:pose(animation, t)                                    -- per node: its world transform at t s
 *
 * The file is parsed once; meshes are made on first use and shared. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/gltf.h"
#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"
#include "scene/gltf_pose.h"

#define GLTF_FILE_MT "caustica.GltfFile"

struct l_gltf_file {
    struct gltf_file *file;
    struct gltf_scene scene;
    struct gltf_pose pose;
    size_t charged; /* the keyframes and nodes, against --script-memory */
    char path[4096];
};

static struct l_gltf_file *check_file(lua_State *L)
{
    struct l_gltf_file *u = luaL_checkudata(L, 1, GLTF_FILE_MT);
    if (!u->file)
        lscene_released(L, 1, "glTF file");
    return u;
}

static int file_gc(lua_State *L)
{
    struct l_gltf_file *u = luaL_checkudata(L, 1, GLTF_FILE_MT);
    if (u->file) {
        gltf_pose_free(&u->pose);
        gltf_scene_free(&u->scene);
        gltf_file_close(u->file);
        u->file = NULL;
        lua_host_uncharge(L, u->charged);
        u->charged = 0;
    }
    return 0;
}

static size_t scene_bytes(const struct gltf_scene *s)
{
    size_t bytes = (size_t)s->node_count * (sizeof(struct gltf_node) + 2 * sizeof(mat4));
    for (int a = 0; a < s->animation_count; a++)
        for (int k = 0; k < s->animations[a].channel_count; k++) {
            const struct gltf_channel *c = &s->animations[a].channels[k];
            size_t per_key = (size_t)c->components * (c->interpolation == GLTF_CUBICSPLINE ? 3u : 1u);
            bytes += c->key_count * (1 + per_key) * sizeof(float);
        }
    return bytes;
}

/* gltf.open(path [, { scene = name | index }]) */
static int file_open(lua_State *L)
{
    const char *rel = luaL_checkstring(L, 1);
    const char *scene_name = NULL;
    lua_Integer scene_index = -1;
    if (!lua_isnoneornil(L, 2)) {
        luaL_checktype(L, 2, LUA_TTABLE);
        static const char *const fields[] = {"scene", NULL};
        lutil_check_fields(L, 2, "gltf.open", fields);
        lua_getfield(L, 2, "scene");
        if (lua_type(L, -1) == LUA_TSTRING)
            scene_name = lua_tostring(L, -1);
        else if (lua_isinteger(L, -1))
            scene_index = lua_tointeger(L, -1);
        else if (!lua_isnil(L, -1))
            lutil_field_error(L, "gltf.open", "scene", "a scene's name or index (from 0)", -1);
        if (scene_name == NULL && !lua_isnil(L, -1) && (scene_index < 0 || scene_index > INT32_MAX))
            lutil_error(L, "bad argument 'scene' to 'gltf.open' (an index from 0 expected, got %lld)",
                        (long long)scene_index);
    }
    struct l_gltf_file *u = lua_newuserdatauv(L, sizeof *u, 1);
    memset(u, 0, sizeof *u);
    luaL_setmetatable(L, GLTF_FILE_MT);
    lua_host_resolve_path(L, rel, u->path, sizeof u->path);
    struct error err;
    if (!lua_host_check_read(L, u->path, &err))
        return lutil_error(L, "%s", err.message);
    struct gltf_file *file;
    if (!gltf_file_open(u->path, &file, &err))
        return lutil_error(L, "%s", err.message);
    if (!gltf_file_scene(file, scene_name, (int)scene_index, &u->scene, &err)) {
        gltf_file_close(file);
        return lutil_error(L, "%s", err.message);
    }
    if (!gltf_pose_init(&u->pose, &u->scene, &err)) {
        gltf_scene_free(&u->scene);
        gltf_file_close(file);
        return lutil_error(L, "%s: %s", u->path, err.message);
    }
    u->file = file;
    size_t bytes = scene_bytes(&u->scene);
    char what[4200];
    snprintf(what, sizeof what, "the nodes and animations of %s", u->path);
    if (!lua_host_charge(L, bytes, what, &err)) {
        gltf_pose_free(&u->pose);
        gltf_scene_free(&u->scene);
        gltf_file_close(u->file);
        u->file = NULL;
        return lutil_error(L, "%s", err.message);
    }
    u->charged = bytes;
    lua_newtable(L); /* uservalue 1: the meshes made, by glTF index */
    lua_setiuservalue(L, -2, 1);
    return 1;
}

static void set_number(lua_State *L, const char *field, double v)
{
    lua_pushnumber(L, v);
    lua_setfield(L, -2, field);
}

static void set_index(lua_State *L, const char *field, int zero_based)
{
    if (zero_based >= 0) {
        lua_pushinteger(L, zero_based + 1);
        lua_setfield(L, -2, field);
    }
}

static void push_floats(lua_State *L, const float *v, int n)
{
    lua_createtable(L, n, 0);
    for (int i = 0; i < n; i++) {
        lua_pushnumber(L, v[i]);
        lua_rawseti(L, -2, i + 1);
    }
}

static int get_name(lua_State *L)
{
    lua_pushstring(L, check_file(L)->scene.name);
    return 1;
}

static int get_generator(lua_State *L)
{
    lua_pushstring(L, check_file(L)->scene.generator);
    return 1;
}

static int get_path(lua_State *L)
{
    lua_pushstring(L, check_file(L)->path);
    return 1;
}

/* f.nodes: { name, parent, mesh, camera, light (1-based indices, nil when
 * none), in_scene, weights } for every node of the file. */
static int get_nodes(lua_State *L)
{
    const struct gltf_scene *s = &check_file(L)->scene;
    lua_createtable(L, s->node_count, 0);
    for (int i = 0; i < s->node_count; i++) {
        const struct gltf_node *n = &s->nodes[i];
        lua_createtable(L, 0, 8);
        lua_pushstring(L, n->name);
        lua_setfield(L, -2, "name");
        set_index(L, "parent", n->parent);
        set_index(L, "mesh", n->mesh);
        set_index(L, "camera", n->camera);
        set_index(L, "light", n->light);
        set_index(L, "skin", n->skin);
        lua_pushboolean(L, n->in_scene);
        lua_setfield(L, -2, "in_scene");
        push_floats(L, n->weights, n->weight_count);
        lua_setfield(L, -2, "weights");
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int get_cameras(lua_State *L)
{
    const struct gltf_scene *s = &check_file(L)->scene;
    lua_createtable(L, s->camera_count, 0);
    for (int i = 0; i < s->camera_count; i++) {
        const struct gltf_camera *c = &s->cameras[i];
        lua_createtable(L, 0, 8);
        lua_pushstring(L, c->name);
        lua_setfield(L, -2, "name");
        lua_pushstring(L, c->orthographic ? "orthographic" : "perspective");
        lua_setfield(L, -2, "type");
        if (c->orthographic) {
            set_number(L, "xmag", c->xmag);
            set_number(L, "ymag", c->ymag);
        } else {
            set_number(L, "yfov", c->yfov);
            if (c->aspect > 0)
                set_number(L, "aspect", c->aspect);
        }
        set_number(L, "znear", c->znear);
        if (c->zfar > 0)
            set_number(L, "zfar", c->zfar);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int get_lights(lua_State *L)
{
    const struct gltf_scene *s = &check_file(L)->scene;
    static const char *const kinds[] = {"directional", "point", "spot"};
    lua_createtable(L, s->light_count, 0);
    for (int i = 0; i < s->light_count; i++) {
        const struct gltf_light *l = &s->lights[i];
        lua_createtable(L, 0, 8);
        lua_pushstring(L, l->name);
        lua_setfield(L, -2, "name");
        lua_pushstring(L, kinds[l->kind]);
        lua_setfield(L, -2, "type");
        push_floats(L, l->color, 3);
        lua_setfield(L, -2, "color");
        set_number(L, "intensity", l->intensity);
        if (l->range > 0)
            set_number(L, "range", l->range);
        if (l->kind == GLTF_LIGHT_SPOT) {
            set_number(L, "inner_cone", l->inner_cone);
            set_number(L, "outer_cone", l->outer_cone);
        }
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int get_animations(lua_State *L)
{
    const struct gltf_scene *s = &check_file(L)->scene;
    lua_createtable(L, s->animation_count, 0);
    for (int i = 0; i < s->animation_count; i++) {
        const struct gltf_animation *a = &s->animations[i];
        lua_createtable(L, 0, 4);
        lua_pushstring(L, a->name);
        lua_setfield(L, -2, "name");
        set_number(L, "start", a->start);
        set_number(L, "stop", a->end);
        lua_pushinteger(L, a->channel_count);
        lua_setfield(L, -2, "channels");
        lua_createtable(L, a->channel_count, 0); /* the nodes it drives, 1-based, one per channel */
        for (int k = 0; k < a->channel_count; k++) {
            lua_pushinteger(L, a->channels[k].node + 1);
            lua_rawseti(L, -2, k + 1);
        }
        lua_setfield(L, -2, "nodes");
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

/* f:mesh(i): glTF mesh i (from 1), made once and shared. */
static int file_mesh(lua_State *L)
{
    struct l_gltf_file *u = check_file(L);
    lua_Integer i = luaL_checkinteger(L, 2);
    int count = gltf_file_mesh_count(u->file);
    if (i < 1 || i > count)
        return luaL_argerror(L, 2, lua_pushfstring(L, "a mesh index in 1..%d expected, got %d", count, (int)i));
    lua_getiuservalue(L, 1, 1);
    if (lua_rawgeti(L, -1, i) != LUA_TNIL)
        return 1;
    lua_pop(L, 1);
    char name[4200];
    snprintf(name, sizeof name, "%s [mesh %d]", u->path, (int)i - 1);
    struct error err;
    struct mesh *m = mesh_load_gltf_mesh(u->file, name, (int)i - 1, lua_host_memory_left(L), &err);
    lmesh_push(L, m, &err);
    lua_pushvalue(L, -1);
    lua_rawseti(L, -3, i);
    return 1;
}

/* The animation argument at idx: nil (the rest pose), an index from 1 or a
 * name; -1 for none. */
static int check_animation(lua_State *L, int idx, const struct gltf_scene *s)
{
    if (lua_isnoneornil(L, idx))
        return -1;
    if (lua_type(L, idx) == LUA_TSTRING) {
        const char *name = lua_tostring(L, idx);
        for (int a = 0; a < s->animation_count; a++)
            if (strcmp(s->animations[a].name, name) == 0)
                return a;
        return luaL_argerror(L, idx, lua_pushfstring(L, "no animation named '%s' (the file has %d)", name,
                                                     s->animation_count));
    }
    lua_Integer a = luaL_checkinteger(L, idx);
    if (a < 1 || a > s->animation_count)
        return luaL_argerror(L, idx, lua_pushfstring(L, "an animation index in 1..%d expected, got %d",
                                                     s->animation_count, (int)a));
    return (int)a - 1;
}

/* f:pose(animation, t): per node (1-based) { position, rotation, scale,
 * weights } of its world transform at t seconds (nil animation: the rest
 * pose); t outside the animation holds its first or last key. Second
 * result: per skin its joint matrices, a flat list of 16 numbers a joint
 * (what object.joint_matrices takes). */
static int file_pose(lua_State *L)
{
    struct l_gltf_file *u = check_file(L);
    int a = check_animation(L, 2, &u->scene);
    double t = lua_isnoneornil(L, 3) ? 0.0 : luaL_checknumber(L, 3);
    if (!isfinite(t))
        return luaL_argerror(L, 3, "a finite time in seconds expected");
    gltf_pose_at(&u->pose, &u->scene, a, t);
    lua_createtable(L, u->scene.node_count, 0);
    for (int i = 0; i < u->scene.node_count; i++) {
        vec3 p, s;
        quat q;
        gltf_pose_decompose(u->pose.world[i], &p, &q, &s);
        lua_createtable(L, 0, 5);
        lutil_push_vec3(L, p);
        lua_setfield(L, -2, "position");
        lutil_push_quat(L, q);
        lua_setfield(L, -2, "rotation");
        lutil_push_vec3(L, s);
        lua_setfield(L, -2, "scale");
        push_floats(L, u->pose.weights[i], u->scene.nodes[i].weight_count);
        lua_setfield(L, -2, "weights");
        lua_rawseti(L, -2, i + 1);
    }
    lua_createtable(L, u->scene.skin_count, 0);
    for (int k = 0; k < u->scene.skin_count; k++) {
        int n = u->scene.skins[k].joint_count;
        float m[GLTF_MAX_JOINTS * 16];
        gltf_pose_joint_matrices(&u->pose, &u->scene, k, m);
        push_floats(L, m, n * 16);
        lua_rawseti(L, -2, k + 1);
    }
    return 2;
}

void lgltf_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__gc", file_gc}, {NULL, NULL}};
    static const luaL_Reg methods[] = {{"mesh", file_mesh}, {"pose", file_pose}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"name", get_name},       {"path", get_path}, {"generator", get_generator},     {"nodes", get_nodes},
                                       {"cameras", get_cameras}, {"lights", get_lights}, {"animations", get_animations},
                                       {NULL, NULL}};
    lutil_class(L, GLTF_FILE_MT, "glTF file", meta, methods, getters, NULL);
    static const luaL_Reg fns[] = {{"open", file_open}, {NULL, NULL}};
    luaL_newlib(L, fns);
    lua_setfield(L, -2, "gltf");
}
