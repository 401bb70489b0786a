/* seeded_normal.h — reproducible normal deviates for the tests' noisy trials:
 * splitmix64 (Steele, Lea, Flood 2014) and the Box-Muller transform. */
#ifndef RD_SEEDED_NORMAL_H
#define RD_SEEDED_NORMAL_H

#include <math.h>
#include <stdint.h>

static inline uint64_t seeded_mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* One N(0, 1) deviate from the stream `s`. */
static inline double seeded_normal(uint64_t *s)
{
    double u1 = ((double)(seeded_mix(s) >> 11) + 0.5) * 0x1p-53;
    double u2 = (double)(seeded_mix(s) >> 11) * 0x1p-53;
    return sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2);
}

#endif
