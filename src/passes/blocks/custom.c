/* custom: a pass written in Lua. Its `run(ctx)` function is called each
 * frame, through the script_run callback the bindings set, with a context
 * that clears outputs and runs fullscreen shaders (src/lua/l_pass_context.c
 * translates those calls). */
#include "graph/pass.h"

bool fullscreen_declare_io(struct pass *p, struct error *err);

static const struct pass_param_desc params[] = {
    {.name = "run", .type = PASS_PARAM_FUNCTION, .required = true, .help = "function(ctx) called every frame"},
    {.name = "inputs", .type = PASS_PARAM_INPUT_MAP, .help = "{name = \"pass.output\", ...}"},
    {.name = "outputs", .type = PASS_PARAM_OUTPUT_MAP, .help = "{name = \"rgba32f\", ...}; default {color = \"rgba32f\"}"},
};

static bool custom_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    if (!p->script_run)
        return error_set(err, "custom pass '%s' has no script to run", p->name);
    return p->script_run(p, f, err);
}

static unsigned custom_draws(const struct pass *p)
{
    (void)p;
    return PASS_DRAWS_ANYTHING;
}

const struct pass_desc custom_pass = {
    .draws = custom_draws,
    .name = "custom",
    .summary = "a pass written in Lua: run(ctx) clears outputs and draws fullscreen shaders",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = fullscreen_declare_io,
    .execute = custom_execute,
};
