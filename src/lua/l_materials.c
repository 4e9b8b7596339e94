/* `mesh.materials` and `object.materials`: the materials of a file's
 * parts (one per material its primitives name, scene/mesh_gltf.c), read
 * and replaced by index or by the file's material name:
 *
 *   local m = c.mesh.load("glass_of_water.glb")
 *   m.materials.Water = c.material.water { absorption = {0.2, 0.1, 0.05} }
 *   local o = c.object { mesh = m }  -- made after: takes the mesh's materials
 *   o.materials[1] = c.material.glass { ior = 1.52 } -- this object only
 *
 * A mesh of one material (or a procedural one) lists that one. A material
 * read is a copy; an assignment copies the material in. */
#include <stdio.h>
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"

#define MATERIALS_MT "caustica.Materials"

/* The owner (mesh or object userdata) is the proxy's user value. */
struct l_materials {
    bool object;
};

struct slots {
    int count;
    struct mesh *mesh;     /* a mesh's list: its parts (or itself) */
    struct object *object; /* an object's list: its parts (or itself) */
};

static struct slots owner_slots(lua_State *L, int proxy)
{
    struct l_materials *u = luaL_checkudata(L, proxy, MATERIALS_MT);
    lua_getiuservalue(L, proxy, 1);
    struct slots s = {0};
    if (u->object) {
        s.object = lobject_check(L, -1);
        s.count = s.object->part_count > 0 ? s.object->part_count : 1;
    } else {
        s.mesh = lmesh_check(L, -1);
        s.count = s.mesh->part_count > 0 ? s.mesh->part_count : 1;
    }
    lua_pop(L, 1);
    return s;
}

/* The file's name of slot i's material ("" when it had none). */
static const char *slot_name(const struct slots *s, int i)
{
    const struct mesh *m = s->mesh ? s->mesh : s->object->mesh;
    return m->part_count > 0 ? m->parts[i]->material_name : m->material_name;
}

/* The slot a key names (an index from 1, or a material name), or a Lua
 * error that lists what there is. */
static int slot_of(lua_State *L, const struct slots *s, int key)
{
    if (lua_type(L, key) == LUA_TNUMBER) {
        lua_Integer i = lua_tointeger(L, key);
        if (!lua_isinteger(L, key) || i < 1 || i > s->count)
            return luaL_error(L, "materials[%s]: there %s %d (index 1 to %d, or a material's name)",
                              lua_tostring(L, key), s->count == 1 ? "is" : "are", s->count, s->count);
        return (int)i - 1;
    }
    if (lua_type(L, key) == LUA_TSTRING) {
        const char *name = lua_tostring(L, key);
        for (int i = 0; i < s->count; i++)
            if (strcmp(slot_name(s, i), name) == 0)
                return i;
        char names[400] = "";
        size_t used = 0;
        for (int i = 0; i < s->count && used < sizeof names; i++) {
            int w = snprintf(names + used, sizeof names - used, "%s'%s'", i ? ", " : "", slot_name(s, i));
            used += w > 0 ? (size_t)w : 0;
        }
        return luaL_error(L, "materials['%s']: no material of that name (the file's are %s)", name, names);
    }
    return luaL_argerror(L, 2, "materials: expected an index (integer) or a material's name (string)");
}

static struct material *slot_material(const struct slots *s, int i)
{
    if (s->object)
        return s->object->part_count > 0 ? &s->object->parts[i]->material : &s->object->material;
    return s->mesh->part_count > 0 ? &s->mesh->parts[i]->material : &s->mesh->material;
}

static int materials_index(lua_State *L)
{
    struct slots s = owner_slots(L, 1);
    lmaterial_push(L, slot_material(&s, slot_of(L, &s, 2)));
    return 1;
}

static int materials_newindex(lua_State *L)
{
    struct slots s = owner_slots(L, 1);
    int i = slot_of(L, &s, 2);
    const struct material *m = luaL_testudata(L, 3, MATERIAL_MT);
    if (!m)
        return luaL_argerror(L, 3, "materials: expected a material (c.material.*)");
    material_assign(slot_material(&s, i), m);
    if (s.object) {
        struct object *o = s.object->part_count > 0 ? s.object->parts[i] : s.object;
        o->version++;
        s.object->version++;
    } else {
        struct mesh *part = s.mesh->part_count > 0 ? s.mesh->parts[i] : s.mesh;
        part->has_material = true;
    }
    return 0;
}

static int materials_len(lua_State *L)
{
    lua_pushinteger(L, owner_slots(L, 1).count);
    return 1;
}

static int materials_tostring(lua_State *L)
{
    struct slots s = owner_slots(L, 1);
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    luaL_addstring(&b, "Materials(");
    for (int i = 0; i < s.count; i++) {
        const struct material *m = slot_material(&s, i);
        if (i)
            luaL_addstring(&b, ", ");
        lua_pushfstring(L, "%s%s%s", slot_name(&s, i), slot_name(&s, i)[0] ? ": " : "", material_kind_name(m->kind));
        luaL_addvalue(&b);
    }
    luaL_addstring(&b, ")");
    luaL_pushresult(&b);
    return 1;
}

void lmaterials_push(lua_State *L, int owner, bool object)
{
    owner = lua_absindex(L, owner);
    struct l_materials *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->object = object;
    luaL_setmetatable(L, MATERIALS_MT);
    lua_pushvalue(L, owner);
    lua_setiuservalue(L, -2, 1);
}

void lmaterials_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__index", materials_index}, {"__newindex", materials_newindex},
                                    {"__len", materials_len}, {"__tostring", materials_tostring},
                                    {NULL, NULL}};
    luaL_newmetatable(L, MATERIALS_MT);
    luaL_setfuncs(L, meta, 0);
    lua_pushstring(L, MATERIALS_MT);
    lua_setfield(L, -2, "__metatable");
    lua_pop(L, 1);
}
