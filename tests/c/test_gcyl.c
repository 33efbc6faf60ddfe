/*
** C unit tests for generalized cylinders (csrc/core/gcyl.c; cpfg guide §3):
** the Hermite axis, the longitudinal section with and without @Gr tangents
** and their adjustment, frame transport, and the strips of a segment:
** counts, radii along the section, texture v, twist kept or minimised,
** frames along a helix without flips.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contour.h"
#include "gcyl.h"

#define PI 3.14159265358979323846
#define NEAR(a, b, tol) (fabs((a) - (b)) <= (tol))

static void near3 (const double *a, double x, double y, double z, double tol) {
  if (!(NEAR(a[0], x, tol) && NEAR(a[1], y, tol) && NEAR(a[2], z, tol))) {
    fprintf(stderr, "got (%g %g %g), expected (%g %g %g)\n", a[0], a[1], a[2], x, y, z);
    assert(0);
  }
}

static void test_hermite (void) {
  double P0[3] = {0, 0, 0}, T0[3] = {0, 2, 0}, P1[3] = {1, 1, 0}, T1[3] = {2, 0, 0};
  double F[3], dF[3];
  lsys_gcyl_hermite(P0, T0, P1, T1, 0, F, dF);
  near3(F, 0, 0, 0, 1e-15); near3(dF, 0, 2, 0, 1e-15);
  lsys_gcyl_hermite(P0, T0, P1, T1, 1, F, dF);
  near3(F, 1, 1, 0, 1e-15); near3(dF, 2, 0, 0, 1e-15);
  /* F(1/2) = (P0 + P1)/2 + (T0 - T1)/8; F'(1/2) = 3/2 (P1 - P0) - (T0 + T1)/4 */
  lsys_gcyl_hermite(P0, T0, P1, T1, 0.5, F, dF);
  near3(F, 0.5 - 0.25, 0.5 + 0.25, 0, 1e-15);
  near3(dF, 1.5 - 0.5, 1.5 - 0.5, 0, 1e-15);
}

static lsys_gcshape shape (void) {
  lsys_gcshape sh;
  memset(&sh, 0, sizeof sh);
  sh.tan0 = sh.tan1 = LSYS_GC_TANGENT;
  sh.strips = 1;
  sh.minimize = 1;
  sh.aspect = 1;
  return sh;
}

static void test_section (void) {
  lsys_gcshape sh = shape();
  double R[2], dR[2];
  /* default: linear from r_b to r_t */
  lsys_gcyl_section(&sh, 0.2, 0.1, 1, 0.3, R, dR);
  assert(NEAR(R[0], 0.3, 1e-15) && NEAR(R[1], 0.17, 1e-15));
  assert(NEAR(dR[0], 1, 1e-15) && NEAR(dR[1], -0.1, 1e-15));
  /* @Gr(30,4.5,0,3.5), r_b 0.2, r_t 0.1 (figure 9b): at t = 1/2 the Hermite
  ** weights are 1/2, 1/8, 1/2, -1/8 */
  sh.rtan[0] = 30; sh.rtan[1] = 4.5; sh.rtan[2] = 0; sh.rtan[3] = 3.5;
  lsys_gcyl_section(&sh, 0.2, 0.1, 1.5, 0.5, R, NULL);
  assert(NEAR(R[0], 0.125 * 4.5 * cos(PI / 6) + 0.5 - 0.125 * 3.5, 1e-12));
  assert(NEAR(R[1], 0.1 + 0.125 * 2.25 + 0.05, 1e-12));
  /* @Gr(1): on a segment of length 1.5 the radius slope is 1.5 times steeper */
  sh.adjust = 1;
  lsys_gcyl_section(&sh, 0.2, 0.1, 1.5, 0.5, R, NULL);
  assert(NEAR(R[1], 0.1 + 0.125 * 2.25 * 1.5 + 0.05, 1e-12));
  lsys_gcyl_section(&sh, 0.2, 0.1, 1.5, 0, R, dR);
  assert(NEAR(atan2(dR[1] / 1.5, dR[0]), PI / 6, 1e-12) || NEAR(atan2(dR[1], dR[0] * 1.5), PI / 6, 1e-12));
  /* a zero length means the default tangent */
  sh.rtan[1] = 0; sh.rtan[3] = 0;
  lsys_gcyl_section(&sh, 0.2, 0.1, 1.5, 0.5, R, NULL);
  assert(NEAR(R[0], 0.5, 1e-15) && NEAR(R[1], 0.15, 1e-15));
}

static void test_transport (void) {
  double V[3] = {0, 1, 0}, T0[3] = {0, 0, 1}, T1[3] = {0, 1, 0};
  lsys_gcyl_transport(V, T0, T1);
  near3(V, 0, 0, -1, 1e-15);
  /* along a straight line V does not move */
  {
    double W[3] = {0.6, 0, 0.8}, H[3] = {0, 1, 0};
    lsys_gcyl_transport(W, H, H);
    near3(W, 0.6, 0, 0.8, 1e-15);
  }
}

/* contour samples for p sides */
static double cv[3 * 65], cn[3 * 65];
static uint32_t capt[3 * 64];

static lsys_gccontour circle (int p) {
  lsys_gccontour c;
  int k;
  lsys_contour_circle(p, cv, cn);
  for (k = 0; k < p - 2; k++) {               /* a fan, anticlockwise in xy */
    capt[3 * k] = 0; capt[3 * k + 1] = (uint32_t)k + 1; capt[3 * k + 2] = (uint32_t)k + 2;
  }
  c.v = cv; c.n = cn; c.left = 0; c.closed = 1; c.cap = capt; c.ncap = p - 2;
  return c;
}

static lsys_gcpoint point (double x, double y, double z, const double *H, const double *U,
                           double r) {
  lsys_gcpoint g;
  memset(&g, 0, sizeof g);
  g.pos[0] = x; g.pos[1] = y; g.pos[2] = z;
  memcpy(g.H, H, sizeof g.H); memcpy(g.U, U, sizeof g.U); memcpy(g.V, U, sizeof g.V);
  g.r = r;
  g.ring = UINT32_MAX;
  return g;
}

static double dist_to_y (const float *p) { return sqrt(p[0] * p[0] + p[2] * p[2]); }

static void test_segment (void) {
  const double H[3] = {0, 1, 0}, U[3] = {0, 0, -1};
  lsys_mesh m;
  lsys_gccontour c = circle(8);
  lsys_gcshape sh = shape();
  lsys_gcpoint a = point(0, 0, 0, H, U, 0.2), b = point(0, 1, 0, H, U, 0.1);
  int j, k;
  lsys_mesh_init(&m);
  sh.strips = 4;
  assert(lsys_gcyl_segment(&m, &a, &b, &sh, &c, &c, 8) == LSYS_OK);
  assert(m.nv == 5 * 9 && m.nt == 2 * 4 * 8);
  /* a straight axis: with tangents 1.2 d the ring at u sits at
  ** y = 0.4 u^3 - 0.6 u^2 + 1.2 u; radii are linear in u (§3.2.2) */
  for (j = 0; j <= 4; j++)
    for (k = 0; k <= 8; k++) {
      const float *p = m.pos + 3 * (9 * j + k);
      double u = j / 4.0;
      assert(NEAR(p[1], 0.4 * u * u * u - 0.6 * u * u + 1.2 * u, 1e-6));
      assert(NEAR(dist_to_y(p), 0.2 - 0.025 * j, 1e-6));
    }
  /* V_0 along the turtle's up (§3.2.3): the first vertex of each ring at -z */
  assert(NEAR(m.pos[2], -0.2, 1e-6) && NEAR(m.pos[0], 0, 1e-6));
  assert(b.ring == 4 * 9);
  near3(b.V, 0, 0, -1, 1e-12);
  /* outward triangles: the normal of the first one points away from the axis */
  {
    const uint32_t *t = m.tri;
    const float *p0 = m.pos + 3 * t[0], *p1 = m.pos + 3 * t[1], *p2 = m.pos + 3 * t[2];
    double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    double v[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double cx = (p0[0] + p1[0] + p2[0]) / 3, cz = (p0[2] + p1[2] + p2[2]) / 3;
    assert(n[0] * cx + n[2] * cz > 0);
    /* and the vertex normals agree */
    assert(m.nrm[0] * p0[0] + m.nrm[2] * p0[2] > 0);
  }
  /* the next segment shares b's ring; caps at @Gs and @Ge add p vertices and
  ** p - 2 triangles each */
  {
    lsys_gcpoint d = point(0, 2, 0, H, U, 0.1);
    size_t nv = m.nv, nt = m.nt;
    sh.strips = 2;
    sh.capend = 1;
    assert(lsys_gcyl_segment(&m, &b, &d, &sh, &c, &c, 8) == LSYS_OK);
    assert(m.nv - nv == 2 * 9 + 8 && m.nt - nt == 2 * 2 * 8 + 6);
  }
  lsys_mesh_free(&m);
}

/* texture v grows by length x aspect / circumference (§5.2) */
static void test_texture_v (void) {
  const double H[3] = {0, 1, 0}, U[3] = {0, 0, -1};
  lsys_mesh m;
  lsys_gccontour c = circle(6);
  lsys_gcshape sh = shape();
  double r = 1 / (2 * PI);
  lsys_gcpoint a = point(0, 0, 0, H, U, r), b = point(0, 3, 0, H, U, r);
  lsys_mesh_init(&m);
  sh.strips = 3;
  sh.aspect = 2;
  sh.tan0 = sh.tan1 = 1;                  /* evenly spaced rings on a straight axis */
  a.v = 0.5;
  assert(lsys_gcyl_segment(&m, &a, &b, &sh, &c, &c, 6) == LSYS_OK);
  assert(NEAR(b.v, 0.5 + 6, 1e-9));
  assert(NEAR(m.uv[2 * 7 + 1], 0.5 + 2, 1e-6));   /* ring 1, vertex 0 */
  assert(NEAR(m.uv[2 * 8], 1.0 / 6, 1e-6));        /* ring 1, vertex 1: u = 1/6 */
  lsys_mesh_free(&m);
}

/* twist of cylinders off: the frame turns evenly to the turtle's up at b */
static void test_twist (void) {
  const double H[3] = {0, 1, 0}, U[3] = {0, 0, -1}, U2[3] = {1, 0, 0};
  lsys_mesh m;
  lsys_gccontour c = circle(8);
  lsys_gcshape sh = shape();
  lsys_gcpoint a = point(0, 0, 0, H, U, 1), b = point(0, 1, 0, H, U2, 1);
  lsys_mesh_init(&m);
  sh.strips = 2;
  sh.minimize = 0;
  assert(lsys_gcyl_segment(&m, &a, &b, &sh, &c, &c, 8) == LSYS_OK);
  {
    const float *mid = m.pos + 3 * 9, *end = m.pos + 3 * 18;
    double s = sqrt(0.5);
    /* U = -z turned toward +x: halfway at 45 degrees */
    assert(NEAR(mid[0], s, 1e-6) && NEAR(mid[2], -s, 1e-6));
    assert(NEAR(end[0], 1, 1e-6) && NEAR(end[2], 0, 1e-6));
  }
  near3(b.V, 1, 0, 0, 1e-12);
  /* minimised: the turtle's roll is ignored */
  m.nv = m.nt = 0;
  sh.minimize = 1;
  b.V[0] = b.V[1] = b.V[2] = 0;
  assert(lsys_gcyl_segment(&m, &a, &b, &sh, &c, &c, 8) == LSYS_OK);
  near3(b.V, 0, 0, -1, 1e-12);
  lsys_mesh_free(&m);
}

/* along a helix with minimised twist the frame stays normal to the axis and
** turns only a little from one control point to the next (no flips), even
** when the turtle's own up vector spins */
static void test_helix (void) {
  lsys_mesh m;
  lsys_gccontour c = circle(8);
  lsys_gcshape sh = shape();
  lsys_gcpoint a, b;
  double R = 2, pitch = 0.5, dt = 0.2;
  int i;
  lsys_mesh_init(&m);
  sh.strips = 3;
  for (i = 0; i <= 200; i++) {
    double t = i * dt, H[3] = {-R * sin(t), pitch, R * cos(t)}, l = sqrt(R * R + pitch * pitch);
    double U[3] = {cos(7 * t), 0, sin(7 * t)};       /* spinning, not normal to H */
    double d;
    H[0] /= l; H[1] /= l; H[2] /= l;
    d = U[0] * H[0] + U[1] * H[1] + U[2] * H[2];
    U[0] -= d * H[0]; U[1] -= d * H[1]; U[2] -= d * H[2];
    d = sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2]);
    U[0] /= d; U[1] /= d; U[2] /= d;
    b = point(R * cos(t), pitch * t, R * sin(t), H, U, 0.1);
    if (i > 0) {
      double prev[3];
      memcpy(prev, a.V, sizeof prev);
      assert(lsys_gcyl_segment(&m, &a, &b, &sh, &c, &c, 8) == LSYS_OK);
      assert(NEAR(b.V[0] * H[0] + b.V[1] * H[1] + b.V[2] * H[2], 0, 1e-12));
      assert(prev[0] * b.V[0] + prev[1] * b.V[1] + prev[2] * b.V[2] > cos(0.25));
    }
    a = b;
  }
  lsys_mesh_free(&m);
}

int main (void) {
  test_hermite();
  test_section();
  test_transport();
  test_segment();
  test_texture_v();
  test_twist();
  test_helix();
  printf("test_gcyl: ok\n");
  return 0;
}
