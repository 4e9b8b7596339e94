/* The GPU side of meshes and objects, owned by the renderer: vertex, index
 * and morph-target buffers per mesh, the Wyman baseline's per-vertex
 * thickness buffer, and per object the deformed (morphed, deformed or
 * simulated) vertex buffers and its VAO. Created and deleted here only; the
 * scene holds CPU data. Entries are keyed by the mesh's and object's serial
 * number (never reused), and an entry whose mesh or object is no longer in
 * the scene being rendered is released at the next frame's start. */
#ifndef CAUSTICA_MESH_CACHE_H
#define CAUSTICA_MESH_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "gl/gl_api.h"
#include "scene/scene.h"

struct gpu_mesh {
    uint64_t serial;
    GLuint positions, normals, indices, target_positions, target_normals;
    GLuint texcoords[2]; /* 0 where the mesh has no such set (attribute locations 2 and 3) */
    GLuint colors;       /* glTF's COLOR_0 (location 4), 0 where the mesh has none */
    GLuint tangents;     /* a normal map's tangents (location 5), 0 where the mesh has none */
    GLuint joints, joint_weights; /* a skin's JOINTS_0 and WEIGHTS_0 (deform.comp reads them), 0 without */
    GLuint thickness; /* d_N per vertex, uploaded on first use */
    bool used;        /* by the scene of the current frame */
};

struct gpu_object {
    uint64_t serial;
    GLuint deformed_positions, deformed_normals; /* 0 until the object animates its geometry */
    GLuint joint_matrices; /* a skinned object's joint matrices this frame, 0 until it has some */
    int joint_capacity;    /* how many it holds */
    size_t deformed_vertices;
    GLuint vao;
    GLuint vao_positions; /* which position buffer the VAO reads */
    bool used;
};

struct mesh_cache {
    struct gpu_mesh *meshes;
    int mesh_count, mesh_capacity;
    struct gpu_object *objects;
    int object_count, object_capacity;
};

void mesh_cache_init(struct mesh_cache *c);
void mesh_cache_release(struct mesh_cache *c);
/* Marks what `scene` uses and releases the rest; uploads every object's
 * mesh. Called by renderer_begin_frame. */
bool mesh_cache_begin_frame(struct mesh_cache *c, const struct scene *scene, struct error *err);
/* The mesh's buffers (uploaded if need be). */
struct gpu_mesh *mesh_cache_mesh(struct mesh_cache *c, const struct mesh *mesh, struct error *err);
/* The object's entry (NULL only when out of memory). */
struct gpu_object *mesh_cache_object(struct mesh_cache *c, const struct object *object, struct error *err);
/* Deformed buffers sized for the object's mesh; *created says they are new
 * (contents undefined: a water surface must fill them again). */
bool mesh_cache_deformed(struct mesh_cache *c, const struct object *object, struct gpu_object **out, bool *created,
                         struct error *err);
/* The mesh's thickness buffer from mesh->thickness (mesh_compute_thickness first). */
bool mesh_cache_thickness(struct mesh_cache *c, const struct mesh *mesh, GLuint *out, struct error *err);
/* Binds the object's VAO: its deformed buffers when it animates, else its mesh's. */
bool mesh_cache_bind(struct mesh_cache *c, const struct object *object, struct error *err);

#endif
