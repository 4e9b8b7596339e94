/* A part of a reference rendered in shards (`reference --shard i/n`): the
 * image holds the mean of the part's independent passes, and OUT.part
 * beside it says which passes those are, so that `caustica merge` can
 * weigh the parts by their passes and refuse parts that do not belong
 * together. A text file of "key value" lines:
 *
 *   caustica-reference-part 1
 *   scene scenes/compare/ball.lua
 *   frame 0
 *   size 512x512
 *   seed 1
 *   photons 200000        (per pass)
 *   passes_total 16       (--spp: the passes the whole estimate has)
 *   shard_count 4
 *   shards 0,2            (the shard indices this part holds; a merge holds several)
 *   passes 8              (the passes in this part's mean)
 *   photons_emitted 1600000
 */
#ifndef CAUSTICA_REFERENCE_PART_H
#define CAUSTICA_REFERENCE_PART_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"

#define REFERENCE_PART_MAX_SHARDS 4096
/* The ranges a part's fields are read in (what reference accepts). */
#define REFERENCE_PART_MAX_FRAME 100000000
#define REFERENCE_PART_MAX_PHOTONS 2000000000LL

struct reference_part {
    char scene[1024];
    int frame, width, height;
    uint64_t seed;
    long photons;
    int passes_total, shard_count;
    int shards[REFERENCE_PART_MAX_SHARDS];
    int shard_parts;
    int passes;
    long long photons_emitted;
};

/* Writes IMAGE.part (atomically: a temporary, then renamed). */
bool reference_part_write(const char *image_path, const struct reference_part *part, struct error *err);
/* Reads IMAGE.part; a missing or malformed file is an error naming it. */
bool reference_part_read(const char *image_path, struct reference_part *part, struct error *err);

#endif
