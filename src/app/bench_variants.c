/* `caustica bench`'s variants: the sweeps given on the command line, and
 * every technique a scene declares at each of its settings, as scene and
 * pass parameters to open a session with (cmd_bench.c measures them). */
#define _POSIX_C_SOURCE 200809L
#include <string.h>

#include "app/bench_internal.h"
#include "core/hash.h"

bool bench_parse_sweep(const char *text, struct sweep *s, struct error *err)
{
    const char *eq = strchr(text, '=');
    snprintf(s->key, sizeof s->key, "%.*s", (int)(eq - text), text);
    s->count = 0;
    const char *p = eq + 1;
    while (*p) {
        const char *comma = strchr(p, ',');
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        if (n == 0 || n >= sizeof s->values[0] || s->count >= MAX_VALUES)
            return error_set(err, "--sweep %s: empty, too long or more than %d values", text, MAX_VALUES);
        snprintf(s->values[s->count++], sizeof s->values[0], "%.*s", (int)n, p);
        p = comma ? comma + 1 : p + n;
    }
    return s->count > 0 ? true : error_set(err, "--sweep %s: no values", text);
}

uint64_t bench_hash_params(uint64_t k, const struct lua_params *params)
{
    for (int i = 0; i < params->count; i++) {
        k = hash_fnv1a(k, params->keys[i], strlen(params->keys[i]) + 1);
        k = hash_fnv1a(k, params->values[i], strlen(params->values[i]) + 1);
    }
    return k;
}

static bool params_merge(struct lua_params *into, const char *key, const char *value, struct error *err)
{
    char assignment[400];
    snprintf(assignment, sizeof assignment, "%.63s=%.300s", key, value);
    return lua_params_add(into, assignment, err);
}

/* The variants of a technique sweep: every declared technique at each of its settings. */
bool bench_technique_variants(const struct technique_list *list, const struct lua_params *base, struct variant *out,
                              int *count, struct error *err)
{
    int n = 0;
    for (int t = 0; t < list->count; t++) {
        const struct technique *tech = &list->items[t];
        for (int p = 0; p < tech->point_count; p++) {
            if (n >= MAX_COMBOS)
                return error_set(err, "more than %d settings in all", MAX_COMBOS);
            struct variant *v = &out[n++];
            memset(v, 0, sizeof *v);
            v->technique = t;
            v->params = *base;
            v->truth_params = *base;
            for (int k = 0; k < tech->set_count; k++)
                if (!params_merge(&v->params, tech->set_keys[k], tech->set_values[k], err))
                    return false;
            const struct technique_point *pt = &tech->points[p];
            for (int k = 0; k < pt->count; k++) {
                if (technique_key_is_pass(pt->keys[k])) {
                    snprintf(v->override_keys[v->override_count], 64, "%s", pt->keys[k]);
                    snprintf(v->override_values[v->override_count++], 64, "%s", pt->values[k]);
                } else if (!params_merge(&v->params, pt->keys[k], pt->values[k], err) ||
                           !params_merge(&v->truth_params, pt->keys[k], pt->values[k], err)) {
                    return false;
                }
            }
            snprintf(v->values[0], sizeof v->values[0], "%s", tech->name);
            technique_point_label(pt, v->values[1], sizeof v->values[1]);
            snprintf(v->label, sizeof v->label, "%s: %s", tech->name, v->values[1]);
        }
    }
    *count = n;
    return true;
}

/* The variants of --sweep key=... (every combination, first sweep slowest). */
bool bench_sweep_variants(const struct sweep *sweeps, int nsweeps, const struct lua_params *base, struct variant *out,
                          int combos, struct error *err)
{
    for (int c = 0; c < combos; c++) {
        struct variant *v = &out[c];
        memset(v, 0, sizeof *v);
        v->technique = -1;
        v->params = *base;
        int rest = c, choice[16];
        for (int k = nsweeps - 1; k >= 0; k--) {
            choice[k] = rest % sweeps[k].count;
            rest /= sweeps[k].count;
        }
        size_t used = 0;
        for (int k = 0; k < nsweeps; k++) {
            const char *value = sweeps[k].values[choice[k]];
            snprintf(v->values[k], sizeof v->values[k], "%s", value);
            int w = snprintf(v->label + used, sizeof v->label - used, "%s%s=%s", k ? " " : "", sweeps[k].key, value);
            if (w > 0 && used + (size_t)w < sizeof v->label)
                used += (size_t)w;
            if (strchr(sweeps[k].key, '.')) {
                snprintf(v->override_keys[v->override_count], 64, "%.63s", sweeps[k].key);
                snprintf(v->override_values[v->override_count++], 64, "%s", value);
            } else if (!params_merge(&v->params, sweeps[k].key, value, err)) {
                return false;
            }
        }
        if (nsweeps == 0)
            snprintf(v->label, sizeof v->label, "default");
        v->truth_params = v->params;
    }
    return true;
}
