#define _POSIX_C_SOURCE 200809L
#include "app/watchdog.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/log.h"
#include "lua/lua_host.h"

static double watchdog_grace;

static void *watchdog_run(void *arg)
{
    (void)arg;
    const struct timespec tick = {0, 100 * 1000 * 1000};
    for (;;) {
        nanosleep(&tick, NULL);
        double deadline = lua_host_watched_deadline();
        if (deadline > 0 && log_now() > deadline + watchdog_grace) {
            /* The script is stuck where no Lua error can be raised; the
             * only way out is to end the process (the one place besides
             * main that does: the process's own time limit). */
            static const char message[] =
                "caustica: a call into the script ran past --script-timeout inside a C function, a message handler "
                "or a finalizer (a backtracking string pattern, a long image operation, a loop in __gc), where it "
                "cannot be stopped with an error: stopped (raise --script-timeout, or 0 for none)\n";
            ssize_t written = write(STDERR_FILENO, message, sizeof message - 1);
            (void)written;
            _exit(1);
        }
    }
    return NULL;
}

bool watchdog_start(double grace)
{
    watchdog_grace = grace;
    pthread_t thread;
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0)
        return false;
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    bool ok = pthread_create(&thread, &attr, watchdog_run, NULL) == 0;
    pthread_attr_destroy(&attr);
    return ok;
}
