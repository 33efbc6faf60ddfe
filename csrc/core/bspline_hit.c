/*
** Intersections of 2D uniform B-spline curves (bspline.h) with a ray and
** with each other, for the branching intersections of Anastacio et al.
** 2009, §3.4 (a ray from a node to a boundary) and the crossings of
** inclination lines with the stem and boundaries (§3.2).
**
** Both work span by span in Bezier form (lsys_bspline_bezier): a span's
** control polygon bounds it (convex hull), so a span or piece whose
** polygon misses the other object is dropped, and the rest is subdivided
** by de Casteljau's algorithm until the answer is unique, then refined by
** Newton's method on the span's exact polynomial. Hits are collected in a
** growing block (freed before returning), deduplicated and sorted.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_impl.h"

#define RAYDEPTH  60          /* halvings of one span's parameter interval */
#define XDEPTH    104         /* halvings of both pieces together (52 each) */
#define MAXWORK   50000000L   /* subdivision steps of one curve-curve call */

typedef struct hitbuf {
  lsys_bspline_hit *h;
  size_t n, cap;
  int err;                    /* LSYS_OK, LSYS_ENOMEM or LSYS_ELIMIT */
  int deep;                   /* the error is MAXWORK */
  long work;
} hitbuf;

static void push (hitbuf *hb, double t, double s, double x, double y) {
  if (hb->err != LSYS_OK) return;
  if (hb->n >= LSYS_BSPLINE_MAXHITS) {
    hb->err = LSYS_ELIMIT;
    return;
  }
  if (hb->n == hb->cap
      && lsys_common_grow((void **)&hb->h, &hb->cap, hb->n + 1, sizeof *hb->h) != LSYS_OK) {
    hb->err = LSYS_ENOMEM;
    return;
  }
  hb->h[hb->n++] = (lsys_bspline_hit){ t, s, x, y };
}

static double totee (const lsys_bspline *c, double u) {
  double t = (u - BS_U0(c)) / (BS_U1(c) - BS_U0(c));
  return t < 0 ? 0 : t > 1 ? 1 : t;
}

/* A Bernstein polynomial of degree p (coefficients b, stride 'st') at x. */
static double bern (const double *b, int p, int st, double x) {
  double w[4] = { 0, 0, 0, 0 };
  int i, r;
  for (i = 0; i <= p; i++) w[i] = b[i * st];
  for (r = 1; r <= p; r++)
    for (i = 0; i <= p - r; i++) w[i] = (1 - x) * w[i] + x * w[i + 1];
  return w[0];
}

/* Its derivative at x. */
static double dbern (const double *b, int p, int st, double x) {
  double d[3];
  int i;
  for (i = 0; i < p; i++) d[i] = p * (b[(i + 1) * st] - b[i * st]);
  return bern(d, p - 1, 1, x);
}

/* Splits Bezier control points (p + 1 points of 'dim' doubles) at 1/2. */
static void split (const double *P, int p, int dim, double *L, double *R) {
  double w[4] = { 0, 0, 0, 0 };
  int i, r, k;
  for (k = 0; k < dim; k++) {
    for (i = 0; i <= p; i++) w[i] = P[i * dim + k];
    L[k] = w[0];
    R[p * dim + k] = w[p];
    for (r = 1; r <= p; r++) {
      for (i = 0; i <= p - r; i++) w[i] = 0.5 * (w[i] + w[i + 1]);
      L[r * dim + k] = w[0];
      R[(p - r) * dim + k] = w[p - r];
    }
  }
}

static int cmp_t (const void *a, const void *b) {
  double x = ((const lsys_bspline_hit *)a)->t, y = ((const lsys_bspline_hit *)b)->t;
  return (x > y) - (x < y);
}

static int cmp_s (const void *a, const void *b) {
  const lsys_bspline_hit *p = (const lsys_bspline_hit *)a, *q = (const lsys_bspline_hit *)b;
  if (p->s != q->s) return (p->s > q->s) - (p->s < q->s);
  return (p->t > q->t) - (p->t < q->t);
}

/* Sorts by t and drops hits within 'dt' in t and 'ds' in s and 'dp' in
** position of the one before. */
static void dedupe (hitbuf *hb, double dt, double ds, double dp) {
  size_t i, k = 0;
  if (hb->n == 0) return;
  qsort(hb->h, hb->n, sizeof *hb->h, cmp_t);
  for (i = 1; i < hb->n; i++) {
    const lsys_bspline_hit *p = &hb->h[k], *q = &hb->h[i];
    if (q->t - p->t <= dt && fabs(q->s - p->s) <= ds
        && fabs(q->x - p->x) <= dp && fabs(q->y - p->y) <= dp) continue;
    hb->h[++k] = *q;
  }
  hb->n = k + 1;
}

/* Copies the hits out and sets the result; frees the block. */
static int finish (hitbuf *hb, lsys_bspline_hit *hits, size_t cap, size_t *count,
                   lsys_error *e) {
  int err = hb->err;
  if (err == LSYS_OK) {
    size_t n = hb->n < cap ? hb->n : cap;
    if (n > 0) memcpy(hits, hb->h, n * sizeof *hits);   /* no hits: h may be NULL */
    *count = hb->n;
  }
  LSYS_FREE(hb->h);
  if (err == LSYS_ENOMEM) return lsys_seterror(e, err, (size_t)-1, "not enough memory");
  if (err == LSYS_ELIMIT && hb->deep)
    return lsys_seterror(e, err, (size_t)-1, "intersection needs too many subdivisions "
                         "(limit is %ld)", MAXWORK);
  if (err == LSYS_ELIMIT)
    return lsys_seterror(e, err, (size_t)-1, "too many intersections (limit is %d)",
                         LSYS_BSPLINE_MAXHITS);
  return LSYS_OK;
}

/* The size of the curve's control polygon: the larger side of its box. */
static double extent (const lsys_bspline *c) {
  double lo[2] = { c->pt[0], c->pt[1] }, hi[2] = { c->pt[0], c->pt[1] };
  size_t i;
  int k;
  for (i = 1; i < c->n; i++)
    for (k = 0; k < 2; k++) {
      double v = c->pt[2 * i + (size_t)k];
      if (v < lo[k]) lo[k] = v;
      if (v > hi[k]) hi[k] = v;
    }
  return fmax(hi[0] - lo[0], hi[1] - lo[1]);
}

/* ---------------------------------------------------------------------- */
/* Curve-ray */

typedef struct rayctx {
  const lsys_bspline *c;
  double o[2], d[2], dd, eps;
  size_t s;                   /* the span */
  double bz[8];               /* its Bezier points */
  double f[4];                /* d x (B(x) - o): the signed distance times |d| */
  hitbuf *hb;
} rayctx;

/* Records the root x of span r->s when it lies on the ray (s >= 0). */
static void rayhit (rayctx *r, double x) {
  int p = r->c->degree;
  double px = bern(r->bz, p, 2, x), py = bern(r->bz + 1, p, 2, x);
  double s = ((px - r->o[0]) * r->d[0] + (py - r->o[1]) * r->d[1]) / r->dd;
  if (s < -r->eps) return;
  push(r->hb, totee(r->c, r->c->knot[r->s] + x), s < 0 ? 0 : s, px, py);
}

/* The one root of f in [lo, hi] (f changes sign there): Newton's method
** kept in the bracket, bisection when a step leaves it. */
static double solve1 (const double *f, int p, double lo, double hi) {
  double flo = bern(f, p, 1, lo), fhi = bern(f, p, 1, hi), x;
  int it;
  if (flo == 0) return lo;
  if (fhi == 0 || (flo > 0) == (fhi > 0)) return fabs(fhi) < fabs(flo) ? hi : lo;
  x = lo + (hi - lo) * flo / (flo - fhi);
  for (it = 0; it < 200; it++) {
    double fx = bern(f, p, 1, x), df, nx;
    if (fx == 0) break;
    if ((fx > 0) == (flo > 0)) lo = x; else hi = x;
    df = dbern(f, p, 1, x);
    nx = df != 0 ? x - fx / df : 0.5 * (lo + hi);
    if (!(nx > lo && nx < hi)) nx = 0.5 * (lo + hi);
    if (nx == x || hi - lo <= 1e-17) break;
    x = nx;
  }
  return x;
}

/* The roots of f (b: its coefficients on [x0, x1]) strictly inside. */
static void rayroots (rayctx *r, const double *b, double x0, double x1, int depth) {
  int p = r->c->degree, i, pos = 0, neg = 0, v = 0, last = 0;
  double L[4], R[4], xm;
  for (i = 0; i <= p; i++) {
    int sg = b[i] > 0 ? 1 : b[i] < 0 ? -1 : 0;
    if (sg > 0) pos = 1;
    if (sg < 0) neg = 1;
    if (sg != 0 && last != 0 && sg != last) v++;
    if (sg != 0) last = sg;
  }
  if (!pos || !neg) return;       /* one sign: no root inside (sum of positive terms) */
  if (v == 1 && b[0] * b[p] < 0) {
    rayhit(r, solve1(r->f, p, x0, x1));
    return;
  }
  xm = 0.5 * (x0 + x1);
  if (depth >= RAYDEPTH || xm <= x0 || xm >= x1) {   /* a touch, or the roots coincide */
    rayhit(r, xm);
    return;
  }
  split(b, p, 1, L, R);
  if (L[p] == 0) rayhit(r, xm);
  rayroots(r, L, x0, xm, depth + 1);
  rayroots(r, R, xm, x1, depth + 1);
}

/* Whether the span's B-spline control points lie strictly on one side of
** the ray's line, or all behind its origin: then the span misses it. */
static int raymisses (const rayctx *r, size_t s) {
  const double *P = r->c->pt + 2 * (s - (size_t)r->c->degree);
  int j, pos = 0, neg = 0, ahead = 0;
  for (j = 0; j <= r->c->degree; j++) {
    double x = P[2 * j] - r->o[0], y = P[2 * j + 1] - r->o[1];
    double cr = r->d[0] * y - r->d[1] * x;
    if (cr >= 0) pos = 1;
    if (cr <= 0) neg = 1;
    if (x * r->d[0] + y * r->d[1] >= -r->eps * r->dd) ahead = 1;
  }
  return !(pos && neg) || !ahead;
}

int lsys_bspline_ray (const lsys_bspline *c, const double o[2], const double d[2],
                      lsys_bspline_hit *hits, size_t cap, size_t *count, lsys_error *e) {
  hitbuf hb = { NULL, 0, 0, LSYS_OK, 0, 0 };
  rayctx r;
  size_t s;
  int p = c->degree, i;
  if (c->dim != 2)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "ray intersection needs a 2D curve");
  if (!isfinite(o[0]) || !isfinite(o[1]) || !isfinite(d[0]) || !isfinite(d[1]))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "ray origin and direction must be finite");
  if (d[0] == 0 && d[1] == 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "ray direction must not be zero");
  r.c = c;
  r.o[0] = o[0], r.o[1] = o[1], r.d[0] = d[0], r.d[1] = d[1];
  r.dd = d[0] * d[0] + d[1] * d[1];
  r.eps = 1e-10 * (extent(c) + fabs(o[0]) + fabs(o[1])) / sqrt(r.dd);
  r.hb = &hb;
  for (s = (size_t)p; s < c->n && hb.err == LSYS_OK; s++) {
    int allzero = 1;
    if (raymisses(&r, s)) continue;
    r.s = s;
    lsys_bspline_bezier(c, s, r.bz);
    for (i = 0; i <= p; i++) {
      r.f[i] = d[0] * (r.bz[2 * i + 1] - o[1]) - d[1] * (r.bz[2 * i] - o[0]);
      if (r.f[i] != 0) allzero = 0;
    }
    if (allzero) continue;             /* the span lies along the ray's line */
    if (r.f[0] == 0) rayhit(&r, 0.0);
    if (r.f[p] == 0) rayhit(&r, 1.0);
    rayroots(&r, r.f, 0.0, 1.0, 0);
  }
  {
    double spans = (double)lsys_bspline_spans(c), sc = extent(c) + 1e-300;
    dedupe(&hb, 1e-9 / spans, 1e-9 * sc / sqrt(r.dd), 1e-9 * sc);
  }
  if (hb.n > 1) qsort(hb.h, hb.n, sizeof *hb.h, cmp_s);
  return finish(&hb, hits, cap, count, e);
}

/* ---------------------------------------------------------------------- */
/* Curve-curve */

typedef struct xctx {
  const lsys_bspline *a, *b;
  size_t sa, sb;              /* the spans */
  double ba[8], bb[8];        /* their Bezier points */
  double tol;                 /* flatness and box padding */
  hitbuf *hb;
} xctx;

static void box (const double *P, int p, double lo[2], double hi[2]) {
  int i, k;
  for (k = 0; k < 2; k++) lo[k] = hi[k] = P[k];
  for (i = 1; i <= p; i++)
    for (k = 0; k < 2; k++) {
      if (P[2 * i + k] < lo[k]) lo[k] = P[2 * i + k];
      if (P[2 * i + k] > hi[k]) hi[k] = P[2 * i + k];
    }
}

/* How far the inner control points stray from the chord P_0 P_p. */
static double flatness (const double *P, int p) {
  double cx = P[2 * p] - P[0], cy = P[2 * p + 1] - P[1], len = hypot(cx, cy), dev = 0.0;
  int i;
  for (i = 1; i < p; i++) {
    double x = P[2 * i] - P[0], y = P[2 * i + 1] - P[1];
    double dv = len > 0 ? fabs(cx * y - cy * x) / len : hypot(x, y);
    if (dv > dev) dev = dv;
  }
  return dev;
}

/* Newton's method on A(xa) = B(xb) (span-local parameters, kept in
** [0, 1]); records the crossing when it converges. */
static void xnewton (xctx *x, double xa, double xb) {
  int pa = x->a->degree, pb = x->b->degree, it;
  double fx = 0, fy = 0;
  for (it = 0; it < 30; it++) {
    double ax = bern(x->ba, pa, 2, xa), ay = bern(x->ba + 1, pa, 2, xa);
    double bx = bern(x->bb, pb, 2, xb), by = bern(x->bb + 1, pb, 2, xb);
    double dax = dbern(x->ba, pa, 2, xa), day = dbern(x->ba + 1, pa, 2, xa);
    double dbx = dbern(x->bb, pb, 2, xb), dby = dbern(x->bb + 1, pb, 2, xb);
    double det = -dax * dby + day * dbx, na, nb;
    fx = ax - bx, fy = ay - by;
    if (det == 0 || (fx == 0 && fy == 0)) break;
    na = xa - (-dby * fx + dbx * fy) / det;   /* J = [dA, -dB], solve J (da, db) = F */
    nb = xb - (-day * fx + dax * fy) / det;
    na = na < 0 ? 0 : na > 1 ? 1 : na;
    nb = nb < 0 ? 0 : nb > 1 ? 1 : nb;
    if (na == xa && nb == xb) break;
    xa = na, xb = nb;
  }
  {
    double ax = bern(x->ba, pa, 2, xa), ay = bern(x->ba + 1, pa, 2, xa);
    fx = ax - bern(x->bb, pb, 2, xb), fy = ay - bern(x->bb + 1, pb, 2, xb);
    if (hypot(fx, fy) > 10 * x->tol) return;    /* did not converge: no crossing here */
    push(x->hb, totee(x->a, x->a->knot[x->sa] + xa), totee(x->b, x->b->knot[x->sb] + xb),
         ax, ay);
  }
}

/* Crosses the chords of two flat pieces; a crossing seeds Newton. */
static void xchords (xctx *x, const double *A, double a0, double a1, const double *B,
                     double b0, double b1) {
  int pa = x->a->degree, pb = x->b->degree;
  double rx = A[2 * pa] - A[0], ry = A[2 * pa + 1] - A[1];
  double qx = B[2 * pb] - B[0], qy = B[2 * pb + 1] - B[1];
  double wx = B[0] - A[0], wy = B[1] - A[1];
  double den = rx * qy - ry * qx, al, be;
  const double slack = 1e-6;
  if (fabs(den) <= 1e-14 * hypot(rx, ry) * hypot(qx, qy) || den == 0) return;   /* parallel */
  al = (wx * qy - wy * qx) / den;
  be = (wx * ry - wy * rx) / den;
  if (al < -slack || al > 1 + slack || be < -slack || be > 1 + slack) return;
  xnewton(x, a0 + (a1 - a0) * al, b0 + (b1 - b0) * be);
}

static void xrec (xctx *x, const double *A, double a0, double a1, const double *B, double b0,
                  double b1, int depth) {
  int pa = x->a->degree, pb = x->b->degree, fa, fb;
  double alo[2], ahi[2], blo[2], bhi[2], L[8], R[8], m;
  if (x->hb->err != LSYS_OK) return;
  if (++x->hb->work > MAXWORK) {
    x->hb->err = LSYS_ELIMIT;
    x->hb->deep = 1;
    return;
  }
  box(A, pa, alo, ahi);
  box(B, pb, blo, bhi);
  if (alo[0] > bhi[0] + x->tol || blo[0] > ahi[0] + x->tol
      || alo[1] > bhi[1] + x->tol || blo[1] > ahi[1] + x->tol) return;
  fa = flatness(A, pa) <= x->tol;
  fb = flatness(B, pb) <= x->tol;
  if ((fa && fb) || depth >= XDEPTH) {
    xchords(x, A, a0, a1, B, b0, b1);
    return;
  }
  if (fb || (!fa && hypot(ahi[0] - alo[0], ahi[1] - alo[1])
                    >= hypot(bhi[0] - blo[0], bhi[1] - blo[1]))) {
    split(A, pa, 2, L, R);
    m = 0.5 * (a0 + a1);
    xrec(x, L, a0, m, B, b0, b1, depth + 1);
    xrec(x, R, m, a1, B, b0, b1, depth + 1);
  } else {
    split(B, pb, 2, L, R);
    m = 0.5 * (b0 + b1);
    xrec(x, A, a0, a1, L, b0, m, depth + 1);
    xrec(x, A, a0, a1, R, m, b1, depth + 1);
  }
}

/* Whether the boxes of the B-spline control points of span sa of a and
** span sb of b (padded by tol) overlap. */
static int spansmeet (const lsys_bspline *a, size_t sa, const lsys_bspline *b, size_t sb,
                      double tol) {
  double alo[2], ahi[2], blo[2], bhi[2];
  box(a->pt + 2 * (sa - (size_t)a->degree), a->degree, alo, ahi);
  box(b->pt + 2 * (sb - (size_t)b->degree), b->degree, blo, bhi);
  return !(alo[0] > bhi[0] + tol || blo[0] > ahi[0] + tol
           || alo[1] > bhi[1] + tol || blo[1] > ahi[1] + tol);
}

int lsys_bspline_intersect (const lsys_bspline *a, const lsys_bspline *b,
                            lsys_bspline_hit *hits, size_t cap, size_t *count, lsys_error *e) {
  hitbuf hb = { NULL, 0, 0, LSYS_OK, 0, 0 };
  xctx x;
  double sc;
  if (a->dim != 2 || b->dim != 2)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "curve intersection needs 2D curves");
  sc = fmax(extent(a), extent(b));
  x.a = a;
  x.b = b;
  x.tol = 1e-9 * (sc > 0 ? sc : 1.0);
  x.hb = &hb;
  for (x.sa = (size_t)a->degree; x.sa < a->n && hb.err == LSYS_OK; x.sa++) {
    lsys_bspline_bezier(a, x.sa, x.ba);
    for (x.sb = (size_t)b->degree; x.sb < b->n && hb.err == LSYS_OK; x.sb++) {
      if (!spansmeet(a, x.sa, b, x.sb, x.tol)) continue;
      lsys_bspline_bezier(b, x.sb, x.bb);
      xrec(&x, x.ba, 0.0, 1.0, x.bb, 0.0, 1.0, 0);
    }
  }
  dedupe(&hb, 1e-7 / (double)lsys_bspline_spans(a), 1e-7 / (double)lsys_bspline_spans(b),
         100 * x.tol);
  return finish(&hb, hits, cap, count, e);
}
