/* Video previews through ffmpeg (see video.h). */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <fcntl.h>
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

/* Runs argv (ffmpeg or ffprobe), its standard output to `stdout_path`
 * when not NULL; true when it exits 0. *status gets its exit code. */
static bool run_tool(const char *const *argv, const char *stdout_path, int *exit_code)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (stdout_path)
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    pid_t pid;
    int rc = posix_spawnp(&pid, argv[0], &actions, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    bool ok = rc == 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    *exit_code = rc == 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return ok;
}

/* The frames ffprobe decodes from the video's first video stream (0 when
 * it has none), or -1 when ffprobe cannot say. */
static long count_video_frames(const char *video, const char *folder)
{
    char listing[4400];
    snprintf(listing, sizeof listing, "%s/frames_out.txt", folder);
    const char *argv[] = {"ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                          "stream=nb_read_frames", "-of", "default=nokey=1:noprint_wrappers=1", video, NULL};
    int code;
    if (!run_tool(argv, listing, &code))
        return -1;
    FILE *f = fopen(listing, "r");
    if (!f)
        return -1;
    long frames = 0; /* no stream: ffprobe prints nothing */
    if (fscanf(f, "%ld", &frames) != 1)
        frames = 0;
    fclose(f);
    return frames;
}

static const char *extension_of(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    return dot && (!slash || dot > slash) ? dot : "";
}

bool video_encode(const char *const *paths, int count, double fps, const char *output, int crf, struct error *err)
{
    if (!video_find_program("ffmpeg"))
        return error_set(err, "--video %s: ffmpeg is not installed (apt-get install ffmpeg); the frames are on disk",
                         output);
    if (count == 0)
        return error_set(err, "--video %s: no frames to encode", output);
    /* An earlier encode killed mid-way (kill -9) left its private folder
     * here: a dead writer's folder is removed before this one is made. */
    char output_dir[4096];
    path_dirname(output, output_dir, sizeof output_dir);
    path_remove_stale_temporaries(output_dir);
    /* ffmpeg reads and writes by name, through any link: everything it is
     * given lives in a private folder (0700) beside the output, where
     * nobody else can plant one, and the video is renamed into place at
     * the end. The frames are links there named 00000000.png, 00000001.png,
     * … read as one numbered sequence (ffmpeg's image2 demuxer): no list
     * file whose syntax a path could break (a newline in a frame's path was
     * a line of ffmpeg's concat list), and exactly one video frame an
     * image at -framerate (the concat list's durations lost the last
     * frame, and a video of one frame had no video stream). */
    char folder[4200], pattern[4300], temporary[4300];
    if (!path_temporary_dir_create(output, folder, sizeof folder, err))
        return false;
    /* a folder named "-..." would reach ffmpeg as an option: ./-name */
    const char *dot = folder[0] == '-' ? "./" : "";
    const char *ext = extension_of(paths[0]);
    if (strlen(ext) > 8 || strchr(ext, '%'))
        ext = ".png";
    for (int i = 0; i < count; i++) {
        char absolute[4200], link_path[4400];
        if (!realpath(paths[i], absolute)) {
            path_temporary_dir_remove(folder);
            return error_set(err, "--video %s: frame %s: %s", output, paths[i], strerror(errno));
        }
        snprintf(link_path, sizeof link_path, "%s/%08d%s", folder, i, ext);
        if (symlink(absolute, link_path) != 0) {
            path_temporary_dir_remove(folder);
            return error_set(err, "--video %s: cannot link frame %d in %s: %s", output, i, folder, strerror(errno));
        }
    }
    /* the sequence's pattern: a '%' of the folder's own name doubled (image2 reads %% as one) */
    size_t used = (size_t)snprintf(pattern, sizeof pattern, "%s", dot);
    for (const char *c = folder; *c && used + 3 < sizeof pattern; c++) {
        if (*c == '%')
            pattern[used++] = '%';
        pattern[used++] = *c;
    }
    snprintf(pattern + used, sizeof pattern - used, "/%%08d%s", ext);
    char rate[64], quality[16];
    bool gif = ends_with(output, ".gif");
    snprintf(rate, sizeof rate, "%.9g", fps);
    snprintf(quality, sizeof quality, "%d", crf);
    snprintf(temporary, sizeof temporary, "%s%s/video%s", dot, folder, gif ? ".gif" : ".mp4");
    const char *argv_mp4[] = {"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-start_number", "0",
                              "-f", "image2", "-i", pattern,
                              /* 4:2:0 chroma wants even sizes: an odd one padded by a pixel (libx264 refuses it) */
                              "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-crf", quality,
                              "-pix_fmt", "yuv420p", "-colorspace", "bt709", "-color_primaries", "bt709",
                              "-color_trc", "iec61966-2-1", "-color_range", "tv", "-movflags", "+faststart",
                              temporary, NULL};
    const char *argv_gif[] = {"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-start_number", "0",
                              "-f", "image2", "-i", pattern, temporary, NULL};
    int code;
    if (!run_tool(gif ? argv_gif : argv_mp4, NULL, &code)) {
        path_temporary_dir_remove(folder);
        return error_set(err, "--video %s: ffmpeg failed (exit %d); the frames are on disk", output, code);
    }
    /* Frames counted in and out: a video that lost one is an error, not a
     * "wrote … (N frames)" that is not true. */
    if (video_find_program("ffprobe")) {
        long decoded = count_video_frames(temporary, folder);
        if (decoded != count) {
            path_temporary_dir_remove(folder);
            if (decoded < 0)
                return error_set(err, "--video %s: ffprobe could not read the encoded video back; the frames are on "
                                      "disk", output);
            return error_set(err, "--video %s: ffmpeg encoded %ld of the %d frames (not written; the frames are on "
                                  "disk)", output, decoded, count);
        }
    }
    bool moved = rename(temporary, output) == 0;
    path_temporary_dir_remove(folder);
    if (!moved)
        return error_set(err, "--video %s: cannot move the encoded video into place", output);
    return true;
}
