/* libFuzzer harness for the glTF loading path (issue 9): the bytes become a
 * .glb (when they start with "glTF") or a .gltf file in a private folder,
 * which gltf_load, and the scene reading (gltf_file_scene, gltf_pose_at),
 * must refuse or load without a sanitizer report. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_files.h"
#include "io/gltf.h"
#include "scene/gltf_pose.h"

static char dir[256];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return fuzz_private_dir("gltf", dir, sizeof dir) ? 0 : 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[320];
    bool binary = size >= 4 && memcmp(data, "glTF", 4) == 0;
    snprintf(path, sizeof path, "%s/input.%s", dir, binary ? "glb" : "gltf");
    if (!fuzz_write_file(path, data, size))
        return 0;
    struct gltf_mesh m;
    struct error err;
    if (gltf_load(path, &m, &err))
        gltf_mesh_free(&m);
    /* the file as a scene (issue 51): its node tree, cameras, lights,
     * animations, each mesh on its own, and the pose at a few times */
    struct gltf_file *file;
    if (!gltf_file_open(path, &file, &err))
        return 0;
    for (int i = 0; i < gltf_file_mesh_count(file) && i < 8; i++)
        if (gltf_file_mesh(file, i, &m, &err))
            gltf_mesh_free(&m);
    struct gltf_scene scene;
    if (gltf_file_scene(file, NULL, -1, &scene, &err)) {
        struct gltf_pose pose;
        if (gltf_pose_init(&pose, &scene, &err)) {
            static const double times[] = {-1.0, 0.0, 0.37, 1.0, 1e9};
            float joints[GLTF_MAX_JOINTS * 16];
            for (int a = -1; a < scene.animation_count && a < 4; a++)
                for (size_t k = 0; k < sizeof times / sizeof *times; k++) {
                    gltf_pose_at(&pose, &scene, a, times[k]);
                    for (int s = 0; s < scene.skin_count && s < 4; s++)
                        gltf_pose_joint_matrices(&pose, &scene, s, joints);
                }
            gltf_pose_free(&pose);
        }
        gltf_scene_free(&scene);
    }
    gltf_file_close(file);
    return 0;
}
