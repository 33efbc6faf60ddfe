/*
** Inverse kinematics of a branch path (ik.h; Power et al. 1999, §3.1 and
** appendix).
*/
#include <math.h>
#include <string.h>

#include "ik.h"
#include "vec3.h"

/* ---------------------------------------------------------------------- */
/* 3 x 3 column-major matrices: M[3 * column + row]; columns H, L, U */

static void mul3 (double C[9], const double A[9], const double B[9]) {
  double T[9];
  int r, c;
  for (c = 0; c < 3; c++)
    for (r = 0; r < 3; r++)
      T[3 * c + r] = A[r] * B[3 * c] + A[3 + r] * B[3 * c + 1] + A[6 + r] * B[3 * c + 2];
  memcpy(C, T, sizeof T);
}

/* C = A^T B */
static void tmul3 (double C[9], const double A[9], const double B[9]) {
  double T[9];
  int r, c;
  for (c = 0; c < 3; c++)
    for (r = 0; r < 3; r++)
      T[3 * c + r] = A[3 * r] * B[3 * c] + A[3 * r + 1] * B[3 * c + 1] +
                     A[3 * r + 2] * B[3 * c + 2];
  memcpy(C, T, sizeof T);
}

/* y = M x */
static void apply3 (double y[3], const double M[9], const double x[3]) {
  int r;
  for (r = 0; r < 3; r++) y[r] = M[r] * x[0] + M[3 + r] * x[1] + M[6 + r] * x[2];
}

/* M = M . R_k(a): a right-handed rotation by a about the local axis k
** (0 H, 1 L, 2 U), i.e. about the world axis M e_k. The other two columns
** turn in the plane they span: for the basis (x, y, z) = (H, L, U),
** about x: y -> c y + s z; about y: z -> c z + s x; about z: x -> c x + s y. */
static void rotlocal (double M[9], int k, double a) {
  int p = (k + 1) % 3, q = (k + 2) % 3, r;
  double c = cos(a), s = sin(a);
  for (r = 0; r < 3; r++) {
    double x = M[3 * p + r], y = M[3 * q + r];
    M[3 * p + r] = c * x + s * y;
    M[3 * q + r] = -s * x + c * y;
  }
}

void lsys_ik_frame (double M[9], const double H[3], const double U[3]) {
  double h[3] = {H[0], H[1], H[2]}, u[3] = {U[0], U[1], U[2]}, l[3], d;
  int i;
  vnormlen(h);
  d = vdot(u, h);
  for (i = 0; i < 3; i++) u[i] -= d * h[i];
  vnormlen(u);
  vcross(l, u, h);
  memcpy(M, h, sizeof h);
  memcpy(M + 3, l, sizeof l);
  memcpy(M + 6, u, sizeof u);
}

/* The joint's own rotation (the order of @J): M = M Rh(a0) Ru(a1) Rl(a2). */
static void joint (double M[9], const double a[3]) {
  rotlocal(M, 0, a[0]);
  rotlocal(M, 2, a[1]);
  rotlocal(M, 1, a[2]);
}

void lsys_ik_setjoint (lsys_ikjoint *j, const double prev[9], const double prevend[3],
                       const double frame[9], const double start[3], const double end[3]) {
  double d[3];
  int i;
  /* pre = prev^T frame R(alpha)^-1, R^-1 = Rl(-a2) Ru(-a1) Rh(-a0) */
  tmul3(j->pre, prev, frame);
  rotlocal(j->pre, 1, -j->alpha[2]);
  rotlocal(j->pre, 2, -j->alpha[1]);
  rotlocal(j->pre, 0, -j->alpha[0]);
  for (i = 0; i < 3; i++) d[i] = start[i] - prevend[i];
  /* off = prev^T d */
  for (i = 0; i < 3; i++) j->off[i] = vdot(prev + 3 * i, d);
  for (i = 0; i < 3; i++) d[i] = end[i] - start[i];
  j->len = vlen(d);
}

/* ---------------------------------------------------------------------- */
/* forward kinematics */

/* Runs the chain with the angles 'a'; fills p, s, t and, when given, the
** frames, the segment ends (pts: start, end per segment), and for the
** gradient the pivot of every joint (piv: 3 per joint) and the world axes
** of its three 1-joints (axes: 9 per joint, H then U then L). */
static void run (const lsys_ikchain *c, const double *a, double p[3], double s[3],
                 double t[3], double *frames, double *pts, double *piv, double *axes) {
  double M[9], P[9], e[3], x[3], o[3];
  int i, k;
  memcpy(M, c->base, sizeof M);
  memcpy(e, c->root, sizeof e);
  for (i = 0; i < c->n; i++) {
    const lsys_ikjoint *j = &c->j[i];
    const double *ai = a ? a + 3 * i : j->alpha;
    apply3(o, M, j->off);
    for (k = 0; k < 3; k++) x[k] = e[k] + o[k];
    mul3(P, M, j->pre);
    if (axes != NULL) {
      memcpy(axes + 9 * i, P, 3 * sizeof *P);            /* H before the joint turns */
      rotlocal(P, 0, ai[0]);
      memcpy(axes + 9 * i + 3, P + 6, 3 * sizeof *P);    /* U after the H turn */
      rotlocal(P, 2, ai[1]);
      memcpy(axes + 9 * i + 6, P + 3, 3 * sizeof *P);    /* L after the U turn */
      rotlocal(P, 1, ai[2]);
    } else
      joint(P, ai);
    memcpy(M, P, sizeof M);
    for (k = 0; k < 3; k++) e[k] = x[k] + j->len * M[k];
    if (piv != NULL) memcpy(piv + 3 * i, x, sizeof x);
    if (frames != NULL) memcpy(frames + 9 * i, M, sizeof M);
    if (pts != NULL) {
      memcpy(pts + 6 * i, x, sizeof x);
      memcpy(pts + 6 * i + 3, e, sizeof e);
    }
  }
  if (p) memcpy(p, e, sizeof e);
  if (s) memcpy(s, M + 3, 3 * sizeof *M);
  if (t) memcpy(t, M + 6, 3 * sizeof *M);
}

void lsys_ik_forward (const lsys_ikchain *c, const double *a, double p[3], double s[3],
                      double t[3], double *frames, double *pts) {
  run(c, a, p, s, t, frames, pts, NULL, NULL);
}

/* ---------------------------------------------------------------------- */
/* objective (1) and its gradient (7-11) */

/* f and g with the scratch 'piv' (3n) and 'axes' (9n). */
static double objective (const lsys_ikchain *c, const lsys_ikgoal *G, const double *a,
                         double *g, double *piv, double *axes, double *pst) {
  double p[3], s[3], t[3], dp[3], ds[3], dt[3], f;
  int i, k, n = c->n;
  run(c, a, p, s, t, NULL, NULL, g ? piv : NULL, g ? axes : NULL);
  if (pst != NULL) {
    memcpy(pst, p, sizeof p);
    memcpy(pst + 3, s, sizeof s);
    memcpy(pst + 6, t, sizeof t);
  }
  for (k = 0; k < 3; k++) {
    dp[k] = p[k] - G->p[k];
    ds[k] = s[k] - G->s[k];
    dt[k] = t[k] - G->t[k];
  }
  f = G->wp * vdot(dp, dp) + G->wt * (vdot(ds, ds) + vdot(dt, dt));
  for (i = 0; i < n; i++) {
    const lsys_ikjoint *j = &c->j[i];
    for (k = 0; k < 3; k++) {
      double d = a[3 * i + k] - j->rest[k];
      f += G->we * j->stiff[k] * d * d;
      if (i + 1 < n) {
        double d1 = a[3 * (i + 1) + k] - c->j[i + 1].rest[k] - d;
        f += G->ws * d1 * d1;
      }
    }
  }
  if (g == NULL) return f;
  for (i = 0; i < n; i++) {
    const lsys_ikjoint *j = &c->j[i];
    double v[3];
    for (k = 0; k < 3; k++) v[k] = p[k] - piv[3 * i + k];
    for (k = 0; k < 3; k++) {
      const double *w = axes + 9 * i + 3 * k;
      double wv[3], ws_[3], wt_[3], d, gi;
      if (!(j->free & (1u << k))) { g[3 * i + k] = 0; continue; }
      vcross(wv, w, v);                   /* dp/da (8) */
      vcross(ws_, w, s);                  /* ds/da (9) */
      vcross(wt_, w, t);
      d = a[3 * i + k] - j->rest[k];
      gi = 2 * G->wp * vdot(dp, wv) + 2 * G->wt * (vdot(ds, ws_) + vdot(dt, wt_)) +
           2 * G->we * j->stiff[k] * d;                                  /* (10) */
      if (i > 0) gi += 2 * G->ws * (d - (a[3 * (i - 1) + k] - c->j[i - 1].rest[k]));
      if (i + 1 < n) gi -= 2 * G->ws * (a[3 * (i + 1) + k] - c->j[i + 1].rest[k] - d);
      g[3 * i + k] = gi;                  /* (11) */
    }
  }
  return f;
}

typedef struct work {
  const lsys_ikchain *c;
  const lsys_ikgoal *goal;
  double *piv, *axes;
  double pst[9];          /* p, s, t of the last evaluation (for the preconditioner) */
} work;

static double cgfn (void *ud, const double *x, double *g, int n) {
  work *w = (work *)ud;
  (void)n;
  return objective(w->c, w->goal, x, g, w->piv, w->axes, w->pst);
}

/*
** The preconditioner: the diagonal of the Gauss-Newton Hessian of (1),
**   2 wp |w x (p - x_i)|^2 + 2 wt (|w x s|^2 + |w x t|^2) + 2 we s_ik + 2 ws (neighbours),
** from the joint axes and pivots of the last evaluation (the line search ends
** by evaluating the point it accepts). The stiffness of a plant varies as r^4
** along its branches, so without it the problem is badly conditioned.
*/
static void precond (void *ud, const double *x, const double *g, double *z, int n) {
  const work *w = (const work *)ud;
  const lsys_ikchain *c = w->c;
  const lsys_ikgoal *G = w->goal;
  const double *p = w->pst, *s = w->pst + 3, *t = w->pst + 6;
  int i, k;
  (void)x;
  (void)n;
  for (i = 0; i < c->n; i++) {
    double v[3];
    for (k = 0; k < 3; k++) v[k] = p[k] - w->piv[3 * i + k];
    for (k = 0; k < 3; k++) {
      const double *ax = w->axes + 9 * i + 3 * k;
      double jp[3], js[3], jt[3], h;
      vcross(jp, ax, v);
      vcross(js, ax, s);
      vcross(jt, ax, t);
      h = 2 * G->wp * vdot(jp, jp) + 2 * G->wt * (vdot(js, js) + vdot(jt, jt)) +
          2 * G->we * c->j[i].stiff[k] + 2 * G->ws * ((i > 0) + (i + 1 < c->n));
      z[3 * i + k] = h > 1e-300 ? g[3 * i + k] / h : g[3 * i + k];
    }
  }
}

/*
** The Gauss-Newton curvature of (1) along d, for the line search's first trial:
** with omega_i = sum_k d_ik w_ik the turn of joint i and Omega their sum, the
** first-order changes are dp = sum_i omega_i x (p - x_i), ds = Omega x s and
** dt = Omega x t (eqs. 8-9), so d'Hd ~ 2 wp |dp|^2 + 2 wt (|ds|^2 + |dt|^2)
** + 2 we sum s_ik d_ik^2 + 2 ws sum (d_i+1,k - d_ik)^2.
*/
static double curv (void *ud, const double *x, const double *d, int n) {
  const work *w = (const work *)ud;
  const lsys_ikchain *c = w->c;
  const lsys_ikgoal *G = w->goal;
  const double *p = w->pst, *s = w->pst + 3, *t = w->pst + 6;
  double jp[3] = {0, 0, 0}, om[3] = {0, 0, 0}, js[3], jt[3], e = 0, sm = 0;
  int i, k;
  (void)x;
  (void)n;
  for (i = 0; i < c->n; i++) {
    const double *ax = w->axes + 9 * i, *di = d + 3 * i;
    double oi[3], v[3], r[3];
    for (k = 0; k < 3; k++) {
      oi[k] = di[0] * ax[k] + di[1] * ax[3 + k] + di[2] * ax[6 + k];
      v[k] = p[k] - w->piv[3 * i + k];
      om[k] += oi[k];
    }
    vcross(r, oi, v);
    for (k = 0; k < 3; k++) {
      jp[k] += r[k];
      e += c->j[i].stiff[k] * di[k] * di[k];
      if (i + 1 < c->n) sm += (di[3 + k] - di[k]) * (di[3 + k] - di[k]);
    }
  }
  vcross(js, om, s);
  vcross(jt, om, t);
  return 2 * G->wp * vdot(jp, jp) + 2 * G->wt * (vdot(js, js) + vdot(jt, jt)) + 2 * G->we * e +
         2 * G->ws * sm;
}

double lsys_ik_objective (const lsys_ikchain *c, const lsys_ikgoal *goal, const double *a,
                          double *g, void *work) {
  double sp[12 * 64], *piv = work != NULL ? (double *)work : sp, f;
  if (g != NULL && work == NULL && c->n > 64) {
    piv = (double *)LSYS_MALLOC((size_t)c->n * 12 * sizeof *piv);
    if (piv == NULL) return NAN;
  }
  f = objective(c, goal, a, g, piv, piv + 3 * (size_t)c->n, NULL);
  if (piv != sp && piv != work) LSYS_FREE(piv);
  return f;
}

/* scratch: pivots and axes (12n), the angles (3n), then the minimiser's */
size_t lsys_ik_work_size (int n) {
  return (size_t)n * 15 * sizeof(double) + lsys_cg_work_size(3 * n);
}

int lsys_ik_solve (lsys_ikchain *c, const lsys_ikgoal *goal, const lsys_cg_opts *o,
                   void *mem, lsys_ik_result *res, lsys_error *e) {
  lsys_cg_opts def, opts;
  work w;
  double *x, p[3], d[3];
  int i, k, st, own = mem == NULL;
  if (c->n < 1) return lsys_seterror(e, LSYS_EARG, (size_t)-1, "an empty branch path");
  if (own && (mem = LSYS_MALLOC(lsys_ik_work_size(c->n))) == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory for the solver");
  if (o == NULL) {
    /* for dragging: stop once two iterations in a row gain less than a millionth of
    ** the starting objective (the pose no longer changes visibly) */
    lsys_cg_defaults(&def);
    def.ftol = -1;               /* set below, when f0 is known */
    o = &def;
  }
  w.c = c;
  w.goal = goal;
  w.piv = (double *)mem;
  w.axes = w.piv + 3 * (size_t)c->n;
  x = w.axes + 9 * (size_t)c->n;
  for (i = 0; i < c->n; i++)
    for (k = 0; k < 3; k++) x[3 * i + k] = c->j[i].alpha[k];
  res->f0 = objective(c, goal, x, NULL, NULL, NULL, NULL);
  if (o == &def) def.ftol = isfinite(res->f0) && res->f0 > 0 ? 1e-6 * fmin(res->f0, 1) : 0;
  if (o->precond == NULL) {    /* the Gauss-Newton diagonal below, unless given another */
    opts = *o;
    opts.precond = precond;
    opts.prec_ud = &w;
    o = &opts;
  }
  if (o->curv == NULL) {       /* and the Gauss-Newton curvature for the first trials */
    if (o != &opts) opts = *o;
    opts.curv = curv;
    opts.curv_ud = &w;
    o = &opts;
  }
  st = lsys_cg_minimize(cgfn, &w, x, 3 * c->n, o, x + 3 * (size_t)c->n, &res->cg, e);
  if (st == LSYS_OK) {
    for (i = 0; i < c->n; i++)
      for (k = 0; k < 3; k++) c->j[i].alpha[k] = x[3 * i + k];
    res->f = res->cg.f;
    run(c, NULL, p, NULL, NULL, NULL, NULL, NULL, NULL);
    for (k = 0; k < 3; k++) d[k] = p[k] - goal->p[k];
    res->dist = vlen(d);
  }
  if (own) LSYS_FREE(mem);
  return st;
}
