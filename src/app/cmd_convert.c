/* `caustica convert IN OUT [--exposure E]`: a PFM (linear) to PNG (clamped,
 * sRGB) or back, e.g. to look at a reference image. */
#include <stdio.h>
#include <stdlib.h>

#include "app/cli.h"
#include "io/image.h"

int cmd_convert(struct app *app, struct cli *cli)
{
    (void)app;
    if (cli->npositional != 2) {
        fprintf(stderr, "caustica: convert needs an input and an output image\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    struct image img = {0};
    struct error err;
    bool ok = image_read(cli->positional[0], &img, &err);
    if (ok && cli->exposure > 0) {
        size_t n = (size_t)img.width * (size_t)img.height * 4;
        for (size_t i = 0; i < n; i++)
            if (i % 4 != 3)
                img.rgba[i] *= (float)cli->exposure;
    }
    ok = ok && image_write(cli->positional[1], &img, &err);
    image_destroy(&img);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
