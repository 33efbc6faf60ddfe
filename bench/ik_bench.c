/*
** Speed of the arrangement solver: lsys_ik_solve (conjugate
** gradients, cg.h) on branch paths of 10, 100 and 1000 joints, from a
** nearby start -- one mouse-move step of a drag -- and, when liblbfgs is
** available (LSYS_HAVE_LBFGS), the L-BFGS of liblbfgs on the same objective
** (lsys_ik_objective) as a reference. Run by bench/arrange.lua, which
** parses the result lines:
**
**   cg n=100 best_ms=... median_ms=... reps=... iters=... evals=... status=... max_iter=200
**      f0=... f=... dist=... gnorm=...          (lsys_ik_solve, default options)
**   eval n=100 us=...            (one lsys_ik_objective call with its gradient)
**   lbfgs n=100 best_ms=... median_ms=... reps=... iters=... evals=... status=... code=...
**      m=6 epsilon=1e-05 f=... dist=...         (liblbfgs, lbfgs_parameter_init defaults)
**   lbfgs_to_cg n=100 ...        (the same, stopped once f <= the CG's final f: the time
**                                 L-BFGS needs for the CG's accuracy)
**   lbfgs unavailable            (instead of the two above: built without liblbfgs)
**   cg_full n=100 ...            (lsys_ik_solve with max_iter = 20000: to convergence)
**   drag n=100 frames=60 reps=... mean_ms=... max_ms=... mean_iters=... max_dist=...
**   lbfgs_drag n=100 ...         (the same drag with L-BFGS)
**   mem peak_kib=...
**
** Lines starting with '#' are comments. Usage: bench_ik [SECONDS] -- the
** least total time of the timed solves per figure (default 0.2). Times are
** wall clock (CLOCK_MONOTONIC); best and median over the repetitions; the
** drag figures take, per frame, the best over repetitions of the whole drag.
**
** The chain: a gently curving 3-D branch of total length 10 (segments of
** length 10 / n), each joint's fixed turn 'pre' a rotation by about 60 / n
** degrees about an axis across the branch that turns slowly along it (with
** a deterministic LCG jitter), so that every n gives a similar shape: turns
** adding up to about 60 degrees, in a direction that goes 0.8 times round,
** so that the tip heads 13-20 degrees away from the base (printed). Radius
** tapering linearly from 1 to 0.3, joint stiffness proportional to r^4
** (eqs. 4, 5 with equal lengths), normalised to mean 1 as lsys.arrange does;
** all three axes free; alpha = rest = 0.
** Weights as lsys.arrange's defaults: wp = 1000 / |v|^2 (v: root to tip),
** wt = 1, we = 1, ws = 0.1.
**
** One step: the tip target moved by 2% of the path length across the tip's
** heading (30 degrees from its L towards its U), the twist targets s, t
** turned by 2 degrees about H x (that direction), from alpha = 0 (where the
** old targets are met exactly). The drag (n = 100): 60 frames of the
** spherical dragger, the path turned about its root by 1, 2, ... 60 degrees
** (the tip moves about 1.5% of the path length a frame), each solve from the
** previous result.
**
** Both solvers evaluate (1) with the same code and the same preallocated
** scratch; lbfgs() allocates its own memory once per solve.
*/
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ik.h"

#ifdef LSYS_HAVE_LBFGS
#include <lbfgs.h>
#endif

#define PI 3.14159265358979323846
#define MAXREPS 200000
#define FRAMES 60

static double min_seconds = 0.2;

/* ---------------------------------------------------------------------------------------- */
/* small helpers */

static unsigned long long lcg_state = 20240601ull;

static double lcg (void) {                    /* uniform in [0, 1) */
  lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(lcg_state >> 11) / 9007199254740992.0;
}

static double now (void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double vdot (const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void vcross (double r[3], const double a[3], const double b[3]) {
  double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
         z = a[0] * b[1] - a[1] * b[0];
  r[0] = x; r[1] = y; r[2] = z;
}

static void vunit (double a[3]) {
  double l = sqrt(vdot(a, a));
  if (l > 0) { a[0] /= l; a[1] /= l; a[2] /= l; }
}

/* r = v rotated by 'ang' radians about the unit axis k (Rodrigues) */
static void vrotate (double r[3], const double v[3], const double k[3], double ang) {
  double c = cos(ang), s = sin(ang), kv = vdot(k, v), kxv[3];
  int i;
  vcross(kxv, k, v);
  for (i = 0; i < 3; i++) r[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1 - c);
}

/* the rotation matrix (column-major) of 'ang' radians about the unit axis k */
static void rotmat (double M[9], const double k[3], double ang) {
  double e[3];
  int col, i;
  for (col = 0; col < 3; col++) {             /* column col: the image of basis vector col */
    e[0] = e[1] = e[2] = 0;
    e[col] = 1;
    vrotate(M + 3 * col, e, k, ang);
    for (i = 0; i < 3; i++) if (fabs(M[3 * col + i]) < 1e-300) M[3 * col + i] = 0;
  }
}

static int cmpd (const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double median (double *t, int n) {
  qsort(t, (size_t)n, sizeof *t, cmpd);
  return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static void *xmalloc (size_t n) {
  void *p = malloc(n ? n : 1);
  if (p == NULL) {
    fprintf(stderr, "bench_ik: out of memory\n");
    exit(1);
  }
  return p;
}

/* ---------------------------------------------------------------------------------------- */
/* the chain and the goals */

typedef struct bench {
  int n;
  lsys_ikchain c;
  lsys_ikjoint *j;
  double *start;              /* the starting angles (3n: zeros) */
  double pbar[3], sbar[3], tbar[3], root[3], v[3];
  double Htip[3], Ltip[3], Utip[3];
  double total;               /* path length */
  lsys_ikgoal goal;           /* the one-step goal */
  void *work;                 /* lsys_ik_work_size(n) */
  double *times;              /* MAXREPS */
} bench;

static void setstart (bench *b) {
  int i, k;
  for (i = 0; i < b->n; i++)
    for (k = 0; k < 3; k++) b->j[i].alpha[k] = b->start[3 * i + k];
}

static void build (bench *b, int n) {
  double H[3] = {0, 0, 1}, U[3] = {1, 0, 0}, sum = 0, mean, *frames;
  int i, k;
  memset(b, 0, sizeof *b);
  b->n = n;
  b->j = (lsys_ikjoint *)xmalloc((size_t)n * sizeof *b->j);
  b->start = (double *)xmalloc(3 * (size_t)n * sizeof *b->start);
  b->work = xmalloc(lsys_ik_work_size(n));
  b->times = (double *)xmalloc(MAXREPS * sizeof *b->times);
  b->total = 10;
  b->c.n = n;
  b->c.j = b->j;
  lsys_ik_frame(b->c.base, H, U);
  memset(b->c.root, 0, sizeof b->c.root);
  lcg_state = 20240601ull;                     /* the same branch for every run */
  for (i = 0; i < n; i++) {
    lsys_ikjoint *J = &b->j[i];
    double s = (i + 0.5) / n;                 /* position along the branch, 0..1 */
    double phi = 2 * PI * 0.8 * s + 0.6 * (lcg() - 0.5);    /* bend direction turns slowly */
    double ax[3], ang, r, st;
    ax[0] = 0.15 * (lcg() - 0.5);             /* a little twist about H as well */
    ax[1] = cos(phi);                         /* local L */
    ax[2] = sin(phi);                         /* local U */
    vunit(ax);
    ang = (60.0 / n) * (0.75 + 0.5 * lcg()) * PI / 180;
    memset(J, 0, sizeof *J);
    if (i == 0) {                             /* the first segment continues the base */
      J->pre[0] = J->pre[4] = J->pre[8] = 1;
    } else {
      rotmat(J->pre, ax, ang);
    }
    J->len = b->total / n;
    r = 1 - 0.7 * s;                          /* tapering radius */
    st = r * r * r * r;
    J->stiff[0] = J->stiff[1] = J->stiff[2] = st;
    sum += 3 * st;
    J->free = 7;
  }
  mean = sum / (3.0 * n);
  for (i = 0; i < n; i++)
    for (k = 0; k < 3; k++) b->j[i].stiff[k] /= mean;
  memset(b->start, 0, 3 * (size_t)n * sizeof *b->start);
  setstart(b);

  /* the original tool: tip, twist vectors, the tip's frame, root and v */
  frames = (double *)xmalloc(9 * (size_t)n * sizeof *frames);
  lsys_ik_forward(&b->c, b->start, b->pbar, b->sbar, b->tbar, frames, NULL);
  memcpy(b->Htip, frames + 9 * (n - 1), sizeof b->Htip);
  memcpy(b->Ltip, frames + 9 * (n - 1) + 3, sizeof b->Ltip);
  memcpy(b->Utip, frames + 9 * (n - 1) + 6, sizeof b->Utip);
  free(frames);
  memcpy(b->root, b->c.root, sizeof b->root);
  for (k = 0; k < 3; k++) b->v[k] = b->pbar[k] - b->root[k];

  /* one mouse-move step: the tip moved sideways by 2% of the path length, the twist
  ** vectors turned by 2 degrees the same way */
  {
    double d[3], kax[3], c30 = cos(PI / 6), s30 = sin(PI / 6), vlen = sqrt(vdot(b->v, b->v));
    lsys_ikgoal *G = &b->goal;
    for (k = 0; k < 3; k++) d[k] = c30 * b->Ltip[k] + s30 * b->Utip[k];
    vcross(kax, b->Htip, d);
    vunit(kax);
    for (k = 0; k < 3; k++) G->p[k] = b->pbar[k] + 0.02 * b->total * d[k];
    vrotate(G->s, b->sbar, kax, 2 * PI / 180);
    vrotate(G->t, b->tbar, kax, 2 * PI / 180);
    G->wp = 1000 / (vlen * vlen);
    G->wt = 1;
    G->we = 1;
    G->ws = 0.1;
    printf("# n=%d: path length %g, |v| = %.3f (root to tip), tip heading %.1f deg from the "
           "base's, stiffness %.3f at the root to %.3f at the tip (mean 1)\n", n, b->total,
           vlen, acos(fmax(-1, fmin(1, vdot(H, b->Htip)))) * 180 / PI, b->j[0].stiff[1],
           b->j[n - 1].stiff[1]);
  }
}

static void release (bench *b) {
  free(b->j);
  free(b->start);
  free(b->work);
  free(b->times);
}

/* The goal of drag frame f (1..FRAMES): the spherical dragger turning the path about its
** root by f degrees, about an axis that moves the tip sideways (as the one-step goal). */
static void draggoal (const bench *b, int f, lsys_ikgoal *G) {
  double d[3], kax[3], v[3];
  int k;
  *G = b->goal;
  for (k = 0; k < 3; k++) d[k] = cos(PI / 6) * b->Ltip[k] + sin(PI / 6) * b->Utip[k];
  vcross(kax, b->v, d);
  vunit(kax);
  vrotate(v, b->v, kax, f * PI / 180);
  for (k = 0; k < 3; k++) G->p[k] = b->root[k] + v[k];
  vrotate(G->s, b->sbar, kax, f * PI / 180);
  vrotate(G->t, b->tbar, kax, f * PI / 180);
}

/* ---------------------------------------------------------------------------------------- */
/* conjugate gradients: lsys_ik_solve */

static const char *cgstatus (int st) {
  switch (st) {
    case LSYS_CG_GTOL: return "gtol";
    case LSYS_CG_FTOL: return "ftol";
    case LSYS_CG_MAXITER: return "maxiter";
    case LSYS_CG_MAXEVAL: return "maxeval";
    case LSYS_CG_LINESEARCH: return "linesearch";
    default: return "?";
  }
}

static void cgsolve (bench *b, const lsys_ikgoal *G, lsys_ik_result *r) {
  lsys_error e;
  if (lsys_ik_solve(&b->c, G, NULL, b->work, r, &e) != LSYS_OK) {
    fprintf(stderr, "bench_ik: lsys_ik_solve failed: %s\n", e.msg);
    exit(1);
  }
}

/* 'max_iter' 0: the default options; else the defaults with that iteration cap. Returns
** the final objective value. */
static double bench_cg (bench *b, const char *name, int max_iter) {
  lsys_cg_opts o;
  lsys_ik_result r;
  lsys_error e;
  double total = 0, t0, t, best = HUGE_VAL, med;
  int reps = 0;
  lsys_cg_defaults(&o);
  if (max_iter > 0) o.max_iter = max_iter;
  setstart(b);
  cgsolve(b, &b->goal, &r);                    /* warm-up */
  while ((total < min_seconds || reps < 3) && reps < MAXREPS) {
    setstart(b);
    t0 = now();
    if (lsys_ik_solve(&b->c, &b->goal, max_iter > 0 ? &o : NULL, b->work, &r, &e) != LSYS_OK) {
      fprintf(stderr, "bench_ik: lsys_ik_solve failed: %s\n", e.msg);
      exit(1);
    }
    t = now() - t0;
    b->times[reps++] = t;
    total += t;
    if (t < best) best = t;
  }
  med = median(b->times, reps);
  printf("%s n=%d best_ms=%.4f median_ms=%.4f reps=%d iters=%d evals=%d status=%s "
         "max_iter=%d f0=%.6e f=%.6e dist=%.3e gnorm=%.2e\n",
         name, b->n, 1e3 * best, 1e3 * med, reps, r.cg.iterations, r.cg.evaluations,
         cgstatus(r.cg.status), o.max_iter, r.f0, r.f, r.dist, r.cg.gnorm);
  fflush(stdout);
  return r.f;
}

/* the whole drag, FRAMES solves each from the previous result, with the solver 'solve';
** per frame the best time over the repetitions */
typedef double (*dragsolve) (bench *b, const lsys_ikgoal *G, int *iters);

static double drag_cg (bench *b, const lsys_ikgoal *G, int *iters) {
  lsys_ik_result r;
  cgsolve(b, G, &r);
  *iters = r.cg.iterations;
  return r.dist;
}

static void bench_drag (bench *b, const char *name, dragsolve solve) {
  lsys_ikgoal goals[FRAMES];
  double best[FRAMES], total = 0, t0, t, sum = 0, mx = 0, maxdist = 0;
  long iters = 0;
  int f, reps = 0, it;
  for (f = 0; f < FRAMES; f++) {
    draggoal(b, f + 1, &goals[f]);
    best[f] = HUGE_VAL;
  }
  while ((total < min_seconds || reps < 3) && reps < MAXREPS) {
    setstart(b);
    iters = 0;
    maxdist = 0;
    for (f = 0; f < FRAMES; f++) {
      double dist;
      t0 = now();
      dist = solve(b, &goals[f], &it);
      t = now() - t0;
      total += t;
      if (t < best[f]) best[f] = t;
      iters += it;
      if (dist > maxdist) maxdist = dist;
    }
    reps++;
  }
  for (f = 0; f < FRAMES; f++) {
    sum += best[f];
    if (best[f] > mx) mx = best[f];
  }
  printf("%s n=%d frames=%d reps=%d mean_ms=%.4f max_ms=%.4f mean_iters=%.1f max_dist=%.3e\n",
         name, b->n, FRAMES, reps, 1e3 * sum / FRAMES, 1e3 * mx, (double)iters / FRAMES, maxdist);
  fflush(stdout);
}

/* the cost of one evaluation of (1) with its gradient through the public entry point */
static void bench_eval (bench *b) {
  double *g = (double *)xmalloc(3 * (size_t)b->n * sizeof *g), t0, t, best = HUGE_VAL;
  volatile double sink = 0;
  int rounds = 0, i, per = b->n >= 1000 ? 20 : b->n >= 100 ? 200 : 2000;
  double total = 0;
  while (total < min_seconds / 4 || rounds < 3) {
    t0 = now();
    for (i = 0; i < per; i++) sink += lsys_ik_objective(&b->c, &b->goal, b->start, g, b->work);
    t = (now() - t0) / per;
    total += t * per;
    if (t < best) best = t;
    rounds++;
  }
  (void)sink;
  free(g);
  printf("eval n=%d us=%.3f\n", b->n, 1e6 * best);
  fflush(stdout);
}

/* ---------------------------------------------------------------------------------------- */
/* the reference: L-BFGS of liblbfgs on lsys_ik_objective */

#ifdef LSYS_HAVE_LBFGS

/* |p - p^| at the angles a */
static double tipdist (const bench *b, const double *a, const lsys_ikgoal *G) {
  double p[3], d[3];
  int k;
  lsys_ik_forward(&b->c, a, p, NULL, NULL, NULL, NULL);
  for (k = 0; k < 3; k++) d[k] = p[k] - G->p[k];
  return sqrt(vdot(d, d));
}

typedef struct lbctx {
  bench *b;
  const lsys_ikgoal *G;
  int evals, iters;
  double fx;                  /* f at the last iteration */
  double target;              /* stop once f <= target (0: never) */
} lbctx;

static lbfgsfloatval_t lb_eval (void *ud, const lbfgsfloatval_t *x, lbfgsfloatval_t *g,
                                const int n, const lbfgsfloatval_t step) {
  lbctx *c = (lbctx *)ud;
  (void)n;
  (void)step;
  c->evals++;
  return lsys_ik_objective(&c->b->c, c->G, x, g, c->b->work);
}

static int lb_progress (void *ud, const lbfgsfloatval_t *x, const lbfgsfloatval_t *g,
                        const lbfgsfloatval_t fx, const lbfgsfloatval_t xnorm,
                        const lbfgsfloatval_t gnorm, const lbfgsfloatval_t step, int n, int k,
                        int ls) {
  lbctx *c = (lbctx *)ud;
  (void)x; (void)g; (void)xnorm; (void)gnorm; (void)step; (void)n; (void)ls;
  c->iters = k;
  c->fx = fx;
  return c->target > 0 && fx <= c->target;    /* nonzero: cancel */
}

static const char *lbstatus (int st) {
  switch (st) {
    case LBFGS_SUCCESS: return "converged";
    case LBFGS_STOP: return "stopped";          /* by the progress callback: target reached */
    case LBFGS_ALREADY_MINIMIZED: return "already_minimized";
    case LBFGSERR_CANCELED: return "canceled";
    case LBFGSERR_ROUNDING_ERROR: return "rounding_error";
    case LBFGSERR_MAXIMUMLINESEARCH: return "max_linesearch";
    case LBFGSERR_MAXIMUMITERATION: return "max_iterations";
    case LBFGSERR_WIDTHTOOSMALL: return "width_too_small";
    case LBFGSERR_MINIMUMSTEP: return "minimum_step";
    case LBFGSERR_INCREASEGRADIENT: return "increase_gradient";
    default: return "error";
  }
}

/* one L-BFGS solve (lbfgs_parameter_init defaults) from the angles in 'x' (3n), in place;
** stops early once f <= target when target > 0 */
static int lbsolve (bench *b, const lsys_ikgoal *G, double target, lbfgsfloatval_t *x,
                    lbctx *c) {
  lbfgs_parameter_t par;
  lbfgsfloatval_t fx = 0;
  int st;
  lbfgs_parameter_init(&par);                  /* m = 6, More-Thuente, epsilon = 1e-5 */
  c->b = b;
  c->G = G;
  c->evals = c->iters = 0;
  c->target = target;
  st = lbfgs(3 * b->n, x, &fx, lb_eval, lb_progress, c, &par);
  c->fx = fx;
  return st;
}

/* 'target' > 0: the time L-BFGS takes to bring f down to it (the CG's final value) */
static void bench_lbfgs (bench *b, const char *name, double target) {
  lbfgsfloatval_t *x = lbfgs_malloc(3 * b->n);
  lbfgs_parameter_t par;
  lbctx c;
  double total = 0, t0, t, best = HUGE_VAL, med;
  size_t bytes = 3 * (size_t)b->n * sizeof *x;
  int reps = 0, st = 0;
  if (x == NULL) {
    fprintf(stderr, "bench_ik: lbfgs_malloc failed\n");
    exit(1);
  }
  lbfgs_parameter_init(&par);
  while ((total < min_seconds || reps < 3) && reps < MAXREPS) {
    memcpy(x, b->start, bytes);
    t0 = now();
    st = lbsolve(b, &b->goal, target, x, &c);
    t = now() - t0;
    b->times[reps++] = t;
    total += t;
    if (t < best) best = t;
  }
  med = median(b->times, reps);
  printf("%s n=%d best_ms=%.4f median_ms=%.4f reps=%d iters=%d evals=%d status=%s code=%d "
         "m=%d epsilon=%.0e f=%.6e dist=%.3e\n",
         name, b->n, 1e3 * best, 1e3 * med, reps, c.iters, c.evals,
         target > 0 && st == LBFGS_STOP ? "reached_cg_f" : lbstatus(st), st, par.m,
         par.epsilon, c.fx, tipdist(b, x, &b->goal));
  fflush(stdout);
  lbfgs_free(x);
}

/* the drag with L-BFGS: the angles live in the joints between frames, as with the CG */
static double drag_lbfgs (bench *b, const lsys_ikgoal *G, int *iters) {
  static lbfgsfloatval_t *x;
  static int cap;
  lbctx c;
  int i, k;
  if (b == NULL) {                             /* release the buffer */
    lbfgs_free(x);
    x = NULL;
    cap = 0;
    return 0;
  }
  if (cap < 3 * b->n) {
    lbfgs_free(x);
    x = lbfgs_malloc(3 * b->n);
    cap = 3 * b->n;
  }
  for (i = 0; i < b->n; i++)
    for (k = 0; k < 3; k++) x[3 * i + k] = b->j[i].alpha[k];
  lbsolve(b, G, 0, x, &c);
  for (i = 0; i < b->n; i++)
    for (k = 0; k < 3; k++) b->j[i].alpha[k] = x[3 * i + k];
  *iters = c.iters;
  return tipdist(b, x, G);
}

#endif

/* ---------------------------------------------------------------------------------------- */

static long peak_kib (void) {
  char line[256];
  long kib = -1;
  FILE *f = fopen("/proc/self/status", "r");
  if (f == NULL) return -1;
  while (fgets(line, sizeof line, f))
    if (strncmp(line, "VmHWM:", 6) == 0) kib = strtol(line + 6, NULL, 10);
  fclose(f);
  return kib;
}

/* How f and |p - p^| fall with the iteration cap (one solve each, from the start). */
static void profile (bench *b) {
  static const int caps[] = {5, 10, 20, 40, 80, 160};
  lsys_cg_opts o;
  lsys_ik_result r;
  lsys_error e;
  size_t k;
  for (k = 0; k < sizeof caps / sizeof *caps; k++) {
    lsys_cg_defaults(&o);
    o.max_iter = caps[k];
    setstart(b);
    if (lsys_ik_solve(&b->c, &b->goal, &o, b->work, &r, &e) != LSYS_OK) exit(1);
    printf("profile n=%d max_iter=%d iters=%d evals=%d f=%.6e dist=%.3e\n", b->n, caps[k],
           r.cg.iterations, r.cg.evaluations, r.f, r.dist);
  }
}

int main (int argc, char **argv) {
  static const int sizes[] = {10, 100, 1000};
  size_t s;
  if (argc > 1) {
    min_seconds = atof(argv[1]);
    if (!(min_seconds > 0)) {
      fprintf(stderr, "usage: bench_ik [SECONDS]  (least total time per figure, default 0.2)\n");
      return 2;
    }
  }
  printf("# bench_ik: lsys_ik_solve (CG, default options, caller workspace) vs L-BFGS\n");
  printf("# one drag step: tip moved 2%% of the path length sideways, twist turned 2 deg;"
         " wp = 1000/|v|^2, wt = we = 1, ws = 0.1\n");
  printf("# timed for at least %.2f s per figure, wall clock\n", min_seconds);
#ifndef LSYS_HAVE_LBFGS
  printf("lbfgs unavailable\n");
#endif
  for (s = 0; s < sizeof sizes / sizeof *sizes; s++) {
    bench b;
    double fcg;
    build(&b, sizes[s]);
    fcg = bench_cg(&b, "cg", 0);
    bench_eval(&b);
#ifdef LSYS_HAVE_LBFGS
    bench_lbfgs(&b, "lbfgs", 0);
    bench_lbfgs(&b, "lbfgs_to_cg", fcg);
#else
    (void)fcg;
#endif
    bench_cg(&b, "cg_full", 20000);
    if (b.n == 100) {
      profile(&b);
      bench_drag(&b, "drag", drag_cg);
#ifdef LSYS_HAVE_LBFGS
      bench_drag(&b, "lbfgs_drag", drag_lbfgs);
      drag_lbfgs(NULL, NULL, NULL);
#endif
    }
    release(&b);
  }
  printf("mem peak_kib=%ld\n", peak_kib());
  return 0;
}
