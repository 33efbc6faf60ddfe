/*
** The turtle's polygons (cpfg guide §4.2): { starts one, '.', F and f inside
** it add the turtle's position as a vertex (F draws no segment there), }
** fills it. Polygons nest (a stack: a { inside one starts another); a stray
** } is ignored, as cpfg does. Filled by ear clipping (polygon.h), uv from
** the turtle's frame at the first vertex (§5.3). See turtle_impl.h.
*/
#include <string.h>

#include "turtle_impl.h"
#include "polygon.h"

/* The triangulation's scratch, growing within this interpretation's budget. */
struct lsys_polywork *lsys_turtle_polywork (lsys_turtle *t) {
  if (t->pw == NULL) {
    t->pw = (struct lsys_polywork *)LSYS_MALLOC(sizeof *t->pw);
    if (t->pw == NULL) return NULL;
    memset(t->pw, 0, sizeof *t->pw);
  }
  t->pw->meter = t->meter;
  return t->pw;
}

int lsys_turtle_polyvertex (run *R) {
  lsys_turtle *t = R->t;
  lsys_polygon *p;
  if (t->npolys == 0 || !R->draw) return LSYS_OK;
  p = &t->polys[t->npolys - 1];
  if (p->n >= LSYS_POLYGON_MAXV)
    return lsys_turtle_fail(R, LSYS_ELIMIT, "a polygon of more than %u vertices (lsys's limit)",
                            (unsigned)LSYS_POLYGON_MAXV);
  if (lsys_common_grow_metered((void **)&p->v, &p->cap, 3 * (p->n + 1), sizeof(double), t->meter) !=
      LSYS_OK)
    return lsys_turtle_nomem(R);
  if (p->n == 0) { vcopy(p->H, R->st.H); vcopy(p->L, R->st.L); }
  vcopy(p->v + 3 * p->n++, R->st.pos);
  return LSYS_OK;
}

int lsys_turtle_polystart (run *R) {
  lsys_turtle *t = R->t;
  if (t->npolys == 0) t->polyfrom = R->mod;
  if (!R->draw) { t->npolys++; return LSYS_OK; }
  if (t->npolys == t->polycap) {
    size_t old = t->polycap;
    if (lsys_common_grow((void **)&t->polys, &t->polycap, t->npolys + 1,
                         sizeof *t->polys) != LSYS_OK)
      return lsys_turtle_nomem(R);
    memset(t->polys + old, 0, (t->polycap - old) * sizeof *t->polys);
  }
  t->polys[t->npolys++].n = 0;
  return LSYS_OK;
}

/* The vertices of 'p', facing 'nrm', with uv the coordinates along the
** right (-L) and heading axes from the first vertex, scaled to 0..1 over
** the polygon (cpfg guide §5.3). */
static void polyvertices (run *R, const lsys_polygon *p, const double *nrm) {
  double lo[2] = {0, 0}, hi[2] = {0, 0}, d[3], c[2];
  size_t k;
  for (k = 0; k < p->n; k++) {
    vlin(d, p->v + 3 * k, 1, p->v, -1);
    c[0] = -vdot(d, p->L); c[1] = vdot(d, p->H);
    if (c[0] < lo[0]) lo[0] = c[0];
    if (c[0] > hi[0]) hi[0] = c[0];
    if (c[1] < lo[1]) lo[1] = c[1];
    if (c[1] > hi[1]) hi[1] = c[1];
  }
  for (k = 0; k < p->n; k++) {
    const double *v = p->v + 3 * k;
    vlin(d, v, 1, p->v, -1);
    c[0] = -vdot(d, p->L); c[1] = vdot(d, p->H);
    lsys_mesh_vertex(R->t->mesh, v, nrm, hi[0] > lo[0] ? (c[0] - lo[0]) / (hi[0] - lo[0]) : 0,
                     hi[1] > lo[1] ? (c[1] - lo[1]) / (hi[1] - lo[1]) : 0,
                     (unsigned)R->st.color, 1);
  }
}

int lsys_turtle_polyend (run *R) {
  lsys_turtle *t = R->t;
  lsys_polygon *p;
  const uint32_t *tri;
  double nrm[3];
  long nt, k;
  uint32_t first;
  if (t->npolys == 0) return LSYS_OK;        /* a stray '}' is ignored, as cpfg does */
  t->npolys--;
  if (!R->draw) return LSYS_OK;
  p = &t->polys[t->npolys];
  if (p->n < 3) return LSYS_OK;
  if (lsys_turtle_polywork(t) == NULL) return lsys_turtle_nomem(R);
  nt = lsys_polygon_triangulate(t->pw, p->v, p->n, nrm, &tri);
  if (nt == LSYS_ELIMIT)
    return lsys_turtle_fail(R, LSYS_ELIMIT, "the polygon of %zu vertices is too intricate to "
                            "fill (its ear tests would look at more than %u n log2 n points)",
                            p->n, (unsigned)LSYS_POLYGON_MAXWORK);
  if (nt < 0) return lsys_turtle_nomem(R);
  if (lsys_mesh_reserve(t->mesh, p->n, (size_t)nt) != LSYS_OK) return lsys_turtle_nomem(R);
  first = (uint32_t)t->mesh->nv;
  t->mesh->curtex = (unsigned)R->st.texture;
  polyvertices(R, p, nrm);
  for (k = 0; k < nt; k++)
    lsys_mesh_tri(t->mesh, first + tri[3 * k], first + tri[3 * k + 1], first + tri[3 * k + 2]);
  return newrec(R, LSYS_REC_POLYGON, p->v + 3 * (p->n - 1), p->v + 3 * (p->n - 1), 0, 0);
}
