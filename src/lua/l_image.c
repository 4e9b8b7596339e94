/* caustica.image: float images (linear RGBA), their files, and the error
 * metrics between two of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "io/image.h"
#include "lua/l_image.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"
#include "reference/image_metrics.h"

/* An image userdata: the image, and the bytes of it charged to the
 * script's memory limit (released with it). */
struct l_image {
    struct image image; /* first: the userdata is the image */
    size_t charged;
};

struct image *limage_check(lua_State *L, int idx) { return luaL_checkudata(L, idx, IMAGE_MT); }

struct image *limage_push(lua_State *L)
{
    struct l_image *u = lua_newuserdatauv(L, sizeof *u, 0);
    memset(u, 0, sizeof *u);
    luaL_setmetatable(L, IMAGE_MT);
    return &u->image;
}

void limage_charge(lua_State *L, struct image *img, long long width, long long height)
{
    struct l_image *u = (struct l_image *)img;
    size_t bytes = width > 0 && height > 0 ? (size_t)width * (size_t)height * 4 * sizeof(float) : 0;
    char what[96];
    snprintf(what, sizeof what, "a %lldx%lld image", width, height);
    struct error err;
    if (!lua_host_charge(L, bytes, what, &err))
        luaL_error(L, "%s", err.message);
    u->charged += bytes;
}

static int image_load_l(lua_State *L)
{
    char path[4096];
    lua_host_resolve_path(L, luaL_checkstring(L, 1), path, sizeof path);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "%s", err.message);
    struct image *img = limage_push(L);
    if (!image_read(path, img, &err))
        return luaL_error(L, "%s", err.message);
    limage_charge(L, img, img->width, img->height); /* its size is known once read (readers cap it) */
    return 1;
}

static int image_new_l(lua_State *L)
{
    lua_Integer w = luaL_checkinteger(L, 1), h = luaL_checkinteger(L, 2);
    if (w < 1 || h < 1 || w > 32768 || h > 32768)
        return luaL_error(L, "image.new: %lldx%lld is out of range (1..32768 a side)", (long long)w, (long long)h);
    struct image *img = limage_push(L);
    limage_charge(L, img, w, h); /* before the pixels exist */
    struct error err;
    if (!image_create(img, (int)w, (int)h, &err))
        return luaL_error(L, "%s", err.message);
    return 1;
}

static void push_metrics(lua_State *L, const struct image_metrics *m)
{
    lua_createtable(L, 0, 7);
    lua_pushnumber(L, m->rmse);
    lua_setfield(L, -2, "rmse");
    lua_pushnumber(L, m->rel_rmse);
    lua_setfield(L, -2, "rel_rmse");
    lua_pushnumber(L, m->psnr);
    lua_setfield(L, -2, "psnr");
    lua_pushnumber(L, m->ssim);
    lua_setfield(L, -2, "ssim");
    lua_pushnumber(L, m->max);
    lua_setfield(L, -2, "max");
    lua_pushinteger(L, m->nan);
    lua_setfield(L, -2, "nan");
    lua_pushinteger(L, m->pixels);
    lua_setfield(L, -2, "pixels");
}

static int image_compare_l(lua_State *L)
{
    struct image *a = limage_check(L, 1), *b = limage_check(L, 2);
    struct image *mask = lua_isnoneornil(L, 3) ? NULL : limage_check(L, 3);
    struct image_metrics m;
    struct error err;
    if (!image_metrics_compute(a, b, mask, &m, &err))
        return luaL_error(L, "%s", err.message);
    push_metrics(L, &m);
    return 1;
}

static int image_gc(lua_State *L)
{
    struct l_image *u = (struct l_image *)limage_check(L, 1);
    image_destroy(&u->image);
    lua_host_uncharge(L, u->charged);
    u->charged = 0;
    return 0;
}

static int image_save_l(lua_State *L)
{
    struct image *img = limage_check(L, 1);
    const char *rel = luaL_checkstring(L, 2);
    char path[4096];
    lua_host_resolve_path(L, rel, path, sizeof path);
    struct error err;
    if (!lua_host_check_write(L, path, &err))
        return luaL_error(L, "image:save: %s", err.message);
    if (!image_write(path, img, &err))
        return luaL_error(L, "%s", err.message);
    return 0;
}

static int image_pixel_l(lua_State *L)
{
    struct image *img = limage_check(L, 1);
    lua_Integer x = luaL_checkinteger(L, 2), y = luaL_checkinteger(L, 3);
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return luaL_error(L, "pixel (%d, %d) is outside the %dx%d image", (int)x, (int)y, img->width, img->height);
    const float *p = img->rgba + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
    for (int c = 0; c < 4; c++)
        lua_pushnumber(L, p[c]);
    return 4;
}

/* Mean and maximum of RGB, count of non-finite values, over a region. */
static int image_stats_l(lua_State *L)
{
    struct image *img = limage_check(L, 1);
    int x0 = (int)luaL_optinteger(L, 2, 0), y0 = (int)luaL_optinteger(L, 3, 0);
    int x1 = (int)luaL_optinteger(L, 4, img->width), y1 = (int)luaL_optinteger(L, 5, img->height);
    if (x0 < 0 || y0 < 0 || x1 > img->width || y1 > img->height || x0 >= x1 || y0 >= y1)
        return luaL_error(L, "stats: region (%d,%d)-(%d,%d) is not inside the %dx%d image", x0, y0, x1, y1,
                          img->width, img->height);
    double sum[3] = {0, 0, 0}, max = 0;
    long nan = 0, n = 0;
    for (int y = y0; y < y1; y++) {
        if ((y & 63) == 0)
            lua_host_check_deadline(L, "image:stats");
        for (int x = x0; x < x1; x++, n++) {
            const float *p = img->rgba + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
            for (int c = 0; c < 3; c++) {
                if (!isfinite(p[c])) {
                    nan++;
                    continue;
                }
                sum[c] += p[c];
                if (p[c] > max)
                    max = p[c];
            }
        }
    }
    lua_createtable(L, 0, 4);
    lua_createtable(L, 3, 0);
    for (int c = 0; c < 3; c++) {
        lua_pushnumber(L, sum[c] / (double)n);
        lua_rawseti(L, -2, c + 1);
    }
    lua_setfield(L, -2, "mean");
    lua_pushnumber(L, (sum[0] + sum[1] + sum[2]) / (3.0 * (double)n));
    lua_setfield(L, -2, "mean_gray");
    lua_pushnumber(L, max);
    lua_setfield(L, -2, "max");
    lua_pushinteger(L, nan);
    lua_setfield(L, -2, "nan");
    return 1;
}

/* A copy with every channel clamped to [0, 1]: what an 8-bit PNG keeps. */
static int image_clamped_l(lua_State *L)
{
    struct image *img = limage_check(L, 1);
    struct image *out = limage_push(L);
    limage_charge(L, out, img->width, img->height);
    struct error err;
    if (!image_create(out, img->width, img->height, &err))
        return luaL_error(L, "%s", err.message);
    size_t n = (size_t)img->width * (size_t)img->height * 4;
    for (size_t i = 0; i < n; i++) {
        if ((i & ((1u << 22) - 1)) == 0)
            lua_host_check_deadline(L, "image:clamped");
        float v = img->rgba[i];
        out->rgba[i] = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
    }
    return 1;
}

/* image.difference(a, b): |a - b| per channel, scaled so that the largest
 * difference is 1 (the scale is returned second), for test reports. */
static int image_difference_l(lua_State *L)
{
    struct image *a = limage_check(L, 1), *b = limage_check(L, 2);
    if (a->width != b->width || a->height != b->height)
        return luaL_error(L, "image.difference: sizes differ (%dx%d and %dx%d)", a->width, a->height, b->width,
                          b->height);
    struct image *out = limage_push(L);
    limage_charge(L, out, a->width, a->height);
    struct error err;
    if (!image_create(out, a->width, a->height, &err))
        return luaL_error(L, "%s", err.message);
    size_t n = (size_t)a->width * (size_t)a->height;
    float largest = 0.0f;
    for (size_t i = 0; i < n * 4; i++) {
        if ((i & ((1u << 22) - 1)) == 0)
            lua_host_check_deadline(L, "image.difference");
        float d = fabsf(a->rgba[i] - b->rgba[i]);
        if (!isfinite(d))
            d = 0.0f;
        out->rgba[i] = d;
        if ((i & 3) != 3 && d > largest)
            largest = d;
    }
    float scale = largest > 0.0f ? 1.0f / largest : 1.0f;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            out->rgba[i * 4 + (size_t)c] *= scale;
        out->rgba[i * 4 + 3] = 1.0f;
    }
    lua_pushnumber(L, scale);
    return 2;
}

static int image_get_width(lua_State *L)
{
    lua_pushinteger(L, limage_check(L, 1)->width);
    return 1;
}

static int image_get_height(lua_State *L)
{
    lua_pushinteger(L, limage_check(L, 1)->height);
    return 1;
}

static int image_tostring(lua_State *L)
{
    struct image *img = limage_check(L, 1);
    lua_pushfstring(L, "Image(%dx%d)", img->width, img->height);
    return 1;
}

int luaopen_caustica_image(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__gc", image_gc}, {"__tostring", image_tostring}, {NULL, NULL}};
    static const luaL_Reg methods[] = {{"save", image_save_l}, {"pixel", image_pixel_l}, {"stats", image_stats_l},
                                       {"clamped", image_clamped_l}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"width", image_get_width}, {"height", image_get_height}, {NULL, NULL}};
    lutil_class(L, IMAGE_MT, "image", meta, methods, getters, NULL);
    static const luaL_Reg funcs[] = {{"load", image_load_l}, {"new", image_new_l}, {"compare", image_compare_l},
                                     {"difference", image_difference_l},
                                     {"render", limage_render}, {"reference", limage_reference}, {NULL, NULL}};
    luaL_newlib(L, funcs);
    return 1;
}
