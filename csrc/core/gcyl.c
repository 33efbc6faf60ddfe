/*
** Generalized cylinders: cpfg guide §3 (see gcyl.h).
**
** A segment between control points a and b is the Hermite curve (§3.1)
**   F(u) = h00 P0 + h10 T0 + h01 P1 + h11 T1,  T0 = c0 d H_a,  T1 = c1 d H_b,
** d = |P1 - P0|, c0 and c1 the tangent coefficients (1.2 unless @Gt). The
** i-th of n strips runs between F(R_u((i-1)/n)) and F(R_u(i/n)) with radii
** R_v((i-1)/n) and R_v(i/n), where R(t) is the longitudinal section: the 2D
** Hermite curve from (0, r_b) to (1, r_t) whose tangents default to
** (1, r_t - r_b) -- linear interpolation -- or come from @Gr (§3.2.2).
** A contour vertex V_i at parameter t is V_i + t (V'_i - V_i) between the
** contours of the two ends, placed at C_i = F + r (x V + y R + z T) with T
** the unit tangent, V the frame's reference vector and R = V x T the
** "right" vector (§3.2.3; V plays the turtle's up vector). V is carried
** along the axis by the smallest rotation between successive tangents
** (§3.3); when the twist is not minimised the frame is turned, evenly along
** the segment, so that it ends on the turtle's own up vector at b.
*/
#include <math.h>
#include <string.h>

#include "gcyl.h"
#include "vec3.h"

#define NOREF UINT32_MAX
#define MAXSLOPE 20.0

void lsys_gcyl_hermite (const double P0[3], const double T0[3], const double P1[3],
                        const double T1[3], double u, double F[3], double dF[3]) {
  double u2 = u * u, u3 = u2 * u;
  int k;
  if (F != NULL) {
    double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
           h11 = u3 - u2;
    for (k = 0; k < 3; k++) F[k] = h00 * P0[k] + h10 * T0[k] + h01 * P1[k] + h11 * T1[k];
  }
  if (dF != NULL) {
    double d00 = 6 * u2 - 6 * u, d10 = 3 * u2 - 4 * u + 1, d01 = -6 * u2 + 6 * u,
           d11 = 3 * u2 - 2 * u;
    for (k = 0; k < 3; k++) dF[k] = d00 * P0[k] + d10 * T0[k] + d01 * P1[k] + d11 * T1[k];
  }
}

/* §3.2.2: a tangent given as (angle, length) is length (cos a, sin a) for
** a segment of unit length. With @Gr(1) it is made (cos a, len sin a) so
** that, once the section is stretched by len along the axis, its angle
** with the axis is still a. */
void lsys_gcyl_section (const lsys_gcshape *sh, double rb, double rt, double len, double t,
                        double R[2], double dR[2]) {
  double T[2][2], t2 = t * t, t3 = t2 * t;
  int k;
  for (k = 0; k < 2; k++) {
    double a = sh->rtan[2 * k] * (PI / 180), l = sh->rtan[2 * k + 1];
    if (l == 0) { T[k][0] = 1; T[k][1] = rt - rb; }
    else {
      T[k][0] = l * cos(a);
      T[k][1] = l * sin(a) * (sh->adjust && len > 0 ? len : 1);
    }
  }
  if (R != NULL) {
    double h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2,
           h00 = 2 * t3 - 3 * t2 + 1;
    R[0] = h10 * T[0][0] + h01 + h11 * T[1][0];
    R[1] = h00 * rb + h10 * T[0][1] + h01 * rt + h11 * T[1][1];
  }
  if (dR != NULL) {
    double d00 = 6 * t2 - 6 * t, d10 = 3 * t2 - 4 * t + 1, d01 = -6 * t2 + 6 * t,
           d11 = 3 * t2 - 2 * t;
    dR[0] = d10 * T[0][0] + d01 + d11 * T[1][0];
    dR[1] = d00 * rb + d10 * T[0][1] + d01 * rt + d11 * T[1][1];
  }
}

/* Makes V a unit vector normal to the unit T (any normal when V is along T). */
static void perpendicular (double V[3], const double T[3]) {
  vlin(V, V, 1, T, -vdot(V, T));
  if (!vnorm(V)) {
    double a[3] = {1, 0, 0};
    if (fabs(T[0]) > 0.9) vset(a, 0, 1, 0);
    vcross(V, T, a);
    vnorm(V);
  }
}

void lsys_gcyl_transport (double V[3], const double T0[3], const double T1[3]) {
  double k[3], s, c = vdot(T0, T1);
  vcross(k, T0, T1);
  s = vlen(k);
  if (s > 1e-12) {
    k[0] /= s; k[1] /= s; k[2] /= s;
    vrotcs(V, k, c, s);
  }
  perpendicular(V, T1);
}

/* One ring of the segment: where, how wide, which frame. */
typedef struct ring {
  double t;               /* section parameter: contour blend */
  double F[3], T[3], V[3], R[3];
  double r, slope;        /* radius and dr/ds along the axis */
} ring;

typedef struct seg {
  const lsys_gcpoint *a, *b;
  const lsys_gcshape *sh;
  double T0[3], T1[3], len;
} seg;

/* Axis point, unit tangent, radius and slope at t = j/n; 'prevT' is the
** tangent to fall back on where the curve has none. */
static void axis (const seg *g, double t, const double *prevT, ring *q) {
  double R[2], dR[2], dF[3], sp;
  lsys_gcyl_section(g->sh, g->a->r, g->b->r, g->len, t, R, dR);
  lsys_gcyl_hermite(g->a->pos, g->T0, g->b->pos, g->T1, R[0], q->F, dF);
  q->t = t;
  q->r = R[1] > 0 ? R[1] : 0;
  vcopy(q->T, dF);
  sp = vlen(dF);
  if (!vnorm(q->T)) vcopy(q->T, prevT);
  sp *= dR[0];
  q->slope = fabs(sp) > 1e-12 ? dR[1] / sp : 0;
  if (q->slope > MAXSLOPE) q->slope = MAXSLOPE;
  if (q->slope < -MAXSLOPE) q->slope = -MAXSLOPE;
}

/* The frame's signed angle from V to the turtle's up vector U at the end,
** about T (twist not minimised). */
static double endtwist (const double V[3], const double T[3], const double U[3]) {
  double W[3], c[3];
  vcopy(W, U);
  perpendicular(W, T);
  vcross(c, V, W);
  return atan2(vdot(c, T), vdot(V, W));
}

/* Appends the p + 1 vertices of ring q; returns the first. */
static uint32_t emit (lsys_mesh *m, const ring *q, const lsys_gccontour *ca,
                      const lsys_gccontour *cb, int p, double v, unsigned col, int twosided) {
  uint32_t first = (uint32_t)m->nv;
  int k, blend = ca != cb && q->t > 0;
  for (k = 0; k <= p; k++) {
    const double *x = ca->v + 3 * k, *nn = ca->n + 3 * k;
    double c[3], cn[3], P[3], N[3], d;
    if (blend) {
      vlin(c, x, 1 - q->t, cb->v + 3 * k, q->t);
      vlin(cn, nn, 1 - q->t, cb->n + 3 * k, q->t);
      if (!vnorm(cn)) vcopy(cn, nn);
      x = c; nn = cn;
    }
    vlin(P, q->V, x[0], q->R, x[1]);
    vlin(P, P, 1, q->T, x[2]);
    vlin(P, q->F, 1, P, q->r);
    vlin(N, q->V, nn[0], q->R, nn[1]);
    if (q->slope != 0) {                       /* the normal leans with the taper */
      d = nn[0] * x[0] + nn[1] * x[1];
      vlin(N, N, 1, q->T, -q->slope * d);
      vnorm(N);
    }
    lsys_mesh_vertex(m, P, N, (double)k / p, v, col, twosided);
  }
  return first;
}

/* A flat cap over ring q from the contour's cap triangles; 'end' turns it
** to face along T (the cap triangles wind anticlockwise in contour space,
** which the left-handed frame (V, R, T) shows facing -T). */
static void cap (lsys_mesh *m, const ring *q, const lsys_gccontour *c, int p, unsigned col,
                 int end) {
  uint32_t first = (uint32_t)m->nv;
  double N[3];
  int k;
  vlin(N, q->T, end ? 1 : -1, q->T, 0);
  for (k = 0; k < p; k++) {
    const double *x = c->v + 3 * k;
    double P[3];
    vlin(P, q->V, x[0], q->R, x[1]);
    vlin(P, P, 1, q->T, x[2]);
    vlin(P, q->F, 1, P, q->r);
    lsys_mesh_vertex(m, P, N, 0.5 + x[0] / 2, 0.5 + x[1] / 2, col, 0);
  }
  for (k = 0; k < c->ncap; k++) {
    const uint32_t *tr = c->cap + 3 * k;
    if (end) lsys_mesh_tri(m, first + tr[0], first + tr[2], first + tr[1]);
    else lsys_mesh_tri(m, first + tr[0], first + tr[1], first + tr[2]);
  }
}

int lsys_gcyl_segment (lsys_mesh *m, const lsys_gcpoint *a, lsys_gcpoint *b,
                       const lsys_gcshape *sh, const lsys_gccontour *ca,
                       const lsys_gccontour *cb, int p) {
  seg g;
  ring q, prev;
  int n = sh->strips < 1 ? 1 : sh->strips, j, k, twosided = !ca->closed || !cb->closed;
  int share, capa, capb;
  unsigned col = (unsigned)b->color;
  double twist = 0, v = a->v, d[3];
  uint32_t r0, r1;
  size_t nv, nt;
  g.a = a; g.b = b; g.sh = sh;
  vlin(d, b->pos, 1, a->pos, -1);
  g.len = vlen(d);
  vlin(g.T0, a->H, sh->tan0 * g.len, a->H, 0);
  vlin(g.T1, b->H, sh->tan1 * g.len, b->H, 0);
  share = a->ring != NOREF && a->sides == p && a->color == b->color &&
          a->texture == b->texture &&
          sh->tan0 > 0 && g.len > 0;
  capa = sh->capstart && ca->closed && ca->cap != NULL && a->r > 0;
  capb = sh->capend && cb->closed && cb->cap != NULL && b->r > 0;
  nv = (size_t)(n + 1) * (p + 1) + (size_t)(capa + capb) * p;
  nt = 2 * (size_t)n * p + (size_t)(capa ? ca->ncap : 0) + (capb ? cb->ncap : 0);
  if (lsys_mesh_reserve(m, nv, nt) != LSYS_OK) return LSYS_ENOMEM;
  m->curtex = (unsigned)b->texture;
  /* the first ring's frame: a's reference vector turned onto the tangent */
  axis(&g, 0, a->H, &q);
  vcopy(q.V, a->V);
  lsys_gcyl_transport(q.V, a->H, q.T);
  if (!sh->minimize) {                      /* how far the turtle turned the frame */
    double V[3], T[3];
    ring e = q;
    vcopy(V, q.V); vcopy(T, q.T);
    for (j = 1; j <= n; j++) {
      axis(&g, (double)j / n, T, &e);
      lsys_gcyl_transport(V, T, e.T);
      vcopy(T, e.T);
    }
    twist = endtwist(V, T, b->U);
  }
  vcross(q.R, q.V, q.T);
  if (capa) cap(m, &q, ca, p, col, 0);
  r0 = share ? a->ring : emit(m, &q, ca, cb, p, v, col, twosided);
  for (j = 1; j <= n; j++) {
    double step[3], rm;
    prev = q;
    axis(&g, (double)j / n, prev.T, &q);
    vcopy(q.V, prev.V);
    lsys_gcyl_transport(q.V, prev.T, q.T);
    vcross(q.R, q.V, q.T);
    /* keep the untwisted frame in prev for transport; apply this ring's twist */
    {
      ring out = q;
      if (twist != 0) {
        vrotate(out.V, out.T, twist * j / n);
        vcross(out.R, out.V, out.T);
      }
      vlin(step, q.F, 1, prev.F, -1);
      rm = (prev.r + q.r) / 2;
      if (rm > 1e-12) v += vlen(step) * sh->aspect / (2 * PI * rm);
      r1 = emit(m, &out, ca, cb, p, v, col, twosided);
      for (k = 0; k < p; k++) {
        uint32_t a0 = r0 + k, a1 = r0 + k + 1, b0 = r1 + k, b1 = r1 + k + 1;
        if (ca->left) { lsys_mesh_tri(m, a0, a1, b0); lsys_mesh_tri(m, a1, b1, b0); }
        else { lsys_mesh_tri(m, a0, b0, a1); lsys_mesh_tri(m, a1, b0, b1); }
      }
      r0 = r1;
      if (j == n) {
        if (capb) cap(m, &out, cb, p, col, 1);
        vcopy(b->V, out.V);
        b->ring = vdot(out.T, b->H) > 0.9999 ? r1 : NOREF;
        b->sides = p;
      }
    }
  }
  b->v = v;
  return LSYS_OK;
}
