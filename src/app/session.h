/* One scene script, loaded and run: its Lua state, scene, graph and
 * animation. Frame N is always the state after update() ran for frames
 * 0..N at the script's fixed time step, whichever verb asks for it. */
#ifndef CAUSTICA_SESSION_H
#define CAUSTICA_SESSION_H

#include <stdbool.h>
#include <stdint.h>

#include <lua.h>

#include "app/app.h"
#include "io/image.h"
#include "lua/lua_host.h"

struct session_options {
    const char *script;
    struct lua_params params;
    int width, height;       /* 0: the script's size */
    const char *write_dir;   /* where a sandboxed script may write */
    bool past_last_frame;    /* frames past the script's count are allowed (bench times still scenes over
                                several frames) */
    int frame_count;         /* --frame-count: the animation's length instead of the script's `frames` (0: its) */
    double fps;              /* --fps: frames a second instead of the script's (0: its) */
};

#define SESSION_MAX_AOVS 8

struct session {
    struct app *app;
    struct session_options options;
    char script[4096];
    lua_State *L;
    int result_ref;          /* the table the script returned */
    struct scene *scene;     /* borrowed from the Lua state */
    struct graph *graph;     /* borrowed from the Lua state */
    int update_ref;          /* LUA_NOREF when the script has no update */
    int frames;
    double fps;
    int width, height;
    float exposure;
    enum tonemap_operator tonemap;
    int advanced;            /* last frame update() ran for; -1 before any */
    bool linted;             /* graph_lint's warnings printed (once per session) */
    const char *aovs[8];     /* --aov pass.output: extra layers of an EXR output (borrowed from argv) */
    int aov_count;
    bool exr_half;           /* --half: an EXR output's own RGBA as half floats */
};

bool session_open(struct app *app, const struct session_options *options, struct session **out, struct error *err);
/* Whether a scene path is a glTF file (.gltf, .glb), which the session runs
 * through lua/caustica/gltf_scene.lua instead of as a script. */
bool session_is_gltf(const char *path);
void session_close(struct session *s);
/* Overrides a number parameter of a pass: "pass.param" = value (what
 * `caustica bench --sweep shadow.size=512,1024` does). Before rendering. */
/* "pass.param" = text: a number, true/false, an enum's choice or a string,
 * as the parameter's type says. */
bool session_set_pass_param(struct session *s, const char *key, const char *text, struct error *err);
/* Loads the script again from scratch (fresh Lua state, passes and caches). */
bool session_reload(struct session *s, struct error *err);
/* Runs update() up to `frame` (reloading the script to go back in time). */
bool session_goto_frame(struct session *s, int frame, struct error *err);
/* Renders `frame`: the graph's output texture holds linear radiance after. */
bool session_render(struct session *s, int frame, struct error *err);
bool session_read_linear(struct session *s, struct image *out, struct error *err);
/* Tone-mapped 8-bit sRGB, rows top to bottom (caller frees). */
bool session_read_srgb(struct session *s, uint8_t **rgba, struct error *err);
struct ref_options;
struct ref_stats;
/* The ground truth of `frame` at the session's size (src/reference). */
/* The EXR header of the frame last rendered (or traced): camera, frame, time, scene, renderer. */
void session_exr_info(const struct session *s, struct image_exr_info *info);
bool session_reference(struct session *s, int frame, const struct ref_options *options, struct image *out,
                       struct ref_stats *stats, struct error *err);
/* ... also giving the caustic part alone (`caustic` may be NULL). */
bool session_reference_parts(struct session *s, int frame, const struct ref_options *options, struct image *out,
                             struct image *caustic, struct ref_stats *stats, struct error *err);
/* The Lua host's render service (lua_render_service) for c.image.render
 * and c.image.reference; `context` is the app. */
bool session_render_service(void *context, const struct lua_render_request *request, struct image *out,
                            struct lua_render_reply *reply, struct error *err);
/* Writes the rendered frame: .png tone mapped, .pfm linear. */
bool session_write_image(struct session *s, const char *path, struct error *err);

#endif
