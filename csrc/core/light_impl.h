/*
** What the files of the light environment share (light.h is the interface):
** the light's struct, the hierarchy's nodes and primitives, the build and
** the ray test that light.c calls.
**
** The triangles and the capsules (line segments with a radius) have a
** hierarchy each, built as a binary tree of axis-aligned boxes and
** traversed as a 4-wide one made from it; a leaf holds a range of packets of
** four triangles, or of capsules, which are in leaf order. Everything is in
** floats, as the mesh is. light_bvh.c builds; light_ray.c tests rays;
** light.c holds the sky and runs the queries.
*/
#ifndef LSYS_LIGHT_IMPL_H
#define LSYS_LIGHT_IMPL_H

#include "light.h"

#define LSYS_LIGHT_STACK 128     /* the binary trees' depth stays below it */

/* A node of a 4-wide tree, made from the binary tree the build makes by
** taking up to four of a node's descendants as children: their boxes side
** by side, for the four slab tests at once. An empty slot has the box
** lo = FLT_MAX, hi = -FLT_MAX, which no ray enters. A child's item holds,
** in its low 40 bits, what a walk needs to visit it (LSYS_LITEM: a walk's
** stack keeps those bits and the mask of its rays above them); bits 40 to
** 55 hold the order of the children for two of the octants (LSYS_LORDER). */
typedef struct lsys_lnode4 {
  float b[6][4];                 /* the children's boxes: lo x, y, z, hi x, y, z */
  uint64_t item[4];              /* the children: LSYS_LITEM, and the orders above */
} lsys_lnode4;

/* A child's item: an inner child's node (n = 0) or a leaf's first packet
** (or capsule) and their number n (1 .. 16). */
#define LSYS_LITEM(first, n) ((uint64_t)(n) << 32 | (uint64_t)(first))

/* The children of q nearest first for a ray of the octant oct (bit c: the
** ray goes down axis c): 2 bits each, the nearest lowest, in bits 48 to 55
** of item[oct / 2] (odd octants) or 40 to 47 (even ones). */
#define LSYS_LORDER(q, oct) \
  ((unsigned)((q)->item[(oct) >> 1] >> (40 + 8 * ((oct) & 1))) & 0xffu)

/* One hierarchy: its nodes (root 0) in an aligned block. */
typedef struct lsys_ltree {
  lsys_lnode4 *node;
  void *mem;
  size_t nnodes, depth;
} lsys_ltree;

/* Four triangles side by side for the Möller-Trumbore test of one ray
** against all four (lane k: triangle k): a vertex and the two edges from
** it. An unused lane is all 0, which no ray hits. */
typedef struct lsys_ltri4 {
  float a[3][4], e1[3][4], e2[3][4];
} lsys_ltri4;

enum { LSYS_LIGHT_TRI = 0, LSYS_LIGHT_CAPSULE = 1 };

/* A primitive as the build gathers it; the capsules stay so. */
typedef struct lsys_lprim {
  float a[3];                    /* triangle: vertex 0; capsule: one end */
  float b[3];                    /* triangle: vertex 1 - vertex 0; capsule: the other end - a */
  float c[3];                    /* triangle: vertex 2 - vertex 0; capsule: radius, |b|^2, 0 */
  uint32_t kind;                 /* LSYS_LIGHT_TRI or LSYS_LIGHT_CAPSULE */
} lsys_lprim;

struct lsys_light {
  lsys_ltree tri, cap;            /* leaves: ranges of packets of triangles; of capsules */
  lsys_ltri4 *pack; size_t npack;
  lsys_lprim *caps;
  size_t ntri, ncap;
  double *dir, *w; size_t ndirs;  /* the sky: unit directions (3 each) and weights */
  float *dirf;                    /* the directions in floats, for the rays */
  double offset;                  /* world units */
  float tmax;                     /* hits at this distance or beyond do not count (inf: none) */
  double tau;                     /* transmittance */
  int maxhits;                    /* hits counted along a ray: 1 when opaque */
  double taupow[LSYS_LIGHT_MAXHITS + 1];   /* tau^k: what a ray with k hits lets through */
  double lo[3], hi[3];            /* the primitives' bounds (0 when there are none) */
};

/*
** Copies the triangles of 's' (and its line segments as capsules of radius
** 'radius' when it is > 0), under their instances' transforms, into L's
** primitives and builds the hierarchy over them; sets L's bounds. Checks the
** memory against 'mt' (NULL: none) before allocating, and counts what L
** keeps in it (light_bvh.c). Returns LSYS_OK, LSYS_ELIMIT, LSYS_EMEMORY or LSYS_ENOMEM
** (message in e); on failure the caller frees L's arrays (lsys_light_free).
*/
int lsys_light_bvh (lsys_light *L, const lsys_scene *s, double radius, lsys_meter *mt,
                    lsys_error *e);

/* The hits along o + t d, tmin < t < L->tmax, counted up to cap (>= 1); brute: every
** primitive tested, without the hierarchy (light_ray.c). */
int lsys_light_trace (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap);
int lsys_light_brute (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap);

/* The rays o[i] + t d, t > tmin, of the m origins with want[i] set (want
** NULL: all of them): their hits, counted up to cap, into hits[i] (0 for
** the others). The same counts as lsys_light_trace gives each. */
void lsys_light_cast (const lsys_light *L, const float (*o)[3], const uint8_t *want, size_t m,
                      const float d[3], float tmin, int cap, uint8_t *hits);

#endif
