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

/*
** The bucket of the cell (x, y, z): a mix of (y, z), plus x. The cells of
** one row along x are in consecutive buckets, so a query reads the cells of
** a row around its own from one stretch of the table and of the cells
** (stored in bucket order), and a walk through the stored points goes along
** rows: what neighbours read is near in memory. Rows fall at random places;
** two that overlap share buckets, told apart by the cells' coordinates.
*/
static inline uint64_t lsys_space_row (int64_t y, int64_t z) {
  uint64_t h = (uint64_t)y * 0x9E3779B97F4A7C15ull ^ (uint64_t)z * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 29;
  return h;
}

static inline uint64_t lsys_space_hash (int64_t x, int64_t y, int64_t z, uint64_t mask) {
  return (lsys_space_row(y, z) + (uint64_t)x) & mask;
}

/* The point ranges [r[i][0], r[i][1]) of the cells (x, y, z) with x0 <= x <=
** x1 that have points, into r (room for x1 - x0 + 1 <= the buckets); returns
** how many. */
static inline int lsys_space_rowcells (const lsys_space *S, int64_t x0, int64_t x1, int64_t y,
                                       int64_t z, uint32_t r[][2]) {
  uint64_t k0 = lsys_space_hash(x0, y, z, S->mask), k1 = k0 + (uint64_t)(x1 - x0), ka, kb;
  int n = 0, part;
  for (part = 0; part < 2; part++) {          /* the stretch, and what wraps around */
    uint32_t c, c1;
    if (part == 0) { ka = k0; kb = k1 <= S->mask ? k1 : S->mask; }
    else if (k1 > S->mask) { ka = 0; kb = k1 - S->mask - 1; }
    else break;
    c1 = S->bstart[kb + 1];
    for (c = S->bstart[ka]; c < c1; c++) {
      const int64_t *q = S->cc + 3 * (size_t)c;
      if (q[1] == y && q[2] == z && q[0] >= x0 && q[0] <= x1) {
        r[n][0] = S->pstart[c];
        r[n][1] = S->pstart[c + 1];
        n++;
      }
    }
  }
  return n;
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
