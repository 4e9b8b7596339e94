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

/* Collects test files under `path` (a file or a folder), sorted. */
static void collect(const char *path, char ***files, int *count, int *cap)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return;
    if (S_ISREG(st.st_mode)) {
        if (*count == *cap) {
            *cap = *cap ? *cap * 2 : 32;
            *files = realloc(*files, (size_t)*cap * sizeof **files);
        }
        (*files)[(*count)++] = strdup(path);
        return;
    }
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
        snprintf(child, sizeof child, "%s/%s", path, e->d_name);
        struct stat cs;
        if (stat(child, &cs) != 0 || (!S_ISDIR(cs.st_mode) && !is_test_file(e->d_name)))
            continue;
        if (n == ncap) {
            ncap = ncap ? ncap * 2 : 32;
            names = realloc(names, (size_t)ncap * sizeof *names);
        }
        names[n++] = strdup(child);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof *names, compare_strings);
    for (int i = 0; i < n; i++) {
        collect(names[i], files, count, cap);
        free(names[i]);
    }
    free(names);
}

/* The harness's t._results (the module table on top of the stack) into the report. */
static void collect_results(lua_State *L, struct test_report *report)
{
    lua_getfield(L, -1, "_results");
    if (!lua_istable(L, -1)) {
        lua_pop(L, 1);
        return;
    }
    lua_Integer n = luaL_len(L, -1);
    for (lua_Integer k = 1; k <= n; k++) {
        lua_rawgeti(L, -1, k);
        struct test_case_result r = {0};
        lua_getfield(L, -1, "file");
        lua_getfield(L, -2, "name");
        lua_getfield(L, -3, "message");
        lua_getfield(L, -4, "ok");
        lua_getfield(L, -5, "seconds");
        r.file = (char *)lua_tostring(L, -5);
        r.name = (char *)lua_tostring(L, -4);
        r.message = (char *)lua_tostring(L, -3);
        r.ok = lua_toboolean(L, -2);
        r.seconds = lua_tonumber(L, -1);
        int images = lua_getfield(L, -6, "images");
        static const char *const keys[3] = {"new", "ref", "diff"};
        for (int j = 0; j < 3; j++) {
            if (images == LUA_TTABLE) {
                lua_getfield(L, -1 - j, keys[j]);
                r.images[j] = (char *)lua_tostring(L, -1);
            }
        }
        test_report_add(report, &r);
        lua_pop(L, 7 + (images == LUA_TTABLE ? 3 : 0));
    }
    lua_pop(L, 1);
}

int cmd_test(struct app *app, struct cli *cli)
{
    char **files = NULL;
    int count = 0, cap = 0;
    char default_dir[4200];
    snprintf(default_dir, sizeof default_dir, "%s/tests/lua", app->root);
    if (cli->npositional == 0)
        collect(default_dir, &files, &count, &cap);
    for (int i = 0; i < cli->npositional; i++) {
        if (!file_exists(cli->positional[i])) {
            fprintf(stderr, "caustica: test: %s: no such file or folder\n", cli->positional[i]);
            return EXIT_USAGE;
        }
        collect(cli->positional[i], &files, &count, &cap);
    }
    long passed = 0, failed = 0;
    struct test_report report = {0};
    for (int i = 0; i < count; i++) {
        const char *asset_dirs[LUA_HOST_ASSET_DIRS_MAX];
        int asset_dir_count = app_asset_dirs(app, asset_dirs, LUA_HOST_ASSET_DIRS_MAX);
        struct lua_host_options ho = {.root = app->root, .script_path = files[i], .trusted = true,
                                      .render = session_render_service, .render_context = app,
                                      .update_refs = cli->update_refs, .filter = cli->filter,
                                      .report = cli->report_html != NULL,
                                      .asset_dirs = asset_dirs, .asset_dir_count = asset_dir_count};
        struct error err;
        lua_State *L = lua_host_create(&ho, &err);
        bool ok = L && lua_host_run_file(L, files[i], 0, &err);
        if (ok) {
            lua_getglobal(L, "require");
            lua_pushstring(L, "caustica.test");
            ok = lua_host_call(L, 1, 1, NULL, &err);
            if (ok) {
                lua_getfield(L, -1, "_run");
                lua_pushstring(L, files[i]);
                ok = lua_host_call(L, 1, 2, NULL, &err);
                if (ok) {
                    passed += (long)lua_tointeger(L, -2);
                    failed += (long)lua_tointeger(L, -1);
                    lua_pop(L, 2);
                    if (cli->report_html || cli->junit)
                        collect_results(L, &report);
                }
            }
        }
        if (!ok) {
            printf("FAIL %s: %s\n", files[i], err.message);
            failed++;
            struct test_case_result r = {.file = files[i], .name = "(the file)", .message = err.message};
            if (cli->report_html || cli->junit)
                test_report_add(&report, &r);
        }
        fflush(stdout);
        lua_host_destroy(L);
        free(files[i]);
    }
    free(files);
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
