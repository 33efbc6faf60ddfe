/*
** The turtle's ribbons (line style "polygon"): a segment is a flat
** two-sided quadrilateral in the plane of H and L, as wide as the line,
** facing U. See turtle_impl.h.
*/
#include "turtle_impl.h"

int lsys_turtle_ribbon (run *R, const double *p0, const double *p1, double w0, double w1,
                        int col) {
  lsys_mesh *m = R->t->mesh;
  double a[3], b[3], c[3], d[3];
  uint32_t i;
  if (lsys_mesh_reserve(m, 4, 2) != LSYS_OK) return lsys_turtle_nomem(R);
  vlin(a, p0, 1, R->st.L, w0 / 2);
  vlin(b, p0, 1, R->st.L, -w0 / 2);
  vlin(c, p1, 1, R->st.L, -w1 / 2);
  vlin(d, p1, 1, R->st.L, w1 / 2);
  i = lsys_mesh_vertex(m, a, R->st.U, 0, 0, (unsigned)col, 1);
  lsys_mesh_vertex(m, b, R->st.U, 1, 0, (unsigned)col, 1);
  lsys_mesh_vertex(m, c, R->st.U, 1, 1, (unsigned)col, 1);
  lsys_mesh_vertex(m, d, R->st.U, 0, 1, (unsigned)col, 1);
  lsys_mesh_tri(m, i, i + 2, i + 1);      /* facing U */
  lsys_mesh_tri(m, i, i + 3, i + 2);
  return LSYS_OK;
}
