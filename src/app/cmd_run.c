/* `caustica run`: the scene in a window (GLFW). Left-drag orbits the camera
 * around its target, the wheel zooms; the script and shaders reload when
 * their files change, and a broken edit keeps the last good frame. With
 * --frames N --screenshot OUT.png it renders N frames, saves what the
 * window shows and exits, so it can be tested under xvfb-run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/cli.h"
#include "core/fileio.h"
#include "core/log.h"
#include "graph/graph.h"

struct orbit {
    bool active, dragging;
    double last_x, last_y;
    float yaw, pitch, zoom; /* offsets from the script's camera */
};

static struct orbit orbit_state = {.zoom = 1.0f};

static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    orbit_state.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &orbit_state.last_x, &orbit_state.last_y);
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    (void)w;
    if (!orbit_state.dragging)
        return;
    orbit_state.yaw -= (float)(x - orbit_state.last_x) * 0.01f;
    orbit_state.pitch += (float)(y - orbit_state.last_y) * 0.01f;
    orbit_state.pitch = fminf(fmaxf(orbit_state.pitch, -1.4f), 1.4f);
    orbit_state.last_x = x;
    orbit_state.last_y = y;
    orbit_state.active = true;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)w;
    (void)dx;
    orbit_state.zoom *= powf(0.9f, (float)dy);
    orbit_state.zoom = fminf(fmaxf(orbit_state.zoom, 0.05f), 20.0f);
    orbit_state.active = true;
}

/* The script's camera turned by the mouse: yaw about +Y, pitch about the
 * camera's right axis, distance scaled by zoom. */
/* The keyboard: space pauses, left/right step one frame (and pause), s
 * writes a screenshot into the current folder, r reloads the script. Keys are
 * queued by the callback (or by --keys, scripted input for tests) and
 * handled once per frame. */
enum run_key { KEY_PAUSE, KEY_BACK, KEY_FORWARD, KEY_SCREENSHOT, KEY_RELOAD };
static struct {
    enum run_key queue[64];
    int count;
} keys;

static void push_key(enum run_key k)
{
    if (keys.count < (int)(sizeof keys.queue / sizeof keys.queue[0]))
        keys.queue[keys.count++] = k;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)w;
    (void)scancode;
    (void)mods;
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    switch (key) {
    case GLFW_KEY_SPACE: push_key(KEY_PAUSE); break;
    case GLFW_KEY_LEFT: push_key(KEY_BACK); break;
    case GLFW_KEY_RIGHT: push_key(KEY_FORWARD); break;
    case GLFW_KEY_S: push_key(KEY_SCREENSHOT); break;
    case GLFW_KEY_R: push_key(KEY_RELOAD); break;
    default: break;
    }
}

/* --keys space,right,s,...: false with the bad name. */
static bool parse_keys(const char *list, char *bad, size_t size)
{
    static const char *const names[] = {"space", "left", "right", "s", "r"};
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        bool found = false;
        for (int k = 0; k < 5 && !found; k++)
            if (strlen(names[k]) == n && strncmp(p, names[k], n) == 0) {
                push_key((enum run_key)k);
                found = true;
            }
        if (!found) {
            snprintf(bad, size, "%.*s", (int)n, p);
            return false;
        }
        p += n;
        if (*p == ',')
            p++;
    }
    return true;
}

/* The screenshot's path: in the folder `run` was started from (not next
 * to the script: a shipped scene lives in the install prefix), named by
 * the script and the frame. */
static void screenshot_path(const char *script, int frame, char *out, size_t size)
{
    const char *slash = strrchr(script, '/');
    const char *base = slash ? slash + 1 : script;
    const char *dot = strrchr(base, '.');
    int stem = dot ? (int)(dot - base) : (int)strlen(base);
    snprintf(out, size, "%.*s_frame_%04d.png", stem, base, frame);
}

static void apply_orbit(struct scene *scene)
{
    if (!orbit_state.active)
        return;
    struct camera *c = &scene->camera;
    vec3 off = vec3_sub(c->eye, c->target);
    float dist = vec3_length(off) * orbit_state.zoom;
    float yaw = atan2f(off.x, off.z) + orbit_state.yaw;
    float pitch = asinf(fminf(fmaxf(math_safe_div(off.y, vec3_length(off), 0.0f), -1.0f), 1.0f)) + orbit_state.pitch;
    pitch = fminf(fmaxf(pitch, -1.5f), 1.5f);
    c->eye = vec3_add(c->target, vec3_make(dist * cosf(pitch) * sinf(yaw), dist * sinf(pitch), dist * cosf(pitch) * cosf(yaw)));
    c->version++;
}

static bool save_window(int w, int h, const char *path, struct error *err)
{
    uint8_t *buf = malloc((size_t)w * (size_t)h * 4);
    uint8_t *flipped = malloc((size_t)w * (size_t)h * 4);
    if (!buf || !flipped) {
        free(buf);
        free(flipped);
        return error_set(err, "out of memory");
    }
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, buf);
    for (int y = 0; y < h; y++)
        memcpy(flipped + (size_t)y * (size_t)w * 4, buf + (size_t)(h - 1 - y) * (size_t)w * 4, (size_t)w * 4);
    bool ok = image_write_png_rgba8(path, flipped, w, h, err);
    free(buf);
    free(flipped);
    return ok;
}

/* The keys pressed since the last frame: pause, a frame back or forward
 * (pausing), a screenshot, a reload. */
static void take_keys(const struct session *s, bool *paused, double *clock, bool *reload, bool *screenshot)
{
    int current = (int)floor(*clock * s->fps + 1e-6);
    for (int k = 0; k < keys.count; k++) {
        switch (keys.queue[k]) {
        case KEY_PAUSE: *paused = !*paused; break;
        case KEY_BACK: *paused = true; current--; break;
        case KEY_FORWARD: *paused = true; current++; break;
        case KEY_SCREENSHOT: *screenshot = true; break;
        case KEY_RELOAD: *reload = true; break;
        }
        if (keys.queue[k] == KEY_BACK || keys.queue[k] == KEY_FORWARD)
            *clock = ((current % s->frames + s->frames) % s->frames) / s->fps;
    }
    keys.count = 0;
}

/* Live reload (a changed script, or r), then shaders. A failure keeps the
 * last good state. */
static void reload_changed(struct app *app, const struct session_options *o, struct session **s,
                           long long *script_mtime, bool reload)
{
    struct error err;
    long long mt = file_mtime_ns((*s)->script);
    if (mt != *script_mtime || reload) {
        *script_mtime = mt;
        struct session *fresh;
        if (session_open(app, o, &fresh, &err)) {
            session_close(*s);
            *s = fresh;
            fprintf(stderr, "caustica: reloaded %s\n", (*s)->script);
        } else {
            cli_print_error(&err);
        }
    }
    bool reloaded;
    if (!gl_program_cache_reload_changed(&app->renderer.programs, &reloaded, &err))
        cli_print_error(&err);
    else if (reloaded)
        fprintf(stderr, "caustica: reloaded shaders\n");
}

int cmd_run(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: run needs one scene script\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    struct error err;
    char bad[64];
    keys.count = 0;
    if (cli->keys && !parse_keys(cli->keys, bad, sizeof bad)) {
        fprintf(stderr, "caustica: --keys: unknown key '%s' (space, left, right, s or r)\n", bad);
        return EXIT_USAGE;
    }
    if (cli->screenshot && !path_check_writable_dir(cli->screenshot, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    struct session_options o = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                .height = cli->height, .frame_count = cli->frame_count,
                                .fps = cli->fps};
    /* The script is read before the window opens, to size the window. */
    struct session *s;
    app->backend = GL_BACKEND_GLFW;
    if (!session_open(app, &o, &s, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    app->window_width = s->width;
    app->window_height = s->height;
    if (!app_ensure_gl(app, &err)) {
        session_close(s);
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    GLFWwindow *window = app->gl->window;
    glfwSetMouseButtonCallback(window, on_mouse_button);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetScrollCallback(window, on_scroll);
    glfwSetKeyCallback(window, on_key);
    if (cli->screenshot)
        glfwSwapInterval(0);
    long long script_mtime = file_mtime_ns(s->script);
    int limit = cli->frames_set ? cli->frames_to + 1 : -1;
    int frame = 0, shown = 0;
    bool ok = true, have_frame = false, paused = false;
    /* the animation's clock: real time while playing, held while paused */
    double clock = 0.0, last = log_now(), fps_time = last;
    int fps_frames = 0;
    double fps = 0.0;
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        double now = log_now();
        if (!paused && limit <= 0)
            clock += now - last;
        last = now;
        bool reload = false, screenshot = false;
        take_keys(s, &paused, &clock, &reload, &screenshot);
        reload_changed(app, &o, &s, &script_mtime, reload);
        /* --frames N steps frame by frame, looping as playback does (a still
         * shows its one frame N times) */
        int want = limit > 0 && !paused && clock == 0.0 ? frame % s->frames
                                                        : (int)floor(clock * s->fps + 1e-6) % s->frames;
        if (session_goto_frame(s, want, &err)) {
            apply_orbit(s->scene);
            if (session_render(s, want, &err))
                have_frame = true;
            else
                cli_print_error(&err);
        } else {
            cli_print_error(&err);
        }
        int fw, fh;
        glfwGetFramebufferSize(window, &fw, &fh);
        struct graph_resource *res = graph_output(s->graph);
        if (have_frame && res && !renderer_present_window(&app->renderer, &res->texture, s->exposure, s->tonemap, fw, fh, &err))
            cli_print_error(&err);
        if (screenshot && have_frame) {
            char path[4200];
            screenshot_path(s->script, want, path, sizeof path);
            if (save_window(fw, fh, path, &err))
                fprintf(stderr, "caustica: wrote %s\n", path);
            else
                cli_print_error(&err);
        }
        /* the title: the script, the frame and the frame rate */
        fps_frames++;
        if (now - fps_time >= 0.5) {
            fps = fps_frames / (now - fps_time);
            fps_frames = 0;
            fps_time = now;
        }
        char title[600];
        snprintf(title, sizeof title, "caustica: %.400s, frame %d/%d%s, %.1f fps", s->script, want, s->frames,
                 paused ? " (paused)" : "", fps);
        glfwSetWindowTitle(window, title);
        shown++;
        frame++;
        if (limit > 0 && frame >= limit) {
            if (cli->screenshot)
                ok = save_window(fw, fh, cli->screenshot, &err);
            glfwSwapBuffers(window);
            break;
        }
        glfwSwapBuffers(window);
    }
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    log_info("showed %d frames", shown);
    return 0;
}
