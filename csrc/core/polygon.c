/*
** Polygon triangulation by ear clipping.
**
** The polygon is projected onto the coordinate plane most perpendicular to
** its Newell normal, mirrored if needed so that it runs counter-clockwise
** there; then vertices are cut off one at a time. A vertex is an ear when
** it is convex and no reflex vertex lies in (or on) the triangle it forms
** with its two neighbours: only reflex vertices can poke into such a
** triangle, so they are kept on a list of their own and the test costs
** O(reflex) instead of O(n). Clipping an ear can only make its neighbours
** more convex, so they are reclassified and nothing else changes.
**
** All tolerances are relative to the size of the projected polygon:
** points closer than EPSLEN * size are one point, and three points whose
** doubled triangle area is at most EPSAREA * size^2 are collinear.
*/
#include <math.h>

#include "polygon.h"

#define EPSLEN  1e-9
#define EPSAREA 1e-12

/* A failed round is a whole turn around the ring without an ear. After
** this many the polygon is taken as self-intersecting and convex vertices
** are clipped without the containment test (linear, not quadratic). */
#define MAXFAILS 16

enum { CONVEX, REFLEX, REMOVED };

typedef struct ring {
  const double *xy;
  uint32_t *prv, *nxt;        /* the polygon ring */
  uint32_t *rprv, *rnxt;      /* the list of reflex vertices */
  uint32_t rhead;             /* first reflex vertex, or NONE */
  uint8_t *state;
  uint32_t *out;              /* triangles written so far: 3 * nt numbers */
  long nt;
  double epsa, epsl2;
} ring;

#define NONE UINT32_MAX

void lsys_polywork_free (lsys_polywork *w) {
  LSYS_FREE(w->xy);
  LSYS_FREE(w->link);
  LSYS_FREE(w->state);
  LSYS_FREE(w->tris);
  *w = (lsys_polywork){0};
}

/* Twice the signed area of triangle (a, b, c): positive when counter-clockwise. */
static double orient (const double *xy, uint32_t a, uint32_t b, uint32_t c) {
  const double *A = xy + 2 * a, *B = xy + 2 * b, *C = xy + 2 * c;
  return (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0]);
}

static void reflexadd (ring *r, uint32_t v) {
  r->rprv[v] = NONE;
  r->rnxt[v] = r->rhead;
  if (r->rhead != NONE) r->rprv[r->rhead] = v;
  r->rhead = v;
}

static void reflexdel (ring *r, uint32_t v) {
  if (r->rprv[v] != NONE) r->rnxt[r->rprv[v]] = r->rnxt[v];
  else r->rhead = r->rnxt[v];
  if (r->rnxt[v] != NONE) r->rprv[r->rnxt[v]] = r->rprv[v];
}

/* Takes 'v' out of the ring (and of the reflex list). */
static void detach (ring *r, uint32_t v) {
  if (r->state[v] == REFLEX) reflexdel(r, v);
  r->state[v] = REMOVED;
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

/* Whether convex 'v' is an ear: no reflex vertex inside or on the border of
** its triangle (within the tolerance), other than its own corners. */
static int isear (const ring *r, uint32_t v) {
  const double *xy = r->xy, eps = -r->epsa;
  uint32_t a = r->prv[v], b = r->nxt[v], p;
  const double *A = xy + 2 * a, *B = xy + 2 * v, *C = xy + 2 * b;
  double x0 = fmin(A[0], fmin(B[0], C[0])), x1 = fmax(A[0], fmax(B[0], C[0]));
  double y0 = fmin(A[1], fmin(B[1], C[1])), y1 = fmax(A[1], fmax(B[1], C[1]));
  for (p = r->rhead; p != NONE; p = r->rnxt[p]) {
    const double *P = xy + 2 * p;
    if (p == a || p == b) continue;
    if (P[0] < x0 || P[0] > x1 || P[1] < y0 || P[1] > y1) continue;
    if (orient(xy, a, v, p) >= eps && orient(xy, v, b, p) >= eps && orient(xy, b, a, p) >= eps)
      return 0;
  }
  return 1;
}

/* Cuts 'v' off with its neighbours as a triangle. */
static void clip (ring *r, uint32_t v) {
  uint32_t a = r->prv[v], b = r->nxt[v];
  emit(r, a, v, b);
  detach(r, v);
  classify(r, a);
  classify(r, b);
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

static void classifyall (ring *r, uint32_t v) {
  uint32_t u = v;
  do {
    classify(r, u);
    u = r->nxt[u];
  } while (u != v);
}

static int reserve (lsys_polywork *w, size_t n) {
  if (lsys_grow((void **)&w->xy, &w->xycap, n, 2 * sizeof(double)) != LSYS_OK ||
      lsys_grow((void **)&w->link, &w->linkcap, n, 4 * sizeof(uint32_t)) != LSYS_OK ||
      lsys_grow((void **)&w->state, &w->statecap, n, 1) != LSYS_OK ||
      lsys_grow((void **)&w->tris, &w->tcap, n, 3 * sizeof(uint32_t)) != LSYS_OK)
    return LSYS_ENOMEM;
  return LSYS_OK;
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

long lsys_polygon_triangulate (lsys_polywork *w, const double *pts, size_t n,
                               double normal[3], const uint32_t **tris) {
  double N[3], len, lo[3], hi[3], size = 0;
  ring r;
  size_t i, m;
  int k, c, i1, i2, fails = 0;
  uint32_t v, stop;
  normal[0] = normal[1] = 0; normal[2] = 1;
  *tris = w->tris;
  if (n < 3) return 0;
  if (n >= (size_t)NONE) return LSYS_ELIMIT;
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
  if (reserve(w, n) != LSYS_OK) return LSYS_ENOMEM;
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
  size = fmax(hi[i1] - lo[i1], hi[i2] - lo[i2]);
  r.xy = w->xy;
  r.prv = w->link; r.nxt = w->link + n; r.rprv = w->link + 2 * n; r.rnxt = w->link + 3 * n;
  r.rhead = NONE;
  r.state = w->state;
  r.out = w->tris;
  r.nt = 0;
  r.epsa = EPSAREA * size * size;
  r.epsl2 = (EPSLEN * size) * (EPSLEN * size);
  for (i = 0; i < n; i++) {
    r.prv[i] = (uint32_t)(i == 0 ? n - 1 : i - 1);
    r.nxt[i] = (uint32_t)(i + 1 == n ? 0 : i + 1);
    r.state[i] = CONVEX;
  }
  m = n;
  v = filter(&r, 0, &m);
  if (m < 3) return 0;
  classifyall(&r, v);

  stop = v;
  while (m > 3) {
    uint32_t nx = r.nxt[v];
    size_t m0;
    if (r.state[v] == CONVEX && (fails > MAXFAILS || isear(&r, v))) {
      clip(&r, v);
      m--;
      v = stop = nx;
      continue;
    }
    v = nx;
    if (v != stop) continue;
    /* a whole round without an ear: the polygon is not simple, or clipping
    ** left a part without area (where it touches itself). Drop what has
    ** no area; failing that, cut the first convex vertex, or fan the rest */
    fails++;
    m0 = m;
    v = filter(&r, v, &m);
    if (m < 3) return r.nt;
    if (m < m0) {
      classifyall(&r, v);
      stop = v;
      continue;
    }
    do {
      if (r.state[v] == CONVEX) break;
      v = r.nxt[v];
    } while (v != stop);
    if (r.state[v] != CONVEX) {
      fan(&r, v, m);
      return r.nt;
    }
    nx = r.nxt[v];
    clip(&r, v);
    m--;
    v = stop = nx;
  }
  fan(&r, v, 3);
  return r.nt;
}
