/* "Did you mean": the known name nearest a misspelt one. */
#ifndef CAUSTICA_SUGGEST_H
#define CAUSTICA_SUGGEST_H

#include <stddef.h>

/* The candidate closest to `word` by edit distance (insertions, deletions,
 * substitutions and swaps of neighbours, case ignored), or a candidate that
 * `word` begins (an abbreviation), or NULL when none is near enough to be a
 * likely typo: at most a third of the word's letters, and at least one. */
const char *suggest_nearest(const char *word, const char *const *candidates, size_t count);

#endif
