/* `caustica compare A B [--mask M]`: one line of key=value metrics (the
 * mask any image format: a pixel counts where its luminance is > 0). */
#include <stdio.h>

#include "app/cli.h"
#include "io/image.h"
#include "reference/image_metrics.h"

int cmd_compare(struct app *app, struct cli *cli)
{
    (void)app;
    if (cli->npositional != 2) {
        fprintf(stderr, "caustica: compare needs two images\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    struct image a = {0}, b = {0}, m = {0};
    struct error err;
    bool ok = image_read(cli->positional[0], &a, &err) && image_read(cli->positional[1], &b, &err) &&
              (!cli->mask || image_read(cli->mask, &m, &err));
    struct image_metrics r;
    ok = ok && image_metrics_compute(&a, &b, cli->mask ? &m : NULL, &r, &err);
    if (ok)
        printf("rmse=%.6g rel_rmse=%.6g psnr=%.4g ssim=%.6g max=%.6g nan=%ld log_rmse=%.6g\n", r.rmse, r.rel_rmse,
               r.psnr, r.ssim, r.max, r.nan, r.log_rmse);
    image_destroy(&a);
    image_destroy(&b);
    image_destroy(&m);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
