/* core/optics.c: Fresnel's reflectance against its closed forms, and the
 * edge cases the CPU code meets (grazing, total internal reflection,
 * matched indices, out-of-range and NaN cosines). */
#include <math.h>

#include "check.h"
#include "core/optics.h"

int main(void)
{
    /* normal incidence: ((n1 - n2) / (n1 + n2))^2, either way through */
    CHECK_NEAR(optics_fresnel(1.0, 1.0 / 1.5), 0.04, 1e-12);
    CHECK_NEAR(optics_fresnel(1.0, 1.5), 0.04, 1e-12);
    CHECK_NEAR(optics_fresnel(1.0, 1.0 / 2.42), pow(1.42 / 3.42, 2.0), 1e-12);
    /* Brewster's angle: the p-polarised part vanishes, R = rs^2 / 2 */
    double tb = atan(1.5), ct = cos(asin(sin(tb) / 1.5)), ci = cos(tb);
    double rs = (ci / 1.5 - ct) / (ci / 1.5 + ct);
    CHECK_NEAR(optics_fresnel(ci, 1.0 / 1.5), 0.5 * rs * rs, 1e-12);
    /* matched indices reflect nothing; grazing reflects everything */
    CHECK_NEAR(optics_fresnel(0.3, 1.0), 0.0, 1e-15);
    CHECK_NEAR(optics_fresnel(0.0, 1.0 / 1.5), 1.0, 1e-12);
    /* total internal reflection past the critical angle (sin = 1 / 1.5) */
    double critical = sqrt(1.0 - 1.0 / (1.5 * 1.5));
    CHECK(optics_fresnel(critical - 1e-6, 1.5) == 1.0);
    CHECK(optics_fresnel(critical + 1e-3, 1.5) < 1.0);
    /* monotone in the angle from the normal towards grazing (outside, n = 1.5) */
    double last = 0.0;
    bool monotone = true, finite = true;
    for (int k = 100; k >= 0; k--) {
        double r = optics_fresnel(k / 100.0, 1.0 / 1.5);
        monotone = monotone && r >= last - 1e-15;
        last = r;
    }
    CHECK(monotone);
    /* out-of-range and NaN cosines, extreme IORs: in [0, 1], never NaN */
    const double cosines[] = {-1.0, 2.0, NAN, 1e-300, 0.5};
    const double etas[] = {1e-6, 0.1, 1.0 / 10.0, 1.0, 1.0001, 10.0, 1e6};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 7; j++) {
            double r = optics_fresnel(cosines[i], etas[j]);
            finite = finite && isfinite(r) && r >= 0.0 && r <= 1.0;
        }
    CHECK(finite);
    /* an ideal interface: nothing reflected but under total internal reflection */
    CHECK(optics_fresnel_of(0.7, 1.0 / 1.5, true) == 0.0);
    CHECK(optics_fresnel_of(critical - 1e-6, 1.5, true) == 1.0);
    CHECK_NEAR(optics_fresnel_of(1.0, 1.0 / 1.5, false), 0.04, 1e-12);
        /* Snell: a 45-degree ray into glass bends to asin(sin45 / 1.5); TIR from
     * inside past the critical angle; eta 1 goes straight through; the
     * result is unit and never NaN, grazing included. */
    {
        const double d[3] = {sqrt(0.5), -sqrt(0.5), 0.0}, n[3] = {0.0, 1.0, 0.0};
        double t[3];
        CHECK(optics_refract(d, n, 1.0 / 1.5, t));
        CHECK_NEAR(t[0], sqrt(0.5) / 1.5, 1e-12);
        CHECK_NEAR(t[0] * t[0] + t[1] * t[1] + t[2] * t[2], 1.0, 1e-12);
        CHECK(t[1] < 0.0);
        const double up[3] = {sqrt(0.5), sqrt(0.5), 0.0}, down_n[3] = {0.0, -1.0, 0.0};
        CHECK(!optics_refract(up, down_n, 1.5, t)); /* 45 degrees inside glass: past 41.8 */
        CHECK(optics_refract(d, n, 1.0, t));
        CHECK_NEAR(t[0], d[0], 1e-12);
        CHECK_NEAR(t[1], d[1], 1e-12);
        const double graze[3] = {1.0, 0.0, 0.0};
        CHECK(optics_refract(graze, n, 1.0 / 1.5, t));
        CHECK(isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]));
        CHECK(!optics_refract(graze, n, 1.5, t)); /* grazing from the denser side: TIR */
        const double zero[3] = {0.0, 0.0, 0.0};
        if (optics_refract(zero, n, 1.5, t))
            CHECK(isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]));
    }
return check_finish("test_optics");
}
