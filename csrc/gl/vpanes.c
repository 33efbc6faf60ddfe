/*
** Panes of the viewer window (vpanes.h): layout, posted images, and their
** drawing as textured quads in window pixels.
*/
#include <GL/gl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "vpanes.h"

void lsys_vpanes_init (lsys_vpanes *p) {
  memset(p, 0, sizeof *p);
  pthread_mutex_init(&p->mu, NULL);
}

void lsys_vpanes_free (lsys_vpanes *p) {
  int k;
  for (k = 0; k < LSYS_VPANES_MAX; k++) {
    LSYS_FREE(p->img[k].rgba);
    LSYS_FREE(p->newimg[k].rgba);
  }
  LSYS_FREE(p->pad);
  pthread_mutex_destroy(&p->mu);
  memset(p, 0, sizeof *p);
}

void lsys_vpanes_set_layout (lsys_vpanes *p, const lsys_vlayout *lay) {
  pthread_mutex_lock(&p->mu);
  p->newlay = *lay;
  if (p->newlay.npanes < 0) p->newlay.npanes = 0;
  if (p->newlay.npanes > LSYS_VPANES_MAX) p->newlay.npanes = LSYS_VPANES_MAX;
  p->changed |= 1;
  pthread_mutex_unlock(&p->mu);
}

int lsys_vpanes_set_image (lsys_vpanes *p, int k, const uint8_t *rgba, int w, int h) {
  size_t n;
  uint8_t *copy, *old;
  if (k < 0 || k >= LSYS_VPANES_MAX || w <= 0 || h <= 0 || w > 16384 || h > 16384)
    return LSYS_EARG;
  n = (size_t)w * (size_t)h * 4;
  copy = (uint8_t *)LSYS_MALLOC(n);   /* outside the lock: the window never waits on it */
  if (copy == NULL) return LSYS_ENOMEM;
  memcpy(copy, rgba, n);
  pthread_mutex_lock(&p->mu);
  old = p->newimg[k].rgba;            /* posted and never taken: replaced */
  p->newimg[k].rgba = copy;
  p->newimg[k].w = w;
  p->newimg[k].h = h;
  p->newimg[k].fresh = 1;
  p->changed |= 2;
  pthread_mutex_unlock(&p->mu);
  LSYS_FREE(old);
  return LSYS_OK;
}

void lsys_vpanes_set_text (lsys_vpanes *p, const char *msg, const char *help) {
  pthread_mutex_lock(&p->mu);
  if (msg != NULL) snprintf(p->newmsg, sizeof p->newmsg, "%s", msg);
  if (help != NULL) snprintf(p->newhelp, sizeof p->newhelp, "%s", help);
  p->changed |= 4;
  pthread_mutex_unlock(&p->mu);
}

int lsys_vpanes_take (lsys_vpanes *p) {
  int changed, k;
  uint8_t *old[LSYS_VPANES_MAX] = {0};
  pthread_mutex_lock(&p->mu);
  changed = p->changed;
  if (changed & 1) p->lay = p->newlay;
  if (changed & 2)
    for (k = 0; k < LSYS_VPANES_MAX; k++)
      if (p->newimg[k].fresh) {
        old[k] = p->img[k].rgba;
        p->img[k] = p->newimg[k];
        memset(&p->newimg[k], 0, sizeof p->newimg[k]);
      }
  if (changed & 4) {
    memcpy(p->msg, p->newmsg, sizeof p->msg);
    memcpy(p->help, p->newhelp, sizeof p->help);
  }
  p->changed = 0;
  pthread_mutex_unlock(&p->mu);
  for (k = 0; k < LSYS_VPANES_MAX; k++) LSYS_FREE(old[k]);
  return changed != 0;
}

/* ---------------------------------------------------------------------- */
/* placement */

static float clamp01 (float x) {
  return x < 0 ? 0 : x > 1 ? 1 : x;
}

void lsys_vpanes_rect (const float r[4], int winw, int winh, int out[4]) {
  int x0 = (int)lroundf(clamp01(r[0]) * (float)winw);
  int y0 = (int)lroundf(clamp01(r[1]) * (float)winh);
  int x1 = (int)lroundf(clamp01(r[2]) * (float)winw);
  int y1 = (int)lroundf(clamp01(r[3]) * (float)winh);
  out[0] = x0;
  out[1] = y0;
  out[2] = x1 > x0 ? x1 - x0 : 0;
  out[3] = y1 > y0 ? y1 - y0 : 0;
}

void lsys_vpanes_scene (const lsys_vpanes *p, int winw, int winh, int out[4]) {
  static const float all[4] = {0, 0, 1, 1};
  lsys_vpanes_rect(p->lay.on ? p->lay.scene : all, winw, winh, out);
  if (out[2] < 1) out[2] = 1;           /* a viewport of one pixel rather than none */
  if (out[3] < 1) out[3] = 1;
}

void lsys_vpanes_fbrect (const int sr[4], int winh, int fbh, int r[4]) {
  double k = (double)fbh / winh;            /* framebuffer pixels per window pixel */
  r[0] = (int)lround(sr[0] * k);
  r[1] = (int)lround((winh - sr[1] - sr[3]) * k);
  r[2] = (int)lround(sr[2] * k);
  r[3] = (int)lround(sr[3] * k);
}

/* Where pane k's image goes, in window coordinates (x, y, scale): as large
** as fits, its aspect kept, centred. Without an image: the pane, scale 1. */
static void placement (const lsys_vpanes *p, int k, int winw, int winh, double *x, double *y,
                       double *s) {
  int r[4];
  const lsys_vimage *im = &p->img[k];
  lsys_vpanes_rect(p->lay.pane[k], winw, winh, r);
  if (im->rgba == NULL || im->w <= 0 || im->h <= 0) {
    *x = r[0];
    *y = r[1];
    *s = 1;
    return;
  }
  *s = fmin((double)r[2] / im->w, (double)r[3] / im->h);
  if (!(*s > 0)) *s = 1e-6;
  *x = r[0] + (r[2] - *s * im->w) / 2;
  *y = r[1] + (r[3] - *s * im->h) / 2;
}

void lsys_vpanes_map (const lsys_vpanes *p, int k, int winw, int winh, double x, double y,
                      double *px, double *py) {
  double ix, iy, s;
  placement(p, k, winw, winh, &ix, &iy, &s);
  *px = (x - ix) / s;
  *py = (y - iy) / s;
}

static int inside (const int r[4], double x, double y) {
  return x >= r[0] && y >= r[1] && x < r[0] + r[2] && y < r[1] + r[3];
}

int lsys_vpanes_hit (const lsys_vpanes *p, int winw, int winh, double x, double y,
                     double *px, double *py) {
  int r[4], k;
  if (!p->lay.on) {
    *px = x;
    *py = y;
    return LSYS_VPANE_SCENE;
  }
  for (k = 0; k < p->lay.npanes; k++) {
    lsys_vpanes_rect(p->lay.pane[k], winw, winh, r);
    if (inside(r, x, y)) {
      lsys_vpanes_map(p, k, winw, winh, x, y, px, py);
      return k;
    }
  }
  lsys_vpanes_scene(p, winw, winh, r);
  *px = x - r[0];
  *py = y - r[1];
  return inside(r, x, y) ? LSYS_VPANE_SCENE : LSYS_VPANE_NONE;
}

/* ---------------------------------------------------------------------- */
/* drawing */

static int pot (int n) {
  int p = 1;
  while (p < n) p <<= 1;
  return p;
}

/* Uploads pane k's image into its texture, padded to a power-of-two size
** (any OpenGL 1.1 takes it); 0 when there is no memory for the padding. */
static int upload (lsys_vpanes *p, int k, const lsys_gl *gl) {
  lsys_vimage *im = &p->img[k];
  int tw = pot(im->w), th = pot(im->h), y;
  size_t row = 4 * (size_t)tw;
  if (lsys_common_grow((void **)&p->pad, &p->padcap, row * (size_t)th, 1) != LSYS_OK) return 0;
  memset(p->pad, 0, row * (size_t)th);
  for (y = 0; y < im->h; y++)
    memcpy(p->pad + (size_t)y * row, im->rgba + (size_t)y * 4 * (size_t)im->w, 4 * (size_t)im->w);
  if (p->tex[k] == 0) gl->GenTextures(1, &p->tex[k]);
  gl->BindTexture(GL_TEXTURE_2D, p->tex[k]);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP);
  gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, tw, th, 0, GL_RGBA, GL_UNSIGNED_BYTE, p->pad);
  p->texw[k] = tw;
  p->texh[k] = th;
  im->fresh = 0;
  return 1;
}

/* One quad of window rectangle (x, y, w, h) scaled to framebuffer pixels;
** with tex: texture coordinates (0, 0)-(u, v). */
static void quad (const lsys_gl *gl, double x, double y, double w, double h, double sc,
                  const uint8_t c[4], float u, float v, int tex) {
  static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
  float pos[8], uv[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  uint8_t col[16];
  int i;
  pos[0] = (float)(x * sc);       pos[1] = (float)(y * sc);
  pos[2] = (float)((x + w) * sc); pos[3] = pos[1];
  pos[4] = pos[2];                pos[5] = (float)((y + h) * sc);
  pos[6] = pos[0];                pos[7] = pos[5];
  uv[2] = u; uv[4] = u; uv[5] = v; uv[7] = v;
  for (i = 0; i < 4; i++) memcpy(col + 4 * i, c, 4);
  gl->VertexPointer(2, GL_FLOAT, 0, pos);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, col);
  if (tex) {
    gl->EnableClientState(GL_TEXTURE_COORD_ARRAY);
    gl->TexCoordPointer(2, GL_FLOAT, 0, uv);
  }
  gl->DrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, idx);
  if (tex) gl->DisableClientState(GL_TEXTURE_COORD_ARRAY);
}

void lsys_vpanes_draw (lsys_vpanes *p, const lsys_gl *gl, int winw, int winh, int fbw, int fbh) {
  static const uint8_t white[4] = {255, 255, 255, 255};
  double m[16] = {0}, sc = winh > 0 ? (double)fbh / winh : 1;
  int k;
  if (!p->lay.on || p->lay.npanes == 0) return;
  /* framebuffer pixels, y down, over the whole window */
  gl->Viewport(0, 0, fbw, fbh);
  m[0] = 2.0 / fbw; m[5] = -2.0 / fbh; m[10] = 1; m[12] = -1; m[13] = 1; m[15] = 1;
  gl->MatrixMode(GL_TEXTURE);
  gl->LoadIdentity();
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(m);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadIdentity();
  gl->Disable(GL_DEPTH_TEST);
  gl->Disable(GL_LIGHTING);
  gl->Disable(GL_BLEND);
  gl->Disable(GL_ALPHA_TEST);
  gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  for (k = 0; k < p->lay.npanes; k++) {
    int r[4];
    double x, y, s;
    lsys_vimage *im = &p->img[k];
    lsys_vpanes_rect(p->lay.pane[k], winw, winh, r);
    gl->Disable(GL_TEXTURE_2D);
    quad(gl, r[0], r[1], r[2], r[3], sc, p->lay.bg[k], 0, 0, 0);
    if (im->rgba == NULL || (im->fresh && !upload(p, k, gl))) continue;
    placement(p, k, winw, winh, &x, &y, &s);
    gl->Enable(GL_TEXTURE_2D);
    gl->BindTexture(GL_TEXTURE_2D, p->tex[k]);
    gl->TexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    quad(gl, x, y, s * im->w, s * im->h, sc, white, (float)im->w / (float)p->texw[k],
         (float)im->h / (float)p->texh[k], 1);
  }
  gl->Disable(GL_TEXTURE_2D);
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
}

void lsys_vpanes_release (lsys_vpanes *p, const lsys_gl *gl) {
  int k;
  for (k = 0; k < LSYS_VPANES_MAX; k++)
    if (p->tex[k] != 0) {
      gl->DeleteTextures(1, &p->tex[k]);
      p->tex[k] = 0;
      if (p->img[k].rgba != NULL) p->img[k].fresh = 1;
    }
}
