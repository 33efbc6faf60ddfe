/*
** Mesh buffers and materials (mesh.h). The export writers that read them
** are in export_*.c (export.h).
*/
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

void lsys_mesh_init (lsys_mesh *m) {
  *m = (lsys_mesh){0};
}

void lsys_mesh_free (lsys_mesh *m) {
  LSYS_FREE(m->pos); LSYS_FREE(m->nrm); LSYS_FREE(m->uv);
  LSYS_FREE(m->col); LSYS_FREE(m->twosided); LSYS_FREE(m->tex); LSYS_FREE(m->tri);
  LSYS_FREE(m->lpos); LSYS_FREE(m->lwidth); LSYS_FREE(m->lcol);
  lsys_mesh_init(m);
}

void lsys_mesh_clear (lsys_mesh *m) {
  m->nv = m->nt = m->nl = 0;
  m->curtex = 0;
}

static int growall (void **arr[], const size_t elem[], int k, size_t *cap, size_t need,
                    lsys_meter *mt);

int lsys_mesh_copy (lsys_mesh *dst, const lsys_mesh *src) {
  lsys_mesh_init(dst);
  dst->curtex = src->curtex;
  if ((src->nv > 0 || src->nt > 0) && lsys_mesh_reserve(dst, src->nv, src->nt) != LSYS_OK)
    goto fail;
  if (src->nv > 0) {
    memcpy(dst->pos, src->pos, src->nv * 3 * sizeof(float));
    memcpy(dst->nrm, src->nrm, src->nv * 3 * sizeof(float));
    memcpy(dst->uv, src->uv, src->nv * 2 * sizeof(float));
    memcpy(dst->col, src->col, src->nv * sizeof(uint16_t));
    memcpy(dst->twosided, src->twosided, src->nv);
    memcpy(dst->tex, src->tex, src->nv * sizeof(uint16_t));
  }
  if (src->nt > 0) memcpy(dst->tri, src->tri, src->nt * 3 * sizeof(uint32_t));
  dst->nv = src->nv;
  dst->nt = src->nt;
  if (src->nl > 0) {
    size_t cap = 0;
    void **arr[3] = { (void **)&dst->lpos, (void **)&dst->lwidth, (void **)&dst->lcol };
    const size_t elem[3] = { 6 * sizeof(float), 2 * sizeof(float), sizeof(uint16_t) };
    if (growall(arr, elem, 3, &cap, src->nl, NULL) != LSYS_OK) goto fail;
    dst->lcap = cap;
    memcpy(dst->lpos, src->lpos, src->nl * 6 * sizeof(float));
    memcpy(dst->lwidth, src->lwidth, src->nl * 2 * sizeof(float));
    memcpy(dst->lcol, src->lcol, src->nl * sizeof(uint16_t));
    dst->nl = src->nl;
  }
  return LSYS_OK;
fail:
  lsys_mesh_free(dst);
  return LSYS_ENOMEM;
}

/*
** Grows the 'k' arrays 'arr' (item sizes 'elem') that share the capacity
** '*cap' to hold 'need' items. Every array starts from the same capacity, so
** lsys_common_grow picks the same new one for all; '*cap' changes only when all of
** them have grown (an array that grew before a failure is merely larger).
*/
static int growall (void **arr[], const size_t elem[], int k, size_t *cap, size_t need,
                    lsys_meter *mt) {
  size_t c = *cap, sum = 0;
  int i, st;
  if (mt != NULL) {              /* the budget for all of them: one block of 'sum' per item */
    for (i = 0; i < k; i++) sum += elem[i];
    if (need <= c) return LSYS_OK;
    if ((st = lsys_common_meter_take(mt, *cap, need, sum, &c)) != LSYS_OK) return st;
    for (i = 0; i < k; i++) {    /* exactly the capacity the budget allowed */
      void *np = LSYS_REALLOC(*arr[i], c * elem[i]);
      if (np == NULL) return LSYS_ENOMEM;
      lsys_common_hugepages(np, c * elem[i]);
      *arr[i] = np;
    }
    *cap = c;
    return LSYS_OK;
  }
  for (i = 0; i < k; i++) {
    c = *cap;
    if (lsys_common_grow(arr[i], &c, need, elem[i]) != LSYS_OK) return LSYS_ENOMEM;
  }
  *cap = c;
  return LSYS_OK;
}

/* Vertices [a, b) of s into d (which has room for them). */
static void copyverts (lsys_mesh *d, const lsys_mesh *s, size_t a, size_t b) {
  size_t n = b - a;
  memcpy(d->pos + 3 * a, s->pos + 3 * a, 3 * n * sizeof(float));
  memcpy(d->nrm + 3 * a, s->nrm + 3 * a, 3 * n * sizeof(float));
  memcpy(d->uv + 2 * a, s->uv + 2 * a, 2 * n * sizeof(float));
  memcpy(d->col + a, s->col + a, n * sizeof(uint16_t));
  memcpy(d->twosided + a, s->twosided + a, n);
  memcpy(d->tex + a, s->tex + a, n * sizeof(uint16_t));
}

int lsys_mesh_sync (lsys_mesh *dst, const lsys_mesh *src, const size_t *r, size_t n) {
  size_t nv0 = dst->nv, k;
  int st;
  if (src->nv < dst->nv || src->nt < dst->nt || src->nl < dst->nl) return LSYS_EARG;
  if ((st = lsys_mesh_reserve(dst, src->nv - dst->nv, src->nt - dst->nt)) != LSYS_OK)
    return st;
  if (src->nl > dst->lcap) {
    void **arr[3] = { (void **)&dst->lpos, (void **)&dst->lwidth, (void **)&dst->lcol };
    const size_t elem[3] = { 6 * sizeof(float), 2 * sizeof(float), sizeof(uint16_t) };
    if (growall(arr, elem, 3, &dst->lcap, src->nl, NULL) != LSYS_OK) return LSYS_ENOMEM;
  }
  for (k = 0; k < n; k++) {             /* changed in place: the ones dst has */
    size_t b = r[2 * k + 1] < nv0 ? r[2 * k + 1] : nv0;
    if (r[2 * k] < b) copyverts(dst, src, r[2 * k], b);
  }
  if (src->nv > nv0) copyverts(dst, src, nv0, src->nv);
  if (src->nt > dst->nt)
    memcpy(dst->tri + 3 * dst->nt, src->tri + 3 * dst->nt,
           3 * (src->nt - dst->nt) * sizeof(uint32_t));
  if (src->nl > dst->nl) {
    memcpy(dst->lpos + 6 * dst->nl, src->lpos + 6 * dst->nl,
           6 * (src->nl - dst->nl) * sizeof(float));
    memcpy(dst->lwidth + 2 * dst->nl, src->lwidth + 2 * dst->nl,
           2 * (src->nl - dst->nl) * sizeof(float));
    memcpy(dst->lcol + dst->nl, src->lcol + dst->nl, (src->nl - dst->nl) * sizeof(uint16_t));
  }
  dst->nv = src->nv;
  dst->nt = src->nt;
  dst->nl = src->nl;
  dst->curtex = src->curtex;
  return LSYS_OK;
}

/* Vertex indices are uint32_t: at most UINT32_MAX vertices (LSYS_ELIMIT). */
int lsys_mesh_reserve (lsys_mesh *m, size_t nv, size_t nt) {
  int st;
  if (nv > (size_t)UINT32_MAX - m->nv || nt > ((size_t)-1 / 12) - m->nt)
    return LSYS_ELIMIT;
  if (m->fixed && (m->nv + nv > m->vcap || m->nt + nt > m->tcap)) return LSYS_ELIMIT;
  if (m->nv + nv > m->vcap) {
    void **arr[6] = { (void **)&m->pos, (void **)&m->nrm, (void **)&m->uv,
                      (void **)&m->col, (void **)&m->twosided, (void **)&m->tex };
    const size_t elem[6] = { 3 * sizeof(float), 3 * sizeof(float), 2 * sizeof(float),
                             sizeof(uint16_t), sizeof(uint8_t), sizeof(uint16_t) };
    if ((st = growall(arr, elem, 6, &m->vcap, m->nv + nv, m->meter)) != LSYS_OK) return st;
  }
  if (m->nt + nt > m->tcap &&
      (st = lsys_common_grow_metered((void **)&m->tri, &m->tcap, m->nt + nt, 3 * sizeof(uint32_t),
                                     m->meter)) != LSYS_OK)
    return st;
  return LSYS_OK;
}

int lsys_mesh_reserve_lines (lsys_mesh *m, size_t nl) {
  void **arr[3] = { (void **)&m->lpos, (void **)&m->lwidth, (void **)&m->lcol };
  const size_t elem[3] = { 6 * sizeof(float), 2 * sizeof(float), sizeof(uint16_t) };
  if (nl > (size_t)UINT32_MAX - m->nl) return LSYS_ELIMIT;
  if (m->nl + nl <= m->lcap) return LSYS_OK;
  if (m->fixed) return LSYS_ELIMIT;
  return growall(arr, elem, 3, &m->lcap, m->nl + nl, m->meter);
}

/* NaN coordinates take no part (every comparison with them is false). */
static void addbounds (const float *p, size_t n, double lo[3], double hi[3]) {
  size_t i;
  int k;
  for (i = 0; i < n; i++, p += 3)
    for (k = 0; k < 3; k++) {
      if (p[k] < lo[k]) lo[k] = p[k];
      if (p[k] > hi[k]) hi[k] = p[k];
    }
}

static int cmpedge (const void *x, const void *y) {
  const uint32_t *a = (const uint32_t *)x, *b = (const uint32_t *)y;
  return a[0] != b[0] ? (a[0] > b[0]) - (a[0] < b[0]) : (a[1] > b[1]) - (a[1] < b[1]);
}

size_t lsys_mesh_edges (const lsys_mesh *m, size_t t0, size_t nt, uint32_t *edges) {
  size_t i, n = 0, k;
  if (t0 >= m->nt) return 0;
  if (nt > m->nt - t0) nt = m->nt - t0;
  for (i = t0; i < t0 + nt; i++)
    for (k = 0; k < 3; k++) {
      uint32_t a = m->tri[3 * i + k], b = m->tri[3 * i + (k + 1) % 3];
      if (a == b) continue;                     /* degenerate */
      edges[2 * n] = a < b ? a : b;
      edges[2 * n + 1] = a < b ? b : a;
      n++;
    }
  qsort(edges, n, 2 * sizeof *edges, cmpedge);
  for (i = k = 0; i < n; i++)
    if (k == 0 || edges[2 * i] != edges[2 * k - 2] || edges[2 * i + 1] != edges[2 * k - 1]) {
      edges[2 * k] = edges[2 * i];
      edges[2 * k + 1] = edges[2 * i + 1];
      k++;
    }
  return k;
}

int lsys_mesh_bounds (const lsys_mesh *m, double lo[3], double hi[3]) {
  int k, ok = 1;
  for (k = 0; k < 3; k++) { lo[k] = HUGE_VAL; hi[k] = -HUGE_VAL; }
  addbounds(m->pos, m->nv, lo, hi);
  addbounds(m->lpos, 2 * m->nl, lo, hi);
  for (k = 0; k < 3; k++)
    if (!(lo[k] <= hi[k])) ok = 0;
  if (!ok)
    for (k = 0; k < 3; k++) lo[k] = hi[k] = 0;
  return ok;
}

void lsys_mesh_material_color (lsys_material *mt, double r, double g, double b) {
  float c[3];
  int k;
  c[0] = lsys_unit(r); c[1] = lsys_unit(g); c[2] = lsys_unit(b);
  *mt = (lsys_material){0};
  for (k = 0; k < 3; k++) {
    mt->diffuse[k] = c[k];
    mt->ambient[k] = 0.3f * c[k];
  }
  mt->diffuse[3] = mt->ambient[3] = mt->specular[3] = mt->emission[3] = 1.0f;
}

size_t lsys_mesh_color_counts (const lsys_mesh *m, uint32_t *count) {
  size_t i, used = 0;
  memset(count, 0, LSYS_MESH_NCOLORS * sizeof *count);
  for (i = 0; i < m->nt; i++) {
    uint32_t *c = &count[m->col[m->tri[3 * i]]];
    if (*c < UINT32_MAX) (*c)++;
  }
  for (i = 0; i < m->nl; i++) {
    uint32_t *c = &count[m->lcol[i]];
    if (*c < UINT32_MAX) (*c)++;
  }
  for (i = 0; i < LSYS_MESH_NCOLORS; i++) used += count[i] > 0;
  return used;
}
