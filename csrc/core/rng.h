/*
** The model's random generator: xoshiro256** seeded through splitmix64, so
** the same seed gives the same numbers on every machine (unlike drand48).
*/
#ifndef LSYS_RNG_H
#define LSYS_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct lsys_rng { uint64_t s[4]; } lsys_rng;

static inline uint64_t lsys_splitmix64 (uint64_t *x) {
  uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static inline void lsys_rng_seed (lsys_rng *r, uint64_t seed) {
  int i;
  for (i = 0; i < 4; i++) r->s[i] = lsys_splitmix64(&seed);
}

static inline uint64_t lsys_rng_next (lsys_rng *r) {
  uint64_t *s = r->s;
  uint64_t x = s[1] * 5, t = s[1] << 17, res = ((x << 7) | (x >> 57)) * 9;
  s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
  s[2] ^= t;
  s[3] = (s[3] << 45) | (s[3] >> 19);
  return res;
}

/* Uniform in [0, 1). */
static inline double lsys_rng_uniform (lsys_rng *r) {
  return (double)(lsys_rng_next(r) >> 11) * 0x1.0p-53;
}

/* Normal with mean 'mu' and standard deviation 'sd' (Box-Muller). */
static inline double lsys_rng_normal (lsys_rng *r, double mu, double sd) {
  double u1 = 1.0 - lsys_rng_uniform(r), u2 = lsys_rng_uniform(r);
  return mu + sd * sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

#endif
