#include "graph/mesh_cache.h"

#include <stdlib.h>

#include "core/array.h"
#include <string.h>

#include "gl/gl_buffer.h"

void mesh_cache_init(struct mesh_cache *c) { memset(c, 0, sizeof *c); }

static void release_mesh(struct gpu_mesh *g)
{
    gl_buffer_destroy(&g->positions);
    gl_buffer_destroy(&g->normals);
    gl_buffer_destroy(&g->indices);
    gl_buffer_destroy(&g->target_positions);
    gl_buffer_destroy(&g->target_normals);
    gl_buffer_destroy(&g->thickness);
    gl_buffer_destroy(&g->texcoords[0]);
    gl_buffer_destroy(&g->texcoords[1]);
    gl_buffer_destroy(&g->colors);
    gl_buffer_destroy(&g->tangents);
    gl_buffer_destroy(&g->joints);
    gl_buffer_destroy(&g->joint_weights);
}

static void release_object(struct gpu_object *g)
{
    gl_buffer_destroy(&g->deformed_positions);
    gl_buffer_destroy(&g->deformed_normals);
    gl_buffer_destroy(&g->joint_matrices);
    if (g->vao && gl_api_ready())
        gl.DeleteVertexArrays(1, &g->vao);
    g->vao = 0;
}

void mesh_cache_release(struct mesh_cache *c)
{
    for (int i = 0; i < c->mesh_count; i++)
        release_mesh(&c->meshes[i]);
    for (int i = 0; i < c->object_count; i++)
        release_object(&c->objects[i]);
    free(c->meshes);
    free(c->objects);
    mesh_cache_init(c);
}


static struct gpu_mesh *find_mesh(struct mesh_cache *c, uint64_t serial)
{
    for (int i = 0; i < c->mesh_count; i++)
        if (c->meshes[i].serial == serial)
            return &c->meshes[i];
    return NULL;
}

static struct gpu_object *find_object(struct mesh_cache *c, uint64_t serial)
{
    for (int i = 0; i < c->object_count; i++)
        if (c->objects[i].serial == serial)
            return &c->objects[i];
    return NULL;
}

struct gpu_mesh *mesh_cache_mesh(struct mesh_cache *c, const struct mesh *m, struct error *err)
{
    struct gpu_mesh *g = find_mesh(c, m->serial);
    if (g)
        return g;
    if (!array_grow((void **)&c->meshes, &c->mesh_capacity, c->mesh_count, sizeof *c->meshes, err))
        return NULL;
    g = &c->meshes[c->mesh_count];
    memset(g, 0, sizeof *g);
    g->serial = m->serial;
    size_t vbytes = m->vertex_count * 3 * sizeof(float);
    bool ok = gl_buffer_create(&g->positions, m->positions, vbytes, 0, err) &&
              gl_buffer_create(&g->normals, m->normals, vbytes, 0, err) &&
              gl_buffer_create(&g->indices, m->indices, m->index_count * sizeof(uint32_t), 0, err);
    for (int set = 0; set < 2 && ok; set++)
        if (m->texcoords[set])
            ok = gl_buffer_create(&g->texcoords[set], m->texcoords[set], m->vertex_count * 2 * sizeof(float), 0, err);
    if (ok && m->colors)
        ok = gl_buffer_create(&g->colors, m->colors, m->vertex_count * 4 * sizeof(float), 0, err);
    if (ok && m->tangents)
        ok = gl_buffer_create(&g->tangents, m->tangents, m->vertex_count * 4 * sizeof(float), 0, err);
    if (ok && m->joints)
        ok = gl_buffer_create(&g->joints, m->joints, m->vertex_count * 4 * sizeof(float), 0, err) &&
             gl_buffer_create(&g->joint_weights, m->joint_weights, m->vertex_count * 4 * sizeof(float), 0, err);
    if (ok && m->target_count > 0)
        ok = gl_buffer_create(&g->target_positions, m->target_positions, vbytes * (size_t)m->target_count, 0, err) &&
             gl_buffer_create(&g->target_normals, m->target_normals, vbytes * (size_t)m->target_count, 0, err);
    if (!ok) {
        release_mesh(g);
        error_prefix(err, "%s", m->name);
        return NULL;
    }
    c->mesh_count++;
    return g;
}

struct gpu_object *mesh_cache_object(struct mesh_cache *c, const struct object *o, struct error *err)
{
    struct gpu_object *g = find_object(c, o->serial);
    if (g)
        return g;
    if (!array_grow((void **)&c->objects, &c->object_capacity, c->object_count, sizeof *c->objects, err))
        return NULL;
    g = &c->objects[c->object_count++];
    memset(g, 0, sizeof *g);
    g->serial = o->serial;
    return g;
}

bool mesh_cache_begin_frame(struct mesh_cache *c, const struct scene *scene, struct error *err)
{
    for (int i = 0; i < c->mesh_count; i++)
        c->meshes[i].used = false;
    for (int i = 0; i < c->object_count; i++)
        c->objects[i].used = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        struct gpu_mesh *m = mesh_cache_mesh(c, o->mesh, err);
        if (!m)
            return false;
        m->used = true;
        struct gpu_object *g = find_object(c, o->serial);
        if (g)
            g->used = true;
    }
    /* Release what this scene does not use (a removed object, the meshes
     * of a script that was reloaded): serials are never reused, so such an
     * entry could only leak. */
    int kept = 0;
    for (int i = 0; i < c->mesh_count; i++) {
        if (c->meshes[i].used)
            c->meshes[kept++] = c->meshes[i];
        else
            release_mesh(&c->meshes[i]);
    }
    c->mesh_count = kept;
    kept = 0;
    for (int i = 0; i < c->object_count; i++) {
        if (c->objects[i].used)
            c->objects[kept++] = c->objects[i];
        else
            release_object(&c->objects[i]);
    }
    c->object_count = kept;
    return true;
}

bool mesh_cache_deformed(struct mesh_cache *c, const struct object *o, struct gpu_object **out, bool *created,
                         struct error *err)
{
    *created = false;
    struct gpu_object *g = mesh_cache_object(c, o, err);
    if (!g)
        return false;
    g->used = true;
    *out = g;
    size_t n = o->mesh->vertex_count;
    if (g->deformed_positions && g->deformed_vertices == n)
        return true;
    gl_buffer_destroy(&g->deformed_positions);
    gl_buffer_destroy(&g->deformed_normals);
    g->deformed_vertices = 0;
    g->vao_positions = 0; /* rebind the VAO */
    if (!gl_buffer_create(&g->deformed_positions, NULL, n * 3 * sizeof(float), GL_DYNAMIC_STORAGE_BIT, err) ||
        !gl_buffer_create(&g->deformed_normals, NULL, n * 3 * sizeof(float), GL_DYNAMIC_STORAGE_BIT, err))
        return error_prefix(err, "deformed vertex buffers");
    g->deformed_vertices = n;
    *created = true;
    return true;
}

bool mesh_cache_thickness(struct mesh_cache *c, const struct mesh *m, GLuint *out, struct error *err)
{
    struct gpu_mesh *g = mesh_cache_mesh(c, m, err);
    if (!g)
        return false;
    if (!g->thickness && !gl_buffer_create(&g->thickness, m->thickness, m->vertex_count * sizeof(float), 0, err))
        return false;
    *out = g->thickness;
    return true;
}

bool mesh_cache_bind(struct mesh_cache *c, const struct object *o, struct error *err)
{
    struct gpu_mesh *m = mesh_cache_mesh(c, o->mesh, err);
    struct gpu_object *g = m ? mesh_cache_object(c, o, err) : NULL;
    if (!g)
        return false;
    bool deformed = g->deformed_positions != 0 && object_is_animated_geometry(o);
    GLuint pos = deformed ? g->deformed_positions : m->positions;
    GLuint nrm = deformed ? g->deformed_normals : m->normals;
    if (!g->vao) {
        gl.CreateVertexArrays(1, &g->vao);
        gl.EnableVertexArrayAttrib(g->vao, 0);
        gl.EnableVertexArrayAttrib(g->vao, 1);
        gl.VertexArrayAttribFormat(g->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribFormat(g->vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribBinding(g->vao, 0, 0);
        gl.VertexArrayAttribBinding(g->vao, 1, 1);
        /* Texture coordinates never animate: the mesh's own buffers. A
         * set the mesh lacks stays disabled and reads (0, 0). */
        for (GLuint set = 0; set < 2; set++) {
            if (!m->texcoords[set])
                continue;
            gl.EnableVertexArrayAttrib(g->vao, 2 + set);
            gl.VertexArrayAttribFormat(g->vao, 2 + set, 2, GL_FLOAT, GL_FALSE, 0);
            gl.VertexArrayAttribBinding(g->vao, 2 + set, 2 + set);
            gl.VertexArrayVertexBuffer(g->vao, 2 + set, m->texcoords[set], 0, 2 * sizeof(float));
        }
        /* COLOR_0 (location 4): a mesh without it leaves it disabled, and
         * u_vertex_colors tells the shader to read white */
        if (m->colors) {
            gl.EnableVertexArrayAttrib(g->vao, 4);
            gl.VertexArrayAttribFormat(g->vao, 4, 4, GL_FLOAT, GL_FALSE, 0);
            gl.VertexArrayAttribBinding(g->vao, 4, 4);
            gl.VertexArrayVertexBuffer(g->vao, 4, m->colors, 0, 4 * sizeof(float));
        }
        /* tangents (location 5): disabled without them (u_has_tangents 0) */
        if (m->tangents) {
            gl.EnableVertexArrayAttrib(g->vao, 5);
            gl.VertexArrayAttribFormat(g->vao, 5, 4, GL_FLOAT, GL_FALSE, 0);
            gl.VertexArrayAttribBinding(g->vao, 5, 5);
            gl.VertexArrayVertexBuffer(g->vao, 5, m->tangents, 0, 4 * sizeof(float));
        }
    }
    if (g->vao_positions != pos) {
        gl.VertexArrayVertexBuffer(g->vao, 0, pos, 0, 3 * sizeof(float));
        gl.VertexArrayVertexBuffer(g->vao, 1, nrm, 0, 3 * sizeof(float));
        gl.VertexArrayElementBuffer(g->vao, m->indices);
        g->vao_positions = pos;
    }
    gl.BindVertexArray(g->vao);
    return true;
}
