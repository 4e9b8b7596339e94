/* libFuzzer harness for the scene-script path (issue 9): the bytes are a
 * scene script, run sandboxed (1 s per call, 256 MB) to its first frame at
 * 16x16 on OSMesa. Any outcome but a sanitizer report or a crash is fine:
 * a clean error is the expected result for most inputs. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <unistd.h>

#include "app/app.h"
#include "app/session.h"
#include "fuzz_files.h"

static char dir[256];
static struct app app;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char out[320];
    if (!fuzz_private_dir("script", dir, sizeof dir))
        return 1;
    snprintf(out, sizeof out, "%s/out", dir);
    if (mkdir(out, 0700) != 0 && errno != EEXIST)
        return 1;
    app_init(&app);
    /* The seed scripts name assets as "scenes/assets/...": a link beside the
     * script to the project's scenes/ (readable to a sandboxed script). */
    char link[600], target[4200];
    snprintf(link, sizeof link, "%s/scenes", dir);
    snprintf(target, sizeof target, "%s/scenes", app.root);
    if (symlink(target, link) != 0 && errno != EEXIST)
        return 1;
    app.backend = GL_BACKEND_OSMESA;
    app.script_timeout = 1.0;
    app.script_memory = 256.0 * 1024 * 1024;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[320], out[320];
    snprintf(path, sizeof path, "%s/scene.lua", dir);
    snprintf(out, sizeof out, "%s/out", dir);
    if (!fuzz_write_file(path, data, size))
        return 0;
    struct session_options o = {.script = path, .width = 16, .height = 16, .write_dir = out};
    struct session *s;
    struct error err;
    if (!session_open(&app, &o, &s, &err))
        return 0;
    (void)session_render(s, 0, &err);
    session_close(s);
    return 0;
}
