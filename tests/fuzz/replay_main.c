/* Replays fuzz inputs through a harness without libFuzzer: every file named
 * on the command line (folders are read file by file) runs once through
 * LLVMFuzzerTestOneInput. ctest runs it on the seed corpus and on every
 * crash input kept in tests/fuzz/crashes_*, so a fixed crash stays fixed in
 * the ordinary (gcc) build, and under -DCAUSTICA_SANITIZE=ON.
 *
 * Each input has REPLAY_SECONDS: libFuzzer keeps an input that ran past its
 * -timeout as a "timeout-" file, and one such input (an endless loop in the
 * EXR layer lookup) once held a CI run until the CI's own limit. Past the
 * limit the replay names the input and fails at once. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <signal.h>
#include <unistd.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { REPLAY_SECONDS = 30 };

static char replay_current[4096];

static void replay_timed_out(int sig)
{
    (void)sig;
    /* async-signal-safe: write(2) only */
    static const char head[] = "replay: an input ran past 30 s (a hang; see tests/fuzz/README.md): ";
    ssize_t ignored = write(2, head, sizeof head - 1);
    ignored = write(2, replay_current, strlen(replay_current));
    ignored = write(2, "\n", 1);
    (void)ignored;
    _exit(124);
}

static int run_file(const char *path)
{
    snprintf(replay_current, sizeof replay_current, "%s", path);
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s: cannot open\n", path);
        return 1;
    }
    uint8_t *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (len == cap) {
            cap = cap ? cap * 2 : 65536;
            uint8_t *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(f);
                return 1;
            }
            buf = grown;
        }
        size_t n = fread(buf + len, 1, cap - len, f);
        if (n == 0)
            break;
        len += n;
    }
    fclose(f);
    alarm(REPLAY_SECONDS);
    LLVMFuzzerTestOneInput(buf, len);
    alarm(0);
    free(buf);
    return 0;
}

int main(int argc, char **argv)
{
    signal(SIGALRM, replay_timed_out);
    LLVMFuzzerInitialize(&argc, &argv);
    int files = 0, failed = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0)
            continue;
        if (!S_ISDIR(st.st_mode)) {
            failed += run_file(argv[i]);
            files++;
            continue;
        }
        DIR *d = opendir(argv[i]);
        struct dirent *e;
        while (d && (e = readdir(d))) {
            if (e->d_name[0] == '.' || strcmp(e->d_name, "README.md") == 0)
                continue;
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[i], e->d_name);
            failed += run_file(path);
            files++;
        }
        if (d)
            closedir(d);
    }
    printf("replayed %d inputs (%d unreadable)\n", files, failed);
    return failed ? 1 : 0;
}
