/*
** The model's random generator: counter-based, so that a number depends only
** on where it is drawn, never on what was drawn before it elsewhere in the
** string (docs/manual.md §10). That makes a derivation step give the same
** string whatever the number of threads that rewrite it, and in whatever
** order its modules are rewritten.
**
** A draw is a function of four things: the key (from the seed), the stream
** (the derivation step and its phase: productions, decomposition, or
** between steps), the position (the module being rewritten) and the number
** of draws made for that module so far. Each module's draws are a SplitMix64
** sequence (Steele, Lea and Flood 2014) started at a hash of (key, stream,
** position); the hash is SplitMix64's own mixer. Only 64-bit integer
** operations: the same seed gives the same numbers on every machine (unlike
** drand48).
**
** A model may ask for cpfg's generator instead (random = "cpfg"; docs/cpfg.md):
** then the numbers are erand48's, in the order they are drawn, as cpfg draws
** them, and a step runs on one thread.
*/
#ifndef LSYS_RNG_H
#define LSYS_RNG_H

#include <math.h>
#include <stdint.h>

#define LSYS_RNG_GAMMA 0x9E3779B97F4A7C15ull
#define LSYS_RNG_FREE  UINT64_MAX    /* position of draws made outside any module */

/* phases of a stream (derivation step s has streams 4s + phase) */
enum { LSYS_RNG_PROD = 0, LSYS_RNG_DECOMP = 1, LSYS_RNG_BETWEEN = 2 };

typedef struct lsys_rng {
  uint64_t key;        /* from the seed */
  uint64_t step;       /* the derivation step (counts from 0 at every seeding) */
  uint64_t base;       /* key and stream mixed */
  uint64_t pos;        /* the module the next draws are for */
  uint64_t origin;     /* positions count from here (a reseed in the middle of a step) */
  uint64_t z;          /* SplitMix64 state of the draws at 'pos' */
  unsigned phase;
  int fresh;           /* z is to be derived from (base, pos) at the next draw */
  /* cpfg's generator (lsys_rng_cpfg): one sequence in the order of the draws */
  int cpfg;            /* 1: draws come from x48, as cpfg's erand48(main_xsubi) */
  int iset;            /* cpfg's nrand: 0 to make a pair, else return gset */
  uint64_t x48;        /* the 48-bit state of erand48 */
  double gset;         /* the second number of nrand's pair */
} lsys_rng;

/*
** drand48's linear congruential step (POSIX: x' = (0x5DEECE66D x + 0xB) mod 2^48), and
** its number x' / 2^48. Integer arithmetic only, so it gives glibc's numbers on every
** machine; cpfg draws ran, nran, bran and biran with erand48 and chooses stochastic
** productions with drand48 (cpfg's utility.c and generate.c).
*/
static inline double lsys_drand48 (uint64_t *x) {
  *x = (*x * 0x5DEECE66Dull + 0xBu) & 0xFFFFFFFFFFFFull;
  return (double)*x * 0x1.0p-48;
}

/* The erand48 state cpfg's srand(a) sets: {0x330E, a & 0xFFFF, (a >> 16) & 0xFFFF}. */
static inline uint64_t lsys_cpfg_srand48 (uint64_t a) {
  return 0x330Eu | (a & 0xFFFFu) << 16 | ((a >> 16) & 0xFFFFu) << 32;
}

/* SplitMix64's output function (a bijection of 64-bit words). */
static inline uint64_t lsys_mix64 (uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static inline uint64_t lsys_splitmix64 (uint64_t *x) {
  return lsys_mix64(*x += LSYS_RNG_GAMMA);
}

/* The stream of the generator's step and phase; draws restart at 'pos'. */
static inline void lsys_rng_setbase (lsys_rng *r) {
  r->base = lsys_mix64(r->key ^ lsys_mix64((r->step * 4 + r->phase) ^ 0x5851F42D4C957F2Dull));
  r->fresh = 1;
}

/* Moves to step 'step', phase 'phase'; the draws that follow are outside any
** module until lsys_rng_at. */
static inline void lsys_rng_stream (lsys_rng *r, uint64_t step, unsigned phase) {
  r->step = step;
  r->phase = phase;
  r->pos = LSYS_RNG_FREE;
  r->origin = 0;
  r->z = 0;
  lsys_rng_setbase(r);
}

/* Seeds the generator: key from 'seed', step 0, between steps. cpfg's
** generator starts where a cpfg run starts, whatever the seed: erand48's state
** {0x330E, 0, 0} and nrand's first number the mean (its pair flag starts at 10,
** not 0: a cpfg quirk). */
static inline void lsys_rng_seed (lsys_rng *r, uint64_t seed) {
  r->key = lsys_splitmix64(&seed);
  lsys_rng_stream(r, 0, LSYS_RNG_BETWEEN);
  r->x48 = lsys_cpfg_srand48(0);
  r->iset = 10;
  r->gset = 0;
}

/* The homomorphism generator of a cpfg model with a homomorphism seed: each
** interpretation starts it at {0x330E, seed & 0xFFFF, seed >> 16} (cpfg's
** interpret.c), leaving nrand's pair as it was. */
static inline void lsys_rng_cpfg_hseed (lsys_rng *r, uint64_t seed) {
  r->x48 = lsys_cpfg_srand48(seed);
}

/*
** cpfg's srand: the draws that follow are those of a derivation seeded with
** 'seed'. Between steps, the next step draws as the first step after seeding
** would; in the middle of a step (a rule function), the modules after the
** current one draw as the modules of a first step would from the start of
** the string, and the current module's own later draws as outside any module.
*/
static inline void lsys_rng_reseed (lsys_rng *r, uint64_t seed) {
  if (r->cpfg) {             /* cpfg's Do_srand: the state from the seed's low 32 bits */
    r->x48 = lsys_cpfg_srand48(seed);
    r->iset = 0;
    return;
  }
  r->key = lsys_splitmix64(&seed);
  if (r->pos == LSYS_RNG_FREE) {
    r->step = 0;
    r->origin = 0;
  }
  else {
    r->step = r->phase == LSYS_RNG_BETWEEN ? 0 : 1;
    r->origin = r->pos + 1;
  }
  lsys_rng_setbase(r);
}

/* The draws that follow are those of module 'pos' of the stream. */
static inline void lsys_rng_at (lsys_rng *r, uint64_t pos) {
  r->pos = pos;
  r->fresh = 1;
}

static inline uint64_t lsys_rng_next (lsys_rng *r) {
  if (r->fresh) {
    r->z = lsys_mix64(r->base + (r->pos - r->origin + 1) * LSYS_RNG_GAMMA);
    r->fresh = 0;
  }
  return lsys_mix64(r->z += LSYS_RNG_GAMMA);
}

/* Uniform in [0, 1). */
static inline double lsys_rng_uniform (lsys_rng *r) {
  if (r->cpfg) return lsys_drand48(&r->x48);
  return (double)(lsys_rng_next(r) >> 11) * 0x1.0p-53;
}

/* cpfg's nrand: Marsaglia's polar method, which makes two numbers and returns
** the second at the next call; the pair is made when iset is 0. */
static inline double lsys_rng_cpfg_normal (lsys_rng *r, double mu, double sd) {
  double v1, v2, rsq, fac;
  if (r->iset != 0) {
    r->iset = 0;
    return r->gset * sd + mu;
  }
  do {
    v1 = 2.0 * lsys_drand48(&r->x48) - 1.0;
    v2 = 2.0 * lsys_drand48(&r->x48) - 1.0;
    rsq = v1 * v1 + v2 * v2;
  } while (rsq >= 1.0 || rsq == 0.0);
  fac = sqrt(-2.0 * log(rsq) / rsq);
  r->gset = v1 * fac;
  r->iset = 1;
  return v2 * fac * sd + mu;
}

/* Normal with mean 'mu' and standard deviation 'sd' (Box-Muller). */
static inline double lsys_rng_normal (lsys_rng *r, double mu, double sd) {
  double u1, u2;
  if (r->cpfg) return lsys_rng_cpfg_normal(r, mu, sd);
  u1 = 1.0 - lsys_rng_uniform(r);
  u2 = lsys_rng_uniform(r);
  return mu + sd * sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

#endif
