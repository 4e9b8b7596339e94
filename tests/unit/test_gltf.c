#define _DEFAULT_SOURCE /* mkstemps */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/gltf.h"
#include "scene/scene.h"

static char root[1024];

static const char *asset(const char *rel)
{
    static char path[2048];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    return path;
}

static bool unit_normals(const struct gltf_mesh *m)
{
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + i * 3;
        if (fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0f) > 1e-3f)
            return false;
    }
    return true;
}

int main(void)
{
    const char *env = getenv("CAUSTICA_ROOT");
    snprintf(root, sizeof root, "%s", env ? env : ".");
    struct gltf_mesh m;
    struct error err;

    /* 16-bit indices, normals in the file */
    CHECK(gltf_load(asset("scenes/assets/teapot.glb"), &m, &err));
    CHECK(m.index_count == 9438 * 3 && m.vertex_count == 4719);
    CHECK(unit_normals(&m));
    gltf_mesh_free(&m);

    /* 32-bit indices: the 800K-triangle dragon */
    CHECK(gltf_load(asset("scenes/assets/dragon_800k.glb"), &m, &err));
    CHECK(m.index_count == 804124u * 3);
    gltf_mesh_free(&m);

    /* morph targets: the dinosaur's "blob" */
    CHECK(gltf_load(asset("scenes/assets/dinosaur_morph.glb"), &m, &err));
    CHECK(m.target_count == 1);
    CHECK(m.weights[0] == 0.0f);
    CHECK(strcmp(m.target_names[0], "blob") == 0);
    gltf_mesh_free(&m);

    /* node transforms: AnimatedMorphCube's node scales by 100 and rotates */
    CHECK(gltf_load(asset("scenes/assets/khronos/AnimatedMorphCube/AnimatedMorphCube.glb"), &m, &err));
    CHECK(m.target_count == 2);
    float extent = 0;
    for (size_t i = 0; i < m.vertex_count * 3; i++)
        extent = fmaxf(extent, fabsf(m.positions[i]));
    CHECK(extent > 0.5f && extent < 2.0f); /* the raw cube is 0.01 across; the node scale of 100 was applied */
    CHECK(unit_normals(&m));
    gltf_mesh_free(&m);

    /* sparse accessors: SimpleSparseAccessor lifts some vertices by sparse substitution */
    CHECK(gltf_load(asset("scenes/assets/khronos/SimpleSparseAccessor/SimpleSparseAccessor.gltf"), &m, &err));
    float ymax = -1e30f;
    for (size_t i = 0; i < m.vertex_count; i++)
        ymax = fmaxf(ymax, m.positions[i * 3 + 1]);
    CHECK(ymax > 4.0f - 1e-4f); /* the base grid has y <= 1; the sparse values lift three vertices to 4 */
    CHECK(unit_normals(&m));   /* no NORMAL attribute: generated */
    gltf_mesh_free(&m);

    /* generated normals of a flat quad point along +Z */
    CHECK(gltf_load(asset("tests/data/quad_no_normals.gltf"), &m, &err));
    CHECK(m.vertex_count == 4);
    CHECK_NEAR(m.normals[2], 1.0, 1e-6);
    gltf_mesh_free(&m);

    /* KHR_materials_transmission / _ior / _volume become glass */
    CHECK(gltf_load(asset("tests/data/glass_material.gltf"), &m, &err));
    CHECK(m.material_count == 1 && m.range_count == 1 && m.ranges[0].material == 0);
    CHECK(m.materials[0].glass);
    CHECK_NEAR(m.materials[0].ior, 1.33, 1e-6);
    CHECK_NEAR(m.materials[0].attenuation_distance, 2.0, 1e-6);
    CHECK_NEAR(m.materials[0].attenuation_color[0], 0.5, 1e-6);
    gltf_mesh_free(&m);
    /* ... and a mesh loaded from it gives objects that glass, with sigma = -ln(c) / d */
    struct mesh *mesh = mesh_load_gltf(asset("tests/data/glass_material.gltf"), 0, &err);
    CHECK(mesh && mesh->has_material && mesh->material.kind == MATERIAL_GLASS);
    struct object *obj = object_create(mesh);
    CHECK(obj->material.kind == MATERIAL_GLASS);
    CHECK_NEAR(obj->material.ior, 1.33, 1e-6);
    CHECK_NEAR(obj->material.absorption.x, -log(0.5) / 2.0, 1e-5);
    CHECK_NEAR(obj->material.absorption.z, 0.0, 1e-6);
    object_destroy(obj);
    mesh_destroy(mesh);

    /* A material per primitive: one mesh of two primitives that share
     * vertices, glass and a red diffuse; the loader keeps both, the mesh
     * splits into two parts (each with the vertices it uses), an object of
     * it is a group of two parts, the scene holds the parts, and what the
     * file asks for and is not drawn is listed per material. */
    CHECK(gltf_load(asset("tests/data/two_materials.gltf"), &m, &err));
    CHECK(m.material_count == 2 && m.range_count == 2);
    if (m.range_count == 2) {
        CHECK(m.ranges[0].first_index == 0 && m.ranges[0].index_count == 3 && m.ranges[0].material == 0);
        CHECK(m.ranges[1].first_index == 3 && m.ranges[1].index_count == 3 && m.ranges[1].material == 1);
        CHECK(m.materials[1].alpha_mode == GLTF_ALPHA_MASK);
        /* KHR_materials_clearcoat is read (issue 50), not listed as unread */
        CHECK(strstr(m.materials[1].unread, "KHR_materials_clearcoat") == NULL);
        CHECK_NEAR(m.materials[1].clearcoat, 1.0, 1e-6);
        CHECK_NEAR(m.materials[1].clearcoat_roughness, 0.0, 1e-6);
    }
    gltf_mesh_free(&m);
    /* Vertex attributes nothing draws (TANGENT, a skin's joints) are
     * listed with the material of the primitive that has them (issue 50:
     * never dropped in silence), and COLOR_0 is read: the second primitive
     * given COLOR_0 and a skin's JOINTS_0 (the positions' accessor stands in
     * for both). TANGENT is read (issue 50): a VEC3 one is refused. */
    {
        FILE *in = fopen(asset("tests/data/two_materials.gltf"), "rb");
        static char text[65536];
        size_t n = in ? fread(text, 1, sizeof text - 1, in) : 0;
        if (in)
            fclose(in);
        text[n] = '\0';
        char *second = strstr(text, "\"indices\": 2");
        char *attrs = second ? strstr(second - 64 > text ? second - 64 : text, "\"POSITION\": 0") : NULL;
        CHECK(attrs != NULL);
        if (attrs) {
            char tmp[] = "/tmp/caustica-test-gltf-XXXXXX.gltf";
            int fd = mkstemps(tmp, 5);
            FILE *out = fd >= 0 ? fdopen(fd, "wb") : NULL;
            CHECK(out != NULL);
            if (out) {
                fwrite(text, 1, (size_t)(attrs - text), out);
                fputs("\"COLOR_0\": 0, \"JOINTS_0\": 0, ", out);
                fputs(attrs, out);
                fclose(out);
            }
            /* (its buffer is a data URI: the copy loads from anywhere) */
            CHECK(gltf_load(tmp, &m, &err));
            if (m.material_count == 2) {
                CHECK(strstr(m.materials[1].unread, "JOINTS_0") != NULL);
                CHECK(strstr(m.materials[0].unread, "JOINTS_0") == NULL);
            }
            /* COLOR_0 is read: white for the first primitive's vertices, the
             * positions (as colours, in [0, 1]) for the second's */
            CHECK(m.colors != NULL);
            if (m.colors && m.range_count == 2) {
                const uint32_t *idx = m.indices;
                const float *first = m.colors + (size_t)idx[m.ranges[0].first_index] * 4;
                CHECK(first[0] == 1.0f && first[1] == 1.0f && first[2] == 1.0f && first[3] == 1.0f);
                bool coloured = false;
                for (size_t i = m.ranges[1].first_index; i < m.ranges[1].first_index + m.ranges[1].index_count; i++) {
                    const float *c = m.colors + (size_t)idx[i] * 4;
                    coloured |= c[0] < 1.0f || c[1] < 1.0f || c[2] < 1.0f;
                    CHECK(c[3] == 1.0f && c[0] >= 0.0f && c[0] <= 1.0f);
                }
                CHECK(coloured);
            }
            gltf_mesh_free(&m);
            /* the same with a TANGENT of three components: refused, named */
            out = fopen(tmp, "wb");
            CHECK(out != NULL);
            if (out) {
                fwrite(text, 1, (size_t)(attrs - text), out);
                fputs("\"TANGENT\": 0, ", out);
                fputs(attrs, out);
                fclose(out);
            }
            CHECK(!gltf_load(tmp, &m, &err) && strstr(err.message, "TANGENT") && strstr(err.message, "VEC4"));
            remove(tmp);
        }
    }
    struct mesh *two = mesh_load_gltf(asset("tests/data/two_materials.gltf"), 0, &err);
    CHECK(two && two->part_count == 2);
    if (two && two->part_count == 2) {
        struct mesh *glass = two->parts[0], *label = two->parts[1];
        CHECK(glass->material.kind == MATERIAL_GLASS && label->material.kind == MATERIAL_DIFFUSE);
        CHECK_NEAR(glass->material.ior, 1.33, 1e-6);
        CHECK_NEAR(label->material.color.x, 0.9, 1e-6);
        CHECK(strcmp(glass->material_name, "Glass") == 0 && strcmp(label->material_name, "Label") == 0);
        CHECK(glass->vertex_count == 3 && glass->index_count == 3 && label->vertex_count == 3);
        /* the label's triangle 0, 2, 3 renumbered: its third vertex is (0, 1, 0) */
        CHECK_NEAR(label->positions[label->indices[2] * 3 + 1], 1.0, 1e-6);
        CHECK_NEAR(label->positions[label->indices[2] * 3 + 0], 0.0, 1e-6);
        CHECK_NEAR(glass->material.roughness, 0.5, 1e-6); /* rough transmission: drawn, not ignored */
        CHECK(strstr(glass->material.ignored, "roughness") == NULL);
        CHECK_NEAR(label->material.alpha_cutoff, 0.5, 1e-6); /* a diffuse MASK cuts out: not ignored */
        CHECK(strstr(label->material.ignored, "alphaMode") == NULL);
        CHECK(strstr(label->material.ignored, "clearcoat") == NULL); /* drawn: the label is glTF's BRDF */
        CHECK(label->material.pbr && label->material.clearcoat == 1.0f);
        struct object *group = object_create(two);
        CHECK(group && group->part_count == 2);
        struct scene scene;
        scene_init(&scene);
        CHECK(scene_object_add(&scene, group, &err));
        CHECK(scene.object_count == 2);
        CHECK(scene.object_count == 2 && scene.objects[0]->material.kind == MATERIAL_GLASS &&
              scene.objects[1]->material.kind == MATERIAL_DIFFUSE);
        group->position = vec3_make(1, 2, 3);
        group->version++;
        CHECK(object_sync_parts(group));
        CHECK_NEAR(scene.objects[1]->position.y, 2.0, 1e-6);
        CHECK(scene.objects[1]->version == group->version);
        scene_object_remove(&scene, group);
        CHECK(scene.object_count == 0);
        object_destroy(group);
        scene_release(&scene);
    }
    mesh_destroy(two);

    /* glTF's thin-walled glass (no KHR_materials_volume): material.thin,
     * its base colour texture, its MASK and its roughness 0 read, nothing
     * ignored (tests/data/pane.gltf, make_pane.py) */
    struct mesh *pane = mesh_load_gltf(asset("tests/data/pane.gltf"), 0, &err);
    CHECK(pane != NULL);
    if (pane) {
        const struct material *m = &pane->material;
        CHECK(m->kind == MATERIAL_GLASS && m->thin && material_role(m) == OBJECT_ROLE_THIN);
        CHECK(m->base_color.texture != NULL && m->alpha_cutoff == 0.5f && !m->alpha_blend);
        CHECK_NEAR(m->tint.x, 1.0, 1e-6);
        CHECK(m->ignored[0] == 0);
        mesh_destroy(pane);
    }

    /* textures: BoxTextured's PNG in the BIN chunk with its sampler, and an
     * external image with KHR_texture_transform */
    struct mesh *box = mesh_load_gltf(asset("scenes/assets/khronos/BoxTextured/BoxTextured.glb"), 0, &err);
    CHECK(box != NULL);
    if (box) {
        CHECK(box->texcoords[0] != NULL && box->texcoords[1] == NULL);
        CHECK(box->material.base_color.texture != NULL);
        if (box->material.base_color.texture)
            CHECK(box->material.base_color.texture->width == 256 && box->material.base_color.texture->height == 256);
        CHECK(box->material.normal.texture == NULL);
        mesh_destroy(box);
    }
    struct mesh *quad = mesh_load_gltf(asset("tests/data/transform_quad.gltf"), 0, &err);
    CHECK(quad != NULL);
    if (quad) {
        const struct texture_ref *ref = &quad->material.base_color;
        CHECK(ref->texture && ref->texture->nearest && !ref->texture->mipmaps);
        /* offset [0, 1], rotation pi/2, scale 0.5: uv (0, 0) -> (0, 1), (1, 1) -> (0.5, 0.5) */
        float uv[2] = {1, 1}, out[2];
        texture_ref_apply(ref, uv, out);
        CHECK_NEAR(out[0], 0.5, 1e-5);
        CHECK_NEAR(out[1], 0.5, 1e-5);
        mesh_destroy(quad);
    }

    /* bad input: errors that name the file, never a crash */
    CHECK(!gltf_load(asset("tests/data/bad_indices.gltf"), &m, &err));
    CHECK_CONTAINS(err.message, "bad_indices.gltf");
    CHECK_CONTAINS(err.message, "index 5 is out of range");
    CHECK(!gltf_load(asset("tests/data/nan_positions.gltf"), &m, &err));
    CHECK_CONTAINS(err.message, "non-finite");
    CHECK(!gltf_load(asset("tests/data/does_not_exist.glb"), &m, &err));
    CHECK_CONTAINS(err.message, "does_not_exist.glb");
    CHECK(m.positions == NULL);
    return check_finish("test_gltf");
}
