/*
** C unit tests for contours (csrc/core/contour.c): the parser on the three
** files of Appendix B.1, on tolerated layouts and on malformed input (exact
** messages); vlab's versioned files ("cver 1 1" .. "cver 1 3": multiplicities,
** open and closed, skipped lines, errors); lsys_contour_set; sampling checked against a direct
** re-implementation of the definition, equal arc length, the rotation of
** V_0 onto +x, outward and left normals, open end points; the circle.
**
** contour.c is compiled into this test with counting allocators: every
** block is freed at the end, and each allocation can be made to fail.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "contour.c"

#define PI 3.14159265358979323846

static const char fig12a[] =
  "12 2 closed\n"
  "0.166482 -1.123751\n0.416204 -1.040511\n0.582686 -0.332963\n1.082131 -0.041620\n"
  "1.082131 0.499445\n0.499445 0.541065\n0.332963 0.915649\n-0.374584 1.040511\n"
  "-0.707547 0.624306\n-1.123751 0.166482\n-0.874029 -0.749168\n-0.416204 -0.665927\n";

static const char fig13a[] =
  "12 3 closed\n"
  "0.166482 -1.123751 1.0\n0.416204 -1.040511 0.0\n0.582686 -0.332963 0.0\n"
  "1.082131 -0.041620 0.0\n1.082131 0.499445 0.0\n0.499445 0.541065 0.0\n"
  "0.332963 0.915649 0.0\n-0.374584 1.040511 0.0\n-0.707547 0.624306 0.0\n"
  "-1.123751 0.166482 0.0\n-0.874029 -0.749168 0.0\n-0.416204 -0.665927 0.0\n";

static const char fig16a[] =
  "15 2 open\n"
  "-0.914286 -0.400000\n-0.914286 -0.400000\n-0.914286 -0.400000\n-0.871429 -0.342857\n"
  "-0.742857 -0.171429\n-0.457143 -0.085714\n-0.285714 0.142857\n0.000000 0.271429\n"
  "0.228571 0.114286\n0.514286 0.142857\n0.657143 -0.028571\n0.892857 -0.114286\n"
  "0.971429 -0.142857\n0.971429 -0.142857\n0.971429 -0.142857\n";

/* Parses a NUL-terminated text (its NUL is not passed); asserts success. */
static void parse (lsys_contour *c, const char *text) {
  lsys_error e;
  int st = lsys_contour_parse(c, text, strlen(text), "t.con", &e);
  if (st != LSYS_OK) fprintf(stderr, "unexpected error: %s\n", e.msg);
  assert(st == LSYS_OK);
}

/* Parses 'text' and expects failure with exactly 'msg'; 'c' is left empty. */
static void bad (const char *text, const char *msg) {
  lsys_contour c;
  lsys_error e;
  lsys_contour_init(&c);
  parse(&c, "3 2 closed\n0 0\n1 0\n0 1\n");      /* emptied by the failure */
  assert(lsys_contour_parse(&c, text, strlen(text), "t.con", &e) == LSYS_ESYNTAX);
  if (strcmp(e.msg, msg) != 0) {
    fprintf(stderr, "for %s\nexpected: %s\n     got: %s\n", text, msg, e.msg);
    assert(0);
  }
  assert(e.code == LSYS_ESYNTAX);
  assert(c.pt == NULL && c.n == 0);
  lsys_contour_free(&c);
}

static void test_files (void) {
  lsys_contour c;
  lsys_contour_init(&c);
  parse(&c, fig12a);
  assert(c.n == 12 && c.dim == 2 && c.closed == 1);
  assert(c.pt[0] == 0.166482 && c.pt[1] == -1.123751 && c.pt[2] == 0);
  assert(c.pt[33] == -0.416204 && c.pt[34] == -0.665927 && c.pt[35] == 0);
  parse(&c, fig13a);                                /* replaces the points */
  assert(c.n == 12 && c.dim == 3 && c.closed == 1);
  assert(c.pt[2] == 1.0 && c.pt[5] == 0.0 && c.pt[3] == 0.416204);
  parse(&c, fig16a);
  assert(c.n == 15 && c.dim == 2 && c.closed == 0);
  assert(c.pt[0] == -0.914286 && c.pt[42] == 0.971429 && c.pt[43] == -0.142857);
  assert(nlive == 1);
  lsys_contour_free(&c);
  lsys_contour_free(&c);                            /* idempotent */
  assert(nlive == 0 && c.pt == NULL && c.n == 0);
}

/* CRLF, tabs, blank lines and comments; the text is not NUL-terminated. */
static void test_layout (void) {
  static const char text[] =
    "# a leaf\r\n\r\n  4\t3   open  # header\r\n"
    "1 2 3\r\n\n# between points\n\t-1e-3 +.5 7\n0x10 2E2 -0\n1 1 1 # last";
  lsys_contour c;
  lsys_error e;
  char *exact = (char *)malloc(sizeof text - 1);    /* no byte after the text */
  memcpy(exact, text, sizeof text - 1);
  lsys_contour_init(&c);
  assert(lsys_contour_parse(&c, exact, sizeof text - 1, "t.con", &e) == LSYS_OK);
  assert(c.n == 4 && c.dim == 3 && !c.closed);
  assert(c.pt[3] == -1e-3 && c.pt[4] == 0.5 && c.pt[5] == 7);
  assert(c.pt[6] == 16 && c.pt[7] == 200 && c.pt[8] == 0);
  assert(c.pt[9] == 1 && c.pt[10] == 1 && c.pt[11] == 1);
  /* only 'len' bytes count: the last "1" is not read as "15" */
  assert(lsys_contour_parse(&c, "3 2 closed\n0 0\n1 0\n0 15", 22, "t.con", &e) == LSYS_OK);
  assert(c.pt[7] == 1);
  /* and a cut in the middle of the points is a truncated file */
  assert(lsys_contour_parse(&c, exact, 61, "t.con", &e) == LSYS_ESYNTAX);
  assert(strcmp(e.msg, "t.con:7: file ends after 1 of 4 points") == 0);
  assert(lsys_contour_parse(&c, NULL, 0, "t.con", &e) == LSYS_ESYNTAX);
  assert(strcmp(e.msg, "t.con:1: expected \"N dim open|closed\", got an empty file") == 0);
  free(exact);
  lsys_contour_free(&c);
}

/* "name:line: message" (common.h): the line is the error's position, and a
** name longer than the message leaves only the first 255 bytes of it. */
static void test_where (void) {
  char name[300];
  lsys_contour c;
  lsys_error e;
  memset(name, 'n', sizeof name - 1);
  name[sizeof name - 1] = '\0';
  lsys_contour_init(&c);
  assert(lsys_contour_parse(&c, "\n\n3 2 closed\n0 0\n1 x\n", 20, "t.con", &e) == LSYS_ESYNTAX);
  assert(e.pos == 5 && strcmp(e.msg, "t.con:5: bad number 'x'") == 0);
  assert(lsys_contour_parse(&c, "2 2 open", 8, name, &e) == LSYS_ESYNTAX);
  assert(strlen(e.msg) == sizeof e.msg - 1 && strncmp(e.msg, name, sizeof e.msg - 1) == 0);
  lsys_contour_free(&c);
}

static void test_errors (void) {
  char big[200];
  bad("", "t.con:1: expected \"N dim open|closed\", got an empty file");
  bad("\n\n# only a comment\n", "t.con:4: expected \"N dim open|closed\", got an empty file");
  bad("12 2\n", "t.con:1: expected \"N dim open|closed\"");
  bad("\n12 2 closed x\n", "t.con:2: expected \"N dim open|closed\"");
  bad("twelve 2 closed\n", "t.con:1: bad point count 'twelve'");
  bad("-3 2 closed\n", "t.con:1: bad point count '-3'");
  bad("3 4 closed\n", "t.con:1: dimension must be 2 or 3, got '4'");
  bad("3 2.0 closed\n", "t.con:1: dimension must be 2 or 3, got '2.0'");
  bad("3 2 Closed\n", "t.con:1: expected 'open' or 'closed', got 'Closed'");
  bad("2 2 closed\n0 0\n1 1\n", "t.con:1: a closed contour needs at least 3 points, got 2");
  bad("3 2 open\n0 0\n1 1\n2 2\n", "t.con:1: an open contour needs at least 4 points, got 3");
  bad("65537 2 closed\n", "t.con:1: too many points (limit is 65536)");
  bad("99999999999999999999999 2 closed\n", "t.con:1: too many points (limit is 65536)");
  bad("3 2 closed\n0 0\n1\n0 1\n", "t.con:3: expected 2 numbers, got 1");
  bad("3 2 closed\n0 0 0\n1 0\n0 1\n", "t.con:2: expected 2 numbers, got 3");
  bad("3 3 closed\n0 0 0\n1 0 0\n0 1 0 0 0 0 0\n", "t.con:4: expected 3 numbers, got 7");
  bad("3 2 closed\n0 0\nnan 0\n0 1\n", "t.con:3: 'nan' is not a finite number");
  bad("3 2 closed\n0 0\n1 -inf\n0 1\n", "t.con:3: '-inf' is not a finite number");
  bad("3 2 closed\n0 0\n1 1e999\n0 1\n", "t.con:3: '1e999' is not a finite number");
  bad("3 2 closed\n0 0\n1 -2e9\n0 1\n", "t.con:3: -2e9 is out of range (limit is 1e9)");
  bad("3 2 closed\n0 0\n1,5 0\n0 1\n", "t.con:3: bad number '1,5'");
  bad("3 2 closed\n0 0\n1 0x\n0 1\n", "t.con:3: bad number '0x'");
  bad("3 2 closed\n0 0\n1 \x01\xff\n0 1\n", "t.con:3: bad number '?\?'");
  bad("3 2 closed\n\n\n0 0\n1 0\n", "t.con:6: file ends after 2 of 3 points");
  bad("3 2 closed\n0 0\n1 0", "t.con:3: file ends after 2 of 3 points");
  bad("3 2 closed\n0 0\n1 0\n0 1\n\nfoo bar\n", "t.con:6: unexpected 'foo' after the 3 points");
  bad("3 2 closed\n0 0\n1 0\n0 1\n0 1\n", "t.con:5: unexpected '0' after the 3 points");
  memset(big, '7', sizeof big);
  memcpy(big, "3 2 closed\n0 ", 13);
  big[sizeof big - 1] = '\0';
  bad(big, "t.con:2: bad number '777777777777...'");
  {   /* a NUL inside the text is just a bad byte */
    lsys_contour c;
    lsys_error e;
    lsys_contour_init(&c);
    assert(lsys_contour_parse(&c, "3 2 closed\n0 \0\n", 15, "t.con", &e) == LSYS_ESYNTAX);
    assert(strcmp(e.msg, "t.con:2: bad number '?'") == 0);
    assert(c.pt == NULL);
  }
  assert(nlive == 0);
}

static void test_set (void) {
  static const double sq[] = { 0, 0, 5, 1, 0, 5, 1, 1, 5, 0, 1, 5 };
  double nan3[12];
  lsys_contour c;
  lsys_error e;
  lsys_contour_init(&c);
  assert(lsys_contour_set(&c, sq, 4, 1, 2, &e) == LSYS_OK);
  assert(c.n == 4 && c.dim == 2 && c.closed == 1);
  assert(c.pt[2] == 0 && c.pt[11] == 0 && c.pt[3] == 1);      /* z dropped in 2D */
  assert(lsys_contour_set(&c, sq, 4, 0, 3, &e) == LSYS_OK);
  assert(c.dim == 3 && !c.closed && c.pt[2] == 5);
  assert(lsys_contour_set(&c, c.pt, 4, 1, 3, &e) == LSYS_OK);  /* from its own points */
  assert(c.closed && c.pt[11] == 5 && nlive == 1);
  assert(lsys_contour_set(&c, sq, 4, 1, 4, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "dimension must be 2 or 3, got 4") == 0);
  assert(lsys_contour_set(&c, sq, 3, 0, 2, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "an open contour needs at least 4 points, got 3") == 0);
  assert(lsys_contour_set(&c, sq, 70000, 1, 2, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "too many points (limit is 65536)") == 0);
  memcpy(nan3, sq, sizeof nan3);
  nan3[7] = NAN;
  assert(lsys_contour_set(&c, nan3, 4, 1, 3, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "point 3: coordinate 2 is not finite") == 0);
  nan3[7] = 1;
  nan3[11] = -1e10;
  assert(lsys_contour_set(&c, nan3, 4, 1, 3, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "point 4: coordinate 3 is out of range (limit is 1e9)") == 0);
  assert(lsys_contour_set(&c, nan3, 4, 1, 2, &e) == LSYS_OK);  /* z is not looked at */
  assert(c.dim == 2 && c.pt[11] == 0);
  lsys_contour_free(&c);
  assert(nlive == 0);
}

/* ---------------------------------------------------------------------- */

/* The definition, directly: the 10n curve points in an array, cumulative
** lengths, each V_i by a search from the start, then the rotation. */
static void reference (const lsys_contour *c, int p, double *out) {
  size_t m = 10 * c->n, nk = c->closed ? m + 1 : m, k, j;
  double *s = (double *)malloc(3 * nk * sizeof *s), *len = (double *)malloc(nk * sizeof *len);
  double ang;
  int i, q;
  for (k = 0; k < nk; k++) {
    double u = c->closed ? (double)(k % m) / 10 : (double)k * (double)(c->n - 3) / (double)(m - 1);
    size_t seg = (size_t)u;
    double t, b[4];
    if (!c->closed && seg == c->n - 3) seg--;
    t = u - (double)seg;
    b[0] = (1 - t) * (1 - t) * (1 - t) / 6;
    b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    b[3] = t * t * t / 6;
    for (q = 0; q < 3; q++) {
      s[3 * k + q] = 0;
      for (j = 0; j < 4; j++) s[3 * k + q] += b[j] * c->pt[3 * ((seg + j) % c->n) + q];
    }
    len[k] = k == 0 ? 0 : len[k - 1] + sqrt(pow(s[3 * k] - s[3 * k - 3], 2) +
                                            pow(s[3 * k + 1] - s[3 * k - 2], 2) +
                                            pow(s[3 * k + 2] - s[3 * k - 1], 2));
  }
  for (i = 0; i <= p; i++) {
    double target = len[nk - 1] * i / p, f;
    for (j = 0; j + 2 < nk && len[j + 1] < target; j++) {}
    f = len[j + 1] > len[j] ? (target - len[j]) / (len[j + 1] - len[j]) : 0;
    for (q = 0; q < 3; q++) out[3 * i + q] = s[3 * j + q] + f * (s[3 * j + 3 + q] - s[3 * j + q]);
  }
  ang = atan2(out[1], out[0]);
  for (i = 0; i <= p; i++) {
    double x = out[3 * i], y = out[3 * i + 1];
    out[3 * i] = cos(ang) * x + sin(ang) * y;
    out[3 * i + 1] = cos(ang) * y - sin(ang) * x;
  }
  free(s);
  free(len);
}

static double dist2 (const double *a, const double *b) {
  return hypot(a[0] - b[0], a[1] - b[1]);
}

/* Vertices match the reference; V_0 on +x; V_p = V_0 when closed; unit
** normals in the xy plane. */
static void check (const lsys_contour *c, int p, double *v, double *n) {
  double *ref = (double *)calloc(3 * ((size_t)p + 1), sizeof *ref);
  int i;
  assert(lsys_contour_sample(c, p, v, n) == LSYS_OK);
  reference(c, p, ref);
  for (i = 0; i <= 3 * p + 2; i++) {
    if (fabs(v[i] - ref[i]) > 1e-9) {
      fprintf(stderr, "n %zu, p %d: vertex %d coordinate %d: %.12g, reference %.12g\n", c->n, p,
              i / 3, i % 3, v[i],
              ref[i]);
      assert(0);
    }
  }
  assert(v[0] > 0 && v[1] == 0);
  if (c->closed) assert(memcmp(v, v + 3 * p, 3 * sizeof *v) == 0);
  for (i = 0; i <= p; i++) {
    assert(fabs(hypot(n[3 * i], n[3 * i + 1]) - 1) < 1e-12);
    assert(n[3 * i + 2] == 0);
  }
  free(ref);
}

static void test_sample_files (void) {
  double v[3 * 33], n[3 * 33], w[3 * 33], r0, r1, a0, a1;
  lsys_contour c;
  lsys_contour_init(&c);
  parse(&c, fig12a);
  check(&c, 32, v, n);
  /* V_0 = F_0(0) = (P_0 + 4 P_1 + P_2) / 6, turned onto +x */
  r0 = hypot((0.166482 + 4 * 0.416204 + 0.582686) / 6, (-1.123751 - 4 * 1.040511 - 0.332963) / 6);
  assert(fabs(v[0] - r0) < 1e-12);
  assert(lsys_contour_sample(&c, 32, w, NULL) == LSYS_OK);      /* normals are optional */
  assert(memcmp(v, w, sizeof v) == 0);
  check(&c, 3, v, n);
  parse(&c, fig13a);
  check(&c, 32, v, n);
  assert(fabs(v[2] - 1.0 / 6) < 1e-15);                         /* z is kept, not rotated */
  parse(&c, fig16a);
  check(&c, 32, v, n);
  /* the tripled end points are the ends of the curve, turned by the same angle */
  r0 = hypot(-0.914286, -0.4);
  r1 = hypot(0.971429, -0.142857);
  assert(fabs(v[0] - r0) < 1e-12 && v[1] == 0);
  assert(fabs(hypot(v[96], v[97]) - r1) < 1e-12);
  a0 = atan2(-0.4, -0.914286);
  a1 = atan2(-0.142857, 0.971429);
  assert(fabs(remainder(atan2(v[97], v[96]) - (a1 - a0), 2 * PI)) < 1e-12);
  assert(lsys_contour_sample(&c, 2, v, n) == LSYS_EARG);
  lsys_contour_free(&c);
  assert(lsys_contour_sample(&c, 8, v, n) == LSYS_EARG);
}

/* Control points on the unit circle at uneven angles: the parameter runs
** at uneven speed, yet the vertices are equally spaced along the curve. */
static void test_arclength (void) {
  enum { N = 48, P = 24 };
  double pt[3 * N], v[3 * (P + 1)], n[3 * (P + 1)], chord = 0, lo = 1e9, hi = 0;
  lsys_contour c;
  lsys_error e;
  int i;
  for (i = 0; i < N; i++) {
    double a = 2 * PI * pow((double)i / N, 2);           /* bunched near angle 0 */
    pt[3 * i] = cos(a);
    pt[3 * i + 1] = sin(a);
    pt[3 * i + 2] = 0;
  }
  lsys_contour_init(&c);
  assert(lsys_contour_set(&c, pt, N, 1, 2, &e) == LSYS_OK);
  check(&c, P, v, n);
  for (i = 0; i < P; i++) {
    double d = dist2(v + 3 * i, v + 3 * i + 3);
    chord += d / P;
    if (d < lo) lo = d;
    if (d > hi) hi = d;
  }
  assert(hi < chord * 1.01 && lo > chord * 0.99);
  for (i = 0; i <= P; i++) {
    double r = hypot(v[3 * i], v[3 * i + 1]);
    assert(r < 1 && r > 0.98);                             /* the spline shrinks a little */
    assert((v[3 * i] * n[3 * i] + v[3 * i + 1] * n[3 * i + 1]) / r > 0.999);   /* outward */
  }
  /* the uneven speed is real: vertices at equal parameter steps would not be */
  {
    double s0[3], s1[3], s2[3];
    curve C = { &c, 10 * N, 10 * N };
    point(&C, 0, s0);
    point(&C, 10, s1);
    point(&C, 10 * (N - 1), s2);
    assert(dist2(s0, s1) < 0.2 * dist2(s2, s0));
  }
  lsys_contour_free(&c);
}

/* A square in both windings: the normals point away from the centre. */
static void test_normals (void) {
  static const double ccw[] = { 1, -1, 0, 1, 1, 0, -1, 1, 0, -1, -1, 0 };
  static const double cw[] = { 1, -1, 0, -1, -1, 0, -1, 1, 0, 1, 1, 0 };
  static const double line[] = { -1, 0, 0, -1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0 };
  const double *sq[2] = { ccw, cw };
  double v[3 * 21], n[3 * 21];
  lsys_contour c;
  lsys_error e;
  int k, i;
  lsys_contour_init(&c);
  for (k = 0; k < 2; k++) {
    assert(lsys_contour_set(&c, sq[k], 4, 1, 2, &e) == LSYS_OK);
    check(&c, 16, v, n);
    for (i = 0; i <= 16; i++) {
      double r = hypot(v[3 * i], v[3 * i + 1]);
      assert((v[3 * i] * n[3 * i] + v[3 * i + 1] * n[3 * i + 1]) / r > 0.5);
    }
    /* V_0 = (P_0 + 4 P_1 + P_2) / 6 = (2/3, 2/3) up to the signs, a rounded
    ** corner: turned onto +x, with the normal along the diagonal, now +x */
    assert(fabs(v[0] - 2 * sqrt(2) / 3) < 1e-12);
    assert(fabs(n[0] - 1) < 1e-12 && fabs(n[1]) < 1e-12);
  }
  /* open: left of the direction of travel; a straight line from -x to +x,
  ** turned half a turn so that V_0 lies on +x: the normals point along -y */
  assert(lsys_contour_set(&c, line, 7, 0, 2, &e) == LSYS_OK);
  check(&c, 8, v, n);
  for (i = 0; i <= 8; i++) {
    assert(fabs(v[3 * i] - (1 - i / 4.0)) < 1e-12 && fabs(v[3 * i + 1]) < 1e-12);
    assert(fabs(n[3 * i]) < 1e-12 && fabs(n[3 * i + 1] + 1) < 1e-12);
  }
  /* fig16a: every normal is left of the chord to the next vertex */
  parse(&c, fig16a);
  check(&c, 20, v, n);
  for (i = 0; i < 20; i++) {
    double dx = v[3 * i + 3] - v[3 * i], dy = v[3 * i + 4] - v[3 * i + 1];
    assert((dx * n[3 * i + 1] - dy * n[3 * i]) / hypot(dx, dy) > 0.9);
  }
  lsys_contour_free(&c);
}

/* Degenerate contours still give unit normals and finite vertices. */
static void test_degenerate (void) {
  static const double point3[] = { 2, 0, 0, 2, 0, 0, 2, 0, 0 };
  static const double origin[] = { 0, 0, 1, 0, 0, 2, 0, 0, 3 };
  double v[3 * 9], n[3 * 9];
  lsys_contour c;
  lsys_error e;
  int i;
  lsys_contour_init(&c);
  assert(lsys_contour_set(&c, point3, 3, 1, 3, &e) == LSYS_OK);
  assert(lsys_contour_sample(&c, 8, v, n) == LSYS_OK);
  for (i = 0; i <= 8; i++) {                       /* all at (2,0,0), normals +x */
    assert(fabs(v[3 * i] - 2) < 1e-15 && v[3 * i + 1] == 0 && v[3 * i + 2] == 0);
    assert(n[3 * i] == 1 && n[3 * i + 1] == 0 && n[3 * i + 2] == 0);
  }
  assert(lsys_contour_set(&c, origin, 3, 1, 3, &e) == LSYS_OK);  /* along z only */
  assert(lsys_contour_sample(&c, 8, v, n) == LSYS_OK);
  for (i = 0; i <= 8; i++) {
    assert(v[3 * i] == 0 && v[3 * i + 1] == 0 && v[3 * i + 2] >= 1 && v[3 * i + 2] <= 3);
    assert(n[3 * i] == 1 && n[3 * i + 1] == 0 && n[3 * i + 2] == 0);
  }
  assert(fabs(v[2] - 2) < 1e-15 && v[26] == v[2]); /* V_0 = (P0 + 4 P1 + P2) / 6 */
  lsys_contour_free(&c);
}

static void test_circle (void) {
  double v[3 * 9], n[3 * 9];
  int i;
  lsys_contour_circle(8, v, n);
  assert(v[0] == 1 && v[1] == 0 && v[2] == 0);
  assert(memcmp(v, v + 24, 3 * sizeof *v) == 0);
  assert(memcmp(v, n, sizeof v) == 0);
  for (i = 0; i <= 8; i++) {
    assert(fabs(v[3 * i] - cos(PI * i / 4)) < 1e-15);
    assert(fabs(v[3 * i + 1] - sin(PI * i / 4)) < 1e-15);
  }
  lsys_contour_circle(3, v, NULL);
  assert(fabs(v[3] + 0.5) < 1e-15 && fabs(v[4] - sqrt(3) / 2) < 1e-15 && v[9] == 1);
}

/* ---------------------------------------------------------------------- */
/* vlab's versioned files ("cver 1 1" .. "cver 1 3"). */

static const char blade13[] =
  "cver 1 3\n"
  "name: test blade\n"
  "points: 4 8\n"
  "type: or\n"
  "samples: 8\n"
  "-2 0 0 3\n"
  "-1 1.5 0 1\n"
  "1 1.25 0.5 1\n"
  "2 0 0 3\n";

/* Asserts that point i of 'c' is (x, y, z). */
static void at (const lsys_contour *c, size_t i, double x, double y, double z) {
  assert(i < c->n);
  assert(c->pt[3 * i] == x && c->pt[3 * i + 1] == y && c->pt[3 * i + 2] == z);
}

static void test_cver (void) {
  double v[3 * 17], n[3 * 17];
  lsys_contour c;
  size_t i;
  lsys_contour_init(&c);
  parse(&c, blade13);                     /* each line's point repeated m times */
  assert(c.n == 8 && c.dim == 3 && c.closed == 0);
  for (i = 0; i < 3; i++) at(&c, i, -2, 0, 0);
  at(&c, 3, -1, 1.5, 0);
  at(&c, 4, 1, 1.25, 0.5);
  for (i = 5; i < 8; i++) at(&c, i, 2, 0, 0);
  check(&c, 16, v, n);                    /* sampled like any open contour */
  assert(fabs(v[0] - 2) < 1e-12 && fabs(hypot(v[48], v[49]) - 2) < 1e-12);
  parse(&c, "cver 1 1\nname: sq\npoints: 4 4\ntype: closed\n"
            "1 -1 0 1\n1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n");
  assert(c.n == 4 && c.dim == 3 && c.closed == 1);
  at(&c, 0, 1, -1, 0);
  at(&c, 3, -1, -1, 0);
  parse(&c, "cver 1 1\nname: x\npoints: 2 4\ntype: open\n0 0 0 2\n1 0 0 2\n");
  assert(c.n == 4 && c.closed == 0);
  at(&c, 1, 0, 0, 0);
  at(&c, 2, 1, 0, 0);
  /* 1.2: o|c then r|e; end-point interpolation is drawn as regular */
  parse(&c, "cver 1 2\nname: t\npoints: 3 3\ntype: cr\n0 0 0 1\n1 0 0 1\n0 1 0 1\n");
  assert(c.n == 3 && c.closed == 1);
  parse(&c, "cver 1 2\nname: t\npoints: 3 3\ntype: ce\n0 0 0 1\n1 0 0 1\n0 1 0 1\n");
  assert(c.n == 3 && c.closed == 1);
  parse(&c, "cver 1 2\nname: t\npoints: 2 4\ntype: oe\n0 0 0 2\n1 0 0 2\n");
  assert(c.n == 4 && c.closed == 0);
  /* 1.3: the editor's background image and markers are skipped; CRLF,
  ** comments, blank lines, an empty name and a last line without '\n' */
  parse(&c, "cver 1 3\r\nname:\r\n\r\npoints: 3 5 # lines, points\r\ntype: cr\r\nsamples: 12\r\n"
            "background: leaf scan.png\r\nbackgroundXY: 0.5 -2\r\nmarkers: 2\r\nm1 0 0\r\n"
            "m2 1 1\r\n0 0 0 1\r\n# the tip\r\n1 0 0 3\r\n0 1 0 1");
  assert(c.n == 5 && c.closed == 1);
  at(&c, 0, 0, 0, 0);
  at(&c, 1, 1, 0, 0);
  at(&c, 3, 1, 0, 0);
  at(&c, 4, 0, 1, 0);
  parse(&c, "cver 1 3\nname: n\npoints: 3 3\ntype: cr\nsamples: 8\nmarkers: 0\n"
            "0 0 0 1\n1 0 0 1\n0 1 0 1\n");
  assert(c.n == 3);
  parse(&c, "cver 01 003\nname: n\npoints: 3 3\ntype: cr\nsamples: 8\n"
            "0 0 0 1\n1 0 0 1\n0 1 0 1\n");
  assert(c.n == 3 && nlive == 1);
  lsys_contour_free(&c);
  assert(nlive == 0);
}

/* A 1.3 header for 'pts', then 'rest'. */
static const char *h13 (char *buf, size_t size, const char *pts, const char *type,
                        const char *rest) {
  snprintf(buf, size, "cver 1 3\nname: t\npoints: %s\ntype: %s\nsamples: 8\n%s", pts, type,
           rest);
  return buf;
}

static void test_cver_errors (void) {
  static const char four[] = "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n";
  char b[512];
  bad("cver 2 0\n",
      "t.con:1: unknown contour format 'cver 2 0' (lsys reads cver 1 1, 1 2 and 1 3)");
  bad("cver 1 4\n",
      "t.con:1: unknown contour format 'cver 1 4' (lsys reads cver 1 1, 1 2 and 1 3)");
  bad("cver 1 0\n",
      "t.con:1: unknown contour format 'cver 1 0' (lsys reads cver 1 1, 1 2 and 1 3)");
  bad("cver 1\n", "t.con:1: expected \"cver MAJOR MINOR\"");
  bad("cver 1 3 x\n", "t.con:1: expected \"cver MAJOR MINOR\"");
  bad("cver 1 three\n", "t.con:1: expected \"cver MAJOR MINOR\"");
  bad("cver -1 3\n", "t.con:1: expected \"cver MAJOR MINOR\"");
  bad("cver 1 3\n", "t.con:2: expected \"name: NAME\", got the end of the file");
  bad("cver 1 3\npoints: 4 4\n", "t.con:2: expected \"name: NAME\"");
  bad("cver 1 3\nname: t\n\n",
      "t.con:4: expected \"points: LINES TOTAL\", got the end of the file");
  bad("cver 1 3\nname: t\npoints: 4\n", "t.con:3: expected \"points: LINES TOTAL\"");
  bad("cver 1 3\nname: t\npoints:4 4\n", "t.con:3: expected \"points: LINES TOTAL\"");
  bad(h13(b, sizeof b, "x 4", "cr", four), "t.con:3: bad point line count 'x'");
  bad(h13(b, sizeof b, "4 -4", "cr", four), "t.con:3: bad point count '-4'");
  bad(h13(b, sizeof b, "4 4.0", "cr", four), "t.con:3: bad point count '4.0'");
  bad("cver 1 3\nname: t\npoints: 4 4\ntype:\n", "t.con:4: expected \"type: o|c r|e\"");
  bad("cver 1 1\nname: t\npoints: 4 4\n",
      "t.con:4: expected \"type: open|closed\", got the end of the file");
  bad(h13(b, sizeof b, "4 4", "open", four),
      "t.con:4: type must be 'or', 'oe', 'cr' or 'ce', got 'open'");
  bad(h13(b, sizeof b, "4 4", "orx", four),
      "t.con:4: type must be 'or', 'oe', 'cr' or 'ce', got 'orx'");
  bad(h13(b, sizeof b, "4 4", "cx", four),
      "t.con:4: type must be 'or', 'oe', 'cr' or 'ce', got 'cx'");
  bad("cver 1 1\nname: t\npoints: 4 4\ntype: or\n",
      "t.con:4: expected 'open' or 'closed', got 'or'");
  bad("cver 1 1\nname: t\npoints: 4 4\ntype: Closed\n",
      "t.con:4: expected 'open' or 'closed', got 'Closed'");
  bad("cver 1 3\nname: t\npoints: 4 4\ntype: cr\n0 0 0 1\n", "t.con:5: expected \"samples: K\"");
  bad("cver 1 3\nname: t\npoints: 4 4\ntype: cr\nsamples: eight\n",
      "t.con:5: bad sample count 'eight'");
  bad(h13(b, sizeof b, "2 2", "cr", four),
      "t.con:3: a closed contour needs at least 3 points, got 2");
  bad(h13(b, sizeof b, "3 3", "or", four),
      "t.con:3: an open contour needs at least 4 points, got 3");
  bad(h13(b, sizeof b, "1 65537", "cr", four), "t.con:3: too many points (limit is 65536)");
  bad(h13(b, sizeof b, "1 99999999999999999999999", "cr", four),
      "t.con:3: too many points (limit is 65536)");
  bad(h13(b, sizeof b, "0 4", "cr", four), "t.con:3: 0 point lines cannot give 4 points");
  bad(h13(b, sizeof b, "5 4", "cr", four), "t.con:3: 5 point lines cannot give 4 points");
  bad(h13(b, sizeof b, "4 4", "cr", "background: a.png\n0 0 0 1\n"),
      "t.con:7: expected \"backgroundXY: X Y\"");
  bad(h13(b, sizeof b, "4 4", "cr", "markers: two\n"), "t.con:6: expected \"markers: K\"");
  bad(h13(b, sizeof b, "4 4", "cr", "markers: 3\nm1 0 0\n"),
      "t.con:8: file ends after 1 of 3 markers");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 0 0\n"),
      "t.con:7: multiplicity must be a whole number >= 1, got '0'");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 0 1.5\n"),
      "t.con:7: multiplicity must be a whole number >= 1, got '1.5'");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 -1\n"),
      "t.con:6: multiplicity must be a whole number >= 1, got '-1'");
  bad(h13(b, sizeof b, "4 5", "cr", "0 0 0 1\n1 0 0 3\n1 1 0 1\n0 1 0 1\n"),
      "t.con:9: the multiplicities add up to more than the 5 points of line 3");
  bad(h13(b, sizeof b, "2 5", "cr", "0 0 0 1\n1 0 0 99999999999999999999\n"),
      "t.con:7: the multiplicities add up to more than the 5 points of line 3");
  bad(h13(b, sizeof b, "4 6", "cr", four), "t.con:3: the multiplicities add up to 4 points, not 6");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 1\n"),
      "t.con:7: expected 4 numbers (x y z multiplicity), got 3");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 0 1 1\n"),
      "t.con:7: expected 4 numbers (x y z multiplicity), got 5");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 x 0 1\n"), "t.con:7: bad number 'x'");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 nan 1\n"),
      "t.con:7: 'nan' is not a finite number");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 2e9 1\n"),
      "t.con:7: 2e9 is out of range (limit is 1e9)");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 0 1\n"),
      "t.con:8: file ends after 2 of 4 point lines");
  bad(h13(b, sizeof b, "4 4", "cr", "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n7\n"),
      "t.con:10: unexpected '7' after the 4 point lines");
  assert(nlive == 0);
}

/* Each allocation fails in turn: LSYS_ENOMEM, 'c' emptied by the parser,
** unchanged by lsys_contour_set; nothing leaked. */
static void test_nomem (void) {
  static const double sq[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0 };
  lsys_contour c;
  lsys_error e;
  lsys_contour_init(&c);
  nalloc = 0;
  failat = 0;
  assert(lsys_contour_parse(&c, fig12a, strlen(fig12a), "t.con", &e) == LSYS_ENOMEM);
  assert(strcmp(e.msg, "not enough memory") == 0 && c.pt == NULL && c.n == 0);
  failat = 1;
  assert(lsys_contour_set(&c, sq, 3, 1, 2, &e) == LSYS_ENOMEM);
  failat = -1;
  assert(nalloc == 2 && nlive == 0);               /* one allocation per call */
  assert(lsys_contour_set(&c, sq, 3, 1, 2, &e) == LSYS_OK);
  failat = nalloc;
  assert(lsys_contour_set(&c, sq, 3, 0 + 1, 3, &e) == LSYS_ENOMEM);
  assert(c.n == 3 && c.dim == 2 && nlive == 1);    /* unchanged */
  failat = nalloc;
  assert(lsys_contour_parse(&c, fig12a, strlen(fig12a), "t.con", &e) == LSYS_ENOMEM);
  assert(c.pt == NULL && c.n == 0 && nlive == 0);
  assert(lsys_contour_set(&c, sq, 3, 1, 2, &e) == LSYS_OK);
  failat = nalloc;                                 /* a versioned file: one allocation too */
  assert(lsys_contour_parse(&c, blade13, strlen(blade13), "t.con", &e) == LSYS_ENOMEM);
  assert(strcmp(e.msg, "not enough memory") == 0 && c.pt == NULL && c.n == 0 && nlive == 0);
  failat = -1;
  lsys_contour_free(&c);
  assert(nlive == 0);
}

int main (void) {
  test_files();
  test_layout();
  test_errors();
  test_where();
  test_cver();
  test_cver_errors();
  test_set();
  test_sample_files();
  test_arclength();
  test_normals();
  test_degenerate();
  test_circle();
  test_nomem();
  assert(nlive == 0);
  printf("test_contour: ok\n");
  return 0;
}
