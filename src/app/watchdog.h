/* The script time limit where the Lua count hook cannot reach: inside a C
 * function (a backtracking string pattern, a long image operation), a
 * message handler or a finalizer (they run without hooks). */
#ifndef CAUSTICA_WATCHDOG_H
#define CAUSTICA_WATCHDOG_H

#include <stdbool.h>

/* Starts the thread that watches lua_host_watched_deadline(): a call still
 * running `grace` seconds past its deadline cannot be stopped from inside,
 * so the process ends with one line and exit status 1 (files are written
 * to temporaries and renamed, so nothing partial is left). False when the
 * thread cannot start (the limit then holds only for Lua code). */
bool watchdog_start(double grace);

#endif
