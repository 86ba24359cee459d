/* xoshiro256** with splitmix64 seeding and the Marsaglia polar Gaussian (see random.h). */
#include "rugo/random.h"

#include <math.h>

static uint64_t splitmix64(uint64_t* x) {
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void rugo_rng_seed(rugo_rng* rng, uint64_t seed) {
    if (rng == NULL) return;
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i)
        rng->state[i] = splitmix64(&x);
    rng->spare = 0.0;
    rng->has_spare = false;
}

uint64_t rugo_rng_next(rugo_rng* rng) {
    uint64_t* s = rng->state;
    const uint64_t result = rotl(s[1] * 5, 7) * 9;
    const uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

rugo_real rugo_rng_uniform(rugo_rng* rng) { return (rugo_real)(rugo_rng_next(rng) >> 11) * 0x1.0p-53; }

rugo_real rugo_rng_range(rugo_rng* rng, rugo_real lo, rugo_real hi) {
    const rugo_real u = rugo_rng_uniform(rng);
    const rugo_real w = hi - lo;
    /* hi - lo overflows only for bounds near the largest doubles: then the weighted form */
    return isfinite(w) || !isfinite(lo) || !isfinite(hi) ? lo + w * u : lo * (1.0 - u) + hi * u;
}

uint32_t rugo_rng_below(rugo_rng* rng, uint32_t n) {
    if (n < 1) return 0;
    /* Reject the top partial block of 2^32 so every value is equally likely. */
    const uint32_t limit = (uint32_t)(0x100000000ull - (0x100000000ull % n));
    for (;;) {
        uint32_t r = (uint32_t)(rugo_rng_next(rng) >> 32);
        if (limit == 0 || r < limit) return r % n;
    }
}

rugo_real rugo_rng_gaussian(rugo_rng* rng) {
    if (rng->has_spare) {
        rng->has_spare = false;
        return rng->spare;
    }
    rugo_real u, v, s;
    do {
        u = 2.0 * rugo_rng_uniform(rng) - 1.0;
        v = 2.0 * rugo_rng_uniform(rng) - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    rugo_real m = sqrt(-2.0 * log(s) / s);
    rng->spare = v * m;
    rng->has_spare = true;
    return u * m;
}
