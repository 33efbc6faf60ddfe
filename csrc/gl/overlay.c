/*
** Text and highlight lines over the viewer's picture (overlay.h).
*/
#include <GL/gl.h>
#include <string.h>

#include "font.h"              /* csrc/core/font.h */
#include "overlay.h"

int lsys_overlay_quad (lsys_overlay *t, float x, float y, float w, float h, const uint8_t c[4]) {
  size_t n = t->n, i;
  float *p;
  if (lsys_common_grow((void **)&t->v, &t->vcap, 8 * (n + 1), sizeof *t->v) ||
      lsys_common_grow((void **)&t->c, &t->ccap, 16 * (n + 1), 1) ||
      lsys_common_grow((void **)&t->i, &t->icap, 6 * (n + 1), sizeof *t->i))
    return LSYS_ENOMEM;
  p = t->v + 8 * n;
  p[0] = x;     p[1] = y;
  p[2] = x + w; p[3] = y;
  p[4] = x + w; p[5] = y + h;
  p[6] = x;     p[7] = y + h;
  for (i = 0; i < 4; i++) memcpy(t->c + 16 * n + 4 * i, c, 4);
  t->i[6 * n + 0] = (uint32_t)(4 * n);
  t->i[6 * n + 1] = (uint32_t)(4 * n + 1);
  t->i[6 * n + 2] = (uint32_t)(4 * n + 2);
  t->i[6 * n + 3] = (uint32_t)(4 * n);
  t->i[6 * n + 4] = (uint32_t)(4 * n + 2);
  t->i[6 * n + 5] = (uint32_t)(4 * n + 3);
  t->n = n + 1;
  return LSYS_OK;
}

void lsys_overlay_text (lsys_overlay *t, const char *s, float x, float y, float px,
                        const uint8_t c[4]) {
  float x0 = x;
  for (; *s; s++) {
    int row, col;
    if (*s == '\n') { x = x0; y += (LSYS_FONT_H + 3) * px; continue; }
    /* letters with descenders are drawn within the 7 rows: lowered by 2,
    ** their bowls sit on the baseline with the other small letters */
    float dy = strchr("gjpqy", *s) != NULL ? 2 * px : 0;
    for (row = 0; row < LSYS_FONT_H; row++) {
      unsigned bits = lsys_font_row((unsigned char)*s, row);
      for (col = 0; col < LSYS_FONT_W; col++)
        if (bits & (1u << (LSYS_FONT_W - 1 - col)))
          lsys_overlay_quad(t, x + col * px, y + dy + row * px, px, px, c);
    }
    x += (LSYS_FONT_W + 1) * px;
  }
}

void lsys_overlay_draw (const lsys_overlay *t, const lsys_gl *gl, int fbw, int fbh) {
  double m[16] = {0};
  if (t->n == 0) return;
  /* pixels, y down: x' = 2x/w - 1, y' = 1 - 2y/h */
  m[0] = 2.0 / fbw;
  m[5] = -2.0 / fbh;
  m[10] = 1;
  m[12] = -1;
  m[13] = 1;
  m[15] = 1;
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(m);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadIdentity();
  gl->Disable(GL_DEPTH_TEST);
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_TEXTURE_2D);
  gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  gl->Enable(GL_BLEND);
  gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(2, GL_FLOAT, 0, t->v);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, t->c);
  gl->DrawElements(GL_TRIANGLES, (int)(6 * t->n), GL_UNSIGNED_INT, t->i);
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
  gl->Disable(GL_BLEND);
}

void lsys_overlay_free (lsys_overlay *t) {
  LSYS_FREE(t->v);
  LSYS_FREE(t->c);
  LSYS_FREE(t->i);
  memset(t, 0, sizeof *t);
}

void lsys_overlay_lines (const lsys_gl *gl, const lsys_vline *lines, size_t n, float scale) {
  size_t k;
  int pass;
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_TEXTURE_2D);
  gl->DepthFunc(GL_LEQUAL);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  for (pass = 0; pass < 2; pass++) {
    if (pass == 0) gl->Enable(GL_DEPTH_TEST);
    else gl->Disable(GL_DEPTH_TEST);
    for (k = 0; k < n; k++) {           /* few lines: one call each, own width */
      static const uint32_t idx[2] = {0, 1};
      const lsys_vline *l = &lines[k];
      float pos[6];
      uint8_t col[8];
      if ((l->ontop != 0) != pass) continue;
      memcpy(pos, l->p0, sizeof l->p0);
      memcpy(pos + 3, l->p1, sizeof l->p1);
      memcpy(col, l->rgba, 4);
      memcpy(col + 4, l->rgba, 4);
      gl->LineWidth(l->width * scale > 1 ? l->width * scale : 1);
      gl->VertexPointer(3, GL_FLOAT, 0, pos);
      gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, col);
      gl->DrawElements(GL_LINES, 2, GL_UNSIGNED_INT, idx);
    }
  }
  gl->Enable(GL_DEPTH_TEST);
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
  gl->LineWidth(1);
}
