/*
** Rays through the light's hierarchy (light_impl.h): the primitive tests
** and the traversal of the 4-wide tree.
**
** A ray's four slab tests against a node's children run side by side in SSE
** on x86-64 (elsewhere, or with LSYS_LIGHT_SCALAR, in a plain loop that
** finds the same children). Each ray uses the near and far planes its
** direction's signs pick, so an empty slot's inverted box is never entered.
** The leaves a node's box test hits are tested at once (an occluded ray may
** stop there), four triangles at a time; its inner children are visited
** nearest first, from a fixed stack on the C stack. Any hit beyond tmin
** counts, up to a cap (a transmittance counts the hits: each primitive is in
** one leaf, so it is met at most once).
*/
#include <float.h>
#include <math.h>
#include <string.h>

#include "light_impl.h"

#define STACK (3 * LSYS_LIGHT_STACK + 4)  /* a node pushes at most 3 of its 4 children */

#if defined(__SSE2__) && !defined(LSYS_LIGHT_SCALAR)
#define VEC 1
#include <emmintrin.h>
#endif

/* Whether the ray o + t d, t > tmin, meets the capsule P (from outside: a
** point in it is not shadowed by it, as a bud by its own stem), in doubles:
** the first of its entries into the body and the two end spheres. */
static int capsule (const lsys_lprim *P, const float o[3], const float d[3], float tmin) {
  double w[3], r = P->c[0], bb = P->c[1], dd = 0, dw = 0, ww = 0, db = 0, wb = 0, t = HUGE_VAL;
  double s, A, Bq, C, h;
  int c, end;
  for (c = 0; c < 3; c++) {
    w[c] = (double)o[c] - P->a[c];
    dd += (double)d[c] * d[c];
    dw += (double)d[c] * w[c];
    ww += w[c] * w[c];
    db += (double)d[c] * P->b[c];
    wb += w[c] * P->b[c];
  }
  s = bb > 0 ? wb / bb : 0;                          /* inside: nearest point of the axis */
  s = s < 0 ? 0 : s > 1 ? 1 : s;
  if (ww - 2 * s * wb + s * s * bb < r * r) return 0;
  if (bb > 0) {                                      /* the body, entered from outside it */
    A = bb * dd - db * db;
    Bq = bb * dw - db * wb;
    C = bb * ww - wb * wb - r * r * bb;
    if (A > 0 && C > 0 && (h = Bq * Bq - A * C) >= 0) {
      double tb = (-Bq - sqrt(h)) / A, y = wb + tb * db;
      if (tb > 0 && y >= 0 && y <= bb) t = tb;
    }
  }
  for (end = 0; end < 2; end++) {                    /* the spheres at a and at a + b */
    double vw = 0, vv = 0;
    for (c = 0; c < 3; c++) {
      double x = w[c] - end * (double)P->b[c];
      vw += (double)d[c] * x;
      vv += x * x;
    }
    if (dd > 0 && (h = vw * vw - dd * (vv - r * r)) >= 0) {
      double ts = (-vw - sqrt(h)) / dd;
      if (ts > 0 && ts < t) t = ts;
    }
  }
  return t > tmin && t < HUGE_VAL;
}

/* A ray set up for the slab tests: for each axis, the rows of a node's
** boxes that hold its near and far planes (lo or hi by the direction's sign),
** the origin and the inverse direction (a zero component made tiny, so that
** no 0 * inf makes a NaN), also 4 times over for the vector tests. */
typedef struct ray {
  int near[3], far[3];
  float o[3], d[3], inv[3], tmin;
#ifdef VEC
  __m128 vo[3], vd[3], vinv[3], vtmin;
#endif
} ray;

/* The entry distances of the ray into the four children of q (tn) and the
** mask of those it enters (bit k: child k). */
static inline int slabs (const lsys_lnode4 *q, const ray *r, float tn[4]) {
#ifdef VEC
  __m128 lo = r->vtmin, hi = _mm_set1_ps(FLT_MAX);
  int c;
  for (c = 0; c < 3; c++) {
    __m128 a = _mm_loadu_ps(q->b[r->near[c]]), b = _mm_loadu_ps(q->b[r->far[c]]);
    lo = _mm_max_ps(lo, _mm_mul_ps(_mm_sub_ps(a, r->vo[c]), r->vinv[c]));
    hi = _mm_min_ps(hi, _mm_mul_ps(_mm_sub_ps(b, r->vo[c]), r->vinv[c]));
  }
  _mm_storeu_ps(tn, lo);
  return _mm_movemask_ps(_mm_cmple_ps(lo, hi));
#else
  int k, c, mask = 0;
  for (k = 0; k < 4; k++) {
    float lo = r->tmin, hi = FLT_MAX;
    for (c = 0; c < 3; c++) {
      float a = (q->b[r->near[c]][k] - r->o[c]) * r->inv[c];
      float b = (q->b[r->far[c]][k] - r->o[c]) * r->inv[c];
      lo = a > lo ? a : lo;
      hi = b < hi ? b : hi;
    }
    tn[k] = lo;
    mask |= (lo <= hi) << k;
  }
  return mask;
#endif
}

/* The hits of the ray among the four triangles of T (Möller and Trumbore,
** both faces), each lane as the scalar test computes it. */
static inline int hit4 (const lsys_ltri4 *T, const ray *r) {
#ifdef VEC
  const __m128 *o = r->vo, *d = r->vd, zero = _mm_setzero_ps(), one = _mm_set1_ps(1);
  __m128 a[3], e1[3], e2[3], p[3], q[3], s[3], det, inv, u, v, t, ok;
  int c;
  for (c = 0; c < 3; c++) {
    a[c] = _mm_loadu_ps(T->a[c]);
    e1[c] = _mm_loadu_ps(T->e1[c]);
    e2[c] = _mm_loadu_ps(T->e2[c]);
    s[c] = _mm_sub_ps(o[c], a[c]);
  }
  p[0] = _mm_sub_ps(_mm_mul_ps(d[1], e2[2]), _mm_mul_ps(d[2], e2[1]));
  p[1] = _mm_sub_ps(_mm_mul_ps(d[2], e2[0]), _mm_mul_ps(d[0], e2[2]));
  p[2] = _mm_sub_ps(_mm_mul_ps(d[0], e2[1]), _mm_mul_ps(d[1], e2[0]));
  det = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e1[0], p[0]), _mm_mul_ps(e1[1], p[1])),
                   _mm_mul_ps(e1[2], p[2]));
  inv = _mm_div_ps(one, det);
  u = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(s[0], p[0]), _mm_mul_ps(s[1], p[1])),
                            _mm_mul_ps(s[2], p[2])), inv);
  q[0] = _mm_sub_ps(_mm_mul_ps(s[1], e1[2]), _mm_mul_ps(s[2], e1[1]));
  q[1] = _mm_sub_ps(_mm_mul_ps(s[2], e1[0]), _mm_mul_ps(s[0], e1[2]));
  q[2] = _mm_sub_ps(_mm_mul_ps(s[0], e1[1]), _mm_mul_ps(s[1], e1[0]));
  v = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(d[0], q[0]), _mm_mul_ps(d[1], q[1])),
                            _mm_mul_ps(d[2], q[2])), inv);
  t = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(e2[0], q[0]), _mm_mul_ps(e2[1], q[1])),
                            _mm_mul_ps(e2[2], q[2])), inv);
  ok = _mm_and_ps(_mm_cmpneq_ps(det, zero), _mm_cmpge_ps(u, zero));
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmple_ps(u, one), _mm_cmpge_ps(v, zero)));
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmple_ps(_mm_add_ps(u, v), one),
                                 _mm_cmpgt_ps(t, r->vtmin)));
  c = _mm_movemask_ps(ok);
  return (c & 1) + (c >> 1 & 1) + (c >> 2 & 1) + (c >> 3 & 1);
#else
  const float *o = r->o, *d = r->d;
  int k, n = 0;
  for (k = 0; k < 4; k++) {
    float e1[3] = {T->e1[0][k], T->e1[1][k], T->e1[2][k]};
    float e2[3] = {T->e2[0][k], T->e2[1][k], T->e2[2][k]}, p[3], q[3], s[3], det, inv, u, v;
    p[0] = d[1] * e2[2] - d[2] * e2[1];
    p[1] = d[2] * e2[0] - d[0] * e2[2];
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0) continue;
    inv = 1 / det;
    s[0] = o[0] - T->a[0][k]; s[1] = o[1] - T->a[1][k]; s[2] = o[2] - T->a[2][k];
    u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
    if (!(u >= 0 && u <= 1)) continue;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) * inv;
    if (!(v >= 0 && u + v <= 1)) continue;
    n += (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv > r->tmin;
  }
  return n;
#endif
}

/* The lowest set bit's index of the non-zero 4-bit mask m. */
static inline int lowbit (int m) {
  return (m & 1) ? 0 : (m & 2) ? 1 : (m & 4) ? 2 : 3;
}

/* The hits of the ray in the tree T (its leaves: packets of triangles when
** 'tri', else capsules), counting on from 'hits' up to cap. */
static int walk (const lsys_light *L, const lsys_ltree *T, int tri, const ray *r, int hits,
                 int cap) {
  uint32_t stack[STACK], cur = 0;
  int sp = 0, c;
  for (;;) {
    const lsys_lnode4 *q = &T->node[cur];
    float tn[4];
    int m = slabs(q, r, tn), lv = m & (int)q->leaves, inner = m & ~(int)q->leaves;
    while (lv != 0) {                               /* leaves: their primitives now */
      int k = lowbit(lv);
      uint32_t i = q->child[k], end = i + q->cnt[k];
      lv &= lv - 1;
      for (; i < end; i++)
        if ((hits += tri ? hit4(&L->pack[i], r) : capsule(&L->caps[i], r->o, r->d, r->tmin))
            >= cap)
          return cap;
    }
    if (inner == 0) {                               /* nothing below: the stack */
      if (sp == 0) return hits;
      cur = stack[--sp];
    } else if ((inner & (inner - 1)) == 0) cur = q->child[lowbit(inner)];   /* one child */
    else {                                          /* several: the nearest first */
      float kt[4];
      uint32_t kn[4];
      int n = 0;
      while (inner != 0) {
        int k = lowbit(inner), i = n++;
        inner &= inner - 1;
        for (; i > 0 && kt[i - 1] < tn[k]; i--) { kt[i] = kt[i - 1]; kn[i] = kn[i - 1]; }
        kt[i] = tn[k];
        kn[i] = q->child[k];
      }
      for (c = 0; c < n - 1; c++) stack[sp++] = kn[c];   /* the farthest deepest */
      cur = kn[n - 1];
    }
  }
}

static void setup (ray *r, const float o[3], const float d[3], float tmin) {
  int c;
  for (c = 0; c < 3; c++) {
    float x = d[c] != 0 ? d[c] : 1e-30f;
    r->o[c] = o[c];
    r->d[c] = d[c];
    r->inv[c] = 1 / x;
    r->near[c] = r->inv[c] >= 0 ? c : 3 + c;
    r->far[c] = r->near[c] == c ? 3 + c : c;
#ifdef VEC
    r->vo[c] = _mm_set1_ps(o[c]);
    r->vd[c] = _mm_set1_ps(d[c]);
    r->vinv[c] = _mm_set1_ps(r->inv[c]);
#endif
  }
  r->tmin = tmin;
#ifdef VEC
  r->vtmin = _mm_set1_ps(tmin);
#endif
}

int lsys_light_trace (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap) {
  ray r;
  int hits = 0;
  setup(&r, o, d, tmin);
  if (L->tri.nnodes > 0) hits = walk(L, &L->tri, 1, &r, 0, cap);
  if (hits < cap && L->cap.nnodes > 0) hits = walk(L, &L->cap, 0, &r, hits, cap);
  return hits;
}

int lsys_light_brute (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap) {
  ray r;
  size_t i;
  int hits = 0;
  setup(&r, o, d, tmin);
  for (i = 0; i < L->npack; i++)
    if ((hits += hit4(&L->pack[i], &r)) >= cap) return cap;
  for (i = 0; i < L->ncap; i++)
    if ((hits += capsule(&L->caps[i], o, d, tmin)) >= cap) return cap;
  return hits;
}
