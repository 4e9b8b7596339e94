/* What every file-reading fuzz harness does: a private folder of its own
 * (named by harness and process, so parallel runs do not share files) and
 * each input written to a file there before the reader opens it. */
#ifndef CAUSTICA_FUZZ_FILES_H
#define CAUSTICA_FUZZ_FILES_H

#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

/* /tmp/caustica-fuzz-NAME.PID, made if missing; false when it cannot be. */
static inline bool fuzz_private_dir(const char *name, char *dir, size_t len)
{
    snprintf(dir, len, "/tmp/caustica-fuzz-%s.%ld", name, (long)getpid());
    return mkdir(dir, 0700) == 0 || errno == EEXIST;
}

/* The input as the file at `path`; false when it cannot be written. */
static inline bool fuzz_write_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    bool ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok;
}

#endif
