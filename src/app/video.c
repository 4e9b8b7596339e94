/* Video previews through ffmpeg (see video.h). */
#define _DEFAULT_SOURCE
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/video.h"
#include "core/fileio.h"

extern char **environ;

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

bool video_path_supported(const char *output) { return ends_with(output, ".mp4") || ends_with(output, ".gif"); }

bool video_find_program(const char *name)
{
    const char *path = getenv("PATH");
    if (!path)
        return false;
    while (*path) {
        size_t n = strcspn(path, ":");
        char candidate[4200];
        snprintf(candidate, sizeof candidate, "%.*s/%s", (int)n, path, name);
        if (n > 0 && access(candidate, X_OK) == 0)
            return true;
        path += n;
        if (*path == ':')
            path++;
    }
    return false;
}

bool video_encode(const char *const *paths, int count, double fps, const char *output, int crf, struct error *err)
{
    if (!video_find_program("ffmpeg"))
        return error_set(err, "--video %s: ffmpeg is not installed (apt-get install ffmpeg); the frames are on disk",
                         output);
    if (count == 0)
        return error_set(err, "--video %s: no frames to encode", output);
    /* ffmpeg writes the list and the video by name, through any link: both
     * live in a private folder (0700) beside the output, where nobody else
     * can plant one, and the video is renamed into place at the end. */
    char folder[4200], list[4300], temporary[4300];
    if (!path_temporary_dir_create(output, folder, sizeof folder, err))
        return false;
    /* a folder named "-..." would reach ffmpeg as an option: ./-name */
    const char *dot = folder[0] == '-' ? "./" : "";
    snprintf(list, sizeof list, "%s%s/frames.txt", dot, folder);
    FILE *f = fopen(list, "w");
    if (!f) {
        path_temporary_dir_remove(folder);
        return error_set(err, "--video %s: cannot write %s", output, list);
    }
    /* ffmpeg's concat list: every frame in order, each shown 1/fps */
    for (int i = 0; i < count; i++) {
        char absolute[4200];
        if (!realpath(paths[i], absolute))
            snprintf(absolute, sizeof absolute, "%s", paths[i]);
        fputs("file '", f);
        for (const char *p = absolute; *p; p++) {
            if (*p == '\'')
                fputs("'\\''", f); /* the concat list's quoting */
            else
                fputc(*p, f);
        }
        fprintf(f, "'\nduration %.9f\n", 1.0 / fps);
    }
    fclose(f);
    char filters[128], quality[16];
    bool gif = ends_with(output, ".gif");
    /* 4:2:0 chroma wants even sizes: pad an odd one by a pixel (libx264 refuses it otherwise) */
    snprintf(filters, sizeof filters, gif ? "fps=%g" : "fps=%g,pad=ceil(iw/2)*2:ceil(ih/2)*2", fps);
    snprintf(quality, sizeof quality, "%d", crf);
    snprintf(temporary, sizeof temporary, "%s%s/video%s", dot, folder, gif ? ".gif" : ".mp4");
    const char *argv_mp4[] = {"ffmpeg", "-y", "-loglevel", "error", "-f", "concat", "-safe", "0", "-i", list,
                              "-vf", filters, "-c:v", "libx264", "-crf", quality, "-pix_fmt", "yuv420p",
                              "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "iec61966-2-1",
                              "-color_range", "tv", "-movflags", "+faststart", temporary, NULL};
    const char *argv_gif[] = {"ffmpeg", "-y", "-loglevel", "error", "-f", "concat", "-safe", "0", "-i", list,
                              "-vf", filters, temporary, NULL};
    pid_t pid;
    int rc = posix_spawnp(&pid, "ffmpeg", NULL, NULL, (char *const *)(gif ? argv_gif : argv_mp4), environ);
    int status = 0;
    bool ok = rc == 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!ok) {
        path_temporary_dir_remove(folder);
        return error_set(err, "--video %s: ffmpeg failed (exit %d); the frames are on disk", output,
                         WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
    bool moved = rename(temporary, output) == 0;
    path_temporary_dir_remove(folder);
    if (!moved)
        return error_set(err, "--video %s: cannot move the encoded video into place", output);
    return true;
}
