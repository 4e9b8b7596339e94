#ifndef CAUSTICA_L_IMAGE_H
#define CAUSTICA_L_IMAGE_H

#include <lua.h>

#include "io/image.h"

#define IMAGE_MT "caustica.Image"

struct image *limage_check(lua_State *L, int idx);
/* Pushes an empty Image userdata (fill it, or it stays 0x0). */
struct image *limage_push(lua_State *L);
/* Charges a width x height image's pixels to the script's memory limit
 * (lua_host_charge), raising a Lua error past it; released when the
 * userdata is collected. */
void limage_charge(lua_State *L, struct image *img, long long width, long long height);
/* render(script, {set = {...}, size = {w, h}, frame = n}) -> Image (l_render.c) */
int limage_render(lua_State *L);
/* reference(script, opts) -> Image, stats (l_render.c) */
int limage_reference(lua_State *L);

#endif
