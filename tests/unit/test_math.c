#include <float.h>

#include "check.h"
#include "core/suggest.h"
#include "core/vecmath.h"

int main(void)
{
    /* guarded division: zero, tiny and non-finite divisors give the fallback */
    CHECK_NEAR(math_safe_div(1.0f, 0.0f, 7.0f), 7.0f, 0);
    CHECK_NEAR(math_safe_div(1.0f, 1e-38f, 7.0f), 7.0f, 0); /* would overflow to inf */
    CHECK_NEAR(math_safe_div(6.0f, 3.0f, 0.0f), 2.0f, 1e-7);
    CHECK_NEAR(math_safe_div_d(1.0, 0.0, -1.0), -1.0, 0);
    CHECK(isfinite(math_safe_div(FLT_MAX, 1e-20f, 0.0f)));

    /* normalising a zero vector gives the fallback, never NaN */
    vec3 n = vec3_normalize_or(vec3_make(0, 0, 0), vec3_make(0, 1, 0));
    CHECK(n.y == 1.0f && n.x == 0.0f);
    n = vec3_normalize_or(vec3_make(3, 0, 4), vec3_make(0, 1, 0));
    CHECK_NEAR(n.x, 0.6, 1e-6);
    CHECK_NEAR(n.z, 0.8, 1e-6);

    /* matrices: inverse of TRS, look-at with a degenerate up vector */
    mat4 m = mat4_trs(vec3_make(1, 2, 3), quat_axis_angle(vec3_make(0, 1, 0), 0.7f), vec3_make(2, 2, 2));
    mat4 inv;
    CHECK(mat4_inverse(m, &inv));
    mat4 id = mat4_mul(m, inv);
    for (int i = 0; i < 16; i++)
        CHECK_NEAR(id.m[i], (i % 5 == 0) ? 1.0 : 0.0, 1e-5);
    vec3 p = mat4_transform_point(m, vec3_make(0, 0, 0));
    CHECK_NEAR(p.x, 1, 1e-6);
    CHECK_NEAR(p.z, 3, 1e-6);
    mat4 singular = {{0}};
    CHECK(!mat4_inverse(singular, &inv));
    CHECK(inv.m[0] == 1.0f);

    mat4 v = mat4_look_at(vec3_make(0, 5, 0), vec3_make(0, 0, 0), vec3_make(0, 1, 0)); /* up parallel to view */
    for (int i = 0; i < 16; i++)
        CHECK(isfinite(v.m[i]));
    vec3 c = mat4_transform_point(v, vec3_make(0, 0, 0));
    CHECK_NEAR(c.z, -5, 1e-5); /* the target lies 5 units in front (-Z) */

    /* perspective maps the near plane to -1 and the far plane to +1 */
    mat4 pr = mat4_perspective(60, 1.5f, 0.1f, 10.0f);
    CHECK_NEAR(mat4_transform_point(pr, vec3_make(0, 0, -0.1f)).z, -1.0, 1e-4);
    CHECK_NEAR(mat4_transform_point(pr, vec3_make(0, 0, -10.0f)).z, 1.0, 1e-4);

    /* quaternions: a quarter turn about Y takes +X to -Z */
    quat q = quat_axis_angle(vec3_make(0, 1, 0), (float)MATH_PI / 2);
    vec3 r = mat4_transform_dir(mat4_from_quat(q), vec3_make(1, 0, 0));
    CHECK_NEAR(r.x, 0, 1e-6);
    CHECK_NEAR(r.z, -1, 1e-6);
    quat z = quat_normalize((quat){0, 0, 0, 0});
    CHECK(z.w == 1.0f);
    /* "did you mean": a typo, a swap, an abbreviation; nothing for a word
     * far from every name */
    static const char *const verbs[] = {"render", "record", "reference", "run", "bench", "choose"};
    CHECK(suggest_nearest("rendr", verbs, 6) && strcmp(suggest_nearest("rendr", verbs, 6), "render") == 0);
    CHECK(suggest_nearest("bnech", verbs, 6) && strcmp(suggest_nearest("bnech", verbs, 6), "bench") == 0);
    CHECK(suggest_nearest("refer", verbs, 6) && strcmp(suggest_nearest("refer", verbs, 6), "reference") == 0);
    CHECK(suggest_nearest("re", verbs, 6) == NULL);
    CHECK(suggest_nearest("compile", verbs, 6) == NULL);
    CHECK(suggest_nearest("", verbs, 6) == NULL);
    static const char *const fields[] = {"radius", "height", "segments"};
    CHECK(suggest_nearest("Radius", fields, 3) && strcmp(suggest_nearest("Radius", fields, 3), "radius") == 0);
    char long_word[200];
    memset(long_word, 'x', sizeof long_word - 1);
    long_word[sizeof long_word - 1] = '\0';
    CHECK(suggest_nearest(long_word, fields, 3) == NULL);
    return check_finish("test_math");
}
