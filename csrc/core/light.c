/*
** The light environment (light.h): the sky's directions, the build, and
** the queries on worker threads. The hierarchy and the ray test are in
** light_bvh.c.
**
** Threads are made and joined per query as derive_par.c does: the caller is
** worker 0, the others take chunks of CHUNK points from an atomic counter.
** Each point's result is computed the same way whichever worker takes it,
** so the results do not depend on the number of threads; a worker's
** traversal stack is on its C stack, and nothing is allocated per ray.
*/
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>

#include "light_impl.h"

#define CHUNK 256               /* points a worker takes at a time */
#define DEFSAMPLES 64
#define DEFHITS 8

void lsys_light_defaults (lsys_light_opts *o) {
  memset(o, 0, sizeof *o);
  o->kind = LSYS_LIGHT_OVERCAST;
  o->radiance = LSYS_LIGHT_UNIFORM;
  o->samples = DEFSAMPLES;
  o->max_hits = DEFHITS;
}

/* ---------------------------------------------------------------------- */
/* the sky */

/* n directions of the overcast sky into dir, w (of total weight 'total'): a
** Fibonacci spiral, y = 1 - (i + 1/2) / n (equal areas of the hemisphere)
** turning by the golden angle, weighted by the sky's radiance there. */
static void overcast (double *dir, double *w, int n, int radiance, double total) {
  const double golden = 3.14159265358979323846 * (3 - sqrt(5.0));
  double sum = 0;
  int i;
  for (i = 0; i < n; i++) {
    double y = 1 - (i + 0.5) / n, r = sqrt(1 - y * y), phi = golden * i;
    dir[3 * i] = r * cos(phi);
    dir[3 * i + 1] = y;
    dir[3 * i + 2] = r * sin(phi);
    w[i] = radiance == LSYS_LIGHT_COSINE ? y : radiance == LSYS_LIGHT_CIE ? 1 + 2 * y : 1;
    sum += w[i];
  }
  for (i = 0; i < n; i++) w[i] *= total / sum;
}

static int finite3 (const double v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* v normalised into u; 0 when it is zero or not finite. */
static int unit (double u[3], const double v[3]) {
  double len;
  if (!finite3(v)) return 0;
  len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 0) || !isfinite(len)) return 0;
  u[0] = v[0] / len; u[1] = v[1] / len; u[2] = v[2] / len;
  return 1;
}

static int bad (lsys_error *e, const char *fmt, const char *what) {
  return lsys_seterror(e, LSYS_EARG, (size_t)-1, fmt, what);
}

/* Checks the options that do not depend on the sky's kind. */
static int checkopts (const lsys_light_opts *o, lsys_error *e) {
  if (o->kind < LSYS_LIGHT_OVERCAST || o->kind > LSYS_LIGHT_DIRS)
    return bad(e, "light: %s: no such sky", "kind");
  if (o->radiance < LSYS_LIGHT_UNIFORM || o->radiance > LSYS_LIGHT_CIE)
    return bad(e, "light: %s must be uniform, cosine or cie", "radiance");
  if (o->samples < 0 || o->samples > LSYS_LIGHT_MAXSAMPLES)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "light: samples must be an integer in "
                         "[1, %d]", LSYS_LIGHT_MAXSAMPLES);
  if (o->max_hits < 0 || o->max_hits > LSYS_LIGHT_MAXHITS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "light: max_hits must be an integer in "
                         "[1, %d]", LSYS_LIGHT_MAXHITS);
  if (!(o->transmittance >= 0 && o->transmittance < 1))
    return bad(e, "light: %s must be a number in [0, 1)", "transmittance");
  if (!(o->line_radius >= 0 && isfinite(o->line_radius)))
    return bad(e, "light: %s must be a finite number >= 0", "line_radius");
  if (!(o->offset >= 0 && isfinite(o->offset)))
    return bad(e, "light: %s must be a finite number > 0", "offset");
  if (!(o->max_distance >= 0) || isnan(o->max_distance))
    return bad(e, "light: %s must be a number >= 0", "max_distance");
  if (o->kind == LSYS_LIGHT_SUN && !(o->ambient >= 0 && o->ambient <= 1))
    return bad(e, "light: %s must be a number in [0, 1]", "ambient");
  return LSYS_OK;
}

/* The caller's directions, checked, into L (room for o->ndirs). */
static int userdirs (lsys_light *L, const lsys_light_opts *o, lsys_error *e) {
  double sum = 0;
  size_t k;
  for (k = 0; k < o->ndirs; k++) {
    const double *d = o->dirs + 4 * k;
    if (!unit(L->dir + 3 * k, d))
      return lsys_seterror(e, LSYS_EARG, k, "light: direction %zu is not a finite non-zero "
                           "vector", k + 1);
    if (!(d[3] >= 0 && isfinite(d[3])))
      return lsys_seterror(e, LSYS_EARG, k, "light: the weight of direction %zu must be a "
                           "finite number >= 0", k + 1);
    L->w[k] = d[3];
    sum += d[3];
  }
  if (!(sum > 0) || !isfinite(sum))
    return bad(e, "light: the %s' weights must not all be 0", "directions");
  for (k = 0; k < o->ndirs; k++) L->w[k] /= sum;
  return LSYS_OK;
}

/* The sky of the options into L's directions and weights. */
static int sky (lsys_light *L, const lsys_light_opts *o, lsys_error *e) {
  int ns = o->samples > 0 ? o->samples : DEFSAMPLES, sun = 0;
  size_t n = 0, k;
  double s[3];
  if (o->kind == LSYS_LIGHT_OVERCAST) n = (size_t)ns;
  else if (o->kind == LSYS_LIGHT_SUN) {
    if (!unit(s, o->sun)) return bad(e, "light: the %s is not a finite non-zero vector", "sun");
    sun = o->ambient < 1;
    n = (size_t)sun + (o->ambient > 0 ? (size_t)ns : 0);
  } else {
    if (o->dirs == NULL || o->ndirs == 0 || o->ndirs > LSYS_LIGHT_MAXSAMPLES)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "light: the sky must have 1 to %d "
                           "directions", LSYS_LIGHT_MAXSAMPLES);
    n = o->ndirs;
  }
  L->dir = (double *)LSYS_MALLOC(n * 3 * sizeof(double));
  L->w = (double *)LSYS_MALLOC(n * sizeof(double));
  L->dirf = (float *)LSYS_MALLOC(n * 3 * sizeof(float));
  if (L->dir == NULL || L->w == NULL || L->dirf == NULL) return LSYS_ENOMEM;
  L->ndirs = n;
  if (o->kind == LSYS_LIGHT_DIRS) {
    int st = userdirs(L, o, e);
    if (st != LSYS_OK) return st;
  } else if (o->kind == LSYS_LIGHT_OVERCAST) overcast(L->dir, L->w, ns, o->radiance, 1);
  else {
    if (sun) {
      memcpy(L->dir, s, sizeof s);
      L->w[0] = 1 - o->ambient;
    }
    if (o->ambient > 0) overcast(L->dir + 3 * sun, L->w + sun, ns, o->radiance, o->ambient);
  }
  for (k = 0; k < 3 * n; k++) L->dirf[k] = (float)L->dir[k];
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* build */

void lsys_light_free (lsys_light *L) {
  if (L == NULL) return;
  LSYS_FREE(L->tri.mem);
  LSYS_FREE(L->cap.mem);
  LSYS_FREE(L->pack);
  LSYS_FREE(L->caps);
  LSYS_FREE(L->dir);
  LSYS_FREE(L->w);
  LSYS_FREE(L->dirf);
  LSYS_FREE(L);
}

int lsys_light_build (lsys_light **out, const lsys_scene *s, const lsys_light_opts *o,
                      lsys_error *e) {
  lsys_light_opts def;
  lsys_light *L;
  double diag = 0;
  int st, c, k;
  *out = NULL;
  if (o == NULL) {
    lsys_light_defaults(&def);
    o = &def;
  }
  if ((st = checkopts(o, e)) != LSYS_OK) return st;
  if ((L = (lsys_light *)LSYS_MALLOC(sizeof *L)) == NULL) return LSYS_ENOMEM;
  memset(L, 0, sizeof *L);
  if ((st = sky(L, o, e)) != LSYS_OK ||
      (st = lsys_light_bvh(L, s, o->line_radius, o->meter, e)) != LSYS_OK) {
    lsys_light_free(L);
    return st;
  }
  for (c = 0; c < 3; c++) diag += (L->hi[c] - L->lo[c]) * (L->hi[c] - L->lo[c]);
  diag = sqrt(diag);
  L->offset = o->offset > 0 ? o->offset : diag > 0 ? 1e-4 * diag : 1e-7;
  L->tmax = o->max_distance > 0 ? (float)o->max_distance : HUGE_VALF;
  L->tau = o->transmittance;
  L->maxhits = L->tau > 0 ? (o->max_hits > 0 ? o->max_hits : DEFHITS) : 1;
  L->taupow[0] = 1;
  for (k = 1; k <= LSYS_LIGHT_MAXHITS; k++) L->taupow[k] = L->taupow[k - 1] * L->tau;
  *out = L;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* queries */

/*
** Rays of one direction from nearby points take nearly the same path
** through the hierarchy, so a worker traces its chunk of points (nearby:
** the points are taken in Morton order) one direction at a time, in
** packets (lsys_light_cast), and the nodes stay in its caches. Each point
** still sums its directions in their order, so its result is what it would
** be alone.
*/
typedef struct qjob {
  const lsys_light *L;
  const double *p, *n;          /* points; unit normals or NULL */
  const uint64_t *ord;          /* the points in Morton order: index in the low 32 bits */
  double *out, *dir;
  size_t np, nch;
  atomic_size_t next;
} qjob;

/* Points ord[a .. b) of the job (b - a <= CHUNK). */
static void chunk (const qjob *j, size_t a, size_t b) {
  const lsys_light *L = j->L;
  float o[CHUNK][3], tmin = (float)L->offset;
  double E[CHUNK], M[CHUNK][3], W[CHUNK];
  uint8_t want[CHUNK], hits[CHUNK];
  size_t idx[CHUNK], m = b - a, i, k;
  int c;
  for (i = 0; i < m; i++) {
    idx[i] = (size_t)(j->ord[a + i] & 0xffffffffu);
    for (c = 0; c < 3; c++) {
      o[i][c] = (float)j->p[3 * idx[i] + c];
      M[i][c] = 0;
    }
    E[i] = 0;
  }
  for (k = 0; k < L->ndirs; k++) {
    const double *d = L->dir + 3 * k;
    int any = 0;
    for (i = 0; i < m; i++) {
      double w = L->w[k];
      if (j->n != NULL) {
        const double *n = j->n + 3 * idx[i];
        double cs = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
        w = cs > 0 ? w * cs : 0;
      }
      W[i] = w;
      any |= want[i] = w != 0;
    }
    if (!any) continue;
    lsys_light_cast(L, (const float (*)[3])o, want, m, L->dirf + 3 * k, tmin, L->maxhits, hits);
    for (i = 0; i < m; i++) {
      double v;
      if (!want[i]) continue;
      v = W[i] * L->taupow[hits[i]];
      E[i] += v;
      for (c = 0; c < 3; c++) M[i][c] += v * d[c];
    }
  }
  for (i = 0; i < m; i++) {
    j->out[idx[i]] = E[i];
    if (j->dir != NULL) {
      double len = sqrt(M[i][0] * M[i][0] + M[i][1] * M[i][1] + M[i][2] * M[i][2]);
      for (c = 0; c < 3; c++) j->dir[3 * idx[i] + c] = len > 0 ? M[i][c] / len : 0;
    }
  }
}

static void *qwork (void *arg) {
  qjob *j = (qjob *)arg;
  size_t c;
  while ((c = atomic_fetch_add(&j->next, 1)) < j->nch)
    chunk(j, c * CHUNK, (c + 1) * CHUNK < j->np ? (c + 1) * CHUNK : j->np);
  return NULL;
}

/* The 10 bits of x spread to every third bit. */
static uint64_t spread (uint64_t x) {
  x &= 0x3ff;
  x = (x | x << 16) & 0x30000ffull;
  x = (x | x << 8) & 0x300f00full;
  x = (x | x << 4) & 0x30c30c3ull;
  x = (x | x << 2) & 0x9249249ull;
  return x;
}

static int cmpkey (const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* The points' Morton codes in the light's box (30 bits, above their
** indices), sorted. */
static void morton (const lsys_light *L, const double *p, size_t n, uint64_t *key) {
  size_t i;
  int c;
  for (i = 0; i < n; i++) {
    uint64_t code = 0;
    for (c = 0; c < 3; c++) {
      double ext = L->hi[c] - L->lo[c], u = ext > 0 ? (p[3 * i + c] - L->lo[c]) / ext : 0;
      u = u > 0 ? (u < 1 ? u : 1) : 0;
      code |= spread((uint64_t)(u * 1023)) << c;
    }
    key[i] = code << 32 | i;
  }
  qsort(key, n, sizeof *key, cmpkey);
}

/* Checks the points and normals; the normals, normalised, into nrm. */
static int checkpoints (const double *points, const double *normals, size_t n, double *nrm,
                        lsys_error *e) {
  size_t i;
  for (i = 0; i < n; i++) {
    if (!finite3(points + 3 * i))
      return lsys_seterror(e, LSYS_EARG, i, "light: point %zu is not finite", i + 1);
    if (normals != NULL && !unit(nrm + 3 * i, normals + 3 * i))
      return lsys_seterror(e, LSYS_EARG, i, "light: normal %zu is not a finite non-zero "
                           "vector", i + 1);
  }
  return LSYS_OK;
}

int lsys_light_query (const lsys_light *L, const double *points, size_t n,
                      const double *normals_or_null, double *out, double *dir_out, int threads,
                      lsys_error *e) {
  pthread_t th[LSYS_LIGHT_MAXTHREADS];
  double *nrm = NULL;
  uint64_t *key;
  qjob j;
  int k, started = 1, st;
  if (n > UINT32_MAX) return lsys_seterror(e, LSYS_EARG, (size_t)-1, "light: more than 2^32 "
                                           "points");
  if ((key = (uint64_t *)LSYS_MALLOC(n > 0 ? n * sizeof *key : 1)) == NULL) return LSYS_ENOMEM;
  if (normals_or_null != NULL && n > 0 &&
      (nrm = (double *)LSYS_MALLOC(3 * n * sizeof(double))) == NULL) {
    LSYS_FREE(key);
    return LSYS_ENOMEM;
  }
  if ((st = checkpoints(points, normals_or_null, n, nrm, e)) != LSYS_OK) {
    LSYS_FREE(nrm);
    LSYS_FREE(key);
    return st;
  }
  morton(L, points, n, key);
  j.L = L; j.p = points; j.n = nrm; j.ord = key; j.out = out; j.dir = dir_out;
  j.np = n;
  j.nch = (n + CHUNK - 1) / CHUNK;
  atomic_init(&j.next, 0);
  if (threads < 1) threads = 1;
  if (threads > LSYS_LIGHT_MAXTHREADS) threads = LSYS_LIGHT_MAXTHREADS;
  if ((size_t)threads > j.nch) threads = j.nch > 0 ? (int)j.nch : 1;
  for (k = 1; k < threads; k++, started++)     /* no thread for one: the caller works alone */
    if (pthread_create(&th[k], NULL, qwork, &j) != 0) break;
  qwork(&j);
  for (k = 1; k < started; k++) pthread_join(th[k], NULL);
  LSYS_FREE(nrm);
  LSYS_FREE(key);
  return LSYS_OK;
}

int lsys_light_hits (const lsys_light *L, const double o[3], const double d[3], int cap,
                     int brute) {
  float of[3], df[3];
  int c;
  for (c = 0; c < 3; c++) {
    of[c] = (float)o[c];
    df[c] = (float)d[c];
  }
  if (cap < 1) cap = 1;
  return brute ? lsys_light_brute(L, of, df, (float)L->offset, cap)
               : lsys_light_trace(L, of, df, (float)L->offset, cap);
}

void lsys_light_info (const lsys_light *L, lsys_light_stats *st) {
  st->triangles = L->ntri;
  st->capsules = L->ncap;
  st->nodes = L->tri.nnodes + L->cap.nnodes;
  st->depth = L->tri.depth > L->cap.depth ? L->tri.depth : L->cap.depth;
  st->ndirs = L->ndirs;
  st->offset = L->offset;
  st->bytes = sizeof *L + L->npack * sizeof *L->pack + L->ncap * sizeof *L->caps +
              st->nodes * sizeof(lsys_lnode4) + L->ndirs * (4 * sizeof(double) + 3 * sizeof(float));
}

size_t lsys_light_sky (const lsys_light *L, const double **dirs, const double **w) {
  *dirs = L->dir;
  *w = L->w;
  return L->ndirs;
}
