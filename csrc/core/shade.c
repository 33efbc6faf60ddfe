/*
** Shadows and ambient occlusion per vertex (shade.h).
*/
#include <math.h>
#include <string.h>

#include "light.h"
#include "shade.h"
#include "vec3.h"

#define SOFTRAYS 9                /* a soft shadow: the centre and a spiral of 8 */
#define LIFT 2e-3                 /* the rays' start off the surface, of the diagonal */

void lsys_shade_defaults (lsys_shade_opts *o) {
  memset(o, 0, sizeof *o);
  o->shadow_strength = 0.6;
  o->ao_samples = 16;
  o->ao_strength = 0.6;
  o->threads = 1;
}

static int bad (lsys_error *e, const char *what, const char *range) {
  return lsys_seterror(e, LSYS_EARG, (size_t)-1, "shade: %s must be %s", what, range);
}

static int checkopts (const lsys_shade_opts *o, lsys_error *e) {
  if (!(o->softness >= 0 && o->softness <= 30)) return bad(e, "softness", "in [0, 30]");
  if (!(o->shadow_strength >= 0 && o->shadow_strength <= 1))
    return bad(e, "the shadow strength", "in [0, 1]");
  if (o->ao_samples < 1 || o->ao_samples > LSYS_SHADE_MAXSAMPLES)
    return bad(e, "the ambient occlusion samples", "an integer in [1, 1024]");
  if (!(o->ao_distance >= 0 && isfinite(o->ao_distance)))
    return bad(e, "the ambient occlusion distance", "a finite number >= 0");
  if (!(o->ao_strength >= 0 && o->ao_strength <= 1))
    return bad(e, "the ambient occlusion strength", "in [0, 1]");
  return LSYS_OK;
}

/* u, w: a unit basis orthogonal to the unit vector d. */
static void basis (const double d[3], double u[3], double w[3]) {
  double a[3] = {0, 0, 0}, len;
  a[fabs(d[0]) < 0.6 ? 0 : fabs(d[1]) < 0.6 ? 1 : 2] = 1;
  u[0] = a[1] * d[2] - a[2] * d[1];
  u[1] = a[2] * d[0] - a[0] * d[2];
  u[2] = a[0] * d[1] - a[1] * d[0];
  len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  u[0] /= len; u[1] /= len; u[2] /= len;
  w[0] = d[1] * u[2] - d[2] * u[1];
  w[1] = d[2] * u[0] - d[0] * u[2];
  w[2] = d[0] * u[1] - d[1] * u[0];
}

/* The shadow rays' directions and weights (x, y, z, w each) around the unit
** direction l into d; returns their number. */
static size_t shadowdirs (double *d, const double l[3], double softness) {
  double u[3], w[3], a = softness * PI / 360;       /* the cone's half angle */
  size_t k, n = softness > 0 ? SOFTRAYS : 1;
  int c;
  basis(l, u, w);
  for (k = 0; k < n; k++) {
    double r = k == 0 ? 0 : tan(a * sqrt((k - 0.5) / (n - 1))), phi = k * 2.39996323;
    for (c = 0; c < 3; c++) d[4 * k + c] = l[c] + r * (cos(phi) * u[c] + sin(phi) * w[c]);
    d[4 * k + 3] = 1;
  }
  return n;
}

/* n directions evenly over the sphere (a Fibonacci spiral), equal weights. */
static void spheredirs (double *d, size_t n) {
  size_t k;
  for (k = 0; k < n; k++) {
    double y = 1 - (2 * (double)k + 1) / (double)n, r = sqrt(1 - y * y), phi = k * 2.39996323;
    d[4 * k] = r * cos(phi);
    d[4 * k + 1] = y;
    d[4 * k + 2] = r * sin(phi);
    d[4 * k + 3] = 1;
  }
}

/* The unit normal of vertex v into n; 0 when it has none. */
static int normal (const lsys_mesh *m, size_t v, double n[3]) {
  double len;
  int c;
  for (c = 0; c < 3; c++) n[c] = m->nrm[3 * v + c];
  len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !isfinite(len)) return 0;
  for (c = 0; c < 3; c++) n[c] /= len;
  return 1;
}

/* One query of 'nq' points (and normals) against a light of directions d. */
static int query (const lsys_scene *s, const double *d, size_t nd, double reach,
                  const double *pts, const double *nrm, size_t nq, double *val,
                  const lsys_shade_opts *o, lsys_error *e) {
  lsys_light_opts lo;
  lsys_light *L = NULL;
  int st;
  lsys_light_defaults(&lo);
  lo.kind = LSYS_LIGHT_DIRS;
  lo.dirs = d;
  lo.ndirs = nd;
  lo.max_distance = reach;
  lo.meter = o->meter;
  if ((st = lsys_light_build(&L, s, &lo, e)) != LSYS_OK) return st;
  st = lsys_light_query(L, pts, nq, nrm, val, NULL, o->threads, e);
  lsys_light_free(L);
  return st;
}

int lsys_shade_compute (uint8_t *out, const lsys_scene *s, const lsys_shade_opts *o,
                        lsys_error *e) {
  const lsys_mesh *m = &s->mesh;
  double *fac = NULL, *pts = NULL, *nrm = NULL, *val = NULL, *dirs = NULL;
  double diag = 0, lo[3], hi[3], l[3], lift, len;
  size_t nv = m->nv, v, k, nq, nd, bytes, used0 = o->meter != NULL ? o->meter->used : 0;
  int st, c;
  char b1[32], b2[32];
  if ((st = checkopts(o, e)) != LSYS_OK) return st;
  memset(out, 255, nv);
  if (nv == 0 || m->nt == 0 || s->ninst > 0 || (!o->shadows && !o->ao)) return LSYS_OK;
  for (c = 0; c < 3; c++) { lo[c] = HUGE_VAL; hi[c] = -HUGE_VAL; }
  for (v = 0; v < nv; v++)
    for (c = 0; c < 3; c++) {
      double x = m->pos[3 * v + c];
      if (x < lo[c]) lo[c] = x;
      if (x > hi[c]) hi[c] = x;
    }
  for (c = 0; c < 3; c++) diag += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  diag = sqrt(diag);
  if (!(diag > 0) || !isfinite(diag)) return LSYS_OK;
  lift = LIFT * diag;
  nd = (size_t)o->ao_samples * 2 > SOFTRAYS ? (size_t)o->ao_samples * 2 : SOFTRAYS;
  bytes = nv * (sizeof *fac + 2 * (7 * sizeof(double))) + nd * 4 * sizeof(double);
  if (!lsys_common_meter_fits(o->meter, bytes)) {
    o->meter->hit = 1;
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "shadows need %s, more than "
                         "max_memory (%s)", lsys_common_fmtsize(b1, bytes),
                         lsys_common_fmtsize(b2, o->meter->limit));
  }
  if (o->meter != NULL) o->meter->used += bytes;
  fac = (double *)LSYS_MALLOC(nv * sizeof *fac);
  pts = (double *)LSYS_MALLOC(2 * nv * 3 * sizeof *pts);
  nrm = (double *)LSYS_MALLOC(2 * nv * 3 * sizeof *nrm);
  val = (double *)LSYS_MALLOC(2 * nv * sizeof *val);
  dirs = (double *)LSYS_MALLOC(nd * 4 * sizeof *dirs);
  st = LSYS_ENOMEM;
  if (fac == NULL || pts == NULL || nrm == NULL || val == NULL || dirs == NULL) goto done;
  for (v = 0; v < nv; v++) fac[v] = 1;
  len = sqrt(s->light[0] * s->light[0] + s->light[1] * s->light[1] +
             s->light[2] * s->light[2]);
  if (o->shadows && len > 0 && isfinite(len)) {
    size_t *which = (size_t *)(void *)nrm;          /* the vertices asked, in nrm's room */
    double *cosk = nrm + nv;                        /* their facing, behind them */
    for (c = 0; c < 3; c++) l[c] = s->light[c] / len;
    for (nq = 0, v = 0; v < nv; v++) {
      double n[3], cs;
      if (!normal(m, v, n)) continue;
      cs = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
      if (cs < 0 && m->twosided[v]) { cs = -cs; for (c = 0; c < 3; c++) n[c] = -n[c]; }
      if (cs <= 0) continue;                        /* turned away: the light misses it */
      for (c = 0; c < 3; c++) pts[3 * nq + c] = m->pos[3 * v + c] + lift * n[c];
      cosk[nq] = cs;
      which[nq++] = v;
    }
    k = shadowdirs(dirs, l, o->softness);
    if (nq > 0 && (st = query(s, dirs, k, 0, pts, NULL, nq, val, o, e)) != LSYS_OK) goto done;
    /* a shadow takes away the key light, which gives a vertex in proportion to its
    ** facing: one lit at a grazing angle loses little */
    for (k = 0; k < nq; k++)
      fac[which[k]] *= 1 - o->shadow_strength * (1 - val[k]) * cosk[k];
  }
  if (o->ao) {
    size_t na = 2 * (size_t)o->ao_samples, i;
    double reach = o->ao_distance > 0 ? o->ao_distance : diag / 4;
    spheredirs(dirs, na);
    for (nq = 0, v = 0; v < nv; v++) {
      double n[3];
      int side, sides;
      if (!normal(m, v, n)) { for (c = 0; c < 3; c++) n[c] = c == 1; }
      sides = m->twosided[v] ? 2 : 1;
      for (side = 0; side < sides; side++, nq++)
        for (c = 0; c < 3; c++) {
          double nc = side ? -n[c] : n[c];
          pts[3 * nq + c] = m->pos[3 * v + c] + lift * nc;
          nrm[3 * nq + c] = nc;
        }
    }
    if ((st = query(s, dirs, na, reach, pts, nrm, nq, val, o, e)) != LSYS_OK) goto done;
    for (k = 0, v = 0; v < nv; v++) {
      int side, sides = m->twosided[v] ? 2 : 1;
      double sum = 0;
      for (side = 0; side < sides; side++, k++) {
        double open = 0;                            /* the unblocked value of this normal */
        for (i = 0; i < na; i++) {
          double cs = nrm[3 * k] * dirs[4 * i] + nrm[3 * k + 1] * dirs[4 * i + 1] +
                      nrm[3 * k + 2] * dirs[4 * i + 2];
          if (cs > 0) open += cs / (double)na;
        }
        sum += open > 0 ? (val[k] / open < 1 ? val[k] / open : 1) : 1;
      }
      fac[v] *= 1 - o->ao_strength * (1 - sum / sides);
    }
  }
  for (v = 0; v < nv; v++) {
    double x = fac[v] * 255 + 0.5;
    out[v] = (uint8_t)(x < 0 ? 0 : x > 255 ? 255 : x);
  }
  st = LSYS_OK;
done:
  LSYS_FREE(fac);
  LSYS_FREE(pts);
  LSYS_FREE(nrm);
  LSYS_FREE(val);
  LSYS_FREE(dirs);
  if (o->meter != NULL) o->meter->used = used0;
  return st;
}

/* Half the side of the ground's square under the box lo .. hi. */
static double halfside (const double lo[3], const double hi[3], double size) {
  double ext = hi[0] - lo[0] > hi[2] - lo[2] ? hi[0] - lo[0] : hi[2] - lo[2];
  if (ext < (hi[1] - lo[1]) / 2) ext = (hi[1] - lo[1]) / 2;
  if (!(ext > 0)) ext = 1;
  return size * ext / 2;
}

double lsys_shade_ground_half (const lsys_mesh *m, const lsys_shade_ground *g) {
  double lo[3], hi[3];
  if (!lsys_mesh_bounds(m, lo, hi)) return 0;
  return halfside(lo, hi, g->size);
}

int lsys_shade_add_ground (lsys_mesh *m, const lsys_shade_ground *g, lsys_error *e) {
  double lo[3], hi[3], c[3], half, diag = 0, p[3], n[3] = {0, 1, 0};
  double x0, z0, x1, z1, cell;
  size_t i, j, nx, nz, v0;
  int a;
  if (!(g->size > 0 && g->size <= 1000))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "ground: size must be in (0, 1000]");
  if (g->cells < 1 || g->cells > 1024)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "ground: cells must be an integer in "
                         "[1, 1024]");
  if (!lsys_mesh_bounds(m, lo, hi)) return LSYS_OK;
  for (a = 0; a < 3; a++) {
    c[a] = (lo[a] + hi[a]) / 2;
    diag += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  }
  half = halfside(lo, hi, g->size);
  x0 = c[0] - half; x1 = c[0] + half;
  z0 = c[2] - half; z1 = c[2] + half;
  if (g->has_rect) {
    double reach = LSYS_SHADE_GROUND_REACH * half;
    x0 = fmin(x0, fmax(g->rect[0], c[0] - reach));
    z0 = fmin(z0, fmax(g->rect[1], c[2] - reach));
    x1 = fmax(x1, fmin(g->rect[2], c[0] + reach));
    z1 = fmax(z1, fmin(g->rect[3], c[2] + reach));
  }
  cell = 2 * half / g->cells;
  while ((x1 - x0) / cell * ((z1 - z0) / cell) > 4.0 * g->cells * g->cells) cell *= 1.25;
  nx = (size_t)ceil((x1 - x0) / cell - 1e-9);
  nz = (size_t)ceil((z1 - z0) / cell - 1e-9);
  if (lsys_mesh_reserve(m, (nx + 1) * (nz + 1), 2 * nx * nz) != LSYS_OK) return LSYS_ENOMEM;
  v0 = m->nv;
  p[1] = lo[1] - 1e-3 * sqrt(diag);
  for (j = 0; j <= nz; j++)
    for (i = 0; i <= nx; i++) {
      unsigned col = g->col;
      p[0] = x0 + (x1 - x0) * (double)i / (double)nx;
      p[2] = z0 + (z1 - z0) * (double)j / (double)nz;
      if (g->nfade > 1) {             /* the fade starts at the square's edge */
        double d = hypot(p[0] - c[0], p[2] - c[2]) / half - 1;
        double t = d <= 0 ? 0 : d >= LSYS_SHADE_GROUND_FADE - 1 ? 1
                                  : d / (LSYS_SHADE_GROUND_FADE - 1);
        col += (unsigned)(t * (g->nfade - 1) + 0.5);
      }
      lsys_mesh_vertex(m, p, n, (double)i / (double)nx, (double)j / (double)nz, col, 0);
      m->tex[m->nv - 1] = 0;
    }
  for (j = 0; j < nz; j++)
    for (i = 0; i < nx; i++) {        /* counterclockwise seen from above */
      uint32_t q = (uint32_t)(v0 + j * (nx + 1) + i), r = q + (uint32_t)(nx + 1);
      lsys_mesh_tri(m, q, r, q + 1);
      lsys_mesh_tri(m, q + 1, r, r + 1);
    }
  return LSYS_OK;
}
