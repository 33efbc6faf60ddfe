/*
** The turtle's cylinders (line style "cylinder"): one segment is a ring at
** each end and the band between them. A segment that starts where the last
** one ended, as wide, about as straight and of the same colour, shares that
** segment's top ring, so a stem has no cracks and no inner caps; the ends
** nothing continued are closed with flat caps when the run ends. The rings,
** caps and bands themselves are mesh_tube.c's (mesh.h), which the export of
** lines as tubes shares. See turtle_impl.h.
*/
#include "turtle_impl.h"

/* A ring of sides + 1 vertices (the last repeats the first, for uv) around
** 'c' in the plane of L and U; normals tilted by 'slope' along H (tapers). */
static uint32_t ring (run *R, const double *c, double r, double slope, double v, int col) {
  lsys_tubeframe f = { R->st.H, R->st.L, R->st.U, R->t->ring, R->st.sides, (unsigned)col };
  return lsys_mesh_ring(R->t->mesh, &f, c, r, slope, v);
}

static int cylend (run *R, const double *c, double r, uint32_t rng, double v, int col) {
  lsys_turtle *t = R->t;
  lsys_cylend *e;
  if (t->nends == t->endcap &&
      lsys_common_grow((void **)&t->ends, &t->endcap, t->nends + 1, sizeof *t->ends) != LSYS_OK)
    return lsys_turtle_nomem(R);
  e = &t->ends[t->nends++];
  vcopy(e->c, c);
  vcopy(e->H, R->st.H);
  e->r = r;
  e->ring = rng;
  e->v = (float)v;
  e->color = col;
  e->continued = 0;
  e->sides = R->st.sides;
  return LSYS_OK;
}

/* Width over height of the current texture (1 without one): v along a
** stem grows by length x aspect / circumference (cpfg guide §5.2). */
static double texaspect (run *R) {
  int k = R->st.texture;
  const lsys_texture *tx;
  if (k <= 0 || k > R->o->ntex || (tx = R->o->tex[k - 1]) == NULL || tx->h <= 0) return 1;
  return (double)tx->w / tx->h;
}

int lsys_turtle_cylinder (run *R, const double *p0, const double *p1, double w0, double w1,
                          double len, int col) {
  lsys_turtle *t = R->t;
  lsys_mesh *m = t->mesh;
  int n = R->st.sides;
  double r0 = w0 / 2, r1 = w1 / 2, slope = len > 0 ? (r0 - r1) / len : 0, v0 = 0;
  uint32_t base = LSYS_NOREC, top;
  lsys_cylend *e = R->st.tip != LSYS_NOREC ? &t->ends[R->st.tip] : NULL;
  if (lsys_mesh_reserve(m, 3 * ((size_t)n + 2), 4 * (size_t)n) != LSYS_OK)
    return lsys_turtle_nomem(R);
  if (e != NULL) {
    double d[3];
    vlin(d, e->c, 1, p0, -1);
    if (vdot(d, d) <= 1e-18 * (1 + vdot(p0, p0)) && fabs(e->r - r0) <= 1e-9 * (1 + r0) &&
        vdot(e->H, R->st.H) > 0.866 && e->color == col && e->sides == n) {
      base = e->ring;                    /* share the ring: no crack, no cap */
      e->continued = 1;
      v0 = e->v;
    }
  }
  if (base == LSYS_NOREC) {
    double back[3];
    base = ring(R, p0, r0, slope, 0, col);
    vlin(back, R->st.H, -1, R->st.H, 0);
    lsys_mesh_cap(m, p0, back, base, n, (unsigned)col, 0);
  }
  /* v runs along the stem so that texture pixels keep their aspect (§5.2) */
  v0 += r0 + r1 > 0 ? len * texaspect(R) / (PI * (r0 + r1)) : 0;
  top = ring(R, p1, r1, slope, v0, col);
  lsys_mesh_band(m, base, top, n);
  if (cylend(R, p1, r1, top, v0, col) != LSYS_OK) return LSYS_ENOMEM;
  R->st.tip = (uint32_t)(t->nends - 1);
  return LSYS_OK;
}

int lsys_turtle_capends (run *R) {
  lsys_turtle *t = R->t;
  lsys_mesh *m = t->mesh;
  size_t e;
  for (e = 0; e < t->nends; e++) {
    lsys_cylend *ce = &t->ends[e];
    int n = ce->sides;
    if (ce->continued) continue;
    if (lsys_mesh_reserve(m, (size_t)n + 1, (size_t)n) != LSYS_OK) return lsys_turtle_nomem(R);
    lsys_mesh_cap(m, ce->c, ce->H, ce->ring, n, (unsigned)ce->color, 1);
  }
  return LSYS_OK;
}
