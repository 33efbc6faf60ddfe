/*
** Populations: prototypes appended to a scene as parts, the sizes and the
** flattened copy of a scene with instances, and instance transforms split
** into translation, rotation and scale (population.h).
*/
#include <math.h>
#include <string.h>

#include "population.h"

/* The bytes a vertex, a triangle and a segment take in a mesh's arrays. */
#define VBYTES (8 * sizeof(float) + 2 * sizeof(uint16_t) + 1)
#define TBYTES (3 * sizeof(uint32_t))
#define LBYTES (8 * sizeof(float) + sizeof(uint16_t))

/* ---------------------------------------------------------------------- */
/* prototypes */

/* Where dst's palette holds the n materials of 'pal': the first offset, or
** -1 when it does not. */
static long findpalette (const lsys_scene *dst, const lsys_material *pal, size_t n) {
  size_t o;
  if (n > dst->npal) return -1;
  for (o = 0; o + n <= dst->npal; o++)
    if (memcmp(dst->pal + o, pal, n * sizeof *pal) == 0) return (long)o;
  return -1;
}

/* The offset of src's palette (one grey material when it has none) in
** dst's, appended when it is not there. */
static int mergepalette (lsys_scene *dst, const lsys_scene *src, size_t *off) {
  lsys_material grey;
  const lsys_material *pal = src->pal;
  size_t n = src->npal;
  long at;
  if (pal == NULL || n == 0) {
    lsys_mesh_material_color(&grey, 0.6, 0.6, 0.6);
    pal = &grey;
    n = 1;
  }
  if ((at = findpalette(dst, pal, n)) >= 0) {
    *off = (size_t)at;
    return LSYS_OK;
  }
  if (n > 65536 - dst->npal) return LSYS_ELIMIT;
  if (lsys_common_grow((void **)&dst->pal, &dst->palcap, dst->npal + n,
                       sizeof *dst->pal) != LSYS_OK)
    return LSYS_ENOMEM;
  memcpy(dst->pal + dst->npal, pal, n * sizeof *pal);
  *off = dst->npal;
  dst->npal += n;
  return LSYS_OK;
}

/* Makes room in dst for src's geometry (and records). */
static int reserveall (lsys_scene *dst, const lsys_scene *src, int records) {
  const lsys_mesh *m = &src->mesh;
  int st;
  if ((st = lsys_mesh_reserve(&dst->mesh, m->nv, m->nt)) != LSYS_OK) return st;
  if ((st = lsys_mesh_reserve_lines(&dst->mesh, m->nl)) != LSYS_OK) return st;
  if (!records || src->nrec == 0) return LSYS_OK;
  if (src->nrec > (size_t)UINT32_MAX - 1 - dst->nrec ||
      src->nshape > (size_t)UINT32_MAX - dst->nshape || src->npt > (size_t)UINT32_MAX - dst->npt)
    return LSYS_ELIMIT;
  if ((st = lsys_scene_reserve_records(dst, src->nrec)) != LSYS_OK ||
      (st = lsys_scene_reserve_shapes(dst, src->nshape)) != LSYS_OK ||
      (st = lsys_scene_reserve_points(dst, src->npt)) != LSYS_OK)
    return st;
  if (src->nstiff > 0)
    st = lsys_common_grow_metered((void **)&dst->stiff, &dst->stiffcap,
                                  3 * (dst->nstiff + src->nstiff), sizeof(float), dst->meter);
  return st;
}

/* Appends src's records and stiffnesses, moved to where dst has them (its
** geometry was appended: the records' triangles and lines are the last
** ones). Room was made (reserveall). (An empty array may be NULL: nothing is
** copied from or to one.) */
static int addrecords (lsys_scene *dst, const lsys_scene *src) {
  int st;
  if (src->nrec == 0) return LSYS_OK;
  if ((st = lsys_scene_append_records(dst, src, dst->nstiff, dst->mesh.nt - src->mesh.nt,
                                      dst->mesh.nl - src->mesh.nl)) != LSYS_OK)
    return st;
  if (src->nstiff > 0)
    memcpy(dst->stiff + 3 * dst->nstiff, src->stiff, 3 * src->nstiff * sizeof(float));
  dst->nstiff += src->nstiff;
  return LSYS_OK;
}

/* Appends src's vertices, triangles and segments with their colours moved
** by 'off' (npal: src's palette size) and textures through 'texmap'. */
static void addgeometry (lsys_mesh *d, const lsys_mesh *s, size_t off, size_t npal,
                         const uint16_t *texmap, int ntex) {
  size_t v0 = d->nv, k;
  if (s->nv > 0) {
    memcpy(d->pos + 3 * v0, s->pos, 3 * s->nv * sizeof(float));
    memcpy(d->nrm + 3 * v0, s->nrm, 3 * s->nv * sizeof(float));
    memcpy(d->uv + 2 * v0, s->uv, 2 * s->nv * sizeof(float));
    memcpy(d->twosided + v0, s->twosided, s->nv);
  }
  for (k = 0; k < s->nv; k++) {
    unsigned t = s->tex[k];
    d->col[v0 + k] = (uint16_t)(off + s->col[k] % npal);
    d->tex[v0 + k] = texmap == NULL ? (uint16_t)t : t >= 1 && (int)t <= ntex ? texmap[t] : 0;
  }
  for (k = 0; k < 3 * s->nt; k++) d->tri[3 * d->nt + k] = s->tri[k] + (uint32_t)v0;
  if (s->nl > 0) {
    memcpy(d->lpos + 6 * d->nl, s->lpos, 6 * s->nl * sizeof(float));
    memcpy(d->lwidth + 2 * d->nl, s->lwidth, 2 * s->nl * sizeof(float));
  }
  for (k = 0; k < s->nl; k++) d->lcol[d->nl + k] = (uint16_t)(off + s->lcol[k] % npal);
  d->nv += s->nv;
  d->nt += s->nt;
  d->nl += s->nl;
}

int lsys_population_add (lsys_scene *dst, const lsys_scene *src, const uint16_t *texmap,
                         int records, size_t *part) {
  size_t off, npal = src->pal != NULL && src->npal > 0 ? src->npal : 1;
  long p;
  int st;
  if ((st = reserveall(dst, src, records)) != LSYS_OK) return st;
  if ((st = mergepalette(dst, src, &off)) != LSYS_OK) return st;
  if ((p = lsys_scene_begin_part(dst)) < 0) return LSYS_ENOMEM;
  addgeometry(&dst->mesh, &src->mesh, off, npal, texmap, src->ntex);
  if (records) st = addrecords(dst, src);      /* room was made: it cannot fail */
  lsys_scene_end_part(dst, (size_t)p);
  *part = (size_t)p;
  return st;
}

int lsys_population_reserve (lsys_scene *dst, size_t n, lsys_meter *mt) {
  size_t more;
  lsys_instance *in;
  if (n <= dst->instcap) return LSYS_OK;
  if (n > SIZE_MAX / sizeof *in) return LSYS_ENOMEM;
  more = (n - dst->instcap) * sizeof *in;
  if (!lsys_common_meter_fits(mt, more)) {
    mt->hit = 1;
    return LSYS_EMEMORY;
  }
  if ((in = (lsys_instance *)LSYS_REALLOC(dst->inst, n * sizeof *in)) == NULL) return LSYS_ENOMEM;
  dst->inst = in;
  dst->instcap = n;
  if (mt != NULL) mt->used += more;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* sizes and the flattened copy */

void lsys_population_size (const lsys_scene *s, size_t *nv, size_t *nt, size_t *nl) {
  size_t i, v = 0, t = 0, l = 0;
  if (s->ninst == 0) {
    *nv = s->mesh.nv; *nt = s->mesh.nt; *nl = s->mesh.nl;
    return;
  }
  for (i = 0; i < s->ninst; i++) {
    const lsys_part *p;
    if (s->inst[i].part >= s->nparts) continue;
    p = &s->parts[s->inst[i].part];
    v += p->nv; t += p->nt; l += p->nl;
  }
  *nv = v; *nt = t; *nl = l;
}

size_t lsys_population_flatbytes (const lsys_scene *s) {
  size_t nv, nt, nl;
  double b;
  lsys_population_size(s, &nv, &nt, &nl);
  b = (double)nv * VBYTES + (double)nt * TBYTES + (double)nl * LBYTES;
  return b < (double)SIZE_MAX ? (size_t)b : SIZE_MAX;
}

/* Half the length of (q - p) x (r - p). */
static double triarea (const double p[3], const double q[3], const double r[3]) {
  double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  double v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
  double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                 u[0] * v[1] - u[1] * v[0]};
  return 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* The area of triangles [t0, t0 + nt) of 'm' under 'xf' (NULL: as they are). */
static double areaof (const lsys_mesh *m, size_t t0, size_t nt, const float *xf) {
  double a = 0, p[3][3];
  size_t k;
  int i, c;
  for (k = t0; k < t0 + nt; k++) {
    for (i = 0; i < 3; i++) {
      const float *v = m->pos + 3 * m->tri[3 * k + i];
      if (xf != NULL) lsys_xform(xf, v, p[i]);
      else for (c = 0; c < 3; c++) p[i][c] = v[c];
    }
    a += triarea(p[0], p[1], p[2]);
  }
  return a;
}

double lsys_population_area (const lsys_scene *s) {
  double a = 0;
  size_t i;
  if (s->ninst == 0) return areaof(&s->mesh, 0, s->mesh.nt, NULL);
  for (i = 0; i < s->ninst; i++)
    if (s->inst[i].part < s->nparts) {
      const lsys_part *p = &s->parts[s->inst[i].part];
      a += areaof(&s->mesh, p->t0, p->nt, s->inst[i].m);
    }
  return a;
}

/* The normal matrix of the affine 'm': the cofactors of its 3 x 3 part
** (its inverse transpose times the determinant, whose sign they keep), as
** 9 doubles column-major. Normals come out unnormalised. */
static void normalmatrix (const float m[16], double n[9]) {
  double a[3][3];
  int i, j;
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) a[i][j] = m[4 * j + i];       /* a[row][col] */
  for (i = 0; i < 3; i++)
    for (j = 0; j < 3; j++) {
      int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      n[3 * j + i] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
    }
  if (a[0][0] * n[0] + a[0][1] * n[3] + a[0][2] * n[6] < 0)   /* det < 0: a mirror */
    for (i = 0; i < 9; i++) n[i] = -n[i];
}

/* Writes part p of s under instance 'in' at the ends of d's arrays. */
static void flatpart (lsys_mesh *d, const lsys_scene *s, const lsys_part *p,
                      const lsys_instance *in) {
  const lsys_mesh *m = &s->mesh;
  size_t v0 = d->nv, k;
  double nm[9];
  normalmatrix(in->m, nm);
  for (k = 0; k < p->nv; k++) {
    const float *P = m->pos + 3 * (p->v0 + k), *N = m->nrm + 3 * (p->v0 + k);
    float *Q = d->pos + 3 * (v0 + k), *R = d->nrm + 3 * (v0 + k);
    double q[3], r[3], len;
    int c;
    lsys_xform(in->m, P, q);
    for (c = 0; c < 3; c++) {
      Q[c] = (float)q[c];
      r[c] = nm[c] * N[0] + nm[3 + c] * N[1] + nm[6 + c] * N[2];
    }
    len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (c = 0; c < 3; c++) R[c] = (float)(len > 0 ? r[c] / len : r[c]);
  }
  if (p->nv > 0) {
    memcpy(d->uv + 2 * v0, m->uv + 2 * p->v0, 2 * p->nv * sizeof(float));
    memcpy(d->col + v0, m->col + p->v0, p->nv * sizeof(uint16_t));
    memcpy(d->twosided + v0, m->twosided + p->v0, p->nv);
    memcpy(d->tex + v0, m->tex + p->v0, p->nv * sizeof(uint16_t));
  }
  for (k = 0; k < 3 * p->nt; k++)
    d->tri[3 * d->nt + k] = m->tri[3 * p->t0 + k] - (uint32_t)p->v0 + (uint32_t)v0;
  for (k = 0; k < 2 * p->nl; k++) {
    double q[3];
    int c;
    lsys_xform(in->m, m->lpos + 3 * (2 * p->l0 + k), q);
    for (c = 0; c < 3; c++) d->lpos[3 * (2 * d->nl + k) + c] = (float)q[c];
  }
  if (p->nl > 0) {
    memcpy(d->lwidth + 2 * d->nl, m->lwidth + 2 * p->l0, 2 * p->nl * sizeof(float));
    memcpy(d->lcol + d->nl, m->lcol + p->l0, p->nl * sizeof(uint16_t));
  }
  d->nv += p->nv;
  d->nt += p->nt;
  d->nl += p->nl;
}

int lsys_population_flatten (lsys_scene *dst, const lsys_scene *s, lsys_meter *mt) {
  size_t nv, nt, nl, i;
  int st;
  lsys_population_size(s, &nv, &nt, &nl);
  if (nv > UINT32_MAX || nl > UINT32_MAX) return LSYS_ELIMIT;
  if (!lsys_common_meter_fits(mt, lsys_population_flatbytes(s))) return LSYS_EMEMORY;
  if (s->ninst == 0) {
    if ((st = lsys_mesh_copy(&dst->mesh, &s->mesh)) != LSYS_OK) return st;
  } else {
    if ((st = lsys_mesh_reserve(&dst->mesh, nv, nt)) != LSYS_OK ||
        (st = lsys_mesh_reserve_lines(&dst->mesh, nl)) != LSYS_OK) {
      lsys_scene_free(dst);
      return st;
    }
    for (i = 0; i < s->ninst; i++)
      if (s->inst[i].part < s->nparts)
        flatpart(&dst->mesh, s, &s->parts[s->inst[i].part], &s->inst[i]);
  }
  if (s->npal > 0 && lsys_scene_set_palette(dst, s->pal, s->npal) != LSYS_OK) {
    lsys_scene_free(dst);
    return LSYS_ENOMEM;
  }
  dst->cam = s->cam;
  memcpy(dst->light, s->light, sizeof dst->light);
  memcpy(dst->lights, s->lights, sizeof dst->lights);
  dst->nlights = s->nlights;
  memcpy(dst->background, s->background, sizeof dst->background);
  dst->tex = s->tex;
  dst->ntex = s->ntex;
  dst->cull = s->cull;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* translation, rotation, scale */

/* The unit quaternion (x, y, z, w) of the rotation matrix r (columns r[0],
** r[1], r[2]), by the largest of its four candidates (Shepperd). */
static void quaternion (const double r[3][3], float q[4]) {
  double m00 = r[0][0], m11 = r[1][1], m22 = r[2][2], tr = m00 + m11 + m22, x, y, z, w, n;
  if (tr > 0) {
    double k = 2 * sqrt(tr + 1);
    w = k / 4; x = (r[1][2] - r[2][1]) / k; y = (r[2][0] - r[0][2]) / k;
    z = (r[0][1] - r[1][0]) / k;
  } else if (m00 > m11 && m00 > m22) {
    double k = 2 * sqrt(1 + m00 - m11 - m22);
    x = k / 4; w = (r[1][2] - r[2][1]) / k; y = (r[1][0] + r[0][1]) / k;
    z = (r[2][0] + r[0][2]) / k;
  } else if (m11 > m22) {
    double k = 2 * sqrt(1 + m11 - m00 - m22);
    y = k / 4; w = (r[2][0] - r[0][2]) / k; x = (r[1][0] + r[0][1]) / k;
    z = (r[2][1] + r[1][2]) / k;
  } else {
    double k = 2 * sqrt(1 + m22 - m00 - m11);
    z = k / 4; w = (r[0][1] - r[1][0]) / k; x = (r[2][0] + r[0][2]) / k;
    y = (r[2][1] + r[1][2]) / k;
  }
  n = sqrt(x * x + y * y + z * z + w * w);
  if (w < 0) n = -n;                       /* the same rotation, with w >= 0 */
  q[0] = (float)(x / n); q[1] = (float)(y / n); q[2] = (float)(z / n); q[3] = (float)(w / n);
}

int lsys_population_trs (const float m[16], float t[3], float q[4], float s[3]) {
  double r[3][3], det;           /* r[j]: column j, normalised */
  int i, j;
  if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) return 0;
  for (j = 0; j < 3; j++) {
    double len = sqrt((double)m[4 * j] * m[4 * j] + (double)m[4 * j + 1] * m[4 * j + 1] +
                      (double)m[4 * j + 2] * m[4 * j + 2]);
    if (!(len > 0 && isfinite(len)) || !isfinite(m[12 + j])) return 0;
    for (i = 0; i < 3; i++) r[j][i] = m[4 * j + i] / len;
    s[j] = (float)len;
    t[j] = m[12 + j];
  }
  for (i = 0; i < 3; i++)
    for (j = i + 1; j < 3; j++)
      if (fabs(r[i][0] * r[j][0] + r[i][1] * r[j][1] + r[i][2] * r[j][2]) > 1e-4) return 0;
  det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
        r[1][0] * (r[0][1] * r[2][2] - r[0][2] * r[2][1]) +
        r[2][0] * (r[0][1] * r[1][2] - r[0][2] * r[1][1]);
  if (!(det > 0)) return 0;                /* a mirror: no positive scales make it */
  quaternion(r, q);
  return 1;
}
