/*
** C unit tests for the shadow-propagation grid (shadow.h): the exact
** pyramid of one caster and the sum of two, weights, the exposure, the
** direction of least shadow (away from a caster above and to the left, the
** heading's ties, the cone and the radius), an obstacle box, the rules
** outside the grid (casters above and beside it cast what falls inside;
** queries outside read 0), a scene's triangles as casters (and its
** instances), random casters against a direct sum, 1, 2 and 3 threads giving
** the same bits, the memory budget, bad options and input, and every
** allocation failing in turn.
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
#include "shadow.c"

#define NEAR(a, b, eps) (fabs((double)(a) - (double)(b)) <= (eps))

/* The grid [0, n]^3 of unit voxels, of the depth given, a = 1, b = 2. */
static lsys_shadow *grid (int n, int depth, lsys_meter *mt) {
  lsys_shadow_opts o;
  lsys_shadow *S;
  lsys_error e;
  int st;
  lsys_shadow_defaults(&o);
  o.hi[0] = o.hi[1] = o.hi[2] = n;
  o.depth = depth;
  o.meter = mt;
  st = lsys_shadow_new(&S, &o, &e);
  if (st != LSYS_OK) fprintf(stderr, "new: %d %s\n", st, e.msg);
  assert(st == LSYS_OK && S != NULL);
  return S;
}

static void add1 (lsys_shadow *S, double x, double y, double z, double w) {
  double p[3] = {x, y, z};
  assert(lsys_shadow_add(S, p, &w, 1, 1, NULL) == LSYS_OK);
}

static double shadow_at (const lsys_shadow *S, double x, double y, double z) {
  double p[3] = {x, y, z}, v = -1;
  assert(lsys_shadow_query(S, p, 1, 0, 0, &v, NULL) == LSYS_OK);
  return v;
}

static double exposure_at (const lsys_shadow *S, double x, double y, double z, double C) {
  double p[3] = {x, y, z}, v = -1;
  assert(lsys_shadow_query(S, p, 1, 1, C, &v, NULL) == LSYS_OK);
  return v;
}

/* What a caster of weight w in voxel (I, J, K) puts in voxel (i, j, k),
** a = 1, b = 2. */
static double pyramid (long I, long J, long K, double w, int depth, long i, long j, long k) {
  long q = J - j;
  if (q < 0 || q > depth || labs(i - I) > q || labs(k - K) > q) return 0;
  return w * ldexp(1, (int)-q);
}

static void test_pyramid (void) {
  lsys_shadow *S = grid(11, 4, NULL);
  lsys_shadow_stats st;
  long i, j, k, nonzero = 0;
  lsys_shadow_info(S, &st);
  assert(st.n[0] == 11 && st.n[1] == 11 && st.n[2] == 11 && st.voxels == 1331);
  assert(st.bytes == 1331 * sizeof(double) + sizeof(lsys_shadow) && st.depth == 4);
  add1(S, 5.5, 8.5, 5.5, 1);                      /* voxel (5, 8, 5) */
  for (j = 0; j < 11; j++)
    for (k = 0; k < 11; k++)
      for (i = 0; i < 11; i++) {
        double v = lsys_shadow_voxel(S, i, j, k);
        assert(v == pyramid(5, 8, 5, 1, 4, i, j, k));
        nonzero += v != 0;
      }
  assert(nonzero == 1 + 9 + 25 + 49 + 81);        /* levels 0 .. 4 */
  assert(lsys_shadow_voxel(S, 5, 8, 5) == 1);
  assert(lsys_shadow_voxel(S, 3, 6, 7) == 0.25);  /* two levels down, at the corner */
  assert(lsys_shadow_voxel(S, 2, 6, 5) == 0);     /* outside that level's square */
  assert(lsys_shadow_voxel(S, 5, 3, 5) == 0);     /* below the last level */
  assert(lsys_shadow_voxel(S, 5, 9, 5) == 0);     /* above the caster */
  assert(shadow_at(S, 5.9, 4.1, 5.0) == 0.0625);  /* a point reads its voxel */
  /* a second caster, of weight 3, one down and one to the right: the sum */
  add1(S, 6.5, 7.5, 5.5, 3);
  for (j = 0; j < 11; j++)
    for (k = 0; k < 11; k++)
      for (i = 0; i < 11; i++)
        assert(lsys_shadow_voxel(S, i, j, k) ==
               pyramid(5, 8, 5, 1, 4, i, j, k) + pyramid(6, 7, 5, 3, 4, i, j, k));
  assert(lsys_shadow_voxel(S, 6, 7, 5) == 0.5 + 3);
  lsys_shadow_clear(S);
  for (i = 0; i < (long)S->nvox; i++) assert(S->s[i] == 0);
  lsys_shadow_free(S);
}

static void test_params (void) {
  lsys_shadow_opts o;
  lsys_shadow *S;
  lsys_shadow_defaults(&o);
  o.hi[0] = o.hi[1] = o.hi[2] = 4;
  o.voxel = 0.5;                                  /* 8 x 8 x 8 */
  o.depth = 2;
  o.a = 3;
  o.b = 4;
  assert(lsys_shadow_new(&S, &o, NULL) == LSYS_OK);
  add1(S, 1.2, 3.9, 1.2, 2);                      /* voxel (2, 7, 2) */
  assert(lsys_shadow_voxel(S, 2, 7, 2) == 6);     /* w a */
  assert(lsys_shadow_voxel(S, 1, 6, 3) == 1.5);   /* w a / b */
  assert(lsys_shadow_voxel(S, 0, 5, 4) == 0.375); /* w a / b^2 */
  assert(lsys_shadow_voxel(S, 2, 4, 2) == 0);     /* depth 2: no level 3 */
  /* the exposure max(C - s + a, 0): a caster does not shade itself */
  assert(exposure_at(S, 1.2, 3.9, 1.2, 10) == 10 - 6 + 3);
  assert(exposure_at(S, 1.2, 3.2, 1.2, 10) == 10 - 1.5 + 3);
  assert(exposure_at(S, 1.2, 3.9, 1.2, 1) == 0);  /* clamped */
  add1(S, 1.2, 3.9, 1.2, -2);                     /* a negative weight takes it back */
  assert(lsys_shadow_voxel(S, 2, 7, 2) == 0 && lsys_shadow_voxel(S, 0, 5, 4) == 0);
  lsys_shadow_free(S);
}

static void dir_at (const lsys_shadow *S, const double p[3], const double h[3], double angle,
                    double radius, double out[3]) {
  lsys_error e;
  int st = lsys_shadow_direction(S, p, h, 1, angle, radius, out, 1, &e);
  if (st != LSYS_OK) fprintf(stderr, "direction: %s\n", e.msg);
  assert(st == LSYS_OK);
}

static void test_direction (void) {
  static const double p[3] = {5.5, 5.5, 5.5}, up[3] = {0, 2, 0};
  lsys_shadow *S = grid(11, 4, NULL);
  double d[3], r = sqrt(0.5);
  /* an empty grid: of the equal shadows, the voxel straight along the heading */
  dir_at(S, p, up, 90, 2, d);
  assert(d[0] == 0 && d[1] == 1 && d[2] == 0);
  /* a caster above and to the left, in (4, 7, 5): above the point, (5, 6, 5) is in its
  ** pyramid, (6, 6, 5) is not: the shoot turns up and to the right */
  add1(S, 4.5, 7.5, 5.5, 1);
  assert(shadow_at(S, 5.5, 6.5, 5.5) == 0.5 && shadow_at(S, 6.5, 6.5, 5.5) == 0);
  dir_at(S, p, up, 90, 1.5, d);
  assert(NEAR(d[0], r, 1e-15) && NEAR(d[1], r, 1e-15) && d[2] == 0);
  /* a cone of 30 degrees around up sees only (5, 6, 5): it goes there */
  dir_at(S, p, up, 30, 1.5, d);
  assert(d[0] == 0 && d[1] == 1 && d[2] == 0);
  /* a radius of 2 reaches (5, 7, 5), beside the caster: unshaded, along the heading */
  dir_at(S, p, up, 90, 2, d);
  assert(d[0] == 0 && d[1] == 1 && d[2] == 0);
  /* no voxel centre within the radius, and a point outside the grid: the heading */
  {
    static const double h[3] = {3, 4, 0}, out[3] = {-1, 5, 5};
    dir_at(S, p, h, 90, 0.5, d);
    assert(NEAR(d[0], 0.6, 1e-15) && NEAR(d[1], 0.8, 1e-15) && d[2] == 0);
    dir_at(S, out, h, 90, 2, d);
    assert(NEAR(d[0], 0.6, 1e-15) && NEAR(d[1], 0.8, 1e-15) && d[2] == 0);
  }
  /* 180 degrees: every direction; right under the caster, the least shadow is below
  ** (level 2 of its pyramid), not beside (level 1) nor above (the caster) */
  {
    static const double q[3] = {4.5, 6.5, 5.5};
    dir_at(S, q, up, 180, 1, d);
    assert(d[0] == 0 && d[1] == -1 && d[2] == 0);
  }
  lsys_shadow_free(S);
}

static void test_box (void) {
  static const double lo[3] = {2, 2, 2}, hi[3] = {4, 3, 4}, pt[3] = {2.5, 2.5, 2.5};
  static const double far0[3] = {20, 0, 0}, far1[3] = {30, 5, 5};
  static const double part0[3] = {-5, 9.5, -5}, part1[3] = {0.5, 20, 0.5};
  lsys_shadow *S = grid(10, 4, NULL);
  long i, j, k, n = 0;
  assert(lsys_shadow_add_box(S, lo, hi, 7, NULL) == LSYS_OK);
  for (j = 0; j < 10; j++)
    for (k = 0; k < 10; k++)
      for (i = 0; i < 10; i++) {
        double v = lsys_shadow_voxel(S, i, j, k);
        int in = i >= 2 && i <= 3 && j == 2 && k >= 2 && k <= 3;   /* faces on boundaries */
        assert(v == (in ? 7 : 0));
        n += in;
      }
  assert(n == 4);
  assert(lsys_shadow_add_box(S, pt, pt, 1, NULL) == LSYS_OK);   /* a point: its voxel */
  assert(lsys_shadow_voxel(S, 2, 2, 2) == 8 && lsys_shadow_voxel(S, 3, 2, 2) == 7);
  assert(lsys_shadow_add_box(S, far0, far1, 1, NULL) == LSYS_OK);   /* beside: nothing */
  assert(lsys_shadow_add_box(S, part0, part1, 2, NULL) == LSYS_OK); /* clamped to the grid */
  assert(lsys_shadow_voxel(S, 0, 9, 0) == 2 && lsys_shadow_voxel(S, 1, 9, 0) == 0);
  assert(lsys_shadow_voxel(S, 0, 8, 0) == 0);
  /* an obstacle steers the direction: a wall on the right of the point, heading up */
  {
    static const double w0[3] = {6, 5, 0}, w1[3] = {7, 7, 10}, p[3] = {5.5, 5.5, 5.5};
    static const double h[3] = {1, 1, 0};
    double d[3];
    assert(lsys_shadow_add_box(S, w0, w1, 100, NULL) == LSYS_OK);
    dir_at(S, p, h, 50, 1.5, d);                 /* (6, 6, 5) and (6, 5, 5) are in it */
    assert(d[0] == 0 && d[1] == 1 && d[2] == 0);
  }
  lsys_shadow_free(S);
}

static void test_outside (void) {
  lsys_shadow *S = grid(11, 4, NULL);
  double big[6] = {1e300, 5, 5, 5, -1e300, 5};
  add1(S, 5.5, 12.5, 5.5, 1);                     /* voxel (5, 12, 5), above the grid */
  assert(lsys_shadow_voxel(S, 5, 10, 5) == 0.25 && lsys_shadow_voxel(S, 3, 10, 3) == 0.25);
  assert(lsys_shadow_voxel(S, 5, 9, 5) == 0.125 && lsys_shadow_voxel(S, 5, 8, 5) == 0.0625);
  assert(lsys_shadow_voxel(S, 5, 7, 5) == 0);
  lsys_shadow_clear(S);
  add1(S, -1.5, 8.5, 5.5, 1);                     /* voxel (-2, 8, 5), beside the grid */
  assert(lsys_shadow_voxel(S, 0, 7, 5) == 0);     /* level 1 reaches x = -1 only */
  assert(lsys_shadow_voxel(S, 0, 6, 5) == 0.25 && lsys_shadow_voxel(S, 1, 6, 5) == 0);
  assert(lsys_shadow_voxel(S, 2, 4, 5) == 0.0625 && lsys_shadow_voxel(S, 3, 4, 5) == 0);
  lsys_shadow_clear(S);
  add1(S, 5.5, 16.5, 5.5, 1);                     /* 6 above the top: level 5 > depth */
  add1(S, 5.5, -0.5, 5.5, 1);                     /* below the grid: nothing */
  add1(S, 17.5, 5.5, 5.5, 1);                     /* 7 right of the last voxel */
  assert(lsys_shadow_add(S, big, NULL, 2, 2, NULL) == LSYS_OK);   /* far away */
  assert(lsys_shadow_voxel(S, 10, 5, 5) == 0);
  {
    long i;
    for (i = 0; i < (long)S->nvox; i++) assert(S->s[i] == 0);
  }
  /* the high faces belong to the grid; beyond them, shadow 0 */
  add1(S, 11, 11, 11, 1);
  assert(lsys_shadow_voxel(S, 10, 10, 10) == 1 && shadow_at(S, 11, 11, 11) == 1);
  assert(shadow_at(S, 11, 11.000001, 11) == 0 && shadow_at(S, -0.1, 5, 5) == 0);
  assert(exposure_at(S, 11, 12, 11, 1) == 2);     /* C - 0 + a */
  assert(lsys_shadow_voxel(S, 11, 10, 10) == 0 && lsys_shadow_voxel(S, -1, 0, 0) == 0);
  lsys_shadow_free(S);
}

static void tri (lsys_scene *s, const double a[3], const double b[3], const double c[3]) {
  static const double n[3] = {0, 1, 0};
  uint32_t v;
  assert(lsys_mesh_reserve(&s->mesh, 3, 1) == LSYS_OK);
  v = lsys_mesh_vertex(&s->mesh, a, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, b, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, c, n, 0, 0, 0, 1);
  lsys_mesh_tri(&s->mesh, v, v + 1, v + 2);
}

static void test_scene (void) {
  /* a right triangle of legs 2 and 3 (area 3) with its centroid at (3.5, 6.5, 2.5) */
  static const double a[3] = {2.5, 6.5, 1.5}, b[3] = {4.5, 6.5, 1.5}, c[3] = {3.5, 6.5, 4.5};
  static const double z[3] = {1, 1, 1};           /* a degenerate one: left out */
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 4, 1, 0, 1};
  lsys_scene s;
  lsys_shadow *S = grid(11, 2, NULL);
  lsys_scene_init(&s);
  assert(lsys_scene_begin_part(&s) == 0);
  tri(&s, a, b, c);
  tri(&s, z, z, z);
  lsys_scene_end_part(&s, 0);
  assert(lsys_shadow_add_scene(S, &s, 0.5, 2, NULL) == LSYS_OK);
  assert(lsys_shadow_voxel(S, 3, 6, 2) == 1.5);   /* 0.5 x area 3 over the face 1 */
  assert(lsys_shadow_voxel(S, 4, 5, 3) == 0.75 && lsys_shadow_voxel(S, 1, 4, 4) == 0.375);
  assert(lsys_shadow_voxel(S, 1, 1, 1) == 0);
  /* as two instances: the part's own place casts nothing */
  lsys_shadow_clear(S);
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  m[12] = -2;
  m[13] = 0;
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  assert(lsys_shadow_add_scene(S, &s, 1, 1, NULL) == LSYS_OK);
  assert(lsys_shadow_voxel(S, 3, 6, 2) == 0);
  assert(lsys_shadow_voxel(S, 7, 7, 2) == 3 && lsys_shadow_voxel(S, 1, 6, 2) == 3);
  lsys_shadow_free(S);
  lsys_scene_free(&s);
}

static uint64_t rs = 88172645463325252ull;
static double rnd (void) {                        /* xorshift64, in [0, 1) */
  rs ^= rs << 13; rs ^= rs >> 7; rs ^= rs << 17;
  return (double)(rs >> 11) / 9007199254740992.0;
}

/* Random casters (some outside the grid) against a direct sum, and 1, 2 and 3
** threads giving the same bits, for adding and for the directions. */
static void test_threads (void) {
  enum { N = 3000, NQ = 500 };
  static double p[3 * N], w[N], q[3 * NQ], h[3 * NQ], d1[3 * NQ], d2[3 * NQ], d3[3 * NQ];
  lsys_shadow_opts o;
  lsys_shadow *S1, *S2, *S3;
  long i, j, k, differ = 0;
  size_t t;
  lsys_shadow_defaults(&o);
  o.lo[0] = -3; o.lo[1] = 0; o.lo[2] = -2;
  o.hi[0] = 9; o.hi[1] = 10; o.hi[2] = 7;
  o.voxel = 0.7;
  o.depth = 5;
  o.b = 1.7;
  for (t = 0; t < N; t++) {
    p[3 * t] = -5 + 16 * rnd();
    p[3 * t + 1] = -1 + 14 * rnd();
    p[3 * t + 2] = -4 + 13 * rnd();
    w[t] = 0.1 + rnd();
  }
  for (t = 0; t < NQ; t++) {
    q[3 * t] = -3 + 12 * rnd(); q[3 * t + 1] = 10 * rnd(); q[3 * t + 2] = -2 + 9 * rnd();
    h[3 * t] = rnd() - 0.5; h[3 * t + 1] = rnd(); h[3 * t + 2] = rnd() - 0.5;
  }
  assert(lsys_shadow_new(&S1, &o, NULL) == LSYS_OK);
  assert(lsys_shadow_new(&S2, &o, NULL) == LSYS_OK);
  assert(lsys_shadow_new(&S3, &o, NULL) == LSYS_OK);
  assert(lsys_shadow_add(S1, p, w, N, 1, NULL) == LSYS_OK);
  assert(lsys_shadow_add(S2, p, w, N, 2, NULL) == LSYS_OK);
  assert(lsys_shadow_add(S3, p, w, N, 3, NULL) == LSYS_OK);
  assert(memcmp(S1->s, S2->s, S1->nvox * sizeof(double)) == 0);
  assert(memcmp(S1->s, S3->s, S1->nvox * sizeof(double)) == 0);
  for (j = 0; j < S1->n[1]; j++)                   /* the direct sum, caster by caster */
    for (k = 0; k < S1->n[2]; k++)
      for (i = 0; i < S1->n[0]; i++) {
        double v = 0;
        for (t = 0; t < N; t++) {
          long I = (long)floor((p[3 * t] + 3) / 0.7), J = (long)floor(p[3 * t + 1] / 0.7);
          long K = (long)floor((p[3 * t + 2] + 2) / 0.7), qq = J - j;
          if (qq >= 0 && qq <= 5 && labs(i - I) <= qq && labs(k - K) <= qq)
            v += w[t] * pow(1.7, (double)-qq);
        }
        assert(NEAR(v, lsys_shadow_voxel(S1, i, j, k), 1e-12 * (1 + v)));
        differ += v != 0;
      }
  assert(differ > (long)S1->nvox / 2);            /* the casters cover most of the grid */
  assert(lsys_shadow_direction(S1, q, h, NQ, 60, 2.5, d1, 1, NULL) == LSYS_OK);
  assert(lsys_shadow_direction(S1, q, h, NQ, 60, 2.5, d2, 2, NULL) == LSYS_OK);
  assert(lsys_shadow_direction(S1, q, h, NQ, 60, 2.5, d3, 3, NULL) == LSYS_OK);
  assert(memcmp(d1, d2, sizeof d1) == 0 && memcmp(d1, d3, sizeof d1) == 0);
  for (t = 0; t < NQ; t++) {                      /* unit, and within the cone */
    double len = sqrt(h[3 * t] * h[3 * t] + h[3 * t + 1] * h[3 * t + 1] +
                      h[3 * t + 2] * h[3 * t + 2]);
    double cs = (d1[3 * t] * h[3 * t] + d1[3 * t + 1] * h[3 * t + 1] +
                 d1[3 * t + 2] * h[3 * t + 2]) / len;
    assert(NEAR(d1[3 * t] * d1[3 * t] + d1[3 * t + 1] * d1[3 * t + 1] +
                d1[3 * t + 2] * d1[3 * t + 2], 1, 1e-12));
    assert(cs >= 0.5 - 1e-12);
  }
  lsys_shadow_free(S1);
  lsys_shadow_free(S2);
  lsys_shadow_free(S3);
}

static void test_errors (void) {
  lsys_shadow_opts o;
  lsys_shadow *S = (lsys_shadow *)&o;
  lsys_meter mt = {1000, 0, 0, NULL};
  lsys_error e;
  double p[6] = {1, 1, 1, 1, NAN, 1}, w[2] = {1, INFINITY}, h[6] = {0, 1, 0, 0, 0, 0};
  double out[6];
  char msg[32], want[128];
  lsys_shadow_defaults(&o);
  o.voxel = 0;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG && S == NULL);
  assert(strcmp(e.msg, "shadow: voxel must be a finite number > 0") == 0);
  lsys_shadow_defaults(&o);
  o.lo[1] = 2;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: lo must not be above hi (on y: 2 > 1)") == 0);
  lsys_shadow_defaults(&o);
  o.hi[2] = INFINITY;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: lo and hi must be finite") == 0);
  lsys_shadow_defaults(&o);
  o.depth = LSYS_SHADOW_MAXDEPTH + 1;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: depth must be an integer in [0, 64]") == 0);
  lsys_shadow_defaults(&o);
  o.a = 0;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: a must be a finite number > 0") == 0);
  lsys_shadow_defaults(&o);
  o.b = 1;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: b must be a finite number > 1") == 0);
  /* too big: along an axis, and for the meter (which is left as it was) */
  lsys_shadow_defaults(&o);
  o.hi[0] = 1e9;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EMEMORY);
  assert(strcmp(e.msg, "shadow: a grid of 1000000000 x 1 x 1 voxels is too big (at most "
                "16777216 along an axis)") == 0);
  lsys_shadow_defaults(&o);
  o.hi[0] = o.hi[1] = o.hi[2] = 10;
  o.meter = &mt;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EMEMORY && S == NULL && mt.hit && mt.used == 0);
  assert(strcmp(e.msg, "shadow: the grid of 10 x 10 x 10 voxels needs 8 KiB, more than "
                "max_memory (1000 bytes)") == 0);
  o.hi[0] = o.hi[1] = o.hi[2] = 1e7;                /* 8e21 bytes */
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_EMEMORY);
  assert(strcmp(e.msg, "shadow: a grid of 10000000 x 10000000 x 10000000 voxels is too big "
                "for max_memory (1000 bytes)") == 0);
  /* the grid fits, an add's blocks do not; the meter counts the grid while it lives */
  mt.limit = 8000 + sizeof(lsys_shadow) + 100;
  mt.hit = 0;
  o.hi[0] = o.hi[1] = o.hi[2] = 10;
  assert(lsys_shadow_new(&S, &o, &e) == LSYS_OK);
  assert(mt.used == 8000 + sizeof(lsys_shadow));
  assert(lsys_shadow_add(S, p, NULL, 1, 1, &e) == LSYS_EMEMORY && mt.hit);
  lsys_common_fmtsize(msg, mt.limit);          /* the blocks: 1 caster, 10 + 4 + 1 layers */
  snprintf(want, sizeof want, "shadow: adding the casters needs 136 bytes more, beyond "
           "max_memory (%s)", msg);
  assert(strcmp(e.msg, want) == 0);
  assert(mt.used == 8000 + sizeof(lsys_shadow) && lsys_shadow_voxel(S, 1, 1, 1) == 0);
  mt.limit = 1 << 20;
  assert(lsys_shadow_add(S, p, NULL, 1, 1, &e) == LSYS_OK);
  assert(lsys_shadow_voxel(S, 1, 1, 1) == 1 && mt.used == 8000 + sizeof(lsys_shadow));
  /* bad input: named, nothing added or written */
  assert(lsys_shadow_add(S, p, NULL, 2, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: point 2 is not finite") == 0 && lsys_shadow_voxel(S, 1, 1, 1)
         == 1);
  p[4] = 1;
  assert(lsys_shadow_add(S, p, w, 2, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: weight 2 is not finite") == 0);
  assert(lsys_shadow_direction(S, p, h, 2, 90, 2, out, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: heading 2 is not a finite non-zero vector") == 0);
  assert(lsys_shadow_direction(S, p, h, 1, 0, 2, out, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: the angle must be a number of degrees in (0, 180]") == 0);
  assert(lsys_shadow_direction(S, p, h, 1, 90, 33, out, 1, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: the radius must be a number of voxels in (0, 32]") == 0);
  assert(lsys_shadow_query(S, p, 1, 1, NAN, out, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "shadow: C must be a finite number") == 0);
  {
    double lo[3] = {1, 1, 1}, hi[3] = {2, 0, 2};
    assert(lsys_shadow_add_box(S, lo, hi, 1, &e) == LSYS_EARG);
    assert(strcmp(e.msg, "shadow: the box's low corner must not be above its high one "
                  "(on y: 1 > 0)") == 0);
    hi[1] = 2;
    assert(lsys_shadow_add_box(S, lo, hi, NAN, &e) == LSYS_EARG);
    assert(strcmp(e.msg, "shadow: the box's value must be finite") == 0);
  }
  lsys_shadow_free(S);
  assert(mt.used == 0);
}

/* Every allocation of making, adding and adding a scene fails in turn: a
** clean error, nothing left. */
static void test_nomem (void) {
  static const double a[3] = {1, 2, 1}, b[3] = {2, 2, 1}, c[3] = {1, 2, 2};
  double p[9] = {1, 1, 1, 2, 3, 2, 0.5, 2.5, 3};
  lsys_scene s;
  long k, n;
  lsys_scene_init(&s);
  tri(&s, a, b, c);
  for (k = 0;; k++) {
    lsys_shadow *S = NULL;
    long live = nlive;
    int st;
    nalloc = 0;
    failat = k;
    st = lsys_shadow_new(&S, NULL, NULL);
    if (st == LSYS_OK) st = lsys_shadow_add(S, p, NULL, 3, 2, NULL);
    if (st == LSYS_OK) st = lsys_shadow_add_scene(S, &s, 1, 2, NULL);
    assert(st == LSYS_OK || st == LSYS_ENOMEM);
    lsys_shadow_free(S);
    n = nalloc;
    failat = -1;
    assert(nlive == live);
    if (k > n) break;
  }
  assert(n >= 6);
  lsys_scene_free(&s);
}

int main (void) {
  test_pyramid();
  test_params();
  test_direction();
  test_box();
  test_outside();
  test_scene();
  test_threads();
  test_errors();
  test_nomem();
  printf("test_shadow: ok\n");
  return 0;
}
