/*
** The turtle's spheres (cpfg guide §2, @O): a uv sphere of 'sides' meridians
** and sides/2 + 1 parallels (at least 3), its poles on the turtle's H axis;
** one-sided, as it is closed. See turtle_impl.h.
*/
#include "turtle_impl.h"

int lsys_turtle_sphere (run *R, const double *c, double d, int col) {
  lsys_mesh *m = R->t->mesh;
  const double *cs = R->t->ring;
  int n = R->st.sides, rows = n / 2 < 2 ? 2 : n / 2, i, k;
  uint32_t first;
  if (lsys_mesh_reserve(m, (size_t)(rows + 1) * (n + 1), 2 * (size_t)rows * n) != LSYS_OK)
    return lsys_turtle_nomem(R);
  first = (uint32_t)m->nv;
  for (i = 0; i <= rows; i++) {
    double th = PI * i / rows, ch = cos(th), sh = sin(th);
    for (k = 0; k <= n; k++) {
      double nn[3], p[3];
      vlin(nn, R->st.L, cs[2 * k] * sh, R->st.U, cs[2 * k + 1] * sh);
      vlin(nn, nn, 1, R->st.H, -ch);
      vlin(p, c, 1, nn, d / 2);
      lsys_mesh_vertex(m, p, nn, (double)k / n, (double)i / rows, (unsigned)col, 0);
    }
  }
  for (i = 0; i < rows; i++)
    for (k = 0; k < n; k++) {
      uint32_t a = first + (uint32_t)(i * (n + 1) + k), b = a + (uint32_t)n + 1;
      if (i > 0) lsys_mesh_tri(m, a, b + 1, a + 1);
      if (i < rows - 1) lsys_mesh_tri(m, a, b, b + 1);
    }
  return LSYS_OK;
}
