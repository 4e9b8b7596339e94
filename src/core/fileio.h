/* Reading whole files, writing atomically (temporary file, then rename), and
 * path helpers. */
#ifndef CAUSTICA_FILEIO_H
#define CAUSTICA_FILEIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "core/error.h"

/* Reads a whole file; the buffer is NUL-terminated and owned by the caller. */
bool file_read_all(const char *path, char **data, size_t *size, struct error *err);
bool file_exists(const char *path);
/* Modification time in nanoseconds, 0 when the file does not exist. */
long long file_mtime_ns(const char *path);
/* Directory part of `path` ("." when none) into `out`. */
void path_dirname(const char *path, char *out, size_t outlen);
/* `rel` resolved against directory `dir` unless it is absolute. */
void path_join(const char *dir, const char *rel, char *out, size_t outlen);
/* Where an atomic writer puts data before renaming: ".<name>.caustica-tmp.<pid>"
 * in the same folder. */
#define PATH_TEMPORARY_MARK ".caustica-tmp."
void path_temporary(const char *path, char *out, size_t outlen);
/* Creates that temporary exclusively (O_EXCL, with an unpredictable suffix:
 * ".<name>.caustica-tmp.<pid>.XXXXXX"), so a file or link planted at a
 * guessable name in a shared folder is never written through; mode 0666
 * less the umask. The open descriptor, or -1 with `err` set. */
int path_temporary_create(const char *path, char *out, size_t outlen, struct error *err);
/* A private folder (mode 0700, mkdtemp) beside `path` for a program that
 * writes files by name (ffmpeg): ".<name>.caustica-tmp.<pid>.XXXXXX", where
 * no one else can plant a link; path_temporary_dir_remove empties (regular
 * files only) and removes it, as path_remove_stale_temporaries does for a
 * dead writer's. */
bool path_temporary_dir_create(const char *path, char *out, size_t outlen, struct error *err);
void path_temporary_dir_remove(const char *dir);
/* Opens a file to read, refusing what is not a regular file (a FIFO would
 * block forever, a device or folder is no image) without blocking on it;
 * `no_follow`: a link as the last component is refused too (cache entries). */
FILE *file_open_read(const char *path, bool no_follow, struct error *err);
/* Removes the temporaries of writers that no longer run (a record killed
 * with SIGKILL) from `dir`; returns how many. */
int path_remove_stale_temporaries(const char *dir);
/* Checks that the folder that would hold `path` exists and is writable. */
bool path_check_writable_dir(const char *path, struct error *err);
/* Creates a directory (one level) when it does not exist. */
bool dir_ensure(const char *path, struct error *err);
/* mkdir -p: `path` and every missing folder above it; `created` gets the
 * topmost folder it made ("" when it made none), to remove on failure. */
bool dir_ensure_all(const char *path, char *created, size_t created_len, struct error *err);

#endif
