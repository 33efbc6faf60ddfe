/*
** Unconstrained minimisation by nonlinear conjugate gradients: the
** Polak-Ribiere method with beta = max(0, beta_PR) ("PR+"), restarted with
** steepest descent every 'restart' iterations, when beta_PR < 0 and when the
** new direction is not a descent direction; each step is found by a line
** search satisfying the strong Wolfe conditions (bracketing, then zoom with
** safeguarded cubic interpolation). Reference: Nocedal & Wright, Numerical
** Optimization (2nd ed.), Alg. 3.5/3.6, eq. 3.59/3.60 and ch. 5.2.
**
** Two departures from the textbook, both for the end game: where values of
** f differ by less than their rounding noise (taken as 1e-10 |f|) the line
** search judges trials by their slope alone, and accepts a step satisfying
** the curvature condition even if f rose by that noise ("approximate
** Wolfe", after Hager & Zhang); and when a line search runs out of
** evaluations without a Wolfe step, its best trial is accepted if it
** lowers f (a "fallback" step), followed by a restart.
**
** Used to fit shapes while the user drags: a solve allocates nothing when
** given a workspace (lsys_cg_work_size).
*/
#ifndef LSYS_CG_H
#define LSYS_CG_H

#include "common.h"

/* Why lsys_cg_minimize stopped (lsys_cg_result.status). */
#define LSYS_CG_GTOL        1   /* gradient small enough: converged */
#define LSYS_CG_FTOL        2   /* f stopped decreasing: converged as far as f can tell */
#define LSYS_CG_MAXITER     3   /* max_iter iterations done */
#define LSYS_CG_MAXEVAL     4   /* max_eval evaluations done; x is the last accepted point */
#define LSYS_CG_LINESEARCH  5   /* no decrease found along the direction (x, the best point
                                   found, has not moved: typically f's noise level reached) */

/* Value and gradient of the objective at x (n values): returns f(x) and
** fills g (n values). A non-finite return value (or a non-finite gradient)
** means "outside the domain": the line search backs off towards the last
** good point. 'ud' is the pointer given to lsys_cg_minimize. */
typedef double (*lsys_cg_fn) (void *ud, const double *x, double *g, int n);

/* Called after every accepted step x1 = x0 + alpha d (a test hook): f0, f1
** are f at x0 and x1, g0d and g1d the slopes g(x0).d and g(x1).d along d.
** Steps satisfy the strong Wolfe conditions f1 <= f0 + c1 alpha g0d and
** |g1d| <= c2 |g0d|, except approximate Wolfe steps, which satisfy the second
** and f1 <= f0 + 1e-10 |f0|, and fallback steps, which satisfy only f1 < f0
** (see above). */
typedef void (*lsys_cg_stepfn) (void *ud, double alpha, double f0, double g0d, double f1,
                                double g1d);

/* z = M^-1 g at x (n values). */
typedef void (*lsys_cg_precfn) (void *ud, const double *x, const double *g, double *z, int n);

/* An estimate of the curvature d' H(x) d of f along d at x (H the Hessian or
** an approximation such as Gauss-Newton's); <= 0 or not finite: no estimate. */
typedef double (*lsys_cg_curvfn) (void *ud, const double *x, const double *d, int n);

typedef struct lsys_cg_opts {
  int max_iter;           /* iteration (accepted step) cap, >= 0 (default 200) */
  double gtol;            /* stop when ||g||_inf <= gtol * max(1, |f|), >= 0 (default 1e-8) */
  double ftol;            /* stop when the decrease of f over an iteration is
                             <= ftol * max(1, |f|) for 2 consecutive iterations, >= 0
                             (default 1e-12) */
  double c1, c2;          /* strong Wolfe constants, 0 < c1 < c2 < 1 (defaults 1e-4 and
                             0.1, as usual for CG; c2 < 1/2 is advisable) */
  int restart;            /* restart with steepest descent every 'restart' iterations
                             (0 = n, the default); restarts also happen when beta_PR < 0,
                             when -g.d <= 0 and after a fallback step */
  int max_eval;           /* cap on evaluations of f, counting the first
                             (0 = 20 * max_iter but at least 1: the default) */
  double step0;           /* first trial step of the first line search, as a multiple of
                             d = -g (0 = 1 / ||g||_2, a step of length 1: the default) */
  lsys_cg_precfn precond; /* a preconditioner z = M^-1 g (M symmetric positive definite,
                             e.g. the diagonal of the Hessian), or NULL (default: none).
                             Called once per iteration at the accepted point; the first
                             trial step is then 1 (a Newton step when M is the Hessian) */
  void *prec_ud;          /* first argument of precond */
  lsys_cg_curvfn curv;    /* the curvature along each search direction, or NULL (default).
                             When given, each line search first tries the minimiser
                             -g.d / curv of the quadratic model along d (at most 10 times
                             as far as eq. 3.60's trial); called at the current point right
                             after f was evaluated there */
  void *curv_ud;          /* first argument of curv */
  lsys_cg_stepfn on_step; /* test hook called on each accepted step, or NULL (default) */
  void *step_ud;          /* first argument of on_step */
} lsys_cg_opts;

typedef struct lsys_cg_result {
  int iterations;         /* accepted steps */
  int evaluations;        /* calls of f, the one at the start included */
  int restarts;           /* steepest-descent restarts after the first iteration */
  double f;               /* f at the final x */
  double gnorm;           /* ||g||_inf at the final x */
  int status;             /* LSYS_CG_*: why the solver stopped */
} lsys_cg_result;

/* Fills 'o' with the defaults above. */
void lsys_cg_defaults (lsys_cg_opts *o);

/* Bytes of workspace for n variables: 4n doubles (0 when n < 1 or the size
** overflows). Allocate it once and pass it to every solve of that size or
** smaller: the solver then allocates nothing. */
size_t lsys_cg_work_size (int n);

/*
** Minimises f from x (n >= 1 values), in place: on return x holds the last
** accepted point, where res->f and res->gnorm were computed (each accepted
** point lowers f, up to rounding noise, so it is the best point found but
** for that noise). 'o' may be NULL
** (defaults). 'work' is lsys_cg_work_size(n) bytes aligned for double, or
** NULL: then it is allocated and freed inside (LSYS_ENOMEM, e set, when
** that fails). Returns LSYS_OK, with the reason for stopping in res->status,
** or LSYS_EARG (e->msg set, x unchanged) when f is NULL, x or res is NULL,
** n < 1, an option is out of range, or f or its gradient is not finite at
** the start.
*/
int lsys_cg_minimize (lsys_cg_fn f, void *ud, double *x, int n, const lsys_cg_opts *o,
                      void *work, lsys_cg_result *res, lsys_error *e);

#endif
