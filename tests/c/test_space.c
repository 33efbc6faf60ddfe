/*
** C unit tests for space (space.h): counts, nearest distances and
** densities on hand-made points, itself left out and not a twin; Honda's
** collision rule on hand-made cases; every query against testing every
** pair, on random points with a radius of one cell and of several, with 1
** and 3 threads giving the same bits; the scene's points and the offset;
** markers associated with the nearest bud that perceives them (within the
** radius and the cone), killed for good, their directions, against a
** brute-force reference and on every number of threads; the resource field's
** diffusion (spelled out on a row, kept on a grid, the same on every number
** of threads), takes shared in proportion, sources and gradients; bad
** options, the memory budget, and every allocation failing in turn.
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
#include "space.c"
#include "space_markers.c"
#include "space_field.c"

#define NEAR(a, b, eps) (fabs((double)(a) - (double)(b)) <= (eps))

static lsys_space *build (const double *p, size_t n, double r, const int64_t *g,
                          const double *v) {
  lsys_space_opts o;
  lsys_space *S;
  lsys_error e;
  int st;
  memset(&o, 0, sizeof o);
  o.radius = r;
  o.groups = g;
  o.vigour = v;
  st = lsys_space_build(&S, p, n, &o, &e);
  if (st != LSYS_OK) fprintf(stderr, "build: %d %s\n", st, e.msg);
  assert(st == LSYS_OK && S != NULL);
  return S;
}

/* Query 'kind' of the space's own points (points NULL) or of n points, radius r. */
static void ask (const lsys_space *S, int kind, const double *pts, size_t n, double r,
                 int threads, double *out) {
  lsys_space_ask q;
  lsys_error e;
  int st;
  memset(&q, 0, sizeof q);
  q.kind = kind;
  q.radius = r;
  q.points = pts;
  q.n = n;
  q.threads = threads;
  st = lsys_space_query(S, &q, out, &e);
  if (st != LSYS_OK) fprintf(stderr, "query: %d %s\n", st, e.msg);
  assert(st == LSYS_OK);
}

static void test_counts (void) {
  /* a row along x: 0, 0.5, 1.2, 1.2 (twins), 3; and one off the row */
  static const double p[] = {0, 0, 0, 0.5, 0, 0, 1.2, 0, 0, 1.2, 0, 0, 3, 0, 0, 0, 0, 0.9};
  static const double q[] = {0.6, 0, 0, 10, 10, 10, -0.1, 0, 0};
  double out[6];
  lsys_space_stats st;
  lsys_space *S = build(p, 6, 1, NULL, NULL);
  lsys_space_info(S, &st);
  assert(st.points == 6 && st.listed == 6 && st.cells == 3 && st.radius == 1 && st.bytes > 0);
  ask(S, LSYS_SPACE_COUNT, NULL, 0, 0, 1, out);
  assert(out[0] == 2 && out[1] == 3 && out[2] == 2 && out[3] == 2 && out[4] == 0 &&
         out[5] == 1);                                   /* twins count each other */
  ask(S, LSYS_SPACE_COUNT, NULL, 0, 2, 1, out);          /* two cells on each side */
  assert(out[0] == 4 && out[1] == 4 && out[2] == 5 && out[3] == 5 && out[4] == 2 &&
         out[5] == 4);
  ask(S, LSYS_SPACE_COUNT, q, 3, 0, 1, out);             /* points of the caller's */
  assert(out[0] == 4 && out[1] == 0 && out[2] == 3);
  ask(S, LSYS_SPACE_NEAREST, NULL, 0, 0, 1, out);
  assert(out[0] == 0.5 && out[1] == 0.5 && out[2] == 0 && out[3] == 0 &&
         out[4] == HUGE_VAL && out[5] == 0.9);
  ask(S, LSYS_SPACE_NEAREST, q, 3, 0, 1, out);
  assert(NEAR(out[0], 0.1, 1e-15) && out[1] == HUGE_VAL && NEAR(out[2], 0.1, 1e-15));
  ask(S, LSYS_SPACE_DENSITY, NULL, 0, 0, 1, out);        /* (1 - d^2 / r^2)^2 each */
  assert(NEAR(out[0], 0.5625 + 0.19 * 0.19, 1e-15) && out[4] == 0);
  lsys_space_free(S);
  S = build(p, 0, 1, NULL, NULL);                        /* empty */
  ask(S, LSYS_SPACE_NEAREST, q, 3, 0, 2, out);
  assert(out[0] == HUGE_VAL && out[2] == HUGE_VAL);
  lsys_space_free(S);
}

/* The density of point 1 above, spelled out: 0 at distance 0.5, 1.2 (twice) at
** 0.7, (0, 0, 0.9) at sqrt(0.25 + 0.81) > 1: out of reach. */
static void test_density (void) {
  static const double p[] = {0, 0, 0, 0.5, 0, 0, 1.2, 0, 0, 1.2, 0, 0, 0, 0, 0.9};
  double out[5], a = 1 - 0.25, b = 1 - 0.7 * 0.7;
  lsys_space *S = build(p, 5, 1, NULL, NULL);
  ask(S, LSYS_SPACE_DENSITY, NULL, 0, 0, 1, out);
  assert(NEAR(out[1], a * a + 2 * b * b, 1e-12));
  ask(S, LSYS_SPACE_DENSITY, p, 1, 0, 1, out);            /* the origin asks: itself is 1 */
  assert(NEAR(out[0], 1 + a * a + pow(1 - 0.81, 2), 1e-12));
  lsys_space_free(S);
}

/* collision.lua's cases: the weaker stops, the stronger goes on; other groups never
** meet; one vigour within the radius: both stop; just beyond it: both go on. */
static void test_free (void) {
  static const double p[] = {0, 0, 0, 0.3, 0, 0, 5, 5, 0, 5.2, 5, 0, 9, 0, 0, 9, 0.5, 0,
                             20, 0, 0, 20.51, 0, 0, 30, 0, 0, 30.1, 0, 0};
  static const int64_t g[] = {0, 0, 0, 1, 0, 0, 0, 0, 0, 0};
  double v[] = {1, 2, 1, 1, 1, 1, 1, 1, NAN, 1}, out[10], q[3] = {0.1, 0, 0};
  int64_t qg = 0;
  double qv = 2;
  lsys_space_ask a;
  lsys_space *S = build(p, 10, 0.5, g, v);
  ask(S, LSYS_SPACE_FREE, NULL, 0, 0, 1, out);
  assert(out[0] == 0 && out[1] == 1 && out[2] == 1 && out[3] == 1 && out[4] == 0 &&
         out[5] == 0 && out[6] == 1 && out[7] == 1);
  assert(out[8] == 1 && out[9] == 1);                    /* NaN: nobody's match (<= fails) */
  memset(&a, 0, sizeof a);                               /* a caller's point, vigour 2 */
  a.kind = LSYS_SPACE_FREE;
  a.points = q;
  a.n = 1;
  a.groups = &qg;
  a.vigour = &qv;
  assert(lsys_space_query(S, &a, out, NULL) == LSYS_OK && out[0] == 0);
  qv = 2.5;
  assert(lsys_space_query(S, &a, out, NULL) == LSYS_OK && out[0] == 1);
  qg = 1;
  qv = 0;
  assert(lsys_space_query(S, &a, out, NULL) == LSYS_OK && out[0] == 1);
  lsys_space_free(S);
}

static uint64_t rs = 88172645463325252ull;
static double rnd (void) {                        /* xorshift64, in [0, 1) */
  rs ^= rs << 13; rs ^= rs >> 7; rs ^= rs << 17;
  return (double)(rs >> 11) / 9007199254740992.0;
}

/* What a query answers, testing every point. */
static double brute (const double *p, size_t n, const int64_t *g, const double *v, int kind,
                     const double x[3], size_t self, int64_t xg, double xv, double r) {
  double acc = kind == LSYS_SPACE_NEAREST ? HUGE_VAL : 0, r2 = r * r;
  size_t j;
  for (j = 0; j < n; j++) {
    double ex = x[0] - p[3 * j], ey = x[1] - p[3 * j + 1], ez = x[2] - p[3 * j + 2];
    double d2 = ex * ex + ey * ey + ez * ez;
    if (j == self || !(d2 <= r2)) continue;
    if (kind == LSYS_SPACE_COUNT) acc += 1;
    else if (kind == LSYS_SPACE_DENSITY) acc += (1 - d2 / r2) * (1 - d2 / r2);
    else if (kind == LSYS_SPACE_NEAREST) { if (d2 < acc) acc = d2; }
    else if (g[j] == xg && xv <= v[j]) return 0;
  }
  if (kind == LSYS_SPACE_FREE) return 1;
  return kind == LSYS_SPACE_NEAREST && acc < HUGE_VAL ? sqrt(acc) : acc;
}

static void test_brute (void) {
  enum { N = 3000, Q = 500 };
  static double p[3 * N], v[N], q[3 * Q], o1[N], o3[N];
  static int64_t g[N];
  static const double radii[] = {0.3, 0.21, 0.7};
  size_t i;
  int kind, k, busy = 0;
  lsys_space *S;
  for (i = 0; i < N; i++) {
    int c;
    for (c = 0; c < 3; c++) p[3 * i + c] = 4 * rnd() - 1;
    if (i > 0 && i % 7 == 0) memcpy(p + 3 * i, p + 3 * (i / 2), 3 * sizeof(double));   /* twins */
    g[i] = (int64_t)(3 * rnd()) - 1;
    v[i] = floor(4 * rnd());
  }
  for (i = 0; i < 3 * Q; i++) q[i] = 5 * rnd() - 1.5;
  S = build(p, N, 0.3, g, v);
  for (k = 0; k < 3; k++)
    for (kind = LSYS_SPACE_COUNT; kind <= LSYS_SPACE_FREE; kind++) {
      ask(S, kind, NULL, 0, radii[k], 1, o1);
      ask(S, kind, NULL, 0, radii[k], 3, o3);
      assert(memcmp(o1, o3, sizeof o1) == 0);
      for (i = 0; i < N; i++) {
        double b = brute(p, N, g, v, kind, p + 3 * i, i, g[i], v[i], radii[k]);
        if (kind == LSYS_SPACE_DENSITY) assert(NEAR(o1[i], b, 1e-12));
        else assert(o1[i] == b);
        busy += kind == LSYS_SPACE_COUNT && o1[i] > 2;
      }
      ask(S, kind, q, Q, radii[k], 2, o1);
      for (i = 0; i < Q; i++) {
        double b = brute(p, N, g, v, kind, q + 3 * i, N, 0, 0, radii[k]);
        if (kind == LSYS_SPACE_DENSITY) assert(NEAR(o1[i], b, 1e-12));
        else assert(o1[i] == b);
      }
    }
  assert(busy > N / 2);                           /* crowded enough to be worth a test */
  lsys_space_free(S);
}

/* A segment (0, 0, 0) -> (0, 1, 0) and the triangle (3, 0, 0), (6, 0, 0), (3, 3, 0)
** into s: its points are (0, 1, 0) and the centroid (4, 1, 0). */
static void drawing (lsys_scene *s) {
  static const double a[3] = {0, 0, 0}, b[3] = {0, 1, 0}, n[3] = {0, 0, 1};
  static const double c0[3] = {3, 0, 0}, c1[3] = {6, 0, 0}, c2[3] = {3, 3, 0};
  uint32_t v;
  assert(lsys_mesh_line(&s->mesh, a, b, 1, 1, 0) == LSYS_OK);
  assert(lsys_mesh_reserve(&s->mesh, 3, 1) == LSYS_OK);
  v = lsys_mesh_vertex(&s->mesh, c0, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, c1, n, 0, 0, 0, 1);
  lsys_mesh_vertex(&s->mesh, c2, n, 0, 0, 0, 1);
  lsys_mesh_tri(&s->mesh, v, v + 1, v + 2);
}

/* A scene's points: each segment's end, each triangle's centroid, placed by
** instances; of group 0 and an infinite vigour; left out nearer than the offset. */
static void test_scene (void) {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 10, 1};
  double p[3] = {0, 1.05, 0}, out[2];
  lsys_scene s;
  lsys_space_opts o;
  lsys_space_ask q;
  lsys_space_stats st;
  lsys_space *S;
  lsys_scene_init(&s);
  drawing(&s);
  assert(lsys_space_scenepoints(&s) == 2);
  memset(&o, 0, sizeof o);
  o.radius = 0.5;
  o.scene = &s;
  assert(lsys_space_build(&S, p, 1, &o, NULL) == LSYS_OK);
  lsys_space_info(S, &st);
  assert(st.points == 3 && st.listed == 1);
  memset(&q, 0, sizeof q);
  q.kind = LSYS_SPACE_NEAREST;
  q.threads = 1;
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && NEAR(out[0], 0.05, 1e-9));
  q.kind = LSYS_SPACE_FREE;                       /* the segment's end: an obstacle */
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && out[0] == 0);
  q.offset = 0.1;                                 /* the end it stands on left out */
  q.kind = LSYS_SPACE_COUNT;
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && out[0] == 0);
  p[0] = 4; p[1] = 1; p[2] = 0;                   /* the triangle's centroid */
  q.points = p;
  q.n = 1;
  q.offset = 0;
  q.kind = LSYS_SPACE_NEAREST;
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && out[0] == 0);
  lsys_space_free(S);
  lsys_scene_free(&s);
  lsys_scene_init(&s);                            /* the same as a part, drawn twice */
  assert(lsys_scene_begin_part(&s) == 0);
  drawing(&s);
  lsys_scene_end_part(&s, 0);
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  m[14] = 20;
  assert(lsys_scene_add_instance(&s, 0, m) == LSYS_OK);
  assert(lsys_space_scenepoints(&s) == 4);
  assert(lsys_space_build(&S, NULL, 0, &o, NULL) == LSYS_OK);
  lsys_space_info(S, &st);
  assert(st.points == 4 && st.listed == 0);
  p[0] = 4; p[1] = 1; p[2] = 20;
  q.kind = LSYS_SPACE_COUNT;
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && out[0] == 1);
  p[2] = 0;                                       /* the part's own place: nothing drawn */
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && out[0] == 0);
  p[0] = 0; p[1] = 1; p[2] = 10.2;
  q.kind = LSYS_SPACE_NEAREST;
  assert(lsys_space_query(S, &q, out, NULL) == LSYS_OK && NEAR(out[0], 0.2, 1e-6));
  lsys_space_free(S);
  lsys_scene_free(&s);
}

/* ---------------------------------------------------------------------- */
/* markers */

static lsys_markers *markers (const double *p, size_t n, lsys_meter *mt) {
  lsys_markers *M;
  lsys_error e;
  int st = lsys_space_markers_new(&M, p, n, mt, &e);
  if (st != LSYS_OK) fprintf(stderr, "markers: %d %s\n", st, e.msg);
  assert(st == LSYS_OK);
  return M;
}

static void perceive (lsys_markers *M, const double *b, const double *h, size_t nb,
                      double per, double angle, double kill, int threads, size_t *cnt,
                      double *dir) {
  lsys_markers_opts o;
  lsys_error e;
  int st;
  o.perception = per;
  o.angle = angle;
  o.kill = kill;
  o.threads = threads;
  st = lsys_space_markers_perceive(M, b, h, nb, &o, cnt, dir, &e);
  if (st != LSYS_OK) fprintf(stderr, "perceive: %d %s\n", st, e.msg);
  assert(st == LSYS_OK);
}

/*
** Two buds at (0, 0, 0) heading +y and (2, 0, 0) heading +x; markers:
**   0 (0, 1, 0)    bud 0's only (bud 1 is 2.2 away);       1 (1.2, 0, 0)  nearer bud 1
**   2 (1, 0, 0)    as near each: the first, bud 0;          3 (0, -1, 0)   behind bud 0
**   4 (2.1, 0, 0)  within bud 1's kill radius: removed;     5 (9, 9, 9)    out of reach
*/
static void test_markers (void) {
  static const double m[] = {0, 1, 0, 1.2, 0, 0, 1, 0, 0, 0, -1, 0, 2.1, 0, 0, 9, 9, 9};
  static const double b[] = {0, 0, 0, 2, 0, 0}, h[] = {0, 3, 0, 1, 0, 0};
  double dir[6];
  size_t cnt[2], removed;
  const double *left;
  lsys_markers *M = markers(m, 6, NULL);
  perceive(M, b, h, 2, 1.5, 180, 0.2, 1, cnt, dir);   /* the whole sphere */
  assert(lsys_space_markers_count(M) == 5);
  assert(cnt[0] == 3 && cnt[1] == 1);                /* markers 0, 2, 3; marker 1 */
  assert(NEAR(dir[0], 1, 1e-15) && dir[1] == 0 && dir[2] == 0);   /* (0,1)+(1,0)+(0,-1) */
  assert(dir[3] == -1 && dir[4] == 0 && dir[5] == 0);
  left = lsys_space_markers_points(M);                     /* the order kept, 4 gone */
  assert(left[9] == 0 && left[10] == -1 && left[12] == 9);
  perceive(M, b, h, 2, 1.5, 90, 0, 3, cnt, dir);     /* cones: the half-space ahead */
  assert(cnt[0] == 3 && cnt[1] == 0);                /* 0, 1 and 2 (at 90 degrees) bud 0's: */
  assert(NEAR(dir[0], 2 / sqrt(5.0), 1e-15) && NEAR(dir[1], 1 / sqrt(5.0), 1e-15) &&
         dir[2] == 0 && dir[3] == 0 && dir[4] == 0);  /* 1 is behind bud 1 */
  perceive(M, b, h, 2, 1.5, 89, 0, 1, cnt, dir);     /* narrower: marker 0 only */
  assert(cnt[0] == 1 && cnt[1] == 0);
  assert(dir[0] == 0 && dir[1] == 1 && dir[2] == 0);
  assert(lsys_space_markers_count(M) == 5);
  assert(lsys_space_markers_remove(M, b, 2, 1.05, 2, &removed, NULL) == LSYS_OK);
  assert(removed == 4 && lsys_space_markers_count(M) == 1);   /* 0, 1, 2, 3 within 1.05 */
  perceive(M, b, h, 2, 1.5, 180, 0, 1, cnt, dir);
  assert(cnt[0] == 0 && cnt[1] == 0 && dir[0] == 0 && dir[3] == 0);
  lsys_space_markers_free(M);
}

/* What fate1 finds, testing every bud. */
static size_t brutefate (const double *x, const double *b, const double *h, size_t nb,
                         double per, double cosa, double kill) {
  size_t k, best = (size_t)-1;
  double bd2 = HUGE_VAL;
  for (k = 0; k < nb; k++) {
    double v[3] = {x[0] - b[3 * k], x[1] - b[3 * k + 1], x[2] - b[3 * k + 2]}, d2, len;
    d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (d2 <= kill * kill) return (size_t)-2;
    len = sqrt(h[3 * k] * h[3 * k] + h[3 * k + 1] * h[3 * k + 1] + h[3 * k + 2] * h[3 * k + 2]);
    if (d2 > per * per || d2 == 0 || !(d2 < bd2)) continue;
    if ((v[0] * h[3 * k] / len + v[1] * h[3 * k + 1] / len + v[2] * h[3 * k + 2] / len) <
        cosa * sqrt(d2)) continue;
    best = k;
    bd2 = d2;
  }
  return best;
}

static void test_markers_brute (void) {
  enum { NM = 4000, NB = 300 };
  static double m[3 * NM], b[3 * NB], h[3 * NB], dir1[3 * NB], dir3[3 * NB], ref[3 * NB];
  static size_t c1[NB], c3[NB], cref[NB];
  const double cosa = cos(60 * 3.14159265358979323846 / 180);
  size_t i, k, left = 0, perceived = 0;
  lsys_markers *M1, *M3;
  for (i = 0; i < 3 * NM; i++) m[i] = 10 * rnd();
  for (i = 0; i < 3 * NB; i++) { b[i] = 10 * rnd(); h[i] = rnd() - 0.5; }
  memset(cref, 0, sizeof cref);
  memset(ref, 0, sizeof ref);
  for (i = 0; i < NM; i++) {
    size_t f = brutefate(m + 3 * i, b, h, NB, 1.5, cosa, 0.3);
    if (f == (size_t)-2) continue;
    left++;
    if (f == (size_t)-1) continue;
    cref[f]++;
    perceived++;
    {
      double v[3] = {m[3 * i] - b[3 * f], m[3 * i + 1] - b[3 * f + 1], m[3 * i + 2] - b[3 * f + 2]};
      double d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (k = 0; k < 3; k++) ref[3 * f + k] += v[k] / d;
    }
  }
  assert(left < NM && perceived > NM / 4);
  M1 = markers(m, NM, NULL);
  M3 = markers(m, NM, NULL);
  perceive(M1, b, h, NB, 1.5, 60, 0.3, 1, c1, dir1);
  perceive(M3, b, h, NB, 1.5, 60, 0.3, 3, c3, dir3);
  assert(lsys_space_markers_count(M1) == left && lsys_space_markers_count(M3) == left);
  assert(memcmp(c1, c3, sizeof c1) == 0 && memcmp(dir1, dir3, sizeof dir1) == 0);
  assert(memcmp(lsys_space_markers_points(M1), lsys_space_markers_points(M3),
                3 * left * sizeof(double)) == 0);
  for (k = 0; k < NB; k++) {
    double *r = ref + 3 * k, len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    assert(c1[k] == cref[k]);
    if (len > 0)
      assert(NEAR(dir1[3 * k], r[0] / len, 1e-12) && NEAR(dir1[3 * k + 1], r[1] / len, 1e-12) &&
             NEAR(dir1[3 * k + 2], r[2] / len, 1e-12));
  }
  lsys_space_markers_free(M1);
  lsys_space_markers_free(M3);
}

static void test_errors (void) {
  static const double p[] = {0, 0, 0, 1, 1, 1}, z[] = {0, 0, 0};
  double bad[3] = {0, NAN, 0}, out[2];
  lsys_space_opts o;
  lsys_space_ask q;
  lsys_markers_opts mo = {1, 90, 0, 1};
  lsys_meter mt = {100, 0, 0, NULL};
  lsys_space *S = (lsys_space *)&o;
  lsys_markers *M;
  lsys_error e;
  size_t cnt[1];
  memset(&o, 0, sizeof o);
  assert(lsys_space_build(&S, p, 2, &o, &e) == LSYS_EARG && S == NULL);
  assert(strcmp(e.msg, "space: the radius must be a finite number > 0") == 0);
  o.radius = 1;
  assert(lsys_space_build(&S, bad, 1, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "space: point 1 is not finite") == 0);
  bad[1] = 1e300;
  assert(lsys_space_build(&S, bad, 1, &o, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "space: point 1 is too far from the origin for the radius") == 0);
  o.meter = &mt;
  assert(lsys_space_build(&S, p, 2, &o, &e) == LSYS_EMEMORY && mt.hit && mt.used == 0);
  assert(strncmp(e.msg, "space: ", 7) == 0 && strstr(e.msg, "more than max_memory (100 "
                                                      "bytes)") != NULL);
  mt.limit = 1 << 20;
  S = build(p, 2, 1, NULL, NULL);
  o.meter = NULL;
  memset(&q, 0, sizeof q);
  q.kind = 7;
  assert(lsys_space_query(S, &q, out, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "space: no such query") == 0);
  q.kind = LSYS_SPACE_COUNT;
  q.radius = 17;
  assert(lsys_space_query(S, &q, out, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "space: the radius must be a number in (0, 16] (16 times the "
                "space's)") == 0);
  q.radius = 16;
  assert(lsys_space_query(S, &q, out, &e) == LSYS_OK && out[0] == 1 && out[1] == 1);
  q.points = bad;
  q.n = 1;
  bad[1] = INFINITY;
  assert(lsys_space_query(S, &q, out, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "space: query point 1 is not finite") == 0);
  lsys_space_free(S);
  assert(lsys_space_markers_new(&M, bad, 1, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: marker 1 is not finite") == 0);
  mt.used = 0;
  mt.limit = 10;
  assert(lsys_space_markers_new(&M, p, 2, &mt, &e) == LSYS_EMEMORY);
  mt.limit = 1 << 20;
  M = markers(p, 2, &mt);
  assert(mt.used == M->bytes);
  assert(lsys_space_markers_perceive(M, z, z, 1, &mo, cnt, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: heading 1 is not a finite non-zero vector") == 0);
  assert(lsys_space_markers_perceive(M, bad, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: bud 1 is not finite") == 0);
  mo.angle = 0;
  assert(lsys_space_markers_perceive(M, z, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: the angle must be a number of degrees in (0, 180]") == 0);
  mo.angle = 90;
  mo.kill = -1;
  assert(lsys_space_markers_perceive(M, z, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_EARG);
  mo.kill = 0;
  mo.perception = 0;
  assert(lsys_space_markers_perceive(M, z, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: the perception radius must be a finite number > 0") == 0);
  mo.perception = 2;
  assert(lsys_space_markers_count(M) == 2);             /* nothing changed by the failures */
  assert(lsys_space_markers_perceive(M, z, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_OK);
  assert(cnt[0] == 1 && mt.used == M->bytes);     /* the scratch given back */
  mt.limit = M->bytes + 8;                        /* no room for the pass's scratch */
  assert(lsys_space_markers_perceive(M, z, p + 3, 1, &mo, cnt, NULL, &e) == LSYS_EMEMORY);
  assert(strstr(e.msg, "more than max_memory") != NULL && mt.used == M->bytes);
  assert(lsys_space_markers_remove(M, z, 1, 0, 1, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "markers: the radius must be a finite number > 0") == 0);
  lsys_space_markers_free(M);
  assert(mt.used == 0);
}

/* ---------------------------------------------------------------------- */
/* the resource field */

static lsys_field *field (double x0, double y0, double z0, double x1, double y1, double z1,
                          double h) {
  double lo[3] = {x0, y0, z0}, hi[3] = {x1, y1, z1};
  lsys_field *F;
  lsys_error e;
  int st = lsys_space_field_new(&F, lo, hi, h, NULL, &e);
  if (st != LSYS_OK) fprintf(stderr, "field: %d %s\n", st, e.msg);
  assert(st == LSYS_OK);
  return F;
}

/* A row of 5 cells: D t / h^2 = 1 takes 2 substeps of a = 1/2, spelled out. */
static void test_field_row (void) {
  lsys_field *F = field(0, 0, 0, 2.5, 0, 0, 0.5);
  size_t n[3];
  double *q = lsys_space_field_values(F), g[3], p[3] = {0.25, 0, 0};
  long m;
  assert(lsys_space_field_dims(F, n) == 0.5 && n[0] == 5 && n[1] == 1 && n[2] == 1);
  assert(q[0] == 0 && q[4] == 0);
  q[2] = 1;
  assert(lsys_space_field_diffuse(F, 0.25, 1, 1, &m, NULL) == LSYS_OK && m == 2);
  q = lsys_space_field_values(F);                  /* the buffers swap */
  assert(q[0] == 0.25 && q[1] == 0 && q[2] == 0.5 && q[3] == 0 && q[4] == 0.25);
  assert(lsys_space_field_total(F) == 1);
  lsys_space_field_gradient(F, p, g);              /* one-sided at a face */
  assert(g[0] == -0.5 && g[1] == 0 && g[2] == 0);
  p[0] = 1.75;                                     /* central: (q4 - q2) / 2h */
  lsys_space_field_gradient(F, p, g);
  assert(g[0] == -0.25);
  p[0] = 2.6;
  lsys_space_field_gradient(F, p, g);
  assert(g[0] == 0 && lsys_space_field_cell(F, p) == -1);
  p[0] = 2.4;
  assert(lsys_space_field_cell(F, p) == 4);
  assert(lsys_space_field_diffuse(F, 0, 1, 1, &m, NULL) == LSYS_OK && m == 0);
  lsys_space_field_free(F);
}

/* A 3D grid: the total kept, nothing negative, the same bits on 1 and 3 threads. */
static void test_field_grid (void) {
  lsys_field *A = field(0, 0, 0, 4, 3, 5, 0.25), *B = field(0, 0, 0, 4, 3, 5, 0.25);
  size_t n[3], i, cells;
  double *a, *b, total;
  long m;
  lsys_space_field_dims(A, n);
  assert(n[0] == 16 && n[1] == 12 && n[2] == 20);
  cells = n[0] * n[1] * n[2];
  a = lsys_space_field_values(A);
  b = lsys_space_field_values(B);
  for (i = 0; i < cells; i++) a[i] = b[i] = rnd() < 0.1 ? 10 * rnd() : 0;
  total = lsys_space_field_total(A);
  assert(lsys_space_field_diffuse(A, 0.3, 2, 1, &m, NULL) == LSYS_OK && m == 58);
  assert(lsys_space_field_diffuse(B, 0.3, 2, 3, NULL, NULL) == LSYS_OK);
  a = lsys_space_field_values(A);
  b = lsys_space_field_values(B);
  assert(memcmp(a, b, cells * sizeof(double)) == 0);
  assert(NEAR(lsys_space_field_total(A), total, 1e-9 * total));
  for (i = 0; i < cells; i++) assert(a[i] >= 0);
  lsys_space_field_free(A);
  lsys_space_field_free(B);
}

/* Takes: shared in proportion where a cell has too little, whole where it has enough;
** sources, and what goes below 0. */
static void test_field_take (void) {
  static const double p[] = {1.2, 0, 0, 1.3, 0, 0, 0.1, 0, 0, 9, 0, 0};
  static const double want[] = {0.4, 0.6, 0.1, 1};
  double got[4], add[2] = {1, -5}, bad[3] = {0, NAN, 0};
  lsys_field *F = field(0, 0, 0, 2.5, 0, 0, 0.5);
  double *q = lsys_space_field_values(F);
  lsys_error e;
  q[0] = 0.25;
  q[2] = 0.5;
  assert(lsys_space_field_take(F, p, want, 4, got, NULL) == LSYS_OK);
  assert(NEAR(got[0], 0.2, 1e-15) && NEAR(got[1], 0.3, 1e-15) && got[2] == 0.1 && got[3] == 0);
  assert(q[2] == 0 && NEAR(q[0], 0.15, 1e-15));
  assert(lsys_space_field_add(F, p + 6, add, 2, NULL) == 1);     /* (9, 0, 0) is outside */
  assert(NEAR(q[0], 1.15, 1e-15));
  assert(lsys_space_field_add(F, p + 3, add + 1, 1, NULL) == 1 && q[2] == 0);   /* not < 0 */
  add[0] = -1;
  assert(lsys_space_field_take(F, p, add, 1, got, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "field: amount 1 must be a finite number >= 0") == 0);
  assert(lsys_space_field_add(F, bad, add, 1, &e) == -1);
  assert(strcmp(e.msg, "field: point 1 is not finite") == 0);
  lsys_space_field_free(F);
}

static void test_field_errors (void) {
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  lsys_meter mt = {100, 0, 0, NULL};
  lsys_field *F;
  lsys_error e;
  assert(lsys_space_field_new(&F, lo, hi, 0, NULL, &e) == LSYS_EARG && F == NULL);
  assert(strcmp(e.msg, "field: the cell must be a finite number > 0") == 0);
  hi[1] = -1;
  assert(lsys_space_field_new(&F, lo, hi, 1, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "field: the box must have finite lo <= hi on each axis") == 0);
  hi[1] = 1e9;
  assert(lsys_space_field_new(&F, lo, hi, 1e-3, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "field: more than 1073741824 cells") == 0);
  hi[1] = 1;
  assert(lsys_space_field_new(&F, lo, hi, 0.1, &mt, &e) == LSYS_EMEMORY);
  assert(strstr(e.msg, "more than max_memory (100 bytes)") != NULL);
  mt.limit = 1 << 20;
  assert(lsys_space_field_new(&F, lo, hi, 0.1, &mt, &e) == LSYS_OK && mt.used == F->bytes);
  assert(lsys_space_field_diffuse(F, 1000, 1, 1, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "field: the diffusion needs 600000 substeps, more than 100000: make "
                "the cells larger") == 0);
  assert(lsys_space_field_diffuse(F, -1, 1, 1, NULL, &e) == LSYS_EARG);
  lsys_space_field_free(F);
  assert(mt.used == 0);
}

/* A build, a query, markers, a pass and a removal, as far as they go. */
static int sequence (const double *p, const double *h) {
  lsys_space *S = NULL;
  lsys_markers *M = NULL;
  lsys_space_opts o;
  lsys_space_ask q;
  lsys_markers_opts mo = {1, 120, 0.2, 2};
  double out[200], dir[60];
  size_t cnt[20];
  int st;
  memset(&o, 0, sizeof o);
  o.radius = 0.5;
  memset(&q, 0, sizeof q);
  q.kind = LSYS_SPACE_DENSITY;
  q.threads = 2;
  if ((st = lsys_space_build(&S, p, 200, &o, NULL)) == LSYS_OK &&
      (st = lsys_space_query(S, &q, out, NULL)) == LSYS_OK &&
      (st = lsys_space_markers_new(&M, p, 200, NULL, NULL)) == LSYS_OK) {
    st = lsys_space_markers_perceive(M, p, h, 20, &mo, cnt, dir, NULL);
    if (st != LSYS_OK) assert(lsys_space_markers_count(M) == 200);     /* nothing removed */
    else st = lsys_space_markers_remove(M, p + 300, 20, 0.3, 2, NULL, NULL);
  }
  if (st == LSYS_OK) {
    double lo[3] = {0, 0, 0}, hi[3] = {3, 3, 3};
    lsys_field *F;
    if ((st = lsys_space_field_new(&F, lo, hi, 0.5, NULL, NULL)) == LSYS_OK) {
      st = lsys_space_field_diffuse(F, 1, 1, 2, NULL, NULL);
      lsys_space_field_free(F);
    }
  }
  lsys_space_free(S);
  lsys_space_markers_free(M);
  return st;
}

/* Every allocation of a build, a query and a pass fails in turn: a clean error, nothing
** left behind. */
static void test_nomem (void) {
  static double p[3 * 200], h[3 * 20];
  long k, n;
  size_t i;
  for (i = 0; i < 3 * 200; i++) p[i] = 3 * rnd();
  for (i = 0; i < 3 * 20; i++) h[i] = rnd() - 0.5;
  nalloc = 0;
  assert(sequence(p, h) == LSYS_OK);
  n = nalloc;
  assert(n > 10);
  for (k = 0; k < n + 2; k++) {
    long live = nlive;
    int st;
    nalloc = 0;
    failat = k;
    st = sequence(p, h);
    failat = -1;
    assert(k < n ? st == LSYS_ENOMEM : st == LSYS_OK);
    assert(nlive == live);
  }
}

int main (void) {
  test_counts();
  test_density();
  test_free();
  test_brute();
  test_scene();
  test_markers();
  test_markers_brute();
  test_errors();
  test_field_row();
  test_field_grid();
  test_field_take();
  test_field_errors();
  test_nomem();
  printf("test_space: ok\n");
  return 0;
}
