/* lcg.h - the one pseudo-random stream of the host's probe and test points: a 64-bit linear
 * congruential generator (Knuth's MMIX constants), its top 53 bits as a double in [0, 1).
 * Fixed seeds make every run draw the same points. */
#ifndef BRDF_LCG_H
#define BRDF_LCG_H

#include <stdint.h>

static inline double lcg_unit(uint64_t *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*state >> 11) / 9007199254740992.0;   /* 2^53 */
}

#endif
