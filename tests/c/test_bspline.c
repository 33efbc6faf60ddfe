/*
** C unit tests for B-spline curves (csrc/core/bspline.c, bspline_hit.c):
** hand-computed points and derivatives of uniform and clamped quadratic and
** cubic curves, derivatives against finite differences, partition of
** unity, arc length of a line, a parabola and a cubic against closed forms
** or an independent integral, at_length round trips, resampling, Chaikin
** subdivision and its reverse, stroke capture, curve-ray and curve-curve
** intersections with hand-computed answers, closest points, bad input.
**
** The core files are compiled in with counting allocators: every block is
** freed, and allocation failures are injected.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "bspline.c"
#include "bspline_hit.c"

static void near (double want, double got, double tol, const char *what) {
  if (!(fabs(want - got) <= tol)) {
    fprintf(stderr, "%s: expected %.17g, got %.17g (tolerance %g)\n", what, want, got, tol);
    assert(0);
  }
}

static void curve (lsys_bspline *c, const double *pt, size_t n, int dim, int degree,
                   int clamped) {
  lsys_error e;
  int st = lsys_bspline_set(c, pt, n, dim, degree, clamped, &e);
  if (st != LSYS_OK) fprintf(stderr, "unexpected error: %s\n", e.msg);
  assert(st == LSYS_OK);
}

static void at (const lsys_bspline *c, double t, int k, double x, double y, const char *what) {
  double p[3];
  lsys_bspline_eval(c, t, k, p);
  near(x, p[0], 1e-13, what);
  near(y, p[1], 1e-13, what);
}

static const double P5[] = { 0, 0, 1, 2, 3, 3, 4, 0, 6, 1 };

static void test_uniform (void) {
  lsys_bspline c;
  lsys_bspline_init(&c);
  /* quadratic, 4 points: on a span with local x the weights are
  ** (1-x)^2/2, (1 + 2x - 2x^2)/2, x^2/2; two spans, t = 0.25 is x = 1/2 */
  curve(&c, P5, 4, 2, 2, 0);
  assert(lsys_bspline_spans(&c) == 2);
  at(&c, 0.0, 0, 0.5, 1.0, "quadratic t=0");              /* (P0 + P1) / 2 */
  at(&c, 0.25, 0, 9.0 / 8, 15.0 / 8, "quadratic t=1/4");  /* (P0 + 6 P1 + P2) / 8 */
  at(&c, 0.5, 0, 2.0, 2.5, "quadratic t=1/2");            /* (P1 + P2) / 2 */
  at(&c, 1.0, 0, 3.5, 1.5, "quadratic t=1");              /* (P2 + P3) / 2 */
  at(&c, 2.0, 0, 3.5, 1.5, "t clamped above");
  at(&c, -1.0, 0, 0.5, 1.0, "t clamped below");
  at(&c, 0.25, 1, 3.0, 3.0, "quadratic C'(1/4)");         /* 2 * (P2 - P0) / 2 */
  at(&c, 0.25, 2, 4.0, -4.0, "quadratic C''(1/4)");       /* 4 * (P0 - 2 P1 + P2) */
  /* cubic, 5 points: weights (1,4,1,0)/6 at x = 0 and (1,23,23,1)/48 at 1/2 */
  curve(&c, P5, 5, 2, 3, 0);
  assert(lsys_bspline_spans(&c) == 2 && c.degree == 3 && c.n == 5);
  at(&c, 0.0, 0, 7.0 / 6, 11.0 / 6, "cubic t=0");
  at(&c, 0.25, 0, 2.0, 115.0 / 48, "cubic t=1/4");
  at(&c, 1.0, 0, 25.0 / 6, 4.0 / 6, "cubic t=1");
  at(&c, 0.0, 1, 3.0, 3.0, "cubic C'(0)");                /* 2 * (P2 - P0) / 2 */
  at(&c, 0.0, 2, 4.0, -4.0, "cubic C''(0)");              /* 4 * (P0 - 2 P1 + P2) */
  lsys_bspline_free(&c);
}

static void test_clamped (void) {
  lsys_bspline c;
  lsys_bspline_init(&c);
  curve(&c, P5, 4, 2, 2, 1);                    /* knots 0 0 0 1 2 2 2 */
  at(&c, 0.0, 0, 0.0, 0.0, "clamped quadratic starts at P0");
  at(&c, 1.0, 0, 4.0, 0.0, "clamped quadratic ends at P3");
  at(&c, 0.5, 0, 2.0, 2.5, "clamped quadratic at the inner knot");   /* (P1 + P2) / 2 */
  at(&c, 0.0, 1, 4.0, 8.0, "clamped quadratic C'(0)");   /* 2 * 2 (P1 - P0) */
  curve(&c, P5, 4, 2, 3, 1);                    /* one span: a cubic Bezier curve */
  at(&c, 0.5, 0, 2.0, 15.0 / 8, "clamped cubic t=1/2");   /* (P0 + 3P1 + 3P2 + P3) / 8 */
  at(&c, 0.0, 1, 3.0, 6.0, "clamped cubic C'(0)");        /* 3 (P1 - P0) */
  at(&c, 1.0, 1, 3.0, -9.0, "clamped cubic C'(1)");       /* 3 (P3 - P2) */
  {
    const double q[] = { 0, 0, 0, 1, 2, 1, 3, 1, 3 };   /* 3D, Bezier */
    double p[3];
    curve(&c, q, 3, 3, 2, 1);
    lsys_bspline_eval(&c, 0.5, 0, p);          /* (P0 + 2 P1 + P2) / 4 */
    near(1.25, p[0], 1e-15, "3D x");
    near(1.25, p[1], 1e-15, "3D y");
    near(1.25, p[2], 1e-15, "3D z");
  }
  lsys_bspline_free(&c);
}

/* Derivatives against central differences; the basis sums to 1 and its
** derivatives to 0, and give the same point as evaluation. */
static void test_basis (void) {
  static const double pts[] = { 0, 0, 1, 3, 2, -1, 4, 2, 5, 5, 7, 1, 8, 0, 9, 4 };
  lsys_bspline c;
  int deg, cl, i, k;
  lsys_bspline_init(&c);
  for (deg = 2; deg <= 3; deg++)
    for (cl = 0; cl <= 1; cl++) {
      curve(&c, pts, 8, 2, deg, cl);
      for (i = 0; i <= 1000; i++) {
        double t = i / 1000.0, N[4], sum = 0, p[2] = { 0, 0 }, q[2];
        size_t first = lsys_bspline_basis(&c, t, 0, N);
        for (k = 0; k <= deg; k++) {
          assert(N[k] >= 0);
          sum += N[k];
          p[0] += N[k] * pts[2 * (first + (size_t)k)];
          p[1] += N[k] * pts[2 * (first + (size_t)k) + 1];
        }
        near(1.0, sum, 1e-14, "partition of unity");
        lsys_bspline_eval(&c, t, 0, q);
        near(q[0], p[0], 1e-12, "basis gives the point");
        near(q[1], p[1], 1e-12, "basis gives the point");
        lsys_bspline_basis(&c, t, 1, N);
        near(0.0, N[0] + N[1] + N[2] + (deg == 3 ? N[3] : 0), 1e-11, "derivatives sum to 0");
      }
      for (i = 1; i < 50; i++) {
        double t = i / 50.0 + 0.003, h = 1e-6, a[2], b[2], d[2];
        for (k = 1; k <= 2; k++) {
          lsys_bspline_eval(&c, t - h, k - 1, a);
          lsys_bspline_eval(&c, t + h, k - 1, b);
          lsys_bspline_eval(&c, t, k, d);
          near((b[0] - a[0]) / (2 * h), d[0], 1e-4 * (1 + fabs(d[0])), "finite difference x");
          near((b[1] - a[1]) / (2 * h), d[1], 1e-4 * (1 + fabs(d[1])), "finite difference y");
        }
      }
    }
  lsys_bspline_free(&c);
}

static void test_length (void) {
  lsys_bspline c;
  int i;
  lsys_bspline_init(&c);
  {   /* lines */
    const double line[] = { 0, 0, 1, 1, 2, 2, 3, 3, 4, 4 }, flat[] = { 0, 0, 1, 0, 2, 0, 3, 0 };
    curve(&c, line, 5, 2, 3, 1);
    near(4 * sqrt(2.0), lsys_bspline_length(&c), 1e-13, "clamped cubic line");
    curve(&c, flat, 4, 2, 2, 0);                 /* from x = 0.5 to 2.5 */
    near(2.0, lsys_bspline_length(&c), 1e-14, "uniform quadratic line");
    near(1.0, lsys_bspline_length_between(&c, 0.25, 0.75), 1e-14, "part of a line");
    near(-1.0, lsys_bspline_length_between(&c, 0.75, 0.25), 1e-14, "backwards");
  }
  {   /* y = x^2 on [-1, 1]: sqrt(5) + asinh(2) / 2 */
    const double par[] = { -1, 1, 0, -1, 1, 1 };
    double L = sqrt(5.0) + asinh(2.0) / 2;
    curve(&c, par, 3, 2, 2, 1);
    near(L, lsys_bspline_length(&c), 1e-10 * L, "parabola");
    near(L / 2, lsys_bspline_length_between(&c, 0.5, 1.0), 1e-10 * L, "half parabola");
    for (i = 0; i <= 20; i++) {
      double s = L * i / 20.0, t = lsys_bspline_at_length(&c, s);
      near(s, lsys_bspline_length_between(&c, 0, t), 1e-11 * L, "at_length round trip");
    }
    near(0.5, lsys_bspline_at_length(&c, L / 2), 1e-12, "middle of the parabola");
    near(0.0, lsys_bspline_at_length(&c, -1), 0, "at_length below 0");
    near(1.0, lsys_bspline_at_length(&c, 2 * L), 0, "at_length beyond the end");
  }
  {   /* y = x^3 on [0, 1] (a cubic Bezier curve); Simpson on sqrt(1 + 9 x^4) */
    const double cub[] = { 0, 0, 1.0 / 3, 0, 2.0 / 3, 0, 1, 1 };
    double L = 0, h = 1.0 / 200000;
    for (i = 0; i <= 200000; i++) {
      double x = i * h, f = sqrt(1 + 9 * x * x * x * x);
      L += f * (i == 0 || i == 200000 ? 1 : i % 2 ? 4 : 2);
    }
    L *= h / 3;
    curve(&c, cub, 4, 2, 3, 1);
    near(L, lsys_bspline_length(&c), 1e-11 * L, "cubic y = x^3");
  }
  {   /* a many-span curve: equal arc-length samples are equally spaced */
    double pts[2 * 40], out[2 * 33], t[33];
    for (i = 0; i < 40; i++) {
      pts[2 * i] = cos(i * 0.3) * (3 + i);
      pts[2 * i + 1] = sin(i * 0.3) * (3 + i);
    }
    curve(&c, pts, 40, 2, 3, 0);
    lsys_bspline_sample_length(&c, 33, out, t);
    assert(t[0] == 0 && t[32] == 1);
    for (i = 0; i < 32; i++)
      near(lsys_bspline_length(&c) / 32, lsys_bspline_length_between(&c, t[i], t[i + 1]),
           1e-9, "equal arc steps");
  }
  lsys_bspline_free(&c);
}

static void test_chaikin (void) {
  double c[2 * 7], f[2 * 14], r[2 * 7], out[2 * 8];
  int i;
  size_t m;
  for (i = 0; i < 14; i++) c[i] = (double)((i * 37) % 11) - 3.5 * (i % 3);
  lsys_bspline_chaikin(f, c, 7, 2);
  near(0, f[0], 0, "ends kept");
  near(c[12], f[26], 0, "ends kept");
  near(0.75 * c[0] + 0.25 * c[2], f[2], 1e-15, "corner cut");
  near(0.25 * c[0] + 0.75 * c[2], f[4], 1e-15, "corner cut");
  m = lsys_bspline_chaikin_reverse(r, f, 14, 2);
  assert(m == 7);
  for (i = 0; i < 14; i++) near(c[i], r[i], 1e-13, "reverse(chaikin(c)) = c");
  m = lsys_bspline_chaikin_reverse(f, f, 14, 2);    /* in place */
  assert(m == 7);
  for (i = 0; i < 14; i++) near(c[i], f[i], 1e-13, "in place");
  {   /* odd count, by hand: x = 0 .. 4 gives 0, 2.5, 4 */
    double g[] = { 0, 0, 1, 0, 2, 0, 3, 0, 4, 0 };
    m = lsys_bspline_chaikin_reverse(out, g, 5, 2);
    assert(m == 3);
    near(0, out[0], 0, "odd");
    near(2.5, out[2], 1e-15, "odd");
    near(4, out[4], 0, "odd");
  }
}

static void test_resample (void) {
  const double l[] = { 0, 0, 3, 0, 3, 4 };
  double out[2 * 20], pt[2 * 2] = { 0, 0, 10, 0 };
  lsys_error e;
  size_t m, i;
  assert(lsys_bspline_resample_count(l, 3, 2, 1.0, &m, &e) == LSYS_OK && m == 8);
  lsys_bspline_resample(out, m, l, 3, 2);
  {
    const double want[] = { 0, 0, 1, 0, 2, 0, 3, 0, 3, 1, 3, 2, 3, 3, 3, 4 };
    for (i = 0; i < 16; i++) near(want[i], out[i], 1e-14, "resample by 1");
  }
  assert(lsys_bspline_resample_count(l, 3, 2, 2.0, &m, &e) == LSYS_OK && m == 5);
  lsys_bspline_resample(out, m, l, 3, 2);      /* 4 steps of 1.75 */
  {
    const double want[] = { 0, 0, 1.75, 0, 3, 0.5, 3, 2.25, 3, 4 };
    for (i = 0; i < 10; i++) near(want[i], out[i], 1e-14, "resample by 2");
  }
  /* stroke: 11 points on x, then 11 -> 6 (0 2.5 4.5 6.5 8.5 10) -> 3 (0 5.5 10) */
  assert(lsys_bspline_stroke_size(pt, 2, 2, 1.0, 2, &m, &e) == LSYS_OK && m == 11);
  assert(lsys_bspline_stroke(out, m, pt, 2, 2, 1.0, 3, 2, &i, &e) == LSYS_OK && i == 3);
  near(0, out[0], 0, "stroke");
  near(5.5, out[2], 1e-14, "stroke");
  near(10, out[4], 0, "stroke");
  assert(lsys_bspline_stroke(out, m, pt, 2, 2, 1.0, 1, 2, &i, &e) == LSYS_OK && i == 6);
  near(2.5, out[2], 1e-14, "one step");
  pt[2] = 1;                                   /* short: degree + 1 points */
  assert(lsys_bspline_stroke_size(pt, 2, 2, 1.0, 2, &m, &e) == LSYS_OK && m == 3);
  assert(lsys_bspline_stroke(out, m, pt, 2, 2, 1.0, 3, 2, &i, &e) == LSYS_OK && i == 3);
  near(0.5, out[2], 1e-15, "short stroke");
  assert(lsys_bspline_stroke_size(pt, 2, 2, 1.0, 3, &m, &e) == LSYS_OK && m == 4);
  assert(lsys_bspline_stroke(out, m, pt, 2, 2, 1.0, 3, 3, &i, &e) == LSYS_OK && i == 4);
  near(2.0 / 3, out[4], 1e-15, "short cubic stroke");
  pt[2] = 0;
  assert(lsys_bspline_stroke(out, 20, pt, 2, 2, 1.0, 3, 2, &i, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "the stroke has no length") == 0);
}

/* Ray hits into 'h' (at most 8); returns the count. */
static size_t ray (const lsys_bspline *c, double ox, double oy, double dx, double dy,
                   lsys_bspline_hit *h) {
  double o[2] = { ox, oy }, d[2] = { dx, dy };
  size_t n;
  lsys_error e;
  assert(lsys_bspline_ray(c, o, d, h, 8, &n, &e) == LSYS_OK);
  return n;
}

static void test_ray (void) {
  const double line[] = { 0, 0, 1, 0, 2, 0, 3, 0, 4, 0 }, arch[] = { -1, 0, 0, 2, 1, 0 };
  lsys_bspline c;
  lsys_bspline_hit h[8];
  lsys_bspline_init(&c);
  curve(&c, line, 5, 2, 3, 0);                 /* x = 1 + 2t, y = 0 */
  assert(ray(&c, 2, -1, 0, 1, h) == 1);
  near(0.5, h[0].t, 1e-14, "line t");
  near(1.0, h[0].s, 1e-14, "line s");
  near(2.0, h[0].x, 1e-14, "line x");
  assert(ray(&c, 2, -1, 0, 2, h) == 1);
  near(0.5, h[0].s, 1e-14, "s in units of |d|");
  assert(ray(&c, 5, -1, 0, 1, h) == 0);        /* beside the curve */
  assert(ray(&c, 2, -1, 0, -1, h) == 0);       /* pointing away */
  assert(ray(&c, 0, -1, 1, 1, h) == 1);        /* diagonal: (1, 0) at t = 0 */
  near(0.0, h[0].t, 1e-14, "end point");
  curve(&c, arch, 3, 2, 2, 1);                 /* y = 1 - x^2, t = (x + 1) / 2 */
  assert(ray(&c, -2, 0.75, 1, 0, h) == 2);
  near(0.25, h[0].t, 1e-14, "arch");
  near(1.5, h[0].s, 1e-14, "arch");
  near(0.75, h[1].t, 1e-14, "arch");
  near(2.5, h[1].s, 1e-14, "arch");
  near(0.5, h[1].x, 1e-14, "arch");
  near(0.75, h[1].y, 1e-14, "arch");
  assert(ray(&c, 2, 0.75, -1, 0, h) == 2);     /* sorted by s */
  near(0.75, h[0].t, 1e-14, "sorted by s");
  assert(ray(&c, 0, 0.75, 1, 0, h) == 1);
  near(0.5, h[0].s, 1e-14, "from inside");
  assert(ray(&c, 0.5, 0.75, -1, 0, h) == 2);   /* starting on the curve */
  near(0.0, h[0].s, 1e-12, "starts on the curve");
  near(0.75, h[0].t, 1e-12, "starts on the curve");
  near(1.0, h[1].s, 1e-12, "starts on the curve");
  assert(ray(&c, 0, -1, 0, 1, h) == 1);        /* through the apex */
  near(0.5, h[0].t, 1e-14, "apex");
  near(2.0, h[0].s, 1e-14, "apex");
  assert(ray(&c, -2, 1, 1, 0, h) <= 1);        /* tangent at the apex */
  assert(ray(&c, -2, 1.5, 1, 0, h) == 0);
  lsys_bspline_free(&c);
}

/* A zigzag of n points (y = +-1) as a uniform quadratic: every span joint is
** on y = 0 and the curve crosses there, n - 1 times. */
static void test_many (void) {
  size_t n = 10001, i, cnt;
  double *pt = (double *)malloc(2 * n * sizeof *pt), o[2] = { -5, 0 }, d[2] = { 1, 0 };
  lsys_bspline_hit *h = (lsys_bspline_hit *)malloc(n * sizeof *h);
  lsys_bspline c, l;
  lsys_error e;
  for (i = 0; i < n; i++) {
    pt[2 * i] = (double)i;
    pt[2 * i + 1] = i % 2 ? 1 : -1;
  }
  lsys_bspline_init(&c);
  lsys_bspline_init(&l);
  curve(&c, pt, n, 2, 2, 0);
  assert(lsys_bspline_ray(&c, o, d, h, n, &cnt, &e) == LSYS_OK);
  assert(cnt == n - 1);
  for (i = 0; i < cnt; i++) {
    near(0.5 + (double)i, h[i].x, 1e-9, "zigzag crossing");
    near(5.5 + (double)i, h[i].s, 1e-9, "zigzag s");
  }
  assert(lsys_bspline_ray(&c, o, d, h, 3, &cnt, &e) == LSYS_OK && cnt == n - 1);
  near(0.5, h[0].x, 1e-12, "first of a short buffer");
  o[1] = 0.25;                                 /* y = 2x(1-x) = 1/4 on the arches up */
  assert(lsys_bspline_ray(&c, o, d, h, n, &cnt, &e) == LSYS_OK);
  assert(cnt == n - 1);                        /* (n - 1) / 2 arches, 2 each */
  near(0.5 + (1 - sqrt(0.5)) / 2, h[0].x, 1e-12, "first arch");
  {   /* the line y = 0 across the zigzag as a second curve */
    const double ln[] = { -5, 0, 5000, 0, 10005, 0 };
    curve(&l, ln, 3, 2, 2, 1);
    assert(lsys_bspline_intersect(&c, &l, h, n, &cnt, &e) == LSYS_OK);
    assert(cnt == n - 1);
    for (i = 0; i < cnt; i++) near(0.5 + (double)i, h[i].x, 1e-9, "zigzag and line");
  }
  lsys_bspline_free(&c);
  lsys_bspline_free(&l);
  free(pt);
  free(h);
}

static void test_intersect (void) {
  const double a[] = { 0, 0, 1, 1, 2, 2 }, b[] = { 0, 2, 1, 1, 2, 0 };
  const double arch[] = { -1, 0, 0, 2, 1, 0 }, ln[] = { -2, 0.75, 0, 0.75, 2, 0.75 };
  lsys_bspline ca, cb;
  lsys_bspline_hit h[8];
  lsys_error e;
  size_t n;
  lsys_bspline_init(&ca);
  lsys_bspline_init(&cb);
  curve(&ca, a, 3, 2, 2, 1);
  curve(&cb, b, 3, 2, 2, 1);
  assert(lsys_bspline_intersect(&ca, &cb, h, 8, &n, &e) == LSYS_OK && n == 1);
  near(0.5, h[0].t, 1e-12, "lines t");
  near(0.5, h[0].s, 1e-12, "lines u");
  near(1.0, h[0].x, 1e-12, "lines x");
  near(1.0, h[0].y, 1e-12, "lines y");
  curve(&ca, arch, 3, 2, 2, 1);
  curve(&cb, ln, 3, 2, 2, 1);                  /* x = -2 + 4u */
  assert(lsys_bspline_intersect(&ca, &cb, h, 8, &n, &e) == LSYS_OK && n == 2);
  near(0.25, h[0].t, 1e-12, "arch and line");
  near(0.375, h[0].s, 1e-12, "arch and line");
  near(0.75, h[1].t, 1e-12, "arch and line");
  near(0.625, h[1].s, 1e-12, "arch and line");
  near(0.75, h[1].y, 1e-12, "arch and line");
  assert(lsys_bspline_intersect(&cb, &ca, h, 8, &n, &e) == LSYS_OK && n == 2);
  near(0.375, h[0].t, 1e-12, "swapped");
  {   /* y = 1 - x on [0, 1]: 1 - x^2 = 1 - x at the apex and at the arch's end */
    const double d[] = { 0, 1, 0.5, 0.5, 1, 0 };
    curve(&cb, d, 3, 2, 2, 1);
  }
  assert(lsys_bspline_intersect(&ca, &cb, h, 8, &n, &e) == LSYS_OK && n == 2);
  near(0.5, h[0].t, 1e-12, "apex");
  near(0.0, h[0].s, 1e-12, "apex");
  near(1.0, h[1].t, 1e-12, "both ends");
  near(1.0, h[1].s, 1e-12, "both ends");
  curve(&cb, b, 3, 2, 2, 1);                   /* y = 2 - x misses the arch */
  assert(lsys_bspline_intersect(&ca, &cb, h, 8, &n, &e) == LSYS_OK && n == 0);
  lsys_bspline_free(&ca);
  lsys_bspline_free(&cb);
}

static void test_closest (void) {
  const double arch[] = { -1, 0, 0, 2, 1, 0 };
  lsys_bspline c;
  double q[2] = { 0, 2 }, t, d, x = 0.1;
  int i;
  lsys_bspline_init(&c);
  curve(&c, arch, 3, 2, 2, 1);
  lsys_bspline_closest(&c, q, &t, &d);
  near(0.5, t, 1e-12, "closest apex");
  near(1.0, d, 1e-12, "closest apex");
  q[0] = 0.5;                                  /* 4x^3 + 6x - 1 = 0 */
  for (i = 0; i < 50; i++) x -= (4 * x * x * x + 6 * x - 1) / (12 * x * x + 6);
  lsys_bspline_closest(&c, q, &t, &d);
  near((x + 1) / 2, t, 1e-10, "closest interior");
  near(hypot(x - 0.5, 1 - x * x - 2), d, 1e-12, "closest interior");
  q[0] = 3, q[1] = -1;                         /* beyond the end (1, 0) */
  lsys_bspline_closest(&c, q, &t, &d);
  near(1.0, t, 0, "closest end");
  near(sqrt(5.0), d, 1e-12, "closest end");
  lsys_bspline_free(&c);
}

static void bad_set (const double *pt, size_t n, int dim, int degree, int code,
                     const char *msg) {
  lsys_bspline c;
  lsys_error e;
  lsys_bspline_init(&c);
  curve(&c, P5, 5, 2, 2, 0);
  assert(lsys_bspline_set(&c, pt, n, dim, degree, 0, &e) == code);
  if (strcmp(e.msg, msg) != 0) {
    fprintf(stderr, "expected: %s\n     got: %s\n", msg, e.msg);
    assert(0);
  }
  assert(c.n == 5 && c.degree == 2);           /* unchanged */
  lsys_bspline_free(&c);
}

static void test_bad (void) {
  double nan[] = { 0, 0, 1, 1, 2, NAN, 3, 3 }, big[] = { 0, 0, 1, 0, 2, 0, 3, 0 };
  double o[2] = { 0, 0 }, d[2] = { 0, 0 }, q[9] = { 0 };
  lsys_bspline c, c3;
  lsys_bspline_hit h[2];
  lsys_error e;
  size_t n;
  bad_set(P5, 3, 2, 3, LSYS_EARG, "a curve of degree 3 needs at least 4 control points, got 3");
  bad_set(P5, 2, 2, 2, LSYS_EARG, "a curve of degree 2 needs at least 3 control points, got 2");
  bad_set(P5, 5, 2, 4, LSYS_EARG, "degree must be 2 or 3, got 4");
  bad_set(P5, 3, 4, 2, LSYS_EARG, "dimension must be 2 or 3, got 4");
  bad_set(nan, 4, 2, 2, LSYS_EARG, "point 3: coordinate 2 is not finite");
  bad_set(big, (size_t)LSYS_BSPLINE_MAXPOINTS + 1, 2, 2, LSYS_ELIMIT,
          "too many control points (limit is 10000000)");
  big[2] = INFINITY;
  bad_set(big, 4, 2, 2, LSYS_EARG, "point 2: coordinate 1 is not finite");
  lsys_bspline_init(&c);
  lsys_bspline_init(&c3);
  curve(&c, P5, 5, 2, 2, 0);
  curve(&c3, q, 3, 3, 2, 0);
  assert(lsys_bspline_ray(&c, o, d, h, 2, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "ray direction must not be zero") == 0);
  d[0] = NAN;
  assert(lsys_bspline_ray(&c, o, d, h, 2, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "ray origin and direction must be finite") == 0);
  d[0] = 1;
  assert(lsys_bspline_ray(&c3, o, d, h, 2, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "ray intersection needs a 2D curve") == 0);
  assert(lsys_bspline_intersect(&c, &c3, h, 2, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "curve intersection needs 2D curves") == 0);
  assert(lsys_bspline_resample_count(P5, 1, 2, 1, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "a polyline needs at least 2 points, got 1") == 0);
  assert(lsys_bspline_resample_count(P5, 2, 2, 0, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "spacing must be a positive finite number") == 0);
  assert(lsys_bspline_resample_count(P5, 2, 2, NAN, &n, &e) == LSYS_EARG);
  assert(lsys_bspline_resample_count(P5, 2, 2, 1e-12, &n, &e) == LSYS_ELIMIT);
  assert(strcmp(e.msg, "resampling gives too many points (limit is 10000000)") == 0);
  assert(lsys_bspline_resample_count(nan, 4, 2, 1, &n, &e) == LSYS_EARG);
  assert(lsys_bspline_stroke(q, 3, P5, 2, 2, 1, -1, 2, &n, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "steps must be >= 0, got -1") == 0);
  lsys_bspline_free(&c);
  lsys_bspline_free(&c3);
}

/* Every allocation of lsys_bspline_set and of the intersections can fail
** cleanly; nothing leaks. */
static void test_nomem (void) {
  const double arch[] = { -1, 0, 0, 2, 1, 0 }, ln[] = { -2, 0.75, 0, 0.75, 2, 0.75 };
  lsys_bspline a, b;
  lsys_bspline_hit h[4];
  lsys_error e;
  size_t n;
  long k;
  for (k = 0; k < 3; k++) {
    lsys_bspline_init(&a);
    failat = nalloc + k;
    assert(lsys_bspline_set(&a, arch, 3, 2, 2, 1, &e) == LSYS_ENOMEM);
    assert(a.pt == NULL);
    failat = -1;
  }
  lsys_bspline_init(&b);
  curve(&a, arch, 3, 2, 2, 1);
  curve(&b, ln, 3, 2, 2, 1);
  failat = nalloc;
  assert(lsys_bspline_intersect(&a, &b, h, 4, &n, &e) == LSYS_ENOMEM);
  failat = nalloc;
  {
    double o[2] = { -2, 0.75 }, d[2] = { 1, 0 };
    assert(lsys_bspline_ray(&a, o, d, h, 4, &n, &e) == LSYS_ENOMEM);
  }
  failat = -1;
  lsys_bspline_free(&a);
  lsys_bspline_free(&b);
}

int main (void) {
  test_uniform();
  test_clamped();
  test_basis();
  test_length();
  test_chaikin();
  test_resample();
  test_ray();
  test_many();
  test_intersect();
  test_closest();
  test_bad();
  test_nomem();
  assert(nlive == 0);
  printf("test_bspline: ok\n");
  return 0;
}
