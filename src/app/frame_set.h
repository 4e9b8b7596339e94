/* Frame sets as render farms write them (`--frames`): `1-100`, `0-119:10`
 * (a step), `1,5,10-20`, the older `A:B` (inclusive), or a count `N`
 * (frames 0..N-1); and the output patterns of `record -o`:
 * `out/shot_####.png` (a run of # is the frame number zero-padded to its
 * length) or a folder (`DIR/frame_####.png`). */
#ifndef CAUSTICA_FRAME_SET_H
#define CAUSTICA_FRAME_SET_H

#include <stdbool.h>
#include <stddef.h>

#define FRAME_SET_MAX_RANGES 64
#define FRAME_SET_MAX_FRAMES 10000000 /* frames one set may name */

struct frame_set {
    struct { int from, to, step; } ranges[FRAME_SET_MAX_RANGES];
    int count;  /* ranges */
};

/* False with a message naming the bad part. */
bool frame_set_parse(const char *text, struct frame_set *set, char *message, size_t size);
/* The frames of the set, in order, duplicates dropped: a malloc'ed array
 * (free it) of *count frames, or NULL when out of memory. */
int *frame_set_list(const struct frame_set *set, int *count);

/* The file of frame `frame` for the output `pattern`: # runs replaced, or
 * PATTERN/frame_####.png for a folder. False when it does not fit. */
bool output_pattern_path(const char *pattern, int frame, char *out, size_t size);
/* Does `pattern` hold a run of #? */
bool output_pattern_is_pattern(const char *pattern);
/* record's -o as given, made a pattern of # runs: %04d (or %d) becomes
 * #### (#); an image file name without a frame number (out/f.png) becomes
 * out/f_####.png, with `note` saying so (else note is ""). False when it does
 * not fit `size`. */
bool output_pattern_normalize(const char *given, char *out, size_t size, char *note, size_t notelen);

#endif
