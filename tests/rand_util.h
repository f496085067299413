/* Deterministic pseudo-random numbers for the tests (header-only). */
#ifndef STICTION_TESTS_RAND_UTIL_H
#define STICTION_TESTS_RAND_UTIL_H

#include <stdint.h>

/* splitmix64 (Steele, Lea & Flood 2014): uniform in (0, 1), state *s. */
static inline double unif(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return ((z >> 11) + 0.5) / 9007199254740992.0;
}

#endif
