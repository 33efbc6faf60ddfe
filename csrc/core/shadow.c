/*
** The shadow-propagation grid (shadow.h): the grid, adding casters layer
** by layer on worker threads, obstacles, and the queries.
**
** The voxels are stored layer by layer (y outermost), each layer row by row
** (z, then x fastest), so a layer is one block of memory that one worker
** writes alone. An add sorts its casters by the layer of their voxel
** (count, prefix sum, fill: the order given is kept within a layer); a
** worker that takes layer y then adds, for q = 0 .. depth, the casters of
** layer y + q to their (2q + 1)^2 voxels of it. Each voxel so receives its
** casters in one order whichever worker takes it, and the sums are the same
** bits for every number of threads. Threads are made and joined per call as
** light.c does: the caller is worker 0.
*/
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>

#include "shadow.h"

#define CHUNK 64                /* points a worker takes at a time (directions) */
#define DEFDEPTH 4

struct lsys_shadow {
  double lo[3], hi[3];          /* hi: lo + n voxel */
  double voxel;
  long n[3];                    /* voxels along x, y, z */
  size_t nvox, bytes;           /* bytes: what the grid holds (counted in the meter) */
  int depth;
  double a, b;
  double lev[LSYS_SHADOW_MAXDEPTH + 1];   /* a b^-q: what a unit caster adds at level q */
  lsys_meter *meter;
  double *s;                    /* the shadows: s[(y n[2] + z) n[0] + x] */
};

/* One caster, sorted by layer: its voxel's x and z (possibly outside the
** grid) and its weight. */
typedef struct caster {
  int32_t i, k;
  double w;
} caster;

void lsys_shadow_defaults (lsys_shadow_opts *o) {
  memset(o, 0, sizeof *o);
  o->hi[0] = o->hi[1] = o->hi[2] = 1;
  o->voxel = 1;
  o->depth = DEFDEPTH;
  o->a = 1;
  o->b = 2;
}

static int finite3 (const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static int bad (lsys_error *e, const char *msg) {
  return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shadow: %s", msg);
}

static int checkopts (const lsys_shadow_opts *o, lsys_error *e) {
  int c;
  if (!finite3(o->lo) || !finite3(o->hi)) return bad(e, "lo and hi must be finite");
  for (c = 0; c < 3; c++)
    if (o->lo[c] > o->hi[c])
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shadow: lo must not be above hi "
                           "(on %c: %g > %g)", "xyz"[c], o->lo[c], o->hi[c]);
  if (!(o->voxel > 0 && isfinite(o->voxel))) return bad(e, "voxel must be a finite number > 0");
  if (o->depth < 0 || o->depth > LSYS_SHADOW_MAXDEPTH)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shadow: depth must be an integer in "
                         "[0, %d]", LSYS_SHADOW_MAXDEPTH);
  if (!(o->a > 0 && isfinite(o->a))) return bad(e, "a must be a finite number > 0");
  if (!(o->b > 1 && isfinite(o->b))) return bad(e, "b must be a finite number > 1");
  return LSYS_OK;
}

/* The grid would be too big: the message says how big. */
static int toobig (lsys_error *e, const double n[3], double bytes, const lsys_meter *mt) {
  char b1[32], b2[32];
  if (n[0] > LSYS_SHADOW_MAXAXIS || n[1] > LSYS_SHADOW_MAXAXIS || n[2] > LSYS_SHADOW_MAXAXIS)
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "shadow: a grid of %.0f x %.0f x %.0f "
                         "voxels is too big (at most %d along an axis)", n[0], n[1], n[2],
                         LSYS_SHADOW_MAXAXIS);
  lsys_common_fmtsize(b2, mt != NULL ? mt->limit : (size_t)-1);
  if (bytes >= 1.8e19)
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "shadow: a grid of %.0f x %.0f x %.0f "
                         "voxels is too big for max_memory (%s)", n[0], n[1], n[2], b2);
  return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "shadow: the grid of %.0f x %.0f x %.0f "
                       "voxels needs %s, more than max_memory (%s)", n[0], n[1], n[2],
                       lsys_common_fmtsize(b1, (size_t)bytes), b2);
}

int lsys_shadow_new (lsys_shadow **out, const lsys_shadow_opts *o, lsys_error *e) {
  lsys_shadow_opts def;
  lsys_shadow *S;
  double n[3], bytes;
  int c, q, st;
  *out = NULL;
  if (o == NULL) {
    lsys_shadow_defaults(&def);
    o = &def;
  }
  if ((st = checkopts(o, e)) != LSYS_OK) return st;
  for (c = 0; c < 3; c++) {          /* whole voxels over lo .. hi, at least one */
    n[c] = ceil((o->hi[c] - o->lo[c]) / o->voxel);
    if (!(n[c] >= 1)) n[c] = 1;
  }
  bytes = n[0] * n[1] * n[2] * (double)sizeof(double) + (double)sizeof *S;
  if (n[0] > LSYS_SHADOW_MAXAXIS || n[1] > LSYS_SHADOW_MAXAXIS || n[2] > LSYS_SHADOW_MAXAXIS ||
      bytes >= (double)((size_t)-1 / 2) || !lsys_common_meter_fits(o->meter, (size_t)bytes)) {
    if (o->meter != NULL) o->meter->hit = 1;
    return toobig(e, n, bytes, o->meter);
  }
  if ((S = (lsys_shadow *)LSYS_MALLOC(sizeof *S)) == NULL) return LSYS_ENOMEM;
  memset(S, 0, sizeof *S);
  for (c = 0; c < 3; c++) {
    S->n[c] = (long)n[c];
    S->lo[c] = o->lo[c];
    S->hi[c] = o->lo[c] + n[c] * o->voxel;
  }
  S->voxel = o->voxel;
  S->nvox = (size_t)S->n[0] * (size_t)S->n[1] * (size_t)S->n[2];
  S->bytes = (size_t)bytes;
  S->depth = o->depth;
  S->a = o->a;
  S->b = o->b;
  for (q = 0; q <= S->depth; q++) S->lev[q] = S->a * pow(S->b, -q);
  if ((S->s = (double *)LSYS_MALLOC(S->nvox * sizeof(double))) == NULL) {
    LSYS_FREE(S);
    return LSYS_ENOMEM;
  }
  lsys_common_hugepages(S->s, S->nvox * sizeof(double));
  memset(S->s, 0, S->nvox * sizeof(double));
  S->meter = o->meter;
  if (S->meter != NULL) S->meter->used += S->bytes;
  *out = S;
  return LSYS_OK;
}

void lsys_shadow_free (lsys_shadow *S) {
  if (S == NULL) return;
  if (S->meter != NULL) S->meter->used -= S->bytes < S->meter->used ? S->bytes
                                                                    : S->meter->used;
  LSYS_FREE(S->s);
  LSYS_FREE(S);
}

void lsys_shadow_clear (lsys_shadow *S) {
  memset(S->s, 0, S->nvox * sizeof(double));
}

void lsys_shadow_info (const lsys_shadow *S, lsys_shadow_stats *st) {
  int c;
  for (c = 0; c < 3; c++) {
    st->n[c] = (int)S->n[c];
    st->lo[c] = S->lo[c];
    st->hi[c] = S->hi[c];
  }
  st->voxels = S->nvox;
  st->bytes = S->bytes;
  st->voxel = S->voxel;
  st->depth = S->depth;
  st->a = S->a;
  st->b = S->b;
}

/* ---------------------------------------------------------------------- */
/* voxels */

/* The index along axis c of the voxel holding x, as a double (it may be
** far outside the grid): a point on the grid's high face is in its last
** voxel. */
static double along (const lsys_shadow *S, int c, double x) {
  double f = floor((x - S->lo[c]) / S->voxel);
  if (f == (double)S->n[c] && x <= S->hi[c]) f -= 1;
  return f;
}

/* The voxel of p into v; whether it is in the grid. */
static int cellof (const lsys_shadow *S, const double p[3], long v[3]) {
  int c;
  for (c = 0; c < 3; c++) {
    double f = along(S, c, p[c]);
    if (!(f >= 0 && f < (double)S->n[c])) return 0;
    v[c] = (long)f;
  }
  return 1;
}

static size_t vindex (const lsys_shadow *S, long i, long j, long k) {
  return ((size_t)j * (size_t)S->n[2] + (size_t)k) * (size_t)S->n[0] + (size_t)i;
}

double lsys_shadow_voxel (const lsys_shadow *S, long i, long j, long k) {
  if (i < 0 || j < 0 || k < 0 || i >= S->n[0] || j >= S->n[1] || k >= S->n[2]) return 0;
  return S->s[vindex(S, i, j, k)];
}

/* ---------------------------------------------------------------------- */
/* casters */

typedef struct addjob {
  lsys_shadow *S;
  const caster *c;              /* sorted by layer */
  const size_t *start;          /* layer L's casters: c[start[L] .. start[L + 1]) */
  long nlayers;                 /* of casters: n[1] + depth */
  atomic_long next;             /* the next layer of the grid to fill */
} addjob;

/* Layer y of the grid: the casters of layers y .. y + depth, level by level. */
static void layer (const addjob *J, long y) {
  const lsys_shadow *S = J->S;
  long nx = S->n[0], nz = S->n[2];
  double *base = S->s + (size_t)y * (size_t)nz * (size_t)nx;
  int q;
  for (q = 0; q <= S->depth && y + q < J->nlayers; q++) {
    size_t a = J->start[y + q], b = J->start[y + q + 1], t;
    for (t = a; t < b; t++) {
      const caster *c = J->c + t;
      double v = c->w * S->lev[q];
      long i0 = c->i - q, i1 = c->i + q, k0 = c->k - q, k1 = c->k + q, i, k;
      if (i0 < 0) i0 = 0;
      if (i1 > nx - 1) i1 = nx - 1;
      if (k0 < 0) k0 = 0;
      if (k1 > nz - 1) k1 = nz - 1;
      for (k = k0; k <= k1; k++) {
        double *row = base + (size_t)k * (size_t)nx;
        for (i = i0; i <= i1; i++) row[i] += v;
      }
    }
  }
}

static void *addwork (void *arg) {
  addjob *J = (addjob *)arg;
  long y;
  while ((y = atomic_fetch_add(&J->next, 1)) < J->S->n[1]) layer(J, y);
  return NULL;
}

/* The layer of caster p's voxel (0 .. n[1] + depth - 1) and its x, z into
** *i, *k; -1 when its pyramid misses the grid. */
static long casterlayer (const lsys_shadow *S, const double p[3], int32_t *i, int32_t *k) {
  double fx = along(S, 0, p[0]), fy = along(S, 1, p[1]), fz = along(S, 2, p[2]);
  double d = (double)S->depth;
  if (!(fy >= 0 && fy < (double)S->n[1] + d && fx >= -d && fx < (double)S->n[0] + d &&
        fz >= -d && fz < (double)S->n[2] + d))
    return -1;
  *i = (int32_t)fx;
  *k = (int32_t)fz;
  return (long)fy;
}

/* Runs 'threads' workers over the job (the caller is one). */
static void run (void *(*work) (void *), void *job, int threads, long units) {
  pthread_t th[LSYS_SHADOW_MAXTHREADS];
  int k, started = 1;
  if (threads < 1) threads = 1;
  if (threads > LSYS_SHADOW_MAXTHREADS) threads = LSYS_SHADOW_MAXTHREADS;
  if ((long)threads > units) threads = units > 0 ? (int)units : 1;
  for (k = 1; k < threads; k++, started++)     /* no thread for one: the caller works alone */
    if (pthread_create(&th[k], NULL, work, job) != 0) break;
  work(job);
  for (k = 1; k < started; k++) pthread_join(th[k], NULL);
}

static int nomemory (lsys_shadow *S, size_t bytes, lsys_error *e) {
  char b1[32], b2[32];
  S->meter->hit = 1;
  return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "shadow: adding the casters needs %s "
                       "more, beyond max_memory (%s)", lsys_common_fmtsize(b1, bytes),
                       lsys_common_fmtsize(b2, S->meter->limit));
}

/* Adds the n checked casters (weights NULL: 1). */
static int addchecked (lsys_shadow *S, const double *p, const double *w, size_t n, int threads,
                       lsys_error *e) {
  long nl = S->n[1] + S->depth, L;
  size_t bytes, t, *start;
  caster *c;
  addjob J;
  if (n == 0) return LSYS_OK;
  if (n > ((size_t)-1 / 2) / sizeof *c) return LSYS_ENOMEM;
  bytes = n * sizeof *c + ((size_t)nl + 1) * sizeof *start;
  if (!lsys_common_meter_fits(S->meter, bytes)) return nomemory(S, bytes, e);
  c = (caster *)LSYS_MALLOC(n * sizeof *c);
  start = (size_t *)LSYS_MALLOC(((size_t)nl + 1) * sizeof *start);
  if (c == NULL || start == NULL) {
    LSYS_FREE(c);
    LSYS_FREE(start);
    return LSYS_ENOMEM;
  }
  if (S->meter != NULL) S->meter->used += bytes;
  memset(start, 0, ((size_t)nl + 1) * sizeof *start);
  for (t = 0; t < n; t++) {                  /* count: start[L + 1] casters in layer L */
    int32_t i, k;
    if ((L = casterlayer(S, p + 3 * t, &i, &k)) >= 0) start[L + 1]++;
  }
  for (L = 0; L < nl; L++) start[L + 1] += start[L];
  for (t = 0; t < n; t++) {                  /* fill, start[L] moving to layer L's end */
    int32_t i, k;
    if ((L = casterlayer(S, p + 3 * t, &i, &k)) >= 0) {
      caster *x = c + start[L]++;
      x->i = i;
      x->k = k;
      x->w = w != NULL ? w[t] : 1;
    }
  }
  for (L = nl; L > 0; L--) start[L] = start[L - 1];   /* back to the layers' beginnings */
  start[0] = 0;
  J.S = S;
  J.c = c;
  J.start = start;
  J.nlayers = nl;
  atomic_init(&J.next, 0);
  run(addwork, &J, threads, S->n[1]);
  LSYS_FREE(c);
  LSYS_FREE(start);
  if (S->meter != NULL) S->meter->used -= bytes;
  return LSYS_OK;
}

int lsys_shadow_add (lsys_shadow *S, const double *points, const double *weights, size_t n,
                     int threads, lsys_error *e) {
  size_t t;
  for (t = 0; t < n; t++) {
    if (!finite3(points + 3 * t))
      return lsys_seterror(e, LSYS_EARG, t, "shadow: point %zu is not finite", t + 1);
    if (weights != NULL && !isfinite(weights[t]))
      return lsys_seterror(e, LSYS_EARG, t, "shadow: weight %zu is not finite", t + 1);
  }
  return addchecked(S, points, weights, n, threads, e);
}

/* The centroids and weights (area over the voxel's face, times 'wt') of the
** triangles of part 'pt' under m (NULL: as they are) into p and w from *n. */
static void centroids (const lsys_shadow *S, const lsys_mesh *ms, const lsys_part *pt,
                       const float *m, double wt, double *p, double *w, size_t *n) {
  double face = S->voxel * S->voxel;
  size_t t;
  for (t = pt->t0; t < pt->t0 + pt->nt && t < ms->nt; t++) {
    const uint32_t *v = ms->tri + 3 * t;
    double x[3][3], e1[3], e2[3], cr[3], area;
    int i, c;
    if (v[0] >= ms->nv || v[1] >= ms->nv || v[2] >= ms->nv) continue;
    for (i = 0; i < 3; i++) {
      const float *q = ms->pos + 3 * v[i];
      if (m != NULL) lsys_xform(m, q, x[i]);
      else for (c = 0; c < 3; c++) x[i][c] = q[c];
    }
    for (c = 0; c < 3; c++) {
      e1[c] = x[1][c] - x[0][c];
      e2[c] = x[2][c] - x[0][c];
    }
    cr[0] = e1[1] * e2[2] - e1[2] * e2[1];
    cr[1] = e1[2] * e2[0] - e1[0] * e2[2];
    cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
    area = 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    if (!(area > 0) || !isfinite(area)) continue;
    for (c = 0; c < 3; c++) p[3 * *n + c] = (x[0][c] + x[1][c] + x[2][c]) / 3;
    if (!finite3(p + 3 * *n)) continue;
    w[(*n)++] = wt * area / face;
  }
}

int lsys_shadow_add_scene (lsys_shadow *S, const lsys_scene *sc, double weight, int threads,
                           lsys_error *e) {
  size_t nt = 0, n = 0, i, bytes;
  double *p, *w;
  int st;
  if (!isfinite(weight)) return bad(e, "the weight must be finite");
  if (sc->ninst == 0) nt = sc->mesh.nt;
  else
    for (i = 0; i < sc->ninst; i++)
      if (sc->inst[i].part < sc->nparts) nt += sc->parts[sc->inst[i].part].nt;
  if (nt == 0) return LSYS_OK;
  if (nt > ((size_t)-1 / 8) / (4 * sizeof(double))) return LSYS_ENOMEM;
  bytes = nt * 4 * sizeof(double);
  if (!lsys_common_meter_fits(S->meter, bytes)) return nomemory(S, bytes, e);
  p = (double *)LSYS_MALLOC(nt * 3 * sizeof(double));
  w = (double *)LSYS_MALLOC(nt * sizeof(double));
  if (p == NULL || w == NULL) {
    LSYS_FREE(p);
    LSYS_FREE(w);
    return LSYS_ENOMEM;
  }
  if (S->meter != NULL) S->meter->used += bytes;
  if (sc->ninst == 0) {
    lsys_part all = {0, sc->mesh.nv, 0, sc->mesh.nt, 0, 0, 0, 0};
    centroids(S, &sc->mesh, &all, NULL, weight, p, w, &n);
  } else
    for (i = 0; i < sc->ninst; i++)
      if (sc->inst[i].part < sc->nparts)
        centroids(S, &sc->mesh, &sc->parts[sc->inst[i].part], sc->inst[i].m, weight, p, w, &n);
  st = addchecked(S, p, w, n, threads, e);
  LSYS_FREE(p);
  LSYS_FREE(w);
  if (S->meter != NULL) S->meter->used -= bytes;
  return st;
}

/* The voxels along axis c that the box's side lo .. hi overlaps, clamped to
** the grid, into *i0 .. *i1; 0 when none. */
static int span (const lsys_shadow *S, int c, double lo, double hi, long *i0, long *i1) {
  double f0 = along(S, c, lo), f1;
  if (hi > lo) f1 = ceil((hi - S->lo[c]) / S->voxel) - 1;
  else f1 = f0;
  if (f1 < f0) f1 = f0;                        /* a side thinner than rounding */
  if (f0 < 0) f0 = 0;
  if (f1 > (double)S->n[c] - 1) f1 = (double)S->n[c] - 1;
  if (!(f0 <= f1)) return 0;
  *i0 = (long)f0;
  *i1 = (long)f1;
  return 1;
}

int lsys_shadow_add_box (lsys_shadow *S, const double lo[3], const double hi[3], double value,
                         lsys_error *e) {
  long a[3], b[3], i, j, k;
  int c;
  if (!finite3(lo) || !finite3(hi)) return bad(e, "the box's corners must be finite");
  if (!isfinite(value)) return bad(e, "the box's value must be finite");
  for (c = 0; c < 3; c++)
    if (lo[c] > hi[c])
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shadow: the box's low corner must not "
                           "be above its high one (on %c: %g > %g)", "xyz"[c], lo[c], hi[c]);
  for (c = 0; c < 3; c++)
    if (!span(S, c, lo[c], hi[c], &a[c], &b[c])) return LSYS_OK;
  for (j = a[1]; j <= b[1]; j++)
    for (k = a[2]; k <= b[2]; k++) {
      double *row = S->s + vindex(S, 0, j, k);
      for (i = a[0]; i <= b[0]; i++) row[i] += value;
    }
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* queries */

static int checkpoints (const double *p, size_t n, lsys_error *e) {
  size_t t;
  for (t = 0; t < n; t++)
    if (!finite3(p + 3 * t))
      return lsys_seterror(e, LSYS_EARG, t, "shadow: point %zu is not finite", t + 1);
  return LSYS_OK;
}

int lsys_shadow_query (const lsys_shadow *S, const double *points, size_t n, int exposure,
                       double C, double *out, lsys_error *e) {
  size_t t;
  int st;
  if (exposure && !isfinite(C)) return bad(e, "C must be a finite number");
  if ((st = checkpoints(points, n, e)) != LSYS_OK) return st;
  for (t = 0; t < n; t++) {
    long v[3];
    double s = cellof(S, points + 3 * t, v) ? S->s[vindex(S, v[0], v[1], v[2])] : 0;
    if (exposure) {
      double Q = C - s + S->a;
      out[t] = Q > 0 ? Q : 0;
    } else out[t] = s;
  }
  return LSYS_OK;
}

typedef struct dirjob {
  const lsys_shadow *S;
  const double *p, *h;
  double *out;
  double cosmax;                /* the cone: cos of the half-angle (-1: every direction) */
  double radius;                /* in voxels */
  size_t np, nch;
  atomic_size_t next;
} dirjob;

/* Whether the offset d (squared length d2 > 0, d . h = dot) lies in the cone
** of cosine cm around the unit heading: dot / |d| >= cm, without the root. */
static int incone (double dot, double d2, double cm) {
  if (cm <= -1) return 1;                      /* 180 degrees: every direction */
  if (cm >= 0) return dot >= 0 && dot * dot >= cm * cm * d2;
  return dot >= 0 || dot * dot <= cm * cm * d2;
}

/*
** The direction of point t (its heading h, unit) into o. The voxels around
** the point's are scanned in the grid's order; a voxel's cosine with the
** heading (a root) is taken only when its shadow is not above the best yet.
*/
static void direction (const dirjob *J, size_t t, const double h[3], double o[3]) {
  const lsys_shadow *S = J->S;
  const double *p = J->p + 3 * t;
  double r2 = J->radius * J->radius * S->voxel * S->voxel, best = 0, bestcs = 0, bd[3] = {0};
  long v[3], lo[3], hi[3], m = (long)ceil(J->radius), i, j, k;
  int c, found = 0;
  if (!cellof(S, p, v)) {
    memcpy(o, h, 3 * sizeof(double));
    return;
  }
  for (c = 0; c < 3; c++) {
    lo[c] = v[c] - m > 0 ? v[c] - m : 0;
    hi[c] = v[c] + m < S->n[c] - 1 ? v[c] + m : S->n[c] - 1;
  }
  for (j = lo[1]; j <= hi[1]; j++) {
    double dy = S->lo[1] + (j + 0.5) * S->voxel - p[1];
    for (k = lo[2]; k <= hi[2]; k++) {
      const double *row = S->s + vindex(S, 0, j, k);
      double dz = S->lo[2] + (k + 0.5) * S->voxel - p[2], dyz = dy * dy + dz * dz;
      double hyz = dy * h[1] + dz * h[2];
      if (dyz > r2) continue;
      for (i = lo[0]; i <= hi[0]; i++) {
        double dx = S->lo[0] + (i + 0.5) * S->voxel - p[0], d2 = dx * dx + dyz;
        double dot = dx * h[0] + hyz, s = row[i], len, cs;
        if (d2 > r2 || !(d2 > 0) || (found && s > best) || !incone(dot, d2, J->cosmax) ||
            (i == v[0] && j == v[1] && k == v[2]))
          continue;
        len = sqrt(d2);
        cs = dot / len;
        if (found && s == best && !(cs > bestcs)) continue;
        found = 1;
        best = s;
        bestcs = cs;
        bd[0] = dx / len;
        bd[1] = dy / len;
        bd[2] = dz / len;
      }
    }
  }
  memcpy(o, found ? bd : h, 3 * sizeof(double));
}

/* h (finite, not zero) normalised into u; scaled first, so that no square
** overflows. */
static void unit (double u[3], const double h[3]) {
  double m = fmax(fabs(h[0]), fmax(fabs(h[1]), fabs(h[2]))), len;
  int c;
  for (c = 0; c < 3; c++) u[c] = h[c] / m;
  len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (c = 0; c < 3; c++) u[c] /= len;
}

static void *dirwork (void *arg) {
  dirjob *J = (dirjob *)arg;
  size_t ch;
  while ((ch = atomic_fetch_add(&J->next, 1)) < J->nch) {
    size_t t, end = (ch + 1) * CHUNK < J->np ? (ch + 1) * CHUNK : J->np;
    for (t = ch * CHUNK; t < end; t++) {
      double u[3];
      unit(u, J->h + 3 * t);
      direction(J, t, u, J->out + 3 * t);
    }
  }
  return NULL;
}

int lsys_shadow_direction (const lsys_shadow *S, const double *points, const double *headings,
                           size_t n, double angle, double radius, double *out, int threads,
                           lsys_error *e) {
  dirjob J;
  size_t t;
  int st;
  if (!(angle > 0 && angle <= 180))
    return bad(e, "the angle must be a number of degrees in (0, 180]");
  if (!(radius > 0 && radius <= LSYS_SHADOW_MAXRADIUS))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shadow: the radius must be a number of "
                         "voxels in (0, %d]", LSYS_SHADOW_MAXRADIUS);
  if ((st = checkpoints(points, n, e)) != LSYS_OK) return st;
  for (t = 0; t < n; t++) {
    const double *h = headings + 3 * t;
    if (!finite3(h) || (h[0] == 0 && h[1] == 0 && h[2] == 0))
      return lsys_seterror(e, LSYS_EARG, t, "shadow: heading %zu is not a finite non-zero "
                           "vector", t + 1);
  }
  J.S = S;
  J.p = points;
  J.h = headings;
  J.out = out;
  J.radius = radius;
  J.cosmax = angle == 180 ? -1 : angle == 90 ? 0 : cos(angle * (3.14159265358979323846 / 180));
  J.np = n;
  J.nch = (n + CHUNK - 1) / CHUNK;
  atomic_init(&J.next, 0);
  run(dirwork, &J, threads, (long)J.nch);
  return LSYS_OK;
}
