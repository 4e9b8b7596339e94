/* `caustica convert IN OUT [--exposure E] [--tonemap OP]`: an image from one
 * format to another (.png, .pfm, .hdr, .exr; IN.exr:layer for one layer).
 * To PNG with --tonemap, the same tone mapping `render -o x.png` applies (the
 * renderer's own present pass on the GPU: one implementation, so a PFM
 * converted matches the PNG render wrote byte for byte); without it, the
 * exposure and a plain clamp. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "gl/gl_api.h"
#include "io/image.h"

/* The linear image through the renderer's present pass into 8-bit sRGB. */
static bool tonemapped_png(struct app *app, const struct image *img, float exposure, enum tonemap_operator op,
                           const char *path, struct error *err)
{
    if (!app_ensure_gl(app, err))
        return false;
    struct gl_texture tex = {0};
    if (!gl_texture_create(&tex, GL_TEXTURE_2D, GL_RGBA32F, img->width, img->height, 1, err))
        return false;
    /* GL rows go bottom to top; images top to bottom */
    size_t row = (size_t)img->width * 4;
    for (int y = 0; y < img->height; y++)
        gl.TextureSubImage2D(tex.id, 0, 0, img->height - 1 - y, img->width, 1, GL_RGBA, GL_FLOAT,
                             img->rgba + (size_t)y * row);
    uint8_t *bytes = malloc((size_t)img->width * (size_t)img->height * 4);
    bool ok = bytes && renderer_present_bytes(&app->renderer, &tex, exposure, op, bytes, err) &&
              image_write_display8(path, bytes, img->width, img->height, err);
    if (!bytes)
        error_set(err, "out of memory");
    free(bytes);
    gl_texture_destroy(&tex);
    return ok;
}

int cmd_convert(struct app *app, struct cli *cli)
{
    if (cli->npositional != 2) {
        fprintf(stderr, "caustica: convert needs an input and an output image\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    const char *out = cli->positional[1];
    enum tonemap_operator op = TONEMAP_CLAMP;
    if (cli->tonemap && !tonemap_parse(cli->tonemap, &op)) {
        fprintf(stderr, "caustica: --tonemap needs clamp, reinhard or aces, got '%s'\n", cli->tonemap);
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    if (cli->tonemap && !image_path_is_display(out)) {
        fprintf(stderr, "caustica: --tonemap: %s keeps linear values; tone mapping is for a .png, .jpg or .tif\n",
                out);
        return EXIT_USAGE;
    }
    struct image img = {0};
    struct error err;
    bool ok = image_read(cli->positional[0], &img, &err);
    if (ok && cli->tonemap) {
        ok = tonemapped_png(app, &img, cli->exposure > 0 ? (float)cli->exposure : 1.0f, op, out, &err);
    } else if (ok) {
        if (cli->exposure > 0) {
            size_t n = (size_t)img.width * (size_t)img.height * 4;
            for (size_t i = 0; i < n; i++)
                if (i % 4 != 3)
                    img.rgba[i] *= (float)cli->exposure;
        }
        ok = image_write(out, &img, &err);
    }
    image_destroy(&img);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
