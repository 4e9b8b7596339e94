#include "app/session.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <lauxlib.h>

#include "core/fileio.h"
#include "graph/graph.h"
#include "graph/graph_lint.h"
#include "core/log.h"
#include "core/suggest.h"
#include "lua/lua_host.h"
#include "reference/reference.h"


static bool field_number(lua_State *L, int t, const char *script, const char *name, double *out, struct error *err)
{
    int type = lua_getfield(L, t, name);
    if (type != LUA_TNIL) {
        if (type != LUA_TNUMBER) {
            lua_pop(L, 1);
            return error_set(err, "%s: the returned table's '%s' must be a number, got %s", script, name,
                             lua_typename(L, type));
        }
        *out = lua_tonumber(L, -1);
        if (!isfinite(*out)) {
            lua_pop(L, 1);
            return error_set(err, "%s: the returned table's '%s' must be a finite number, got %g", script, name, *out);
        }
    }
    lua_pop(L, 1);
    return true;
}

/* Checks the table a scene script returns (LUA_API.md: fixed keys). */
static bool read_result(struct session *s, struct error *err)
{
    lua_State *L = s->L;
    /* the errors name the line of the return statement that wrote the table */
    char where[4200];
    int line = lua_host_return_line(L);
    if (line > 0)
        snprintf(where, sizeof where, "%s:%d", s->script, line);
    else
        snprintf(where, sizeof where, "%s", s->script);
    const char *script = where;
    if (!lua_istable(L, -1))
        return error_set(err, "%s: a scene script must return a table {scene = ..., graph = ...}, it returned %s",
                         script, luaL_typename(L, -1));
    int t = lua_gettop(L);
    lua_getfield(L, t, "scene");
    s->scene = lua_host_to_scene(L, -1);
    if (!s->scene)
        return error_set(err, "%s: the returned table's 'scene' must be a scene (c.scene{...}), got %s", script,
                         luaL_typename(L, -1));
    lua_pop(L, 1);
    lua_getfield(L, t, "graph");
    s->graph = lua_host_to_graph(L, -1);
    if (!s->graph)
        return error_set(err, "%s: the returned table's 'graph' must be a graph (c.graph()), got %s", script,
                         luaL_typename(L, -1));
    lua_pop(L, 1);
    int type = lua_getfield(L, t, "update");
    if (type == LUA_TFUNCTION) {
        s->update_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    } else {
        lua_pop(L, 1);
        s->update_ref = LUA_NOREF;
        if (type != LUA_TNIL)
            return error_set(err, "%s: the returned table's 'update' must be a function, got %s", script,
                             lua_typename(L, type));
    }
    double frames = 1, fps = 30, exposure = 1;
    if (!field_number(L, t, script, "frames", &frames, err) || !field_number(L, t, script, "fps", &fps, err) ||
        !field_number(L, t, script, "exposure", &exposure, err))
        return false;
    if (!(frames >= 1) || frames > 1e7)
        return error_set(err, "%s: the returned table's frames = %g: a count of frames from 1 to 10^7 (a still is "
                              "frames = 1)", script, frames);
    if (!(fps > 0) || fps > 1e4)
        return error_set(err, "%s: the returned table's fps = %g: frames a second in (0, 10000]", script, fps);
    if (!(exposure >= 0) || !isfinite(exposure))
        return error_set(err, "%s: the returned table's exposure = %g: a multiplier >= 0", script, exposure);
    s->frames = s->options.frame_count > 0 ? s->options.frame_count : (int)frames; /* --frame-count wins */
    s->fps = s->options.fps > 0 ? s->options.fps : fps; /* --fps wins */
    s->exposure = (float)exposure;
    s->tonemap = TONEMAP_CLAMP;
    if (lua_getfield(L, t, "tonemap") != LUA_TNIL) {
        if (lua_type(L, -1) != LUA_TSTRING || !tonemap_parse(lua_tostring(L, -1), &s->tonemap))
            return error_set(err, "%s: tonemap must be \"clamp\", \"reinhard\" or \"aces\"", script);
    }
    lua_pop(L, 1);
    s->width = s->height = 512;
    if (lua_getfield(L, t, "size") != LUA_TNIL) {
        if (!lua_istable(L, -1))
            return error_set(err, "%s: the returned table's 'size' must be {width, height} in pixels, got %s", script,
                             luaL_typename(L, -1));
        lua_rawgeti(L, -1, 1);
        lua_rawgeti(L, -2, 2);
        if (!lua_isinteger(L, -2) || !lua_isinteger(L, -1) || lua_tointeger(L, -2) < 1 || lua_tointeger(L, -1) < 1 ||
            lua_tointeger(L, -2) > 16384 || lua_tointeger(L, -1) > 16384)
            return error_set(err, "%s: size must be {width, height} in pixels (1..16384)", script);
        s->width = (int)lua_tointeger(L, -2);
        s->height = (int)lua_tointeger(L, -1);
        lua_pop(L, 2);
    }
    lua_pop(L, 1);
    if (s->options.width > 0) {
        s->width = s->options.width;
        s->height = s->options.height;
    }
    s->result_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    return true;
}

static void unload(struct session *s)
{
    if (s->L)
        lua_host_destroy(s->L); /* runs __gc: GL objects go while the context lives */
    s->L = NULL;
    s->scene = NULL;
    s->graph = NULL;
}

bool session_is_gltf(const char *path)
{
    size_t n = strlen(path);
    return (n > 5 && strcasecmp(path + n - 5, ".gltf") == 0) || (n > 4 && strcasecmp(path + n - 4, ".glb") == 0);
}

static bool load(struct session *s, struct error *err)
{
    const char *asset_dirs[LUA_HOST_ASSET_DIRS_MAX];
    int asset_dir_count = app_asset_dirs(s->app, asset_dirs, LUA_HOST_ASSET_DIRS_MAX);
    struct lua_host_options ho = {
        .root = s->app->root,
        .script_path = s->script,
        .params = &s->options.params,
        .trusted = s->app->trusted,
        .write_dir = s->options.write_dir ? s->options.write_dir : s->app->allow_write,
        .render = session_render_service,
        .render_context = s->app,
        .timeout = s->app->script_timeout,
        .memory_limit = s->app->script_memory,
        .read_dirs = s->app->allow_read,
        .read_dir_count = s->app->allow_read_count,
        .asset_dirs = asset_dirs,
        .asset_dir_count = asset_dir_count,
    };
    log_info("data folder %s (lua/, shaders/, scenes/assets)", s->app->root);
    s->L = lua_host_create(&ho, err);
    if (!s->L)
        return false;
    s->advanced = -1;
    /* A glTF file given for a script is run as the built-in scene script
     * for it (lua/caustica/gltf_scene.lua); the host still names the file
     * as the scene's (its folder readable, its name in messages). */
    char builtin[4200];
    const char *run = s->script;
    if (session_is_gltf(s->script)) {
        snprintf(builtin, sizeof builtin, "%s/lua/caustica/gltf_scene.lua", s->app->root);
        run = builtin;
    }
    if (!lua_host_run_file(s->L, run, 1, err) || !read_result(s, err)) {
        unload(s);
        return false;
    }
    char unused[512];
    lua_host_unused_params(s->L, unused, sizeof unused);
    if (unused[0])
        fprintf(stderr, "caustica: warning: %s: --set %s: the script has no c.param of that name\n", s->script, unused);
    return true;
}

bool session_open(struct app *app, const struct session_options *options, struct session **out, struct error *err)
{
    struct session *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->app = app;
    s->options = *options;
    snprintf(s->script, sizeof s->script, "%s", options->script);
    s->options.script = s->script;
    /* --fps tells a glTF file's built-in script the rate its animations'
     * frames are counted at (a script's own `fps` it simply replaces) */
    if (session_is_gltf(s->script) && s->options.fps > 0) {
        char assignment[64];
        snprintf(assignment, sizeof assignment, "fps=%.17g", s->options.fps);
        if (!lua_params_add(&s->options.params, assignment, err)) {
            free(s);
            return false;
        }
    }
    if (!load(s, err)) {
        free(s);
        return false;
    }
    *out = s;
    return true;
}

void session_close(struct session *s)
{
    if (!s)
        return;
    unload(s);
    free(s);
}

bool session_reload(struct session *s, struct error *err)
{
    unload(s);
    return load(s, err);
}

bool session_goto_frame(struct session *s, int frame, struct error *err)
{
    if (frame < 0)
        return error_set(err, "frame %d: frames count from 0", frame);
    /* Every frame runs update() for all frames before it: an index past the
     * script's frame count is a typo more often than a wish, and 10^9 of
     * them never end. */
    if (frame >= s->frames && !s->options.past_last_frame)
        return error_set(err, "%s: frame %d is past the script's last frame %d (it returns frames = %d; raise frames "
                              "in the returned table to render later frames)", s->script, frame, s->frames - 1,
                         s->frames);
    if (frame < s->advanced) {
        /* Going back in time: the script's state only moves forward. */
        unload(s);
        if (!load(s, err))
            return false;
    }
    double dt = 1.0 / s->fps;
    while (s->advanced < frame) {
        int i = s->advanced + 1;
        if (s->update_ref != LUA_NOREF) {
            lua_rawgeti(s->L, LUA_REGISTRYINDEX, s->update_ref);
            lua_pushnumber(s->L, (double)i * dt);
            lua_pushnumber(s->L, dt);
            char context[64];
            snprintf(context, sizeof context, "(in update, frame %d)", i);
            if (!lua_host_call(s->L, 2, 0, context, err))
                return false;
        }
        s->advanced = i;
    }
    return true;
}

/* "script.lua: message", unless the message already starts with the
 * script (a graph error that names the script line). */
static bool script_error(const struct session *s, struct error *err)
{
    if (strncmp(err->message, s->script, strlen(s->script)) == 0)
        return false;
    return error_prefix(err, "%s", s->script);
}

bool session_render(struct session *s, int frame, struct error *err)
{
    if (!session_goto_frame(s, frame, err))
        return false;
    if (!app_ensure_gl(s->app, err))
        return false;
    struct renderer *r = &s->app->renderer;
    if (!graph_compile(s->graph, r, s->width, s->height, err))
        return script_error(s, err);
    if (!renderer_begin_frame(r, s->scene, s->width, s->height, frame, (double)frame / s->fps, err))
        return script_error(s, err);
    if (!s->linted) {
        /* mistakes that render without an error: said once per session */
        char messages[GRAPH_LINT_MAX][400];
        int n = graph_lint(s->graph, s->scene, &r->frame.view_proj, messages, GRAPH_LINT_MAX);
        for (int i = 0; i < n; i++)
            log_warn("%s: %s", s->script, messages[i]);
        s->linted = true;
    }
    if (!graph_execute(s->graph, r, s->scene, frame, (double)frame / s->fps, err))
        return script_error(s, err);
    return true;
}

/* A colour resource of the graph as a linear float image (rows top to bottom). */
static bool read_resource(struct session *s, struct graph_resource *res, struct image *out, struct error *err)
{
    if (res->texture.target == GL_TEXTURE_2D && gl_format_is_depth(res->texture.format)) {
        /* a depth buffer: its window depth in R, G and B */
        if (!image_create(out, res->texture.width, res->texture.height, err))
            return false;
        size_t n = (size_t)res->texture.width * (size_t)res->texture.height;
        float *depth = malloc(n * sizeof *depth);
        if (!depth || !gl_texture_read_depth32f(&res->texture, depth, err)) {
            free(depth);
            image_destroy(out);
            return depth ? false : error_set(err, "out of memory");
        }
        for (size_t i = 0; i < n; i++) {
            out->rgba[i * 4] = out->rgba[i * 4 + 1] = out->rgba[i * 4 + 2] = depth[i];
            out->rgba[i * 4 + 3] = 1.0f;
        }
        free(depth);
        image_flip_rows(out);
        return true;
    }
    if (res->texture.target != GL_TEXTURE_2D)
        return error_set(err, "%s: '%s' is not a 2D image (a cube map output cannot be written)", s->script,
                         res->name);
    if (!image_create(out, res->texture.width, res->texture.height, err))
        return false;
    if (!gl_texture_read_rgba32f(&res->texture, 0, out->rgba, err)) {
        image_destroy(out);
        return false;
    }
    image_flip_rows(out);
    return true;
}

bool session_read_linear(struct session *s, struct image *out, struct error *err)
{
    struct graph_resource *res = graph_output(s->graph);
    if (!res)
        return error_set(err, "%s: nothing rendered yet", s->script);
    if (res->texture.target != GL_TEXTURE_2D || gl_format_is_depth(res->texture.format))
        return error_set(err, "%s: the graph output '%s' is not a colour image", s->script, res->name);
    if (!image_create(out, res->texture.width, res->texture.height, err))
        return false;
    if (!gl_texture_read_rgba32f(&res->texture, 0, out->rgba, err)) {
        image_destroy(out);
        return false;
    }
    image_flip_rows(out);
    return true;
}

bool session_read_srgb(struct session *s, uint8_t **rgba, struct error *err)
{
    struct graph_resource *res = graph_output(s->graph);
    if (!res)
        return error_set(err, "%s: nothing rendered yet", s->script);
    if (res->texture.target != GL_TEXTURE_2D || gl_format_is_depth(res->texture.format))
        return error_set(err, "%s: the graph output '%s' is not a colour image", s->script, res->name);
    uint8_t *buf = malloc((size_t)res->texture.width * (size_t)res->texture.height * 4);
    if (!buf)
        return error_set(err, "out of memory");
    if (!renderer_present_bytes(&s->app->renderer, &res->texture, s->exposure, s->tonemap, buf, err)) {
        free(buf);
        return false;
    }
    *rgba = buf;
    return true;
}

/* A depth buffer's window depths made what compositors call Z: the distance
 * along the camera's view axis (camera-space -z), +inf where nothing was
 * drawn (the far plane). */
static void depth_to_distance(struct image *img, const mat4 *proj)
{
    mat4 inv;
    if (!mat4_inverse(*proj, &inv))
        return;
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++) {
        float d = img->rgba[i * 4];
        if (!(d < 1.0f)) {
            img->rgba[i * 4] = INFINITY;
            continue;
        }
        /* clip (0, 0, 2d - 1, 1) back to the camera: z / w of the inverse */
        float zn = 2.0f * d - 1.0f;
        float z = inv.m[10] * zn + inv.m[14], w = inv.m[11] * zn + inv.m[15];
        img->rgba[i * 4] = w != 0.0f ? -z / w : INFINITY;
    }
}

/* The EXR header's camera and caustica attributes for the frame just rendered. */
void session_exr_info(const struct session *s, struct image_exr_info *info)
{
    const struct frame *f = &s->app->renderer.frame;
    memset(info, 0, sizeof *info);
    info->camera = true;
    memcpy(info->world_to_camera, f->view.m, sizeof info->world_to_camera);
    memcpy(info->world_to_ndc, f->view_proj.m, sizeof info->world_to_ndc);
    info->frame = f->index;
    info->time = f->time;
    info->fps = s->fps;
    info->scene = s->script;
    info->renderer = s->app->gl ? s->app->gl->renderer : NULL;
    info->output = s->graph && graph_output(s->graph) ? graph_output(s->graph)->name : NULL;
}

/* "; the graph's images: a.b, c.d (did you mean a.b?)": what --aov may
 * name in this graph (texture outputs of the passes it kept). */
static void aov_choices(const struct session *s, const char *wanted, char *out, size_t outlen)
{
    const char *names[256];
    size_t count = 0, used = (size_t)snprintf(out, outlen, "; the graph's images:");
    for (int r = 0; r < s->graph->resource_count && count < 256; r++) {
        const struct graph_resource *res = &s->graph->resources[r];
        if (res->decl.kind == RESOURCE_RECORD || (res->producer >= 0 && res->producer < s->graph->count &&
                            s->graph->entries[res->producer].state != GRAPH_PASS_KEPT))
            continue;
        names[count++] = res->name;
        if (used < outlen)
            used += (size_t)snprintf(out + used, outlen - used, "%s %s", count > 1 ? "," : "", res->name);
    }
    const char *near = count ? suggest_nearest(wanted, names, count) : NULL;
    if (near && used < outlen)
        snprintf(out + used, outlen - used, " (did you mean %s?)", near);
    else if (!count)
        snprintf(out, outlen, "; the graph keeps no image output");
}

bool session_write_image(struct session *s, const char *path, struct error *err)
{
    if (image_path_is_exr(path)) {
        /* the output, and each --aov resource as a named layer */
        struct image img, layers_img[SESSION_MAX_AOVS];
        struct image_layer layers[SESSION_MAX_AOVS];
        int n = 0;
        if (!session_read_linear(s, &img, err))
            return false;
        bool ok = true;
        int holdout = -1; /* the layer made from the image and the first surface, below */
        for (int i = 0; ok && i < s->aov_count; i++) {
            if (strcmp(s->aovs[i], "holdout") == 0) {
                holdout = n;
                layers[n] = (struct image_layer){.name = "holdout", .image = &layers_img[n]};
                memset(&layers_img[n], 0, sizeof layers_img[n]);
                n++;
                continue;
            }
            struct graph_resource *res = graph_find_resource(s->graph, s->aovs[i]);
            if (!res) {
                char choices[1024];
                aov_choices(s, s->aovs[i], choices, sizeof choices);
                ok = error_set(err, "--aov %s: no pass makes it (outputs are named \"pass.output\")%s", s->aovs[i],
                               choices);
                break;
            }
            if (res->producer >= 0 && res->producer < s->graph->count &&
                s->graph->entries[res->producer].state != GRAPH_PASS_KEPT) {
                ok = error_set(err, "--aov %s: its pass was left out (%s)", s->aovs[i],
                               s->graph->entries[res->producer].reason);
                break;
            }
            if (res->decl.kind == RESOURCE_RECORD) {
                ok = error_set(err, "--aov %s: a %s, not an image; name one of the textures its readers make",
                               s->aovs[i], res->decl.record->name);
                break;
            }
            ok = read_resource(s, res, &layers_img[n], err);
            if (ok) {
                size_t len = strlen(s->aovs[i]);
                layers[n].name = s->aovs[i];
                layers[n].image = &layers_img[n];
                layers[n].depth = gl_format_is_depth(res->texture.format);
                if (layers[n].depth)
                    depth_to_distance(&layers_img[n], &s->app->renderer.frame.proj);
                /* shade's and the receivers' normals keep their object id + 1 in w: left out of the
                 * layer (the file's objectId is the first surface's, which sees glass too) */
                layers[n].object_id = len > 7 && strcmp(s->aovs[i] + len - 7, ".normal") == 0;
                n++;
            }
        }
        /* alpha: coverage, 0 where only the background shows (OpenEXR's
         * "luminous" pixels: colour with no coverage, left as it is); Z and
         * objectId: the first surface of every object, glass and water
         * included (the refraction passes draw those after the G-buffer,
         * which leaves them out) */
        struct image surface = {0};
        ok = ok && renderer_first_surface(&s->app->renderer, s->scene, img.width, img.height, &surface, err);
        for (size_t i = 0; ok && i < (size_t)img.width * (size_t)img.height; i++)
            img.rgba[i * 4 + 3] = surface.rgba[i * 4];
        /* the holdout: the image over nothing (premultiplied by coverage), for
         * a compositor to put over its own plate: plate * (1 - A) + RGB */
        if (ok && holdout >= 0 && (ok = image_create(&layers_img[holdout], img.width, img.height, err)))
            for (size_t i = 0; i < (size_t)img.width * (size_t)img.height; i++) {
                const float *from = img.rgba + i * 4;
                float *to = layers_img[holdout].rgba + i * 4;
                to[0] = from[0] * from[3];
                to[1] = from[1] * from[3];
                to[2] = from[2] * from[3];
                to[3] = from[3];
            }
        struct image_exr_info info;
        session_exr_info(s, &info);
        info.half = s->exr_half;
        info.surface = ok ? &surface : NULL;
        ok = ok && image_write_exr(path, &img, layers, n, &info, err);
        image_destroy(&surface);
        for (int i = 0; i < n; i++)
            image_destroy(&layers_img[i]);
        image_destroy(&img);
        return ok;
    }
    if (image_path_is_pfm(path) || image_path_is_hdr(path)) {
        struct image img;
        if (!session_read_linear(s, &img, err))
            return false;
        bool ok = image_write(path, &img, err);
        image_destroy(&img);
        return ok;
    }
    if (!image_path_is_display(path))
        return error_set(err, "%s: unknown image format (use .png, .jpg, .tif, .pfm, .hdr or .exr)", path);
    /* An 8-bit PNG, JPEG or TIFF cannot hold NaN (the conversion makes it 0), but a pass
     * that produced some should not go unnoticed. */
    struct image linear;
    if (!session_read_linear(s, &linear, err))
        return false;
    long nonfinite = 0;
    for (size_t i = 0; i < (size_t)linear.width * (size_t)linear.height; i++) {
        const float *p = linear.rgba + i * 4;
        nonfinite += !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
    }
    image_destroy(&linear);
    if (nonfinite)
        fprintf(stderr, "caustica: warning: %s: %ld pixel%s had NaN or Inf values, written as 0\n", path, nonfinite,
                nonfinite == 1 ? "" : "s");
    uint8_t *bytes;
    if (!session_read_srgb(s, &bytes, err))
        return false;
    struct graph_resource *res = graph_output(s->graph);
    bool ok = image_write_display8(path, bytes, res->texture.width, res->texture.height, err);
    free(bytes);
    return ok;
}

bool session_reference(struct session *s, int frame, const struct ref_options *options, struct image *out,
                       struct ref_stats *stats, struct error *err)
{
    return session_reference_parts(s, frame, options, out, NULL, stats, err);
}

bool session_reference_parts(struct session *s, int frame, const struct ref_options *options, struct image *out,
                             struct image *caustic, struct ref_stats *stats, struct error *err)
{
    if (!session_goto_frame(s, frame, err) || !app_ensure_gl(s->app, err))
        return false;
    /* The same frame set-up as a GPU frame: deformers run into the buffers
     * the reference then reads back, lights are expanded the same way. */
    struct renderer *r = &s->app->renderer;
    if (!renderer_begin_frame(r, s->scene, s->width, s->height, frame, (double)frame / s->fps, err))
        return error_prefix(err, "%s", s->script);
    struct ref_options o = *options;
    if (o.threads <= 0)
        o.threads = s->app->threads; /* --threads; 0 still: the CPUs this process may use */
    o.width = s->width;
    o.height = s->height;
    if (!ref_render_parts(r, s->scene, &o, out, caustic, stats, err))
        return error_prefix(err, "%s", s->script);
    return true;
}

/* The text as the parameter's type reads it. */
static bool set_from_text(struct pass *p, const char *name, const char *text, struct error *err)
{
    int index = pass_param_index(p->desc, name);
    switch (p->desc->params[index].type) {
    case PASS_PARAM_BOOLEAN:
        if (strcmp(text, "true") != 0 && strcmp(text, "false") != 0)
            return error_set(err, "'%s' is not true or false", text);
        return pass_set_boolean(p, name, strcmp(text, "true") == 0, err);
    case PASS_PARAM_ENUM:
        return pass_set_enum(p, name, text, err);
    case PASS_PARAM_STRING:
        return pass_set_string(p, name, text, err);
    default: {
        char *end;
        double v = strtod(text, &end);
        if (end == text || *end)
            return error_set(err, "'%s' is not a number", text);
        return pass_set_number(p, name, v, err);
    }
    }
}

bool session_set_pass_param(struct session *s, const char *key, const char *text, struct error *err)
{
    const char *dot = strchr(key, '.');
    if (!dot)
        return error_set(err, "'%s' is not a pass parameter (pass.param)", key);
    char pass_name[PASS_NAME_MAX];
    snprintf(pass_name, sizeof pass_name, "%.*s", (int)(dot - key), key);
    for (int i = 0; i < s->graph->count; i++) {
        struct pass *p = s->graph->entries[i].pass;
        if (strcmp(p->name, pass_name) != 0)
            continue;
        if (pass_param_index(p->desc, dot + 1) < 0)
            return error_set(err, "%s: pass '%s' (%s) has no parameter '%s'", s->script, pass_name, p->desc->name, dot + 1);
        if (p->created)
            return error_set(err, "%s: %s: the pass already ran; set parameters before rendering", s->script, key);
        /* Validated where the bindings validate; outputs may depend on the
         * value (a shadow map's size): declare again. */
        if (!set_from_text(p, dot + 1, text, err) || !pass_declare(p, err))
            return error_prefix(err, "%s: %s", s->script, key);
        s->graph->compiled = false;
        return true;
    }
    return error_set(err, "%s: no pass named '%s' in the graph", s->script, pass_name);
}

/* c.image.render and c.image.reference (the test harness's tools): another
 * script in its own session, on the same GL context. Nesting is capped: a
 * script that renders itself would recurse until the C stack ends. */
#define SESSION_RENDER_MAX_DEPTH 4

bool session_render_service(void *context, const struct lua_render_request *request, struct image *out,
                            struct lua_render_reply *reply, struct error *err)
{
    struct app *app = context;
    memset(reply, 0, sizeof *reply);
    if (app->render_depth >= SESSION_RENDER_MAX_DEPTH)
        return error_set(err, "scripts rendering scripts nest deeper than %d (does '%s' render itself?)",
                         SESSION_RENDER_MAX_DEPTH, request->script);
    struct session_options o = {.script = request->script, .params = request->params, .width = request->width,
                                .height = request->height};
    struct session *s = NULL;
    app->render_depth++;
    bool ok = session_open(app, &o, &s, err);
    if (ok && request->reference) {
        struct ref_stats st;
        struct image caustic = {0};
        ok = session_reference_parts(s, request->frame, request->reference, out,
                                     request->without_caustics ? &caustic : NULL, &st, err);
        if (ok && request->without_caustics) {
            size_t n = (size_t)out->width * (size_t)out->height * 4;
            for (size_t i = 0; i < n; i++)
                if (i % 4 != 3)
                    out->rgba[i] = fmaxf(out->rgba[i] - caustic.rgba[i], 0.0f);
        }
        image_destroy(&caustic);
        if (ok) {
            reply->iterations = st.iterations;
            reply->photons = st.photons;
            reply->caustic_photons = st.caustic_photons;
            for (int k = 0; k < 3; k++)
                reply->caustic_power[k] = st.caustic_power[k];
            reply->seconds = st.seconds;
        }
    } else if (ok) {
        ok = session_render(s, request->frame, err) && session_read_linear(s, out, err);
        for (int i = 0; ok && i < s->graph->count && reply->pass_count < LUA_RENDER_MAX_PASSES; i++)
            if (s->graph->entries[i].state == GRAPH_PASS_KEPT) {
                snprintf(reply->pass_names[reply->pass_count], sizeof reply->pass_names[0], "%s",
                         s->graph->entries[i].pass->name);
                reply->pass_ms[reply->pass_count++] = s->graph->entries[i].last_ms;
            }
    }
    app->render_depth--;
    session_close(s);
    return ok;
}
