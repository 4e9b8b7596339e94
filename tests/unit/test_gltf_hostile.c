/* Hostile and careless glTF files (issue 9): each must be refused with a
 * message naming the file and the problem, never read out of bounds,
 * overflow the stack or grow without bound. The files are made here, in a
 * temporary folder, from one valid triangle. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "io/gltf.h"

static char dir[256];

/* A triangle: 3 VEC3 floats (36 bytes) and 3 uint16 indices (6 bytes + 2 padding). */
static const char *BUFFER =
    "{\"byteLength\": 44, \"uri\": \"data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=\"}";

/* Writes a glTF with the given parts (NULL: the valid default) and loads it. */
static bool load_parts(const char *name, const char *nodes, const char *accessors, const char *views,
                       const char *extra, const char *buffers, struct error *err)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.gltf", dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return false;
    fprintf(f,
            "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],\n"
            " \"nodes\": %s,\n"
            " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, \"material\": 0}]}],\n"
            " \"buffers\": [%s],\n"
            " \"bufferViews\": %s,\n"
            " \"accessors\": %s%s%s}\n",
            nodes ? nodes : "[{\"mesh\": 0}]", buffers ? buffers : BUFFER,
            views ? views
                  : "[{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 36}, "
                    "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}]",
            accessors ? accessors
                      : "[{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", "
                        "\"min\": [0,0,0], \"max\": [1,1,0]}, "
                        "{\"bufferView\": 1, \"componentType\": 5123, \"count\": 3, \"type\": \"SCALAR\"}]",
            extra ? ",\n " : "", extra ? extra : "");
    fclose(f);
    struct gltf_mesh m;
    bool ok = gltf_load(path, &m, err);
    if (ok)
        gltf_mesh_free(&m);
    return ok;
}

#define VALID_ACCESSOR0 \
    "{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"min\": [0,0,0], \"max\": [1,1,0]}"
#define VALID_ACCESSOR1 "{\"bufferView\": 1, \"componentType\": 5123, \"count\": 3, \"type\": \"SCALAR\"}"
#define MATERIAL(body) "\"materials\": [{\"name\": \"m\", " body "}]"

static void expect_refused(const char *name, const char *nodes, const char *accessors, const char *views,
                           const char *extra, const char *buffers, const char *part)
{
    struct error err;
    bool ok = load_parts(name, nodes, accessors, views, extra, buffers, &err);
    CHECK(!ok);
    if (!ok) {
        CHECK_CONTAINS(err.message, name);
        CHECK_CONTAINS(err.message, part);
    } else {
        fprintf(stderr, "  (%s was accepted)\n", name);
    }
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/caustica-gltf-hostile.%ld", (long)getpid());
    char cmd[512];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    if (system(cmd) != 0)
        return 1;
    struct error err;

    /* The valid triangle loads: the cases below differ from it in one place. */
    CHECK(load_parts("valid", NULL, NULL, NULL, MATERIAL("\"pbrMetallicRoughness\": {}"), NULL, &err));

    /* byteOffset near 2^64 wraps a size_t sum: heap read before the fix. */
    expect_refused("offset_wrap", NULL,
                   "[{\"bufferView\": 0, \"byteOffset\": 18446744073709549568, \"componentType\": 5126, \"count\": 3, "
                   "\"type\": \"VEC3\"}, " VALID_ACCESSOR1 "]",
                   NULL, NULL, NULL, "POSITION");
    expect_refused("view_offset_wrap", NULL, NULL,
                   "[{\"buffer\": 0, \"byteOffset\": 18446744073709549568, \"byteLength\": 4096}, "
                   "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}]",
                   NULL, NULL, "");
    /* A byteStride smaller than one element would read overlapping, past-the-view values. */
    /* Negative sparse offsets, float sparse indices. */
    expect_refused("sparse_negative", NULL,
                   "[{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", "
                   "\"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 1, \"byteOffset\": -8, \"componentType\": 5123}, "
                   "\"values\": {\"bufferView\": 0, \"componentType\": 5126}}}, " VALID_ACCESSOR1 "]",
                   NULL, NULL, NULL, "");
    expect_refused("sparse_float_indices", NULL,
                   "[{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", "
                   "\"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 0, \"componentType\": 5126}, "
                   "\"values\": {\"bufferView\": 0, \"componentType\": 5126}}}, " VALID_ACCESSOR1 "]",
                   NULL, NULL, NULL, "");
    /* A count asking for 16 GiB of zeros from a 1 KB file. */
    expect_refused("huge_count", NULL,
                   "[{\"componentType\": 5126, \"count\": 715827882, \"type\": \"VEC3\", "
                   "\"sparse\": {\"count\": 1, \"indices\": {\"bufferView\": 1, \"componentType\": 5123}, "
                   "\"values\": {\"bufferView\": 0, \"componentType\": 5126}}}, " VALID_ACCESSOR1 "]",
                   NULL, NULL, NULL, "larger than the file can describe");

    /* 10^5 levels of nesting: a stack overflow inside the JSON parser before. */
    {
        size_t depth = 100000;
        char *deep = malloc(depth * 2 + 64);
        size_t n = (size_t)sprintf(deep, "\"extras\": ");
        for (size_t i = 0; i < depth; i++)
            deep[n++] = '[';
        for (size_t i = 0; i < depth; i++)
            deep[n++] = ']';
        deep[n] = '\0';
        expect_refused("deep_json", NULL, NULL, NULL, deep, NULL, "nested deeper");
        free(deep);
    }

    /* Images are never decoded: a corrupt JPEG and an image view past the data load as plain meshes. */
    CHECK(load_parts("corrupt_jpeg", NULL, NULL, NULL,
                     "\"images\": [{\"uri\": \"data:image/jpeg;base64,/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAP//////////\"}]",
                     NULL, &err));
    {
        struct error e2;
        bool ok = load_parts("image_view_past_end", NULL, NULL,
                             "[{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 36}, "
                             "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}, "
                             "{\"buffer\": 0, \"byteOffset\": 40, \"byteLength\": 100000}]",
                             "\"images\": [{\"bufferView\": 2, \"mimeType\": \"image/png\"}]", NULL, &e2);
        (void)ok; /* refused by tinygltf or loaded without the image: either, without a crash */
        CHECK(1);
    }
    /* ... but a material's texture is read from its bufferView with bounds
     * checks (tinygltf hands the view over unchecked). */
    expect_refused("texture_view_past_end", NULL, NULL,
                   "[{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 36}, "
                   "{\"buffer\": 0, \"byteOffset\": 36, \"byteLength\": 6}, "
                   "{\"buffer\": 0, \"byteOffset\": 40, \"byteLength\": 100000}]",
                   "\"images\": [{\"bufferView\": 2, \"mimeType\": \"image/png\"}], \"textures\": [{\"source\": 0}], "
                   MATERIAL("\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}"),
                   NULL, "runs past the buffer");
    expect_refused("texture_no_source", NULL, NULL, NULL,
                   "\"textures\": [{\"source\": 7}], "
                   MATERIAL("\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}"),
                   NULL, "has no image");
    expect_refused("texture_transform_inf", NULL, NULL, NULL,
                   "\"images\": [{\"uri\": \"data:image/png;base64,AAAA\"}], \"textures\": [{\"source\": 0}], "
                   MATERIAL("\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0, \"extensions\": "
                            "{\"KHR_texture_transform\": {\"scale\": [1e300, 1]}}}}"),
                   NULL, "KHR_texture_transform");

    /* A DAG with fan-out: 25 nodes each listing the next twice = 2^24 visits. */
    {
        char nodes[4096];
        size_t n = (size_t)sprintf(nodes, "[");
        for (int i = 0; i < 24; i++)
            n += (size_t)sprintf(nodes + n, "{\"children\": [%d, %d]}, ", i + 1, i + 1);
        sprintf(nodes + n, "{\"mesh\": 0}]");
        expect_refused("fan_out", nodes, NULL, NULL, NULL, NULL, "expands to more than");
        /* Legal instancing stays legal: a node shared twice. */
        CHECK(load_parts("instanced", "[{\"children\": [1, 1]}, {\"mesh\": 0}]", NULL, NULL, NULL, NULL, &err));
    }

    /* Materials by the rules of c.material.glass. */
    expect_refused("attenuation_color", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1}, "
                            "\"KHR_materials_volume\": {\"attenuationColor\": [2, 1, 1], \"attenuationDistance\": 1}}"),
                   NULL, "attenuationColor");
    expect_refused("attenuation_distance", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1}, "
                            "\"KHR_materials_volume\": {\"attenuationColor\": [0.5, 1, 1], \"attenuationDistance\": 1e-40}}"),
                   NULL, "attenuationDistance");
    expect_refused("negative_ior", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1}, "
                            "\"KHR_materials_ior\": {\"ior\": -2}}"),
                   NULL, "ior");

    /* glTF's BRDF's inputs (issue 50): a specular weight outside [0, 1], a
     * specular colour that is negative or huge, an occlusion strength
     * outside [0, 1] would reach both renderers as NaN or energy from nowhere. */
    expect_refused("specular_factor", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_specular\": {\"specularFactor\": 1.5}}"), NULL,
                   "specularFactor must be in [0, 1]");
    expect_refused("specular_color", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_specular\": {\"specularColorFactor\": [1, -1, 1]}}"),
                   NULL, "specularColorFactor must be in [0, 1000]");
    expect_refused("specular_nan", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_specular\": {\"specularColorFactor\": [1, 1e39, 1]}}"),
                   NULL, "specularColorFactor");
    expect_refused("clearcoat_factor", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 2}}"), NULL,
                   "clearcoatFactor and clearcoatRoughnessFactor must be in [0, 1]");
    expect_refused("clearcoat_roughness", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1, "
                            "\"clearcoatRoughnessFactor\": -0.5}}"),
                   NULL, "clearcoatRoughnessFactor");
    expect_refused("clearcoat_texture", NULL, NULL, NULL,
                   MATERIAL("\"extensions\": {\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1, "
                            "\"clearcoatNormalTexture\": {\"index\": 7}}}"),
                   NULL, "texture index 7 is out of range");
    expect_refused("occlusion_strength", NULL, NULL, NULL,
                   MATERIAL("\"occlusionTexture\": {\"index\": 0, \"strength\": 2}"), NULL,
                   "occlusionTexture");

    /* A texture whose image file is missing: the error names the file
     * (it said "image 0 has no data"). */
    expect_refused("missing_image", NULL, NULL, NULL,
                   MATERIAL("\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}], "
                            "\"textures\": [{\"source\": 0}], \"images\": [{\"uri\": \"gone.png\""),
                   NULL, "image 0 'gone.png': cannot read it");

    /* A node scale of 1e300 makes finite file values Inf after the transform. */
    expect_refused("huge_scale", "[{\"mesh\": 0, \"scale\": [1e300, 1e300, 1e300]}]", NULL, NULL, NULL, NULL,
                   "not finite after its node transform");

    /* External files only from the glTF's own folder. */
    expect_refused("parent_buffer", NULL, NULL, NULL, NULL,
                   "{\"byteLength\": 44, \"uri\": \"../../../../../../../../etc/passwd\"}",
                   "outside the glTF file's folder");

    /* A folder named like a glTF file. */
    {
        char path[512];
        snprintf(path, sizeof path, "%s/folder.gltf", dir);
        snprintf(cmd, sizeof cmd, "mkdir -p %s", path);
        CHECK(system(cmd) == 0);
        struct gltf_mesh m;
        CHECK(!gltf_load(path, &m, &err));
        CHECK_CONTAINS(err.message, "folder.gltf");
    }

    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0)
        return 1;
    return check_finish("test_gltf_hostile");
}
