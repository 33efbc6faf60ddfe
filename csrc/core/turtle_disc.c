/*
** The turtle's discs (cpfg guide §2): @c draws one in the plane of the
** turtle's L and U, facing H; @o one in the world's xy plane, facing +z.
** A two-sided fan of 'sides' triangles around the centre, uv the unit
** square. See turtle_impl.h.
*/
#include "turtle_impl.h"

int lsys_turtle_disc (run *R, const double *c, const double *a, const double *b,
                      const double *nrm, double d, int col) {
  lsys_mesh *m = R->t->mesh;
  const double *cs = R->t->ring;
  int n = R->st.sides, k;
  uint32_t first;
  double ab[3];
  if (lsys_mesh_reserve(m, (size_t)n + 1, (size_t)n) != LSYS_OK) return lsys_turtle_nomem(R);
  first = lsys_mesh_vertex(m, c, nrm, 0.5, 0.5, (unsigned)col, 1);
  for (k = 0; k < n; k++) {
    double p[3];
    vlin(p, a, cs[2 * k] * d / 2, b, cs[2 * k + 1] * d / 2);
    vlin(p, p, 1, c, 1);
    lsys_mesh_vertex(m, p, nrm, 0.5 + cs[2 * k] / 2, 0.5 + cs[2 * k + 1] / 2, (unsigned)col, 1);
  }
  vcross(ab, a, b);
  for (k = 0; k < n; k++) {               /* wound to face 'nrm' */
    uint32_t u = first + 1 + (uint32_t)k, v = first + 1 + (uint32_t)((k + 1) % n);
    if (vdot(ab, nrm) >= 0) lsys_mesh_tri(m, first, u, v);
    else lsys_mesh_tri(m, first, v, u);
  }
  return LSYS_OK;
}
