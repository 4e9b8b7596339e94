/* `caustica compare A B [A_NEXT B_NEXT] [--mask M]`: one line of key=value
 * metrics (the mask any image format: a pixel counts where its luminance is
 * > 0); with the next frames of both, the flicker of A's change against B's
 * (image_flicker_compute, issue 32). */
#include <stdio.h>

#include "app/cli.h"
#include "io/image.h"
#include "reference/image_metrics.h"

int cmd_compare(struct app *app, struct cli *cli)
{
    (void)app;
    if (cli->npositional != 2 && cli->npositional != 4) {
        fprintf(stderr, "caustica: compare needs two images (A B), or four (A B A_NEXT B_NEXT: the flicker of A's "
                        "change against B's too)\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    struct image a = {0}, b = {0}, m = {0}, a1 = {0}, b1 = {0};
    struct error err;
    bool ok = image_read(cli->positional[0], &a, &err) && image_read(cli->positional[1], &b, &err) &&
              (!cli->mask || image_read(cli->mask, &m, &err));
    bool temporal = cli->npositional == 4;
    ok = ok && (!temporal || (image_read(cli->positional[2], &a1, &err) && image_read(cli->positional[3], &b1, &err)));
    struct image_metrics r;
    double flicker = 0.0;
    ok = ok && image_metrics_compute(&a, &b, cli->mask ? &m : NULL, &r, &err) &&
         (!temporal || image_flicker_compute(&a, &a1, &b, &b1, cli->mask ? &m : NULL, &flicker, &err));
    if (ok) {
        printf("rmse=%.6g rel_rmse=%.6g psnr=%.4g ssim=%.6g max=%.6g nan=%ld log_rmse=%.6g", r.rmse, r.rel_rmse, r.psnr,
               r.ssim, r.max, r.nan, r.log_rmse);
        if (temporal)
            printf(" flicker=%.6g", flicker);
        printf("\n");
    }
    image_destroy(&a1);
    image_destroy(&b1);
    image_destroy(&a);
    image_destroy(&b);
    image_destroy(&m);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
