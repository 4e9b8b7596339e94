#define _DEFAULT_SOURCE
/* The graph's order check and pruning, without a GL context. */
#include <stdlib.h>

#include "check.h"
#include "graph/graph.h"
#include "scene/scene.h"

static struct pass *make(const char *kind, const char *param, const char *value, struct light *light)
{
    const struct pass_desc *d = pass_registry_find(kind);
    struct pass *p = pass_create(d);
    if (light) {
        int i = pass_param_index(d, "light");
        pass_set_light(p, i, light);
        p->values[i].set = true;
    }
    if (param) {
        int i = pass_param_index(d, param);
        struct pass_value *v = &p->values[i];
        v->set = true;
        if (d->params[i].type == PASS_PARAM_INPUT_LIST) {
            struct error e;
            const char *items[1] = {value};
            if (!pass_set_list(p, i, items, 1, &e))
                fprintf(stderr, "list failed: %s\n", e.message);
        } else {
            v->string = strdup(value);
        }
    }
    struct error err;
    if (!pass_declare(p, &err))
        fprintf(stderr, "declare failed: %s\n", err.message);
    return p;
}

/* The parameter setters: the one place values are validated. */
static void test_setters(void)
{
    struct error err;
    /* lists, maps and colours by index: capped, checked, copied */
    {
        struct pass *sh = pass_create(pass_registry_find("shade"));
        int caustics = pass_param_index(sh->desc, "caustics");
        const char *five[5] = {"a.irradiance", "b.irradiance", "c.irradiance", "d.irradiance", "e.irradiance"};
        CHECK(!pass_set_list(sh, caustics, five, 5, &err));
        CHECK_CONTAINS(err.message, "at most 4 inputs, got 5");
        const char *bad[2] = {"a.irradiance", "nodot"};
        CHECK(!pass_set_list(sh, caustics, bad, 2, &err));
        CHECK_CONTAINS(err.message, "item 2");
        char name[32] = "x.irradiance";
        const char *two[2] = {name, "y.irradiance"};
        CHECK(pass_set_list(sh, caustics, two, 2, &err));
        name[0] = 'z'; /* the pass keeps its own copy */
        CHECK(strcmp(sh->values[caustics].list[0], "x.irradiance") == 0 && sh->values[caustics].list_count == 2);
        CHECK(pass_declare(sh, &err));
        bool declared = false;
        for (int k = 0; k < sh->input_count; k++)
            declared = declared || (strcmp(sh->inputs[k].name, "caustics1") == 0 &&
                                    strcmp(sh->inputs[k].source, "y.irradiance") == 0);
        CHECK(declared);
        CHECK(!pass_set_color(sh, caustics, vec3_make(1, 1, 1), &err)); /* not a colour parameter */
        pass_destroy(sh);
        struct pass *custom = pass_create(pass_registry_find("fullscreen"));
        int uniforms = pass_param_index(custom->desc, "uniforms");
        CHECK(uniforms >= 0);
        if (uniforms >= 0) {
            const char *keys[2] = {"u_gain", "u_tint"};
            const float vectors[2][4] = {{2, 0, 0, 0}, {1, NAN, 0, 0}};
            const int sizes[2] = {1, 3};
            CHECK(!pass_set_map(custom, uniforms, keys, NULL, vectors, sizes, 2, &err));
            CHECK_CONTAINS(err.message, "u_tint");
            CHECK(pass_set_map(custom, uniforms, keys, NULL, vectors, sizes, 1, &err));
            CHECK(custom->values[uniforms].list_count == 1 && custom->values[uniforms].vector_sizes[0] == 1);
        }
        pass_destroy(custom);
    }
    struct light *lamp = light_create(LIGHT_POINT);
    struct pass *shadow = make("shadow_map", NULL, NULL, lamp);
    CHECK(pass_set_number(shadow, "size", 512, &err));
    CHECK(pass_int(shadow, pass_param_index(shadow->desc, "size")) == 512);
    CHECK(!pass_set_number(shadow, "size", 0, &err));
    CHECK_CONTAINS(err.message, "bad argument 'size' to 'shadow_map' (0 is out of range 16..8192)");
    CHECK(!pass_set_number(shadow, "size", 100.5, &err));
    CHECK_CONTAINS(err.message, "integer expected, got 100.5");
    CHECK(!pass_set_number(shadow, "bias", NAN, &err));
    CHECK_CONTAINS(err.message, "a finite number expected, got nan");
    CHECK(!pass_set_number(shadow, "light", 1, &err));
    CHECK_CONTAINS(err.message, "not a number parameter");
    CHECK(!pass_set_number(shadow, "nosuch", 1, &err));
    CHECK_CONTAINS(err.message, "has no parameter 'nosuch'");
    CHECK(pass_int(shadow, pass_param_index(shadow->desc, "size")) == 512); /* a refused value changes nothing */

    /* Enums are stored as their index into the choices; the default too. */
    struct pass *refr = pass_create(pass_registry_find("refraction"));
    int method = pass_param_index(refr->desc, "method");
    CHECK(pass_choice(refr, method) == 0);
    CHECK(pass_set_enum(refr, "method", "wyman", &err));
    CHECK(pass_choice(refr, method) == 1);
    CHECK(!pass_set_enum(refr, "method", "snell", &err));
    CHECK_CONTAINS(err.message, "one of huqin|wyman expected, got 'snell'");
    /* An input with a default beside another: depth follows color's pass. */
    CHECK(pass_set_string(refr, "color", "shade.color", &err));
    CHECK(pass_declare(refr, &err));
    CHECK(refr->input_count == 2 && strcmp(refr->inputs[1].name, "depth") == 0 &&
          strcmp(refr->inputs[1].source, "shade.depth") == 0);
    CHECK(pass_set_string(refr, "depth", "other.depth", &err) && pass_declare(refr, &err));
    CHECK(strcmp(refr->inputs[1].source, "other.depth") == 0);
    pass_destroy(refr);
    pass_destroy(shadow);
    light_destroy(lamp);
}

int main(void)
{
    test_setters();
    struct error err;
    struct light *sun = light_create(LIGHT_DIRECTIONAL);

    /* A working graph: shadow -> shade, output shade.color; env is unused. */
    struct graph g;
    graph_init(&g);
    struct pass *env = make("environment", NULL, NULL, NULL);
    struct pass *shadow = make("shadow_map", NULL, NULL, sun);
    struct pass *shade = make("shade", "shadow", "shadow.depth", NULL);
    CHECK(graph_add(&g, "env", env, &err));
    CHECK(graph_add(&g, "shadow", shadow, &err));
    CHECK(graph_add(&g, "shade", shade, &err));
    CHECK(!graph_add(&g, "shade", env, &err));
    CHECK_CONTAINS(err.message, "already in the graph");
    CHECK(!graph_add(&g, "bad.name", env, &err));
    CHECK(!graph_check(&g, &err));
    CHECK_CONTAINS(err.message, "no output");
    CHECK(graph_set_output(&g, "shade.color", &err));
    CHECK(graph_check(&g, &err));
    CHECK(g.entries[0].state == GRAPH_PASS_PRUNED);
    CHECK_CONTAINS(g.entries[0].reason, "contributes nothing");
    CHECK(g.entries[1].state == GRAPH_PASS_KEPT);
    CHECK(g.entries[2].state == GRAPH_PASS_KEPT);

    /* The output names a missing output. */
    CHECK(graph_set_output(&g, "shade.colour", &err));
    CHECK(!graph_check(&g, &err));
    CHECK_CONTAINS(err.message, "'shade.colour' is made by no pass");
    CHECK(!graph_set_output(&g, "nodot", &err));
    graph_release(&g);

    /* Order: shade reads shadow.depth, made only by a later pass. */
    graph_init(&g);
    CHECK(graph_add(&g, "shade", shade, &err));
    CHECK(graph_add(&g, "shadow", shadow, &err));
    CHECK(graph_set_output(&g, "shade.color", &err));
    CHECK(!graph_check(&g, &err));
    CHECK_CONTAINS(err.message, "pass 'shade'");
    CHECK_CONTAINS(err.message, "shadow.depth");
    CHECK_CONTAINS(err.message, "move 'shadow' before 'shade'");
    graph_release(&g);

    /* An input nobody makes: the message lists outputs of that name. */
    struct pass *shade2 = make("shade", "shadow", "lamp.depth", NULL);
    graph_init(&g);
    CHECK(graph_add(&g, "shadow", shadow, &err));
    CHECK(graph_add(&g, "shade", shade2, &err));
    CHECK(graph_set_output(&g, "shade.color", &err));
    CHECK(!graph_check(&g, &err));
    CHECK_CONTAINS(err.message, "'lamp.depth', which no earlier pass makes");
    CHECK_CONTAINS(err.message, "'shadow.depth'");
    graph_release(&g);

    /* Registry: every descriptor has a name, an execute and unique params. */
    for (int i = 0; i < pass_registry_count(); i++) {
        const struct pass_desc *d = pass_registry_get(i);
        CHECK(d->name && d->execute && d->declare);
        CHECK(pass_registry_find(d->name) == d);
    }
    CHECK(pass_registry_find("no_such_pass") == NULL);

    pass_destroy(env);
    pass_destroy(shadow);
    pass_destroy(shade);
    pass_destroy(shade2);
    light_destroy(sun);
    return check_finish("test_graph");
}
