/* What the scene bindings (l_scene.c, l_object.c, l_light.c, l_material.c,
 * l_medium.c) share: the userdata types and their metatable names, the
 * checks, and each file's registration into the caustica.scene module. */
#ifndef CAUSTICA_L_SCENE_H
#define CAUSTICA_L_SCENE_H

#include <stdbool.h>

#include <lauxlib.h>
#include <lua.h>

#include "scene/scene.h"

#define MESH_MT "caustica.Mesh"
#define MATERIAL_MT "caustica.Material"
#define OBJECT_MT "caustica.Object"
#define LIGHT_MT "caustica.Light"
#define CAMERA_MT "caustica.Camera"
#define ENVIRONMENT_MT "caustica.Environment"
#define DEFORMER_MT "caustica.Deformer"
#define SCENE_MT "caustica.Scene"
#define MEDIUM_MT "caustica.Medium"
#define TEXTURE_MT "caustica.Texture" /* userdata: struct l_texture (l_texture.c) */

struct l_mesh {
    struct mesh *mesh;
    size_t charged; /* bytes counted against --script-memory while the script holds it */
};
struct l_object { struct object *obj; };
struct l_light { struct light *light; };
struct l_environment { struct environment *env; };
struct l_medium { struct medium *medium; };

/* luaL_argerror for a userdata whose __gc already ran (a trusted script can
 * reach __gc through debug): an error, never a NULL dereference. */
int lscene_released(lua_State *L, int idx, const char *what);
struct mesh *lmesh_check(lua_State *L, int idx);
/* Pushes m as a mesh value, charged against --script-memory (its arrays
 * and textures); m NULL or over the limit: the error, raised. */
int lmesh_push(lua_State *L, struct mesh *m, struct error *err);
/* Refuses (an error) a procedural mesh of this size that --script-memory
 * cannot hold, before it is made. */
void lmesh_check_planned(lua_State *L, const char *fn, size_t vertices, size_t indices);
struct object *lobject_check(lua_State *L, int idx);
struct light *llight_check(lua_State *L, int idx);
/* NULL when the value is something else (or released). */
struct object *lobject_test(lua_State *L, int idx);
struct light *llight_test(lua_State *L, int idx);
/* A copy of `m` as a new material userdata. */
void lmaterial_push(lua_State *L, const struct material *m);

/* Pushes the `materials` list of the mesh (object = false) or object at
 * `owner` (l_materials.c). */
void lmaterials_push(lua_State *L, int owner, bool object);
void lmaterials_open(lua_State *L);
/* Each file's classes and constructors, into the module table at the top. */
void lobject_open(lua_State *L);
void llight_open(lua_State *L);
void lmaterial_open(lua_State *L);
void lmedium_open(lua_State *L);
void ltexture_open(lua_State *L);
void lgltf_open(lua_State *L);
void lmesh_open(lua_State *L);
/* The texture reference of a Texture value, or NULL when it is something else. */
const struct texture_ref *ltexture_test(lua_State *L, int idx);
/* Pushes a Texture value for a reference a material holds (retained; not
 * charged again: the value that made the texture was). */
void ltexture_push_ref(lua_State *L, const struct texture_ref *ref);

#endif
