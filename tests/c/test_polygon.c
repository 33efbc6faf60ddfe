/*
** C unit tests for polygon triangulation: convex, concave and star-shaped
** polygons, both orientations, repeated and collinear points, warped and
** tilted polygons, self-intersecting input, and large polygons.
**
** Every result is checked the same way (check): the triangles face the
** normal, their areas add up to the polygon's, and each triangle's centroid
** lies inside the polygon. Big polygons of hostile shapes (combs, zigzag
** corridors, spirals, saws, stars of random radii) are checked
** in linear time instead (tiling): every side of the polygon is the side of
** one triangle and every other side of a triangle is the side of another,
** the other way round. The ways of cutting (the reflex list or the tree, the
** walk or the heap) are compared with each other (test_modes).
**
** polygon.c is compiled into this test with counting allocators, so that
** test_nomem can make each allocation fail (the library's polygon.o is then
** not linked).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static long nalloc, failat = -1;    /* allocation number 'failat' fails */

static void *trealloc (void *p, size_t n) {
  return nalloc++ == failat ? NULL : realloc(p, n);
}

/* the sizes at which polygon.c builds its tree and cuts from its heap, and the
** work it allows, as variables: test_modes compares the ways of cutting */
static size_t kdmin = 64, qmin = 1024;
static double maxwork = 256;
#define KDMIN kdmin
#define QMIN qmin
#define MAXWORK maxwork

/* polygon.c compiled in with counting allocators (see test_nomem) */
#define LSYS_MALLOC(n)     malloc(n)
#define LSYS_REALLOC(p, n) trealloc((p), (n))
#define LSYS_FREE(p)       free(p)
#include "common.c"
#include "polygon.c"

#define PI 3.14159265358979323846

static lsys_polywork work;

static void cross (const double *a, const double *b, const double *c, double r[3]) {
  double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  r[0] = u[1] * v[2] - u[2] * v[1];
  r[1] = u[2] * v[0] - u[0] * v[2];
  r[2] = u[0] * v[1] - u[1] * v[0];
}

static double dot (const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Coordinates of 'p' in the plane through 'o' with unit normal 'nz'. */
static void planar (const double *nz, const double *o, const double *p, double q[2]) {
  double ex[3], ey[3], d[3] = { p[0] - o[0], p[1] - o[1], p[2] - o[2] }, l;
  if (fabs(nz[0]) < 0.9) { ex[0] = 0; ex[1] = -nz[2]; ex[2] = nz[1]; }   /* x axis cross n */
  else { ex[0] = nz[2]; ex[1] = 0; ex[2] = -nz[0]; }
  l = sqrt(dot(ex, ex));
  ex[0] /= l; ex[1] /= l; ex[2] /= l;
  ey[0] = nz[1] * ex[2] - nz[2] * ex[1];
  ey[1] = nz[2] * ex[0] - nz[0] * ex[2];
  ey[2] = nz[0] * ex[1] - nz[1] * ex[0];
  q[0] = dot(d, ex);
  q[1] = dot(d, ey);
}

/* Even-odd point in polygon test in the plane of 'nz'. */
static int inside (const double *pts, size_t n, const double *nz, const double *p) {
  double q[2], a[2], b[2];
  size_t i;
  int in = 0;
  planar(nz, pts, p, q);
  for (i = 0; i < n; i++) {
    planar(nz, pts, pts + 3 * i, a);
    planar(nz, pts, pts + 3 * ((i + 1) % n), b);
    if ((a[1] > q[1]) != (b[1] > q[1]) &&
        q[0] < a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]))
      in = !in;
  }
  return in;
}

/* Area of the polygon (half the length of its Newell normal). */
static double polyarea (const double *pts, size_t n) {
  double N[3] = {0, 0, 0};
  size_t i;
  for (i = 0; i < n; i++) {
    const double *a = pts + 3 * i, *b = pts + 3 * ((i + 1) % n);
    N[0] += (a[1] - b[1]) * (a[2] + b[2]);
    N[1] += (a[2] - b[2]) * (a[0] + b[0]);
    N[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return 0.5 * sqrt(dot(N, N));
}

/* Triangulates and checks; returns the triangle count. 'simple' asks for
** the area check (1) and the centroids-inside check too (2, quadratic);
** -1 skips even the facing check (wildly non-planar input);
** 'expect' is the triangle count (-1: any). */
static long check (const double *pts, size_t n, int simple, long expect, double normal[3]) {
  const uint32_t *t;
  double area = 0, tol;
  long nt = lsys_polygon_triangulate(&work, pts, n, normal, &t), i;
  assert(nt >= 0);
  assert(nt <= (long)n - 2 || nt == 0);
  assert(fabs(sqrt(dot(normal, normal)) - 1) < 1e-12);
  if (expect >= 0 && nt != expect) {
    fprintf(stderr, "expected %ld triangles, got %ld (n = %zu)\n", expect, nt, n);
    assert(0);
  }
  for (i = 0; i < nt; i++) {
    const double *a = pts + 3 * t[3 * i], *b = pts + 3 * t[3 * i + 1], *c = pts + 3 * t[3 * i + 2];
    double r[3], g[3];
    int k;
    assert(t[3 * i] < n && t[3 * i + 1] < n && t[3 * i + 2] < n);
    cross(a, b, c, r);
    assert(simple < 0 || dot(r, normal) > 0);  /* faces the normal */
    area += 0.5 * sqrt(dot(r, r));
    for (k = 0; k < 3; k++) g[k] = (a[k] + b[k] + c[k]) / 3;
    if (simple > 1 && !inside(pts, n, normal, g)) {
      fprintf(stderr, "triangle %ld (%u %u %u) is outside the polygon\n", i,
              t[3 * i], t[3 * i + 1], t[3 * i + 2]);
      assert(0);
    }
  }
  if (simple > 0) {
    double pa = polyarea(pts, n);
    tol = 1e-9 * (pa > 1 ? pa : 1);
    if (fabs(area - pa) > tol) {
      fprintf(stderr, "area %.17g, polygon %.17g\n", area, pa);
      assert(0);
    }
  }
  return nt;
}

/* 2D points (x, y) to 3D with z = 0. */
static double *flat (const double *xy, size_t n) {
  double *p = malloc(3 * n * sizeof *p);
  size_t i;
  assert(p != NULL);
  for (i = 0; i < n; i++) { p[3 * i] = xy[2 * i]; p[3 * i + 1] = xy[2 * i + 1]; p[3 * i + 2] = 0; }
  return p;
}

static void reverse (double *p, size_t n) {
  size_t i, k;
  for (i = 0; i < n / 2; i++)
    for (k = 0; k < 3; k++) {
      double t = p[3 * i + k];
      p[3 * i + k] = p[3 * (n - 1 - i) + k];
      p[3 * (n - 1 - i) + k] = t;
    }
}

static void test_basic (void) {
  static const double square[] = { 0, 0, 1, 0, 1, 1, 0, 1 };
  static const double ell[] = { 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2 };
  double nrm[3], *p, star[20];
  int i;
  p = flat(square, 4);
  assert(check(p, 4, 2, 2, nrm) == 2);
  assert(nrm[2] == 1);
  free(p);
  p = flat(ell, 6);                            /* concave L, area 3 */
  assert(check(p, 6, 2, 4, nrm) == 4);
  assert(fabs(polyarea(p, 6) - 3) < 1e-15);
  reverse(p, 6);                               /* clockwise: the normal turns over */
  assert(check(p, 6, 2, 4, nrm) == 4);
  assert(nrm[2] == -1);
  free(p);
  for (i = 0; i < 10; i++) {                   /* five-pointed star */
    double a = i * PI / 5, rad = i % 2 ? 0.4 : 1;
    star[2 * i] = rad * cos(a);
    star[2 * i + 1] = rad * sin(a);
  }
  p = flat(star, 10);
  check(p, 10, 2, 8, nrm);
  reverse(p, 10);
  check(p, 10, 2, 8, nrm);
  assert(nrm[2] < 0);
  free(p);
}

static void test_degenerate (void) {
  /* square with points on its edges, repeated points and a closing point */
  static const double sq[] = { 0, 0, 0.5, 0, 1, 0, 1, 0, 1, 0.25, 1, 1, 0.5, 1, 0, 1,
                               0, 1, 0, 0.5, 0, 0 };
  static const double line[] = { 0, 0, 1, 0, 2, 0, 3, 0 };
  static const double spike[] = { 0, 0, 1, 0, 1, 1, 1, 3, 1, 1, 0, 1 };   /* hair on an edge */
  double nrm[3], *p;
  const uint32_t *t;
  p = flat(sq, 11);
  assert(check(p, 11, 2, -1, nrm) == 2);
  free(p);
  p = flat(line, 4);                           /* no area: nothing, normal +z */
  assert(lsys_polygon_triangulate(&work, p, 4, nrm, &t) == 0);
  assert(nrm[0] == 0 && nrm[1] == 0 && nrm[2] == 1);
  assert(lsys_polygon_triangulate(&work, p, 2, nrm, &t) == 0);
  assert(lsys_polygon_triangulate(&work, p, 0, nrm, &t) == 0);
  p[4] = NAN;
  assert(lsys_polygon_triangulate(&work, p, 4, nrm, &t) == 0);
  p[4] = INFINITY;
  assert(lsys_polygon_triangulate(&work, p, 4, nrm, &t) == 0);
  free(p);
  p = flat(spike, 6);
  assert(check(p, 6, 0, -1, nrm) == 2);
  free(p);
  {                                             /* all points the same */
    double same[12] = { 1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3 };
    assert(lsys_polygon_triangulate(&work, same, 4, nrm, &t) == 0);
  }
  {                                             /* a triangle */
    double tri[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
    assert(check(tri, 3, 2, 1, nrm) == 1);
  }
}

/* Rotation about a unit axis, then translation. */
static void transform (double *p, size_t n, const double ax[3], double ang, const double off[3]) {
  double c = cos(ang), s = sin(ang), C = 1 - c;
  double R[3][3] = {
    { c + ax[0] * ax[0] * C, ax[0] * ax[1] * C - ax[2] * s, ax[0] * ax[2] * C + ax[1] * s },
    { ax[1] * ax[0] * C + ax[2] * s, c + ax[1] * ax[1] * C, ax[1] * ax[2] * C - ax[0] * s },
    { ax[2] * ax[0] * C - ax[1] * s, ax[2] * ax[1] * C + ax[0] * s, c + ax[2] * ax[2] * C } };
  size_t i;
  int k;
  for (i = 0; i < n; i++) {
    double q[3] = { p[3 * i], p[3 * i + 1], p[3 * i + 2] };
    for (k = 0; k < 3; k++) p[3 * i + k] = R[k][0] * q[0] + R[k][1] * q[1] + R[k][2] * q[2] + off[k];
  }
}

static void test_3d (void) {
  static const double ell[] = { 0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2 };
  double warped[12] = { 0, 0, 0.02, 1, 0, -0.02, 1, 1, 0.02, 0, 1, -0.02 };
  double nrm[3], *p, l = 1 / sqrt(3.0);
  const double axis[3] = { l, -l, l }, off[3] = { 1000, -500, 250 };
  const uint32_t *t;
  long nt, i;
  assert(check(warped, 4, 0, 2, nrm) == 2);
  assert(nrm[2] > 0.99);
  nt = lsys_polygon_triangulate(&work, warped, 4, nrm, &t);
  for (i = 0; i < nt; i++) {                    /* each triangle faces the normal */
    double r[3];
    cross(warped + 3 * t[3 * i], warped + 3 * t[3 * i + 1], warped + 3 * t[3 * i + 2], r);
    assert(dot(r, nrm) > 0.9 * sqrt(dot(r, r)));
  }
  p = flat(ell, 6);                            /* the L in a tilted plane, far out */
  transform(p, 6, axis, 1.1, off);
  assert(check(p, 6, 2, 4, nrm) == 4);
  {
    double z[3] = { 0, 0, 1 }, zero[3] = { 0, 0, 0 };
    transform(z, 1, axis, 1.1, zero);
    assert(fabs(dot(z, nrm) - 1) < 1e-9);
  }
  reverse(p, 6);
  assert(check(p, 6, 2, 4, nrm) == 4);
  free(p);
}

/* Self-intersecting and self-touching polygons: no hang, triangles face
** the normal. */
static void test_bad (void) {
  static const double bowtie[] = { 0, 0, 2, 1, 2, 0, 0, 1.5 };
  static const double touch[] = { 0, 0, 1, 0, 1, 1, 2, 1, 2, 2, 1, 2, 1, 1, 0, 1 };
  static const double hole[] = { 0, 0, 4, 0, 4, 4, 0, 4, 0, 0, 1, 1, 1, 3, 3, 3, 3, 1, 1, 1 };
  double nrm[3], *p, pent[15];
  int i;
  p = flat(bowtie, 4);
  check(p, 4, 0, -1, nrm);
  free(p);
  for (i = 0; i < 5; i++) {                    /* pentagram drawn in one stroke */
    double a = i * 4 * PI / 5;
    pent[3 * i] = cos(a); pent[3 * i + 1] = sin(a); pent[3 * i + 2] = 0;
  }
  assert(check(pent, 5, 0, -1, nrm) >= 1);
  p = flat(touch, 8);                          /* two squares meeting at a corner */
  assert(check(p, 8, 2, -1, nrm) >= 4);
  free(p);
  p = flat(hole, 10);                          /* a square hole joined by a bridge */
  assert(check(p, 10, 2, -1, nrm) == 8);
  assert(fabs(polyarea(p, 10) - 12) < 1e-12);
  free(p);
  p = malloc(3 * 40 * sizeof *p);
  assert(p != NULL);
  for (i = 0; i < 3000; i++) {                 /* random points: any triangles, no hang */
    size_t n = 4 + (size_t)(rand() % 30), j;
    for (j = 0; j < 3 * n; j++) p[j] = rand() / (RAND_MAX + 1.0);
    if (i % 3 != 0)                            /* in a plane, or warped (i % 3 == 0) */
      for (j = 0; j < n; j++) p[3 * j + 2] = i % 3 == 1 ? 0 : 0.3 * p[3 * j] - 0.5 * p[3 * j + 1];
    check(p, n, i % 3 == 0 ? -1 : 0, -1, nrm);
  }
  free(p);
}

static double urand (void) {
  return rand() / (RAND_MAX + 1.0);
}

/* Random star-shaped polygons (simple by construction) and combs. */
static void test_random (void) {
  double nrm[3], *p = malloc(3 * 200 * sizeof *p);
  int trial;
  srand(7);
  assert(p != NULL);
  for (trial = 0; trial < 500; trial++) {
    size_t n = 5 + (size_t)(urand() * 150), i;
    for (i = 0; i < n; i++) {                  /* gaps below 180 degrees: simple */
      double r = 0.1 + urand(), a = 2 * PI * ((double)i + 0.8 * urand()) / (double)n;
      p[3 * i] = r * cos(a);
      p[3 * i + 1] = r * sin(a);
      p[3 * i + 2] = 0;
    }
    if (trial % 2) reverse(p, n);
    if (trial % 3 == 0) {
      double ax[3] = { 0.6, 0, 0.8 }, off[3] = { 3, 2, 1 };
      transform(p, n, ax, 0.3 * trial, off);
    }
    check(p, n, 2, -1, nrm);
  }
  free(p);
}

/* A comb with 'teeth' teeth: many reflex vertices in a row. */
static size_t comb (double *p, size_t teeth) {
  size_t i, n = 0;
  for (i = 0; i < teeth; i++) {
    double x = (double)i;
    p[3 * n] = x; p[3 * n + 1] = 0; p[3 * n + 2] = 0; n++;
    p[3 * n] = x + 0.5; p[3 * n + 1] = 0; p[3 * n + 2] = 0; n++;
    p[3 * n] = x + 0.5; p[3 * n + 1] = -10; p[3 * n + 2] = 0; n++;
    p[3 * n] = x + 1; p[3 * n + 1] = -10; p[3 * n + 2] = 0; n++;
  }
  p[3 * n] = (double)teeth; p[3 * n + 1] = 1; p[3 * n + 2] = 0; n++;
  p[3 * n] = 0; p[3 * n + 1] = 1; p[3 * n + 2] = 0; n++;
  return n;
}

static void test_large (void) {
  size_t n = 10000, i;
  double *p = malloc(3 * (n + 8) * sizeof *p), nrm[3];
  const uint32_t *t;
  clock_t c0;
  long nt;
  assert(p != NULL);
  for (i = 0; i < n; i++) {
    double a = 2 * PI * (double)i / (double)n, r = i % 2 ? 0.5 : 1;
    p[3 * i] = r * cos(a); p[3 * i + 1] = r * sin(a); p[3 * i + 2] = 0;
  }
  c0 = clock();
  nt = lsys_polygon_triangulate(&work, p, n, nrm, &t);
  printf("star of %zu vertices: %ld triangles in %.3f s\n", n, nt,
         (double)(clock() - c0) / CLOCKS_PER_SEC);
  assert(nt == (long)n - 2);
  check(p, n, 1, (long)n - 2, nrm);
  n = comb(p, 2500);
  c0 = clock();
  nt = lsys_polygon_triangulate(&work, p, n, nrm, &t);
  printf("comb of %zu vertices: %ld triangles in %.3f s\n", n, nt,
         (double)(clock() - c0) / CLOCKS_PER_SEC);
  assert(nt == (long)n - 2);
  check(p, n, 1, (long)n - 2, nrm);
  for (i = 0; i < 5000; i++) {                 /* a spiral band: outer edge out, inner back */
    double a = 0.01 * (double)i, r = 1 + 0.2 * a / (2 * PI);
    p[3 * i] = r * cos(a); p[3 * i + 1] = r * sin(a); p[3 * i + 2] = 0;
    p[3 * (9999 - i)] = (r - 0.1) * cos(a); p[3 * (9999 - i) + 1] = (r - 0.1) * sin(a);
    p[3 * (9999 - i) + 2] = 0;
  }
  c0 = clock();
  nt = lsys_polygon_triangulate(&work, p, 10000, nrm, &t);
  printf("spiral of 10000 vertices: %ld triangles in %.3f s\n", nt,
         (double)(clock() - c0) / CLOCKS_PER_SEC);
  assert(nt == 9998);
  check(p, 10000, 1, 9998, nrm);
  for (i = 0; i < 10000; i++) {                /* random points: self-intersecting */
    p[3 * i] = urand(); p[3 * i + 1] = urand(); p[3 * i + 2] = 0;
  }
  c0 = clock();
  nt = lsys_polygon_triangulate(&work, p, 10000, nrm, &t);
  printf("10000 random points: %ld triangles in %.3f s\n", nt,
         (double)(clock() - c0) / CLOCKS_PER_SEC);
  assert(nt >= 0 && nt <= 9998);
  free(p);
}

/* ---------------------------------------------------------------------- */
/* big and hostile polygons */

static int cmpu64 (const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* Whether the nt triangles t tile the polygon of n vertices (none repeated,
** collinear or doubled back): each side i -> i + 1 of the polygon is the
** side of exactly one triangle, run the same way, and every other triangle
** side u -> v is matched by exactly one v -> u. With every triangle facing
** the normal and the areas adding up (check), that makes a triangulation. */
static int tiling (const uint32_t *t, long nt, size_t n) {
  uint64_t *e = malloc(3 * (size_t)nt * sizeof *e);
  long i, k, m = 3 * nt;
  int ok = 1;
  assert(e != NULL);
  for (i = 0; i < nt; i++)
    for (k = 0; k < 3; k++)
      e[3 * i + k] = (uint64_t)t[3 * i + k] << 32 | t[3 * i + (k + 1) % 3];
  qsort(e, (size_t)m, sizeof *e, cmpu64);
  for (i = 0; i < m && ok; i++) {
    uint32_t u = (uint32_t)(e[i] >> 32), v = (uint32_t)e[i];
    uint64_t back = (uint64_t)v << 32 | u;
    if (i > 0 && e[i] == e[i - 1]) ok = 0;                  /* a side used twice */
    else if (v != (u + 1) % n)                              /* not a side: matched */
      ok = bsearch(&back, e, (size_t)m, sizeof *e, cmpu64) != NULL;
    else ok = bsearch(&back, e, (size_t)m, sizeof *e, cmpu64) == NULL;
  }
  if (ok) {                                                 /* every side is there */
    size_t j;
    for (j = 0; j < n && ok; j++) {
      uint64_t side = (uint64_t)j << 32 | (uint32_t)((j + 1) % n);
      ok = bsearch(&side, e, (size_t)m, sizeof *e, cmpu64) != NULL;
    }
  }
  free(e);
  return ok;
}

#define PT(x, y) do { p[3 * n] = (x); p[3 * n + 1] = (y); p[3 * n + 2] = 0; n++; } while (0)

/* Hostile simple polygons of about 'size' vertices into p (room for 2 size
** + 8): 0 a comb, 1 a zigzag corridor between combs from both sides, 2 a
** spiral band, 3 a saw, 4 a star of random radii, 5 a comb whose teeth
** widen 100 times along it. Returns the vertex count. */
static size_t hostile (double *p, int kind, size_t size) {
  size_t n = 0, i, teeth = size / 4;
  switch (kind) {
  case 0: return comb(p, teeth);
  case 1:
    for (i = 0; i < teeth / 2; i++) {            /* walls up from the floor ... */
      double x = 2.0 * (double)i;
      PT(x + 0.25, 0); PT(x + 0.25, 9); PT(x + 0.75, 9); PT(x + 0.75, 0);
    }
    PT((double)teeth, 0); PT((double)teeth, 10);
    for (i = teeth / 2; i-- > 0;) {              /* ... and down from the ceiling */
      double x = 2.0 * (double)i + 1;
      PT(x + 0.75, 10); PT(x + 0.75, 1); PT(x + 0.25, 1); PT(x + 0.25, 10);
    }
    PT(0, 10); PT(0, 0);
    return n;
  case 2:
    for (i = 0; i < size / 2; i++) {
      double a = 0.002 * (double)i, r = 1 + 0.2 * a / (2 * PI);
      p[3 * i] = r * cos(a); p[3 * i + 1] = r * sin(a); p[3 * i + 2] = 0;
      p[3 * (size - 1 - i)] = (r - 0.1) * cos(a);
      p[3 * (size - 1 - i) + 1] = (r - 0.1) * sin(a);
      p[3 * (size - 1 - i) + 2] = 0;
    }
    return size / 2 * 2;
  case 3:
    for (i = 0; i + 2 < size; i++) PT((double)i, i % 2 ? 1.0 : 0.0);
    PT((double)size, -5); PT(0, -5);
    return n;
  case 4:
    for (i = 0; i < size; i++) {
      double a = 2 * PI * (double)i / (double)size, r = 0.1 + urand();
      PT(r * cos(a), r * sin(a));
    }
    return n;
  default:
    for (i = 0; i < teeth; i++) {
      double k = log(100.0) / (double)teeth, x = exp(k * (double)i) - 1;
      double x2 = exp(k * ((double)i + 0.5)) - 1, x3 = exp(k * ((double)i + 1)) - 1;
      PT(x, 0); PT(x2, 0); PT(x2, -10); PT(x3, -10);
    }
    PT(p[3 * (n - 1)], 1); PT(0, 1);
    return n;
  }
}

/* The ways of cutting agree: the tree finds what the reflex list finds
** (the same triangles when walking); cut from the heap, small polygons are
** still triangulations; the heap's result does not depend on how the tree
** searches. */
static void test_modes (void) {
  double *p = malloc(3 * 600 * sizeof *p), nrm[3];
  uint32_t *first = malloc(3 * 600 * sizeof *first);
  const uint32_t *t;
  int trial;
  assert(p != NULL && first != NULL);
  srand(11);
  for (trial = 0; trial < 600; trial++) {
    size_t n, i;
    long nt, nt2;
    int kind = trial % 4;
    if (kind == 0) n = hostile(p, trial / 4 % 6, 64 + (size_t)(urand() * 200));
    else {
      n = 64 + (size_t)(urand() * 200);
      for (i = 0; i < n; i++) {
        double r = 0.1 + urand(), a = 2 * PI * ((double)i + 0.8 * urand()) / (double)n;
        if (kind == 1) { p[3 * i] = r * cos(a); p[3 * i + 1] = r * sin(a); }
        else if (kind == 2) { p[3 * i] = floor(6 * r * cos(a)); p[3 * i + 1] = floor(6 * r * sin(a)); }
        else { p[3 * i] = urand(); p[3 * i + 1] = urand(); }      /* self-intersecting */
        p[3 * i + 2] = 0;
      }
    }
    kdmin = 64; qmin = (size_t)-1;              /* walking: the tree, then the list */
    nt = lsys_polygon_triangulate(&work, p, n, nrm, &t);
    assert(nt >= 0);
    memcpy(first, t, 3 * (size_t)nt * sizeof *t);
    kdmin = (size_t)-1;
    nt2 = lsys_polygon_triangulate(&work, p, n, nrm, &t);
    assert(nt2 == nt && memcmp(first, t, 3 * (size_t)nt * sizeof *t) == 0);
    kdmin = 3; qmin = 3;                         /* the heap, with the tree */
    if (kind <= 1) assert(check(p, n, 2, -1, nrm) == nt);
    else check(p, n, 0, -1, nrm);            /* snapped to a grid or random: not simple */
    if (kind == 0) {
      nt = lsys_polygon_triangulate(&work, p, n, nrm, &t);
      assert(tiling(t, nt, n));
    }
  }
  kdmin = 64; qmin = 1024;
  free(first);
  free(p);
}

/* Big hostile polygons: n - 2 triangles that tile them (linear checks). */
static void test_hostile (void) {
  const size_t size = 200000;
  double *p = malloc(3 * (2 * size + 8) * sizeof *p), nrm[3];
  int kind;
  assert(p != NULL);
  srand(5);
  for (kind = 0; kind < 6; kind++) {              /* a star of slivers is the slowest */
    size_t n = hostile(p, kind, kind == 4 ? size / 8 : size);
    long nt = check(p, n, 1, (long)n - 2, nrm);
    assert(tiling(work.tris, nt, n));            /* check's triangles */
    reverse(p, n);                               /* the other way round */
    nt = check(p, n, 1, (long)n - 2, nrm);
    assert(tiling(work.tris, nt, n));
  }
  free(p);
}

/* What is refused: more than LSYS_POLYGON_MAXV vertices (before anything is
** read), more work than allowed, more memory than the meter leaves. */
static void test_limits (void) {
  static const double sq[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  double *p = malloc(3 * 4100 * sizeof *p), nrm[3];
  const uint32_t *t;
  lsys_polywork w = {0};
  lsys_meter mt = {1000, 0, 0, NULL};
  size_t n;
  assert(p != NULL);
  assert(lsys_polygon_triangulate(&work, sq, (size_t)LSYS_POLYGON_MAXV + 1, nrm, &t) ==
         LSYS_ELIMIT);
  n = comb(p, 1000);
  maxwork = 0.01;                                /* a comb of 4002 needs about 2 */
  assert(lsys_polygon_triangulate(&work, p, n, nrm, &t) == LSYS_ELIMIT);
  maxwork = 256;
  assert(lsys_polygon_triangulate(&work, p, n, nrm, &t) == (long)n - 2);
  w.meter = &mt;                                 /* 1000 bytes: 4 vertices, not 4002 */
  assert(lsys_polygon_triangulate(&w, sq, 4, nrm, &t) == 2);
  assert(lsys_polygon_triangulate(&w, p, n, nrm, &t) == LSYS_EMEMORY && mt.hit);
  mt.limit = (size_t)-1;
  assert(lsys_polygon_triangulate(&w, p, n, nrm, &t) == (long)n - 2);
  lsys_polygon_work_free(&w);
  assert(w.meter == &mt && w.xy == NULL);       /* freeing keeps the meter */
  free(p);
}

/* Each allocation fails in turn: LSYS_ENOMEM, and the work area stays usable. */
static void test_nomem (void) {
  static const double sq[] = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  double nrm[3];
  const uint32_t *t;
  long k, nt;
  for (k = 0; k < 4; k++) {
    lsys_polywork w = {0};
    nalloc = 0;
    failat = k;
    assert(lsys_polygon_triangulate(&w, sq, 4, nrm, &t) == LSYS_ENOMEM);
    failat = -1;
    nt = lsys_polygon_triangulate(&w, sq, 4, nrm, &t);
    assert(nt == 2 && t == w.tris);
    lsys_polygon_work_free(&w);
  }
}

int main (void) {
  test_basic();
  test_degenerate();
  test_3d();
  test_bad();
  test_random();
  test_large();
  test_modes();
  test_hostile();
  test_limits();
  test_nomem();
  lsys_polygon_work_free(&work);
  lsys_polygon_work_free(&work);                   /* idempotent */
  printf("test_polygon: ok\n");
  return 0;
}
