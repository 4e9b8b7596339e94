/* caustica: the command line. Exit status: 0 success, 1 a scene, asset or
 * render error (message on stderr), 2 bad usage. */
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "app/cli.h"
#include "app/watchdog.h"

int main(int argc, char **argv)
{
    /* past `ulimit -f` a write fails with EFBIG, which is reported as the
     * file's error, instead of the signal killing the process mid-frame */
    signal(SIGXFSZ, SIG_IGN);
    if (argc >= 2 && strcmp(argv[1], "help") == 0)
        return cmd_help(argc - 2, argv + 2);
    /* the three spellings users try (`-V` as git and gcc take it, `version` as a verb) */
    if (argc >= 2 && (strcmp(argv[1], "--version") == 0 || strcmp(argv[1], "-V") == 0 ||
                      strcmp(argv[1], "version") == 0)) {
        printf("caustica %s\n", CAUSTICA_VERSION);
        return 0;
    }
    if (argc < 2 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        cli_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? EXIT_USAGE : 0;
    }
    static const struct {
        const char *name;
        int (*run)(struct app *, struct cli *);
    } verbs[] = {
        {"render", cmd_render}, {"record", cmd_record}, {"run", cmd_run},
        {"test", cmd_test},     {"info", cmd_info},     {"compare", cmd_compare},
        {"reference", cmd_reference}, {"bench", cmd_bench}, {"choose", cmd_choose},
        {"convert", cmd_convert}, {"merge", cmd_merge},
    };
    for (size_t i = 0; i < sizeof verbs / sizeof verbs[0]; i++) {
        if (strcmp(argv[1], verbs[i].name) != 0)
            continue;
        if (argc >= 3 && (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
            cli_usage_verb(stdout, verbs[i].name);
            return 0;
        }
        static struct app app;
        static struct cli cli;
        app_init(&app);
        if (!cli_parse(verbs[i].name, argc - 2, argv + 2, &app, &cli))
            return EXIT_USAGE;
        /* the script time limit inside C functions too: a second past it */
        if (app.script_timeout > 0 && !watchdog_start(1.0))
            fprintf(stderr, "caustica: warning: no watchdog thread: --script-timeout holds only for Lua code\n");
        int rc = verbs[i].run(&app, &cli);
        app_shutdown(&app);
        return rc;
    }
    const char *near = cli_suggest_verb(argv[1]);
    if (near)
        fprintf(stderr, "caustica: unknown command '%s' (did you mean '%s'?)\n", argv[1], near);
    else
        fprintf(stderr, "caustica: unknown command '%s'\n", argv[1]);
    cli_usage_hint(NULL);
    return EXIT_USAGE;
}
