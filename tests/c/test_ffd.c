/*
** C unit tests for the free-form deformations (ffd.h): the hyperpatch is the
** identity on its regular lattice and exact for affine maps of its control
** points at every degree; one moved control point moves a point by the
** Bernstein weights computed by hand; normals after a shear; functions and
** affine maps; ranges, failures, the dirty range; what modules drew.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <string.h>

#include "ffd.h"

static const double FRAME[3][3] = {{2, 0.5, 0}, {0, 1.5, 0.3}, {0.2, -0.4, 1}};
static const double ORIGIN[3] = {-1, 0.5, 2};

static int near (double a, double b, double tol) { return fabs(a - b) <= tol; }

/* A scene of n vertices at scattered points in and around the box of
** ORIGIN and FRAME (lattice coordinates -0.3 .. 1.3), with unit normals,
** and 2 line segments. */
static void makescene (lsys_scene *s, int n) {
  int i, r;
  lsys_scene_init(s);
  assert(lsys_mesh_reserve(&s->mesh, (size_t)n, 0) == LSYS_OK);
  for (i = 0; i < n; i++) {
    double stu[3] = {-0.3 + 1.6 * ((i * 7) % 11) / 10.0, -0.3 + 1.6 * ((i * 5) % 13) / 12.0,
                     -0.3 + 1.6 * ((i * 3) % 7) / 6.0};
    double p[3], nr[3] = {0.6 * ((i % 3) - 1), 0.8, 0.3 * (i % 2)}, l;
    for (r = 0; r < 3; r++)
      p[r] = ORIGIN[r] + stu[0] * FRAME[0][r] + stu[1] * FRAME[1][r] + stu[2] * FRAME[2][r];
    l = sqrt(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2]);
    for (r = 0; r < 3; r++) nr[r] /= l;
    lsys_mesh_vertex(&s->mesh, p, nr, 0, 0, 1, 0);
  }
  {
    const double a[3] = {0, 1, 2}, b[3] = {0.5, 1.5, 2.5}, c[3] = {-1, 0.7, 2.9};
    assert(lsys_mesh_line(&s->mesh, a, b, 1, 1, 0) == LSYS_OK);
    assert(lsys_mesh_line(&s->mesh, b, c, 1, 1, 0) == LSYS_OK);
  }
}

static int allegree (int d[3], int k) {     /* the k-th of the 64 degree triples, k < 64 */
  d[0] = 1 + k % 4; d[1] = 1 + (k / 4) % 4; d[2] = 1 + k / 16;
  return k < 64;
}

static void identity (void) {
  lsys_scene s, orig;
  lsys_hyperpatch hp;
  lsys_error e;
  int d[3], k, total = 0;
  size_t v;
  makescene(&orig, 60);
  for (k = 0; k < 65; k++) {
    if (k < 64) allegree(d, k); else { d[0] = 1; d[1] = 3; d[2] = 4; }
    makescene(&s, 60);
    assert(lsys_ffd_hyperpatch_init(&hp, d, ORIGIN, FRAME, &e) == LSYS_OK);
    assert(lsys_ffd_hyperpatch_count(&hp) == (size_t)((d[0] + 1) * (d[1] + 1) * (d[2] + 1)));
    assert(lsys_ffd_range(&s, 0, s.mesh.nv, 0, s.mesh.nl, &hp) == LSYS_OK);
    for (v = 0; v < 3 * s.mesh.nv; v++) {
      assert(near(s.mesh.pos[v], orig.mesh.pos[v], 1e-6 * (1 + fabs(orig.mesh.pos[v]))));
      assert(near(s.mesh.nrm[v], orig.mesh.nrm[v], 1e-6));
      total++;
    }
    for (v = 0; v < 6 * s.mesh.nl; v++)
      assert(near(s.mesh.lpos[v], orig.mesh.lpos[v], 1e-6 * (1 + fabs(orig.mesh.lpos[v]))));
    lsys_scene_free(&s);
  }
  assert(total == 65 * 180);
  lsys_scene_free(&orig);
}

/* A rotation about (1, 2, 2)/3 by 40 degrees times diag(1.5, 0.5, 2), and a
** translation: the map the lattice undergoes. */
static void affinemap (double A[12]) {
  double ax[3] = {1 / 3.0, 2 / 3.0, 2 / 3.0}, a = 40 * acos(-1) / 180, c = cos(a), sn = sin(a);
  double R[3][3], S[3] = {1.5, 0.5, 2}, t[3] = {0.7, -1.2, 3};
  int r, k;
  for (r = 0; r < 3; r++)
    for (k = 0; k < 3; k++) R[r][k] = (r == k ? c : 0) + (1 - c) * ax[r] * ax[k];
  R[0][1] -= sn * ax[2]; R[1][0] += sn * ax[2];
  R[0][2] += sn * ax[1]; R[2][0] -= sn * ax[1];
  R[1][2] -= sn * ax[0]; R[2][1] += sn * ax[0];
  for (r = 0; r < 3; r++) {
    for (k = 0; k < 3; k++) A[4 * r + k] = R[r][k] * S[k];
    A[4 * r + 3] = t[r];
  }
}

static void applyaff (const double A[12], const double p[3], double q[3]) {
  int r;
  for (r = 0; r < 3; r++) q[r] = A[4 * r] * p[0] + A[4 * r + 1] * p[1] + A[4 * r + 2] * p[2] + A[4 * r + 3];
}

/* n' = A^-T n normalized, by hand from the 3 x 3 part: rows of A^-T are
** the cross products of A's columns over det. */
static void affnormal (const double A[12], const float n[3], double out[3]) {
  double c0[3] = {A[0], A[4], A[8]}, c1[3] = {A[1], A[5], A[9]}, c2[3] = {A[2], A[6], A[10]};
  double x[3][3], l;
  int r;
  x[0][0] = c1[1] * c2[2] - c1[2] * c2[1]; x[0][1] = c1[2] * c2[0] - c1[0] * c2[2];
  x[0][2] = c1[0] * c2[1] - c1[1] * c2[0];
  x[1][0] = c2[1] * c0[2] - c2[2] * c0[1]; x[1][1] = c2[2] * c0[0] - c2[0] * c0[2];
  x[1][2] = c2[0] * c0[1] - c2[1] * c0[0];
  x[2][0] = c0[1] * c1[2] - c0[2] * c1[1]; x[2][1] = c0[2] * c1[0] - c0[0] * c1[2];
  x[2][2] = c0[0] * c1[1] - c0[1] * c1[0];
  /* A^-1 has rows x[k] / det, so A^-T n = sum_k n[k] x[k] / det; det > 0 here */
  for (r = 0; r < 3; r++) out[r] = n[0] * x[0][r] + n[1] * x[1][r] + n[2] * x[2][r];
  l = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  for (r = 0; r < 3; r++) out[r] /= l;
}

static void affine (void) {
  lsys_scene s, orig, aff;
  lsys_hyperpatch hp;
  lsys_error e;
  double A[12];
  int d[3], k, i, j, l, r;
  size_t v;
  affinemap(A);
  makescene(&orig, 40);
  makescene(&aff, 40);
  assert(lsys_ffd_affine(&aff, 0, aff.mesh.nv, 0, aff.mesh.nl, A) == LSYS_OK);
  for (v = 0; v < orig.mesh.nv; v++) {       /* the affine map itself, by hand */
    double p[3] = {orig.mesh.pos[3 * v], orig.mesh.pos[3 * v + 1], orig.mesh.pos[3 * v + 2]};
    double q[3], n[3];
    applyaff(A, p, q);
    affnormal(A, orig.mesh.nrm + 3 * v, n);
    for (r = 0; r < 3; r++) {
      assert(near(aff.mesh.pos[3 * v + r], q[r], 1e-5));
      assert(near(aff.mesh.nrm[3 * v + r], n[r], 1e-6));
    }
  }
  for (k = 0; k < 65; k++) {
    if (k < 64) allegree(d, k); else { d[0] = 1; d[1] = 3; d[2] = 4; }
    assert(lsys_ffd_hyperpatch_init(&hp, d, ORIGIN, FRAME, &e) == LSYS_OK);
    for (l = 0; l <= d[2]; l++)
      for (j = 0; j <= d[1]; j++)
        for (i = 0; i <= d[0]; i++) {
          double *P = lsys_ffd_hyperpatch_point(&hp, i, j, l), q[3];
          applyaff(A, P, q);
          memcpy(P, q, sizeof q);
        }
    makescene(&s, 40);
    assert(lsys_ffd_range(&s, 0, s.mesh.nv, 0, s.mesh.nl, &hp) == LSYS_OK);
    for (v = 0; v < 3 * s.mesh.nv; v++) {
      assert(near(s.mesh.pos[v], aff.mesh.pos[v], 1e-5));
      assert(near(s.mesh.nrm[v], aff.mesh.nrm[v], 1e-5));
    }
    for (v = 0; v < 6 * s.mesh.nl; v++) assert(near(s.mesh.lpos[v], aff.mesh.lpos[v], 1e-5));
    lsys_scene_free(&s);
  }
  lsys_scene_free(&orig);
  lsys_scene_free(&aff);
}

/* Degrees (2, 3, 1) on the unit cube, P_120 moved by delta: the point
** (0.3, 0.6, 0.2) moves by B_1^2(0.3) B_2^3(0.6) B_0^1(0.2) delta
** = (2 * 0.3 * 0.7) (3 * 0.36 * 0.4) (0.8) delta = 0.145152 delta. */
static void onepoint (void) {
  static const double unit[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, o[3] = {0, 0, 0};
  const int d[3] = {2, 3, 1};
  const double delta[3] = {0.3, -0.2, 0.5}, p[3] = {0.3, 0.6, 0.2};
  lsys_hyperpatch hp;
  lsys_error e;
  double q[3], J[3][3], *P;
  int r;
  assert(lsys_ffd_hyperpatch_init(&hp, d, o, unit, &e) == LSYS_OK);
  P = lsys_ffd_hyperpatch_point(&hp, 1, 2, 0);
  assert(P == hp.cp[1 + 3 * (2 + 4 * 0)]);
  assert(near(P[0], 0.5, 1e-15) && near(P[1], 2 / 3.0, 1e-15) && P[2] == 0);
  for (r = 0; r < 3; r++) P[r] += delta[r];
  lsys_ffd_hyperpatch_eval(&hp, p, q, J);
  for (r = 0; r < 3; r++) assert(near(q[r], p[r] + 0.145152 * delta[r], 1e-12));
  /* d/ds of B_1^2(s) = 2 - 4 s = 0.8 at 0.3: J[r][0] = [r == 0] + 0.8 * 0.432 * 0.8 delta[r] */
  for (r = 0; r < 3; r++) assert(near(J[r][0], (r == 0) + 0.8 * 0.432 * 0.8 * delta[r], 1e-12));
  /* d/du of B_0^1(u) = -1: J[r][2] = [r == 2] - 0.42 * 0.432 delta[r] */
  for (r = 0; r < 3; r++) assert(near(J[r][2], (r == 2) - 0.42 * 0.432 * delta[r], 1e-12));
  /* outside the cube the same polynomial (extrapolation): s = 1.5 */
  {
    const double x[3] = {1.5, 0.6, 0.2};
    lsys_ffd_hyperpatch_eval(&hp, x, q, NULL);
    /* B_1^2(1.5) = 2 * 1.5 * -0.5 = -1.5 */
    for (r = 0; r < 3; r++) assert(near(q[r], x[r] - 1.5 * 0.432 * 0.8 * delta[r], 1e-12));
  }
  assert(lsys_ffd_hyperpatch_point(&hp, 3, 0, 0) == NULL);
  assert(lsys_ffd_hyperpatch_point(&hp, 0, 4, 0) == NULL);
  assert(lsys_ffd_hyperpatch_point(&hp, 0, 0, 2) == NULL);
  assert(lsys_ffd_hyperpatch_point(&hp, -1, 0, 0) == NULL);
  assert(lsys_ffd_hyperpatch_point(&hp, 2, 3, 1) == hp.cp[23]);
}

/* The square z = 0, normal +z, under the shear z' = z + 0.5 x: the plane
** goes to z = 0.5 x, whose normal is (-0.5, 0, 1) / sqrt(1.25). */
static int shear (void *ud, const double p[3], double out[3]) {
  (void)ud;
  out[0] = p[0]; out[1] = p[1]; out[2] = p[2] + 0.5 * p[0];
  return LSYS_OK;
}

static void square (lsys_scene *s) {
  static const double n[3] = {0, 0, 1};
  int k;
  lsys_scene_init(s);
  assert(lsys_mesh_reserve(&s->mesh, 4, 2) == LSYS_OK);
  for (k = 0; k < 4; k++) {
    double p[3] = {k == 1 || k == 2 ? 2 : 0, k >= 2 ? 2 : 0, 0};
    lsys_mesh_vertex(&s->mesh, p, n, 0, 0, 1, 1);
  }
  lsys_mesh_tri(&s->mesh, 0, 1, 2);
  lsys_mesh_tri(&s->mesh, 0, 2, 3);
}

static void normals (void) {
  static const double o[3] = {0, 0, -1}, ax[3][3] = {{2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const int d[3] = {1, 1, 1};
  const double want[3] = {-0.5 / sqrt(1.25), 0, 1 / sqrt(1.25)};
  lsys_scene s;
  lsys_hyperpatch hp;
  lsys_error e;
  int i, j, k, r, pass;
  size_t v;
  assert(lsys_ffd_hyperpatch_init(&hp, d, o, ax, &e) == LSYS_OK);
  for (k = 0; k < 2; k++)
    for (j = 0; j < 2; j++)
      for (i = 0; i < 2; i++) {
        double *P = lsys_ffd_hyperpatch_point(&hp, i, j, k);
        P[2] += 0.5 * P[0];
      }
  for (pass = 0; pass < 3; pass++) {
    square(&s);
    if (pass == 0) assert(lsys_ffd_range(&s, 0, 4, 0, 0, &hp) == LSYS_OK);
    else if (pass == 1) assert(lsys_ffd_func(&s, 0, 4, 0, 0, shear, NULL, &e) == LSYS_OK);
    else {
      const double m[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0.5, 0, 1, 0};
      assert(lsys_ffd_affine(&s, 0, 4, 0, 0, m) == LSYS_OK);
    }
    for (v = 0; v < 4; v++) {
      float *P = s.mesh.pos + 3 * v;
      assert(near(P[2], 0.5 * P[0], 1e-6));
      for (r = 0; r < 3; r++) assert(near(s.mesh.nrm[3 * v + r], want[r], 1e-6));
    }
    lsys_scene_free(&s);
  }
}

static void rejected (void) {
  static const double o[3] = {0, 0, 0}, unit[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const double flat[3][3] = {{1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  static const double zero[3][3] = {{1, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  lsys_hyperpatch hp;
  lsys_error e;
  int d0[3] = {1, 0, 2}, d5[3] = {5, 1, 1}, ok[3] = {4, 4, 4};
  double nan3[3] = {0, NAN, 0};
  assert(lsys_ffd_hyperpatch_init(&hp, d0, o, unit, &e) == LSYS_EARG);
  assert(strstr(e.msg, "degree 2 is 0") != NULL);
  assert(lsys_ffd_hyperpatch_init(&hp, d5, o, unit, &e) == LSYS_EARG);
  assert(strstr(e.msg, "degree 1 is 5") != NULL && strstr(e.msg, "1 (linear) to 4") != NULL);
  assert(lsys_ffd_hyperpatch_init(&hp, ok, o, flat, &e) == LSYS_EARG);
  assert(strstr(e.msg, "degenerate") != NULL);
  assert(lsys_ffd_hyperpatch_init(&hp, ok, o, zero, &e) == LSYS_EARG);
  assert(lsys_ffd_hyperpatch_init(&hp, ok, nan3, unit, &e) == LSYS_EARG);
  assert(strstr(e.msg, "origin[2]") != NULL);
  assert(lsys_ffd_hyperpatch_init(&hp, ok, o, unit, &e) == LSYS_OK);
  assert(lsys_ffd_hyperpatch_count(&hp) == 125);
}

/* A callback that fails at its 'fail'-th call and counts its calls. */
typedef struct counter { int calls, fail; } counter;

static int failing (void *ud, const double p[3], double out[3]) {
  counter *c = (counter *)ud;
  if (c->calls++ == c->fail) return LSYS_ERULE;
  out[0] = p[0] + 1; out[1] = p[1]; out[2] = p[2];
  return LSYS_OK;
}

static void ranges (void) {
  lsys_scene s, orig;
  lsys_hyperpatch hp;
  lsys_error e;
  const double m[12] = {1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0};
  counter c = {0, 7 * 2};                    /* 7 calls per vertex: fails at vertex 2 of 1.. */
  const int d[3] = {2, 2, 2};
  size_t v, a, b;
  makescene(&orig, 10);
  makescene(&s, 10);
  assert(lsys_ffd_affine(&s, 3, 11, 0, 0, m) == LSYS_EARG);
  assert(lsys_ffd_affine(&s, 4, 3, 0, 0, m) == LSYS_EARG);
  assert(lsys_ffd_affine(&s, 0, 0, 1, 3, m) == LSYS_EARG);
  assert(lsys_ffd_hyperpatch_init(&hp, d, ORIGIN, FRAME, &e) == LSYS_OK);
  assert(lsys_ffd_range(&s, 0, 11, 0, 0, &hp) == LSYS_EARG);
  assert(lsys_scene_take_dirty(&s, &a, &b) == 0);
  /* vertices [3, 6) and line 1 only; the rest untouched bit for bit */
  assert(lsys_ffd_affine(&s, 3, 6, 1, 2, m) == LSYS_OK);
  for (v = 0; v < 10; v++)
    assert(s.mesh.pos[3 * v] == orig.mesh.pos[3 * v] + (v >= 3 && v < 6 ? 5.0f : 0.0f));
  assert(memcmp(s.mesh.lpos, orig.mesh.lpos, 6 * sizeof(float)) == 0);
  assert(s.mesh.lpos[6] == orig.mesh.lpos[6] + 5 && s.mesh.lpos[9] == orig.mesh.lpos[9] + 5);
  assert(lsys_scene_take_dirty(&s, &a, &b) == 1 && a == 3 && b == 6);
  lsys_scene_free(&s);
  /* a failing callback stops at vertex 1 + 2 = 3 of the range [1, 8) */
  makescene(&s, 10);
  memset(&e, 0, sizeof e);
  assert(lsys_ffd_func(&s, 1, 8, 0, 2, failing, &c, &e) == LSYS_ERULE);
  assert(e.code == LSYS_ERULE && e.pos == 3);
  assert(strcmp(e.msg, "the deformation function failed at vertex 3") == 0);
  for (v = 0; v < 10; v++)
    assert(s.mesh.pos[3 * v] == orig.mesh.pos[3 * v] + (v >= 1 && v < 3 ? 1.0f : 0.0f));
  assert(memcmp(s.mesh.lpos, orig.mesh.lpos, 12 * sizeof(float)) == 0);
  assert(lsys_scene_take_dirty(&s, &a, &b) == 1 && a == 1 && b == 3);
  /* failing on a line end: e->pos = nv + 2 * segment + end */
  c.calls = 0;
  c.fail = 7 * 10 + 3;                        /* all 10 vertices, then the 4th line end */
  assert(lsys_ffd_func(&s, 0, 10, 0, 2, failing, &c, &e) == LSYS_ERULE);
  assert(e.pos == 10 + 3 && strcmp(e.msg, "the deformation function failed at line end 3") == 0);
  lsys_scene_free(&s);
  lsys_scene_free(&orig);
}

/* Records of modules 0, 2, 2, 5 with triangles [0, 2), [2, 3), none, [3, 5)
** over vertices 0..9, triangle 2 sharing vertex 3 with triangle 1; then
** the scene's lines, one per segment record. */
static void modules (void) {
  static const double p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
  static const uint32_t tri[15] = {0, 1, 2, 2, 3, 1, 4, 5, 3, 6, 7, 8, 9, 8, 6};
  static const uint32_t mod[4] = {0, 2, 2, 5}, t0[4] = {0, 2, 3, 3}, nt[4] = {2, 1, 0, 2};
  static const uint8_t kind[4] = {LSYS_REC_SPHERE, LSYS_REC_SEGMENT, LSYS_REC_SEGMENT,
                                  LSYS_REC_SPHERE};
  lsys_scene s;
  size_t v0, v1, l0, l1;
  int k;
  lsys_scene_init(&s);
  assert(lsys_mesh_reserve(&s.mesh, 10, 5) == LSYS_OK);
  for (k = 0; k < 10; k++) lsys_mesh_vertex(&s.mesh, p, n, 0, 0, 1, 0);
  for (k = 0; k < 5; k++) lsys_mesh_tri(&s.mesh, tri[3 * k], tri[3 * k + 1], tri[3 * k + 2]);
  assert(lsys_ffd_module_range(&s, 0, 9, &v0, &v1, &l0, &l1) == 0);   /* no records */
  for (k = 0; k < 4; k++) {
    lsys_trec r;
    memset(&r, 0, sizeof r);
    r.module = mod[k]; r.kind = kind[k]; r.tri0 = t0[k]; r.ntri = nt[k];
    assert(lsys_scene_add_record(&s, &r) == LSYS_OK);
  }
  assert(lsys_ffd_module_range(&s, 0, 1, &v0, &v1, &l0, &l1) == 1);
  assert(v0 == 0 && v1 == 4 && l0 == 0 && l1 == 0);     /* no lines: not the line style */
  assert(lsys_ffd_module_range(&s, 1, 3, &v0, &v1, &l0, &l1) == 1);
  /* triangle 2 (4 5 3) made vertices 4 and 5; vertex 3 belongs to earlier triangles */
  assert(v0 == 4 && v1 == 6);
  assert(lsys_ffd_module_range(&s, 3, 5, &v0, &v1, &l0, &l1) == 0);   /* drew nothing */
  assert(v0 == 0 && v1 == 0);
  assert(lsys_ffd_module_range(&s, 2, 9, &v0, &v1, &l0, &l1) == 1);
  assert(v0 == 4 && v1 == 10);
  assert(lsys_ffd_module_range(&s, 6, 9, &v0, &v1, &l0, &l1) == 0);
  /* the line style: two lines for the two segment records */
  {
    const double a[3] = {0, 0, 0}, b[3] = {0, 1, 0};
    assert(lsys_mesh_line(&s.mesh, a, b, 1, 1, 0) == LSYS_OK);
    assert(lsys_mesh_line(&s.mesh, b, a, 1, 1, 0) == LSYS_OK);
  }
  assert(lsys_ffd_module_range(&s, 2, 3, &v0, &v1, &l0, &l1) == 1);
  assert(l0 == 0 && l1 == 2);
  assert(lsys_ffd_module_range(&s, 0, 1, &v0, &v1, &l0, &l1) == 1);
  assert(l0 == 0 && l1 == 0);
  assert(lsys_ffd_module_range(&s, 3, 9, &v0, &v1, &l0, &l1) == 1);
  assert(l0 == 2 && l1 == 2 && v0 == 6 && v1 == 10);
  lsys_scene_free(&s);
}

int main (void) {
  identity();
  affine();
  onepoint();
  normals();
  rejected();
  ranges();
  modules();
  return 0;
}
