/*
** The scene: see scene.h.
*/
#include <math.h>
#include <string.h>

#include "scene.h"

void lsys_scene_camera_defaults (lsys_camera *c) {
  memset(c, 0, sizeof *c);
  c->up[1] = 1;
  c->dir[2] = -1;
  c->projection = LSYS_PARALLEL;
  c->fov = 30;
  c->zoom = 1;
}

void lsys_scene_init (lsys_scene *s) {
  memset(s, 0, sizeof *s);
  lsys_mesh_init(&s->mesh);
  lsys_scene_camera_defaults(&s->cam);
  s->light[0] = 0.4; s->light[1] = 0.8; s->light[2] = 0.6;
  s->background[0] = 0.93f; s->background[1] = 0.96f; s->background[2] = 1.0f;
}

void lsys_scene_free (lsys_scene *s) {
  lsys_mesh_free(&s->mesh);
  LSYS_FREE(s->pal);
  LSYS_FREE(s->rec);
  LSYS_FREE(s->shape);
  LSYS_FREE(s->recpt);
  LSYS_FREE(s->stiff);
  LSYS_FREE(s->parts);
  LSYS_FREE(s->inst);
  lsys_scene_init(s);
}

void lsys_scene_clear (lsys_scene *s) {
  lsys_mesh_clear(&s->mesh);
  s->nrec = s->nshape = s->npt = s->nstiff = s->nparts = s->ninst = 0;
  s->ndirty = 0;
}

int lsys_scene_set_palette (lsys_scene *s, const lsys_material *pal, size_t n) {
  lsys_material *p = NULL;
  if (n > 0) {
    if (n > SIZE_MAX / sizeof *p) return LSYS_ENOMEM;
    if ((p = (lsys_material *)LSYS_MALLOC(n * sizeof *p)) == NULL) return LSYS_ENOMEM;
    memcpy(p, pal, n * sizeof *p);
  }
  LSYS_FREE(s->pal);
  s->pal = p;
  s->npal = s->palcap = n;
  return LSYS_OK;
}

int lsys_scene_add_material (lsys_scene *s, const lsys_material *m, size_t *idx) {
  lsys_material copy = *m;             /* m may point into the palette */
  if (s->npal >= 65536) return LSYS_ELIMIT;
  if (lsys_common_grow((void **)&s->pal, &s->palcap, s->npal + 1, sizeof *s->pal) != LSYS_OK)
    return LSYS_ENOMEM;
  s->pal[s->npal] = copy;
  *idx = s->npal++;
  return LSYS_OK;
}

int lsys_scene_reserve_records (lsys_scene *s, size_t n) {
  if (n > SIZE_MAX - s->nrec) return LSYS_ENOMEM;
  return lsys_common_grow_metered((void **)&s->rec, &s->reccap, s->nrec + n, sizeof *s->rec,
                                  s->meter);
}

int lsys_scene_reserve_shapes (lsys_scene *s, size_t n) {
  if (n > SIZE_MAX - s->nshape) return LSYS_ENOMEM;
  return lsys_common_grow_metered((void **)&s->shape, &s->shapecap, s->nshape + n,
                                  sizeof *s->shape, s->meter);
}

int lsys_scene_reserve_points (lsys_scene *s, size_t n) {
  if (n > SIZE_MAX / 3 - s->npt) return LSYS_ENOMEM;
  return lsys_common_grow_metered((void **)&s->recpt, &s->ptcap, 3 * (s->npt + n),
                                  sizeof *s->recpt, s->meter);
}

void lsys_scene_record (const lsys_scene *s, size_t k, lsys_trec *r) {
  const lsys_rec *q = &s->rec[k];
  const lsys_rshape *h = lsys_scene_recshape(s, k);
  const float *p = NULL;
  int j;
  r->module = q->module;
  r->parent = q->parent;
  r->kind = h->kind;
  r->pad = 0;
  r->color = h->color;
  r->w0 = h->w0; r->w1 = h->w1;
  r->len = h->len;
  r->stiff = h->stiff;
  r->tri0 = h->tri0; r->ntri = h->ntri;
  if (h->line) { if (q->at < s->mesh.nl) p = s->mesh.lpos + 6 * (size_t)q->at + 3; }
  else if (q->at < s->npt) p = s->recpt + 3 * (size_t)q->at;
  for (j = 0; j < 3; j++) {
    r->p1[j] = p != NULL ? p[j] : 0.0f;
    r->H[j] = h->H[j];
    r->U[j] = h->U[j];
  }
}

int lsys_scene_add_record (lsys_scene *s, const lsys_trec *r) {
  lsys_rshape *h;
  lsys_rec *q;
  int st, j;
  if (s->nrec >= LSYS_NOREC || s->nshape >= UINT32_MAX || s->npt >= UINT32_MAX)
    return LSYS_ELIMIT;
  if ((st = lsys_scene_reserve_records(s, 1)) != LSYS_OK ||
      (st = lsys_scene_reserve_shapes(s, 1)) != LSYS_OK ||
      (st = lsys_scene_reserve_points(s, 1)) != LSYS_OK)
    return st;
  h = &s->shape[s->nshape];
  memset(h, 0, sizeof *h);
  h->kind = r->kind;
  h->color = r->color;
  h->w0 = r->w0; h->w1 = r->w1;
  h->len = r->len;
  h->stiff = r->stiff;
  h->tri0 = r->tri0; h->ntri = r->ntri;
  for (j = 0; j < 3; j++) {
    h->H[j] = r->H[j];
    h->U[j] = r->U[j];
    s->recpt[3 * s->npt + j] = r->p1[j];
  }
  q = &s->rec[s->nrec++];
  q->module = r->module;
  q->parent = r->parent;
  q->shape = (uint32_t)s->nshape++;
  q->at = (uint32_t)s->npt++;
  return LSYS_OK;
}

int lsys_scene_append_records (lsys_scene *dst, const lsys_scene *src, size_t ds, size_t dt,
                               size_t dl) {
  size_t r0 = dst->nrec, h0 = dst->nshape, p0 = dst->npt, k;
  int st;
  if (src->nrec == 0) return LSYS_OK;
  if (src->nrec > LSYS_NOREC - 1 - r0 || src->nshape > UINT32_MAX - h0 ||
      src->npt > UINT32_MAX - p0)
    return LSYS_ELIMIT;
  if ((st = lsys_scene_reserve_records(dst, src->nrec)) != LSYS_OK ||
      (st = lsys_scene_reserve_shapes(dst, src->nshape)) != LSYS_OK ||
      (st = lsys_scene_reserve_points(dst, src->npt)) != LSYS_OK)
    return st;
  for (k = 0; k < src->nrec; k++) {
    const lsys_rec *q = &src->rec[k];
    lsys_rec *d = &dst->rec[r0 + k];
    int line = q->shape < src->nshape && src->shape[q->shape].line;
    d->module = q->module;
    d->parent = q->parent == LSYS_NOREC ? LSYS_NOREC : (uint32_t)(q->parent + r0);
    d->shape = (uint32_t)(q->shape + h0);
    d->at = (uint32_t)(q->at + (line ? dl : p0));
  }
  for (k = 0; k < src->nshape; k++) {
    lsys_rshape *h = &dst->shape[h0 + k];
    *h = src->shape[k];
    if (h->stiff != LSYS_NOREC) h->stiff += (uint32_t)ds;
    h->tri0 += (uint32_t)dt;
  }
  if (src->npt > 0) memcpy(dst->recpt + 3 * p0, src->recpt, 3 * src->npt * sizeof *src->recpt);
  dst->nrec += src->nrec;
  dst->nshape += src->nshape;
  dst->npt += src->npt;
  return LSYS_OK;
}

int lsys_scene_detach_records (lsys_scene *s) {
  size_t k, n = 0;
  for (k = 0; k < s->nshape; k++) n += s->shape[k].line;
  if (n == 0) return LSYS_OK;
  for (k = 0, n = 0; k < s->nrec; k++) n += lsys_scene_recshape(s, k)->line;
  if (n > UINT32_MAX - s->npt || lsys_scene_reserve_points(s, n) != LSYS_OK) return LSYS_ENOMEM;
  for (k = 0; k < s->nrec; k++) {
    lsys_rec *q = &s->rec[k];
    float *d;
    int j;
    if (!lsys_scene_recshape(s, k)->line) continue;
    d = s->recpt + 3 * s->npt;
    for (j = 0; j < 3; j++)
      d[j] = q->at < s->mesh.nl ? s->mesh.lpos[6 * (size_t)q->at + 3 + j] : 0.0f;
    q->at = (uint32_t)s->npt++;
  }
  for (k = 0; k < s->nshape; k++) s->shape[k].line = 0;
  return LSYS_OK;
}

int lsys_scene_add_stiffness (lsys_scene *s, const double k[3], uint32_t *idx) {
  int st, j;
  if (s->nstiff >= LSYS_NOREC) return LSYS_ENOMEM;
  st = lsys_common_grow_metered((void **)&s->stiff, &s->stiffcap, 3 * (s->nstiff + 1),
                                sizeof(float), s->meter);
  if (st != LSYS_OK) return st;
  for (j = 0; j < 3; j++) s->stiff[3 * s->nstiff + j] = (float)k[j];
  *idx = (uint32_t)s->nstiff++;
  return LSYS_OK;
}

long lsys_scene_begin_part (lsys_scene *s) {
  lsys_part *p;
  if (lsys_common_grow((void **)&s->parts, &s->partcap, s->nparts + 1, sizeof *s->parts) != LSYS_OK)
    return -1;
  p = &s->parts[s->nparts];
  memset(p, 0, sizeof *p);
  p->v0 = s->mesh.nv; p->t0 = s->mesh.nt; p->l0 = s->mesh.nl; p->r0 = s->nrec;
  return (long)s->nparts++;
}

void lsys_scene_end_part (lsys_scene *s, size_t part) {
  lsys_part *p;
  if (part >= s->nparts) return;
  p = &s->parts[part];
  p->nv = s->mesh.nv - p->v0;
  p->nt = s->mesh.nt - p->t0;
  p->nl = s->mesh.nl - p->l0;
  p->nr = s->nrec - p->r0;
}

int lsys_scene_add_instance (lsys_scene *s, size_t part, const float m[16]) {
  lsys_instance *in;
  if (part >= s->nparts || part > UINT32_MAX) return LSYS_EARG;
  if (lsys_common_grow((void **)&s->inst, &s->instcap, s->ninst + 1, sizeof *s->inst) != LSYS_OK)
    return LSYS_ENOMEM;
  in = &s->inst[s->ninst++];
  in->part = (uint32_t)part;
  memcpy(in->m, m, sizeof in->m);
  return LSYS_OK;
}

void lsys_scene_ranges_add (size_t *r, size_t *n, size_t max, size_t a, size_t b) {
  size_t i = 0, j, k, best = 0;
  if (b <= a) return;
  if (*n > 0 && a >= r[2 * *n - 2]) i = *n - 1;       /* usually at or after the last */
  while (i < *n && r[2 * i + 1] < a) i++;              /* the first that ends at or after a */
  for (j = i; j < *n && r[2 * j] <= b; j++) {}         /* [i, j): overlap or touch [a, b) */
  if (j > i) {                                         /* merge them into range i */
    if (r[2 * i] < a) a = r[2 * i];
    if (r[2 * j - 1] > b) b = r[2 * j - 1];
    memmove(r + 2 * i + 2, r + 2 * j, 2 * (*n - j) * sizeof *r);
    *n -= j - i - 1;
  } else {                                             /* insert before range i */
    memmove(r + 2 * i + 2, r + 2 * i, 2 * (*n - i) * sizeof *r);
    (*n)++;
  }
  r[2 * i] = a;
  r[2 * i + 1] = b;
  if (*n <= max || *n < 2) return;
  for (k = 1; k + 1 < *n; k++)                         /* the smallest gap: after range best */
    if (r[2 * k + 2] - r[2 * k + 1] < r[2 * best + 2] - r[2 * best + 1]) best = k;
  r[2 * best + 1] = r[2 * best + 3];
  memmove(r + 2 * best + 2, r + 2 * best + 4, 2 * (*n - best - 2) * sizeof *r);
  (*n)--;
}

void lsys_scene_touch (lsys_scene *s, size_t v0, size_t nv) {
  lsys_scene_ranges_add(s->dirty, &s->ndirty, LSYS_SCENE_NDIRTY, v0, v0 + nv);
}

int lsys_scene_take_dirty (lsys_scene *s, size_t *v0, size_t *v1) {
  int any = s->ndirty > 0;
  *v0 = any ? s->dirty[0] : 0;
  *v1 = any ? s->dirty[2 * s->ndirty - 1] : 0;
  s->ndirty = 0;
  return any;
}

size_t lsys_scene_take_ranges (lsys_scene *s, size_t *r) {
  size_t n = s->ndirty;
  memcpy(r, s->dirty, 2 * n * sizeof *r);
  s->ndirty = 0;
  return n;
}

long lsys_scene_part_of_record (const lsys_scene *s, size_t r) {
  size_t lo = 0, hi = s->nparts;
  if (r >= s->nrec) return -1;
  if (s->nparts == 0) return 0;     /* no parts: the whole scene is part 0 */
  while (lo < hi) {                 /* parts are in order: the last one with r0 <= r */
    size_t mid = lo + (hi - lo) / 2;
    if (s->parts[mid].r0 <= r) lo = mid + 1; else hi = mid;
  }
  if (lo == 0) return -1;
  lo--;
  return r < s->parts[lo].r0 + s->parts[lo].nr ? (long)lo : -1;
}

/* Adds the 'n' points of 'p' (3 floats each) under 'm' to the bounds. NaN
** coordinates take no part, as in lsys_mesh_bounds. */
static void addxformed (const float m[16], const float *p, size_t n, double lo[3],
                        double hi[3]) {
  size_t i;
  int k;
  for (i = 0; i < n; i++, p += 3) {
    double q[3];
    lsys_xform(m, p, q);
    for (k = 0; k < 3; k++) {
      if (q[k] < lo[k]) lo[k] = q[k];
      if (q[k] > hi[k]) hi[k] = q[k];
    }
  }
}

int lsys_scene_bounds (const lsys_scene *s, double lo[3], double hi[3]) {
  const lsys_mesh *m = &s->mesh;
  size_t i;
  int k, ok = 1;
  if (s->ninst == 0) return lsys_mesh_bounds(m, lo, hi);
  for (k = 0; k < 3; k++) { lo[k] = HUGE_VAL; hi[k] = -HUGE_VAL; }
  for (i = 0; i < s->ninst; i++) {
    const lsys_instance *in = &s->inst[i];
    const lsys_part *p;
    if (in->part >= s->nparts) continue;
    p = &s->parts[in->part];
    /* (an empty mesh's arrays are NULL: no pointer arithmetic on them) */
    if (p->nv > 0) addxformed(in->m, m->pos + 3 * p->v0, p->nv, lo, hi);
    if (p->nl > 0) addxformed(in->m, m->lpos + 6 * p->l0, 2 * p->nl, lo, hi);
  }
  for (k = 0; k < 3; k++)
    if (!(lo[k] <= hi[k])) ok = 0;
  if (!ok)
    for (k = 0; k < 3; k++) lo[k] = hi[k] = 0;
  return ok;
}

size_t lsys_scene_bytes (const lsys_scene *s) {
  const lsys_mesh *m = &s->mesh;
  return m->vcap * (8 * sizeof(float) + 2 * sizeof(uint16_t) + 1) +
         m->tcap * 3 * sizeof(uint32_t) +
         m->lcap * (8 * sizeof(float) + sizeof(uint16_t)) +
         s->palcap * sizeof *s->pal + s->reccap * sizeof *s->rec +
         s->shapecap * sizeof *s->shape + s->ptcap * sizeof *s->recpt +
         s->stiffcap * sizeof *s->stiff + s->partcap * sizeof *s->parts +
         s->instcap * sizeof *s->inst;
}
