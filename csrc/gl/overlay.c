/*
** Text and highlight lines over the viewer's picture (overlay.h).
*/
#include <GL/gl.h>
#include <string.h>

#include "font.h"              /* csrc/core/font.h */
#include "overlay.h"
#include "vlight.h"

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

const char lsys_overlay_help[] =
  "drag: orbit   right-drag / shift-drag: pan   scroll: zoom\n"
  "click: pick a module\n"
  "left / right: step back / forward   home / end: first / last\n"
  "space: animate   + / -: faster / slower\n"
  "R: reset view   F: fit   W: wireframe   S: screenshot\n"
  "L: colour the leaves by the light they receive   G: sky and ground\n"
  "S while animating: save every step (this camera) to a folder\n"
  "H: this help   Esc / Q: quit";

#define ADV(px) ((LSYS_FONT_W + 1) * (px))    /* the advance of a character */

/* The legend of the light colours at the top right, from y down: a title,
** the ramp between 0 and 1, and 'note'. */
static void legend (lsys_overlay *t, int fbw, float y, float px, const char *note,
                    const uint8_t fg[4], const uint8_t bg[4]) {
  static const char title[] = "leaf light (L)";
  size_t n = strlen(note) > sizeof title - 1 ? strlen(note) : sizeof title - 1, k;
  float w = (float)n * ADV(px) + 4 * px, lh = (LSYS_FONT_H + 4) * px, x, bw;
  if (w > fbw / 2 && px > 1) {                      /* smaller to fit */
    px = px / 2 < 1 ? 1 : px / 2;
    w = (float)n * ADV(px) + 4 * px;
    lh = (LSYS_FONT_H + 4) * px;
  }
  x = (float)fbw - w - 2 * px;
  y += 2 * px;
  lsys_overlay_quad(t, x, y, w, 3 * lh + 2 * px, bg);
  lsys_overlay_text(t, title, x + 2 * px, y + 2 * px, px, fg);
  lsys_overlay_text(t, "0", x + 2 * px, y + lh + 2 * px, px, fg);
  lsys_overlay_text(t, "1", x + w - 2 * px - ADV(px), y + lh + 2 * px, px, fg);
  bw = (w - 4 * px - 2 * ADV(px) - 2 * px) / LSYS_VLIGHT_BINS;
  for (k = 0; k < LSYS_VLIGHT_BINS; k++) {
    float rgb[3];
    uint8_t c[4] = {0, 0, 0, 255};
    int i;
    lsys_vlight_ramp((double)k / (LSYS_VLIGHT_BINS - 1), rgb);
    for (i = 0; i < 3; i++) c[i] = (uint8_t)(255 * rgb[i] + 0.5f);
    lsys_overlay_quad(t, x + 3 * px + ADV(px) + (float)k * bw, y + lh + px, bw + 0.5f,
                      LSYS_FONT_H * px + 2 * px, c);
  }
  lsys_overlay_text(t, note, x + 2 * px, y + 2 * lh + 2 * px, px, fg);
}

void lsys_overlay_screen (lsys_overlay *t, const lsys_gl *gl, int fbw, int fbh, int winh,
                          const char *line, const char *help, const char *light) {
  static const uint8_t fg[4] = {255, 255, 255, 255}, bg[4] = {0, 0, 0, 140};
  float px = (float)(winh > 0 ? 2.0 * fbh / winh : 2.0), lh, top = 0;
  size_t n = line != NULL ? strlen(line) : 0;
  t->n = 0;
  if (fbw < (float)(n + 12) * ADV(px) && px > 1) px = px / 2 < 1 ? 1 : px / 2;
  lh = (LSYS_FONT_H + 4) * px;
  if (line != NULL) {
    lsys_overlay_quad(t, 0, (float)fbh - lh, (float)fbw, lh, bg);
    lsys_overlay_text(t, line, 2 * px, (float)fbh - lh + 2 * px, px, fg);
    if (help == NULL && n + 14 < (size_t)(fbw / ADV(px)))
      lsys_overlay_text(t, "H: help", (float)fbw - 9 * ADV(px), (float)fbh - lh + 2 * px, px,
                        fg);
  }
  if (help != NULL) {
    const char *s;
    int lines = 1;
    for (s = help; *s; s++) lines += *s == '\n';
    top = lines * (LSYS_FONT_H + 3) * px + 4 * px;
    lsys_overlay_quad(t, 0, 0, (float)fbw, top, bg);
    lsys_overlay_text(t, help, 2 * px, 2 * px, px, fg);
  }
  if (light != NULL) legend(t, fbw, top, px, light, fg, bg);
  lsys_overlay_draw(t, gl, fbw, fbh);
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
