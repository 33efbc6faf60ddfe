/*
** The inside of a space (space.h), shared by space.c (the hash and its
** queries) and space_markers.c (space colonisation).
**
** The points are stored sorted by (bucket, cell, index): the points of one
** cell are consecutive, and the cells of one bucket too. A bucket lists its
** cells (cstart / cc), a cell its points (pstart); each point keeps its
** index in the caller's order (id), group and vigour. Struct of arrays, so
** a query reads only what it needs.
*/
#ifndef LSYS_SPACE_IMPL_H
#define LSYS_SPACE_IMPL_H

#include <math.h>

#include "space.h"

#define LSYS_SPACE_FAR 4503599627370496.0     /* 2^52: cells beyond are refused */

struct lsys_space {
  double cell;                  /* the cells' side (the radius) */
  size_t n, listed;             /* points; the first 'listed' ids are the caller's list */
  size_t ncell;
  uint64_t mask;                /* buckets - 1 (a power of two, less one) */
  uint32_t *bstart;             /* mask + 2: bucket k's cells are bstart[k] .. bstart[k+1] */
  int64_t *cc;                  /* 3 a cell: its coordinates */
  uint32_t *pstart;             /* ncell + 1: cell k's points are pstart[k] .. pstart[k+1] */
  double *p;                    /* 3 a point, in stored order */
  int64_t *g;                   /* its group */
  double *v;                    /* its vigour */
  uint32_t *id;                 /* its index: < listed for the caller's, then the scene's */
  size_t bytes;
};

/* The cell of a coordinate; the caller checked |x / c| < LSYS_SPACE_FAR. */
static inline int64_t lsys_space_coord (double x, double c) {
  return (int64_t)floor(x / c);
}

/* The bucket of the cell (x, y, z). */
static inline uint64_t lsys_space_hash (int64_t x, int64_t y, int64_t z, uint64_t mask) {
  uint64_t h = (uint64_t)x * 0x9E3779B97F4A7C15ull ^ (uint64_t)y * 0xC2B2AE3D27D4EB4Full ^
               (uint64_t)z * 0x165667B19E3779F9ull;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return h & mask;
}

/* The stored points of the cell (x, y, z): [*a, *b), empty when it has none. */
static inline void lsys_space_cellrange (const lsys_space *S, int64_t x, int64_t y, int64_t z,
                                         uint32_t *a, uint32_t *b) {
  uint64_t k = lsys_space_hash(x, y, z, S->mask);
  uint32_t c, c1 = S->bstart[k + 1];
  for (c = S->bstart[k]; c < c1; c++) {
    const int64_t *q = S->cc + 3 * (size_t)c;
    if (q[0] == x && q[1] == y && q[2] == z) {
      *a = S->pstart[c];
      *b = S->pstart[c + 1];
      return;
    }
  }
  *a = *b = 0;
}

/* The cells a query of radius r looks at on each side of its own. */
static inline int64_t lsys_space_span (double r, double c) {
  double k = ceil(r / c);
  return k < 1 ? 1 : (int64_t)k;
}

/* Whether p's cell coordinates are in range for cells of side c. */
static inline int lsys_space_near (const double p[3], double c) {
  return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) &&
         fabs(p[0] / c) < LSYS_SPACE_FAR && fabs(p[1] / c) < LSYS_SPACE_FAR &&
         fabs(p[2] / c) < LSYS_SPACE_FAR;
}

/*
** Runs work(ctx, k) for k = 0 .. nchunks - 1 on 'threads' workers (the
** caller one of them), each taking the next chunk from a shared counter,
** as light.c's queries do. A thread that cannot be started leaves its
** share to the others.
*/
void lsys_space_run (int threads, size_t nchunks, void (*work) (void *, size_t), void *ctx);

#endif
