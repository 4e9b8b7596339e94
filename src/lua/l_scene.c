#define _POSIX_C_SOURCE 200809L
/* caustica.scene: scenes, objects, meshes, materials, lights, cameras,
 * environments and deformers as userdata with live fields. Assigning a
 * field takes effect on the next frame and bumps the owner's version. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "lua/l_util.h"
#include "lua/lua_host.h"
#include "scene/scene.h"
#include "scene/water.h"

#define MESH_MT "caustica.Mesh"
#define MATERIAL_MT "caustica.Material"
#define OBJECT_MT "caustica.Object"
#define LIGHT_MT "caustica.Light"
#define CAMERA_MT "caustica.Camera"
#define ENVIRONMENT_MT "caustica.Environment"
#define DEFORMER_MT "caustica.Deformer"
#define SCENE_MT "caustica.Scene"
#define MEDIUM_MT "caustica.Medium"

struct l_mesh { struct mesh *mesh; };
struct l_object { struct object *obj; };
struct l_light { struct light *light; };
struct l_camera { struct camera *cam; struct camera own; };
struct l_environment { struct environment *env; };
struct l_scene { struct scene scene; };

/* ---- meshes ---------------------------------------------------------- */

static int push_mesh(lua_State *L, struct mesh *m, struct error *err)
{
    if (!m)
        return luaL_error(L, "%s", err->message);
    struct l_mesh *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->mesh = m;
    luaL_setmetatable(L, MESH_MT);
    return 1;
}

static int mesh_load(lua_State *L)
{
    const char *rel = luaL_checkstring(L, 1);
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "%s", err.message);
    return push_mesh(L, mesh_load_gltf(path, &err), &err);
}

static int mesh_sphere(lua_State *L)
{
    float radius = 1.0f;
    int segments = 32;
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"radius", "segments", NULL};
        lutil_check_fields(L, 1, "sphere", fields);
        lutil_opt_number(L, 1, "sphere", "radius", &radius);
        lutil_opt_integer(L, 1, "sphere", "segments", &segments);
    }
    struct error err;
    return push_mesh(L, mesh_create_sphere(radius, segments, &err), &err);
}

static int mesh_plane(lua_State *L)
{
    float size = 1.0f;
    int subdivisions = 1;
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"size", "subdivisions", NULL};
        lutil_check_fields(L, 1, "plane", fields);
        lutil_opt_number(L, 1, "plane", "size", &size);
        lutil_opt_integer(L, 1, "plane", "subdivisions", &subdivisions);
    }
    struct error err;
    return push_mesh(L, mesh_create_plane(size, subdivisions, &err), &err);
}

static int mesh_grid(lua_State *L)
{
    float size = 1.0f;
    int resolution = 64;
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"size", "resolution", NULL};
        lutil_check_fields(L, 1, "grid", fields);
        lutil_opt_number(L, 1, "grid", "size", &size);
        lutil_opt_integer(L, 1, "grid", "resolution", &resolution);
    }
    struct error err;
    return push_mesh(L, mesh_create_grid(size, resolution, &err), &err);
}

static int mesh_box(lua_State *L)
{
    vec3 size = {1, 1, 1};
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"size", NULL};
        lutil_check_fields(L, 1, "box", fields);
        lutil_opt_vec3(L, 1, "box", "size", &size);
    }
    struct error err;
    return push_mesh(L, mesh_create_box(size, &err), &err);
}

static int mesh_torus(lua_State *L)
{
    float radius = 1.0f, tube = 0.25f;
    int segments = 64, sides = 24;
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const fields[] = {"radius", "tube", "segments", "sides", NULL};
        lutil_check_fields(L, 1, "torus", fields);
        lutil_opt_number(L, 1, "torus", "radius", &radius);
        lutil_opt_number(L, 1, "torus", "tube", &tube);
        lutil_opt_integer(L, 1, "torus", "segments", &segments);
        lutil_opt_integer(L, 1, "torus", "sides", &sides);
    }
    struct error err;
    return push_mesh(L, mesh_create_torus(radius, tube, segments, sides, &err), &err);
}

/* A userdata whose __gc already ran (the script cannot reach __gc through
 * the protected metatables; a trusted one can through debug): an error,
 * never a NULL dereference. */
static int released(lua_State *L, int idx, const char *what)
{
    return luaL_argerror(L, idx, lua_pushfstring(L, "this %s was already released", what));
}

static struct mesh *check_mesh(lua_State *L, int idx)
{
    struct l_mesh *u = luaL_checkudata(L, idx, MESH_MT);
    if (!u->mesh)
        released(L, idx, "mesh");
    return u->mesh;
}

static int mesh_gc(lua_State *L)
{
    struct l_mesh *u = luaL_checkudata(L, 1, MESH_MT);
    mesh_destroy(u->mesh);
    u->mesh = NULL;
    return 0;
}

static int mesh_index(lua_State *L)
{
    struct l_mesh *u = luaL_checkudata(L, 1, MESH_MT);
    check_mesh(L, 1);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "vertex_count") == 0)
        lua_pushinteger(L, (lua_Integer)u->mesh->vertex_count);
    else if (strcmp(k, "triangle_count") == 0)
        lua_pushinteger(L, (lua_Integer)(u->mesh->index_count / 3));
    else if (strcmp(k, "morph_targets") == 0)
        lua_pushinteger(L, u->mesh->target_count);
    else if (strcmp(k, "bounds") == 0) {
        lua_createtable(L, 2, 0);
        lutil_push_vec3(L, u->mesh->bounds_min);
        lua_rawseti(L, -2, 1);
        lutil_push_vec3(L, u->mesh->bounds_max);
        lua_rawseti(L, -2, 2);
    } else if (strcmp(k, "name") == 0)
        lua_pushstring(L, u->mesh->name);
    else
        lua_pushnil(L);
    return 1;
}

static int mesh_tostring(lua_State *L)
{
    struct l_mesh *u = luaL_checkudata(L, 1, MESH_MT);
    check_mesh(L, 1);
    lua_pushfstring(L, "Mesh(%s, %d triangles)", u->mesh->name, (int)(u->mesh->index_count / 3));
    return 1;
}

/* ---- materials ------------------------------------------------------- */

static int push_material(lua_State *L, enum material_kind kind, const char *fn)
{
    struct material m = {.kind = kind, .color = {0.8f, 0.8f, 0.8f}, .ior = kind == MATERIAL_WATER ? 1.33f : 1.5f};
    if (kind == MATERIAL_MIRROR)
        m.color = vec3_make(1, 1, 1);
    if (!lua_isnoneornil(L, 1)) {
        luaL_checktype(L, 1, LUA_TTABLE);
        static const char *const diffuse_fields[] = {"color", NULL};
        static const char *const glass_fields[] = {"ior", "absorption", NULL};
        lutil_check_fields(L, 1, fn, kind == MATERIAL_DIFFUSE || kind == MATERIAL_MIRROR ? diffuse_fields : glass_fields);
        lutil_opt_color(L, 1, fn, "color", &m.color);
        lutil_opt_number(L, 1, fn, "ior", &m.ior);
        lutil_opt_color(L, 1, fn, "absorption", &m.absorption);
    }
    if (!(m.ior > 0.0f) || !isfinite(m.ior))
        return lutil_error(L, "bad argument 'ior' to '%s' (a positive number expected, got %g)", fn, (double)m.ior);
    if (m.absorption.x < 0 || m.absorption.y < 0 || m.absorption.z < 0)
        return luaL_error(L, "bad argument 'absorption' to '%s' (non-negative coefficients expected)", fn);
    struct material *u = lua_newuserdatauv(L, sizeof *u, 0);
    *u = m;
    luaL_setmetatable(L, MATERIAL_MT);
    return 1;
}

static int material_diffuse(lua_State *L) { return push_material(L, MATERIAL_DIFFUSE, "diffuse"); }
static int material_glass(lua_State *L) { return push_material(L, MATERIAL_GLASS, "glass"); }
static int material_mirror(lua_State *L) { return push_material(L, MATERIAL_MIRROR, "mirror"); }
static int material_water(lua_State *L) { return push_material(L, MATERIAL_WATER, "water"); }

static int material_index(lua_State *L)
{
    struct material *m = luaL_checkudata(L, 1, MATERIAL_MT);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "kind") == 0)
        lua_pushstring(L, material_kind_name(m->kind));
    else if (strcmp(k, "color") == 0)
        lutil_push_vec3(L, m->color);
    else if (strcmp(k, "ior") == 0)
        lua_pushnumber(L, m->ior);
    else if (strcmp(k, "absorption") == 0)
        lutil_push_vec3(L, m->absorption);
    else
        lua_pushnil(L);
    return 1;
}

static int material_tostring(lua_State *L)
{
    struct material *m = luaL_checkudata(L, 1, MATERIAL_MT);
    lua_pushfstring(L, "Material(%s)", material_kind_name(m->kind));
    return 1;
}

/* ---- deformers ------------------------------------------------------- */

static int deform_gc(lua_State *L)
{
    struct deformer *d = luaL_checkudata(L, 1, DEFORMER_MT);
    free(d->glsl);
    d->glsl = NULL;
    return 0;
}

static struct deformer *new_deformer(lua_State *L)
{
    struct deformer *d = lua_newuserdatauv(L, sizeof *d, 0);
    memset(d, 0, sizeof *d);
    luaL_setmetatable(L, DEFORMER_MT);
    lutil_where(L, d->origin, sizeof d->origin);
    return d;
}

static int deform_wave(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"amplitude", "frequency", "speed", "direction", NULL};
    lutil_check_fields(L, 1, "wave", fields);
    float amplitude = 0.05f, frequency = 4.0f, speed = 2.0f;
    vec3 dir = {1, 0, 0};
    lutil_opt_number(L, 1, "wave", "amplitude", &amplitude);
    lutil_opt_number(L, 1, "wave", "frequency", &frequency);
    lutil_opt_number(L, 1, "wave", "speed", &speed);
    lutil_opt_vec3(L, 1, "wave", "direction", &dir);
    struct deformer *d = new_deformer(L);
    d->kind = DEFORM_WAVE;
    d->amplitude = amplitude;
    d->frequency = frequency;
    d->speed = speed;
    d->direction = dir;
    return 1;
}

static int deform_glsl(lua_State *L)
{
    const char *src = luaL_checkstring(L, 1);
    if (!strstr(src, "deform"))
        return luaL_error(L, "bad argument #1 to 'glsl' (GLSL defining 'vec3 deform(vec3 p, float t)' expected)");
    struct deformer *d = new_deformer(L);
    d->kind = DEFORM_GLSL;
    d->glsl = strdup(src);
    strncat(d->origin, " (deformer)", sizeof d->origin - strlen(d->origin) - 1);
    return 1;
}

/* ---- objects --------------------------------------------------------- */

static struct object *check_object(lua_State *L, int idx)
{
    struct object *o = ((struct l_object *)luaL_checkudata(L, idx, OBJECT_MT))->obj;
    if (!o)
        released(L, idx, "object");
    return o;
}

static void set_morph_weights(lua_State *L, struct object *o, int idx)
{
    if (!lua_istable(L, idx))
        lutil_field_error(L, "object", "morph_weights", "table of numbers", idx);
    int n = (int)lua_rawlen(L, idx);
    if (n > o->mesh->target_count)
        luaL_error(L, "bad argument 'morph_weights' to 'object' (the mesh has %d morph target%s, got %d weights)",
                   o->mesh->target_count, o->mesh->target_count == 1 ? "" : "s", n);
    for (int i = 0; i < n; i++) {
        lua_rawgeti(L, idx, i + 1);
        if (!lua_isnumber(L, -1))
            lutil_field_error(L, "object", "morph_weights", "table of numbers", -1);
        float w = (float)lua_tonumber(L, -1);
        if (!isfinite(w))
            luaL_error(L, "bad argument 'morph_weights' to 'object' (weight %d is not finite)", i + 1);
        if (o->morph_weights[i] != w)
            o->version++;
        o->morph_weights[i] = w;
        lua_pop(L, 1);
    }
}

static void set_deformer(lua_State *L, struct object *o, int idx)
{
    free(o->deform.glsl);
    o->deform.glsl = NULL;
    if (lua_isnil(L, idx) || (lua_isboolean(L, idx) && !lua_toboolean(L, idx))) {
        o->deform.kind = DEFORM_NONE;
    } else {
        struct deformer *d = luaL_testudata(L, idx, DEFORMER_MT);
        if (!d)
            lutil_field_error(L, "object", "deform", "deformer (c.deform.wave{...} or c.deform.glsl(...))", idx);
        o->deform = *d;
        o->deform.glsl = d->glsl ? strdup(d->glsl) : NULL;
    }
    o->version++;
}

/* Sets field `k` of object `o` from the value at `v`. */
static void object_set(lua_State *L, struct object *o, const char *k, int v)
{
    if (strcmp(k, "position") == 0) {
        vec3 p = lutil_check_vec3(L, v, "object", k);
        if (memcmp(&p, &o->position, sizeof p) != 0)
            o->version++;
        o->position = p;
    } else if (strcmp(k, "rotation") == 0) {
        quat q = lutil_check_quat(L, v, "object", k);
        if (memcmp(&q, &o->rotation, sizeof q) != 0)
            o->version++;
        o->rotation = q;
    } else if (strcmp(k, "scale") == 0) {
        vec3 s = lutil_check_vec3(L, v, "object", k);
        if (memcmp(&s, &o->scale, sizeof s) != 0)
            o->version++;
        o->scale = s;
    } else if (strcmp(k, "visible") == 0 || strcmp(k, "cast_shadows") == 0) {
        if (!lua_isboolean(L, v))
            lutil_field_error(L, "object", k, "boolean", v);
        bool *field = k[0] == 'v' ? &o->visible : &o->cast_shadows;
        if (*field != (bool)lua_toboolean(L, v))
            o->version++;
        *field = lua_toboolean(L, v);
    } else if (strcmp(k, "material") == 0) {
        struct material *m = luaL_testudata(L, v, MATERIAL_MT);
        if (!m)
            lutil_field_error(L, "object", k, "material (c.material.*)", v);
        o->material = *m;
        o->version++;
    } else if (strcmp(k, "morph_weights") == 0) {
        set_morph_weights(L, o, v);
    } else if (strcmp(k, "deform") == 0) {
        set_deformer(L, o, v);
    } else {
        luaL_error(L, "object has no field '%s' (fields: position, rotation, scale, visible, cast_shadows, material, "
                      "morph_weights, deform)", k);
    }
}

static int object_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"mesh", "material", "position", "rotation", "scale", "visible",
                                         "cast_shadows", "morph_weights", "deform", NULL};
    lutil_check_fields(L, 1, "object", fields);
    lua_getfield(L, 1, "mesh");
    struct l_mesh *mu = luaL_testudata(L, -1, MESH_MT);
    if (!mu || !mu->mesh)
        return lutil_field_error(L, "object", "mesh", "mesh (c.mesh.*)", -1);
    int mesh_idx = lua_gettop(L);
    struct l_object *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->obj = NULL;
    luaL_setmetatable(L, OBJECT_MT);
    int obj_idx = lua_gettop(L);
    u->obj = object_create(mu->mesh);
    if (!u->obj)
        return luaL_error(L, "out of memory");
    lua_pushvalue(L, mesh_idx);
    lua_setiuservalue(L, obj_idx, 1); /* the object keeps its mesh alive */
    static const char *const order[] = {"material", "position", "rotation", "scale", "visible", "cast_shadows",
                                        "morph_weights", "deform", NULL};
    for (int i = 0; order[i]; i++) {
        if (lua_getfield(L, 1, order[i]) != LUA_TNIL)
            object_set(L, u->obj, order[i], lua_gettop(L));
        lua_pop(L, 1);
    }
    lua_settop(L, obj_idx);
    return 1;
}

/* c.water { size, resolution, depth, attenuation = {r,g,b}, ior, damping,
 * wave_speed, boundary = "reflective" | "fixed", position }: a water
 * surface object (material water) driven by a height-field simulation. */
static int water_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"size", "resolution", "depth", "attenuation", "ior", "damping",
                                         "wave_speed", "boundary", "position", "visible", "cast_shadows", NULL};
    lutil_check_fields(L, 1, "water", fields);
    float size = 2.0f, depth = 1.0f, ior = 1.33f, damping = 0.0f, speed = 1.0f;
    int resolution = 64;
    vec3 attenuation = {0.0f, 0.0f, 0.0f};
    lutil_opt_number(L, 1, "water", "size", &size);
    lutil_opt_integer(L, 1, "water", "resolution", &resolution);
    lutil_opt_number(L, 1, "water", "depth", &depth);
    lutil_opt_number(L, 1, "water", "ior", &ior);
    lutil_opt_number(L, 1, "water", "damping", &damping);
    lutil_opt_number(L, 1, "water", "wave_speed", &speed);
    lutil_opt_color(L, 1, "water", "attenuation", &attenuation);
    bool fixed = false;
    if (lua_getfield(L, 1, "boundary") != LUA_TNIL) {
        const char *b = lua_tostring(L, -1);
        if (!b || (strcmp(b, "fixed") != 0 && strcmp(b, "reflective") != 0))
            return luaL_error(L, "bad argument 'boundary' to 'water' (\"reflective\" or \"fixed\" expected)");
        fixed = strcmp(b, "fixed") == 0;
    }
    lua_pop(L, 1);
    if (!(ior > 0) || attenuation.x < 0 || attenuation.y < 0 || attenuation.z < 0)
        return luaL_error(L, "bad argument to 'water' (ior > 0 and non-negative attenuation expected)");
    struct error err;
    struct mesh *m = mesh_create_grid(size, resolution - 1, &err);
    if (!m)
        return luaL_error(L, "water: %s", err.message);
    snprintf(m->name, sizeof m->name, "water %dx%d", resolution, resolution);
    struct l_mesh *mu = lua_newuserdatauv(L, sizeof *mu, 0);
    mu->mesh = m;
    luaL_setmetatable(L, MESH_MT);
    int mesh_idx = lua_gettop(L);
    struct l_object *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->obj = object_create(m);
    luaL_setmetatable(L, OBJECT_MT);
    if (!u->obj)
        return luaL_error(L, "out of memory");
    lua_pushvalue(L, mesh_idx);
    lua_setiuservalue(L, -2, 1);
    struct object *o = u->obj;
    o->water = calloc(1, sizeof *o->water);
    if (!o->water)
        return luaL_error(L, "water: out of memory");
    if (!water_create(o->water, resolution, size, depth, speed, damping, fixed, &err)) {
        free(o->water);
        o->water = NULL;
        return luaL_error(L, "water: %s", err.message);
    }
    o->material.kind = MATERIAL_WATER;
    o->material.ior = ior;
    o->material.absorption = attenuation;
    o->material.color = vec3_make(1, 1, 1);
    int obj_idx = lua_gettop(L);
    static const char *const passthrough[] = {"position", "visible", "cast_shadows", NULL};
    for (int i = 0; passthrough[i]; i++) {
        if (lua_getfield(L, 1, passthrough[i]) != LUA_TNIL)
            object_set(L, o, passthrough[i], lua_gettop(L));
        lua_pop(L, 1);
    }
    lua_settop(L, obj_idx);
    return 1;
}

static struct water *check_water(lua_State *L, const char *fn)
{
    struct object *o = check_object(L, 1);
    if (!o->water)
        luaL_error(L, "%s: this object is not a water surface (make one with c.water{...})", fn);
    return o->water;
}

/* water:drop(x, z, radius, strength) */
static int water_drop_l(lua_State *L)
{
    struct water *w = check_water(L, "drop");
    float x = lutil_check_number(L, 2, "drop", "x"), z = lutil_check_number(L, 3, "drop", "z");
    float radius = lutil_check_number(L, 4, "drop", "radius"), strength = lutil_check_number(L, 5, "drop", "strength");
    if (!(radius > 0.0f))
        return lutil_error(L, "bad argument 'radius' to 'drop' (a positive number expected, got %g)", (double)radius);
    water_drop(w, x, z, radius, strength);
    check_object(L, 1)->version++;
    return 0;
}

/* water:step(dt): advances the simulation, substepping to its stability limit */
static int water_step_l(lua_State *L)
{
    struct water *w = check_water(L, "step");
    double dt = luaL_checknumber(L, 2);
    if (!(dt >= 0) || !isfinite(dt))
        return luaL_error(L, "bad argument #1 to 'step' (a finite time step >= 0 expected)");
    water_step(w, dt);
    check_object(L, 1)->version++;
    return 0;
}

/* water:set_heights(function(x, z) return h end) (velocities reset to 0) */
static int water_set_heights_l(lua_State *L)
{
    struct water *w = check_water(L, "set_heights");
    luaL_checktype(L, 2, LUA_TFUNCTION);
    int n = w->resolution;
    double dx = (double)w->size / (n - 1), half = 0.5 * w->size;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            lua_pushvalue(L, 2);
            lua_pushnumber(L, -half + i * dx);
            lua_pushnumber(L, -half + j * dx);
            lua_call(L, 2, 1);
            double h = lua_tonumber(L, -1);
            lua_pop(L, 1);
            if (!isfinite(h))
                return luaL_error(L, "set_heights: the function returned a non-finite height at (%f, %f)",
                                  -half + i * dx, -half + j * dx);
            w->height[(size_t)j * (size_t)n + (size_t)i] = h;
            w->velocity[(size_t)j * (size_t)n + (size_t)i] = 0.0;
        }
    w->dirty = true;
    w->dirty_energy = true;
    check_object(L, 1)->version++;
    return 0;
}

static int object_gc(lua_State *L)
{
    struct l_object *u = luaL_checkudata(L, 1, OBJECT_MT);
    object_destroy(u->obj);
    u->obj = NULL;
    return 0;
}

static int object_index(lua_State *L)
{
    struct object *o = check_object(L, 1);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "position") == 0)
        lutil_push_vec3(L, o->position);
    else if (strcmp(k, "rotation") == 0)
        lutil_push_quat(L, o->rotation);
    else if (strcmp(k, "scale") == 0)
        lutil_push_vec3(L, o->scale);
    else if (strcmp(k, "visible") == 0)
        lua_pushboolean(L, o->visible);
    else if (strcmp(k, "cast_shadows") == 0)
        lua_pushboolean(L, o->cast_shadows);
    else if (strcmp(k, "mesh") == 0)
        lua_getiuservalue(L, 1, 1);
    else if (strcmp(k, "material") == 0) {
        struct material *m = lua_newuserdatauv(L, sizeof *m, 0);
        *m = o->material;
        luaL_setmetatable(L, MATERIAL_MT);
    } else if (strcmp(k, "morph_weights") == 0) {
        lua_createtable(L, o->mesh->target_count, 0);
        for (int i = 0; i < o->mesh->target_count; i++) {
            lua_pushnumber(L, o->morph_weights[i]);
            lua_rawseti(L, -2, i + 1);
        }
    } else if (strcmp(k, "id") == 0)
        lua_pushinteger(L, o->id);
    else if (o->water && strcmp(k, "drop") == 0)
        lua_pushcfunction(L, water_drop_l);
    else if (o->water && strcmp(k, "step") == 0)
        lua_pushcfunction(L, water_step_l);
    else if (o->water && strcmp(k, "set_heights") == 0)
        lua_pushcfunction(L, water_set_heights_l);
    else if (o->water && strcmp(k, "energy") == 0)
        lua_pushnumber(L, water_energy(o->water));
    else if (o->water && strcmp(k, "stable_step") == 0)
        lua_pushnumber(L, water_stable_step(o->water));
    else if (o->water && strcmp(k, "substeps") == 0)
        lua_pushinteger(L, o->water->substeps);
    else if (o->water && strcmp(k, "max_height") == 0) {
        double hmax = 0.0;
        for (size_t i = 0; i < (size_t)o->water->resolution * (size_t)o->water->resolution; i++)
            hmax = fmax(hmax, fabs(o->water->height[i]));
        lua_pushnumber(L, hmax);
    } else if (o->water && strcmp(k, "depth") == 0)
        lua_pushnumber(L, o->water->depth);
    else
        lua_pushnil(L);
    return 1;
}

static int object_newindex(lua_State *L)
{
    object_set(L, check_object(L, 1), luaL_checkstring(L, 2), 3);
    return 0;
}

static int object_tostring(lua_State *L)
{
    struct object *o = check_object(L, 1);
    lua_pushfstring(L, "Object(%s, %s)", o->mesh->name, material_kind_name(o->material.kind));
    return 1;
}

/* ---- lights ---------------------------------------------------------- */

static struct light *check_light(lua_State *L, int idx)
{
    struct light *l = ((struct l_light *)luaL_checkudata(L, idx, LIGHT_MT))->light;
    if (!l)
        released(L, idx, "light");
    return l;
}

static void light_set(lua_State *L, struct light *l, const char *k, int v)
{
    const char *fn = light_kind_name(l->kind);
    vec3 *vec = NULL;
    if (strcmp(k, "position") == 0 || strcmp(k, "start") == 0)
        vec = &l->position;
    else if (strcmp(k, "end") == 0)
        vec = &l->end;
    else if (strcmp(k, "direction") == 0)
        vec = &l->direction;
    else if (strcmp(k, "intensity") == 0)
        vec = &l->intensity;
    if (vec) {
        vec3 x = vec == &l->intensity ? lutil_check_color(L, v, fn, k) : lutil_check_vec3(L, v, fn, k);
        if (vec == &l->direction && vec3_dot(x, x) < 1e-20f)
            lutil_error(L, "bad argument 'direction' to '%s' (a non-zero vector expected)", fn);
        if (memcmp(&x, vec, sizeof x) != 0)
            l->version++;
        *vec = x;
        return;
    }
    if (strcmp(k, "angle") == 0 || strcmp(k, "softness") == 0) {
        float x = lutil_check_number(L, v, fn, k);
        if (k[0] == 'a' && !(x > 0.0f && x <= 90.0f))
            lutil_error(L, "bad argument 'angle' to '%s' (a half-angle in (0, 90] degrees expected, got %g)", fn,
                        (double)x);
        if (k[0] == 's' && !(x >= 0.0f && x <= 1.0f))
            lutil_error(L, "bad argument 'softness' to '%s' (a fraction in [0, 1] expected, got %g)", fn, (double)x);
        float *f = k[0] == 'a' ? &l->angle : &l->softness;
        if (*f != x)
            l->version++;
        *f = x;
    } else if (strcmp(k, "samples") == 0) {
        if (!lua_isinteger(L, v) || lua_tointeger(L, v) < 1 || lua_tointeger(L, v) > 32)
            luaL_error(L, "bad argument 'samples' to '%s' (integer 1..32 expected)", fn);
        l->samples = (int)lua_tointeger(L, v);
        l->version++;
    } else if (strcmp(k, "cast_shadows") == 0) {
        if (!lua_isboolean(L, v))
            lutil_field_error(L, fn, k, "boolean", v);
        l->cast_shadows = lua_toboolean(L, v);
        l->version++;
    } else {
        luaL_error(L, "%s light has no field '%s' (fields: position, end, direction, intensity, angle, softness, "
                      "samples, cast_shadows)", fn, k);
    }
}

static int push_light(lua_State *L, enum light_kind kind)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"position", "start", "end", "direction", "intensity", "angle",
                                         "softness", "samples", "cast_shadows", NULL};
    lutil_check_fields(L, 1, light_kind_name(kind), fields);
    struct l_light *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->light = light_create(kind);
    luaL_setmetatable(L, LIGHT_MT);
    if (!u->light)
        return luaL_error(L, "out of memory");
    int idx = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        light_set(L, u->light, lua_tostring(L, -2), lua_gettop(L));
        lua_pop(L, 1);
    }
    lua_settop(L, idx);
    return 1;
}

static int light_point(lua_State *L) { return push_light(L, LIGHT_POINT); }
static int light_directional(lua_State *L) { return push_light(L, LIGHT_DIRECTIONAL); }
static int light_spot(lua_State *L) { return push_light(L, LIGHT_SPOT); }
static int light_linear(lua_State *L) { return push_light(L, LIGHT_LINEAR); }

static int light_gc(lua_State *L)
{
    struct l_light *u = luaL_checkudata(L, 1, LIGHT_MT);
    light_destroy(u->light);
    u->light = NULL;
    return 0;
}

static int light_index(lua_State *L)
{
    struct light *l = check_light(L, 1);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "position") == 0 || strcmp(k, "start") == 0)
        lutil_push_vec3(L, l->position);
    else if (strcmp(k, "end") == 0)
        lutil_push_vec3(L, l->end);
    else if (strcmp(k, "direction") == 0)
        lutil_push_vec3(L, l->direction);
    else if (strcmp(k, "intensity") == 0)
        lutil_push_vec3(L, l->intensity);
    else if (strcmp(k, "angle") == 0)
        lua_pushnumber(L, l->angle);
    else if (strcmp(k, "softness") == 0)
        lua_pushnumber(L, l->softness);
    else if (strcmp(k, "samples") == 0)
        lua_pushinteger(L, l->samples);
    else if (strcmp(k, "cast_shadows") == 0)
        lua_pushboolean(L, l->cast_shadows);
    else if (strcmp(k, "kind") == 0)
        lua_pushstring(L, light_kind_name(l->kind));
    else
        lua_pushnil(L);
    return 1;
}

static int light_newindex(lua_State *L)
{
    light_set(L, check_light(L, 1), luaL_checkstring(L, 2), 3);
    return 0;
}

static int light_tostring(lua_State *L)
{
    lua_pushfstring(L, "Light(%s)", light_kind_name(check_light(L, 1)->kind));
    return 1;
}

/* ---- cameras --------------------------------------------------------- */

static void camera_set(lua_State *L, struct camera *c, const char *k, int v)
{
    if (strcmp(k, "eye") == 0)
        c->eye = lutil_check_vec3(L, v, "camera", k);
    else if (strcmp(k, "target") == 0)
        c->target = lutil_check_vec3(L, v, "camera", k);
    else if (strcmp(k, "up") == 0)
        c->up = lutil_check_vec3(L, v, "camera", k);
    else if (strcmp(k, "fov") == 0 || strcmp(k, "near") == 0 || strcmp(k, "far") == 0) {
        float x = lutil_check_number(L, v, "camera", k);
        if (k[0] == 'f' && k[1] == 'o') {
            if (!(x > 0.5f && x < 179.5f))
                lutil_error(L, "bad argument 'fov' to 'camera' (degrees in (0.5, 179.5) expected, got %g)", (double)x);
            c->fov = x;
        } else if (!(x > 0.0f)) {
            lutil_error(L, "bad argument '%s' to 'camera' (a positive distance expected, got %g)", k, (double)x);
        } else if (k[0] == 'n') {
            c->znear = x;
        } else {
            c->zfar = x;
        }
    } else {
        luaL_error(L, "camera has no field '%s' (fields: eye, target, up, fov, near, far)", k);
    }
    c->version++;
}

/* near >= far leaves no depth range; checked once all fields are set. */
static void check_clip_range(lua_State *L, const struct camera *c)
{
    if (!(c->znear < c->zfar))
        lutil_error(L, "bad argument 'near' to 'camera' (near %g must be less than far %g)", (double)c->znear,
                    (double)c->zfar);
}

static int camera_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"eye", "target", "up", "fov", "near", "far", NULL};
    lutil_check_fields(L, 1, "camera", fields);
    struct l_camera *u = lua_newuserdatauv(L, sizeof *u, 1);
    struct scene defaults;
    scene_init(&defaults);
    u->own = defaults.camera;
    u->cam = &u->own;
    luaL_setmetatable(L, CAMERA_MT);
    int idx = lua_gettop(L);
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        camera_set(L, u->cam, lua_tostring(L, -2), lua_gettop(L));
        lua_pop(L, 1);
    }
    lua_settop(L, idx);
    check_clip_range(L, u->cam);
    return 1;
}

static int camera_index(lua_State *L)
{
    struct l_camera *u = luaL_checkudata(L, 1, CAMERA_MT);
    const char *k = luaL_checkstring(L, 2);
    struct camera *c = u->cam;
    if (strcmp(k, "eye") == 0)
        lutil_push_vec3(L, c->eye);
    else if (strcmp(k, "target") == 0)
        lutil_push_vec3(L, c->target);
    else if (strcmp(k, "up") == 0)
        lutil_push_vec3(L, c->up);
    else if (strcmp(k, "fov") == 0)
        lua_pushnumber(L, c->fov);
    else if (strcmp(k, "near") == 0)
        lua_pushnumber(L, c->znear);
    else if (strcmp(k, "far") == 0)
        lua_pushnumber(L, c->zfar);
    else
        lua_pushnil(L);
    return 1;
}

static int camera_newindex(lua_State *L)
{
    struct l_camera *u = luaL_checkudata(L, 1, CAMERA_MT);
    struct camera before = *u->cam;
    camera_set(L, u->cam, luaL_checkstring(L, 2), 3);
    if (!(u->cam->znear < u->cam->zfar)) {
        struct camera wanted = *u->cam;
        *u->cam = before;
        check_clip_range(L, &wanted);
    }
    return 0;
}

/* ---- environments ---------------------------------------------------- */

static int cubemap_new(lua_State *L)
{
    const char *rel = luaL_checkstring(L, 1);
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "%s", err.message);
    struct environment *env = environment_load(path, &err);
    if (!env)
        return luaL_error(L, "%s", err.message);
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

/* ---- media ------------------------------------------------------------ */

struct l_medium { struct medium *medium; };

/* c.medium { sigma_s, sigma_a, g, density = number | function(x, y, z), resolution = {nx, ny, nz}, box = {min, max} } */
static int medium_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"sigma_s", "sigma_a", "g", "density", "resolution", "box", NULL};
    lutil_check_fields(L, 1, "medium", fields);
    struct l_medium *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->medium = medium_create();
    luaL_setmetatable(L, MEDIUM_MT);
    if (!u->medium)
        return luaL_error(L, "out of memory");
    int idx = lua_gettop(L);
    struct medium *m = u->medium;
    lutil_opt_color(L, 1, "medium", "sigma_s", &m->sigma_s);
    lutil_opt_color(L, 1, "medium", "sigma_a", &m->sigma_a);
    lutil_opt_number(L, 1, "medium", "g", &m->g);
    if (!(m->g > -0.99f && m->g < 0.99f))
        return lutil_error(L, "bad argument 'g' to 'medium' (a number in (-0.99, 0.99) expected, got %g)", (double)m->g);
    if (m->sigma_s.x < 0 || m->sigma_s.y < 0 || m->sigma_s.z < 0 || m->sigma_a.x < 0 || m->sigma_a.y < 0 ||
        m->sigma_a.z < 0 || !math_finite3(m->sigma_s) || !math_finite3(m->sigma_a))
        return luaL_error(L, "bad argument 'sigma_s'/'sigma_a' to 'medium' (non-negative finite coefficients expected)");
    if (lua_getfield(L, 1, "box") != LUA_TTABLE)
        return luaL_error(L, "bad argument 'box' to 'medium' ({{x0, y0, z0}, {x1, y1, z1}} expected, got %s)",
                          luaL_typename(L, -1));
    lua_rawgeti(L, -1, 1);
    m->box_min = lutil_check_vec3(L, -1, "medium", "box");
    lua_rawgeti(L, -2, 2);
    m->box_max = lutil_check_vec3(L, -1, "medium", "box");
    lua_pop(L, 3);
    if (!(m->box_min.x < m->box_max.x && m->box_min.y < m->box_max.y && m->box_min.z < m->box_max.z))
        return luaL_error(L, "bad argument 'box' to 'medium' (min must be below max on every axis)");
    int type = lua_getfield(L, 1, "density");
    if (type == LUA_TNUMBER) {
        m->density = (float)lua_tonumber(L, -1);
        if (!(m->density >= 0) || !isfinite(m->density))
            return luaL_error(L, "bad argument 'density' to 'medium' (a non-negative number expected)");
        m->max_density = m->density;
    } else if (type == LUA_TFUNCTION) {
        /* A density function, sampled once on the corners of a grid. */
        int res[3] = {32, 32, 32};
        if (lua_getfield(L, 1, "resolution") == LUA_TTABLE)
            for (int k = 0; k < 3; k++) {
                lua_rawgeti(L, -1, k + 1);
                res[k] = (int)luaL_checkinteger(L, -1);
                lua_pop(L, 1);
            }
        lua_pop(L, 1);
        for (int k = 0; k < 3; k++)
            if (res[k] < 2 || res[k] > 256)
                return luaL_error(L, "bad argument 'resolution' to 'medium' (2..256 per axis expected)");
        m->nx = res[0];
        m->ny = res[1];
        m->nz = res[2];
        m->grid = malloc((size_t)res[0] * (size_t)res[1] * (size_t)res[2] * sizeof(float));
        if (!m->grid)
            return luaL_error(L, "out of memory for a %dx%dx%d density grid", res[0], res[1], res[2]);
        m->max_density = 0;
        int fn = lua_gettop(L);
        for (int z = 0; z < res[2]; z++)
            for (int y = 0; y < res[1]; y++)
                for (int x = 0; x < res[0]; x++) {
                    vec3 p = {m->box_min.x + (m->box_max.x - m->box_min.x) * (float)x / (float)(res[0] - 1),
                              m->box_min.y + (m->box_max.y - m->box_min.y) * (float)y / (float)(res[1] - 1),
                              m->box_min.z + (m->box_max.z - m->box_min.z) * (float)z / (float)(res[2] - 1)};
                    lua_pushvalue(L, fn);
                    lua_pushnumber(L, p.x);
                    lua_pushnumber(L, p.y);
                    lua_pushnumber(L, p.z);
                    lua_call(L, 3, 1);
                    if (!lua_isnumber(L, -1))
                        return luaL_error(L, "medium density function must return a number, got %s", luaL_typename(L, -1));
                    float d = (float)lua_tonumber(L, -1);
                    lua_pop(L, 1);
                    if (!(d >= 0) || !isfinite(d))
                        return luaL_error(L, "medium density function returned %f at (%f, %f, %f): non-negative finite "
                                             "values expected", (double)d, (double)p.x, (double)p.y, (double)p.z);
                    m->grid[((size_t)z * (size_t)res[1] + (size_t)y) * (size_t)res[0] + (size_t)x] = d;
                    if (d > m->max_density)
                        m->max_density = d;
                }
    } else if (type != LUA_TNIL) {
        return lutil_field_error(L, "medium", "density", "number or function(x, y, z)", -1);
    }
    lua_settop(L, idx);
    return 1;
}

/* medium:density_at{x, y, z} */
static int medium_density_at(lua_State *L)
{
    struct l_medium *u = luaL_checkudata(L, 1, MEDIUM_MT);
    if (!u->medium)
        return released(L, 1, "medium");
    vec3 p = lutil_check_vec3(L, 2, "density_at", "point");
    lua_pushnumber(L, medium_density(u->medium, p));
    return 1;
}

static int medium_gc(lua_State *L)
{
    struct l_medium *u = luaL_checkudata(L, 1, MEDIUM_MT);
    medium_destroy(u->medium);
    u->medium = NULL;
    return 0;
}

static int medium_index(lua_State *L)
{
    struct l_medium *u = luaL_checkudata(L, 1, MEDIUM_MT);
    if (!u->medium)
        return released(L, 1, "medium");
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "sigma_s") == 0)
        lutil_push_vec3(L, u->medium->sigma_s);
    else if (strcmp(k, "sigma_a") == 0)
        lutil_push_vec3(L, u->medium->sigma_a);
    else if (strcmp(k, "g") == 0)
        lua_pushnumber(L, u->medium->g);
    else if (strcmp(k, "density_at") == 0)
        lua_pushcfunction(L, medium_density_at);
    else
        lua_pushnil(L);
    return 1;
}

/* ---- scenes ---------------------------------------------------------- */

static struct scene *check_scene(lua_State *L, int idx)
{
    return &((struct l_scene *)luaL_checkudata(L, idx, SCENE_MT))->scene;
}

static void scene_set(lua_State *L, int scene_idx, struct scene *s, const char *k, int v)
{
    if (strcmp(k, "camera") == 0) {
        struct l_camera *c = luaL_testudata(L, v, CAMERA_MT);
        if (!c)
            lutil_field_error(L, "scene", k, "camera (c.camera{...})", v);
        uint64_t version = s->camera.version;
        s->camera = *c->cam;
        s->camera.version = version + 1;
    } else if (strcmp(k, "background") == 0) {
        s->background = lutil_check_color(L, v, "scene", k);
    } else if (strcmp(k, "ambient") == 0) {
        s->ambient = lutil_check_color(L, v, "scene", k);
    } else if (strcmp(k, "environment") == 0) {
        if (lua_isnil(L, v)) {
            scene_set_environment(s, NULL);
        } else {
            struct l_environment *e = luaL_testudata(L, v, ENVIRONMENT_MT);
            if (!e || !e->env)
                lutil_field_error(L, "scene", k, "environment (c.cubemap \"folder\")", v);
            scene_set_environment(s, e->env);
        }
        lua_pushvalue(L, v);
        lua_setiuservalue(L, scene_idx, 2); /* keep it alive */
    } else if (strcmp(k, "medium") == 0) {
        if (lua_isnil(L, v)) {
            scene_set_medium(s, NULL);
        } else {
            struct l_medium *m = luaL_testudata(L, v, MEDIUM_MT);
            if (!m || !m->medium)
                lutil_field_error(L, "scene", k, "medium (c.medium{...})", v);
            scene_set_medium(s, m->medium);
        }
        /* keep it alive in the members table */
        lua_getiuservalue(L, scene_idx, 1);
        lua_pushstring(L, "medium");
        lua_pushvalue(L, v);
        lua_rawset(L, -3);
        lua_pop(L, 1);
    } else {
        luaL_error(L, "scene has no field '%s' (fields: camera, background, ambient, environment, medium)", k);
    }
    s->version++;
}

static int scene_new(lua_State *L)
{
    if (lua_isnoneornil(L, 1))
        lua_newtable(L);
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"camera", "background", "ambient", "environment", "medium", NULL};
    lutil_check_fields(L, 1, "scene", fields);
    struct l_scene *u = lua_newuserdatauv(L, sizeof *u, 2);
    scene_init(&u->scene);
    luaL_setmetatable(L, SCENE_MT);
    int idx = lua_gettop(L);
    lua_newtable(L); /* members kept alive: objects and lights */
    lua_setiuservalue(L, idx, 1);
    lua_pushnil(L);
    while (lua_next(L, 1)) {
        scene_set(L, idx, &u->scene, lua_tostring(L, -2), lua_gettop(L));
        lua_pop(L, 1);
    }
    lua_settop(L, idx);
    return 1;
}

static int scene_gc(lua_State *L)
{
    struct l_scene *u = luaL_checkudata(L, 1, SCENE_MT);
    scene_release(&u->scene);
    return 0;
}

static int scene_add(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    struct error err;
    bool ok;
    if (luaL_testudata(L, 2, OBJECT_MT))
        ok = scene_object_add(s, check_object(L, 2), &err);
    else if (luaL_testudata(L, 2, LIGHT_MT))
        ok = scene_light_add(s, check_light(L, 2), &err);
    else
        return luaL_argerror(L, 2, lua_pushfstring(L, "object or light expected, got %s", luaL_typename(L, 2)));
    if (!ok)
        return luaL_error(L, "%s", err.message);
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
    if (luaL_testudata(L, 2, OBJECT_MT)) {
        scene_object_remove(s, check_object(L, 2));
    } else {
        scene_light_remove(s, check_light(L, 2));
    }
    lua_getiuservalue(L, 1, 1);
    lua_pushvalue(L, 2);
    lua_pushnil(L);
    lua_rawset(L, -3);
    return 0;
}

static int scene_index(lua_State *L)
{
    struct scene *s = check_scene(L, 1);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "camera") == 0) {
        /* A live view of the scene's camera. */
        struct l_camera *c = lua_newuserdatauv(L, sizeof *c, 1);
        c->cam = &s->camera;
        luaL_setmetatable(L, CAMERA_MT);
        lua_pushvalue(L, 1);
        lua_setiuservalue(L, -2, 1);
    } else if (strcmp(k, "background") == 0)
        lutil_push_vec3(L, s->background);
    else if (strcmp(k, "ambient") == 0)
        lutil_push_vec3(L, s->ambient);
    else if (strcmp(k, "environment") == 0)
        lua_getiuservalue(L, 1, 2);
    else if (strcmp(k, "medium") == 0) {
        lua_getiuservalue(L, 1, 1);
        lua_getfield(L, -1, "medium");
    }
    else if (strcmp(k, "add") == 0)
        lua_pushcfunction(L, scene_add);
    else if (strcmp(k, "remove") == 0)
        lua_pushcfunction(L, scene_remove);
    else if (strcmp(k, "object_count") == 0)
        lua_pushinteger(L, s->object_count);
    else if (strcmp(k, "light_count") == 0)
        lua_pushinteger(L, s->light_count);
    else
        lua_pushnil(L);
    return 1;
}

static int scene_newindex(lua_State *L)
{
    scene_set(L, 1, check_scene(L, 1), luaL_checkstring(L, 2), 3);
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
    float angle = (float)luaL_checknumber(L, 2);
    lutil_push_quat(L, quat_axis_angle(axis, angle));
    return 1;
}

static int quat_mul_l(lua_State *L)
{
    quat a = lutil_check_quat(L, 1, "mul", "a"), b = lutil_check_quat(L, 2, "mul", "b");
    lutil_push_quat(L, quat_mul(a, b));
    return 1;
}

struct scene *lua_host_to_scene(lua_State *L, int idx)
{
    struct l_scene *u = luaL_testudata(L, idx, SCENE_MT);
    return u ? &u->scene : NULL;
}
struct object *lobject_test(lua_State *L, int idx)
{
    struct l_object *u = luaL_testudata(L, idx, OBJECT_MT);
    return u ? u->obj : NULL; /* NULL too when released */
}

struct light *llight_test(lua_State *L, int idx)
{
    struct l_light *u = luaL_testudata(L, idx, LIGHT_MT);
    return u ? u->light : NULL;
}

/* Protected (__metatable): getmetatable(x) gives a string, so a script
 * cannot reach __gc and free what the scene still uses. */
static void new_metatable(lua_State *L, const char *name, const luaL_Reg *methods)
{
    luaL_newmetatable(L, name);
    luaL_setfuncs(L, methods, 0);
    lua_pushstring(L, name);
    lua_setfield(L, -2, "__metatable");
    lua_pop(L, 1);
}

int luaopen_caustica_scene(lua_State *L)
{
    static const luaL_Reg mesh_meta[] = {{"__gc", mesh_gc}, {"__index", mesh_index}, {"__tostring", mesh_tostring}, {NULL, NULL}};
    static const luaL_Reg material_meta[] = {{"__index", material_index}, {"__tostring", material_tostring}, {NULL, NULL}};
    static const luaL_Reg object_meta[] = {{"__gc", object_gc}, {"__index", object_index}, {"__newindex", object_newindex},
                                           {"__tostring", object_tostring}, {NULL, NULL}};
    static const luaL_Reg light_meta[] = {{"__gc", light_gc}, {"__index", light_index}, {"__newindex", light_newindex},
                                          {"__tostring", light_tostring}, {NULL, NULL}};
    static const luaL_Reg camera_meta[] = {{"__index", camera_index}, {"__newindex", camera_newindex}, {NULL, NULL}};
    static const luaL_Reg environment_meta[] = {{"__gc", environment_gc}, {NULL, NULL}};
    static const luaL_Reg deformer_meta[] = {{"__gc", deform_gc}, {NULL, NULL}};
    static const luaL_Reg medium_meta[] = {{"__gc", medium_gc}, {"__index", medium_index}, {NULL, NULL}};
    static const luaL_Reg scene_meta[] = {{"__gc", scene_gc}, {"__index", scene_index}, {"__newindex", scene_newindex},
                                          {"__tostring", scene_tostring}, {NULL, NULL}};
    new_metatable(L, MESH_MT, mesh_meta);
    new_metatable(L, MATERIAL_MT, material_meta);
    new_metatable(L, OBJECT_MT, object_meta);
    new_metatable(L, LIGHT_MT, light_meta);
    new_metatable(L, CAMERA_MT, camera_meta);
    new_metatable(L, ENVIRONMENT_MT, environment_meta);
    new_metatable(L, DEFORMER_MT, deformer_meta);
    new_metatable(L, SCENE_MT, scene_meta);
    new_metatable(L, MEDIUM_MT, medium_meta);

    static const luaL_Reg top[] = {{"scene", scene_new}, {"object", object_new}, {"camera", camera_new},
                                   {"cubemap", cubemap_new}, {"medium", medium_new},
                                   {"water", water_new}, {NULL, NULL}};
    static const luaL_Reg meshes[] = {{"load", mesh_load}, {"sphere", mesh_sphere}, {"plane", mesh_plane},
                                      {"box", mesh_box}, {"grid", mesh_grid}, {"torus", mesh_torus}, {NULL, NULL}};
    static const luaL_Reg materials[] = {{"diffuse", material_diffuse}, {"glass", material_glass},
                                         {"mirror", material_mirror}, {"water", material_water}, {NULL, NULL}};
    static const luaL_Reg lights[] = {{"point", light_point}, {"directional", light_directional},
                                      {"spot", light_spot}, {"linear", light_linear}, {NULL, NULL}};
    static const luaL_Reg deformers[] = {{"wave", deform_wave}, {"glsl", deform_glsl}, {NULL, NULL}};
    static const luaL_Reg quats[] = {{"axis_angle", quat_axis_angle_l}, {"mul", quat_mul_l}, {NULL, NULL}};
    luaL_newlib(L, top);
    luaL_newlib(L, meshes);
    lua_setfield(L, -2, "mesh");
    luaL_newlib(L, materials);
    lua_setfield(L, -2, "material");
    luaL_newlib(L, lights);
    lua_setfield(L, -2, "light");
    luaL_newlib(L, deformers);
    lua_setfield(L, -2, "deform");
    luaL_newlib(L, quats);
    lua_setfield(L, -2, "quat");
    return 1;
}
