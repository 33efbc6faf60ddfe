/*
** The sky behind a scene (render.h): a quad over the viewport in clip
** coordinates, its top edge one colour and its bottom edge the other, which
** smooth shading blends row by row. It is drawn right after the clear, with
** neither lighting nor depth, so the scene covers it; and the per-vertex
** shading factors of baked shadows (lsys_render_shade).
*/
#include <math.h>
#include <string.h>

#include <GL/gl.h>

#include "render.h"

const float lsys_render_sky_top[3] = {0.55f, 0.72f, 0.92f};
const float lsys_render_sky_bottom[3] = {0.93f, 0.95f, 0.97f};
const float lsys_render_ground[3] = {0.72f, 0.76f, 0.68f};

int lsys_render_solid (const double lo[3], const double hi[3]) {
  double d[3], big = 0;
  int i;
  for (i = 0; i < 3; i++) {
    d[i] = hi[i] - lo[i];
    if (!(d[i] >= 0) || !isfinite(d[i])) return 0;
    if (d[i] > big) big = d[i];
  }
  return big > 0 && d[0] >= big / 20 && d[1] >= big / 20 && d[2] >= big / 20;
}

void lsys_render_setfloor (lsys_render_opts *o, const double lo[3], const double hi[3]) {
  double ext = fmax(fmax(hi[0] - lo[0], hi[2] - lo[2]), (hi[1] - lo[1]) / 2), diag = 0, half;
  int i;
  for (i = 0; i < 3; i++) diag += (hi[i] - lo[i]) * (hi[i] - lo[i]);
  if (!(ext > 0)) ext = 1;
  half = 1.6 * ext / 2;
  o->floor = 1;
  o->floor_rect[0] = lo[1] - 1e-3 * sqrt(diag);
  o->floor_rect[1] = (lo[0] + hi[0]) / 2 - half;
  o->floor_rect[2] = (lo[2] + hi[2]) / 2 - half;
  o->floor_rect[3] = (lo[0] + hi[0]) / 2 + half;
  o->floor_rect[4] = (lo[2] + hi[2]) / 2 + half;
  for (i = 0; i < 3; i++) o->floor_rgb[i] = lsys_render_ground[i];
}

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

void lsys_render_backdrops (lsys_render_opts *o, lsys_camera *cam, int sky, int ground) {
  const double *b = cam->bounds;
  double lo[3] = {b[0], b[1], b[2]}, hi[3] = {b[3], b[4], b[5]};
  int k;
  if (!cam->has_bounds || !lsys_render_solid(lo, hi)) return;
  if (sky) {
    o->sky = 1;
    memcpy(o->sky_top, lsys_render_sky_top, sizeof o->sky_top);
    memcpy(o->sky_bottom, lsys_render_sky_bottom, sizeof o->sky_bottom);
  }
  if (ground && (!cam->has_eye || cam->eye[1] > lo[1])) {     /* not seen from below */
    lsys_render_setfloor(o, lo, hi);
    cam->bounds[1] = o->floor_rect[0];          /* the near and far planes reach it too */
    for (k = 0; k < 2; k++) {
      cam->bounds[2 * k] = fmin(cam->bounds[2 * k], o->floor_rect[1 + k]);
      cam->bounds[3 + 2 * k] = fmax(cam->bounds[3 + 2 * k], o->floor_rect[3 + k]);
    }
  }
}
