/* Deformers (c.deform.*), objects (c.object) and water surfaces (c.water)
 * with live fields: an assignment takes effect on the next frame and bumps
 * the object's version. Meshes are l_mesh.c; the simulation itself is
 * scene/water.c; this file only translates. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/gltf.h"
#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"
#include "scene/water.h"

/* ---- deformers -------------------------------------------------------- */

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
    luaL_argcheck(L, strstr(src, "deform") != NULL, 1, "GLSL defining 'vec3 deform(vec3 p, float t)' expected");
    struct deformer *d = new_deformer(L);
    d->kind = DEFORM_GLSL;
    d->glsl = strdup(src);
    if (!d->glsl)
        return lutil_error(L, "out of memory");
    strncat(d->origin, " (deformer)", sizeof d->origin - strlen(d->origin) - 1);
    return 1;
}

/* ---- objects --------------------------------------------------------- */

struct object *lobject_check(lua_State *L, int idx)
{
    struct object *o = ((struct l_object *)luaL_checkudata(L, idx, OBJECT_MT))->obj;
    if (!o)
        lscene_released(L, idx, "object");
    return o;
}

struct object *lobject_test(lua_State *L, int idx)
{
    struct l_object *u = luaL_testudata(L, idx, OBJECT_MT);
    return u ? u->obj : NULL;
}

/* After a change to a group, its parts follow (scene/scene.c). */
static void parts_follow(lua_State *L, struct object *o)
{
    if (!object_sync_parts(o))
        lutil_error(L, "out of memory");
}

static int set_position(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    vec3 p = lutil_check_vec3(L, 3, "object", "position");
    if (memcmp(&p, &o->position, sizeof p) != 0)
        o->version++;
    o->position = p;
    parts_follow(L, o);
    return 0;
}

static int set_rotation(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    quat q = lutil_check_quat(L, 3, "object", "rotation");
    if (memcmp(&q, &o->rotation, sizeof q) != 0)
        o->version++;
    o->rotation = q;
    parts_follow(L, o);
    return 0;
}

static int set_scale(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    vec3 s = lutil_check_vec3(L, 3, "object", "scale");
    if (memcmp(&s, &o->scale, sizeof s) != 0)
        o->version++;
    o->scale = s;
    parts_follow(L, o);
    return 0;
}

static void set_flag(lua_State *L, struct object *o, bool *field, const char *name)
{
    if (!lua_isboolean(L, 3))
        lutil_field_error(L, "object", name, "boolean", 3);
    if (*field != (bool)lua_toboolean(L, 3))
        o->version++;
    *field = lua_toboolean(L, 3);
    parts_follow(L, o);
}

static int set_visible(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    set_flag(L, o, &o->visible, "visible");
    return 0;
}

static int set_cast_shadows(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    set_flag(L, o, &o->cast_shadows, "cast_shadows");
    return 0;
}

static int set_material(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    struct material *m = luaL_testudata(L, 3, MATERIAL_MT);
    if (!m)
        lutil_field_error(L, "object", "material", "material (c.material.*)", 3);
    object_set_material(o, m);
    return 0;
}

static int set_morph_weights(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    if (!lua_istable(L, 3))
        lutil_field_error(L, "object", "morph_weights", "table of numbers", 3);
    int n = (int)lua_rawlen(L, 3);
    if (n > o->mesh->target_count)
        lutil_error(L, "bad argument 'morph_weights' to 'object' (the mesh has %d morph target%s, got %d weights)",
                   o->mesh->target_count, o->mesh->target_count == 1 ? "" : "s", n);
    for (int i = 0; i < n; i++) {
        lua_rawgeti(L, 3, i + 1);
        if (lua_type(L, -1) != LUA_TNUMBER)
            lutil_field_error(L, "object", "morph_weights", "table of numbers", -1);
        float w = (float)lua_tonumber(L, -1);
        if (!isfinite(w))
            lutil_error(L, "bad argument 'morph_weights' to 'object' (weight %d is not finite)", i + 1);
        if (o->morph_weights[i] != w)
            o->version++;
        o->morph_weights[i] = w;
        lua_pop(L, 1);
    }
    parts_follow(L, o);
    return 0;
}

/* object.joint_matrices = { 16 numbers a joint, ... } (a skinned glTF
 * mesh, c.gltf.load's animations set it): each joint's world matrix times
 * its inverse bind matrix, column-major; {} takes the skin off. */
static int set_joint_matrices(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    if (!lua_istable(L, 3))
        lutil_field_error(L, "object", "joint_matrices", "table of numbers (16 a joint)", 3);
    lua_Integer n = (lua_Integer)lua_rawlen(L, 3);
    if (n % 16 != 0 || n / 16 > GLTF_MAX_JOINTS)
        lutil_error(L, "bad argument 'joint_matrices' to 'object' (16 numbers a joint, at most %d joints, got %lld "
                       "numbers)", GLTF_MAX_JOINTS, (long long)n);
    if (n > 0 && !o->mesh->joints)
        lutil_error(L, "bad argument 'joint_matrices' to 'object' (mesh '%s' has no skin: no JOINTS_0 and WEIGHTS_0)",
                    o->mesh->name);
    if (n > 0 && n / 16 < o->mesh->joint_count)
        lutil_error(L, "bad argument 'joint_matrices' to 'object' (the mesh's skin uses %d joints, got %lld)",
                    o->mesh->joint_count, (long long)(n / 16));
    float m[GLTF_MAX_JOINTS * 16];
    for (lua_Integer i = 0; i < n; i++) {
        lua_rawgeti(L, 3, i + 1);
        if (lua_type(L, -1) != LUA_TNUMBER)
            lutil_field_error(L, "object", "joint_matrices", "table of numbers (16 a joint)", -1);
        m[i] = (float)lua_tonumber(L, -1);
        if (!isfinite(m[i]))
            lutil_error(L, "bad argument 'joint_matrices' to 'object' (number %lld is not finite)", (long long)i + 1);
        lua_pop(L, 1);
    }
    if (!object_set_joint_matrices(o, m, (int)(n / 16)))
        lutil_error(L, "object: out of memory for %lld joint matrices", (long long)(n / 16));
    o->version++;
    parts_follow(L, o);
    return 0;
}

/* object.bounds: its world box now ({min, max}): the mesh's box through
 * its transform, grown by its morphs and deformer, a skin's as posed; a
 * group's spans its parts. */
static int get_object_bounds(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    vec3 lo, hi;
    object_world_bounds(o, &lo, &hi);
    for (int p = 0; p < o->part_count; p++) {
        vec3 a, b;
        object_world_bounds(o->parts[p], &a, &b);
        lo = vec3_min(lo, a);
        hi = vec3_max(hi, b);
    }
    lutil_push_box(L, lo, hi);
    return 1;
}

static int get_joint_matrices(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    lua_createtable(L, o->joint_matrix_count * 16, 0);
    for (int i = 0; i < o->joint_matrix_count * 16; i++) {
        lua_pushnumber(L, o->joint_matrices[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int set_deform(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    struct deformer *d = NULL;
    if (!lua_isnil(L, 3) && !(lua_isboolean(L, 3) && !lua_toboolean(L, 3))) {
        d = luaL_testudata(L, 3, DEFORMER_MT);
        if (!d)
            lutil_field_error(L, "object", "deform", "deformer (c.deform.wave{...} or c.deform.glsl(...))", 3);
    }
    char *glsl = d && d->glsl ? strdup(d->glsl) : NULL;
    if (d && d->glsl && !glsl)
        return lutil_error(L, "out of memory");
    free(o->deform.glsl);
    if (d) {
        o->deform = *d;
        o->deform.glsl = glsl;
    } else {
        o->deform.kind = DEFORM_NONE;
        o->deform.glsl = NULL;
    }
    o->version++;
    parts_follow(L, o);
    return 0;
}

static int get_position(lua_State *L)
{
    lutil_push_vec3(L, lobject_check(L, 1)->position);
    return 1;
}

static int get_rotation(lua_State *L)
{
    lutil_push_quat(L, lobject_check(L, 1)->rotation);
    return 1;
}

static int get_scale(lua_State *L)
{
    lutil_push_vec3(L, lobject_check(L, 1)->scale);
    return 1;
}

static int get_visible(lua_State *L)
{
    lua_pushboolean(L, lobject_check(L, 1)->visible);
    return 1;
}

static int get_cast_shadows(lua_State *L)
{
    lua_pushboolean(L, lobject_check(L, 1)->cast_shadows);
    return 1;
}

static int get_mesh(lua_State *L)
{
    lobject_check(L, 1);
    lua_getiuservalue(L, 1, 1);
    return 1;
}

static int get_material(lua_State *L)
{
    lmaterial_push(L, &lobject_check(L, 1)->material);
    return 1;
}

static int get_materials(lua_State *L)
{
    lobject_check(L, 1);
    lmaterials_push(L, 1, true);
    return 1;
}

static int get_morph_weights(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    lua_createtable(L, o->mesh->target_count, 0);
    for (int i = 0; i < o->mesh->target_count; i++) {
        lua_pushnumber(L, o->morph_weights[i]);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int get_id(lua_State *L)
{
    lua_pushinteger(L, lobject_check(L, 1)->id);
    return 1;
}

static const char *const object_fields[] = {"material", "position", "rotation", "scale", "visible",
                                            "cast_shadows", "morph_weights", "deform", NULL};

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
        return lutil_error(L, "out of memory");
    lua_pushvalue(L, mesh_idx);
    lua_setiuservalue(L, obj_idx, 1); /* the object keeps its mesh's userdata alive */
    lutil_assign_fields(L, obj_idx, 1, object_fields);
    parts_follow(L, u->obj);
    lua_settop(L, obj_idx);
    return 1;
}

static int object_gc(lua_State *L)
{
    struct l_object *u = luaL_checkudata(L, 1, OBJECT_MT);
    object_destroy(u->obj);
    u->obj = NULL;
    return 0;
}

static int object_tostring(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    if (o->part_count > 0)
        lua_pushfstring(L, "Object(%s, %d parts)", o->mesh->name, o->part_count);
    else
        lua_pushfstring(L, "Object(%s, %s)", o->mesh->name, material_kind_name(o->material.kind));
    return 1;
}

/* ---- water surfaces --------------------------------------------------- */

/* c.water { size = s | {w, d}, resolution, depth, attenuation = {r,g,b},
 * ior, damping, wave_speed, boundary = "reflective" | "fixed", position }:
 * a water surface object (material water) driven by a height-field
 * simulation, square or w (along x) by d (along z); `resolution` vertices
 * along the longer side. */
static int water_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"size", "resolution", "depth", "attenuation", "ior", "fresnel", "damping",
                                         "wave_speed", "boundary", "position", "visible", "cast_shadows", NULL};
    lutil_check_fields(L, 1, "water", fields);
    float size_x = 2.0f, size_z = 2.0f, depth = 1.0f, ior = 1.33f, damping = 0.0f, speed = 1.0f;
    int resolution = 64;
    vec3 attenuation = {0.0f, 0.0f, 0.0f};
    lutil_opt_extent(L, 1, "water", "size", &size_x, &size_z);
    lutil_opt_integer(L, 1, "water", "resolution", &resolution);
    lutil_opt_number(L, 1, "water", "depth", &depth);
    lutil_opt_number(L, 1, "water", "ior", &ior);
    lutil_opt_number(L, 1, "water", "damping", &damping);
    lutil_opt_number(L, 1, "water", "wave_speed", &speed);
    lutil_opt_color(L, 1, "water", "attenuation", &attenuation);
    bool fresnel = true;
    lutil_opt_boolean(L, 1, "water", "fresnel", &fresnel);
    static const char *const boundaries[] = {"reflective", "fixed", NULL};
    bool fixed = lutil_opt_option(L, 1, "water", "boundary", boundaries, 0) == 1;
    if (!(ior > 0))
        return lutil_error(L, "bad argument 'ior' to 'water' (a positive number expected, got %g)", (double)ior);
    if (resolution >= 2 && resolution <= 2048 && size_x > 0 && size_z > 0 && isfinite(size_x) && isfinite(size_z)) {
        int nx, nz;
        water_grid_counts(resolution, size_x, size_z, &nx, &nz);
        size_t nv, ni;
        mesh_grid_counts(nx - 1, nz - 1, &nv, &ni);
        lmesh_check_planned(L, "water", nv, ni); /* before the simulation's arrays and the grid are made */
    }
    struct error err;
    /* The simulation checks the values; the grid has its vertex counts. */
    struct water *sim = calloc(1, sizeof *sim);
    if (!sim)
        return lutil_error(L, "water: out of memory");
    if (!water_create(sim, resolution, size_x, size_z, depth, speed, damping, fixed, &err)) {
        free(sim);
        return lutil_error(L, "water: %s", err.message);
    }
    struct mesh *m = mesh_create_grid_xz(size_x, size_z, sim->nx - 1, sim->nz - 1, &err);
    if (!m) {
        water_release(sim);
        free(sim);
        return lutil_error(L, "water: %s", err.message);
    }
    snprintf(m->name, sizeof m->name, "water %dx%d", sim->nx, sim->nz);
    lmesh_push(L, m, &err);
    int mesh_idx = lua_gettop(L);
    struct l_object *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->obj = object_create(m);
    luaL_setmetatable(L, OBJECT_MT);
    if (!u->obj) {
        water_release(sim);
        free(sim);
        return lutil_error(L, "out of memory");
    }
    int obj_idx = lua_gettop(L);
    lua_pushvalue(L, mesh_idx);
    lua_setiuservalue(L, obj_idx, 1);
    struct object *o = u->obj;
    o->water = sim;
    o->material.kind = MATERIAL_WATER;
    o->material.ior = ior;
    o->material.absorption = attenuation;
    o->material.ideal = !fresnel;
    o->material.color = vec3_make(1, 1, 1);
    static const char *const passthrough[] = {"position", "visible", "cast_shadows", NULL};
    lutil_assign_fields(L, obj_idx, 1, passthrough);
    lua_settop(L, obj_idx);
    return 1;
}

static struct water *check_water(lua_State *L, const char *fn)
{
    struct object *o = lobject_check(L, 1);
    if (!o->water)
        lutil_error(L, "%s: this object is not a water surface (make one with c.water{...})", fn);
    return o->water;
}

/* water:drop(x, z, radius, strength) */
static int water_drop_l(lua_State *L)
{
    struct water *w = check_water(L, "drop");
    float x = lutil_check_number(L, 2, "drop", "x"), z = lutil_check_number(L, 3, "drop", "z");
    float radius = lutil_check_number(L, 4, "drop", "radius"), strength = lutil_check_number(L, 5, "drop", "strength");
    luaL_argcheck(L, radius > 0.0f, 4, "a positive radius expected");
    water_drop(w, x, z, radius, strength);
    lobject_check(L, 1)->version++;
    return 0;
}

/* water:step(dt): advances the simulation, substepping to its stability limit */
static int water_step_l(lua_State *L)
{
    struct water *w = check_water(L, "step");
    double dt = luaL_checknumber(L, 2);
    luaL_argcheck(L, dt >= 0 && isfinite(dt), 2, "a finite time step >= 0 expected");
    water_step(w, dt);
    lobject_check(L, 1)->version++;
    return 0;
}

static double call_height(void *user, double x, double z)
{
    lua_State *L = user;
    lua_pushvalue(L, 2);
    lua_pushnumber(L, x);
    lua_pushnumber(L, z);
    lua_call(L, 2, 1);
    double h = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return h;
}

/* water:set_heights(function(x, z) return h end) (velocities reset to 0) */
static int water_set_heights_l(lua_State *L)
{
    struct water *w = check_water(L, "set_heights");
    luaL_checktype(L, 2, LUA_TFUNCTION);
    struct error err;
    if (!water_set_heights(w, call_height, L, &err))
        return lutil_error(L, "%s", err.message);
    lobject_check(L, 1)->version++;
    return 0;
}

/* Read-only facts of a water surface; nil on other objects. */
static int push_water_fact(lua_State *L, double (*fact)(const struct water *w))
{
    struct object *o = lobject_check(L, 1);
    if (o->water)
        lua_pushnumber(L, fact(o->water));
    else
        lua_pushnil(L);
    return 1;
}

static double water_depth(const struct water *w) { return w->depth; }

static int get_energy(lua_State *L) { return push_water_fact(L, water_energy); }
static int get_stable_step(lua_State *L) { return push_water_fact(L, water_stable_step); }
static int get_max_height(lua_State *L) { return push_water_fact(L, water_max_height); }
static int get_depth(lua_State *L) { return push_water_fact(L, water_depth); }

/* water.grid = {nx, nz}: the simulation's vertices along x and z (nil on other objects) */
static int get_grid(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    if (!o->water) {
        lua_pushnil(L);
        return 1;
    }
    lua_createtable(L, 2, 0);
    lua_pushinteger(L, o->water->nx);
    lua_rawseti(L, -2, 1);
    lua_pushinteger(L, o->water->nz);
    lua_rawseti(L, -2, 2);
    return 1;
}

static int get_substeps(lua_State *L)
{
    struct object *o = lobject_check(L, 1);
    if (o->water)
        lua_pushinteger(L, o->water->substeps); /* a count: an integer */
    else
        lua_pushnil(L);
    return 1;
}

void lobject_open(lua_State *L)
{
    static const luaL_Reg deformer_meta[] = {{"__gc", deform_gc}, {NULL, NULL}};
    lutil_class(L, DEFORMER_MT, "deformer", deformer_meta, NULL, NULL, NULL);
    static const luaL_Reg object_meta[] = {{"__gc", object_gc}, {"__tostring", object_tostring}, {NULL, NULL}};
    static const luaL_Reg object_methods[] = {{"drop", water_drop_l}, {"step", water_step_l},
                                              {"set_heights", water_set_heights_l}, {NULL, NULL}};
    static const luaL_Reg object_getters[] = {{"position", get_position}, {"rotation", get_rotation},
                                              {"scale", get_scale}, {"visible", get_visible},
                                              {"cast_shadows", get_cast_shadows}, {"mesh", get_mesh},
                                              {"material", get_material}, {"materials", get_materials},
                                              {"morph_weights", get_morph_weights},
                                              {"joint_matrices", get_joint_matrices},
                                              {"bounds", get_object_bounds},
                                              {"id", get_id}, {"energy", get_energy},
                                              {"stable_step", get_stable_step}, {"substeps", get_substeps},
                                              {"max_height", get_max_height}, {"depth", get_depth},
                                              {"grid", get_grid}, {NULL, NULL}};
    static const luaL_Reg object_setters[] = {{"position", set_position}, {"rotation", set_rotation},
                                              {"scale", set_scale}, {"visible", set_visible},
                                              {"cast_shadows", set_cast_shadows}, {"material", set_material},
                                              {"morph_weights", set_morph_weights}, {"deform", set_deform},
                                              {"joint_matrices", set_joint_matrices}, {NULL, NULL}};
    lutil_class(L, OBJECT_MT, "object", object_meta, object_methods, object_getters, object_setters);

    lua_pushcfunction(L, object_new);
    lua_setfield(L, -2, "object");
    lua_pushcfunction(L, water_new);
    lua_setfield(L, -2, "water");
    static const luaL_Reg deformers[] = {{"wave", deform_wave}, {"glsl", deform_glsl}, {NULL, NULL}};
    luaL_newlib(L, deformers);
    lua_setfield(L, -2, "deform");
}
