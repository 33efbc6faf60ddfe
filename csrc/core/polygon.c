/*
** Polygon triangulation by ear clipping.
**
** The polygon is projected onto the coordinate plane most perpendicular to
** its Newell normal, mirrored if needed so that it runs counter-clockwise
** there; then vertices are cut off one at a time. A vertex is an ear when
** it is convex and no reflex vertex lies in (or on) the triangle it forms
** with its two neighbours: only reflex vertices can poke into such a
** triangle, so they are kept on a list of their own. Clipping an ear can
** only make its neighbours more convex, so they are reclassified and
** nothing else changes.
**
** A ring of KDMIN vertices or more also counts its reflex vertices in a
** 2-d tree of its vertices, built once (a median split along the wider side
** of each node's points; the counts follow the vertices as they turn convex
** or go): an ear test visits only the nodes that hold a reflex vertex and
** whose region meets the ear's bounding box and triangle, instead of every
** reflex vertex. Both ask the same question, so the triangles are the same.
**
** The order of the cuts: a ring of fewer than QMIN vertices is walked
** around, each vertex tested when the walk reaches it, the walk going on
** from an ear's neighbour; that is what lsys has always done. A bigger ring
** could take as many rounds as it has vertices (a zigzag corridor has ears
** at its two ends only), and makes fans of long triangles that a tree
** search is slow on, so it is cut in another order: the candidates wait in a
** heap, the smallest triangle first, and a vertex whose triangle holds a
** reflex vertex waits on that vertex until it turns convex or goes, or
** until the vertex's own neighbours change: no test is repeated that must
** fail. Its work (the tree nodes visited) is bounded: past MAXWORK n log2 n
** the polygon is refused (LSYS_ELIMIT) rather than taking hours.
**
** All tolerances are relative to the size of the projected polygon:
** points closer than EPSLEN * size are one point, and three points whose
** doubled triangle area is at most EPSAREA * size^2 are collinear.
*/
#include <math.h>
#include <string.h>

#include "polygon.h"

#define EPSLEN  1e-9
#define EPSAREA 1e-12

/* A failed round is a whole turn around the ring without an ear. After
** this many the polygon is taken as self-intersecting and convex vertices
** are clipped without the containment test (linear, not quadratic). */
#define MAXFAILS 16

/* Rings of fewer vertices search the reflex list alone (the tree would cost more). */
#ifndef KDMIN
#define KDMIN 64
#endif

/* Rings of this many vertices or more are cut from the heap (see the top). */
#ifndef QMIN
#define QMIN 1024
#endif

/* The tree nodes (and list entries) the ear tests of a heap-cut ring may
** visit, per vertex of the ring and per level of its tree. What a simple
** polygon needs, at 512,000 vertices (19 levels): a comb, a zigzag corridor,
** a spiral band or a star about 2; a star of random radii, all slivers (a
** sliver crosses about sqrt(n) nodes of the tree), about 40. */
#ifndef MAXWORK
#define MAXWORK LSYS_POLYGON_MAXWORK
#endif

enum { CONVEX, REFLEX, REMOVED };

typedef struct ring {
  const double *xy;
  uint32_t *prv, *nxt;        /* the polygon ring */
  uint32_t *rprv, *rnxt;      /* the list of reflex vertices */
  uint32_t rhead;             /* first reflex vertex, or NONE */
  uint32_t any;               /* a vertex still in the ring */
  uint8_t *state;
  uint32_t *out;              /* triangles written so far: 3 * nt numbers */
  long nt;
  double epsa, epsl2;
  /* the 2-d tree (kdn > 0 once built): node i holds vertex ord[i] and is the
  ** middle of its range [lo, hi) of ord, its children those of [lo, i) and
  ** [i + 1, hi) (points on the left <= its own on axis[i] <= those on the
  ** right); cnt[i]: the reflex vertices of its range; pos[v]: v's node */
  uint32_t *ord, *cnt, *pos;
  uint8_t *axis;
  float *kdbox;               /* per node: the box of its range's points (x0, x1, y0, y1) */
  uint32_t kdn;
  /* the heap of candidates (queue set): heap[0 .. nheap) by key, hpos[v] its
  ** place in it (NONE: not in it); wblk[v]: the reflex vertex v waits on
  ** (NONE), its waiters listed from whead[p] through wprv and wnxt */
  int queue;
  uint32_t *heap, *hpos, *wblk, *whead, *wprv, *wnxt;
  double *key;
  uint32_t nheap;
  double work, maxwork;
} ring;

#define NONE UINT32_MAX

void lsys_polygon_work_free (lsys_polywork *w) {
  lsys_meter *mt = w->meter;
  LSYS_FREE(w->xy);
  LSYS_FREE(w->link);
  LSYS_FREE(w->state);
  LSYS_FREE(w->tris);
  LSYS_FREE(w->kd);
  LSYS_FREE(w->kdaxis);
  LSYS_FREE(w->kdbox);
  LSYS_FREE(w->queue);
  LSYS_FREE(w->key);
  *w = (lsys_polywork){0};
  w->meter = mt;
}

/* Twice the signed area of triangle (a, b, c): positive when counter-clockwise. */
static double orient (const double *xy, uint32_t a, uint32_t b, uint32_t c) {
  const double *A = xy + 2 * a, *B = xy + 2 * b, *C = xy + 2 * c;
  return (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
}

/* {======================================================================
** The heap of candidates and the waiting lists (a ring cut from the heap)
** ======================================================================= */

/* The key of convex v: the squared sides of its triangle, summed. */
static double keyof (const ring *r, uint32_t v) {
  const double *A = r->xy + 2 * r->prv[v], *B = r->xy + 2 * v, *C = r->xy + 2 * r->nxt[v];
  double ux = B[0] - A[0], uy = B[1] - A[1], vx = C[0] - B[0], vy = C[1] - B[1];
  double wx = A[0] - C[0], wy = A[1] - C[1];
  return ux * ux + uy * uy + vx * vx + vy * vy + wx * wx + wy * wy;
}

/* Whether heap entry i goes before j: the smaller key, then the lower vertex. */
static int before (const ring *r, uint32_t i, uint32_t j) {
  uint32_t a = r->heap[i], b = r->heap[j];
  return r->key[a] < r->key[b] || (r->key[a] == r->key[b] && a < b);
}

static void hswap (ring *r, uint32_t i, uint32_t j) {
  uint32_t t = r->heap[i];
  r->heap[i] = r->heap[j];
  r->heap[j] = t;
  r->hpos[r->heap[i]] = i;
  r->hpos[r->heap[j]] = j;
}

static void hup (ring *r, uint32_t i) {
  while (i > 0 && before(r, i, (i - 1) / 2)) {
    hswap(r, i, (i - 1) / 2);
    i = (i - 1) / 2;
  }
}

static void hdown (ring *r, uint32_t i) {
  for (;;) {
    uint32_t c = 2 * i + 1;
    if (c >= r->nheap) return;
    if (c + 1 < r->nheap && before(r, c + 1, c)) c++;
    if (!before(r, c, i)) return;
    hswap(r, i, c);
    i = c;
  }
}

static void hremove (ring *r, uint32_t v) {
  uint32_t i = r->hpos[v];
  if (i == NONE) return;
  r->hpos[v] = NONE;
  if (i == --r->nheap) return;
  v = r->heap[r->nheap];               /* the last entry fills the gap */
  r->heap[i] = v;
  r->hpos[v] = i;
  hup(r, i);
  hdown(r, r->hpos[v]);
}

/* Puts convex v in the heap with the key of its triangle now (or moves it). */
static void hput (ring *r, uint32_t v) {
  hremove(r, v);
  r->key[v] = keyof(r, v);
  r->heap[r->nheap] = v;
  r->hpos[v] = r->nheap++;
  hup(r, r->hpos[v]);
}

static void unwait (ring *r, uint32_t v) {
  uint32_t p = r->wblk[v];
  if (p == NONE) return;
  if (r->wprv[v] != NONE) r->wnxt[r->wprv[v]] = r->wnxt[v];
  else r->whead[p] = r->wnxt[v];
  if (r->wnxt[v] != NONE) r->wprv[r->wnxt[v]] = r->wprv[v];
  r->wblk[v] = NONE;
}

/* v waits on reflex vertex p, which is in its triangle. */
static void waiton (ring *r, uint32_t v, uint32_t p) {
  r->wblk[v] = p;
  r->wprv[v] = NONE;
  r->wnxt[v] = r->whead[p];
  if (r->whead[p] != NONE) r->wprv[r->whead[p]] = v;
  r->whead[p] = v;
}

/* p is no longer reflex: what waited on it is a candidate again. */
static void release (ring *r, uint32_t p) {
  while (r->whead[p] != NONE) {
    uint32_t w = r->whead[p];
    unwait(r, w);
    if (r->state[w] == CONVEX) hput(r, w);
  }
}

/* u's neighbours or state changed: it waits on nothing, and is a candidate
** when convex. */
static void touch (ring *r, uint32_t u) {
  if (!r->queue) return;
  unwait(r, u);
  if (r->state[u] == CONVEX) hput(r, u);
  else hremove(r, u);
}

/* }====================================================================== */

/* Adds d (+1 or -1) to the reflex counts of the tree nodes above v's, and
** its own: the path from the root to pos[v]. */
static void kdcount (ring *r, uint32_t v, int d) {
  uint32_t lo = 0, hi = r->kdn, at = r->pos[v];
  while (lo < hi) {
    uint32_t mid = lo + (hi - lo) / 2;
    r->cnt[mid] += (uint32_t)d;
    if (at == mid) break;
    if (at < mid) hi = mid;
    else lo = mid + 1;
  }
}

static void reflexadd (ring *r, uint32_t v) {
  if (r->kdn > 0) kdcount(r, v, 1);
  r->rprv[v] = NONE;
  r->rnxt[v] = r->rhead;
  if (r->rhead != NONE) r->rprv[r->rhead] = v;
  r->rhead = v;
}

/* v is reflex no longer. */
static void reflexdel (ring *r, uint32_t v) {
  if (r->kdn > 0) kdcount(r, v, -1);
  if (r->rprv[v] != NONE) r->rnxt[r->rprv[v]] = r->rnxt[v];
  else r->rhead = r->rnxt[v];
  if (r->rnxt[v] != NONE) r->rprv[r->rnxt[v]] = r->rprv[v];
  if (r->queue) release(r, v);
}

/* Takes 'v' out of the ring (and of the reflex list, the heap, the waits). */
static void detach (ring *r, uint32_t v) {
  if (r->state[v] == REFLEX) reflexdel(r, v);
  r->state[v] = REMOVED;
  if (r->queue) {
    hremove(r, v);
    unwait(r, v);
  }
  if (r->any == v) r->any = r->nxt[v];
  r->nxt[r->prv[v]] = r->nxt[v];
  r->prv[r->nxt[v]] = r->prv[v];
}

/* Sets the state of 'v' from its angle; collinear counts as reflex. */
static void classify (ring *r, uint32_t v) {
  int s = orient(r->xy, r->prv[v], v, r->nxt[v]) > r->epsa ? CONVEX : REFLEX;
  if (s == r->state[v]) return;
  if (r->state[v] == REFLEX) reflexdel(r, v);
  r->state[v] = (uint8_t)s;
  if (s == REFLEX) reflexadd(r, v);
}

static void emit (ring *r, uint32_t a, uint32_t b, uint32_t c) {
  uint32_t *t = r->out + 3 * r->nt++;
  t[0] = a; t[1] = b; t[2] = c;
}

/* Whether reflex vertex p lies in triangle (a, v, b) or on its border,
** within the tolerance. */
static int pokes (const ring *r, uint32_t a, uint32_t v, uint32_t b, uint32_t p) {
  const double eps = -r->epsa;
  return orient(r->xy, a, v, p) >= eps && orient(r->xy, v, b, p) >= eps &&
         orient(r->xy, b, a, p) >= eps;
}

static int inbox (const double *P, const double box[4]) {
  return !(P[0] < box[0] || P[0] > box[1] || P[1] < box[2] || P[1] > box[3]);
}

/* Whether no point of the rectangle q = [x0, x1] x [y0, y1] can be in
** triangle t: its four corners are beyond one of the edges by more than
** twice the tolerance (orient is affine, so the corners bound every point
** of the rectangle; the margin covers rounding). */
static int outside (const ring *r, const uint32_t t[3], const double q[4]) {
  const double lim = -2 * r->epsa;
  int e, k;
  for (e = 0; e < 3; e++) {
    const double *A = r->xy + 2 * t[e], *B = r->xy + 2 * t[(e + 1) % 3];
    double ex = B[0] - A[0], ey = B[1] - A[1];
    for (k = 0; k < 4; k++) {
      double px = q[k & 1] - A[0], py = q[2 + (k >> 1)] - A[1];
      if (ex * py - ey * px >= lim) break;
    }
    if (k == 4) return 1;
  }
  return 0;
}

/* Ranges of more nodes than this are checked against the triangle itself. */
#define KDTRI 4

/* A reflex vertex other than a and b in triangle (a, v, b), or NONE, by the
** tree: a node is visited when its range holds a reflex vertex and the box
** of its points meets the triangle's (and, for a big range, the triangle). */
static uint32_t kdpoked (ring *r, uint32_t a, uint32_t v, uint32_t b, const double box[4]) {
  uint32_t stack[64], sp = 0;         /* ranges [lo, hi); the tree is at most 25 deep */
  const uint32_t t[3] = {a, v, b};
  stack[sp++] = 0;
  stack[sp++] = r->kdn;
  while (sp > 0) {
    uint32_t hi = stack[--sp], lo = stack[--sp], mid = lo + (hi - lo) / 2, p;
    const float *f = r->kdbox + 4 * (size_t)mid;
    const double *P;
    double q[4];
    int ax, near, side;
    r->work++;
    if (r->cnt[mid] == 0 || f[0] > box[1] || f[1] < box[0] || f[2] > box[3] || f[3] < box[2])
      continue;
    if (hi - lo > KDTRI) {
      q[0] = f[0]; q[1] = f[1]; q[2] = f[2]; q[3] = f[3];
      if (outside(r, t, q)) continue;
    }
    p = r->ord[mid];
    P = r->xy + 2 * p;
    if (r->state[p] == REFLEX && p != a && p != b && inbox(P, box) && pokes(r, a, v, b, p))
      return p;
    ax = r->axis[mid];
    near = r->xy[2 * v + ax] <= P[ax];   /* v's side, where a poking vertex is likeliest, is
                                            pushed last: searched first */
    for (side = 0; side < 2; side++) {
      if ((side == 0) != near) {       /* the left half */
        if (lo < mid) { stack[sp++] = lo; stack[sp++] = mid; }
      }
      else if (mid + 1 < hi) { stack[sp++] = mid + 1; stack[sp++] = hi; }
    }
  }
  return NONE;
}

/* A reflex vertex inside or on the border of the triangle of convex 'v'
** (within the tolerance), other than its own corners; NONE when v is an ear. */
static uint32_t blocker (ring *r, uint32_t v) {
  const double *xy = r->xy;
  uint32_t a = r->prv[v], b = r->nxt[v], p;
  const double *A = xy + 2 * a, *B = xy + 2 * v, *C = xy + 2 * b;
  double box[4];
  box[0] = fmin(A[0], fmin(B[0], C[0])); box[1] = fmax(A[0], fmax(B[0], C[0]));
  box[2] = fmin(A[1], fmin(B[1], C[1])); box[3] = fmax(A[1], fmax(B[1], C[1]));
  if (r->kdn > 0) return kdpoked(r, a, v, b, box);
  for (p = r->rhead; p != NONE; p = r->rnxt[p]) {
    r->work++;
    if (p == a || p == b) continue;
    if (inbox(xy + 2 * p, box) && pokes(r, a, v, b, p)) return p;
  }
  return NONE;
}

/* Cuts 'v' off with its neighbours as a triangle. */
static void clip (ring *r, uint32_t v) {
  uint32_t a = r->prv[v], b = r->nxt[v];
  emit(r, a, v, b);
  detach(r, v);
  classify(r, a);
  classify(r, b);
  touch(r, a);
  touch(r, b);
}

/* The last resort: a fan from 'v' over the rest of the ring, each triangle
** turned to face the normal, those without area left out. */
static void fan (ring *r, uint32_t v, size_t m) {
  uint32_t u = r->nxt[v];
  size_t i;
  for (i = 2; i < m; i++) {
    uint32_t t = r->nxt[u];
    double o = orient(r->xy, v, u, t);
    if (o > r->epsa) emit(r, v, u, t);
    else if (o < -r->epsa) emit(r, v, t, u);
    u = t;
  }
}

/*
** Drops repeated points and vertices without an angle (straight or a
** hairpin) from the ring of '*m' vertices that contains 'v'; after each
** removal it steps back, since the previous vertex may have become one of
** them. Returns a vertex still in the ring; '*m' < 3 when nothing is left.
*/
static uint32_t filter (ring *r, uint32_t v, size_t *m) {
  size_t checked = 0;
  while (*m >= 3 && checked < *m) {
    uint32_t a = r->prv[v];
    const double *P = r->xy + 2 * v, *A = r->xy + 2 * a;
    double dx = P[0] - A[0], dy = P[1] - A[1];
    if (dx * dx + dy * dy <= r->epsl2 || fabs(orient(r->xy, a, v, r->nxt[v])) <= r->epsa) {
      detach(r, v);
      (*m)--;
      v = a;
      checked = 0;
    }
    else {
      v = r->nxt[v];
      checked++;
    }
  }
  return v;
}

/* Classifies every vertex of the ring from v (and, cutting from the heap,
** makes each a candidate anew). */
static void classifyall (ring *r, uint32_t v) {
  uint32_t u = v;
  do {
    classify(r, u);
    u = r->nxt[u];
  } while (u != v);
  if (r->queue)
    do {
      touch(r, u);
      u = r->nxt[u];
    } while (u != v);
}

/* {======================================================================
** The 2-d tree of the ring's vertices
** ======================================================================= */

#define COORD(r, i, ax) ((r)->xy[2 * (size_t)(r)->ord[i] + (ax)])

static void swapord (uint32_t *o, int64_t i, int64_t j) {
  uint32_t t = o[i];
  o[i] = o[j];
  o[j] = t;
}

/* Sifts heap entry k of ord[lo, lo + n) down (a max-heap by coordinate ax). */
static void siftdown (ring *r, int64_t lo, int64_t n, int64_t k, int ax) {
  for (;;) {
    int64_t c = 2 * k + 1;
    if (c >= n) return;
    if (c + 1 < n && COORD(r, lo + c + 1, ax) > COORD(r, lo + c, ax)) c++;
    if (COORD(r, lo + c, ax) <= COORD(r, lo + k, ax)) return;
    swapord(r->ord, lo + k, lo + c);
    k = c;
  }
}

/* Heapsort of ord[lo, hi] (inclusive) by coordinate ax: kdselect's way out
** when its pivots keep failing. */
static void kdsort (ring *r, int64_t lo, int64_t hi, int ax) {
  int64_t n = hi - lo + 1, i;
  for (i = n / 2; i-- > 0;) siftdown(r, lo, n, i, ax);
  for (i = n - 1; i > 0; i--) {
    swapord(r->ord, lo, lo + i);
    siftdown(r, lo, i, 0, ax);
  }
}

/* Reorders ord[lo, hi] (inclusive) so that ord[k] has coordinate ax of the
** k-th point in that order, none before it greater and none after it less
** (Hoare's selection, pivot the median of three; a heapsort after too many
** rounds, so that no input makes it quadratic). */
static void kdselect (ring *r, int64_t lo, int64_t hi, int64_t k, int ax) {
  int rounds = 0;
  while (hi > lo) {
    int64_t i = lo, j = hi, m = lo + (hi - lo) / 2;
    double a = COORD(r, lo, ax), b = COORD(r, m, ax), c = COORD(r, hi, ax), piv;
    if (++rounds > 64) {
      kdsort(r, lo, hi, ax);
      return;
    }
    piv = a < b ? (b < c ? b : a < c ? c : a) : (a < c ? a : b < c ? c : b);
    while (i <= j) {
      while (COORD(r, i, ax) < piv) i++;
      while (COORD(r, j, ax) > piv) j--;
      if (i <= j) swapord(r->ord, i++, j--);
    }
    if (k <= j) hi = j;
    else if (k >= i) lo = i;
    else return;                       /* ord[k] is between: equal to the pivot */
  }
}

/* Builds the nodes of ord[lo, hi): the median along the wider side of the
** range's points in the middle, then each half. */
static void kdbuild (ring *r, uint32_t lo, uint32_t hi) {
  while (hi > lo) {
    uint32_t mid = lo + (hi - lo) / 2, i;
    double x0 = COORD(r, lo, 0), x1 = x0, y0 = COORD(r, lo, 1), y1 = y0;
    int ax;
    for (i = lo + 1; i < hi; i++) {
      double x = COORD(r, i, 0), y = COORD(r, i, 1);
      if (x < x0) x0 = x;
      if (x > x1) x1 = x;
      if (y < y0) y0 = y;
      if (y > y1) y1 = y;
    }
    ax = y1 - y0 > x1 - x0;
    kdselect(r, lo, hi - 1, mid, ax);
    r->axis[mid] = (uint8_t)ax;
    kdbuild(r, lo, mid);
    lo = mid + 1;                      /* the right half without recursion */
  }
}

/* The box of the points of ord[lo, hi) (not empty), written to its node's
** kdbox, rounded outwards to floats. */
static void kdboxes (ring *r, uint32_t lo, uint32_t hi, double out[4]) {
  uint32_t mid = lo + (hi - lo) / 2;
  const double *P = r->xy + 2 * (size_t)r->ord[mid];
  float *f = r->kdbox + 4 * (size_t)mid;
  double b[4], c[4];
  int k;
  b[0] = b[1] = P[0];
  b[2] = b[3] = P[1];
  if (lo < mid) {
    kdboxes(r, lo, mid, c);
    for (k = 0; k < 4; k++) b[k] = k % 2 ? fmax(b[k], c[k]) : fmin(b[k], c[k]);
  }
  if (mid + 1 < hi) {
    kdboxes(r, mid + 1, hi, c);
    for (k = 0; k < 4; k++) b[k] = k % 2 ? fmax(b[k], c[k]) : fmin(b[k], c[k]);
  }
  for (k = 0; k < 4; k++) {
    float x = (float)b[k];
    if (k % 2 ? (double)x < b[k] : (double)x > b[k]) x = nextafterf(x, k % 2 ? INFINITY : -INFINITY);
    f[k] = x;
    out[k] = b[k];
  }
}

/* The tree of the m vertices of the ring from v, no vertex reflex yet. */
static void kdinit (ring *r, uint32_t v, size_t m) {
  uint32_t u = v, i;
  double box[4];
  for (i = 0; i < m; i++, u = r->nxt[u]) r->ord[i] = u;
  kdbuild(r, 0, (uint32_t)m);
  kdboxes(r, 0, (uint32_t)m, box);
  for (i = 0; i < m; i++) {
    r->pos[r->ord[i]] = i;
    r->cnt[i] = 0;
  }
  r->kdn = (uint32_t)m;
}

/* }====================================================================== */

/* {======================================================================
** Cutting
** ======================================================================= */

/*
** A whole round (of the walk) or an empty heap without an ear: the polygon
** is not simple, or clipping left a part without area (where it touches
** itself). Drops what has no area; failing that, cuts the first convex
** vertex from *v. Returns 1 when the ring was reclassified (something
** dropped), 0 when a vertex was cut, -1 when the ring is done (nothing
** left, or a fan of the rest when no vertex is convex). *v: where to go on.
*/
static int stuck (ring *r, uint32_t *v, size_t *m) {
  size_t m0 = *m;
  uint32_t u = filter(r, *v, m), stop = u, nx;
  if (*m < 3) return -1;
  if (*m < m0) {
    classifyall(r, u);
    *v = u;
    return 1;
  }
  do {
    if (r->state[u] == CONVEX) break;
    u = r->nxt[u];
  } while (u != stop);
  if (r->state[u] != CONVEX) {
    fan(r, u, *m);
    return -1;
  }
  nx = r->nxt[u];
  clip(r, u);
  (*m)--;
  *v = nx;
  return 0;
}

/* The walk around the ring of m vertices from v; 'fails' rounds failed
** already (past MAXFAILS every convex vertex is cut untested). */
static void walk (ring *r, uint32_t v, size_t m, int fails) {
  uint32_t stop = v;
  while (m > 3) {
    uint32_t nx = r->nxt[v];
    int st;
    if (r->state[v] == CONVEX && (fails > MAXFAILS || blocker(r, v) == NONE)) {
      clip(r, v);
      m--;
      v = stop = nx;
      continue;
    }
    v = nx;
    if (v != stop) continue;
    fails++;
    if ((st = stuck(r, &v, &m)) < 0) return;
    stop = v;
  }
  fan(r, v, 3);
}

/* Cuts the ring of m vertices from the heap (see the top); walks it once
** MAXFAILS tries found no ear. Returns LSYS_OK, or LSYS_ELIMIT past the work
** allowed. */
static int cut (ring *r, size_t m) {
  int fails = 0;
  while (m > 3) {
    uint32_t v, p;
    int st;
    if (r->work > r->maxwork) return LSYS_ELIMIT;
    if (r->nheap == 0) {
      v = r->any;
      if (++fails > MAXFAILS) {
        r->queue = 0;
        walk(r, v, m, fails);
        return LSYS_OK;
      }
      if ((st = stuck(r, &v, &m)) < 0) return LSYS_OK;
      continue;
    }
    v = r->heap[0];
    hremove(r, v);
    if ((p = blocker(r, v)) == NONE) {
      clip(r, v);
      m--;
    }
    else waiton(r, v, p);
  }
  fan(r, r->any, 3);
  return LSYS_OK;
}

/* }====================================================================== */

/* The arrays for n vertices (the tree's and the heap's only for a big
** polygon), within w->meter. */
static int reserve (lsys_polywork *w, size_t n) {
  lsys_meter *mt = w->meter;
  int st;
  if ((st = lsys_common_grow_metered((void **)&w->xy, &w->xycap, n, 2 * sizeof(double), mt)) ||
      (st = lsys_common_grow_metered((void **)&w->link, &w->linkcap, n, 4 * sizeof(uint32_t),
                                     mt)) ||
      (st = lsys_common_grow_metered((void **)&w->state, &w->statecap, n, 1, mt)) ||
      (st = lsys_common_grow_metered((void **)&w->tris, &w->tcap, n, 3 * sizeof(uint32_t), mt)))
    return st;
  if (n < KDMIN) return LSYS_OK;
  if ((st = lsys_common_grow_metered((void **)&w->kd, &w->kdcap, n, 3 * sizeof(uint32_t), mt)) ||
      (st = lsys_common_grow_metered((void **)&w->kdaxis, &w->kdaxiscap, n, 1, mt)) ||
      (st = lsys_common_grow_metered((void **)&w->kdbox, &w->kdboxcap, n, 4 * sizeof(float), mt)))
    return st;
  if (n < QMIN) return LSYS_OK;
  if ((st = lsys_common_grow_metered((void **)&w->queue, &w->qcap, n, 6 * sizeof(uint32_t), mt)))
    return st;
  return lsys_common_grow_metered((void **)&w->key, &w->keycap, n, sizeof(double), mt);
}

/* The Newell normal of the polygon, with the first point as origin so that
** a polygon far from the origin loses no precision. */
static void newell (const double *pts, size_t n, double N[3]) {
  const double *o = pts;
  size_t i;
  N[0] = N[1] = N[2] = 0;
  for (i = 0; i < n; i++) {
    const double *a = pts + 3 * i, *b = pts + 3 * (i + 1 == n ? 0 : i + 1);
    double ax = a[0] - o[0], ay = a[1] - o[1], az = a[2] - o[2];
    double bx = b[0] - o[0], by = b[1] - o[1], bz = b[2] - o[2];
    N[0] += (ay - by) * (az + bz);
    N[1] += (az - bz) * (ax + bx);
    N[2] += (ax - bx) * (ay + by);
  }
}

/* The ring of the n projected points of w, all convex for now. */
static void ringinit (ring *r, lsys_polywork *w, size_t n, double size) {
  size_t i;
  memset(r, 0, sizeof *r);
  r->xy = w->xy;
  r->prv = w->link; r->nxt = w->link + n; r->rprv = w->link + 2 * n;
  r->rnxt = w->link + 3 * n;
  r->rhead = NONE;
  r->state = w->state;
  r->out = w->tris;
  r->epsa = EPSAREA * size * size;
  r->epsl2 = (EPSLEN * size) * (EPSLEN * size);
  if (n >= KDMIN) {                    /* the tree's arrays (none for a small polygon) */
    r->ord = w->kd; r->cnt = w->kd + n; r->pos = w->kd + 2 * n;
    r->axis = w->kdaxis;
    r->kdbox = w->kdbox;
  }
  for (i = 0; i < n; i++) {
    r->prv[i] = (uint32_t)(i == 0 ? n - 1 : i - 1);
    r->nxt[i] = (uint32_t)(i + 1 == n ? 0 : i + 1);
    r->state[i] = CONVEX;
  }
}

/* Cuts the heap of the ring of m vertices from v ready, and the work it may take. */
static void queueinit (ring *r, lsys_polywork *w, size_t n, uint32_t v, size_t m) {
  uint32_t u = v, *q = w->queue;
  size_t i, levels = 1;
  r->heap = q; r->hpos = q + n; r->wblk = q + 2 * n; r->whead = q + 3 * n;
  r->wprv = q + 4 * n; r->wnxt = q + 5 * n;
  r->key = w->key;
  for (i = 0; i < m; i++, u = r->nxt[u]) r->hpos[u] = r->wblk[u] = r->whead[u] = NONE;
  while ((size_t)1 << levels < m) levels++;
  r->work = 0;
  r->maxwork = (double)MAXWORK * (double)m * (double)levels;
  r->queue = 1;
}

long lsys_polygon_triangulate (lsys_polywork *w, const double *pts, size_t n,
                               double normal[3], const uint32_t **tris) {
  double N[3], len, lo[3], hi[3], size = 0;
  ring r;
  size_t i, m;
  int k, c, i1, i2;
  uint32_t v;
  normal[0] = normal[1] = 0; normal[2] = 1;
  *tris = w->tris;
  if (n < 3) return 0;
  if (n > LSYS_POLYGON_MAXV) return LSYS_ELIMIT;
  for (c = 0; c < 3; c++) lo[c] = hi[c] = pts[c];
  for (i = 1; i < n; i++)
    for (c = 0; c < 3; c++) {
      double x = pts[3 * i + c];
      if (x < lo[c]) lo[c] = x;
      if (x > hi[c]) hi[c] = x;
    }
  for (c = 0; c < 3; c++) {
    if (!isfinite(lo[c]) || !isfinite(hi[c])) return 0;    /* NaN fails too */
    if (hi[c] - lo[c] > size) size = hi[c] - lo[c];
  }
  newell(pts, n, N);
  len = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
  if (!(len > EPSAREA * size * size) || !isfinite(len)) return 0;
  for (c = 0; c < 3; c++) normal[c] = N[c] / len;
  if ((c = reserve(w, n)) != LSYS_OK) return c;
  *tris = w->tris;

  /* project onto the plane of the dominant axis k; (k+1, k+2) runs
  ** counter-clockwise when N[k] > 0, otherwise swap the two axes */
  k = fabs(N[0]) >= fabs(N[1]) ? (fabs(N[0]) >= fabs(N[2]) ? 0 : 2)
                               : (fabs(N[1]) >= fabs(N[2]) ? 1 : 2);
  i1 = (k + 1) % 3; i2 = (k + 2) % 3;
  if (N[k] < 0) { int t = i1; i1 = i2; i2 = t; }
  for (i = 0; i < n; i++) {
    w->xy[2 * i] = pts[3 * i + i1] - pts[i1];
    w->xy[2 * i + 1] = pts[3 * i + i2] - pts[i2];
  }
  ringinit(&r, w, n, fmax(hi[i1] - lo[i1], hi[i2] - lo[i2]));
  m = n;
  r.any = 0;
  v = filter(&r, 0, &m);
  if (m < 3) return 0;
  r.any = v;
  if (m >= KDMIN) kdinit(&r, v, m);
  if (m >= QMIN) queueinit(&r, w, n, v, m);
  classifyall(&r, v);
  if (!r.queue) walk(&r, v, m, 0);
  else if ((c = cut(&r, m)) != LSYS_OK) return c;
  return r.nt;
}
