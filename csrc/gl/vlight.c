/*
** Leaves coloured by their light (vlight.h).
*/
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "light.h"
#include "vlight.h"

/* The ramp: dark purple, blue, teal, green, yellow at 0, 1/4, 1/2, 3/4, 1 (the
** perceptually even "viridis" scale of matplotlib, sampled at its quarters). */
static const float RAMP[5][3] = {
  {0.267f, 0.005f, 0.329f}, {0.229f, 0.322f, 0.546f}, {0.128f, 0.567f, 0.551f},
  {0.369f, 0.789f, 0.383f}, {0.993f, 0.906f, 0.144f}
};

void lsys_vlight_ramp (double x, float rgb[3]) {
  double t = (x > 0 ? (x < 1 ? x : 1) : 0) * 4;
  int k = t >= 4 ? 3 : (int)t, c;
  float f = (float)(t - k);
  for (c = 0; c < 3; c++) rgb[c] = RAMP[k][c] + f * (RAMP[k + 1][c] - RAMP[k][c]);
}

void lsys_vlight_free (lsys_vlight *l) {
  LSYS_FREE(l->col);
  LSYS_FREE(l->tex);
  LSYS_FREE(l->lcol);
  LSYS_FREE(l->pal);
  memset(l, 0, sizeof *l);
}

static int isleaf (int kind) {
  return kind == LSYS_REC_DISC || kind == LSYS_REC_POLYGON || kind == LSYS_REC_SURFACE;
}

int lsys_vlight_leaves (lsys_vframe *f, const lsys_scene *s) {
  size_t k, n = 0, pass, nrec = s->nrec;
  f->leafr = NULL;
  f->nleafr = 0;
  if (f->sc.ninst > 0) return LSYS_OK;
  for (pass = 0; pass < 2; pass++) {        /* count the ranges, then fill them */
    uint32_t a = 0, b = 0;
    n = 0;
    for (k = 0; k <= nrec; k++) {
      const lsys_rshape *r = k < nrec ? lsys_scene_recshape(s, k) : NULL;
      if (r != NULL && (!isleaf(r->kind) || r->ntri == 0)) continue;
      if (r != NULL && b > a && r->tri0 == b) { b += r->ntri; continue; }   /* touches */
      if (b > a) {
        if (pass == 1) { f->leafr[2 * n] = a; f->leafr[2 * n + 1] = b; }
        n++;
      }
      if (r != NULL) { a = r->tri0; b = r->tri0 + r->ntri; }
    }
    if (n == 0) return LSYS_OK;
    if (pass == 0 && (f->leafr = (uint32_t *)LSYS_MALLOC(2 * n * sizeof *f->leafr)) == NULL)
      return LSYS_ENOMEM;
  }
  f->nleafr = n;
  return LSYS_OK;
}

/* The leaf triangles of f, in order, into tris (NULL: only counted): those of
** its leaf ranges within the mesh that are two-sided (not a cylinder that a
** pending segment drew while the leaf's module ran). Returns their number. */
static size_t leaves (const lsys_vframe *f, uint32_t *tris) {
  const lsys_mesh *m = &f->sc.mesh;
  size_t r, t, n = 0;
  for (r = 0; r < f->nleafr; r++)
    for (t = f->leafr[2 * r]; t < f->leafr[2 * r + 1] && t < m->nt; t++)
      if (m->twosided[m->tri[3 * t]]) {
        if (tris != NULL) tris[n] = (uint32_t)t;
        n++;
      }
  return n;
}

/* Triangle t's centroid c, its unit normal facing up n, and its area;
** 0 when it is degenerate or not finite. */
static double facet (const lsys_mesh *m, size_t t, double c[3], double n[3]) {
  const float *p0 = m->pos + 3 * m->tri[3 * t], *p1 = m->pos + 3 * m->tri[3 * t + 1],
              *p2 = m->pos + 3 * m->tri[3 * t + 2];
  double u[3], v[3], len;
  int i;
  for (i = 0; i < 3; i++) {
    c[i] = ((double)p0[i] + p1[i] + p2[i]) / 3;
    u[i] = (double)p1[i] - p0[i];
    v[i] = (double)p2[i] - p0[i];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !isfinite(len) || !isfinite(c[0] + c[1] + c[2])) return 0;
  if (n[1] < 0) len = -len;                 /* the face that looks up */
  for (i = 0; i < 3; i++) n[i] /= len;
  return fabs(len) / 2;
}

/* Nothing to colour: l empty but for the message. */
static int nothing (lsys_vlight *l, const char *msg) {
  snprintf(l->msg, sizeof l->msg, "%s", msg);
  return LSYS_OK;
}

/* The palette of l: the frame's (a grey one when it has none) and the ramp. */
static int palette (lsys_vlight *l, const lsys_scene *sc, size_t npal0) {
  size_t k;
  l->npal = npal0 + LSYS_VLIGHT_BINS;
  if ((l->pal = (lsys_material *)LSYS_MALLOC(l->npal * sizeof *l->pal)) == NULL)
    return LSYS_ENOMEM;
  if (sc->npal > 0) memcpy(l->pal, sc->pal, npal0 * sizeof *l->pal);
  else lsys_mesh_material_color(&l->pal[0], 0.8, 0.8, 0.8);
  for (k = 0; k < LSYS_VLIGHT_BINS; k++) {
    float rgb[3];
    lsys_vlight_ramp((double)k / (LSYS_VLIGHT_BINS - 1), rgb);
    lsys_mesh_material_color(&l->pal[npal0 + k], rgb[0], rgb[1], rgb[2]);
  }
  return LSYS_OK;
}

/*
** The indices of l from the vertices' light: acc[2 i] the area-weighted sum of
** the light of the leaf triangles at vertex i, acc[2 i + 1] their area.
*/
static void indices (lsys_vlight *l, const lsys_mesh *m, size_t npal0, const double *acc) {
  size_t i, k;
  int textured = 0;
  for (i = 0; i < m->nv; i++) {
    if (acc[2 * i + 1] > 0) {
      double x = acc[2 * i] / acc[2 * i + 1];
      l->col[i] = (uint16_t)(npal0 + (size_t)floor(x * (LSYS_VLIGHT_BINS - 1) + 0.5));
      textured |= m->tex[i] != 0;
    } else l->col[i] = (uint16_t)(m->col[i] % npal0);
  }
  if (l->tex != NULL && textured)
    for (i = 0; i < m->nv; i++) l->tex[i] = acc[2 * i + 1] > 0 ? 0 : m->tex[i];
  else {
    LSYS_FREE(l->tex);
    l->tex = NULL;
  }
  if (l->lcol != NULL)
    for (k = 0; k < m->nl; k++) l->lcol[k] = (uint16_t)(m->lcol[k] % npal0);
}

int lsys_vlight_compute (lsys_vlight *l, const lsys_vframe *f, int live, int threads,
                         lsys_meter *mt, lsys_error *e) {
  const lsys_mesh *m = &f->sc.mesh;
  lsys_light_opts o;
  lsys_light *L = NULL;
  const double *dir, *w;
  double *pts = NULL, *nrm = NULL, *val = NULL, *acc = NULL, open = 0, sum = 0, area = 0;
  uint32_t *tris = NULL;
  size_t n = 0, t, k, nd, npal0 = f->sc.npal > 0 ? f->sc.npal : 1, bytes, used0;
  int st, wrap = 0;
  char b1[32], b2[32];
  memset(l, 0, sizeof *l);
  if (live) return nothing(l, "not for a growing scene");
  if (f->sc.ninst > 0) return nothing(l, "not for a population");
  if ((n = leaves(f, NULL)) == 0) return nothing(l, "no leaves in this step");
  if (npal0 + LSYS_VLIGHT_BINS > 65536) return nothing(l, "the palette is full");
  for (k = 0; k < m->nl; k++) wrap |= m->lcol[k] >= npal0;
  /* what is held besides the hierarchy: the queries, the vertices' sums, the indices */
  bytes = n * (7 * sizeof(double) + sizeof(uint32_t)) + m->nv * (2 * sizeof(double) +
          2 * sizeof(uint16_t)) + (wrap ? m->nl * sizeof(uint16_t) : 0);
  used0 = mt != NULL ? mt->used : 0;
  if (!lsys_common_meter_fits(mt, bytes)) {
    mt->hit = 1;
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "the light colours need %s, more than "
                         "max_memory (%s)", lsys_common_fmtsize(b1, bytes),
                         lsys_common_fmtsize(b2, mt->limit));
  }
  if (mt != NULL) mt->used += bytes;
  lsys_light_defaults(&o);
  o.samples = LSYS_VLIGHT_SAMPLES;
  o.meter = mt;
  if ((st = lsys_light_build(&L, &f->sc, &o, e)) != LSYS_OK) goto done;
  pts = (double *)LSYS_MALLOC(n * 3 * sizeof *pts);
  nrm = (double *)LSYS_MALLOC(n * 3 * sizeof *nrm);
  val = (double *)LSYS_MALLOC(n * sizeof *val);
  tris = (uint32_t *)LSYS_MALLOC(n * sizeof *tris);
  acc = (double *)LSYS_MALLOC((m->nv > 0 ? m->nv : 1) * 2 * sizeof *acc);
  l->col = (uint16_t *)LSYS_MALLOC((m->nv > 0 ? m->nv : 1) * sizeof *l->col);
  l->tex = (uint16_t *)LSYS_MALLOC((m->nv > 0 ? m->nv : 1) * sizeof *l->tex);
  if (wrap) l->lcol = (uint16_t *)LSYS_MALLOC(m->nl * sizeof *l->lcol);
  st = LSYS_ENOMEM;
  if (pts == NULL || nrm == NULL || val == NULL || tris == NULL || acc == NULL ||
      l->col == NULL || l->tex == NULL || (wrap && l->lcol == NULL) ||
      palette(l, &f->sc, npal0) != LSYS_OK)
    goto done;
  leaves(f, tris);
  for (k = 0, t = 0; t < n; t++)            /* the queries: the leaves that have an area */
    if (facet(m, tris[t], pts + 3 * k, nrm + 3 * k) > 0) tris[k++] = tris[t];
  n = k;
  if ((st = lsys_light_query(L, pts, n, nrm, val, NULL, threads, e)) != LSYS_OK) goto done;
  nd = lsys_light_sky(L, &dir, &w);         /* an open horizontal leaf's light: 1 */
  for (k = 0; k < nd; k++) open += w[k] * (dir[3 * k + 1] > 0 ? dir[3 * k + 1] : 0);
  memset(acc, 0, m->nv * 2 * sizeof *acc);
  l->min = 1;
  for (k = 0; k < n; k++) {
    double x = open > 0 ? val[k] / open : 0, c[3], nn[3], a;
    int i;
    x = x > 0 ? (x < 1 ? x : 1) : 0;
    a = facet(m, tris[k], c, nn);
    for (i = 0; i < 3; i++) {
      uint32_t v = m->tri[3 * (size_t)tris[k] + i];
      acc[2 * v] += a * x;
      acc[2 * v + 1] += a;
    }
    sum += a * x;
    area += a;
    if (x < l->min) l->min = x;
    if (x > l->max) l->max = x;
  }
  if (n == 0) l->min = 0;
  l->mean = area > 0 ? sum / area : 0;
  l->nleaves = n;
  indices(l, m, npal0, acc);
  if (n == 0) snprintf(l->msg, sizeof l->msg, "the leaves have no area");
  st = LSYS_OK;
done:
  lsys_light_free(L);
  LSYS_FREE(pts);
  LSYS_FREE(nrm);
  LSYS_FREE(val);
  LSYS_FREE(tris);
  LSYS_FREE(acc);
  if (mt != NULL) mt->used = used0;
  if (st != LSYS_OK) lsys_vlight_free(l);
  return st;
}

void lsys_vlight_apply (const lsys_vlight *l, lsys_scene *sc) {
  if (l == NULL || l->col == NULL) return;
  sc->mesh.col = l->col;
  if (l->tex != NULL) sc->mesh.tex = l->tex;
  if (l->lcol != NULL) sc->mesh.lcol = l->lcol;
  sc->pal = l->pal;
  sc->npal = l->npal;
}

void lsys_vlight_note (const lsys_vlight *l, char *buf, size_t n) {
  if (l == NULL) snprintf(buf, n, "computing ...");
  else if (l->nleaves == 0) snprintf(buf, n, "%.60s", l->msg);
  else snprintf(buf, n, "%.2f - %.2f, mean %.2f", l->min, l->max, l->mean);
}
