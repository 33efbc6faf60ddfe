/*
** The turtle's tropisms (the cpfg guide of Měch and Prusinkiewicz, §6: eq. 1-2,
** the twist response of §6.1, the minimisation of twist) and cpfg's old-style
** tropism, with the frame they keep orthonormal. See turtle.c for the frame's
** conventions (L = H x U).
*/
#include <math.h>

#include "turtle_impl.h"

/* Rebuilds an orthonormal frame from H and an approximate U. */
void lsys_turtle_orthonormal (lsys_tstate *st) {
  double d;
  if (!vnorm(st->H)) vset(st->H, 0, 1, 0);
  d = vdot(st->U, st->H);
  vlin(st->U, st->U, 1, st->H, -d);
  if (!vnorm(st->U)) {                  /* U parallel to H: any perpendicular */
    double t[3] = {1, 0, 0};
    if (fabs(st->H[0]) > 0.9) vset(t, 0, 0, 1);
    vcross(st->U, t, st->H);
    vnorm(st->U);
  }
  vcross(st->L, st->H, st->U);
}

/* Carries the reference frame to the current heading by the smallest
** rotation, which keeps U free of twist (§3.3), then makes it the
** reference. */
void lsys_turtle_untwist (lsys_tstate *st) {
  double axis[3], s, c;
  vcross(axis, st->refH, st->H);
  s = vlen(axis);
  c = vdot(st->refH, st->H);
  vcopy(st->U, st->refU);
  if (s > 1e-12) {
    axis[0] /= s; axis[1] /= s; axis[2] /= s;
    vrotate(st->U, axis, atan2(s, c));
  }
  else if (c < 0) {                      /* reversed: turn about the old U */
    vlin(st->U, st->U, 1, st->H, 0);
  }
  lsys_turtle_orthonormal(st);
  vcopy(st->refH, st->H);
  vcopy(st->refU, st->U);
}

/* Before each move: bends H toward the tropism vectors (eq. 2, which is
** eq. 1 for gamma = 0), removes the twist the bend would add, then turns
** U about H toward the torque vectors (§6.1). */
void lsys_turtle_tropisms (run *R) {
  const lsys_turtle_opts *o = R->o;
  lsys_tstate *st = &R->st;
  double A[3] = {0, 0, 0}, a;
  int k, bent = 0, twisted = 0;
  for (k = 0; k < o->ntrop; k++) {
    const lsys_tropism *tp = &o->trop[k];
    double T[3], hxt[3], s, e = st->elast[k] * tp->intensity, f;
    if (tp->torque || e == 0) continue;
    vcopy(T, tp->vec);
    if (!vnorm(T)) continue;
    vcross(hxt, st->H, T);
    s = vlen(hxt);
    if (s < 1e-12) continue;               /* H along T: no torque */
    f = e * (cos(RAD(tp->angle)) - sin(RAD(tp->angle)) * vdot(st->H, T) / s);
    vlin(A, A, 1, hxt, f);
    bent = 1;
  }
  if (bent && (a = vlen(A)) > 1e-15) {
    double axis[3];
    vlin(axis, A, 1.0 / a, A, 0);
    if (a > 1) a = 1;                      /* at most one radian per segment */
    vrotate(st->H, axis, a);
  }
  if (bent) lsys_turtle_untwist(st);
  /* Torques (§6.1) act together, as cpfg's do: D = sum of e_i T_i (unit vectors), V the
  ** projection of D / |D| on the plane normal to H, of length |H x D/|D||; U turns about H
  ** towards |D| V by |U x |D| V| radians, at most one. */
  {
    double D[3] = {0, 0, 0}, n[3], w[3], V[3], c[3], dl;
    int any = 0;
    for (k = 0; k < o->ntrop; k++) {
      const lsys_tropism *tp = &o->trop[k];
      double T[3], e = st->elast[k] * tp->intensity;
      if (!tp->torque || e == 0) continue;
      vcopy(T, tp->vec);
      if (!vnorm(T)) continue;
      vlin(D, D, 1, T, e);
      any = 1;
    }
    if (any && (dl = vlen(D)) > 0) {
      vlin(n, D, 1.0 / dl, D, 0);
      vcross(w, st->H, n);
      if (vdot(w, w) > 1e-8) {
        vcross(V, w, st->H);
        vlin(V, V, dl, V, 0);
        vcross(c, st->U, V);
        if ((a = vlen(c)) >= 1e-7) {
          double axis[3];
          vlin(axis, c, 1.0 / a, c, 0);
          vrotate(st->U, axis, -(a > 1 ? 1 : a));
          vcross(st->L, st->H, st->U);
          lsys_turtle_orthonormal(st);
        }
        twisted = 1;
      }
    }
  }
  if (!bent || twisted) { vcopy(st->refH, st->H); vcopy(st->refU, st->U); }
}

/* After each move, cpfg's old-style tropism (its interpret.c `bend`): H turns towards U
** by the angle whose sine is e (T . U), then towards L by the one whose sine is e (T . L),
** e the elasticity `_` sets. Each is a rotation in a plane of the frame, so the frame
** stays orthonormal. */
/* Turns H towards A (U or L) by the angle whose sine is e (T . A), in their plane. */
static void bendto (double *H, double *A, const double *T, double e) {
  double h[3], c = e * vdot(T, A), s;
  if (c > 1) c = 1; else if (c < -1) c = -1;
  s = sqrt(1 - c * c);
  vlin(h, H, s, A, c);
  vlin(A, A, s, H, -c);
  vcopy(H, h);
}

void lsys_turtle_oldbend (run *R) {
  lsys_tstate *st = &R->st;
  bendto(st->H, st->U, R->o->otrop, st->oelast);
  bendto(st->H, st->L, R->o->otrop, st->oelast);
}
