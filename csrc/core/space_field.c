/*
** A resource field (space.h): the grid, its diffusion on worker threads (a
** substep computes each cell from the old amounts alone, so the workers may
** take the rows in any order), the plant's takes and the sources.
*/
#include <string.h>

#include "space_impl.h"

#define ROWS 16                       /* rows (along x) a worker takes at a time */

struct lsys_field {
  double lo[3], cell;
  size_t n[3], cells;
  double *q, *tmp;                    /* the amounts; the next substep's (and scratch) */
  size_t bytes;
  lsys_meter *mt;
};

int lsys_space_field_new (lsys_field **out, const double lo[3], const double hi[3],
                          double cell, lsys_meter *mt, lsys_error *e) {
  lsys_field *F;
  double cells = 1;
  size_t n[3], bytes;
  int a;
  *out = NULL;
  if (!(cell > 0 && isfinite(cell)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "field: the cell must be a finite number "
                         "> 0");
  for (a = 0; a < 3; a++) {
    double k;
    if (!isfinite(lo[a]) || !isfinite(hi[a]) || !(lo[a] <= hi[a]))
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "field: the box must have finite lo <= "
                           "hi on each axis");
    k = ceil((hi[a] - lo[a]) / cell);
    if (k < 1) k = 1;
    cells *= k;
    if (!(cells <= (double)LSYS_FIELD_MAXCELLS))
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "field: more than %zu cells",
                           LSYS_FIELD_MAXCELLS);
    n[a] = (size_t)k;
  }
  bytes = sizeof *F + 2 * (size_t)cells * sizeof(double);
  if (!lsys_common_meter_fits(mt, bytes)) {
    char b1[32], b2[32];
    mt->hit = 1;
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "field: %s needed, more than "
                         "max_memory (%s)", lsys_common_fmtsize(b1, bytes),
                         lsys_common_fmtsize(b2, mt->limit));
  }
  if ((F = (lsys_field *)LSYS_MALLOC(sizeof *F)) == NULL) return LSYS_ENOMEM;
  memset(F, 0, sizeof *F);
  F->q = (double *)LSYS_MALLOC((size_t)cells * sizeof(double));
  F->tmp = (double *)LSYS_MALLOC((size_t)cells * sizeof(double));
  if (F->q == NULL || F->tmp == NULL) {
    lsys_space_field_free(F);
    return LSYS_ENOMEM;
  }
  memcpy(F->lo, lo, sizeof F->lo);
  memcpy(F->n, n, sizeof F->n);
  F->cell = cell;
  F->cells = (size_t)cells;
  memset(F->q, 0, F->cells * sizeof(double));
  F->bytes = bytes;
  F->mt = mt;
  if (mt != NULL) mt->used += bytes;
  *out = F;
  return LSYS_OK;
}

void lsys_space_field_free (lsys_field *F) {
  if (F == NULL) return;
  if (F->mt != NULL) F->mt->used -= F->bytes;
  LSYS_FREE(F->q);
  LSYS_FREE(F->tmp);
  LSYS_FREE(F);
}

double lsys_space_field_dims (const lsys_field *F, size_t n[3]) {
  memcpy(n, F->n, sizeof F->n);
  return F->cell;
}

double *lsys_space_field_values (lsys_field *F) { return F->q; }

/* The cell coordinates of p into ijk; 0 when it is outside the grid. */
static int cellof (const lsys_field *F, const double p[3], size_t ijk[3]) {
  int a;
  for (a = 0; a < 3; a++) {
    double u = floor((p[a] - F->lo[a]) / F->cell);
    if (!(u >= 0 && u < (double)F->n[a])) return 0;     /* NaN too */
    ijk[a] = (size_t)u;
  }
  return 1;
}

long long lsys_space_field_cell (const lsys_field *F, const double p[3]) {
  size_t c[3];
  if (!cellof(F, p, c)) return -1;
  return (long long)(c[0] + F->n[0] * (c[1] + F->n[1] * c[2]));
}

/* ---------------------------------------------------------------------- */
/* diffusion */

typedef struct djob {
  const lsys_field *F;
  const double *q;
  double *out, a;
} djob;

/* Rows [chunk ROWS, chunk ROWS + ROWS) of a substep: the row of index r is
** (y, z) = (r % ny, r / ny). */
static void drows (void *ctx, size_t chunk) {
  const djob *j = (const djob *)ctx;
  const lsys_field *F = j->F;
  const size_t nx = F->n[0], ny = F->n[1], nz = F->n[2], sy = nx, sz = nx * ny;
  const double *q = j->q, a = j->a;
  size_t r, r1 = (chunk + 1) * ROWS < ny * nz ? (chunk + 1) * ROWS : ny * nz;
  for (r = chunk * ROWS; r < r1; r++) {
    size_t y = r % ny, z = r / ny, x, c = r * nx;
    for (x = 0; x < nx; x++, c++) {
      double v = q[c], f = 0;
      if (x > 0) f += q[c - 1] - v;
      if (x + 1 < nx) f += q[c + 1] - v;
      if (y > 0) f += q[c - sy] - v;
      if (y + 1 < ny) f += q[c + sy] - v;
      if (z > 0) f += q[c - sz] - v;
      if (z + 1 < nz) f += q[c + sz] - v;
      j->out[c] = v + a * f;
    }
  }
}

int lsys_space_field_diffuse (lsys_field *F, double D, double t, int threads, long *substeps,
                              lsys_error *e) {
  double k = D * t / (F->cell * F->cell), m;
  int d = (F->n[0] > 1) + (F->n[1] > 1) + (F->n[2] > 1);
  long s, ms;
  djob j;
  if (substeps != NULL) *substeps = 0;
  if (!(D >= 0 && isfinite(D) && t >= 0 && isfinite(t)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "field: the diffusion and the time must be "
                         "finite numbers >= 0");
  if (k == 0 || d == 0) return LSYS_OK;
  m = ceil(2 * d * k);
  if (!(m <= LSYS_FIELD_MAXSUBSTEPS))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "field: the diffusion needs %.0f substeps, "
                         "more than %d: make the cells larger", m, LSYS_FIELD_MAXSUBSTEPS);
  ms = m < 1 ? 1 : (long)m;
  j.F = F;
  j.a = k / (double)ms;
  for (s = 0; s < ms; s++) {
    double *x;
    j.q = F->q;
    j.out = F->tmp;
    lsys_space_run(threads, (F->n[1] * F->n[2] + ROWS - 1) / ROWS, drows, &j);
    x = F->q;
    F->q = F->tmp;
    F->tmp = x;
  }
  if (substeps != NULL) *substeps = ms;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* takes, sources, gradients */

static int checkpts (const double *points, const double *v, size_t n, int nonneg,
                     lsys_error *e) {
  size_t i;
  for (i = 0; i < n; i++) {
    const double *p = points + 3 * i;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
      return lsys_seterror(e, LSYS_EARG, i, "field: point %zu is not finite", i + 1);
    if (!isfinite(v[i]) || (nonneg && v[i] < 0))
      return lsys_seterror(e, LSYS_EARG, i, "field: amount %zu must be a finite number%s",
                           i + 1, nonneg ? " >= 0" : "");
  }
  return LSYS_OK;
}

int lsys_space_field_take (lsys_field *F, const double *points, const double *want, size_t n,
                           double *got, lsys_error *e) {
  double *ask = F->tmp;               /* free between substeps: what each cell is asked */
  size_t i;
  int st;
  if ((st = checkpts(points, want, n, 1, e)) != LSYS_OK) return st;
  for (i = 0; i < n; i++) {
    long long c = lsys_space_field_cell(F, points + 3 * i);
    if (c >= 0) ask[c] = 0;
  }
  for (i = 0; i < n; i++) {
    long long c = lsys_space_field_cell(F, points + 3 * i);
    if (c >= 0) ask[c] += want[i];
  }
  for (i = 0; i < n; i++) {
    long long c = lsys_space_field_cell(F, points + 3 * i);
    double s;
    got[i] = 0;
    if (c < 0 || !((s = ask[c]) > 0)) continue;
    got[i] = s <= F->q[c] ? want[i] : want[i] * (F->q[c] / s);
  }
  for (i = 0; i < n; i++) {           /* each cell once: its ask is then set to -1 */
    long long c = lsys_space_field_cell(F, points + 3 * i);
    if (c < 0 || ask[c] < 0) continue;
    F->q[c] = ask[c] <= F->q[c] ? F->q[c] - ask[c] : 0;
    ask[c] = -1;
  }
  return LSYS_OK;
}

long long lsys_space_field_add (lsys_field *F, const double *points, const double *amount,
                                size_t n, lsys_error *e) {
  long long in = 0;
  size_t i;
  if (checkpts(points, amount, n, 0, e) != LSYS_OK) return -1;
  for (i = 0; i < n; i++) {
    long long c = lsys_space_field_cell(F, points + 3 * i);
    if (c < 0) continue;
    F->q[c] += amount[i];
    if (F->q[c] < 0) F->q[c] = 0;
    in++;
  }
  return in;
}

void lsys_space_field_gradient (const lsys_field *F, const double p[3], double g[3]) {
  size_t c[3], st[3] = {1, F->n[0], F->n[0] * F->n[1]}, at;
  int a;
  g[0] = g[1] = g[2] = 0;
  if (!cellof(F, p, c)) return;
  at = c[0] + st[1] * c[1] + st[2] * c[2];
  for (a = 0; a < 3; a++) {
    size_t lo = c[a] > 0 ? at - st[a] : at, hi = c[a] + 1 < F->n[a] ? at + st[a] : at;
    if (hi != lo) g[a] = (F->q[hi] - F->q[lo]) / ((double)((hi - lo) / st[a]) * F->cell);
  }
}

double lsys_space_field_total (const lsys_field *F) {
  double s = 0;
  size_t i;
  for (i = 0; i < F->cells; i++) s += F->q[i];
  return s;
}
