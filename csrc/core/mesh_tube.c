/*
** Tubes (mesh.h): the rings, caps and bands of the turtle's cylinders
** (turtle_cyl.c), and the same tubes made from line segments for the export
** writers (export.c, lines = tubes).
*/
#include <float.h>
#include <math.h>
#include <string.h>

#include "mesh.h"
#include "vec3.h"

void lsys_mesh_ringtable (double *cs, int n) {
  int k;
  for (k = 0; k <= n; k++) {
    double a = 2 * PI * k / n;
    cs[2 * k] = k == n ? 1 : cos(a);
    cs[2 * k + 1] = k == n ? 0 : sin(a);
  }
}

uint32_t lsys_mesh_ring (lsys_mesh *m, const lsys_tubeframe *f, const double c[3], double r,
                         double slope, double v) {
  int n = f->n, k;
  uint32_t first = (uint32_t)m->nv;
  for (k = 0; k <= n; k++) {
    double d[3], p[3], nn[3];
    vlin(d, f->L, f->cs[2 * k], f->U, f->cs[2 * k + 1]);
    vlin(p, c, 1, d, r);
    vlin(nn, d, 1, f->H, slope);
    if (slope != 0) vnorm(nn);
    lsys_mesh_vertex(m, p, nn, f->u0 + (double)k / n, v, f->col, 0);
  }
  return first;
}

void lsys_mesh_cap (lsys_mesh *m, const double c[3], const double nn[3], uint32_t ring, int n,
                    unsigned col, int flip) {
  uint32_t first = (uint32_t)m->nv, k;
  lsys_mesh_vertex(m, c, nn, 0.5, 0.5, col, 0);
  for (k = 0; k < (uint32_t)n; k++) {
    double p[3] = {m->pos[3 * (ring + k)], m->pos[3 * (ring + k) + 1],
                   m->pos[3 * (ring + k) + 2]};
    lsys_mesh_vertex(m, p, nn, m->uv[2 * (ring + k)], 0.5, col, 0);
  }
  for (k = 0; k < (uint32_t)n; k++) {
    uint32_t a = first + 1 + k, b = first + 1 + (k + 1) % n;
    if (flip) lsys_mesh_tri(m, first, b, a);
    else lsys_mesh_tri(m, first, a, b);
  }
}

/* A twist below this (radians) counts as none: the two diagonals of an
** untwisted band are as long, and rounding must not pick between them. */
#define NOTWIST 1e-9

void lsys_mesh_band (lsys_mesh *m, uint32_t base, uint32_t top, int n, double twist) {
  uint32_t k;
  if (twist > NOTWIST) {        /* top k sits ahead of base k: base k + 1 to top k is shorter */
    for (k = 0; k < (uint32_t)n; k++) {
      lsys_mesh_tri(m, base + k, top + k, base + k + 1);
      lsys_mesh_tri(m, base + k + 1, top + k, top + k + 1);
    }
    return;
  }
  for (k = 0; k < (uint32_t)n; k++) {     /* outward facing */
    lsys_mesh_tri(m, base + k, top + k + 1, base + k + 1);
    lsys_mesh_tri(m, base + k, top + k, top + k + 1);
  }
}

void lsys_mesh_transport (double out[3], const double v[3], const double a[3],
                          const double b[3]) {
  double s[3], c = vdot(a, b), av = vdot(a, v), sv;
  vlin(s, a, 1, b, 1);
  sv = vdot(s, v) / (1 + c);
  out[0] = v[0] + 2 * av * b[0] - sv * s[0];
  out[1] = v[1] + 2 * av * b[1] - sv * s[1];
  out[2] = v[2] + 2 * av * b[2] - sv * s[2];
}

/* The ring's own angle of the old first vertex is phi; the nearest whole
** side k * 2 pi / n is where the new first vertex goes, so the band between
** them turns by k * 2 pi / n - phi, at most half a side either way. */
double lsys_mesh_ringmatch (double L2[3], double U2[3], int *steps, const double pH[3],
                            const double pL[3], const double H[3], const double L[3],
                            const double U[3], const double *cs, int n) {
  double t[3], phi, side = 2 * PI / n, k, c, s;
  int j;
  lsys_mesh_transport(t, pL, pH, H);
  phi = atan2(vdot(t, U), vdot(t, L));
  k = floor(phi / side + 0.5);
  j = (int)k % n;
  if (j < 0) j += n;
  c = cs[2 * j];
  s = cs[2 * j + 1];
  vlin(L2, L, c, U, s);
  vlin(U2, U, c, L, -s);
  *steps = j;
  return k * side - phi;
}

/* ------------------------------------------------------------------ */
/* Line segments as tubes                                               */
/* ------------------------------------------------------------------ */

/* A segment as a tube sees it. */
typedef struct seg {
  double p0[3], p1[3], H[3];   /* ends, unit direction */
  double len, r0, r1;          /* length, radii at the ends */
  unsigned col;
} seg;

/* The radius of a line of width 'w' (see lsys_mesh_tubes). */
static double radius (float w, double unit) {
  double x = w >= 1 ? (w < 16384 ? w : 16384) : 1;
  return 0.5 * x * unit;
}

/* Segment i of 'm' into *s; 0 when it is left out. */
static int readseg (const lsys_mesh *m, size_t i, double unit, seg *s) {
  const float *q = m->lpos + 6 * i;
  int k;
  for (k = 0; k < 3; k++) {
    s->p0[k] = q[k];
    s->p1[k] = q[3 + k];
    if (!isfinite(q[k]) || !isfinite(q[3 + k])) return 0;
  }
  vlin(s->H, s->p1, 1, s->p0, -1);
  s->len = vlen(s->H);
  if (!(s->len > 0) || !vnorm(s->H)) return 0;
  s->r0 = radius(m->lwidth[2 * i], unit);
  s->r1 = radius(m->lwidth[2 * i + 1], unit);
  s->col = m->lcol[i];
  return 1;
}

/* Whether 'b' continues 'a' (the turtle's test, turtle_cyl.c). */
static int joins (const seg *a, const seg *b) {
  double d[3];
  vlin(d, a->p1, 1, b->p0, -1);
  return vdot(d, d) <= 1e-18 * (1 + vdot(b->p0, b->p0)) &&
         fabs(a->r1 - b->r0) <= 1e-9 * (1 + b->r0) && vdot(a->H, b->H) > 0.866 &&
         a->col == b->col;
}

/* The vertices and triangles the tubes of 'm' add (lsys_mesh_tubes): a
** tube that starts a run has two rings and two caps, one that continues a
** run its top ring and its top cap, and takes the cap of the one before. */
static void counttubes (const lsys_mesh *m, int n, double unit, uint64_t *nv, uint64_t *nt) {
  seg s[2];
  int open = 0;
  size_t i;
  *nv = *nt = 0;
  for (i = 0; i < m->nl; i++) {
    seg *cur = &s[i & 1], *prev = &s[(i + 1) & 1];
    if (!readseg(m, i, unit, cur)) { open = 0; continue; }
    if (open && joins(prev, cur)) {
      *nv += (uint64_t)n + 1;
      *nt += 2 * (uint64_t)n;
    }
    else {
      *nv += 4 * ((uint64_t)n + 1);
      *nt += 4 * (uint64_t)n;
    }
    open = 1;
  }
}

/* A unit vector normal to the unit vector H: the axis least along H, made
** normal to it. */
static void normalto (double U[3], const double H[3]) {
  double e[3] = {0, 0, 0};
  int k = fabs(H[0]) <= fabs(H[1]) ? (fabs(H[0]) <= fabs(H[2]) ? 0 : 2)
                                   : (fabs(H[1]) <= fabs(H[2]) ? 1 : 2);
  e[k] = 1;
  vlin(U, e, 1, H, -H[k]);
  vnorm(U);
}

/* The open end of the last tube: its top ring, to share or to cap. */
typedef struct tubeend {
  double c[3], H[3], U[3];
  uint32_t ring;
  unsigned col;
  int open;
} tubeend;

static void capend (lsys_mesh *d, tubeend *e, int n) {
  if (e->open) lsys_mesh_cap(d, e->c, e->H, e->ring, n, e->col, 1);
  e->open = 0;
}

/*
** One tube for segment 'cur' ('prev' the segment before it, when e->open).
** A continuing tube carries the frame of the one before over the bend
** (parallel transport, lsys_mesh_transport), so that its rings line up with
** the shared one and the band between them does not twist;
** a new run takes a frame of its own.
*/
static void addtube (lsys_mesh *d, const seg *cur, const seg *prev, tubeend *e,
                     const double *cs, int n) {
  double U[3], L[3], back[3], slope = (cur->r0 - cur->r1) / cur->len, v0 = 0;
  lsys_tubeframe f = { cur->H, L, U, cs, n, cur->col, 0 };
  uint32_t base = 0;
  int shared = e->open && joins(prev, cur);
  if (shared) {                 /* the frame carried over the bend: no twist */
    lsys_mesh_transport(U, e->U, e->H, cur->H);
    vlin(U, U, 1, cur->H, -vdot(U, cur->H));
    if (!vnorm(U)) normalto(U, cur->H);
    base = e->ring;
    v0 = d->uv[2 * base + 1];
  }
  else {
    capend(d, e, n);
    normalto(U, cur->H);
  }
  vcross(L, cur->H, U);
  if (!shared) {
    base = lsys_mesh_ring(d, &f, cur->p0, cur->r0, slope, 0);
    vlin(back, cur->H, -1, cur->H, 0);
    lsys_mesh_cap(d, cur->p0, back, base, n, cur->col, 0);
  }
  e->ring = lsys_mesh_ring(d, &f, cur->p1, cur->r1, slope,
                           v0 + (cur->r0 + cur->r1 > 0 ? cur->len / (PI * (cur->r0 + cur->r1))
                                                       : 0));
  lsys_mesh_band(d, base, e->ring, n, 0);
  vcopy(e->c, cur->p1);
  vcopy(e->H, cur->H);
  vcopy(e->U, U);
  e->col = cur->col;
  e->open = 1;
}

/* The vertices and triangles of 'src' into 'dst', which has room. */
static void copymesh (lsys_mesh *d, const lsys_mesh *s) {
  if (s->nv > 0) {
    memcpy(d->pos, s->pos, 3 * s->nv * sizeof(float));
    memcpy(d->nrm, s->nrm, 3 * s->nv * sizeof(float));
    memcpy(d->uv, s->uv, 2 * s->nv * sizeof(float));
    memcpy(d->col, s->col, s->nv * sizeof(uint16_t));
    memcpy(d->twosided, s->twosided, s->nv);
    memcpy(d->tex, s->tex, s->nv * sizeof(uint16_t));
  }
  if (s->nt > 0) memcpy(d->tri, s->tri, 3 * s->nt * sizeof(uint32_t));
  d->nv = s->nv;
  d->nt = s->nt;
}

int lsys_mesh_tubes (lsys_mesh *dst, const lsys_mesh *src, int n, double unit) {
  double *cs;
  uint64_t nv, nt;
  seg s[2];
  tubeend e = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0, 0, 0};
  size_t i;
  int st;
  lsys_mesh_init(dst);
  if (n < 3 || n > 1024 || !(unit > 0 && unit <= DBL_MAX)) return LSYS_EARG;
  counttubes(src, n, unit, &nv, &nt);
  if (nv > (uint64_t)UINT32_MAX - src->nv || nt > (uint64_t)UINT32_MAX - src->nt)
    return LSYS_ELIMIT;
  cs = (double *)LSYS_MALLOC((2 * (size_t)n + 2) * sizeof *cs);
  if (cs == NULL) return LSYS_ENOMEM;
  if ((st = lsys_mesh_reserve(dst, src->nv + (size_t)nv, src->nt + (size_t)nt)) != LSYS_OK) {
    LSYS_FREE(cs);
    lsys_mesh_free(dst);
    return st;
  }
  lsys_mesh_ringtable(cs, n);
  copymesh(dst, src);
  for (i = 0; i < src->nl; i++) {
    seg *cur = &s[i & 1], *prev = &s[(i + 1) & 1];
    if (readseg(src, i, unit, cur)) addtube(dst, cur, prev, &e, cs, n);
    else capend(dst, &e, n);
  }
  capend(dst, &e, n);
  LSYS_FREE(cs);
  return LSYS_OK;
}
