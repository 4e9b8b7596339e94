/* `record --video out.mp4|out.gif`: the recorded frames encoded by ffmpeg
 * (when it is on PATH; the frames stay on disk either way). */
#ifndef CAUSTICA_VIDEO_H
#define CAUSTICA_VIDEO_H

#include <stdbool.h>

#include "core/error.h"

/* Is `name` an executable on PATH? */
bool video_find_program(const char *name);
/* Encodes the `count` image files in `paths` (in order) at `fps` into
 * `output` (.mp4 or .gif) with ffmpeg; false with a message naming what to
 * install when ffmpeg is missing, or ffmpeg's failure. */
/* H.264 (mp4) at quality `crf` (0..51) or a GIF; an odd width or height
 * padded by one pixel (4:2:0 needs even ones); tagged BT.709 primaries and
 * the sRGB transfer the PNGs carry; written to a temporary beside `output`
 * and renamed, so a failed encode leaves no half file. */
bool video_encode(const char *const *paths, int count, double fps, const char *output, int crf, struct error *err);
bool video_path_supported(const char *output);

#endif
