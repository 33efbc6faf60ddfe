/*
** C unit tests for the conjugate-gradient minimiser (csrc/core/cg.c): Rosenbrock
** in 2, 10 and 100 dimensions, quadratics with a known minimum (diagonal
** and random SPD), the strong Wolfe conditions on every accepted step, each
** way of stopping, bad arguments, an objective undefined outside a region,
** and the caller's workspace (no allocation, same results).
**
** cg.c is compiled into this test with counting allocators, so that a
** solve with a workspace can be shown to allocate nothing and the
** allocation of the internal one can be made to fail.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "cg.c"

#define PI 3.14159265358979323846

/* ---------------------------------------------------------------------- */
/* Objectives */

/* Extended Rosenbrock (n even): the sum over the pairs (x_2i, x_2i+1) of
** 100 (x_2i+1 - x_2i^2)^2 + (1 - x_2i)^2; minimum 0 at x = 1. */
static double rosen (void *ud, const double *x, double *g, int n) {
  double f = 0;
  int i;
  (void)ud;
  for (i = 0; i < n; i += 2) {
    double u = x[i + 1] - x[i] * x[i], v = 1 - x[i];
    f += 100 * u * u + v * v;
    g[i] = -400 * x[i] * u - 2 * v;
    g[i + 1] = 200 * u;
  }
  return f;
}

/* f = 1/2 x'Ax - b'x, A dense n x n (row-major), gradient Ax - b. */
typedef struct quad { int n; const double *a, *b; } quad;

static double quadf (void *ud, const double *x, double *g, int n) {
  const quad *q = (const quad *)ud;
  double f = 0;
  int i, j;
  assert(n == q->n);
  for (i = 0; i < n; i++) {
    double ax = 0;
    for (j = 0; j < n; j++) ax += q->a[i * n + j] * x[j];
    g[i] = ax - q->b[i];
    f += x[i] * (0.5 * ax - q->b[i]);
  }
  return f;
}

/* d'Ad, the curvature of quadf along d. */
static double quadcurv (void *ud, const double *x, const double *d, int n) {
  const quad *q = (const quad *)ud;
  double c = 0;
  int i, j;
  (void)x;
  for (i = 0; i < n; i++)
    for (j = 0; j < n; j++) c += d[i] * q->a[i * n + j] * d[j];
  return c;
}

/* Barrier: f = sum (a_i x_i - log x_i), minimum at x_i = 1 / a_i; NaN
** where some x_i <= 0 (counted in 'outside'). */
static int outside;

static double barrier (void *ud, const double *x, double *g, int n) {
  double f = 0;
  int i;
  (void)ud;
  for (i = 0; i < n; i++) {
    if (!(x[i] > 0)) {
      outside++;
      return NAN;
    }
    f += (i + 1) * x[i] - log(x[i]);
    g[i] = (i + 1) - 1 / x[i];
  }
  return f;
}

/* x^2 with the gradient's sign wrong: -g points uphill. */
static double wrongslope (void *ud, const double *x, double *g, int n) {
  (void)ud; (void)n;
  g[0] = -2 * x[0];
  return x[0] * x[0];
}

/* |x - pi| with slopes -1 and 1 (1 at pi too): never small, so the
** curvature condition never holds. */
static double kink (void *ud, const double *x, double *g, int n) {
  (void)ud; (void)n;
  g[0] = x[0] >= PI ? 1 : -1;
  return fabs(x[0] - PI);
}

/* Simple seeded LCG (Knuth's MMIX constants): uniform in [-1, 1). */
static unsigned long long lcg = 12345;

static double rnd (void) {
  lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(lcg >> 11) / 4503599627370496.0 - 1;   /* 53 bits / 2^52 - 1 */
}

/* ---------------------------------------------------------------------- */
/* The Wolfe hook: every accepted step satisfies the strong Wolfe
** conditions; with 'noisy' set, steps that satisfy the curvature condition
** and raise f by at most the noise level EPSF |f0| (approximate Wolfe steps,
** taken where f cannot tell a decrease from rounding) are counted apart. */

typedef struct wolfe { double c1, c2; int steps, approx, noisy; } wolfe;

static void onstep (void *ud, double alpha, double f0, double g0d, double f1, double g1d) {
  wolfe *w = (wolfe *)ud;
  assert(alpha > 0 && g0d < 0);
  assert(fabs(g1d) <= w->c2 * fabs(g0d));       /* strong curvature condition */
  if (!(f1 <= f0 + w->c1 * alpha * g0d)) {      /* sufficient decrease */
    assert(w->noisy && f1 <= f0 + EPSF * fabs(f0));
    w->approx++;
  }
  w->steps++;
}

static void hook (lsys_cg_opts *o, wolfe *w) {
  w->c1 = o->c1;
  w->c2 = o->c2;
  w->steps = w->approx = w->noisy = 0;
  o->on_step = onstep;
  o->step_ud = w;
}

static void report (const char *name, const lsys_cg_result *r) {
  printf("  %-22s iterations %4d  evaluations %5d  restarts %4d  f %.3g  |g| %.3g  status %d\n",
         name, r->iterations, r->evaluations, r->restarts, r->f, r->gnorm, r->status);
}

static void startrosen (double *x, int n) {
  int i;
  for (i = 0; i < n; i += 2) {
    x[i] = -1.2;
    x[i + 1] = 1;
  }
}

/* ---------------------------------------------------------------------- */

static void test_rosenbrock (void) {
  static const int sizes[] = { 2, 10, 100 };
  double x[100];
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  wolfe w;
  int k, i;
  for (k = 0; k < 3; k++) {
    int n = sizes[k];
    char name[32];
    lsys_cg_defaults(&o);
    o.max_iter = 1000;
    hook(&o, &w);
    startrosen(x, n);
    assert(lsys_cg_minimize(rosen, NULL, x, n, &o, NULL, &r, &e) == LSYS_OK);
    snprintf(name, sizeof name, "rosenbrock n=%d", n);
    report(name, &r);
    assert(r.status == LSYS_CG_GTOL);
    assert(w.steps == r.iterations);            /* every step was a Wolfe step */
    assert(r.gnorm <= 1e-8 && r.f < 1e-15);
    for (i = 0; i < n; i++) assert(fabs(x[i] - 1) <= (n == 2 ? 1e-6 : 1e-5));
  }
}

/* A quadratic's result: stopped by itself (by the gradient or, at the noise
** level of f, because f stopped decreasing or no decrease could be found)
** within 3n iterations, x within 1e-6 of x*. */
static void checkquad (const lsys_cg_result *r, const wolfe *w, const double *x,
                       const double *xs, int n) {
  double err = 0;
  int i;
  assert(r->status == LSYS_CG_GTOL || r->status == LSYS_CG_FTOL ||
         r->status == LSYS_CG_LINESEARCH);
  assert(w->steps == r->iterations);
  assert(r->iterations <= 3 * n);
  for (i = 0; i < n; i++) err = fmax(err, fabs(x[i] - xs[i]));
  printf("  %-22s |x - x*|_inf %.2g, %d approximate Wolfe steps\n", "", err, w->approx);
  assert(err <= 1e-6);
}

/* Diagonal A, eigenvalues 1 .. 100 (condition number 100), n = 50. */
/* A diagonal A with condition number 100 (entries 1 to 100), x* = sin(i + 1),
** b = A x*, start x = 0. */
static void diagonal (double *a, double *b, double *xs, double *x, int n) {
  int i;
  for (i = 0; i < n; i++) {
    a[i * n + i] = 1 + 99.0 * i / (n - 1);
    xs[i] = sin(i + 1.0);
    b[i] = a[i * n + i] * xs[i];
    x[i] = 0;
  }
}

/* Minimises q from x with o (Wolfe-checked on every step, noise allowed) and
** checks the minimum xs was found; returns the solver's result. */
static lsys_cg_result solvequad (const char *name, quad *q, double *x, const double *xs,
                                 lsys_cg_opts *o) {
  lsys_cg_result r;
  lsys_error e;
  wolfe w;
  hook(o, &w);
  w.noisy = 1;
  assert(lsys_cg_minimize(quadf, q, x, q->n, o, NULL, &r, &e) == LSYS_OK);
  report(name, &r);
  checkquad(&r, &w, x, xs, q->n);
  return r;
}

static void test_diagonal (void) {
  enum { N = 50 };
  static double a[N * N];
  double b[N], xs[N], x[N];
  quad q = { N, a, b };
  lsys_cg_opts o;
  diagonal(a, b, xs, x, N);
  lsys_cg_defaults(&o);
  o.gtol = 1e-12;
  o.ftol = 0;           /* |f| ~ 600: f alone cannot place x within 1e-6 */
  solvequad("quadratic diag n=50", &q, x, xs, &o);
}

/* Jacobi preconditioner: z = g / diag(A). */
static void jacobi (void *ud, const double *x, const double *g, double *z, int n) {
  const quad *q = (const quad *)ud;
  int i;
  (void)x;
  for (i = 0; i < n; i++) z[i] = g[i] / q->a[i * n + i];
}

/* The diagonal quadratic with the exact (diagonal) preconditioner: one Newton step. */
static void test_precond (void) {
  enum { N = 50 };
  static double a[N * N];
  double b[N], xs[N], x[N];
  quad q = { N, a, b };
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  int i;
  diagonal(a, b, xs, x, N);
  lsys_cg_defaults(&o);
  o.gtol = 1e-12;
  o.ftol = 0;
  o.precond = jacobi;
  o.prec_ud = &q;
  assert(lsys_cg_minimize(quadf, &q, x, N, &o, NULL, &r, &e) == LSYS_OK);
  report("quadratic diag, Jacobi", &r);
  assert(r.iterations <= 2);
  for (i = 0; i < N; i++) assert(fabs(x[i] - xs[i]) < 1e-9);
}

/* A = M'M + I with M random (seeded), n = 20. */
static void test_spd (void) {
  enum { N = 20 };
  double m[N * N], a[N * N], b[N], xs[N], x[N];
  quad q = { N, a, b };
  lsys_cg_opts o;
  lsys_cg_result r;
  int i, j, k;
  lcg = 12345;
  for (i = 0; i < N * N; i++) m[i] = rnd();
  for (i = 0; i < N; i++)
    for (j = 0; j < N; j++) {
      double s = i == j;
      for (k = 0; k < N; k++) s += m[k * N + i] * m[k * N + j];
      a[i * N + j] = s;
    }
  for (i = 0; i < N; i++) xs[i] = rnd() * 3;
  for (i = 0; i < N; i++) {
    b[i] = 0;
    for (j = 0; j < N; j++) b[i] += a[i * N + j] * xs[j];
    x[i] = 0;
  }
  lsys_cg_defaults(&o);
  o.gtol = 1e-12;
  o.ftol = 0;           /* |f| ~ 600: f alone cannot place x within 1e-6 */
  solvequad("quadratic SPD n=20", &q, x, xs, &o);
  /* a nearly exact line search (c2 = 0.001): close to linear CG */
  for (i = 0; i < N; i++) x[i] = 0;
  o.c2 = 1e-3;
  solvequad("quadratic SPD c2=1e-3", &q, x, xs, &o);
  /* the exact curvature d'Ad: every first trial is the exact minimiser along d,
  ** so each line search takes one evaluation and PR+ is linear CG */
  for (i = 0; i < N; i++) x[i] = 0;
  o.c2 = 0.1;
  o.curv = quadcurv;
  o.curv_ud = &q;
  r = solvequad("quadratic SPD, exact curvature", &q, x, xs, &o);
  assert(r.evaluations == r.iterations + 1);
  assert(r.iterations <= 2 * N);
}

static void test_stops (void) {
  double x[2], x0[2];
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  int i;
  /* max_iter */
  lsys_cg_defaults(&o);
  o.max_iter = 5;
  startrosen(x, 2);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_MAXITER && r.iterations == 5);
  assert(r.f < 24.2 && r.evaluations > 5);      /* f(-1.2, 1) = 24.2 */
  o.max_iter = 0;
  startrosen(x, 2);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_MAXITER && r.iterations == 0 && r.evaluations == 1);
  assert(x[0] == -1.2 && x[1] == 1 && fabs(r.f - 24.2) < 1e-12);
  /* max_eval */
  lsys_cg_defaults(&o);
  o.max_eval = 10;
  startrosen(x, 2);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_MAXEVAL && r.evaluations == 10 && r.f < 24.2);
  /* at the minimum: g = 0 exactly, nothing to do */
  x[0] = x[1] = 1;
  lsys_cg_defaults(&o);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_GTOL && r.iterations == 0 && r.evaluations == 1);
  assert(x[0] == 1 && x[1] == 1 && r.f == 0 && r.gnorm == 0);
  /* gtol = 0 on a quadratic: stops when f no longer decreases */
  {
    double a[4] = { 3, 1, 1, 2 }, b[2] = { 1, 1 };
    quad q = { 2, a, b };
    lsys_cg_defaults(&o);
    o.gtol = 0;
    x[0] = 5; x[1] = -7;
    assert(lsys_cg_minimize(quadf, &q, x, 2, &o, NULL, &r, &e) == LSYS_OK);
    report("quadratic gtol=0", &r);
    assert(r.status == LSYS_CG_FTOL || r.status == LSYS_CG_LINESEARCH ||
           (r.status == LSYS_CG_GTOL && r.gnorm == 0));
    assert(fabs(x[0] - 0.2) < 1e-12 && fabs(x[1] - 0.4) < 1e-12);   /* A^-1 b */
  }
  /* an uphill "gradient": no decrease, x unchanged */
  x0[0] = x[0] = 3;
  lsys_cg_defaults(&o);
  assert(lsys_cg_minimize(wrongslope, NULL, x, 1, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_LINESEARCH && x[0] == x0[0] && r.f == 9 && r.iterations == 0);
  assert(r.evaluations > 1 && r.evaluations <= 2 + LSMAX);
  /* restart = 1: steepest descent, a restart after every step */
  lsys_cg_defaults(&o);
  o.restart = 1;
  o.max_iter = 20;
  startrosen(x, 2);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.status == LSYS_CG_MAXITER && r.restarts == 20);
  /* the default restart (n = 2) on n = 2 restarts at least every other step */
  lsys_cg_defaults(&o);
  startrosen(x, 2);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_OK);
  assert(r.restarts >= r.iterations / 2);
  for (i = 0; i < 2; i++) assert(fabs(x[i] - 1) < 1e-6);
}

static void test_args (void) {
  double x[2] = { -1.2, 1 }, nanx[2] = { NAN, 1 };
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  e.msg[0] = 0;
  assert(lsys_cg_minimize(rosen, NULL, x, 0, NULL, NULL, &r, &e) == LSYS_EARG);
  assert(e.code == LSYS_EARG && strcmp(e.msg, "bad number of variables 0") == 0);
  assert(lsys_cg_minimize(NULL, NULL, x, 2, NULL, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "missing objective function") == 0);
  assert(lsys_cg_minimize(rosen, NULL, x, 2, NULL, NULL, NULL, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "missing result") == 0);
  assert(lsys_cg_minimize(rosen, NULL, x, -3, NULL, NULL, &r, NULL) == LSYS_EARG);
  lsys_cg_defaults(&o);
  o.c1 = 0.5; o.c2 = 0.1;
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "Wolfe constants need 0 < c1 < c2 < 1, got c1 = 0.5, c2 = 0.1") == 0);
  lsys_cg_defaults(&o);
  o.gtol = NAN;
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "gtol and ftol must be >= 0") == 0);
  lsys_cg_defaults(&o);
  o.max_iter = -1;
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "max_iter must be >= 0, got -1") == 0);
  lsys_cg_defaults(&o);
  o.step0 = -1;
  assert(lsys_cg_minimize(rosen, NULL, x, 2, &o, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "step0 must be finite and >= 0") == 0);
  /* not finite at the start */
  assert(lsys_cg_minimize(rosen, NULL, nanx, 2, NULL, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "the function is not finite at the start point") == 0);
  nanx[0] = 0;
  assert(lsys_cg_minimize(barrier, NULL, nanx, 2, NULL, NULL, &r, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "the function is not finite at the start point") == 0);
  assert(x[0] == -1.2 && x[1] == 1);
  assert(lsys_cg_work_size(0) == 0 && lsys_cg_work_size(-1) == 0);
  assert(lsys_cg_work_size(3) == 18 * sizeof(double));
  assert(nlive == 0);
}

/* NaN outside x > 0: the line search backs off (a long first step forces it). */
static void test_domain (void) {
  double x[3] = { 5, 5, 5 };
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  wolfe w;
  int i;
  lsys_cg_defaults(&o);
  o.step0 = 100;
  hook(&o, &w);
  outside = 0;
  assert(lsys_cg_minimize(barrier, NULL, x, 3, &o, NULL, &r, &e) == LSYS_OK);
  report("barrier", &r);
  printf("  %-22s %d evaluations outside the domain\n", "", outside);
  assert(outside > 0);
  assert(r.status == LSYS_CG_GTOL && w.steps == r.iterations);
  for (i = 0; i < 3; i++) assert(fabs(x[i] - 1.0 / (i + 1)) < 1e-7);
  /* default first step, starting near the wall */
  for (i = 0; i < 3; i++) x[i] = 1e-3;
  lsys_cg_defaults(&o);
  hook(&o, &w);
  outside = 0;
  assert(lsys_cg_minimize(barrier, NULL, x, 3, &o, NULL, &r, &e) == LSYS_OK);
  report("barrier near the wall", &r);
  assert((r.status == LSYS_CG_GTOL || r.status == LSYS_CG_FTOL) && w.steps == r.iterations);
  for (i = 0; i < 3; i++) assert(fabs(x[i] - 1.0 / (i + 1)) < 1e-6);
}

/* No Wolfe step exists: each line search falls back on its best trial
** (sufficient decrease only), and the next direction is a restart. */
static int nsteps, nwolfe;

static void countstep (void *ud, double alpha, double f0, double g0d, double f1, double g1d) {
  (void)ud;
  assert(alpha > 0 && g0d < 0 && f1 < f0);
  nsteps++;
  nwolfe += f1 <= f0 + 1e-4 * alpha * g0d && fabs(g1d) <= 0.1 * fabs(g0d);
}

static void test_fallback (void) {
  double x[1] = { 0 };
  lsys_cg_opts o;
  lsys_cg_result r;
  lsys_error e;
  lsys_cg_defaults(&o);
  o.on_step = countstep;
  nsteps = nwolfe = 0;
  assert(lsys_cg_minimize(kink, NULL, x, 1, &o, NULL, &r, &e) == LSYS_OK);
  report("|x - pi|", &r);
  assert(r.status == LSYS_CG_LINESEARCH || r.status == LSYS_CG_FTOL);
  assert(r.iterations >= 1 && nsteps == r.iterations && nwolfe == 0);
  assert(r.restarts == r.iterations && fabs(x[0] - PI) < 1e-6);
}

/* A caller's workspace: no allocation, bit-identical results; and the
** internal one failing. */
static void test_work (void) {
  enum { N = 100 };
  double x1[N], x2[N];
  lsys_cg_result r1, r2;
  lsys_cg_opts o;
  lsys_error e;
  void *work;
  long before;
  int k;
  lsys_cg_defaults(&o);
  o.max_iter = 1000;
  startrosen(x1, N);
  before = nalloc;
  assert(lsys_cg_minimize(rosen, NULL, x1, N, &o, NULL, &r1, &e) == LSYS_OK);
  assert(nalloc == before + 1 && nlive == 0);   /* one block, freed */
  work = malloc(lsys_cg_work_size(N));
  for (k = 0; k < 3; k++) {                     /* the workspace is reused */
    startrosen(x2, N);
    before = nalloc;
    assert(lsys_cg_minimize(rosen, NULL, x2, N, &o, work, &r2, &e) == LSYS_OK);
    assert(nalloc == before);
    assert(memcmp(x1, x2, sizeof x1) == 0);
    assert(memcmp(&r1, &r2, sizeof r1) == 0);
  }
  /* a larger workspace serves a smaller problem */
  startrosen(x2, 2);
  assert(lsys_cg_minimize(rosen, NULL, x2, 2, NULL, work, &r2, &e) == LSYS_OK);
  assert(r2.status == LSYS_CG_GTOL && fabs(x2[0] - 1) < 1e-6 && fabs(x2[1] - 1) < 1e-6);
  free(work);
  /* allocation failure */
  startrosen(x2, N);
  failat = nalloc;
  assert(lsys_cg_minimize(rosen, NULL, x2, N, &o, NULL, &r2, &e) == LSYS_ENOMEM);
  assert(e.code == LSYS_ENOMEM && x2[0] == -1.2 && nlive == 0);
  failat = -1;
}

int main (void) {
  setvbuf(stdout, NULL, _IONBF, 0);     /* the report lines show up before a failed assert */
  test_rosenbrock();
  test_diagonal();
  test_precond();
  test_spd();
  test_stops();
  test_args();
  test_domain();
  test_fallback();
  test_work();
  assert(nlive == 0);
  printf("test_cg: ok\n");
  return 0;
}
