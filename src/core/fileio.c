#define _POSIX_C_SOURCE 200809L
#include "core/fileio.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool file_read_all(const char *path, char **data, size_t *size, struct error *err)
{
    /* A folder opens and "seeks" to a huge size, a FIFO blocks: only regular files. */
    FILE *f = file_open_read(path, false, err);
    if (!f)
        return false;
    if (fseek(f, 0, SEEK_END) != 0) {
        fclose(f);
        return error_set(err, "%s: cannot seek", path);
    }
    long len = ftell(f);
    if (len < 0) {
        fclose(f);
        return error_set(err, "%s: cannot tell size", path);
    }
    rewind(f);
    char *buf = malloc((size_t)len + 1);
    if (!buf) {
        fclose(f);
        return error_set(err, "%s: out of memory (%ld bytes)", path, len);
    }
    size_t got = fread(buf, 1, (size_t)len, f);
    fclose(f);
    if (got != (size_t)len) {
        free(buf);
        return error_set(err, "%s: short read", path);
    }
    buf[len] = '\0';
    *data = buf;
    if (size)
        *size = (size_t)len;
    return true;
}

bool file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

long long file_mtime_ns(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 0;
    return (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
}

void path_dirname(const char *path, char *out, size_t outlen)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(out, outlen, ".");
        return;
    }
    size_t n = (size_t)(slash - path);
    if (n == 0)
        n = 1; /* "/file" -> "/" */
    if (n >= outlen)
        n = outlen - 1;
    memcpy(out, path, n);
    out[n] = '\0';
}

void path_join(const char *dir, const char *rel, char *out, size_t outlen)
{
    if (rel[0] == '/' || !dir || !dir[0] || strcmp(dir, ".") == 0)
        snprintf(out, outlen, "%s", rel);
    else
        snprintf(out, outlen, "%s/%s", dir, rel);
}

/* ".<name>.caustica-tmp.<pid>" beside the file: hidden, and named so that
 * path_remove_stale_temporaries can tell a dead writer's leftovers. */
void path_temporary(const char *path, char *out, size_t outlen)
{
    const char *slash = strrchr(path, '/');
    int dir_len = slash ? (int)(slash - path + 1) : 0;
    snprintf(out, outlen, "%.*s.%s" PATH_TEMPORARY_MARK "%ld", dir_len, path, path + dir_len, (long)getpid());
}

int path_temporary_create(const char *path, char *out, size_t outlen, struct error *err)
{
    char base[4096];
    path_temporary(path, base, sizeof base);
    if ((size_t)snprintf(out, outlen, "%s.XXXXXX", base) >= outlen) {
        error_set(err, "%s: path too long", path);
        return -1;
    }
    int fd = mkstemp(out); /* O_CREAT | O_EXCL: never an existing file, never through a link */
    if (fd < 0) {
        error_set(err, "%s: cannot create a temporary beside it: %s", path, strerror(errno));
        return -1;
    }
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask); /* mkstemp's 0600 would make every image private */
    return fd;
}

bool path_temporary_dir_create(const char *path, char *out, size_t outlen, struct error *err)
{
    char base[4096];
    path_temporary(path, base, sizeof base);
    if ((size_t)snprintf(out, outlen, "%s.XXXXXX", base) >= outlen)
        return error_set(err, "%s: path too long", path);
    if (!mkdtemp(out))
        return error_set(err, "%s: cannot create a temporary folder beside it: %s", path, strerror(errno));
    return true;
}

void path_temporary_dir_remove(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d))) {
        char path[4400];
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (lstat(path, &st) == 0 && (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)))
            unlink(path); /* a link is removed, never followed */
    }
    closedir(d);
    rmdir(dir);
}

FILE *file_open_read(const char *path, bool no_follow, struct error *err)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | (no_follow ? O_NOFOLLOW : 0));
    if (fd < 0) {
        if (errno == ELOOP && no_follow)
            error_set(err, "%s: is a symbolic link; a cache entry is never read through one", path);
        else
            error_set(err, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        error_set(err, "%s: not a regular file%s", path,
                  S_ISDIR(st.st_mode) ? " (it is a folder)" : S_ISFIFO(st.st_mode) ? " (a FIFO: refused, it would block)"
                                                                                   : " (a device or socket)");
        close(fd);
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0)
        fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        error_set(err, "%s: cannot open: %s", path, strerror(errno));
        close(fd);
    }
    return f;
}

int path_remove_stale_temporaries(const char *dir)
{
    DIR *d = opendir(dir && dir[0] ? dir : ".");
    if (!d)
        return 0;
    int removed = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        const char *mark = e->d_name[0] == '.' ? strstr(e->d_name, PATH_TEMPORARY_MARK) : NULL;
        if (!mark)
            continue;
        char *end;
        long pid = strtol(mark + strlen(PATH_TEMPORARY_MARK), &end, 10);
        if ((*end && *end != '.') || pid <= 0) /* ".<pid>" or ".<pid>.XXXXXX" */
            continue;
        /* A writer that still runs keeps its file (kill(pid, 0) succeeds
         * or says EPERM); only a dead one's is stale. */
        if (pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir && dir[0] ? dir : ".", e->d_name);
        struct stat st;
        if (lstat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode)) { /* a video encoder's private folder */
            if (st.st_uid == geteuid()) {
                path_temporary_dir_remove(path);
                removed += access(path, F_OK) != 0;
            }
        } else if (unlink(path) == 0)
            removed++;
    }
    closedir(d);
    return removed;
}

bool path_check_writable_dir(const char *path, struct error *err)
{
    char dir[4096];
    path_dirname(path, dir, sizeof dir);
    struct stat st;
    if (stat(dir, &st) != 0)
        return error_set(err, "%s: output folder '%s' does not exist", path, dir);
    if (!S_ISDIR(st.st_mode))
        return error_set(err, "%s: '%s' is not a folder", path, dir);
    /* Try it: permission bits say nothing for root or read-only mounts. */
    char probe[4200];
    snprintf(probe, sizeof probe, "%s/.caustica-probe.%ld", dir, (long)getpid());
    int fd = open(probe, O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0)
        return error_set(err, "%s: output folder '%s' is not writable: %s", path, dir, strerror(errno));
    close(fd);
    unlink(probe);
    return true;
}

bool dir_ensure_all(const char *path, char *created, size_t created_len, struct error *err)
{
    if (created_len)
        created[0] = '\0';
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return error_set(err, "%s: path too long", path);
    /* each ancestor from the top, then the folder itself (mkdir -p) */
    for (char *p = buf + 1; ; p++) {
        bool last = *p == '\0';
        if (*p != '/' && !last)
            continue;
        char saved = *p;
        *p = '\0';
        struct stat st;
        if (buf[0] && stat(buf, &st) != 0) {
            if (mkdir(buf, 0777) != 0)
                return error_set(err, "%s: cannot create folder: %s", buf, strerror(errno));
            if (created_len && !created[0])
                snprintf(created, created_len, "%s", buf);
        } else if (buf[0] && !S_ISDIR(st.st_mode)) {
            return error_set(err, "%s: exists and is not a folder", buf);
        }
        *p = saved;
        if (last)
            break;
    }
    return dir_ensure(path, err);
}

bool dir_ensure(const char *path, struct error *err)
{
    struct stat st;
    if (stat(path, &st) == 0) {
        if (!S_ISDIR(st.st_mode))
            return error_set(err, "%s: exists and is not a folder", path);
        if (access(path, W_OK) != 0)
            return error_set(err, "%s: folder is not writable", path);
        return true;
    }
    if (mkdir(path, 0777) != 0)
        return error_set(err, "%s: cannot create folder: %s", path, strerror(errno));
    return true;
}
