/* Reference parts' sidecar files (see reference_part.h). */
#include "reference/reference_part.h"

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"
#include "io/image.h"

#define PART_MAGIC "caustica-reference-part 1"

bool reference_part_write(const char *image_path, const struct reference_part *part, struct error *err)
{
    char path[4200], tmp[4400];
    snprintf(path, sizeof path, "%s.part", image_path);
    /* the image writers' temporary and rename: never a half-written sidecar */
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return false;
    bool ok = fprintf(f, PART_MAGIC "\nscene %s\nframe %d\nsize %dx%d\nseed %" PRIu64 "\nphotons %ld\npasses_total %d\n"
                         "shard_count %d\nshards ",
                      part->scene, part->frame, part->width, part->height, part->seed, part->photons,
                      part->passes_total, part->shard_count) > 0;
    for (int i = 0; ok && i < part->shard_parts; i++)
        ok = fprintf(f, "%s%d", i ? "," : "", part->shards[i]) > 0;
    ok = ok && fprintf(f, "\npasses %d\nphotons_emitted %lld\n", part->passes, part->photons_emitted) > 0;
    if (!ok)
        error_set(err, "%s: write failed: %s", path, strerror(errno));
    return image_file_finish(f, tmp, path, ok, err);
}

/* A whole number in [min, max] as the part's text writes it (decimal, no
 * sign for a count); false for anything else, so that 4294967298 is not
 * read as 2 nor -1 as a huge seed. `end` is left after the digits. */
static bool parse_range(const char *text, long long min, long long max, long long *out, char **end)
{
    const char *p = text;
    if (*p == '+' || (*p == '-' && min >= 0) || !(*p == '-' || (*p >= '0' && *p <= '9')))
        return false;
    errno = 0;
    long long v = strtoll(p, end, 10);
    if (*end == p || errno == ERANGE || v < min || v > max)
        return false;
    *out = v;
    return true;
}

static bool parse_seed(const char *text, uint64_t *out, char **end)
{
    if (!(*text >= '0' && *text <= '9'))
        return false; /* strtoull would take "-1" as 2^64 - 1 */
    errno = 0;
    unsigned long long v = strtoull(text, end, 10);
    if (*end == text || errno == ERANGE)
        return false;
    *out = (uint64_t)v;
    return true;
}

static bool parse_shards(const char *text, struct reference_part *part)
{
    part->shard_parts = 0;
    const char *p = text;
    while (*p && *p != '\n') {
        char *end;
        errno = 0;
        long v = strtol(p, &end, 10);
        if (end == p || errno || v < 0 || v >= REFERENCE_PART_MAX_SHARDS ||
            part->shard_parts >= REFERENCE_PART_MAX_SHARDS)
            return false;
        part->shards[part->shard_parts++] = (int)v;
        p = end;
        if (*p == ',')
            p++;
        else if (*p && *p != '\n')
            return false;
    }
    return part->shard_parts > 0;
}

bool reference_part_read(const char *image_path, struct reference_part *part, struct error *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s.part", image_path);
    char *data;
    size_t size;
    if (!file_read_all(path, &data, &size, err))
        return error_prefix(err, "%s: not a reference part (reference --shard writes one beside its image)",
                            image_path);
    memset(part, 0, sizeof *part);
    bool ok = strncmp(data, PART_MAGIC "\n", strlen(PART_MAGIC) + 1) == 0;
    unsigned seen = 0;
    int line_number = 1;
    for (char *line = strchr(data, '\n'); ok && line && line[1]; line = strchr(line + 1, '\n')) {
        char *key = line + 1, *value = strchr(key, ' ');
        line_number++;
        char *eol = strchr(key, '\n');
        if (!value || (eol && value > eol)) {
            ok = false;
            break;
        }
        value++;
        char *end = NULL;
        long long number = 0;
        errno = 0;
        if (strncmp(key, "scene ", 6) == 0) {
            size_t n = eol ? (size_t)(eol - value) : strlen(value);
            ok = n < sizeof part->scene;
            if (ok) {
                memcpy(part->scene, value, n);
                part->scene[n] = '\0';
            }
            seen |= 1u;
        } else if (strncmp(key, "frame ", 6) == 0) {
            ok = parse_range(value, 0, REFERENCE_PART_MAX_FRAME, &number, &end);
            part->frame = (int)number;
            seen |= 2u;
        } else if (strncmp(key, "size ", 5) == 0) {
            long long w = 0, h = 0;
            ok = parse_range(value, 1, 16384, &w, &end) && *end == 'x' &&
                 parse_range(end + 1, 1, 16384, &h, &end);
            part->width = (int)w;
            part->height = (int)h;
            seen |= 4u;
        } else if (strncmp(key, "seed ", 5) == 0) {
            ok = parse_seed(value, &part->seed, &end);
            seen |= 8u;
        } else if (strncmp(key, "photons ", 8) == 0) {
            ok = parse_range(value, 0, REFERENCE_PART_MAX_PHOTONS, &number, &end);
            part->photons = (long)number;
            seen |= 16u;
        } else if (strncmp(key, "passes_total ", 13) == 0) {
            ok = parse_range(value, 1, INT_MAX, &number, &end);
            part->passes_total = (int)number;
            seen |= 32u;
        } else if (strncmp(key, "shard_count ", 12) == 0) {
            ok = parse_range(value, 1, REFERENCE_PART_MAX_SHARDS, &number, &end);
            part->shard_count = (int)number;
            seen |= 64u;
        } else if (strncmp(key, "shards ", 7) == 0) {
            ok = parse_shards(value, part);
            end = eol;
            seen |= 128u;
        } else if (strncmp(key, "passes ", 7) == 0) {
            ok = parse_range(value, 1, INT_MAX, &number, &end);
            part->passes = (int)number;
            seen |= 256u;
        } else if (strncmp(key, "photons_emitted ", 16) == 0) {
            ok = parse_range(value, 0, LLONG_MAX / 2, &number, &end);
            part->photons_emitted = number;
            seen |= 512u;
        } /* an unknown key is skipped: a later version may add some */
        if (ok && end && end != eol && !(eol == NULL && *end == '\0'))
            ok = false;
    }
    free(data);
    if (!ok || seen != 1023u || part->passes < 1 || part->passes_total < part->passes || part->shard_count < 1 ||
        part->shard_count > REFERENCE_PART_MAX_SHARDS || part->photons < 0)
        return error_set(err, "%s: malformed reference part (line %d; every key of reference --shard's file, with "
                              "sensible values, is needed)", path, line_number);
    for (int i = 0; i < part->shard_parts; i++)
        if (part->shards[i] >= part->shard_count)
            return error_set(err, "%s: shard %d of %d does not exist", path, part->shards[i], part->shard_count);
    return true;
}
