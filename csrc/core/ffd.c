/*
** Free-form deformations of a finished scene (ffd.h): the Hyperpatch's
** Bezier volume, maps given by functions, affine maps, and the ranges of a
** scene that modules drew. Lintermann and Deussen 1999, sidebar "FFD and
** Hyperpatch" and section "Free-form deformations", name the components but
** give no formulas; the volume here is the tensor-product Bezier form of
** free-form deformation (Sederberg and Parry 1986), written out in ffd.h.
*/
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ffd.h"

/* ---------------------------------------------------------------------- */
/* 3 x 3 helpers */

static double det3 (const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
       - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
       + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The cofactor matrix: cof(M) = det(M) M^-T, defined also where M is singular. */
static void cofactor (double c[3][3], const double m[3][3]) {
  int r, k;
  for (r = 0; r < 3; r++)
    for (k = 0; k < 3; k++) {
      int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c[r][k] = m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1];
    }
}

static double len3 (const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* n <- J^-T n, normalized: cof(J) n / det(J), whose direction is sign(det)
** times that of cof(J) n. Keeps n where J is singular or the result is not
** finite. */
static void transform_normal (float n[3], const double J[3][3]) {
  double c[3][3], d = det3(J), m[3], l, sg;
  int r;
  if (!(fabs(d) > 0) || !isfinite(d)) return;
  cofactor(c, J);
  for (r = 0; r < 3; r++) m[r] = c[r][0] * n[0] + c[r][1] * n[1] + c[r][2] * n[2];
  l = len3(m);
  if (!(l > 0) || !isfinite(l)) return;
  sg = d > 0 ? 1 : -1;
  for (r = 0; r < 3; r++) n[r] = (float)(sg * m[r] / l);
}

/* ---------------------------------------------------------------------- */
/* the hyperpatch */

int lsys_ffd_hyperpatch_init (lsys_hyperpatch *hp, const int deg[3], const double origin[3],
                              const double axes[3][3], lsys_error *e) {
  double A[3][3], c[3][3], d;
  int r, k, i, j, l;
  memset(hp, 0, sizeof *hp);
  for (r = 0; r < 3; r++)
    if (deg[r] < 1 || deg[r] > LSYS_HP_MAXDEG)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                           "hyperpatch degree %d is %d: degrees are 1 (linear) to 4 (quartic)",
                           r + 1, deg[r]);
  for (r = 0; r < 3; r++) {
    if (!isfinite(origin[r]))
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "hyperpatch origin[%d] is not finite", r + 1);
    for (k = 0; k < 3; k++)
      if (!isfinite(axes[r][k]))
        return lsys_seterror(e, LSYS_EARG, (size_t)-1, "hyperpatch axis %d[%d] is not finite",
                             r + 1, k + 1);
  }
  for (r = 0; r < 3; r++)                    /* A: the edge vectors as columns */
    for (k = 0; k < 3; k++) A[r][k] = axes[k][r];
  d = det3(A);
  if (!(fabs(d) > 1e-12 * len3(axes[0]) * len3(axes[1]) * len3(axes[2])) || !isfinite(d))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "hyperpatch axes are degenerate (zero, parallel or in one plane)");
  cofactor(c, A);
  for (r = 0; r < 3; r++)                    /* A^-1 = cof(A)^T / det(A) */
    for (k = 0; k < 3; k++) hp->inv[r][k] = c[k][r] / d;
  memcpy(hp->deg, deg, sizeof hp->deg);
  memcpy(hp->origin, origin, sizeof hp->origin);
  memcpy(hp->axis, axes, sizeof hp->axis);
  for (l = 0; l <= deg[2]; l++)
    for (j = 0; j <= deg[1]; j++)
      for (i = 0; i <= deg[0]; i++) {
        double *P = lsys_ffd_hyperpatch_point(hp, i, j, l);
        double s = (double)i / deg[0], t = (double)j / deg[1], u = (double)l / deg[2];
        for (r = 0; r < 3; r++)
          P[r] = origin[r] + s * axes[0][r] + t * axes[1][r] + u * axes[2][r];
      }
  return LSYS_OK;
}

size_t lsys_ffd_hyperpatch_count (const lsys_hyperpatch *hp) {
  return (size_t)(hp->deg[0] + 1) * (size_t)(hp->deg[1] + 1) * (size_t)(hp->deg[2] + 1);
}

double *lsys_ffd_hyperpatch_point (lsys_hyperpatch *hp, int i, int j, int k) {
  if (i < 0 || i > hp->deg[0] || j < 0 || j > hp->deg[1] || k < 0 || k > hp->deg[2])
    return NULL;
  return hp->cp[i + (hp->deg[0] + 1) * (j + (hp->deg[1] + 1) * k)];
}

void lsys_ffd_hyperpatch_local (const lsys_hyperpatch *hp, const double p[3], double stu[3]) {
  double q[3] = {p[0] - hp->origin[0], p[1] - hp->origin[1], p[2] - hp->origin[2]};
  int r;
  for (r = 0; r < 3; r++)
    stu[r] = hp->inv[r][0] * q[0] + hp->inv[r][1] * q[1] + hp->inv[r][2] * q[2];
}

/* The Bernstein polynomials B_i^d(x), i = 0..d, and their derivatives
** d (B_{i-1}^{d-1}(x) - B_i^{d-1}(x)) (with B_{-1} = B_d^{d-1} = 0), by de
** Casteljau's triangle; any real x (extrapolation outside [0, 1]). */
static void bernstein (int d, double x, double b[LSYS_HP_MAXDEG + 1],
                       double db[LSYS_HP_MAXDEG + 1]) {
  double lo[LSYS_HP_MAXDEG + 1];
  int n, i;
  b[0] = 1;
  for (n = 1; n <= d; n++) {               /* b: degree n from degree n - 1 */
    if (n == d) memcpy(lo, b, (size_t)n * sizeof *b);     /* degree d - 1 */
    b[n] = x * b[n - 1];
    for (i = n - 1; i > 0; i--) b[i] = x * b[i - 1] + (1 - x) * b[i];
    b[0] = (1 - x) * b[0];
  }
  for (i = 0; i <= d; i++) db[i] = d * ((i > 0 ? lo[i - 1] : 0) - (i < d ? lo[i] : 0));
}

void lsys_ffd_hyperpatch_eval (const lsys_hyperpatch *hp, const double p[3], double out[3],
                               double J[3][3]) {
  double stu[3], b[3][LSYS_HP_MAXDEG + 1], db[3][LSYS_HP_MAXDEG + 1];
  double D[3][3] = {{0}};                  /* D[r][c]: d out[r] / d stu[c] */
  int i, j, k, r, c;
  lsys_ffd_hyperpatch_local(hp, p, stu);
  for (r = 0; r < 3; r++) bernstein(hp->deg[r], stu[r], b[r], db[r]);
  out[0] = out[1] = out[2] = 0;
  for (k = 0; k <= hp->deg[2]; k++)
    for (j = 0; j <= hp->deg[1]; j++) {
      double bjk = b[1][j] * b[2][k], dt = db[1][j] * b[2][k], du = b[1][j] * db[2][k];
      const double *P = hp->cp[(hp->deg[0] + 1) * (j + (hp->deg[1] + 1) * k)];
      for (i = 0; i <= hp->deg[0]; i++, P += 3) {
        double w = b[0][i] * bjk, ws = db[0][i] * bjk, wt = b[0][i] * dt, wu = b[0][i] * du;
        for (r = 0; r < 3; r++) {
          out[r] += w * P[r];
          D[r][0] += ws * P[r]; D[r][1] += wt * P[r]; D[r][2] += wu * P[r];
        }
      }
    }
  if (J == NULL) return;
  for (r = 0; r < 3; r++)                  /* chain rule: d stu / d p is inv */
    for (c = 0; c < 3; c++)
      J[r][c] = D[r][0] * hp->inv[0][c] + D[r][1] * hp->inv[1][c] + D[r][2] * hp->inv[2][c];
}

/* ---------------------------------------------------------------------- */
/* applying a map to a range */

/* A map: the image of p in out and, when J is not NULL, its Jacobian.
** A non-zero status stops the deformation. */
typedef int (*mapfn) (void *ctx, const double p[3], double out[3], double J[3][3]);

static int checkrange (const lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1) {
  return v0 <= v1 && v1 <= s->mesh.nv && l0 <= l1 && l1 <= s->mesh.nl ? LSYS_OK : LSYS_EARG;
}

/* Applies 'map' to vertices [v0, v1) (positions and normals) and line ends
** [2 l0, 2 l1); on a failure returns its status and sets *at (ffd.h). A
** point's place is found again after its map ran: a callback map runs code
** of the caller's, which must leave the mesh's size alone (ffd.h) but may
** have moved its arrays. */
static int apply (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1, mapfn map,
                  void *ctx, size_t *at) {
  lsys_mesh *m = &s->mesh;
  size_t v, e;
  int st = LSYS_OK, r;
  *at = (size_t)-1;
  if (l1 > l0 && lsys_scene_detach_records(s) != LSYS_OK) return LSYS_ENOMEM;   /* scene.h */
  for (v = v0; v < v1; v++) {
    const float *P = m->pos + 3 * v;
    double p[3] = {P[0], P[1], P[2]}, q[3], J[3][3];
    if ((st = map(ctx, p, q, J)) != LSYS_OK) { *at = v; break; }
    for (r = 0; r < 3; r++) m->pos[3 * v + r] = (float)q[r];
    transform_normal(m->nrm + 3 * v, J);
  }
  for (e = 2 * l0; st == LSYS_OK && e < 2 * l1; e++) {
    const float *P = m->lpos + 3 * e;
    double p[3] = {P[0], P[1], P[2]}, q[3];
    if ((st = map(ctx, p, q, NULL)) != LSYS_OK) { *at = m->nv + e; break; }
    for (r = 0; r < 3; r++) m->lpos[3 * e + r] = (float)q[r];
  }
  if (v > v0) lsys_scene_touch(s, v0, v - v0);
  return st;
}

static int hpmap (void *ctx, const double p[3], double out[3], double J[3][3]) {
  lsys_ffd_hyperpatch_eval((const lsys_hyperpatch *)ctx, p, out, J);
  return LSYS_OK;
}

int lsys_ffd_range (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                    const lsys_hyperpatch *hp) {
  size_t at;
  if (checkrange(s, v0, v1, l0, l1) != LSYS_OK) return LSYS_EARG;
  return apply(s, v0, v1, l0, l1, hpmap, (void *)hp, &at);
}

static int affmap (void *ctx, const double p[3], double out[3], double J[3][3]) {
  const double *a = (const double *)ctx;
  int r, c;
  for (r = 0; r < 3; r++) {
    out[r] = a[4 * r] * p[0] + a[4 * r + 1] * p[1] + a[4 * r + 2] * p[2] + a[4 * r + 3];
    if (J != NULL)
      for (c = 0; c < 3; c++) J[r][c] = a[4 * r + c];
  }
  return LSYS_OK;
}

int lsys_ffd_affine (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                     const double m[12]) {
  size_t at;
  if (checkrange(s, v0, v1, l0, l1) != LSYS_OK) return LSYS_EARG;
  return apply(s, v0, v1, l0, l1, affmap, (void *)m, &at);
}

/* A callback map with its Jacobian by central differences of step h. */
typedef struct fnctx {
  lsys_deform_fn fn;
  void *ud;
  double h;
} fnctx;

static int fnmap (void *ctx, const double p[3], double out[3], double J[3][3]) {
  fnctx *f = (fnctx *)ctx;
  int st, c, r;
  if ((st = f->fn(f->ud, p, out)) != LSYS_OK) return st;
  if (J == NULL) return LSYS_OK;
  for (c = 0; c < 3; c++) {
    double a[3] = {p[0], p[1], p[2]}, b[3] = {p[0], p[1], p[2]}, qa[3], qb[3];
    a[c] += f->h;
    b[c] -= f->h;
    if ((st = f->fn(f->ud, a, qa)) != LSYS_OK || (st = f->fn(f->ud, b, qb)) != LSYS_OK)
      return st;
    for (r = 0; r < 3; r++) J[r][c] = (qa[r] - qb[r]) / (2 * f->h);
  }
  return LSYS_OK;
}

/* The diagonal of the bounding box of the range's vertices and line ends. */
static double rangediag (const lsys_mesh *m, size_t v0, size_t v1, size_t l0, size_t l1) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, d[3];
  size_t v;
  int r, any = 0;
  for (v = 0; v < (v1 - v0) + 2 * (l1 - l0); v++) {
    const float *P = v < v1 - v0 ? m->pos + 3 * (v0 + v) : m->lpos + 3 * (2 * l0 + v - (v1 - v0));
    for (r = 0; r < 3; r++) {
      if (P[r] < lo[r]) lo[r] = P[r];
      if (P[r] > hi[r]) hi[r] = P[r];
    }
    any = 1;
  }
  if (!any) return 0;
  for (r = 0; r < 3; r++) d[r] = hi[r] - lo[r];
  return len3(d);
}

int lsys_ffd_func (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                   lsys_deform_fn fn, void *ud, lsys_error *e) {
  fnctx f;
  size_t at = (size_t)-1;
  int st;
  if (checkrange(s, v0, v1, l0, l1) != LSYS_OK)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "deformation range out of the scene");
  f.fn = fn;
  f.ud = ud;
  f.h = 1e-4 * rangediag(&s->mesh, v0, v1, l0, l1);
  if (!(f.h > 0) || !isfinite(f.h)) f.h = 1e-4;
  st = apply(s, v0, v1, l0, l1, fnmap, &f, &at);
  if (st == LSYS_ENOMEM && at == (size_t)-1)
    lsys_seterror(e, st, at, "not enough memory");
  else if (st != LSYS_OK)
    lsys_seterror(e, st, at, "the deformation function failed at %s %zu",
                  at < s->mesh.nv ? "vertex" : "line end", at < s->mesh.nv ? at : at - s->mesh.nv);
  return st;
}

/* ---------------------------------------------------------------------- */
/* what modules drew */

/* The first record of a module >= m (records are in module order), or nrec. */
static size_t firstrec (const lsys_scene *s, uint32_t m) {
  size_t lo = 0, hi = s->nrec;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (s->rec[mid].module < m) lo = mid + 1; else hi = mid;
  }
  return lo;
}

int lsys_ffd_module_range (const lsys_scene *s, uint32_t m0, uint32_t m1, size_t *v0,
                           size_t *v1, size_t *l0, size_t *l1) {
  const lsys_mesh *m = &s->mesh;
  size_t r0, r1, t0, t1, t, nseg = 0, k;
  *v0 = *v1 = *l0 = *l1 = 0;
  if (s->nrec == 0 || m0 >= m1) return 0;
  r0 = firstrec(s, m0);
  r1 = firstrec(s, m1);
  if (r0 >= r1) return 0;
  t0 = lsys_scene_recshape(s, r0)->tri0;
  t1 = r1 < s->nrec ? lsys_scene_recshape(s, r1)->tri0 : m->nt;
  if (t1 > m->nt) t1 = m->nt;
  if (t0 < t1) {                           /* vertices: see ffd.h */
    size_t before = 0, last = 0;
    for (t = 0; t < 3 * t0; t++)
      if (m->tri[t] + (size_t)1 > before) before = m->tri[t] + (size_t)1;
    for (t = 3 * t0; t < 3 * t1; t++)
      if (m->tri[t] + (size_t)1 > last) last = m->tri[t] + (size_t)1;
    if (last > before) { *v0 = before; *v1 = last; }
  }
  for (k = 0; k < s->nrec; k++) nseg += lsys_scene_reckind(s, k) == LSYS_REC_SEGMENT;
  if (nseg == m->nl && nseg > 0) {          /* the line style: one line per segment record */
    for (k = 0; k < r0; k++) *l0 += lsys_scene_reckind(s, k) == LSYS_REC_SEGMENT;
    *l1 = *l0;
    for (k = r0; k < r1; k++) *l1 += lsys_scene_reckind(s, k) == LSYS_REC_SEGMENT;
  }
  return *v1 > *v0 || *l1 > *l0;
}
