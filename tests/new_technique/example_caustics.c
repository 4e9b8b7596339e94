/* example_caustics: a technique that exists only in the test build of
 * tests/cli/new_technique_test.sh (issue 54), registered there by
 * -DCAUSTICA_EXTRA_PASS=example_caustics as docs/ARCHITECTURE.md's "Adding
 * a pass" says a new one is: one descriptor, one registry line. It makes no
 * caustics (its irradiance is zero): what the test checks is that a
 * technique joins `help`, the optics matrix and `bench --sweep
 * technique=all` by being registered, with nothing else edited. */
#include "graph/pass.h"

enum example_param { EXAMPLE_LIGHT };

static const struct pass_param_desc params[] = {
    [EXAMPLE_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true,
                       .help = "the light whose caustics it would make"},
};

static bool example_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool example_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    (void)p;
    (void)err;
    const float zero[4] = {0, 0, 0, 0};
    gl_texture_clear(&f->outputs[0]->texture, zero);
    return true;
}

const struct pass_desc example_caustics_pass = {
    .name = "example_caustics",
    .summary = "no caustics at all (the test build's stand-in for a new technique)",
    .technique = PASS_TECHNIQUE_CAUSTICS,
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = example_declare,
    .execute = example_execute,
};
