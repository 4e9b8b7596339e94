/* PCG32 (O'Neill 2014): small, fast, and seeded per pixel or photon so
 * the reference is deterministic whatever the thread count. */
#ifndef CAUSTICA_REF_RNG_H
#define CAUSTICA_REF_RNG_H

#include <stdint.h>

struct ref_rng {
    uint64_t state, inc;
    /* numbers ref_rng_choice hands out before the stream's own: a photon's
     * first two Fresnel choices (reflect or refract) drawn from its
     * quasi-random point like its position (ref_emit_point), so that the
     * share of photons a surface reflects is stratified too */
    double given[2];
    unsigned given_count, given_next;
};

static inline uint32_t ref_rng_u32(struct ref_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
}

/* Uniform in [0, 1). */
static inline double ref_rng_uniform(struct ref_rng *r) { return ref_rng_u32(r) * (1.0 / 4294967296.0); }

/* Uniform in [0, 1) for a choice between a surface's reflection and its
 * transmission: the given numbers first, then the stream's. (Only those:
 * a medium's free flights or a rough surface's microfacets drawn from the
 * given numbers instead made the fog's bench truth a third slower for no
 * gain.) */
static inline double ref_rng_choice(struct ref_rng *r)
{
    if (r->given_next < r->given_count)
        return r->given[r->given_next++];
    return ref_rng_uniform(r);
}

static inline uint64_t ref_hash64(uint64_t x)
{
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    x ^= x >> 33;
    return x;
}

static inline struct ref_rng ref_rng_seed(uint64_t seed, uint64_t stream, uint64_t index)
{
    struct ref_rng r = {0, (ref_hash64(stream * 0x9e3779b97f4a7c15ULL + seed) << 1u) | 1u, {0.0, 0.0}, 0, 0};
    ref_rng_u32(&r);
    r.state += ref_hash64(index ^ (seed * 0x632be59bd9b4e019ULL));
    ref_rng_u32(&r);
    return r;
}

#endif
