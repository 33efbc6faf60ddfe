/*
** Nonlinear conjugate gradients (Polak-Ribiere, PR+) with a strong Wolfe
** line search, written from Nocedal & Wright, Numerical Optimization:
** Alg. 3.5 (bracketing) and 3.6 (zoom), the cubic interpolation of eq. 3.59,
** the initial step of eq. 3.60 and the PR+ method of ch. 5.2.
**
** Notation: x the current point, g its gradient, d the search direction,
** phi(a) = f(x + a d) and phi'(a) = g(x + a d).d its slope. The workspace
** holds g, d and the trial point xt with its gradient gt; an accepted trial
** becomes the new point by copying xt into x and swapping g and gt, so the
** gradient computed by the line search is reused.
*/
#include <float.h>
#include <limits.h>
#include <math.h>
#include <string.h>

#include "cg.h"

#define LSMAX   30      /* evaluations per line search (one more for a fallback) */
#define EXTMIN  1.0     /* bracketing: the next trial is a + [EXTMIN, EXTMAX] (a - a_prev) */
#define EXTMAX  4.0
#define SAFE    0.1     /* zoom: trials stay SAFE * width away from the interval's ends */
#define GROW    10.0    /* a first trial moves x at most GROW times as far as the last step */
#define EPSF    1e-10   /* values within EPSF |f| of each other are equal, as far as we know */

void lsys_cg_defaults (lsys_cg_opts *o) {
  o->max_iter = 200;
  o->gtol = 1e-8;
  o->ftol = 1e-12;
  o->c1 = 1e-4;
  o->c2 = 0.1;
  o->restart = 0;
  o->max_eval = 0;
  o->step0 = 0;
  o->on_step = NULL;
  o->step_ud = NULL;
  o->precond = NULL;
  o->prec_ud = NULL;
  o->curv = NULL;
  o->curv_ud = NULL;
}

size_t lsys_cg_work_size (int n) {
  if (n < 1 || (size_t)n > ((size_t)-1) / (6 * sizeof(double))) return 0;
  return 6 * (size_t)n * sizeof(double);      /* g, d, xt, gt, and z, zt for precond */
}

static double dot (const double *a, const double *b, int n) {
  double s = 0;
  int i;
  for (i = 0; i < n; i++) s += a[i] * b[i];
  return s;
}

/* ||v||_inf; NaN when some entry is NaN. */
static double normi (const double *v, int n) {
  double m = 0;
  int i;
  for (i = 0; i < n; i++) {
    double a = fabs(v[i]);
    if (isnan(a)) return a;
    if (a > m) m = a;
  }
  return m;
}

/* ---------------------------------------------------------------------- */
/* Line search */

typedef struct search {
  lsys_cg_fn f;
  void *ud;
  int n;
  const double *x, *d;    /* the point and the direction */
  double *xt, *gt;        /* the last trial point and its gradient */
  double at;              /* the step of the point in xt, gt (-1: none) */
  double ft, dt;          /* phi and phi' there (ft = +inf outside the domain) */
  double f0, d0;          /* phi(0), phi'(0) < 0 */
  double epsf;            /* the noise level of values: EPSF |f0| */
  double c1, c2;
  double best, fbest;     /* the trial with the lowest phi, and that phi */
  int *evals;             /* the solver's evaluation count */
  int left;               /* evaluations this search may still make */
} search;

/* Evaluates phi and phi' at step 'a' into s->xt, s->gt, s->ft, s->dt. A
** non-finite value or slope (outside the domain) is recorded as ft = +inf. */
static void trial (search *s, double a) {
  int i;
  for (i = 0; i < s->n; i++) s->xt[i] = s->x[i] + a * s->d[i];
  s->ft = s->f(s->ud, s->xt, s->gt, s->n);
  (*s->evals)++;
  s->left--;
  s->at = a;
  s->dt = dot(s->gt, s->d, s->n);
  if (!isfinite(s->ft) || !isfinite(s->dt)) s->ft = HUGE_VAL;
  else if (s->ft < s->fbest) {
    s->fbest = s->ft;
    s->best = a;
  }
}

static int armijo (const search *s, double a) {
  return s->ft <= s->f0 + s->c1 * a * s->d0;
}

static int curvature (const search *s) {
  return fabs(s->dt) <= s->c2 * fabs(s->d0);
}

/* The minimiser of the cubic with values fa, fb and slopes da, db at a and
** b (N&W eq. 3.59); NaN when the cubic has no minimiser. */
static double cubicmin (double a, double fa, double da, double b, double fb, double db) {
  double d1 = da + db - 3 * (fa - fb) / (a - b);
  double r = d1 * d1 - da * db, d2, den;
  if (!(r >= 0)) return NAN;
  d2 = b > a ? sqrt(r) : -sqrt(r);
  den = db - da + 2 * d2;
  if (den == 0) return NAN;
  return b - (b - a) * (db + d2 - d1) / den;
}

#define LS_WOLFE     0  /* strong Wolfe step found */
#define LS_FALLBACK  1  /* no Wolfe step, but the best trial (in xt, gt) lowers f */
#define LS_FAIL      2  /* no decrease found */
#define LS_BUDGET    3  /* the solver's evaluations ran out first */

/* Last resort when the search gives up: the best trial if it lowers f
** (evaluated again when xt no longer holds it). 'own' tells whether
** s->left was the search's own cap, below what the solver has left. */
static int fallback (search *s, int own) {
  int more = own || s->left > 0;        /* the solver may still evaluate f */
  if (s->fbest < s->f0) {
    if (s->at == s->best) return LS_FALLBACK;
    if (more) {
      s->left = 1;
      trial(s, s->best);
      if (s->ft < s->f0) return LS_FALLBACK;
    }
  }
  return more ? LS_FAIL : LS_BUDGET;
}

/*
** Strong Wolfe line search from step 'a' (> 0); 'maxeval' is what remains
** of the solver's evaluations. On LS_WOLFE or LS_FALLBACK the step taken
** is s->at, and xt, gt, ft, dt describe the new point.
**
** Near a minimum the decrease a step can bring falls below the rounding
** noise of f, and comparisons of values say nothing. A trial whose value
** is within s->epsf of the one it is compared with is then judged by its
** slope alone: it is accepted when it satisfies the curvature condition
** (an "approximate Wolfe" step: for a quadratic phi that condition implies
** sufficient decrease), and otherwise its slope tells which way the
** minimiser along d lies.
*/
static int linesearch (search *s, double a, int maxeval) {
  double ap = 0, fp = s->f0, dp = s->d0;          /* previous trial */
  double lo, flo, dlo, hi, fhi, dhi;
  int i, own = maxeval > LSMAX;                   /* whether 'left' is our own cap */
  s->left = own ? LSMAX : maxeval;
  s->at = -1;
  s->best = 0;
  s->fbest = s->f0;
  /* Bracketing (Alg. 3.5): grow the step until [ap, a] holds a Wolfe step. */
  for (i = 1; ; i++) {
    double lob, hib, c;
    int bad;
    if (s->left <= 0) return fallback(s, own);
    trial(s, a);
    bad = !armijo(s, a) || (i > 1 && s->ft >= fp);  /* also outside the domain */
    if (curvature(s) && (!bad || s->ft <= s->f0 + s->epsf)) return LS_WOLFE;
    if (bad && (s->ft > fp + s->epsf || s->dt >= 0)) {
      lo = ap; flo = fp; dlo = dp;
      hi = a; fhi = s->ft; dhi = s->dt;
      break;
    }
    if (s->dt >= 0) {                               /* phi turned up: [a, ap] */
      lo = a; flo = s->ft; dlo = s->dt;
      hi = ap; fhi = fp; dhi = dp;
      break;
    }
    /* still going down: extrapolate by the cubic, within limits */
    lob = a + EXTMIN * (a - ap);
    hib = a + EXTMAX * (a - ap);
    c = cubicmin(ap, fp, dp, a, s->ft, s->dt);
    if (!(c > a) || c > hib) c = hib;
    else if (c < lob) c = lob;
    ap = a; fp = s->ft; dp = s->dt;
    a = c;
  }
  /* Zoom (Alg. 3.6): lo is the best step so far (it satisfies the
  ** sufficient decrease condition, up to noise), and phi'(lo) (hi - lo) < 0. */
  for (;;) {
    double l = fmin(lo, hi), u = fmax(lo, hi), c;
    int bad;
    if (s->left <= 0 || u - l <= DBL_EPSILON * u) return fallback(s, own);
    c = isfinite(fhi) ? cubicmin(lo, flo, dlo, hi, fhi, dhi) : NAN;
    if (!(c > l && c < u)) c = lo + 0.5 * (hi - lo);   /* bisection (hi outside the domain) */
    else c = fmin(fmax(c, l + SAFE * (u - l)), u - SAFE * (u - l));
    trial(s, c);
    bad = !armijo(s, c) || s->ft >= flo;
    if (curvature(s) && (!bad || s->ft <= s->f0 + s->epsf)) return LS_WOLFE;
    if (bad && (s->ft > flo + s->epsf || s->dt * (hi - lo) >= 0)) {
      hi = c; fhi = s->ft; dhi = s->dt;
    }
    else {                    /* c is better than lo, or as good and still going down */
      if (!bad && s->dt * (hi - lo) >= 0) {
        hi = lo; fhi = flo; dhi = dlo;
      }
      lo = c; flo = s->ft; dlo = s->dt;
    }
  }
}

/* ---------------------------------------------------------------------- */
/* The solver */

static int checkopts (const lsys_cg_opts *o, lsys_error *e) {
  if (o->max_iter < 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "max_iter must be >= 0, got %d", o->max_iter);
  if (!(o->gtol >= 0) || !(o->ftol >= 0))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "gtol and ftol must be >= 0");
  if (!(0 < o->c1 && o->c1 < o->c2 && o->c2 < 1))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "Wolfe constants need 0 < c1 < c2 < 1, got c1 = %g, c2 = %g",
                         o->c1, o->c2);
  if (o->restart < 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "restart must be >= 0, got %d", o->restart);
  if (o->max_eval < 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "max_eval must be >= 0, got %d", o->max_eval);
  if (!(o->step0 >= 0) || isinf(o->step0))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "step0 must be finite and >= 0");
  return LSYS_OK;
}

/* The first trial from the caller's curvature estimate: the minimiser of
** the quadratic model along d (slope 'd0' < 0 at 0), at most GROW times
** the usual trial 'a0'; a0 when there is no estimate. */
static double modelstep (const lsys_cg_opts *o, const double *x, const double *d, int n,
                         double d0, double a0) {
  double c, a;
  if (o->curv == NULL) return a0;
  c = o->curv(o->curv_ud, x, d, n);
  a = -d0 / c;
  if (!(c > 0 && isfinite(a) && a > 0)) return a0;
  return a < GROW * a0 ? a : GROW * a0;
}

int lsys_cg_minimize (lsys_cg_fn f, void *ud, double *x, int n, const lsys_cg_opts *o,
                      void *work, lsys_cg_result *res, lsys_error *e) {
  lsys_cg_opts def;
  search s;
  double *w, *g, *d, *t, *z, *zt;
  double fx, gnorm, gg, alpha;
  int st, maxeval, restart, i, evals = 0, k = 0, small = 0;
  if (f == NULL || x == NULL || res == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "missing %s",
                         f == NULL ? "objective function" : x == NULL ? "x" : "result");
  if (n < 1 || lsys_cg_work_size(n) == 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "bad number of variables %d", n);
  if (o == NULL) {
    lsys_cg_defaults(&def);
    o = &def;
  }
  if ((st = checkopts(o, e)) != LSYS_OK) return st;
  maxeval = o->max_eval > 0 ? o->max_eval
          : o->max_iter < INT_MAX / 20 ? 20 * o->max_iter : INT_MAX;
  if (maxeval < 1) maxeval = 1;
  restart = o->restart > 0 ? o->restart : n;
  w = (double *)work;
  if (w == NULL && (w = (double *)LSYS_MALLOC(lsys_cg_work_size(n))) == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  memset(res, 0, sizeof *res);
  g = w; d = w + n;
  s.f = f; s.ud = ud; s.n = n;
  s.x = x; s.d = d; s.xt = w + 2 * n; s.gt = w + 3 * n;
  s.c1 = o->c1; s.c2 = o->c2;
  s.evals = &evals;
  fx = f(ud, x, g, n);
  evals++;
  gnorm = normi(g, n);
  if (!isfinite(fx) || !isfinite(gnorm)) {
    st = lsys_seterror(e, LSYS_EARG, (size_t)-1, "%s is not finite at the start point",
                       isfinite(fx) ? "the gradient" : "the function");
    goto done;
  }
  /* preconditioned PR+ (N&W §5.2): z = M^-1 g replaces g in the direction and in
  ** beta = z_new.(g_new - g) / z.g; without a preconditioner z is g itself */
  z = g;
  zt = s.gt;
  if (o->precond != NULL) {
    z = w + 4 * n;
    zt = w + 5 * n;
    o->precond(o->prec_ud, x, g, z, n);
  }
  gg = dot(z, g, n);
  if (!(gg > 0)) {            /* a preconditioner that is not positive definite here */
    z = g;
    zt = s.gt;
    gg = dot(g, g, n);
  }
  for (i = 0; i < n; i++) d[i] = -z[i];
  alpha = o->step0 > 0 ? o->step0 : z != g ? 1 : 1 / sqrt(gg);
  if (!(isfinite(alpha) && alpha > 0)) alpha = 1 / gnorm;   /* gg overflowed */
  if (o->step0 == 0) alpha = modelstep(o, x, d, n, -gg, alpha);
  for (;;) {
    double d0, dn, beta, gtg, ggt, a0;
    int r;
    if (gnorm == 0 || gnorm <= o->gtol * fmax(1, fabs(fx))) { res->status = LSYS_CG_GTOL; break; }
    if (small >= 2) { res->status = LSYS_CG_FTOL; break; }
    if (res->iterations >= o->max_iter) { res->status = LSYS_CG_MAXITER; break; }
    if (evals >= maxeval) { res->status = LSYS_CG_MAXEVAL; break; }
    s.f0 = fx;
    s.d0 = d0 = dot(g, d, n);                   /* < 0: d is a descent direction */
    s.epsf = EPSF * fabs(fx);
    r = linesearch(&s, alpha, maxeval - evals);
    if (r == LS_FAIL) { res->status = LSYS_CG_LINESEARCH; break; }
    if (r == LS_BUDGET) { res->status = LSYS_CG_MAXEVAL; break; }
    if (o->on_step != NULL) o->on_step(o->step_ud, s.at, fx, d0, s.ft, s.dt);
    /* accept: x = xt, g <-> gt; beta_PR = zt.(gt - g) / z.g (zt = gt unpreconditioned) */
    memcpy(x, s.xt, (size_t)n * sizeof *x);
    if (z != g) {
      o->precond(o->prec_ud, x, s.gt, zt, n);
      ggt = dot(zt, s.gt, n);
      gtg = dot(zt, g, n);
      t = z; z = zt; zt = t;
    } else {
      ggt = dot(s.gt, s.gt, n);
      gtg = dot(s.gt, g, n);
    }
    beta = (ggt - gtg) / gg;
    t = g; g = s.gt; s.gt = t;
    if (z == s.gt) z = g;        /* unpreconditioned: z follows g through the swap */
    small = fx - s.ft <= o->ftol * fmax(1, fabs(s.ft)) ? small + 1 : 0;
    fx = s.ft;
    gg = ggt;
    gnorm = normi(g, n);
    res->iterations++;
    k++;
    /* the next direction d = -g + beta d, or -g on a restart */
    alpha = s.at * normi(d, n);                 /* how far x moved */
    if (r == LS_WOLFE && k < restart && beta > 0 && isfinite(beta)) {
      for (i = 0; i < n; i++) d[i] = -z[i] + beta * d[i];
      dn = dot(g, d, n);
    }
    else dn = 0;                                /* restart */
    if (!(dn < 0)) {
      for (i = 0; i < n; i++) d[i] = -z[i];
      dn = -gg;
      k = 0;
      res->restarts++;
    }
    /* first trial (N&W eq. 3.60): the same first-order change as the last
    ** step, moving x at most GROW times as far */
    a0 = s.at * d0 / dn;
    alpha /= normi(d, n);                       /* the step moving x as far as the last */
    if (!(a0 > 0 && a0 <= GROW * alpha)) a0 = isfinite(a0) && a0 > 0 ? GROW * alpha : alpha;
    alpha = modelstep(o, x, d, n, dn, a0);
  }
  res->f = fx;
  res->gnorm = gnorm;
  st = LSYS_OK;
done:
  res->evaluations = evals;
  if (work == NULL) LSYS_FREE(w);
  return st;
}
