/* The GL function table reports every missing entry point by name. */
#include "check.h"
#include "gl/gl_api.h"

static void dummy(void) {}

static gl_proc fake_get_proc(const char *name)
{
    if (strcmp(name, "glClear") == 0 || strcmp(name, "glDispatchCompute") == 0)
        return NULL;
    return dummy;
}

static gl_proc complete_get_proc(const char *name)
{
    (void)name;
    return dummy;
}

int main(void)
{
    struct error err;
    CHECK(!gl_api_load(fake_get_proc, &err));
    CHECK_CONTAINS(err.message, "lacks 2 entry points");
    CHECK_CONTAINS(err.message, "glClear");
    CHECK_CONTAINS(err.message, "glDispatchCompute");
    CHECK(!gl_api_ready());
    CHECK(gl_api_load(complete_get_proc, &err));
    CHECK(gl_api_ready());
    gl_api_unload();
    CHECK(!gl_api_ready());
    return check_finish("test_gl");
}
