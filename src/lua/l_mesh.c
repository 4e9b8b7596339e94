/* Meshes (c.mesh.*): glTF files and the procedural shapes, each charged
 * against --script-memory while the script holds it (its arrays and its
 * materials' textures), and their read-only fields. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"

/* ---- meshes ---------------------------------------------------------- */

/* The bytes of a mesh's arrays: positions, normals, two texture coordinate
 * sets, indices and morph targets, its parts' too (their own copies). */
/* What a mesh's arrays are charged: ten floats a vertex (position,
 * normal, two texture coordinates, tangent room), an index, six floats a
 * vertex a morph target. */
static size_t mesh_bytes(size_t vertices, size_t indices, size_t targets)
{
    return vertices * 10 * sizeof(float) + indices * sizeof(uint32_t) + targets * vertices * 6 * sizeof(float);
}

static size_t mesh_array_bytes(const struct mesh *m)
{
    size_t bytes = mesh_bytes(m->vertex_count, m->index_count, (size_t)m->target_count);
    for (int p = 0; p < m->part_count; p++)
        bytes += mesh_array_bytes(m->parts[p]);
    return bytes;
}

int lmesh_push(lua_State *L, struct mesh *m, struct error *err)
{
    if (!m)
        return lutil_error(L, "%s", err->message);
    /* its arrays count against --script-memory, and its materials'
     * textures (checked against what was left before each was decoded) */
    size_t bytes = mesh_array_bytes(m) + mesh_texture_bytes(m);
    char what[160];
    snprintf(what, sizeof what, "mesh '%.100s' (%zu vertices)", m->name, m->vertex_count);
    if (!lua_host_charge(L, bytes, what, err)) {
        mesh_destroy(m);
        return lutil_error(L, "%s", err->message);
    }
    struct l_mesh *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->mesh = m;
    u->charged = bytes;
    luaL_setmetatable(L, MESH_MT);
    return 1;
}

/* A procedural mesh whose size follows from its parameters is checked
 * against --script-memory before it is made: a lathe of 4096 x 4096 is
 * refused at once, not after its gigabyte was allocated and filled. */
void lmesh_check_planned(lua_State *L, const char *fn, size_t vertices, size_t indices)
{
    size_t bytes = mesh_bytes(vertices, indices, 0);
    char what[160];
    snprintf(what, sizeof what, "mesh '%s' (%zu vertices)", fn, vertices);
    struct error err;
    if (!lua_host_charge(L, bytes, what, &err))
        lutil_error(L, "%s", err.message);
    lua_host_uncharge(L, bytes); /* charged for real by lmesh_push, once made */
}

static int mesh_load(lua_State *L)
{
    const char *rel = luaL_checkstring(L, 1);
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return lutil_error(L, "%s", err.message);
    unsigned long long left = lua_host_memory_left(L);
    struct mesh *m = mesh_load_gltf(path, left, &err);
    if (!m && left && strstr(err.message, "more than the"))
        return lutil_error(L, "%s (what --script-memory leaves the script; raise it, 0 = no limit)", err.message);
    return lmesh_push(L, m, &err);
}

/* An optional option table at 1 with these fields only. */
static bool options(lua_State *L, const char *fn, const char *const *fields)
{
    if (lua_isnoneornil(L, 1))
        return false;
    luaL_checktype(L, 1, LUA_TTABLE);
    lutil_check_fields(L, 1, fn, fields);
    return true;
}

static int mesh_sphere(lua_State *L)
{
    float radius = 1.0f;
    int segments = 32;
    static const char *const fields[] = {"radius", "segments", NULL};
    if (options(L, "sphere", fields)) {
        lutil_opt_number(L, 1, "sphere", "radius", &radius);
        lutil_opt_integer(L, 1, "sphere", "segments", &segments);
    }
    size_t nv, ni;
    mesh_sphere_counts(segments, &nv, &ni);
    lmesh_check_planned(L, "sphere", nv, ni);
    struct error err;
    return lmesh_push(L, mesh_create_sphere(radius, segments, &err), &err);
}

/* c.mesh.plane { size = s | {x, z}, subdivisions }: in the xz plane, +y up */
static int mesh_plane(lua_State *L)
{
    float size_x = 1.0f, size_z = 1.0f;
    int subdivisions = 1;
    static const char *const fields[] = {"size", "subdivisions", NULL};
    if (options(L, "plane", fields)) {
        lutil_opt_extent(L, 1, "plane", "size", &size_x, &size_z);
        lutil_opt_integer(L, 1, "plane", "subdivisions", &subdivisions);
    }
    size_t nv, ni;
    mesh_grid_counts(subdivisions, subdivisions, &nv, &ni);
    lmesh_check_planned(L, "plane", nv, ni);
    struct error err;
    struct mesh *m = size_x == size_z ? mesh_create_plane(size_x, subdivisions, &err)
                                      : mesh_create_grid_xz(size_x, size_z, subdivisions, subdivisions, &err);
    if (m)
        snprintf(m->name, sizeof m->name, "plane");
    return lmesh_push(L, m, &err);
}

static int mesh_grid(lua_State *L)
{
    float size = 1.0f;
    int resolution = 64;
    static const char *const fields[] = {"size", "resolution", NULL};
    if (options(L, "grid", fields)) {
        lutil_opt_number(L, 1, "grid", "size", &size);
        lutil_opt_integer(L, 1, "grid", "resolution", &resolution);
    }
    size_t nv, ni;
    mesh_grid_counts(resolution, resolution, &nv, &ni);
    lmesh_check_planned(L, "grid", nv, ni);
    struct error err;
    return lmesh_push(L, mesh_create_grid(size, resolution, &err), &err);
}

static int mesh_box(lua_State *L)
{
    vec3 size = {1, 1, 1};
    static const char *const fields[] = {"size", NULL};
    if (options(L, "box", fields))
        lutil_opt_vec3(L, 1, "box", "size", &size);
    struct error err;
    return lmesh_push(L, mesh_create_box(size, &err), &err);
}

static int mesh_torus(lua_State *L)
{
    float radius = 1.0f, tube = 0.25f;
    int segments = 64, sides = 24;
    static const char *const fields[] = {"radius", "tube", "segments", "sides", NULL};
    if (options(L, "torus", fields)) {
        lutil_opt_number(L, 1, "torus", "radius", &radius);
        lutil_opt_number(L, 1, "torus", "tube", &tube);
        lutil_opt_integer(L, 1, "torus", "segments", &segments);
        lutil_opt_integer(L, 1, "torus", "sides", &sides);
    }
    size_t nv, ni;
    mesh_torus_counts(segments, sides, &nv, &ni);
    lmesh_check_planned(L, "torus", nv, ni);
    struct error err;
    return lmesh_push(L, mesh_create_torus(radius, tube, segments, sides, &err), &err);
}

/* c.mesh.cylinder / c.mesh.cone { radius, height, segments }: about +y,
 * centred at the origin like the box and the sphere. */
static int mesh_round(lua_State *L, const char *fn, bool cone)
{
    float radius = 0.5f, height = 1.0f;
    int segments = 64;
    static const char *const fields[] = {"radius", "height", "segments", NULL};
    if (options(L, fn, fields)) {
        lutil_opt_number(L, 1, fn, "radius", &radius);
        lutil_opt_number(L, 1, fn, "height", &height);
        lutil_opt_integer(L, 1, fn, "segments", &segments);
    }
    size_t nv, ni;
    mesh_lathe_counts(cone ? 3 : 4, segments, &nv, &ni);
    lmesh_check_planned(L, fn, nv, ni);
    struct error err;
    return lmesh_push(L, cone ? mesh_create_cone(radius, height, segments, &err)
                             : mesh_create_cylinder(radius, height, segments, &err), &err);
}

static int mesh_cylinder(lua_State *L) { return mesh_round(L, "cylinder", false); }
static int mesh_cone(lua_State *L) { return mesh_round(L, "cone", true); }

/* c.mesh.lathe { profile = {{r, y}, ...}, segments }: the profile turned about +y. */
static int mesh_lathe(lua_State *L)
{
    int segments = 64;
    static const char *const fields[] = {"profile", "segments", NULL};
    luaL_checktype(L, 1, LUA_TTABLE);
    lutil_check_fields(L, 1, "lathe", fields);
    lutil_opt_integer(L, 1, "lathe", "segments", &segments);
    if (lua_getfield(L, 1, "profile") != LUA_TTABLE)
        return lutil_field_error(L, "lathe", "profile", "a list of {radius, height} points", -1);
    lua_Unsigned length = lua_rawlen(L, -1);
    if (length < 2 || length > 4096)
        return lutil_error(L, "bad argument 'profile' to 'lathe' (2..4096 points expected, got %llu)",
                           (unsigned long long)length);
    int count = (int)length;
    size_t nv, ni;
    mesh_lathe_counts(count, segments, &nv, &ni);
    lmesh_check_planned(L, "lathe", nv, ni);
    float *profile = lua_newuserdatauv(L, (size_t)count * 2 * sizeof(float), 0); /* freed by Lua on error */
    for (int i = 0; i < count; i++) {
        lua_rawgeti(L, -2, i + 1);
        for (int k = 0; k < 2; k++) {
            if (lua_type(L, -1) != LUA_TTABLE || lua_rawgeti(L, -1, k + 1) != LUA_TNUMBER)
                return lutil_error(L, "bad argument 'profile' to 'lathe' (point %d: {radius, height} expected)",
                                   i + 1);
            profile[i * 2 + k] = (float)lua_tonumber(L, -1);
            lua_pop(L, 1);
        }
        lua_pop(L, 1);
    }
    struct error err;
    struct mesh *m = mesh_create_lathe("lathe", profile, count, segments, &err);
    lua_pop(L, 2);
    return lmesh_push(L, m, &err);
}

struct mesh *lmesh_check(lua_State *L, int idx)
{
    struct l_mesh *u = luaL_checkudata(L, idx, MESH_MT);
    if (!u->mesh)
        lscene_released(L, idx, "mesh");
    return u->mesh;
}

static int mesh_gc(lua_State *L)
{
    struct l_mesh *u = luaL_checkudata(L, 1, MESH_MT);
    mesh_destroy(u->mesh);
    u->mesh = NULL;
    lua_host_uncharge(L, u->charged);
    u->charged = 0;
    return 0;
}

static int mesh_get_vertex_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)lmesh_check(L, 1)->vertex_count);
    return 1;
}

static int mesh_get_triangle_count(lua_State *L)
{
    lua_pushinteger(L, (lua_Integer)(lmesh_check(L, 1)->index_count / 3));
    return 1;
}

static int mesh_get_morph_targets(lua_State *L)
{
    lua_pushinteger(L, lmesh_check(L, 1)->target_count);
    return 1;
}

/* mesh.skinned: it carries a glTF skin's JOINTS_0 and WEIGHTS_0 (a mesh of
 * c.gltf.load); mesh.joint_count: how many joints they use. */
static int mesh_get_skinned(lua_State *L)
{
    lua_pushboolean(L, lmesh_check(L, 1)->joints != NULL);
    return 1;
}

static int mesh_get_joint_count(lua_State *L)
{
    lua_pushinteger(L, lmesh_check(L, 1)->joint_count);
    return 1;
}

static int mesh_get_bounds(lua_State *L)
{
    struct mesh *m = lmesh_check(L, 1);
    lutil_push_box(L, m->bounds_min, m->bounds_max);
    return 1;
}

static int mesh_get_name(lua_State *L)
{
    lua_pushstring(L, lmesh_check(L, 1)->name);
    return 1;
}

static int mesh_get_materials(lua_State *L)
{
    lmesh_check(L, 1);
    lmaterials_push(L, 1, false);
    return 1;
}

static int mesh_tostring(lua_State *L)
{
    struct mesh *m = lmesh_check(L, 1);
    lua_pushfstring(L, "Mesh(%s, %d triangles)", m->name, (int)(m->index_count / 3));
    return 1;
}

/* ---- deformers ------------------------------------------------------- */


void lmesh_open(lua_State *L)
{
    static const luaL_Reg mesh_meta[] = {{"__gc", mesh_gc}, {"__tostring", mesh_tostring}, {NULL, NULL}};
    static const luaL_Reg mesh_getters[] = {{"vertex_count", mesh_get_vertex_count},
                                            {"triangle_count", mesh_get_triangle_count},
                                            {"morph_targets", mesh_get_morph_targets}, {"bounds", mesh_get_bounds},
                                            {"skinned", mesh_get_skinned}, {"joint_count", mesh_get_joint_count},
                                            {"name", mesh_get_name}, {"materials", mesh_get_materials},
                                            {NULL, NULL}};
    lutil_class(L, MESH_MT, "mesh", mesh_meta, NULL, mesh_getters, NULL);
    static const luaL_Reg meshes[] = {{"load", mesh_load}, {"sphere", mesh_sphere}, {"plane", mesh_plane},
                                      {"box", mesh_box}, {"grid", mesh_grid}, {"torus", mesh_torus},
                                      {"cylinder", mesh_cylinder}, {"cone", mesh_cone}, {"lathe", mesh_lathe},
                                      {NULL, NULL}};
    luaL_newlib(L, meshes);
    lua_setfield(L, -2, "mesh");
}
