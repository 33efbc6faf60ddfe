/*
** Uniform B-spline curves (bspline.h): knots, basis functions and their
** derivatives on one span, evaluation, arc length and its inverse, closest
** points; the polyline operations of stroke capture (Anastacio et al.
** 2009, §3.1). Intersections are in bspline_hit.c.
*/
#include <math.h>
#include <string.h>

#include "bspline_impl.h"

#define MAXDEG 3

void lsys_bspline_init (lsys_bspline *c) {
  memset(c, 0, sizeof *c);
}

void lsys_bspline_free (lsys_bspline *c) {
  LSYS_FREE(c->pt);
  LSYS_FREE(c->knot);
  LSYS_FREE(c->cum);
  lsys_bspline_init(c);
}

size_t lsys_bspline_spans (const lsys_bspline *c) {
  return c->n - (size_t)c->degree;
}

/* Checks dim and the coordinates of n points; messages count from 1. */
static int checkpoints (const double *pt, size_t n, int dim, lsys_error *e) {
  size_t i;
  int k;
  if (dim != 2 && dim != 3)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "dimension must be 2 or 3, got %d", dim);
  for (i = 0; i < n; i++)
    for (k = 0; k < dim; k++)
      if (!isfinite(pt[i * (size_t)dim + (size_t)k]))
        return lsys_seterror(e, LSYS_EARG, i, "point %zu: coordinate %d is not finite",
                             i + 1, k + 1);
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Basis functions */

/*
** The basis functions of degree 0 .. p that are not zero on span s
** (knot[s] <= u <= knot[s+1]), by the Cox-de Boor recursion:
** B[d][j] = N_(s-d+j, d)(u). A quotient with a zero knot interval (the
** repeated end knots of a clamped curve) counts as 0.
*/
static void basistable (const double *U, size_t s, double u, int p,
                        double B[MAXDEG + 1][MAXDEG + 1]) {
  int d, j;
  B[0][0] = 1.0;
  for (d = 1; d <= p; d++) {
    for (j = 0; j <= d; j++) {
      size_t i = s - (size_t)d + (size_t)j;
      double v = 0.0, den;
      if (j > 0 && (den = U[i + (size_t)d] - U[i]) > 0)
        v += (u - U[i]) / den * B[d - 1][j - 1];
      if (j < d && (den = U[i + (size_t)d + 1] - U[i + 1]) > 0)
        v += (U[i + (size_t)d + 1] - u) / den * B[d - 1][j];
      B[d][j] = v;
    }
  }
}

/*
** The k-th derivative (w.r.t. u) of the p + 1 basis functions of degree p on
** span s into N: from the functions of degree p - k, each step applies
** N'_(i,q) = q (N_(i,q-1) / (u_(i+q) - u_i) - N_(i+1,q-1) / (u_(i+q+1) - u_(i+1)))
** to the derivatives of one order less and one degree less.
*/
static void dbasis (const double *U, size_t s, double u, int p, int k, double *N) {
  double B[MAXDEG + 1][MAXDEG + 1], D[MAXDEG + 1], E[MAXDEG + 1];
  int q, j;
  basistable(U, s, u, p, B);
  for (j = 0; j <= p - k; j++) D[j] = B[p - k][j];
  for (q = p - k + 1; q <= p; q++) {
    for (j = 0; j <= q; j++) {
      size_t i = s - (size_t)q + (size_t)j;
      double v = 0.0, den;
      if (j > 0 && (den = U[i + (size_t)q] - U[i]) > 0) v += D[j - 1] / den;
      if (j < q && (den = U[i + (size_t)q + 1] - U[i + 1]) > 0) v -= D[j] / den;
      E[j] = q * v;
    }
    for (j = 0; j <= q; j++) D[j] = E[j];
  }
  for (j = 0; j <= p; j++) N[j] = D[j];
}

size_t lsys_bspline_span (const lsys_bspline *c, double u) {
  double f = floor(u - BS_U0(c));
  size_t s;
  if (!(f > 0)) return (size_t)c->degree;            /* also NaN */
  if (f >= (double)(c->n - (size_t)c->degree)) return c->n - 1;
  s = (size_t)c->degree + (size_t)f;
  return s < c->n ? s : c->n - 1;
}

void lsys_bspline_eval_span (const lsys_bspline *c, size_t s, double u, int k, double *out) {
  double N[MAXDEG + 1];
  int j, d;
  const double *P = c->pt + (s - (size_t)c->degree) * (size_t)c->dim;
  for (d = 0; d < c->dim; d++) out[d] = 0.0;
  if (k > c->degree) return;
  dbasis(c->knot, s, u, c->degree, k, N);
  for (j = 0; j <= c->degree; j++)
    for (d = 0; d < c->dim; d++) out[d] += N[j] * P[j * c->dim + d];
}

/* Knot value of t in [0, 1] (clamped; NaN gives 0). */
static double tou (const lsys_bspline *c, double t) {
  if (!(t > 0)) t = 0;
  if (t > 1) t = 1;
  return BS_U0(c) + t * (BS_U1(c) - BS_U0(c));
}

static double tot (const lsys_bspline *c, double u) {
  double t = (u - BS_U0(c)) / (BS_U1(c) - BS_U0(c));
  return t < 0 ? 0 : t > 1 ? 1 : t;
}

size_t lsys_bspline_basis (const lsys_bspline *c, double t, int k, double *N) {
  double u = tou(c, t), scale = 1.0;
  size_t s = lsys_bspline_span(c, u);
  int j;
  if (k < 0 || k > c->degree) {
    for (j = 0; j <= c->degree; j++) N[j] = 0.0;
    return s - (size_t)c->degree;
  }
  dbasis(c->knot, s, u, c->degree, k, N);
  for (j = 0; j < k; j++) scale *= (double)lsys_bspline_spans(c);
  for (j = 0; j <= c->degree; j++) N[j] *= scale;
  return s - (size_t)c->degree;
}

void lsys_bspline_eval (const lsys_bspline *c, double t, int k, double *out) {
  double u = tou(c, t), scale = 1.0;
  int j;
  lsys_bspline_eval_span(c, lsys_bspline_span(c, u), u, k, out);
  for (j = 0; j < k; j++) scale *= (double)lsys_bspline_spans(c);
  for (j = 0; j < c->dim; j++) out[j] *= scale;
}

void lsys_bspline_sample (const lsys_bspline *c, size_t m, double *out) {
  size_t i;
  for (i = 0; i < m; i++)
    lsys_bspline_eval(c, m > 1 ? (double)i / (double)(m - 1) : 0.0, 0, out + i * (size_t)c->dim);
}

/*
** The Bezier control points of span s: the power form of the span from its
** derivatives at the span's start (x = u - knot[s] in [0, 1], unit knot
** interval), a_j = C^(j)(knot[s]) / j!, then b_i = sum_(j<=i) C(i,j)/C(p,j) a_j.
*/
void lsys_bspline_bezier (const lsys_bspline *c, size_t s, double *bz) {
  static const double binom[MAXDEG + 1][MAXDEG + 1] = {
    {1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}
  };
  double a[MAXDEG + 1][3];
  int p = c->degree, dim = c->dim, i, j, d;
  double fact = 1.0;
  for (j = 0; j <= p; j++) {
    if (j > 1) fact *= j;
    lsys_bspline_eval_span(c, s, c->knot[s], j, a[j]);
    for (d = 0; d < dim; d++) a[j][d] /= fact;
  }
  for (i = 0; i <= p; i++)
    for (d = 0; d < dim; d++) {
      double v = 0.0;
      for (j = 0; j <= i; j++) v += binom[i][j] / binom[p][j] * a[j][d];
      bz[i * dim + d] = v;
    }
}

/* ---------------------------------------------------------------------- */
/* Setting a curve */

static void spanlengths (lsys_bspline *c);

int lsys_bspline_set (lsys_bspline *c, const double *pt, size_t n, int dim, int degree,
                      int clamped, lsys_error *e) {
  lsys_bspline nc;
  size_t j, nk, spans;
  int st;
  if (degree != 2 && degree != 3)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "degree must be 2 or 3, got %d", degree);
  if (n > LSYS_BSPLINE_MAXPOINTS)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "too many control points (limit is %d)", LSYS_BSPLINE_MAXPOINTS);
  if (n < (size_t)degree + 1)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "a curve of degree %d needs at least %d control points, got %zu",
                         degree, degree + 1, n);
  if ((st = checkpoints(pt, n, dim, e)) != LSYS_OK) return st;
  lsys_bspline_init(&nc);
  nk = n + (size_t)degree + 1;
  spans = n - (size_t)degree;
  nc.pt = (double *)LSYS_MALLOC(n * (size_t)dim * sizeof *nc.pt);
  nc.knot = (double *)LSYS_MALLOC(nk * sizeof *nc.knot);
  nc.cum = (double *)LSYS_MALLOC((spans + 1) * sizeof *nc.cum);
  if (nc.pt == NULL || nc.knot == NULL || nc.cum == NULL) {
    lsys_bspline_free(&nc);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  }
  memcpy(nc.pt, pt, n * (size_t)dim * sizeof *nc.pt);
  nc.n = n;
  nc.dim = dim;
  nc.degree = degree;
  nc.clamped = clamped != 0;
  for (j = 0; j < nk; j++) {
    if (!nc.clamped) nc.knot[j] = (double)j;
    else if (j <= (size_t)degree) nc.knot[j] = 0.0;
    else if (j >= n) nc.knot[j] = (double)spans;
    else nc.knot[j] = (double)(j - (size_t)degree);
  }
  spanlengths(&nc);
  lsys_bspline_free(c);
  *c = nc;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Arc length */

/* Gauss-Legendre, 8 nodes on [-1, 1]: the positive nodes and their weights. */
static const double GL[4][2] = {
  {9.60289856497536231684e-1, 1.01228536290376259153e-1},
  {7.96666477413626739592e-1, 2.22381034453374470544e-1},
  {5.25532409916328985818e-1, 3.13706645877887287338e-1},
  {1.83434642495649804939e-1, 3.62683783378361982965e-1},
};

static double speed (const lsys_bspline *c, size_t s, double u) {
  double d[3];
  lsys_bspline_eval_span(c, s, u, 1, d);
  return sqrt(d[0] * d[0] + d[1] * d[1] + (c->dim == 3 ? d[2] * d[2] : 0.0));
}

static double gl8 (const lsys_bspline *c, size_t s, double a, double b) {
  double m = 0.5 * (a + b), h = 0.5 * (b - a), v = 0.0;
  int i;
  for (i = 0; i < 4; i++)
    v += GL[i][1] * (speed(c, s, m - h * GL[i][0]) + speed(c, s, m + h * GL[i][0]));
  return v * h;
}

/* Adaptive: halves until the halves agree with the whole to 1e-13 (the
** error of 8-point Gauss is far below the difference), at most 30 levels. */
static double adapt (const lsys_bspline *c, size_t s, double a, double b, double whole,
                     int depth) {
  double m = 0.5 * (a + b);
  double l = gl8(c, s, a, m), r = gl8(c, s, m, b);
  if (depth >= 30 || fabs(l + r - whole) <= 1e-13 * fabs(l + r) + 1e-300) return l + r;
  return adapt(c, s, a, m, l, depth + 1) + adapt(c, s, m, b, r, depth + 1);
}

/* Arc length over [a, b] within span s. */
static double spanlength (const lsys_bspline *c, size_t s, double a, double b) {
  if (!(b > a)) return 0.0;
  return adapt(c, s, a, b, gl8(c, s, a, b), 0);
}

/* Arc length from the start to u. */
static double lengthto (const lsys_bspline *c, double u) {
  size_t s = lsys_bspline_span(c, u);
  if (u <= BS_U0(c)) return 0.0;
  return c->cum[s - (size_t)c->degree] + spanlength(c, s, c->knot[s], u);
}

/* Fills c->cum: the arc length from the start to the start of each span. */
static void spanlengths (lsys_bspline *c) {
  size_t j, spans = lsys_bspline_spans(c);
  double acc = 0.0;
  c->cum[0] = 0.0;
  for (j = 0; j < spans; j++) {
    size_t s = j + (size_t)c->degree;
    acc += spanlength(c, s, c->knot[s], c->knot[s + 1]);
    c->cum[j + 1] = acc;
  }
}

double lsys_bspline_length (const lsys_bspline *c) {
  return c->cum[lsys_bspline_spans(c)];
}

double lsys_bspline_length_between (const lsys_bspline *c, double t0, double t1) {
  double u0 = tou(c, t0), u1 = tou(c, t1);
  size_t s0 = lsys_bspline_span(c, u0), s1 = lsys_bspline_span(c, u1);
  if (u1 < u0) return -lsys_bspline_length_between(c, t1, t0);
  if (s0 == s1) return spanlength(c, s0, u0, u1);
  return lengthto(c, u1) - lengthto(c, u0);
}

double lsys_bspline_at_length (const lsys_bspline *c, double s) {
  size_t spans = lsys_bspline_spans(c), lo = 0, hi = spans, sp;
  double L = c->cum[spans], a, b, u, seg, acc;
  int it;
  if (!(s > 0) || !(L > 0)) return 0.0;
  if (s >= L) return 1.0;
  while (hi - lo > 1) {                   /* cum[lo] <= s < cum[hi] */
    size_t mid = lo + (hi - lo) / 2;
    if (c->cum[mid] <= s) lo = mid; else hi = mid;
  }
  sp = lo + (size_t)c->degree;
  a = c->knot[sp];
  b = c->knot[sp + 1];
  seg = c->cum[lo + 1] - c->cum[lo];
  s -= c->cum[lo];
  u = seg > 0 ? a + (b - a) * (s / seg) : a;
  acc = spanlength(c, sp, c->knot[sp], u);    /* then updated by the steps' lengths */
  for (it = 0; it < 100; it++) {
    double g = acc - s, v = speed(c, sp, u), nu;
    if (g == 0) break;
    if (g < 0) a = u; else b = u;
    nu = v > 0 ? u - g / v : 0.5 * (a + b);
    if (fabs(nu - u) <= 1e-14 * (1.0 + fabs(u))) {   /* converged (u is on the bracket) */
      if (nu >= a && nu <= b) u = nu;
      break;
    }
    if (!(nu > a && nu < b)) nu = 0.5 * (a + b);
    acc += nu > u ? spanlength(c, sp, u, nu) : -spanlength(c, sp, nu, u);
    u = nu;
  }
  return tot(c, u);
}

void lsys_bspline_sample_length (const lsys_bspline *c, size_t m, double *out, double *t) {
  double L = lsys_bspline_length(c);
  size_t i;
  for (i = 0; i < m; i++) {
    double ti = i == 0 ? 0.0 : i + 1 == m ? 1.0
              : lsys_bspline_at_length(c, L * (double)i / (double)(m - 1));
    lsys_bspline_eval(c, ti, 0, out + i * (size_t)c->dim);
    if (t != NULL) t[i] = ti;
  }
}

/* ---------------------------------------------------------------------- */
/* Closest point */

static double dist2 (const double *a, const double *b, int dim) {
  double s = 0.0;
  int k;
  for (k = 0; k < dim; k++) s += (a[k] - b[k]) * (a[k] - b[k]);
  return s;
}

/* Squared distance from q to the box of the control points of span s. */
static double boxdist2 (const lsys_bspline *c, size_t s, const double *q) {
  const double *P = c->pt + (s - (size_t)c->degree) * (size_t)c->dim;
  double d2 = 0.0;
  int k, j;
  for (k = 0; k < c->dim; k++) {
    double lo = P[k], hi = P[k];
    for (j = 1; j <= c->degree; j++) {
      double v = P[j * c->dim + k];
      if (v < lo) lo = v;
      if (v > hi) hi = v;
    }
    if (q[k] < lo) d2 += (lo - q[k]) * (lo - q[k]);
    else if (q[k] > hi) d2 += (q[k] - hi) * (q[k] - hi);
  }
  return d2;
}

/* Newton's method on g(u) = (C(u) - q) . C'(u) within [a, b] from u. */
static double refine (const lsys_bspline *c, size_t s, const double *q, double u,
                      double a, double b) {
  int it, k;
  for (it = 0; it < 30; it++) {
    double p[3], d1[3], d2[3], g = 0.0, dg = 0.0, nu;
    lsys_bspline_eval_span(c, s, u, 0, p);
    lsys_bspline_eval_span(c, s, u, 1, d1);
    lsys_bspline_eval_span(c, s, u, 2, d2);
    for (k = 0; k < c->dim; k++) {
      g += (p[k] - q[k]) * d1[k];
      dg += d1[k] * d1[k] + (p[k] - q[k]) * d2[k];
    }
    if (!(dg > 0)) break;
    nu = u - g / dg;
    if (nu < a) nu = a;
    if (nu > b) nu = b;
    if (fabs(nu - u) <= 1e-15 * (1.0 + fabs(u))) return nu;
    u = nu;
  }
  return u;
}

void lsys_bspline_closest (const lsys_bspline *c, const double *q, double *t, double *dist) {
  double best, bu = BS_U0(c), p[3];
  size_t s;
  lsys_bspline_eval_span(c, (size_t)c->degree, bu, 0, p);
  best = dist2(p, q, c->dim);
  for (s = (size_t)c->degree; s < c->n; s++) {    /* a first bound: the spans' middles */
    lsys_bspline_eval_span(c, s, c->knot[s] + 0.5, 0, p);
    if (dist2(p, q, c->dim) < best) {
      best = dist2(p, q, c->dim);
      bu = c->knot[s] + 0.5;
    }
  }
  for (s = (size_t)c->degree; s < c->n; s++) {
    double a = c->knot[s], b = c->knot[s + 1], su = b, sd, u;
    int i;
    if (boxdist2(c, s, q) > best) continue;
    lsys_bspline_eval_span(c, s, b, 0, p);
    sd = dist2(p, q, c->dim);
    for (i = 0; i < 8; i++) {
      double x = a + (b - a) * (i / 8.0);
      lsys_bspline_eval_span(c, s, x, 0, p);
      if (dist2(p, q, c->dim) < sd) {
        sd = dist2(p, q, c->dim);
        su = x;
      }
    }
    u = refine(c, s, q, su, a, b);
    lsys_bspline_eval_span(c, s, u, 0, p);
    if (dist2(p, q, c->dim) < sd) {
      sd = dist2(p, q, c->dim);
      su = u;
    }
    if (sd < best) {
      best = sd;
      bu = su;
    }
  }
  *t = tot(c, bu);
  *dist = sqrt(best);
}

/* ---------------------------------------------------------------------- */
/* Polylines */

static double seglen (const double *a, const double *b, int dim) {
  return sqrt(dist2(a, b, dim));
}

int lsys_bspline_resample_count (const double *pt, size_t n, int dim, double spacing,
                                 size_t *m, lsys_error *e) {
  double L = 0.0, r;
  size_t i;
  int st;
  if (n > LSYS_BSPLINE_MAXPOINTS)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "too many points (limit is %d)",
                         LSYS_BSPLINE_MAXPOINTS);
  if (n < 2)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "a polyline needs at least 2 points, got %zu",
                         n);
  if ((st = checkpoints(pt, n, dim, e)) != LSYS_OK) return st;
  if (!(spacing > 0) || !isfinite(spacing))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "spacing must be a positive finite number");
  for (i = 0; i + 1 < n; i++) L += seglen(pt + i * (size_t)dim, pt + (i + 1) * (size_t)dim, dim);
  r = floor(L / spacing + 0.5);
  if (!(r < LSYS_BSPLINE_MAXPOINTS))
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "resampling gives too many points (limit is %d)",
                         LSYS_BSPLINE_MAXPOINTS);
  *m = (r < 1 ? 1 : (size_t)r) + 1;
  return LSYS_OK;
}

void lsys_bspline_resample (double *out, size_t m, const double *pt, size_t n, int dim) {
  double L = 0.0, acc = 0.0, len;
  size_t i, j = 0, d = (size_t)dim;
  int k;
  for (i = 0; i + 1 < n; i++) L += seglen(pt + i * d, pt + (i + 1) * d, dim);
  memcpy(out, pt, d * sizeof *out);
  len = n > 1 ? seglen(pt, pt + d, dim) : 0.0;
  for (i = 1; i + 1 < m; i++) {
    double target = L * (double)i / (double)(m - 1), f;
    while (j + 2 < n && acc + len < target) {    /* segment j: [acc, acc + len] */
      acc += len;
      j++;
      len = seglen(pt + j * d, pt + (j + 1) * d, dim);
    }
    f = len > 0 ? (target - acc) / len : 0.0;
    if (f < 0) f = 0;
    if (f > 1) f = 1;
    for (k = 0; k < dim; k++)
      out[i * d + (size_t)k] = pt[j * d + (size_t)k] + f * (pt[(j + 1) * d + (size_t)k]
                                                            - pt[j * d + (size_t)k]);
  }
  if (m > 1) memcpy(out + (m - 1) * d, pt + (n - 1) * d, d * sizeof *out);
}

void lsys_bspline_chaikin (double *out, const double *pt, size_t n, int dim) {
  size_t i, d = (size_t)dim;
  int k;
  memcpy(out, pt, d * sizeof *out);
  for (i = 0; i + 1 < n; i++)
    for (k = 0; k < dim; k++) {
      double a = pt[i * d + (size_t)k], b = pt[(i + 1) * d + (size_t)k];
      out[(2 * i + 1) * d + (size_t)k] = 0.75 * a + 0.25 * b;
      out[(2 * i + 2) * d + (size_t)k] = 0.25 * a + 0.75 * b;
    }
  memcpy(out + (2 * n - 1) * d, pt + (n - 1) * d, d * sizeof *out);
}

size_t lsys_bspline_chaikin_reverse (double *out, const double *pt, size_t n, int dim) {
  size_t m = (n + 1) / 2, i, d = (size_t)dim;
  int k;
  if (out != pt) memcpy(out, pt, d * sizeof *out);
  for (i = 1; i + 1 < m; i++)            /* reads points 2i-1 .. 2i+2 >= i: not yet written */
    for (k = 0; k < dim; k++)
      out[i * d + (size_t)k] = -0.25 * pt[(2 * i - 1) * d + (size_t)k]
                               + 0.75 * pt[(2 * i) * d + (size_t)k]
                               + 0.75 * pt[(2 * i + 1) * d + (size_t)k]
                               - 0.25 * pt[(2 * i + 2) * d + (size_t)k];
  memmove(out + (m - 1) * d, pt + (n - 1) * d, d * sizeof *out);
  return m;
}

int lsys_bspline_stroke_size (const double *pt, size_t n, int dim, double spacing, int degree,
                              size_t *cap, lsys_error *e) {
  size_t m;
  int st = lsys_bspline_resample_count(pt, n, dim, spacing, &m, e);
  if (st != LSYS_OK) return st;
  *cap = m < (size_t)degree + 1 ? (size_t)degree + 1 : m;
  return LSYS_OK;
}

int lsys_bspline_stroke (double *out, size_t cap, const double *pt, size_t n, int dim,
                         double spacing, int steps, int degree, size_t *nout, lsys_error *e) {
  size_t m, need, i;
  int st, k;
  double L = 0.0;
  if (degree != 2 && degree != 3)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "degree must be 2 or 3, got %d", degree);
  if (steps < 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "steps must be >= 0, got %d", steps);
  if ((st = lsys_bspline_resample_count(pt, n, dim, spacing, &m, e)) != LSYS_OK) return st;
  for (i = 0; i + 1 < n; i++)
    L += seglen(pt + i * (size_t)dim, pt + (i + 1) * (size_t)dim, dim);
  if (!(L > 0)) return lsys_seterror(e, LSYS_EARG, (size_t)-1, "the stroke has no length");
  need = (size_t)degree + 1;
  if (cap < (m < need ? need : m))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "output too small for the stroke");
  if (m < need) m = need;                 /* a short stroke: degree + 1 points */
  lsys_bspline_resample(out, m, pt, n, dim);
  for (k = 0; k < steps && (m + 1) / 2 >= need; k++)
    m = lsys_bspline_chaikin_reverse(out, out, m, dim);
  *nout = m;
  return LSYS_OK;
}
