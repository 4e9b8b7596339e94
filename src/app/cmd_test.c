/* `caustica test [PATH ...]`: runs scripted regression tests (files named
 * *_test.lua, folders searched), one line per case, and ends with
 * "N passed, N failed". */
#define _DEFAULT_SOURCE
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <lauxlib.h>

#include "app/cli.h"
#include "app/test_report.h"
#include "core/fileio.h"
#include "lua/lua_host.h"

static int compare_strings(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static bool is_test_file(const char *name)
{
    size_t n = strlen(name);
    return n > 9 && strcmp(name + n - 9, "_test.lua") == 0;
}

/* The folders a walk has entered, by device and inode: a folder reached
 * again (a link to itself or to a parent) is not walked twice. */
struct walk_seen {
    dev_t *dev;
    ino_t *ino;
    int count, capacity;
};

#define TEST_WALK_DEPTH 32

/* Collects test files under `path` (a file or a folder), sorted. Links
 * are followed (a tests folder may be linked in), but each folder is
 * walked once and no deeper than TEST_WALK_DEPTH. */
static void collect(const char *path, char ***files, int *count, int *cap, struct walk_seen *seen, int depth)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return;
    if (S_ISREG(st.st_mode)) {
        if (*count == *cap) {
            int ncap = *cap ? *cap * 2 : 32;
            char **grown = realloc(*files, (size_t)ncap * sizeof **files);
            if (!grown)
                return;
            *files = grown;
            *cap = ncap;
        }
        char *copy = strdup(path);
        if (copy)
            (*files)[(*count)++] = copy;
        return;
    }
    if (!S_ISDIR(st.st_mode) || depth > TEST_WALK_DEPTH)
        return;
    for (int i = 0; i < seen->count; i++)
        if (seen->dev[i] == st.st_dev && seen->ino[i] == st.st_ino)
            return; /* walked already: a link back into the tree */
    if (seen->count == seen->capacity) {
        int grown = seen->capacity ? seen->capacity * 2 : 64;
        dev_t *dev = realloc(seen->dev, (size_t)grown * sizeof *dev);
        if (dev)
            seen->dev = dev;
        ino_t *ino = dev ? realloc(seen->ino, (size_t)grown * sizeof *ino) : NULL;
        if (!ino)
            return;
        seen->ino = ino;
        seen->capacity = grown;
    }
    seen->dev[seen->count] = st.st_dev;
    seen->ino[seen->count++] = st.st_ino;
    DIR *d = opendir(path);
    if (!d)
        return;
    struct dirent *e;
    char **names = NULL;
    int n = 0, ncap = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.')
            continue;
        char child[4096];
        if (snprintf(child, sizeof child, "%s/%s", path, e->d_name) >= (int)sizeof child)
            continue;
        struct stat cs;
        if (stat(child, &cs) != 0 || (!S_ISDIR(cs.st_mode) && !is_test_file(e->d_name)))
            continue;
        if (n == ncap) {
            int grown_cap = ncap ? ncap * 2 : 32;
            char **grown = realloc(names, (size_t)grown_cap * sizeof *names);
            if (!grown)
                break;
            names = grown;
            ncap = grown_cap;
        }
        if ((names[n] = strdup(child)))
            n++;
    }
    closedir(d);
    if (n > 1)
        qsort(names, (size_t)n, sizeof *names, compare_strings);
    for (int i = 0; i < n; i++) {
        collect(names[i], files, count, cap, seen, depth + 1);
        free(names[i]);
    }
    free(names);
}

/* The harness's t._results from index `from` on (the module table on top
 * of the stack) into the report; returns the count now collected. A
 * result the test file added itself may lack any field: it is reported
 * under the test file's name. */
static lua_Integer collect_results(lua_State *L, const char *file, lua_Integer from, struct test_report *report)
{
    lua_getfield(L, -1, "_results");
    if (!lua_istable(L, -1)) {
        lua_pop(L, 1);
        return from;
    }
    lua_Integer n = luaL_len(L, -1);
    for (lua_Integer k = from + 1; k <= n; k++) {
        if (lua_rawgeti(L, -1, k) != LUA_TTABLE) {
            lua_pop(L, 1);
            continue;
        }
        struct test_case_result r = {0};
        lua_getfield(L, -1, "file");
        lua_getfield(L, -2, "name");
        lua_getfield(L, -3, "message");
        lua_getfield(L, -4, "ok");
        lua_getfield(L, -5, "seconds");
        r.file = lua_type(L, -5) == LUA_TSTRING ? (char *)lua_tostring(L, -5) : (char *)file;
        r.name = lua_type(L, -4) == LUA_TSTRING ? (char *)lua_tostring(L, -4) : "(a result without a name)";
        r.message = lua_type(L, -3) == LUA_TSTRING ? (char *)lua_tostring(L, -3) : "";
        r.ok = lua_toboolean(L, -2);
        r.seconds = lua_type(L, -1) == LUA_TNUMBER ? lua_tonumber(L, -1) : 0.0;
        int images = lua_getfield(L, -6, "images");
        static const char *const keys[3] = {"new", "ref", "diff"};
        for (int j = 0; j < 3; j++) {
            if (images == LUA_TTABLE) {
                lua_getfield(L, -1 - j, keys[j]);
                r.images[j] = lua_type(L, -1) == LUA_TSTRING ? (char *)lua_tostring(L, -1) : NULL;
            }
        }
        test_report_add(report, &r);
        lua_pop(L, 7 + (images == LUA_TTABLE ? 3 : 0));
    }
    lua_pop(L, 1);
    return n > from ? n : from;
}

/* Calls the harness's function `fn` (the module on top of the stack) with
 * the file's path and, when k > 0, a case index. */
static bool harness_call(lua_State *L, const char *fn, const char *file, lua_Integer k, int nresults,
                         struct error *err)
{
    lua_getfield(L, -1, fn);
    int nargs = 0;
    if (file) {
        lua_pushstring(L, file);
        nargs++;
    }
    if (k > 0) {
        lua_pushinteger(L, k);
        nargs++;
    }
    return lua_host_call(L, nargs, nresults, NULL, err);
}

/* Runs one test file's cases, each a call of its own into the script, so
 * that --script-timeout and --script-memory hold every case (nested
 * renders included: their hosts have the same limits). */
static void run_file(struct app *app, struct cli *cli, const char *file, long *passed, long *failed,
                     struct test_report *report)
{
    bool reporting = cli->report_html || cli->junit;
    const char *asset_dirs[LUA_HOST_ASSET_DIRS_MAX];
    int asset_dir_count = app_asset_dirs(app, asset_dirs, LUA_HOST_ASSET_DIRS_MAX);
    struct lua_host_options ho = {.root = app->root, .script_path = file, .trusted = true,
                                  .render = session_render_service, .render_context = app,
                                  .update_refs = cli->update_refs, .filter = cli->filter,
                                  .report = cli->report_html != NULL,
                                  .timeout = app->script_timeout, .memory_limit = app->script_memory,
                                  .asset_dirs = asset_dirs, .asset_dir_count = asset_dir_count};
    struct error err;
    lua_State *L = lua_host_create(&ho, &err);
    bool ok = L && lua_host_run_file(L, file, 0, &err);
    if (ok) {
        lua_getglobal(L, "require");
        lua_pushstring(L, "caustica.test");
        ok = lua_host_call(L, 1, 1, NULL, &err) && harness_call(L, "_case_count", NULL, 0, 1, &err);
    }
    if (!ok) {
        printf("FAIL %s: %s\n", file, err.message);
        (*failed)++;
        struct test_case_result r = {.file = (char *)file, .name = "(the file)", .message = err.message};
        if (reporting)
            test_report_add(report, &r);
        fflush(stdout);
        lua_host_destroy(L);
        return;
    }
    lua_Integer cases = lua_isinteger(L, -1) ? lua_tointeger(L, -1) : 0;
    lua_pop(L, 1);
    lua_Integer collected = 0;
    for (lua_Integer k = 1; k <= cases; k++) {
        char name[512];
        if (!harness_call(L, "_case_name", NULL, k, 1, &err)) {
            snprintf(name, sizeof name, "case %lld", (long long)k);
        } else {
            bool skipped = lua_isnil(L, -1);
            snprintf(name, sizeof name, "%s", skipped ? "" : luaL_tolstring(L, -1, NULL));
            lua_pop(L, skipped ? 1 : 2);
            if (skipped)
                continue;
        }
        if (harness_call(L, "_run_case", file, k, 1, &err)) {
            if (lua_toboolean(L, -1))
                (*passed)++;
            else
                (*failed)++;
            lua_pop(L, 1);
        } else {
            /* the case ran past a limit: it fails, the file goes on */
            printf("FAIL %s: %s: %s\n", file, name, err.message);
            (*failed)++;
            struct test_case_result r = {.file = (char *)file, .name = name, .message = err.message};
            if (reporting)
                test_report_add(report, &r);
        }
        if (reporting)
            collected = collect_results(L, file, collected, report);
        fflush(stdout);
    }
    lua_host_destroy(L);
}

int cmd_test(struct app *app, struct cli *cli)
{
    char **files = NULL;
    int count = 0, cap = 0;
    char default_dir[4200];
    snprintf(default_dir, sizeof default_dir, "%s/tests/lua", app->root);
    struct walk_seen seen = {0};
    if (cli->npositional == 0)
        collect(default_dir, &files, &count, &cap, &seen, 0);
    for (int i = 0; i < cli->npositional; i++) {
        if (!file_exists(cli->positional[i])) {
            fprintf(stderr, "caustica: test: %s: no such file or folder\n", cli->positional[i]);
            return EXIT_USAGE;
        }
        collect(cli->positional[i], &files, &count, &cap, &seen, 0);
    }
    long passed = 0, failed = 0;
    struct test_report report = {0};
    for (int i = 0; i < count; i++) {
        run_file(app, cli, files[i], &passed, &failed, &report);
        free(files[i]);
    }
    free(files);
    free(seen.dev);
    free(seen.ino);
    if (count == 0)
        printf("no test files found\n");
    /* A filter that selects nothing is a typo, not a green run. */
    bool none_ran = count > 0 && passed == 0 && failed == 0;
    if (none_ran)
        fprintf(stderr, "caustica: test: no case matches --filter '%s' in %d file%s\n", cli->filter ? cli->filter : "",
                count, count == 1 ? "" : "s");
    bool written = true;
    if (cli->report_html) {
        struct error err;
        written = test_report_write(&report, cli->report_html, &err);
        if (written)
            fprintf(stderr, "caustica: test: report in %s\n", cli->report_html);
        else
            cli_print_error(&err);
    }
    if (cli->junit) {
        struct error err;
        bool junit = test_report_write_junit(&report, cli->junit, &err);
        if (junit)
            fprintf(stderr, "caustica: test: JUnit XML in %s\n", cli->junit);
        else
            cli_print_error(&err);
        written = written && junit;
    }
    test_report_release(&report);
    printf("%ld passed, %ld failed\n", passed, failed);
    return failed == 0 && count > 0 && !none_ran && written ? 0 : EXIT_SCENE_ERROR;
}
