/*
** C unit tests for the light environment (light.h): a triangle over a point
** shadows it from the sun straight above and not once moved aside; the
** overcast sky gives 1 in the open, 0 under a wide plane and what the
** sampling gives (about 1/2) under a half-plane; two half-transparent
** layers let a quarter through; leaves' normals weigh directions by their
** cosine; lines occlude as capsules only with a radius, and not a point in
** them; instances are placed; 1 and 3 threads give the same bits; the
** hierarchy agrees with testing every primitive on random triangles and
** points, with and without a transmittance, ray by ray and in packets;
** the memory budget, bad options, and every allocation failing in turn.
**
** The core files are compiled in with counting allocators (talloc.h).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "mesh.c"
#include "scene.c"
#include "light.c"
#include "light_bvh.c"
#include "light_ray.c"

#define NEAR(a, b, eps) (fabs((double)(a) - (double)(b)) <= (eps))

static void tri (lsys_scene *s, const double a[3], const double b[3], const double c[3]) {
  static const double n[3] = {0, 1, 0};
  uint32_t v;
  assert(lsys_mesh_reserve(&s->mesh, 3, 1) == LSYS_OK);
  v = lsys_mesh_vertex(&s->mesh, a, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, b, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, c, n, 0, 0, 0, 1);
  lsys_mesh_tri(&s->mesh, v, v + 1, v + 2);
}

/* The square [x0, x1] x [z0, z1] at height y, as two triangles. */
static void quad (lsys_scene *s, double x0, double x1, double z0, double z1, double y) {
  double a[3] = {x0, y, z0}, b[3] = {x1, y, z0}, c[3] = {x1, y, z1}, d[3] = {x0, y, z1};
  tri(s, a, b, c);
  tri(s, a, c, d);
}

static lsys_light *build (const lsys_scene *s, const lsys_light_opts *o) {
  lsys_light *L;
  lsys_error e;
  int st = lsys_light_build(&L, s, o, &e);
  if (st != LSYS_OK) fprintf(stderr, "build: %d %s\n", st, e.msg);
  assert(st == LSYS_OK && L != NULL);
  return L;
}

static double at (const lsys_light *L, double x, double y, double z, const double *n) {
  double p[3] = {x, y, z}, v = -1;
  assert(lsys_light_query(L, p, 1, n, &v, NULL, 1, NULL) == LSYS_OK);
  return v;
}

static void sun_opts (lsys_light_opts *o, double x, double y, double z) {
  lsys_light_defaults(o);
  o->kind = LSYS_LIGHT_SUN;
  o->sun[0] = x; o->sun[1] = y; o->sun[2] = z;
}

static void test_sun_triangle (void) {
  static const double a[3] = {-1, 2, -1}, b[3] = {1, 2, -1}, c[3] = {0, 2, 1};
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_scene_init(&s);
  tri(&s, a, b, c);
  sun_opts(&o, 0, 1, 0);
  L = build(&s, &o);
  assert(at(L, 0, 0, 0, NULL) == 0);              /* straight under it */
  assert(at(L, 5, 0, 0, NULL) == 1);              /* moved aside */
  assert(at(L, 0, 3, 0, NULL) == 1);              /* above it */
  lsys_light_free(L);
  sun_opts(&o, 1, 1, 0);                          /* the sun at 45 degrees: the shadow moves */
  L = build(&s, &o);
  assert(at(L, 0, 0, 0, NULL) == 1);
  assert(at(L, -2, 0, 0, NULL) == 0);
  lsys_light_free(L);
  lsys_scene_free(&s);
}

/* max_distance: the triangle 2 above the point stops the sun's ray only when it is within
** reach; a reach of 0 is no limit, a negative one an error. */
static void test_max_distance (void) {
  static const double a[3] = {-1, 2, -1}, b[3] = {1, 2, -1}, c[3] = {0, 2, 1};
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_error e;
  lsys_scene_init(&s);
  tri(&s, a, b, c);
  sun_opts(&o, 0, 1, 0);
  o.max_distance = 2.5;
  L = build(&s, &o);
  assert(at(L, 0, 0, 0, NULL) == 0);              /* 2 away: blocked */
  assert(at(L, 0, -1, 0, NULL) == 1);             /* 3 away: beyond the reach */
  lsys_light_free(L);
  o.max_distance = 1.5;
  L = build(&s, &o);
  assert(at(L, 0, 0, 0, NULL) == 1);
  assert(at(L, 0, 1, 0, NULL) == 0);              /* 1 away */
  lsys_light_free(L);
  o.max_distance = -1;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG && L == NULL);
  assert(strstr(e.msg, "max_distance") != NULL);
  lsys_scene_free(&s);
}

static void test_overcast (void) {
  lsys_scene s;
  lsys_light *L;
  lsys_light_opts o;
  const double *d, *w;
  double v, expect = 0, sum = 0, p[3] = {0, 0, 0}, dir[3];
  size_t k, n;
  lsys_scene_init(&s);
  L = build(&s, NULL);                            /* an empty scene: all open */
  assert(NEAR(at(L, 0, 0, 0, NULL), 1, 1e-12));
  lsys_light_free(L);
  quad(&s, -1000, 1000, -1000, 1000, 1);          /* a plane ~infinite at height 1 */
  L = build(&s, NULL);
  n = lsys_light_sky(L, &d, &w);
  assert(n == 64);
  for (k = 0; k < n; k++) {
    assert(d[3 * k + 1] > 0 && NEAR(d[3 * k] * d[3 * k] + d[3 * k + 1] * d[3 * k + 1] +
                                    d[3 * k + 2] * d[3 * k + 2], 1, 1e-12));
    assert(NEAR(w[k], 1.0 / 64, 1e-15));
    sum += w[k];
  }
  assert(NEAR(sum, 1, 1e-12));
  assert(at(L, 0, 0, 0, NULL) == 0);              /* under the plane */
  assert(NEAR(at(L, 0, 2, 0, NULL), 1, 1e-12));   /* above it */
  lsys_light_free(L);
  lsys_scene_clear(&s);
  quad(&s, 0, 1000, -1000, 1000, 1);              /* a half-plane over x > 0 */
  L = build(&s, NULL);
  n = lsys_light_sky(L, &d, &w);
  for (k = 0; k < n; k++) expect += d[3 * k] < 0 ? w[k] : 0;
  assert(lsys_light_query(L, p, 1, NULL, &v, dir, 1, NULL) == LSYS_OK);
  assert(NEAR(v, expect, 1e-12));                 /* what the sampling gives, */
  assert(NEAR(v, 0.5, 1.5 / 64));                 /* half the sky within a direction or so */
  assert(dir[0] < -0.5 && dir[1] > 0 && NEAR(dir[0] * dir[0] + dir[1] * dir[1] +
                                              dir[2] * dir[2], 1, 1e-12));
  lsys_light_free(L);
  lsys_light_defaults(&o);                        /* the other skies' weights */
  o.radiance = LSYS_LIGHT_CIE;
  o.samples = 4096;
  L = build(&s, &o);
  n = lsys_light_sky(L, &d, &w);
  for (k = 0, sum = 0; k < n; k++) sum += w[k] * d[3 * k + 1];
  assert(NEAR(sum, 7.0 / 12, 1e-3));              /* a horizontal leaf in the open */
  p[1] = 2;
  dir[0] = 0; dir[1] = 1; dir[2] = 0;
  assert(lsys_light_query(L, p, 1, dir, &v, NULL, 1, NULL) == LSYS_OK);
  assert(NEAR(v, sum, 1e-12));
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static void test_transmittance (void) {
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_scene_init(&s);
  quad(&s, -1, 1, -1, 1, 1);
  quad(&s, -1, 1, -1, 1, 2);
  sun_opts(&o, 0, 1, 0);
  o.transmittance = 0.5;
  L = build(&s, &o);
  assert(NEAR(at(L, 0.1, 0, 0.2, NULL), 0.25, 1e-15));
  assert(NEAR(at(L, 0.1, 1.5, 0.2, NULL), 0.5, 1e-15));
  assert(at(L, 0.1, 2.5, 0.2, NULL) == 1);
  lsys_light_free(L);
  o.max_hits = 1;                                 /* the first hit only */
  L = build(&s, &o);
  assert(NEAR(at(L, 0.1, 0, 0.2, NULL), 0.5, 1e-15));
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static void test_normals (void) {
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_error e;
  double up[3] = {0, 2, 0}, side[3] = {1, 0, 0}, tilt[3] = {sqrt(3.0), 1, 0}, zero[3] = {0};
  double p[3] = {0, 0, 0}, v;
  lsys_scene_init(&s);
  sun_opts(&o, 0, 1, 0);
  L = build(&s, &o);
  assert(NEAR(at(L, 0, 0, 0, up), 1, 1e-15));     /* normalised here */
  assert(at(L, 0, 0, 0, side) == 0);
  assert(NEAR(at(L, 0, 0, 0, tilt), 0.5, 1e-12)); /* 60 degrees off the sun */
  assert(lsys_light_query(L, p, 1, zero, &v, NULL, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: normal 1 is not a finite non-zero vector") == 0);
  p[0] = NAN;
  assert(lsys_light_query(L, p, 1, NULL, &v, NULL, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: point 1 is not finite") == 0);
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static void test_lines (void) {
  static const double a[3] = {-1, 1, 0}, b[3] = {1, 1, 0};
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_light_stats st;
  lsys_scene_init(&s);
  assert(lsys_mesh_line(&s.mesh, a, b, 1, 1, 0) == LSYS_OK);
  sun_opts(&o, 0, 1, 0);
  L = build(&s, &o);                              /* no radius: lines do not occlude */
  assert(at(L, 0, 0, 0, NULL) == 1);
  lsys_light_info(L, &st);
  assert(st.capsules == 0 && st.triangles == 0);
  lsys_light_free(L);
  o.line_radius = 0.1;
  L = build(&s, &o);
  lsys_light_info(L, &st);
  assert(st.capsules == 1);
  assert(at(L, 0, 0, 0, NULL) == 0);              /* under the capsule's body */
  assert(at(L, 0, 0, 0.09, NULL) == 0);
  assert(at(L, 0, 0, 0.11, NULL) == 1);           /* beside it */
  assert(at(L, 1.05, 0, 0, NULL) == 0);           /* under an end's sphere */
  assert(at(L, 1.2, 0, 0, NULL) == 1);
  assert(at(L, 0, 1, 0, NULL) == 1);              /* in it: not shadowed by it */
  assert(at(L, 0, 1.05, 0, NULL) == 1);
  lsys_light_free(L);
  o.sun[0] = 1; o.sun[1] = 0; o.sun[2] = 0;       /* along the axis: the sphere, then the body */
  L = build(&s, &o);
  assert(at(L, -3, 1, 0, NULL) == 0);
  assert(at(L, -3, 1.15, 0, NULL) == 1);
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static void test_instances (void) {
  static const double a[3] = {-1, 0, -1}, b[3] = {1, 0, -1}, c[3] = {0, 0, 1};
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 2, 0, 1};
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_light_stats st;
  lsys_scene_init(&s);
  assert(lsys_scene_begin_part(&s) == 0);
  tri(&s, a, b, c);
  lsys_scene_end_part(&s, 0);
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  m[12] = -10;
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  sun_opts(&o, 0, 1, 0);
  L = build(&s, &o);
  lsys_light_info(L, &st);
  assert(st.triangles == 2);
  assert(at(L, 0, 0, 0, NULL) == 1);              /* the part's own place: nothing drawn */
  assert(at(L, 10, 0, 0, NULL) == 0);
  assert(at(L, -10, 0, 0, NULL) == 0);
  assert(at(L, 10, 3, 0, NULL) == 1);
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static uint64_t rs = 88172645463325252ull;
static double rnd (void) {                        /* xorshift64, in [0, 1) */
  rs ^= rs << 13; rs ^= rs >> 7; rs ^= rs << 17;
  return (double)(rs >> 11) / 9007199254740992.0;
}

/* 2000 random triangles in a box, lines as capsules, 500 random points. */
static void randomscene (lsys_scene *s, double *pts, size_t np) {
  size_t k;
  int c;
  lsys_scene_init(s);
  for (k = 0; k < 2000; k++) {
    double v[3][3], ctr[3];
    for (c = 0; c < 3; c++) ctr[c] = 10 * rnd();
    for (c = 0; c < 9; c++) v[c / 3][c % 3] = ctr[c % 3] + rnd() - 0.5;
    tri(s, v[0], v[1], v[2]);
  }
  for (k = 0; k < 100; k++) {
    double a[3], b[3];
    for (c = 0; c < 3; c++) { a[c] = 10 * rnd(); b[c] = a[c] + rnd() - 0.5; }
    assert(lsys_mesh_line(&s->mesh, a, b, 1, 1, 0) == LSYS_OK);
  }
  for (k = 0; k < 3 * np; k++) pts[k] = 12 * rnd() - 1;
}

static void test_brute (void) {
  enum { NP = 500 };
  static double pts[3 * NP], out1[NP], out3[NP], dir1[3 * NP], dir3[3 * NP];
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  lsys_light_stats st;
  const double *d, *w;
  size_t k, i, n, blocked = 0, rays = 0;
  int cap;
  randomscene(&s, pts, NP);
  lsys_light_defaults(&o);
  o.line_radius = 0.05;
  o.transmittance = 0.3;
  L = build(&s, &o);
  lsys_light_info(L, &st);
  assert(st.triangles == 2000 && st.capsules == 100 && st.depth < LSYS_LIGHT_STACK);
  n = lsys_light_sky(L, &d, &w);
  for (i = 0; i < NP; i++)                        /* every ray of every point, */
    for (k = 0; k < n; k++) {
      double dd[3] = {d[3 * k], d[3 * k + 1], d[3 * k + 2]};
      int h = lsys_light_hits(L, pts + 3 * i, dd, 1, 0);
      assert(h == lsys_light_hits(L, pts + 3 * i, dd, 1, 1));
      blocked += h > 0;
      rays++;
      if (i % 25 != 0) continue;
      for (cap = 8; cap <= 64; cap += 56) {          /* counting hits, and downwards too */
        assert(lsys_light_hits(L, pts + 3 * i, dd, cap, 0) ==
               lsys_light_hits(L, pts + 3 * i, dd, cap, 1));
        dd[1] = -dd[1];
        assert(lsys_light_hits(L, pts + 3 * i, dd, cap, 0) ==
               lsys_light_hits(L, pts + 3 * i, dd, cap, 1));
        dd[1] = -dd[1];
      }
    }
  assert(blocked > rays / 10 && blocked < rays * 9 / 10);   /* a test worth its name */
  assert(lsys_light_query(L, pts, NP, NULL, out1, dir1, 1, NULL) == LSYS_OK);
  for (i = 0; i < NP; i++) {                      /* a query is its rays, summed in order */
    double E = 0;
    for (k = 0; k < n; k++)
      E += w[k] * L->taupow[lsys_light_hits(L, pts + 3 * i, d + 3 * k, L->maxhits, 1)];
    assert(E == out1[i]);
  }
  assert(lsys_light_query(L, pts, NP, NULL, out3, dir3, 3, NULL) == LSYS_OK);
  assert(memcmp(out1, out3, sizeof out1) == 0 && memcmp(dir1, dir3, sizeof dir1) == 0);
  assert(lsys_light_query(L, pts, NP, pts, out3, NULL, 3, NULL) == LSYS_OK);  /* normals */
  assert(lsys_light_query(L, pts, NP, pts, out1, NULL, 1, NULL) == LSYS_OK);
  assert(memcmp(out1, out3, sizeof out1) == 0);
  lsys_light_free(L);
  lsys_scene_free(&s);
}

/* The light and mean direction of point i as its rays one by one give them,
** summed in the sky's order (what a query must give, bit for bit). */
static void byrays (const lsys_light *L, const double *p, double *E, double dir[3]) {
  const double *d, *w;
  double M[3] = {0, 0, 0}, len;
  size_t k, n = lsys_light_sky(L, &d, &w);
  int c;
  *E = 0;
  for (k = 0; k < n; k++) {
    double v = w[k] * L->taupow[lsys_light_hits(L, p, d + 3 * k, L->maxhits, 1)];
    *E += v;
    for (c = 0; c < 3; c++) M[c] += v * d[3 * k + c];
  }
  len = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
  for (c = 0; c < 3; c++) dir[c] = len > 0 ? M[c] / len : 0;
}

/*
** Opaque surfaces, where a query's rays stop at their first hit and try the
** primitive that stopped the last packet first: clusters of nearly the same
** point (so that packets fill and the last stopper stops the next), points
** spread out, and more points than a worker takes at a time. Every value
** and direction is what the point's rays give one by one, for 1, 2 and 3
** threads; and a direction's rays cast together (some left out, in blocks
** larger than one ordering) count what each counts alone.
*/
static void test_packets (void) {
  enum { NP = 1200 };
  static double pts[3 * NP], out1[NP], out2[NP], out3[NP], dir1[3 * NP], dir3[3 * NP];
  static float of[NP][3];
  static uint8_t want[NP], hits[NP];
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L;
  const double *d, *w;
  size_t i, k, n;
  double mean = 0;
  int c, cap;
  randomscene(&s, pts, NP);
  for (i = 0; i < NP / 2; i++)                    /* the first half: clusters of 8 */
    for (c = 0; c < 3; c++) pts[3 * i + c] = pts[3 * (i / 8 * 8) + c] + 1e-3 * rnd();
  lsys_light_defaults(&o);
  o.line_radius = 0.05;
  L = build(&s, &o);
  assert(L->maxhits == 1);
  assert(lsys_light_query(L, pts, NP, NULL, out1, dir1, 1, NULL) == LSYS_OK);
  assert(lsys_light_query(L, pts, NP, NULL, out2, NULL, 2, NULL) == LSYS_OK);
  assert(lsys_light_query(L, pts, NP, NULL, out3, dir3, 3, NULL) == LSYS_OK);
  assert(memcmp(out1, out2, sizeof out1) == 0 && memcmp(out1, out3, sizeof out1) == 0);
  assert(memcmp(dir1, dir3, sizeof dir1) == 0);
  for (i = 0; i < NP; i++) {
    double E, dir[3];
    byrays(L, pts + 3 * i, &E, dir);
    assert(E == out1[i]);
    assert(dir[0] == dir1[3 * i] && dir[1] == dir1[3 * i + 1] && dir[2] == dir1[3 * i + 2]);
    mean += E / NP;
  }
  assert(mean > 0.1 && mean < 0.9);               /* rays stopped and rays through */
  n = lsys_light_sky(L, &d, &w);
  for (i = 0; i < NP; i++) {
    for (c = 0; c < 3; c++) of[i][c] = (float)pts[3 * i + c];
    want[i] = i % 7 != 3;
  }
  for (cap = 1; cap <= 8; cap += 7)
    for (k = 0; k < n; k += 9) {
      float df[3] = {(float)d[3 * k], (float)d[3 * k + 1], (float)d[3 * k + 2]};
      lsys_light_cast(L, (const float (*)[3])of, want, NP, df, (float)L->offset, cap, hits);
      for (i = 0; i < NP; i++)
        assert(hits[i] == (want[i] ? lsys_light_brute(L, of[i], df, (float)L->offset, cap) : 0));
    }
  lsys_light_free(L);
  lsys_scene_free(&s);
}

static void test_errors (void) {
  lsys_scene s;
  lsys_light_opts o;
  lsys_light *L = (lsys_light *)&o;
  lsys_meter mt = {100, 0, 0, NULL};
  lsys_error e;
  double dirs[8] = {0, 1, 0, 0, 1, 0, 0, 0};
  lsys_scene_init(&s);
  quad(&s, 0, 1, 0, 1, 1);
  lsys_light_defaults(&o);
  o.samples = LSYS_LIGHT_MAXSAMPLES + 1;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG && L == NULL);
  assert(strcmp(e.msg, "light: samples must be an integer in [1, 65536]") == 0);
  lsys_light_defaults(&o);
  o.transmittance = 1;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: transmittance must be a number in [0, 1)") == 0);
  sun_opts(&o, 0, 0, 0);
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: the sun is not a finite non-zero vector") == 0);
  lsys_light_defaults(&o);
  o.kind = LSYS_LIGHT_DIRS;
  o.dirs = dirs;
  o.ndirs = 2;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: the directions' weights must not all be 0") == 0);
  dirs[3] = 1;
  dirs[4] = 0;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "light: direction 2 is not a finite non-zero vector") == 0);
  dirs[4] = 1;
  lsys_light_free(build(&s, &o));
  lsys_light_defaults(&o);
  o.meter = &mt;
  assert(lsys_light_build(&L, &s, &o, &e) == LSYS_EMEMORY && mt.hit && mt.used == 0);
  assert(strcmp(e.msg, "light: the hierarchy needs 280 bytes, more than max_memory "
                "(100 bytes)") == 0);
  mt.limit = 1 << 20;
  mt.hit = 0;
  L = build(&s, &o);
  assert(mt.used == sizeof(lsys_ltri4) + sizeof(lsys_lnode4));   /* what it keeps: a packet */
  lsys_light_free(L);
  lsys_scene_free(&s);
}

/* Every allocation of a build and a query fails in turn: a clean error, nothing left. */
static void test_nomem (void) {
  static double pts[3 * 50];
  lsys_scene s;
  lsys_light_opts o;
  long k, n;
  randomscene(&s, pts, 50);
  lsys_light_defaults(&o);
  o.line_radius = 0.1;
  nalloc = 0;
  lsys_light_free(build(&s, &o));
  n = nalloc;
  for (k = 0; k < n + 2; k++) {
    lsys_light *L;
    long live = nlive;
    double out[50];
    int st;
    nalloc = 0;
    failat = k;
    st = lsys_light_build(&L, &s, &o, NULL);
    if (st == LSYS_OK) st = lsys_light_query(L, pts, 50, pts, out, NULL, 2, NULL);
    assert(st == LSYS_OK || st == LSYS_ENOMEM);
    lsys_light_free(L);
    failat = -1;
    assert(nlive == live);
  }
  lsys_scene_free(&s);
}

int main (void) {
  test_sun_triangle();
  test_max_distance();
  test_overcast();
  test_transmittance();
  test_normals();
  test_lines();
  test_instances();
  test_brute();
  test_packets();
  test_errors();
  test_nomem();
  printf("test_light: ok\n");
  return 0;
}
