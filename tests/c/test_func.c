/*
** C unit tests for positional functions (csrc/core/func.c): values of a
** 4-point and a 6-point function against hand-computed clamped cubic
** B-spline points and an independent Cox-de Boor evaluation in this file;
** clamping, NaN and vertical pieces; the samples table as cpfg computes it;
** the parser on the old, fver 1 1 (multiplicity, markers, background,
** flip) and .fset forms and on malformed input (exact messages); the
** writer and its round trip; allocation failures.
**
** func.c is compiled into this test with counting allocators: every block
** is freed at the end, and each allocation can be made to fail.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "func.c"
#include "expr.c"

static void set (lsys_func *f, const double *pt, size_t n, int samples) {
  lsys_error e;
  int st = lsys_func_set(f, pt, n, "f", samples, &e);
  if (st != LSYS_OK) { fprintf(stderr, "set: %s\n", e.msg); assert(0); }
}

/* Cox-de Boor: basis function i of degree p at t for the clamped knots of
** n points (the right end belongs to the last non-empty interval). */
static double cdb (int i, int p, double t, int n) {
  double s = 0;
  if (p == 0) {
    double a = knot((size_t)i, (size_t)n), b = knot((size_t)i + 1, (size_t)n);
    return (a <= t && t < b) || (t == n - 3 && a < b && b == n - 3) ? 1 : 0;
  }
  {
    double ki = knot((size_t)i, (size_t)n), kp = knot((size_t)(i + p), (size_t)n);
    double k1 = knot((size_t)i + 1, (size_t)n), kq = knot((size_t)(i + p + 1), (size_t)n);
    if (kp != ki) s += (t - ki) / (kp - ki) * cdb(i, p - 1, t, n);
    if (kq != k1) s += (kq - t) / (kq - k1) * cdb(i + 1, p - 1, t, n);
  }
  return s;
}

static void curve (const double *pt, int n, double t, double *x, double *y) {
  int i;
  *x = *y = 0;
  for (i = 0; i < n; i++) {
    double b = cdb(i, 3, t, n);
    *x += b * pt[2 * i];
    *y += b * pt[2 * i + 1];
  }
}

/* 4 points with x equally spaced: x(t) = t, and f(x) = 3x(1 - x). */
static void test_four (void) {
  static const double pt[] = { 0, 0, 1.0 / 3, 1, 2.0 / 3, 1, 1, 0 };
  lsys_func f;
  double x;
  lsys_func_init(&f);
  set(&f, pt, 4, 0);
  assert(lsys_func_eval(&f, 0) == 0 && lsys_func_eval(&f, 1) == 0);
  assert(fabs(lsys_func_eval(&f, 0.5) - 0.75) < 1e-15);
  assert(fabs(lsys_func_eval(&f, 0.25) - 0.5625) < 1e-15);
  for (x = 0; x <= 1; x += 1.0 / 64)
    assert(fabs(lsys_func_eval(&f, x) - 3 * x * (1 - x)) < 1e-15);
  assert(lsys_func_eval(&f, -5) == 0 && lsys_func_eval(&f, 7) == 0);     /* clamped */
  assert(lsys_func_eval(&f, -HUGE_VAL) == 0 && lsys_func_eval(&f, HUGE_VAL) == 0);
  x = lsys_func_eval(&f, NAN);
  assert(x != x);
  lsys_func_free(&f);
}

/* 6 points: knots 0,0,0,0,1,2,3,3,3,3. At t = 1 the basis is (0, 1/4, 7/12,
** 1/6, 0, 0): x = 0.1/4 + 0.3*7/12 + 0.5/6 = 17/60, y = 2/4 - 7/12 + 3/6 =
** 5/12. The other values were worked out the same way, with fractions. */
static void test_six (void) {
  static const double pt[] = { 0, 0, 0.1, 2, 0.3, -1, 0.5, 3, 0.8, 1, 1, 0.5 };
  static const double known[][2] = {
    { 17.0 / 60, 5.0 / 12 }, { 13.0 / 24, 11.0 / 6 }, { 129.0 / 320, 33.0 / 32 },
    { 71.0 / 480, 95.0 / 96 }, { 707.0 / 960, 17.0 / 12 }, { 0, 0 }, { 1, 0.5 } };
  lsys_func f;
  size_t k;
  double t;
  lsys_func_init(&f);
  set(&f, pt, 6, 0);
  for (k = 0; k < sizeof known / sizeof known[0]; k++)
    assert(fabs(lsys_func_eval(&f, known[k][0]) - known[k][1]) < 1e-14);
  assert(lsys_func_eval(&f, 1) == 0.5);          /* the end point exactly */
  for (t = 0; t <= 3; t += 3.0 / 997) {          /* against Cox-de Boor, the curve inverted */
    double x, y;
    curve(pt, 6, t, &x, &y);
    assert(fabs(lsys_func_eval(&f, x) - y) < 1e-12);
  }
  lsys_func_free(&f);
}

/* Repeated x: a steep rise; four equal x: a vertical piece, where f takes
** the value at the lowest t. The result is monotone where y is. */
static void test_vertical (void) {
  static const double step[] = { 0, 0, 0.5, 0, 0.5, 0, 0.5, 0, 0.5, 1, 0.5, 1, 0.5, 1, 1, 1 };
  static const double ramp[] = { 0, 0, 0.2, 0.1, 0.4, 0.3, 0.4, 0.5, 0.7, 0.8, 1, 1 };
  lsys_func f;
  double x, prev = -1;
  lsys_func_init(&f);
  set(&f, step, 8, 0);
  assert(lsys_func_eval(&f, 0.25) == 0 && lsys_func_eval(&f, 0.75) == 1);
  assert(lsys_func_eval(&f, 0.5) == 0);          /* the lowest t of the vertical piece */
  assert(lsys_func_eval(&f, 0.5 + 1e-9) > 0.99);
  set(&f, ramp, 6, 0);
  for (x = 0; x <= 1; x += 1.0 / 4096) {
    double y = lsys_func_eval(&f, x);
    assert(y >= prev - 1e-15);
    prev = y;
  }
  lsys_func_free(&f);
}

/* samples > 2: linear interpolation of samples values, cpfg's formula. */
static void test_samples (void) {
  static const double pt[] = { 0, 0, 1.0 / 3, 1, 2.0 / 3, 1, 1, 0 };
  lsys_func f, g;
  double x;
  lsys_func_init(&f); lsys_func_init(&g);
  set(&f, pt, 4, 5);                    /* values at 0, .25, .5, .75, 1: 0 .5625 .75 .5625 0 */
  set(&g, pt, 4, 0);
  assert(f.samples == 5 && f.vals != NULL && g.vals == NULL);
  assert(fabs(lsys_func_eval(&f, 0.125) - 0.28125) < 1e-15);
  assert(fabs(lsys_func_eval(&f, 0.375) - (0.5625 + 0.75) / 2) < 1e-15);
  assert(lsys_func_eval(&f, 1) == f.vals[4] && lsys_func_eval(&f, 2) == f.vals[4]);
  for (x = 0; x <= 1; x += 0.25) assert(fabs(lsys_func_eval(&f, x) - lsys_func_eval(&g, x)) < 1e-15);
  set(&f, pt, 4, 2);                    /* 1 and 2 mean exact, as in cpfg */
  assert(f.vals == NULL && lsys_func_eval(&f, 0.125) == lsys_func_eval(&g, 0.125));
  lsys_func_free(&f); lsys_func_free(&g);
}

/* cpfg's approximation: y(0) of 3 x = 3t(1-t) by bisection stops where
** |x(d)| <= 0.001 and is not 0; cpfg's Lilac table value at 0 is 0.531232. */
static void test_cpfg (void) {
  static const double pt[] = { 0, 0, 1.0 / 3, 1, 2.0 / 3, 1, 1, 0 };
  static const double lilac[] = { 0, 0.531316, 0.32381, 0.502745, 0.647619, 0.450364,
                                  1, 0.417031 };
  lsys_func f;
  double y;
  lsys_func_init(&f);
  set(&f, pt, 4, 0);
  lsys_func_cpfg(&f);
  assert(f.cpfg == 1);
  y = lsys_func_eval(&f, 0.5);                 /* x(d) = 0.5 at d = 0.5: found at once */
  assert(fabs(y - 0.75) < 1e-15);
  y = lsys_func_eval(&f, 0);                   /* 10 halvings: d = 2^-10, y = 3d(1-d) */
  assert(y > 0 && fabs(y - 3 * 0x1p-10 * (1 - 0x1p-10)) < 1e-12);
  lsys_func_cpfg(&f);                          /* a second call changes nothing */
  assert(lsys_func_eval(&f, 0) == y);
  set(&f, lilac, 4, 10);
  assert(f.cpfg == 0 && f.vals[0] == 0.531316);
  lsys_func_cpfg(&f);
  assert(fabs(f.vals[0] - 0.531232) < 5e-7 && fabs(lsys_func_eval(&f, 0) - f.vals[0]) < 1e-15);
  lsys_func_free(&f);
}

static void seterr (const double *pt, size_t n, const char *name, int samples, const char *msg) {
  lsys_func f;
  lsys_error e;
  lsys_func_init(&f);
  assert(lsys_func_set(&f, pt, n, name, samples, &e) == LSYS_EARG);
  if (strcmp(e.msg, msg) != 0) { fprintf(stderr, "expected: %s\n     got: %s\n", msg, e.msg); assert(0); }
  assert(f.pt == NULL && f.n == 0);
}

static void test_set_errors (void) {
  static const double ok[] = { 0, 0, 0.2, 1, 0.6, 1, 1, 0 };
  static const double back[] = { 0, 0, 0.5, 1, 0.4, 1, 1, 0 };
  static const double end[] = { 0, 0, 0.2, 1, 0.6, 1, 0.9, 0 };
  static const double start[] = { 0.1, 0, 0.2, 1, 0.6, 1, 1, 0 };
  double bad[8];
  seterr(ok, 3, "f", 0, "a function needs at least 4 points, got 3");
  seterr(back, 4, "f", 0, "point 3: x is 0.40000000000000002, less than the x of point 2 "
         "(0.5)");
  seterr(end, 4, "f", 0, "point 4: x is 0.90000000000000002, not 1 (the last x must be 1)");
  seterr(start, 4, "f", 0, "point 1: x is 0.10000000000000001, not 0 (the first x must be 0)");
  memcpy(bad, ok, sizeof bad);
  bad[3] = NAN;
  seterr(bad, 4, "f", 0, "point 2: y is not a finite number");
  bad[3] = 2e9;
  seterr(bad, 4, "f", 0, "point 2: y is out of range (limit is 1e9)");
  seterr(ok, 4, "", 0, "a function's name must be 1 to 127 bytes without control characters");
  seterr(ok, 4, "a\nb", 0, "a function's name must be 1 to 127 bytes without control characters");
  seterr(ok, 4, "f", -1, "samples must be from 0 to 1000000, got -1");
  {   /* within the tolerance: accepted */
    double near[8];
    lsys_func f;
    memcpy(near, ok, sizeof near);
    near[0] = -1e-7; near[6] = 1 + 1e-7;
    lsys_func_init(&f);
    set(&f, near, 4, 0);
    assert(fabs(lsys_func_eval(&f, 1)) < 1e-5 && fabs(lsys_func_eval(&f, 0)) < 1e-5);
    lsys_func_free(&f);
  }
}

/* Parses 'text' (not NUL-terminated: copied into a block of its length). */
static lsys_func *parse (const char *text, const char *name, int samples, size_t *n) {
  size_t len = strlen(text);
  char *copy = (char *)malloc(len + 1);
  lsys_func *fs;
  lsys_error e;
  int st;
  memcpy(copy, text, len);
  st = lsys_func_parse(&fs, n, copy, len, name, samples, &e);
  free(copy);
  if (st != LSYS_OK) { fprintf(stderr, "parse: %s\n", e.msg); assert(0); }
  return fs;
}

static void freeall (lsys_func *fs, size_t n) {
  size_t k;
  for (k = 0; k < n; k++) lsys_func_free(&fs[k]);
  LSYS_FREE(fs);
}

static void test_parse (void) {
  size_t n;
  lsys_func *fs;
  /* the old form: named after the file, the view's samples */
  fs = parse("range: 0.0 1.0\npoints: 4\n0 0\n0.333333 1\n0.666667 1\n1 0\n",
             "models/leaf-length.func", 10, &n);
  assert(n == 1 && fs[0].n == 4 && strcmp(fs[0].name, "leaf-length") == 0);
  assert(fs[0].samples == 10 && fs[0].pt[2] == 0.333333 && fs[0].pt[7] == 0);
  freeall(fs, n);
  /* fver 1 1 as funcedit writes it, CRLF; its own samples win over the view's */
  fs = parse("fver 1 1\r\nname: flower\r\nsamples: 10\r\nflip: off\r\npoints: 4\r\n"
             "0.000000 0.000000 1\r\n0.535950 -0.001705 1\r\n0.535950 1.001755 1\r\n"
             "1.000000 1.003176 1\r\n", "flower.func", 100, &n);
  assert(n == 1 && fs[0].n == 4 && strcmp(fs[0].name, "flower") == 0 && fs[0].samples == 10);
  assert(fs[0].pt[4] == 0.535950 && fs[0].pt[7] == 1.003176);
  freeall(fs, n);
  /* multiplicity, markers, background lines, no flip line, a name with a blank */
  fs = parse("fver 1 1\nname: leaf width\nsamples: 0\nbackground: img.png\n"
             "backgroundXY: 0.5 0.5\nmarkers: 2\nm1 0.2 0.3\nm2 0.7 0.1\npoints: 3\n"
             "0 0 1\n0.5 2 3\n1 1\n", "w.func", 0, &n);
  assert(n == 1 && fs[0].n == 5 && strcmp(fs[0].name, "leaf width") == 0);
  assert(fs[0].pt[2] == 0.5 && fs[0].pt[5] == 2 && fs[0].pt[6] == 0.5 && fs[0].pt[8] == 1);
  assert(lsys_func_eval(&fs[0], 0.5) == 2);   /* a triple point: the curve passes through it */
  freeall(fs, n);
  /* a function set */
  fs = parse("funcgalleryver 1 1\nitems: 2\nfver 1 1\nname: A\nsamples: 100\nflip: off\n"
             "points: 4\n0 1\n0.3 1\n0.6 1\n1 1\n\nfver 1 1\nname: B\nsamples: 0\nflip: on\n"
             "points: 4\n0 0\n0.25 0.25\n0.75 0.75\n1 1\n", "set.fset", 0, &n);
  assert(n == 2 && strcmp(fs[0].name, "A") == 0 && strcmp(fs[1].name, "B") == 0);
  assert(fs[0].samples == 100 && lsys_func_eval(&fs[0], 0.3) == 1);
  assert(fabs(lsys_func_eval(&fs[1], 0.4) - 0.4) < 1e-15);
  freeall(fs, n);
}

static void parserr (const char *text, const char *msg) {
  lsys_func *fs = (lsys_func *)&fs;
  size_t n = 7;
  lsys_error e;
  assert(lsys_func_parse(&fs, &n, text, strlen(text), "x.func", 0, &e) == LSYS_ESYNTAX);
  if (strcmp(e.msg, msg) != 0) {
    fprintf(stderr, "for %s\nexpected: %s\n     got: %s\n", text, msg, e.msg);
    assert(0);
  }
  assert(fs == NULL && n == 0);
}

static void test_parse_errors (void) {
  parserr("", "x.func:1: empty file (expected 'fver 1 1')");
  parserr("hello\n", "x.func:1: expected 'fver 1 1' or 'range: 0.0 1.0', got 'hello'");
  parserr("fver 2 0\n", "x.func:1: unsupported function version 'fver 2 0' (only 'fver 1 1')");
  parserr("fver 1 1\nsamples: 3\n", "x.func:2: expected 'name: NAME'");
  parserr("fver 1 1\nname: a\nsamples: x\n",
          "x.func:3: 'samples' must be a whole number from 0 to 1000000");
  parserr("fver 1 1\nname: a\nsamples: 0\nflip: maybe\n",
          "x.func:4: 'flip' must be 'on' or 'off', got 'maybe'");
  parserr("fver 1 1\nname: a\nsamples: 0\nmarkers: 2\nm1 0 0\n",
          "x.func:6: the file ends after 1 of 2 markers");
  parserr("fver 1 1\nname: a\nsamples: 0\npoints: 4\n0 0\n0.5 1\n",
          "x.func:7: the file ends after 2 of 4 points");
  parserr("range: 0 1\npoints: 4\n0 0\n0.5 1 2\n", "x.func:4: expected 'x y', got '0.5 1 2'");
  parserr("fver 1 1\nname: a\nsamples: 0\npoints: 2\n0 0\n0.5 1 0\n",
          "x.func:6: the multiplicity must be a whole number from 1 to 65536, got '0'");
  parserr("range: 0 1\npoints: 4\n0 0\n0.5 zz\n", "x.func:4: bad number 'zz'");
  parserr("range: 0 1\npoints: 4\n0 0\n0.5 inf\n", "x.func:4: y is not a finite number");
  parserr("range: 0 1\npoints: 4\n0 0\n0.5 1\n0.4 1\n1 1\n",
          "x.func:5: x is 0.40000000000000002, less than the x before it (0.5)");
  parserr("range: 0 1\npoints: 3\n0 0\n0.5 1\n1 1\n",
          "x.func:1: function 'x': a function needs at least 4 points, got 3");
  parserr("fver 1 1\nname: a\nsamples: 0\npoints: 4\n0 0\n0.5 1\n0.6 1\n0.9 1\n",
          "x.func:1: function 'a': point 4: x is 0.90000000000000002, not 1 (the last x "
          "must be 1)");
  parserr("range: 0 1\npoints: 4\n0 0\n0.5 1\n0.6 1\n1 1\n7\n",
          "x.func:7: unexpected '7' after the points");
  parserr("funcgalleryver 1 1\nitems: 2\nfver 1 1\nname: a\nsamples: 0\npoints: 4\n0 0\n"
          "0.5 1\n0.6 1\n1 1\n", "x.func:11: the file ends after 1 of 2 functions");
  parserr("funcgalleryver 1 1\nitems: 2\nrange: 0 1\n",
          "x.func:3: expected 'fver 1 1' (function 1 of 2), got 'range: 0 1'");
  parserr("funcgalleryver 2 1\n", "x.func:1: unsupported function set version "
          "'funcgalleryv...' (only 'funcgalleryver 1 1')");
  parserr("funcgalleryver 1 1\nitems: 0\n", "x.func:2: a function set needs at least 1 item");
}

static void test_format (void) {
  static const double pt[] = { 0, 0, 0.1, 2, 0.1, 2, 0.1, 2, 0.3, -1.5, 1, 1.0 / 3 };
  static const char want[] = "fver 1 1\nname: f\nsamples: 7\nflip: off\npoints: 4\n0 0 1\n"
                             "0.1 2 3\n0.3 -1.5 1\n1 0.3333333333333333 1\n";
  lsys_func f, *fs;
  char buf[512], buf2[512];
  size_t n, len;
  lsys_error e;
  lsys_func_init(&f);
  set(&f, pt, 6, 7);
  len = lsys_func_format(&f, buf, sizeof buf);
  assert(len == strlen(want) && strcmp(buf, want) == 0);
  assert(lsys_func_format(&f, NULL, 0) == len);   /* the length only */
  assert(lsys_func_format(&f, buf2, 10) == len && strlen(buf2) == 9);   /* cut, terminated */
  assert(lsys_func_parse(&fs, &n, buf, len, "f.func", 0, &e) == LSYS_OK && n == 1);
  assert(fs[0].n == 6 && memcmp(fs[0].pt, pt, sizeof pt) == 0 && fs[0].samples == 7);
  assert(lsys_func_format(&fs[0], buf2, sizeof buf2) == len && strcmp(buf, buf2) == 0);
  freeall(fs, n);
  lsys_func_free(&f);
}

/* Every allocation of a parse can fail: LSYS_ENOMEM and nothing leaks. */
static void test_nomem (void) {
  static const char text[] = "funcgalleryver 1 1\nitems: 2\nfver 1 1\nname: A\nsamples: 9\n"
    "points: 4\n0 1\n0.3 1\n0.6 1\n1 1\nfver 1 1\nname: B\nsamples: 0\npoints: 4\n0 0\n"
    "0.25 0.25\n0.75 0.75\n1 1\n";
  long k;
  for (k = 0; ; k++) {
    lsys_func *fs;
    size_t n;
    lsys_error e;
    int st;
    nalloc = 0; failat = k;
    st = lsys_func_parse(&fs, &n, text, sizeof text - 1, "x", 0, &e);
    failat = -1;
    if (st == LSYS_OK) { freeall(fs, n); assert(nlive == 0); break; }
    assert(st == LSYS_ENOMEM && fs == NULL && nlive == 0);
  }
  assert(k > 3);
}

/* LSYS_OP_FN on the expression machine: the index is checked against the
** table's size, and the value is lsys_func_eval's. */
static void test_machine (void) {
  static const double pt[] = { 0, 0, 1.0 / 3, 1, 2.0 / 3, 1, 1, 0 };
  const lsys_ins prog[] = { {LSYS_OP_ARG, 0, 0}, {LSYS_OP_FN, 1, 0}, {LSYS_OP_K, 0, 2},
                            {LSYS_OP_MUL, 0, 0}, {LSYS_OP_RET, 0, 0} };
  lsys_ins bad[5];
  lsys_func f[2];
  const lsys_func *t[2];
  double x = 0.25, out[1];
  lsys_rng rng;
  lsys_rng_seed(&rng, 1);
  lsys_func_init(&f[0]); lsys_func_init(&f[1]);
  set(&f[0], pt, 4, 0);
  set(&f[1], pt, 4, 5);
  t[0] = &f[0]; t[1] = &f[1];
  assert(lsys_expr_check(prog, 5, 1, 2) == 1);
  assert(lsys_expr_check(prog, 5, 1, 1) == -1);   /* index 1 of a table of 1 */
  memcpy(bad, prog, sizeof bad);
  bad[1].a = -1;
  assert(lsys_expr_check(bad, 5, 1, 2) == -1);
  bad[0].op = LSYS_OP_FN; bad[0].a = 0;           /* nothing on the stack */
  assert(lsys_expr_check(bad, 5, 1, 2) == -1);
  assert(lsys_expr_run(prog, 5, &x, out, &rng, t) == 1);
  assert(out[0] == 2 * lsys_func_eval(&f[1], 0.25) && fabs(out[0] - 1.125) < 1e-15);
  lsys_func_free(&f[0]); lsys_func_free(&f[1]);
}

int main (void) {
  test_cpfg();
  test_four();
  test_six();
  test_vertical();
  test_samples();
  test_set_errors();
  test_parse();
  test_parse_errors();
  test_format();
  test_nomem();
  test_machine();
  assert(nlive == 0);
  printf("test_func: ok\n");
  return 0;
}
