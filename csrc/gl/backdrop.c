/*
** The sky behind a scene (render.h): a quad over the viewport in clip
** coordinates, its top edge one colour and its bottom edge the other, which
** smooth shading blends row by row. It is drawn right after the clear, with
** neither lighting nor depth, so the scene covers it; and the per-vertex
** shading factors of baked shadows (lsys_render_shade).
*/
#include <GL/gl.h>

#include "render.h"

void lsys_render_backdrop (const lsys_gl *gl, const lsys_render_opts *o, const double proj[16],
                           const double view[16]) {
  static const float quad[12] = {-1, -1, 0.999f, 1, -1, 0.999f, 1, 1, 0.999f, -1, 1, 0.999f};
  static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
  uint8_t rgba[16];
  int k, c;
  for (k = 0; k < 4; k++)
    for (c = 0; c < 4; c++) {
      float x = c == 3 ? 1 : k < 2 ? o->sky_bottom[c] : o->sky_top[c];
      rgba[4 * k + c] = (uint8_t)(x <= 0 ? 0 : x >= 1 ? 255 : x * 255 + 0.5f);
    }
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadIdentity();
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadIdentity();
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_DEPTH_TEST);
  gl->DepthMask(GL_FALSE);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(3, GL_FLOAT, 0, quad);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, rgba);
  gl->DrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, idx);
  gl->DisableClientState(GL_COLOR_ARRAY);
  gl->DepthMask(GL_TRUE);
  gl->Enable(GL_DEPTH_TEST);
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(proj);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadMatrixd(view);
}

void lsys_render_shade (uint8_t *rgba, const uint8_t *f, size_t n) {
  size_t v;
  int c;
  for (v = 0; v < n; v++)
    for (c = 0; c < 3; c++) rgba[4 * v + c] = (uint8_t)((rgba[4 * v + c] * f[v] + 127) / 255);
}
