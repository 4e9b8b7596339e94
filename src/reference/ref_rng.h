/* PCG32 (O'Neill 2014): small, fast, and seeded per pixel or photon so
 * the reference is deterministic whatever the thread count. */
#ifndef CAUSTICA_REF_RNG_H
#define CAUSTICA_REF_RNG_H

#include <stdint.h>

struct ref_rng {
    uint64_t state, inc;
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
    struct ref_rng r = {0, (ref_hash64(stream * 0x9e3779b97f4a7c15ULL + seed) << 1u) | 1u};
    ref_rng_u32(&r);
    r.state += ref_hash64(index ^ (seed * 0x632be59bd9b4e019ULL));
    ref_rng_u32(&r);
    return r;
}

#endif
