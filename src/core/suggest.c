#include "core/suggest.h"

#include <ctype.h>
#include <string.h>

#define SUGGEST_MAX 64 /* longer words are not compared */

/* Optimal string alignment distance (Damerau-Levenshtein without repeated
 * edits of one substring), case folded. */
static size_t edit_distance(const char *a, const char *b)
{
    size_t n = strlen(a), m = strlen(b);
    if (n > SUGGEST_MAX || m > SUGGEST_MAX)
        return (size_t)-1;
    size_t d[SUGGEST_MAX + 1][SUGGEST_MAX + 1];
    for (size_t i = 0; i <= n; i++)
        d[i][0] = i;
    for (size_t j = 0; j <= m; j++)
        d[0][j] = j;
    for (size_t i = 1; i <= n; i++) {
        for (size_t j = 1; j <= m; j++) {
            int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
            size_t best = d[i - 1][j - 1] + (ca != cb);
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) && tolower((unsigned char)a[i - 2]) == cb &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    }
    return d[n][m];
}

const char *suggest_nearest(const char *word, const char *const *candidates, size_t count)
{
    if (!word || !*word)
        return NULL;
    size_t len = strlen(word);
    size_t limit = len / 3 > 0 ? len / 3 : 1;
    const char *best = NULL;
    size_t best_distance = limit + 1;
    for (size_t i = 0; i < count; i++) {
        const char *c = candidates[i];
        if (!c)
            continue;
        /* an abbreviation of one name (not of two) */
        if (len >= 3 && strncmp(c, word, len) == 0 && strlen(c) > len) {
            size_t others = 0;
            for (size_t k = 0; k < count; k++)
                others += k != i && candidates[k] && strncmp(candidates[k], word, len) == 0;
            if (others == 0)
                return c;
        }
        size_t d = edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best;
}
