/*
** Space colonisation's markers (space.h): a pass hashes the buds into a
** space of cells as wide as the perception radius; each marker, on any
** worker, then looks at the buds of the cells around it and finds whether
** one is within the kill radius (it goes) or else which one perceives it
** nearest. What the buds get is summed afterwards on one thread, in the
** markers' order, so it does not depend on the number of threads.
*/
#include <string.h>

#include "space_impl.h"

#define MCHUNK 512                   /* markers a worker takes at a time */
#define KILLED UINT32_MAX            /* a marker's fate in a pass: removed, */
#define ALONE (UINT32_MAX - 1)       /* or perceived by no bud */

struct lsys_markers {
  double *p;                         /* 3 a marker */
  size_t n;
  size_t bytes;                      /* what they hold, counted in mt */
  lsys_meter *mt;
};

static int overbudget (lsys_error *e, lsys_meter *mt, size_t need) {
  char b1[32], b2[32];
  mt->hit = 1;
  return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "markers: %s needed, more than "
                       "max_memory (%s)", lsys_common_fmtsize(b1, need),
                       lsys_common_fmtsize(b2, mt->limit));
}

int lsys_space_markers_new (lsys_markers **out, const double *points, size_t n,
                            lsys_meter *mt, lsys_error *e) {
  lsys_markers *M;
  size_t i, bytes;
  *out = NULL;
  if (n > LSYS_SPACE_MAXPOINTS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: more than %u markers",
                         LSYS_SPACE_MAXPOINTS);
  for (i = 0; i < 3 * n; i++)
    if (!isfinite(points[i]))
      return lsys_seterror(e, LSYS_EARG, i / 3, "markers: marker %zu is not finite", i / 3 + 1);
  bytes = sizeof *M + 3 * n * sizeof(double);
  if (!lsys_common_meter_fits(mt, bytes)) return overbudget(e, mt, bytes);
  if ((M = (lsys_markers *)LSYS_MALLOC(sizeof *M)) == NULL) return LSYS_ENOMEM;
  if ((M->p = (double *)LSYS_MALLOC(n > 0 ? 3 * n * sizeof(double) : 1)) == NULL) {
    LSYS_FREE(M);
    return LSYS_ENOMEM;
  }
  if (n > 0) memcpy(M->p, points, 3 * n * sizeof(double));
  M->n = n;
  M->bytes = bytes;
  M->mt = mt;
  if (mt != NULL) mt->used += bytes;
  *out = M;
  return LSYS_OK;
}

void lsys_space_markers_free (lsys_markers *M) {
  if (M == NULL) return;
  if (M->mt != NULL) M->mt->used -= M->bytes;
  LSYS_FREE(M->p);
  LSYS_FREE(M);
}

size_t lsys_space_markers_count (const lsys_markers *M) { return M->n; }

const double *lsys_space_markers_points (const lsys_markers *M) { return M->p; }

/* ---------------------------------------------------------------------- */
/* a pass */

typedef struct pjob {
  const lsys_markers *M;
  const lsys_space *S;               /* the buds */
  const double *h;                   /* their unit headings (NULL: no perception) */
  double per2, kill2, cosa;
  int cone;                          /* whether the cone narrows perception */
  int64_t span;
  uint32_t *fate;                    /* a marker's bud, KILLED or ALONE */
} pjob;

/* The fate of marker x. */
static uint32_t fate1 (const pjob *j, const double x[3]) {
  const lsys_space *S = j->S;
  int64_t c[3], dy, dz, k = j->span;
  uint32_t best = ALONE;
  double bd2 = HUGE_VAL;
  int i;
  if (!lsys_space_near(x, S->cell)) return ALONE;      /* beyond every cell: no bud near */
  for (i = 0; i < 3; i++) c[i] = lsys_space_coord(x[i], S->cell);
  for (dy = -k; dy <= k; dy++)
    for (dz = -k; dz <= k; dz++) {
      uint32_t rg[2 * LSYS_SPACE_MAXSPAN + 1][2], s;
      int nr = lsys_space_rowcells(S, c[0] - k, c[0] + k, c[1] + dy, c[2] + dz, rg), ir;
      for (ir = 0; ir < nr; ir++)
        for (s = rg[ir][0]; s < rg[ir][1]; s++) {
          const double *p = S->p + 3 * (size_t)s;
          double v[3], d2;
          uint32_t bud = S->id[s];
          v[0] = x[0] - p[0];
          v[1] = x[1] - p[1];
          v[2] = x[2] - p[2];
          d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
          if (d2 <= j->kill2) return KILLED;
          if (j->h == NULL || !(d2 <= j->per2) || d2 == 0) continue;
          if (d2 > bd2 || (d2 == bd2 && bud > best)) continue;
          if (j->cone) {
            const double *h = j->h + 3 * (size_t)bud;
            if (!(v[0] * h[0] + v[1] * h[1] + v[2] * h[2] >= j->cosa * sqrt(d2))) continue;
          }
          best = bud;
          bd2 = d2;
        }
    }
  return best;
}

static void pwork (void *ctx, size_t chunk) {
  const pjob *j = (const pjob *)ctx;
  size_t m, a = chunk * MCHUNK, b = a + MCHUNK < j->M->n ? a + MCHUNK : j->M->n;
  for (m = a; m < b; m++) j->fate[m] = fate1(j, j->M->p + 3 * m);
}

/* The markers' fates under j (j->S and the rest set), then what they give
** the buds and the removal; *removed the markers removed. */
static int pass (lsys_markers *M, pjob *j, const double *buds, size_t nb, int threads,
                 size_t *counts, double *dirs, size_t *removed, lsys_error *e) {
  size_t m, w = 0, b, bytes = M->n > 0 ? M->n * sizeof(uint32_t) : 1;
  if (!lsys_common_meter_fits(M->mt, bytes)) return overbudget(e, M->mt, bytes);
  if ((j->fate = (uint32_t *)LSYS_MALLOC(bytes)) == NULL) return LSYS_ENOMEM;
  if (M->mt != NULL) M->mt->used += bytes;
  j->M = M;
  lsys_space_run(threads, (M->n + MCHUNK - 1) / MCHUNK, pwork, j);
  if (counts != NULL) memset(counts, 0, nb * sizeof *counts);
  if (dirs != NULL) memset(dirs, 0, 3 * nb * sizeof *dirs);
  for (m = 0; m < M->n; m++) {
    uint32_t f = j->fate[m];
    const double *x = M->p + 3 * m;
    if (f == KILLED) continue;
    if (f != ALONE) {
      const double *p = buds + 3 * (size_t)f;
      double v[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
      double d = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (counts != NULL) counts[f]++;
      if (dirs != NULL)
        for (b = 0; b < 3; b++) dirs[3 * (size_t)f + b] += v[b] / d;
    }
    if (w != m) memcpy(M->p + 3 * w, x, 3 * sizeof(double));
    w++;
  }
  if (dirs != NULL)
    for (b = 0; b < nb; b++) {
      double *d = dirs + 3 * b, len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (len > 0) { d[0] /= len; d[1] /= len; d[2] /= len; }
    }
  LSYS_FREE(j->fate);
  if (M->mt != NULL) M->mt->used -= bytes;
  if (removed != NULL) *removed = M->n - w;
  M->n = w;
  return LSYS_OK;
}

/* Checks the buds (or points) for cells of side c. */
static int checkbuds (const double *buds, size_t nb, double c, const char *what,
                      lsys_error *e) {
  size_t i;
  if (nb > LSYS_SPACE_MAXPOINTS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: more than %u %ss",
                         LSYS_SPACE_MAXPOINTS, what);
  for (i = 0; i < nb; i++) {
    const double *p = buds + 3 * i;
    if (!lsys_space_near(p, c))
      return lsys_seterror(e, LSYS_EARG, i, "markers: %s %zu is %s", what, i + 1,
                           isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])
                           ? "too far from the origin" : "not finite");
  }
  return LSYS_OK;
}

/* The unit headings of the nb buds into h. */
static int headings (double *h, const double *heads, size_t nb, lsys_error *e) {
  size_t i;
  for (i = 0; i < nb; i++) {
    const double *v = heads + 3 * i;
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 0) || !isfinite(len))
      return lsys_seterror(e, LSYS_EARG, i, "markers: heading %zu is not a finite non-zero "
                           "vector", i + 1);
    h[3 * i] = v[0] / len;
    h[3 * i + 1] = v[1] / len;
    h[3 * i + 2] = v[2] / len;
  }
  return LSYS_OK;
}

int lsys_space_markers_perceive (lsys_markers *M, const double *buds, const double *heads,
                                 size_t nb, const lsys_markers_opts *o, size_t *counts,
                                 double *dirs, lsys_error *e) {
  const double pi = 3.14159265358979323846;
  lsys_space_opts so;
  lsys_space *S = NULL;
  size_t bytes = nb > 0 ? 3 * nb * sizeof(double) : 1;
  double *h;
  pjob j;
  int st;
  if (!(o->perception > 0 && isfinite(o->perception)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: the perception radius must be a "
                         "finite number > 0");
  if (!(o->angle > 0 && o->angle <= 180))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: the angle must be a number of "
                         "degrees in (0, 180]");
  if (!(o->kill >= 0 && o->kill <= LSYS_SPACE_MAXSPAN * o->perception))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: the kill radius must be a number "
                         "in [0, %d times the perception radius]", LSYS_SPACE_MAXSPAN);
  if ((st = checkbuds(buds, nb, o->perception, "bud", e)) != LSYS_OK) return st;
  if (!lsys_common_meter_fits(M->mt, bytes)) return overbudget(e, M->mt, bytes);
  if ((h = (double *)LSYS_MALLOC(bytes)) == NULL) return LSYS_ENOMEM;
  if (M->mt != NULL) M->mt->used += bytes;
  memset(&so, 0, sizeof so);
  so.radius = o->perception;
  so.meter = M->mt;
  if ((st = headings(h, heads, nb, e)) == LSYS_OK &&
      (st = lsys_space_build(&S, buds, nb, &so, e)) == LSYS_OK) {
    j.S = S;
    j.h = h;
    j.per2 = o->perception * o->perception;
    j.kill2 = o->kill > 0 ? o->kill * o->kill : -1;
    j.cone = o->angle < 180;
    j.cosa = o->angle == 90 ? 0 : cos(o->angle * pi / 180);
    j.span = lsys_space_span(o->kill > o->perception ? o->kill : o->perception, S->cell);
    st = pass(M, &j, buds, nb, o->threads, counts, dirs, NULL, e);
  }
  if (M->mt != NULL) M->mt->used -= bytes + (S != NULL ? S->bytes : 0);
  lsys_space_free(S);
  LSYS_FREE(h);
  return st;
}

int lsys_space_markers_remove (lsys_markers *M, const double *points, size_t n,
                               double radius, int threads, size_t *removed, lsys_error *e) {
  lsys_space_opts so;
  lsys_space *S = NULL;
  pjob j;
  int st;
  if (removed != NULL) *removed = 0;
  if (!(radius > 0 && isfinite(radius)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "markers: the radius must be a finite "
                         "number > 0");
  if ((st = checkbuds(points, n, radius, "point", e)) != LSYS_OK) return st;
  memset(&so, 0, sizeof so);
  so.radius = radius;
  so.meter = M->mt;
  if ((st = lsys_space_build(&S, points, n, &so, e)) != LSYS_OK) return st;
  j.S = S;
  j.h = NULL;
  j.per2 = 0;
  j.kill2 = radius * radius;
  j.cone = 0;
  j.cosa = 0;
  j.span = 1;
  st = pass(M, &j, points, n, threads, NULL, NULL, removed, e);
  if (M->mt != NULL) M->mt->used -= S->bytes;
  lsys_space_free(S);
  return st;
}
