/*
** The turtle's cylinders (line style "cylinder"): one segment is a ring at
** each end and the band between them. A segment that starts where the last
** one ended, as wide, about as straight and of the same colour, shares that
** segment's top ring, so a stem has no cracks and no inner caps; the ends
** nothing continued are closed with flat caps when the run ends. The rings,
** caps and bands themselves are mesh_tube.c's (mesh.h), which the export of
** lines as tubes shares. See turtle_impl.h.
**
** A roll or a twist between two segments turns the turtle's ring about the
** heading. cpfg draws each segment as a cylinder of its own in the turtle's
** frame, so the turn shows only in the facets; a band joining the shared
** ring vertex k to the new ring's vertex k would twist by the whole turn and
** pinch the stem (to nothing at half a turn). So the new ring starts at the
** turtle's ring vertex nearest the old ring's first one (lsys_mesh_ringmatch):
** its vertices are the turtle's own, where cpfg puts them, and the band
** twists by at most half a side, split along its shorter diagonals. The
** texture runs on without a seam; when the view asks for the turtle's twist
** (minimize_twist = false, cpfg's "twist of cylinders: on") u follows the
** turtle instead, as cpfg's cylinders take it, turning within the band.
*/
#include "turtle_impl.h"

/* A ring of sides + 1 vertices (the last repeats the first, for uv) around
** 'c' in the plane of L and U, u from u0; normals tilted by 'slope' along H
** (tapers). */
static uint32_t ring (run *R, const double *c, const double *L, const double *U, double u0,
                      double r, double slope, double v, int col) {
  lsys_tubeframe f = { R->st.H, L, U, R->t->ring, R->st.sides, (unsigned)col, u0 };
  return lsys_mesh_ring(R->t->mesh, &f, c, r, slope, v);
}

static int cylend (run *R, const double *c, const double *L, double r, uint32_t rng,
                   double u0, double v, int col) {
  lsys_turtle *t = R->t;
  lsys_cylend *e;
  if (t->nends == t->endcap &&
      lsys_common_grow((void **)&t->ends, &t->endcap, t->nends + 1, sizeof *t->ends) != LSYS_OK)
    return lsys_turtle_nomem(R);
  e = &t->ends[t->nends++];
  vcopy(e->c, c);
  vcopy(e->H, R->st.H);
  vcopy(e->L, L);
  e->r = r;
  e->ring = rng;
  e->u0 = u0;
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
  double L[3], U[3], u0 = 0, twist = 0;
  uint32_t base = LSYS_NOREC, top;
  lsys_cylend *e = R->st.tip != LSYS_NOREC ? &t->ends[R->st.tip] : NULL;
  if (lsys_mesh_reserve(m, 3 * ((size_t)n + 2), 4 * (size_t)n) != LSYS_OK)
    return lsys_turtle_nomem(R);
  if (e != NULL) {
    double d[3];
    vlin(d, e->c, 1, p0, -1);
    if (vdot(d, d) <= 1e-18 * (1 + vdot(p0, p0)) && fabs(e->r - r0) <= 1e-9 * (1 + r0) &&
        vdot(e->H, R->st.H) > 0.866 && e->color == col && e->sides == n) {
      int k;
      base = e->ring;                    /* share the ring: no crack, no cap */
      e->continued = 1;
      v0 = e->v;
      twist = lsys_mesh_ringmatch(L, U, &k, e->H, e->L, R->st.H, R->st.L, R->st.U,
                                  t->ring, n);
      u0 = e->u0;
      if (!R->o->minimize_twist) {       /* u of the turtle's vertex k, the nearest turn */
        double du = (double)k / n - u0;
        u0 += du - floor(du + 0.5);
      }
    }
  }
  if (base == LSYS_NOREC) {
    double back[3];
    vcopy(L, R->st.L);
    vcopy(U, R->st.U);
    base = ring(R, p0, L, U, 0, r0, slope, 0, col);
    vlin(back, R->st.H, -1, R->st.H, 0);
    lsys_mesh_cap(m, p0, back, base, n, (unsigned)col, 0);
  }
  /* v runs along the stem so that texture pixels keep their aspect (§5.2) */
  v0 += r0 + r1 > 0 ? len * texaspect(R) / (PI * (r0 + r1)) : 0;
  top = ring(R, p1, L, U, u0, r1, slope, v0, col);
  lsys_mesh_band(m, base, top, n, twist);
  if (cylend(R, p1, L, r1, top, u0, v0, col) != LSYS_OK) return LSYS_ENOMEM;
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
