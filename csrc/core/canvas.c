/*
** The 2D canvas (canvas.h). Every primitive is drawn the same way: find
** the pixels its shape can reach, cut to the clip rectangle, and blend its
** colour into each with the pixel's coverage. Coverage comes from the
** distance of the pixel's centre to the shape (lines, discs) or from the
** pixel's area inside it (rectangles); text is whole pixels.
*/
#include <limits.h>
#include <math.h>
#include <string.h>

#include "canvas.h"
#include "font.h"
#include "pngio.h"

/* A colour ready to blend: channels in [0, 255], alpha in [0, 1]. */
typedef struct paint {
  float c[3];
  float a;
  uint8_t full[4];     /* the bytes of the colour at full coverage */
} paint;

static double unit (double v) {
  return v >= 0 ? (v <= 1 ? v : 1) : 0;      /* NaN -> 0 */
}

static paint mkpaint (const double rgba[4]) {
  paint p;
  int i;
  for (i = 0; i < 3; i++) {
    p.c[i] = (float)(unit(rgba[i]) * 255.0);
    p.full[i] = (uint8_t)(p.c[i] + 0.5f);
  }
  p.a = (float)unit(rgba[3]);
  p.full[3] = (uint8_t)(p.a * 255.0f + 0.5f);
  return p;
}

/* Source over: the paint at coverage 'cov' (0..1] onto the pixel 'd'. */
static void blend (uint8_t *d, const paint *p, float cov) {
  float a = p->a * cov, da, k, oa;
  int i;
  if (a <= 0.0f) return;
  if (a >= 1.0f) {
    memcpy(d, p->full, 4);
    return;
  }
  da = d[3] * (1.0f / 255.0f);
  k = da * (1.0f - a);                        /* what shows of the pixel below */
  oa = a + k;
  for (i = 0; i < 3; i++) d[i] = (uint8_t)((p->c[i] * a + d[i] * k) / oa + 0.5f);
  d[3] = (uint8_t)(oa * 255.0f + 0.5f);
}

static int finite4 (double a, double b, double c, double d) {
  return isfinite(a) && isfinite(b) && isfinite(c) && isfinite(d);
}

/* The whole pixels i with centres in [lo, hi], cut to [min, max); returns
** 0 when there are none. Safe for any finite lo, hi (clamped before the
** conversion to int). */
static int span (double lo, double hi, int min, int max, int *i0, int *i1) {
  double a = ceil(lo - 0.5), b = floor(hi - 0.5);
  if (a < min) a = min;
  if (b > max - 1) b = max - 1;
  if (!(a <= b)) return 0;
  *i0 = (int)a;
  *i1 = (int)b;
  return 1;
}

int lsys_canvas_init (lsys_canvas *c, int w, int h, lsys_error *e) {
  size_t bytes;
  char b1[32], b2[32];
  memset(c, 0, sizeof *c);
  if (w < 1 || h < 1 || w > LSYS_CANVAS_MAXSIZE || h > LSYS_CANVAS_MAXSIZE)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "canvas size %dx%d is outside 1x1 .. %dx%d",
                         w, h, LSYS_CANVAS_MAXSIZE, LSYS_CANVAS_MAXSIZE);
  bytes = (size_t)w * (size_t)h * 4;
  if (bytes > lsys_common_memory_limit())
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "a %dx%d canvas needs %s, more than the "
                         "memory limit (%s)", w, h, lsys_common_fmtsize(b1, bytes),
                         lsys_common_fmtsize(b2, lsys_common_memory_limit()));
  c->px = (uint8_t *)LSYS_MALLOC(bytes);
  if (c->px == NULL) return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  memset(c->px, 0, bytes);
  c->w = w;
  c->h = h;
  lsys_canvas_unclip(c);
  return LSYS_OK;
}

void lsys_canvas_free (lsys_canvas *c) {
  LSYS_FREE(c->px);
  c->px = NULL;
}

void lsys_canvas_clear (lsys_canvas *c, const double rgba[4]) {
  paint p = mkpaint(rgba);
  size_t i, n = (size_t)c->w * (size_t)c->h;
  for (i = 0; i < n; i++) memcpy(c->px + 4 * i, p.full, 4);
}

void lsys_canvas_unclip (lsys_canvas *c) {
  c->cx0 = c->cy0 = 0;
  c->cx1 = c->w;
  c->cy1 = c->h;
}

void lsys_canvas_clip (lsys_canvas *c, double x, double y, double w, double h) {
  int i0, i1, j0, j1;
  /* the centres i + 0.5 in [x, x + w): i in [ceil(x - 0.5), ceil(x + w - 0.5)) */
  if (finite4(x, y, w, h) && w > 0 && h > 0
      && span(x, nextafter(x + w, -HUGE_VAL), 0, c->w, &i0, &i1)
      && span(y, nextafter(y + h, -HUGE_VAL), 0, c->h, &j0, &j1)) {
    c->cx0 = i0; c->cx1 = i1 + 1;
    c->cy0 = j0; c->cy1 = j1 + 1;
  } else {
    c->cx0 = c->cx1 = c->cy0 = c->cy1 = 0;
  }
}

/*
** Cuts the segment p = {x0, y0, x1, y1} to the box b = {x0, y0, x1, y1}
** (Liang-Barsky) and clamps the result into it, so that far-away ends
** cannot leave it by rounding. A cut end is put exactly on the side that
** cut it, which keeps a far-reaching horizontal or vertical line exact.
** Returns 0 when nothing of the segment is in the box.
*/
static int clipseg (double p[4], const double b[4]) {
  double dx = p[2] - p[0], dy = p[3] - p[1], t[2] = { 0, 1 };
  double q[4], d[4], out[4];
  int k, side[2] = { -1, -1 };          /* the side (0..3) that cut each end */
  if (!isfinite(dx) || !isfinite(dy)) return 0;  /* ends beyond +-1e308 apart */
  d[0] = -dx; q[0] = p[0] - b[0];
  d[1] = dx;  q[1] = b[2] - p[0];
  d[2] = -dy; q[2] = p[1] - b[1];
  d[3] = dy;  q[3] = b[3] - p[1];
  for (k = 0; k < 4; k++) {
    if (d[k] == 0) {
      if (q[k] < 0) return 0;
    } else {
      double u = q[k] / d[k];
      int end = d[k] > 0;                 /* entering sides move t0, leaving ones t1 */
      if (end ? u < t[1] : u > t[0]) {
        t[end] = u;
        side[end] = k;
      }
    }
  }
  if (!(t[0] <= t[1])) return 0;
  for (k = 0; k < 2; k++) {
    static const int bi[4] = { 0, 2, 1, 3 };   /* side -> its coordinate in b */
    out[2 * k] = p[0] + t[k] * dx;
    out[2 * k + 1] = p[1] + t[k] * dy;
    if (side[k] >= 0) out[2 * k + side[k] / 2] = b[bi[side[k]]];
  }
  for (k = 0; k < 4; k += 2) {
    p[k] = out[k] < b[0] ? b[0] : out[k] > b[2] ? b[2] : out[k];
    p[k + 1] = out[k + 1] < b[1] ? b[1] : out[k + 1] > b[3] ? b[3] : out[k + 1];
  }
  return 1;
}

/* The line of lsys_canvas_line with its paint made. */
static void drawline (lsys_canvas *c, double x0, double y0, double x1, double y1, double width,
                      const paint *pt) {
  double p[4] = { x0, y0, x1, y1 }, box[4], r, cmax, dx, dy, l2;
  int j, j0, j1;
  if (!finite4(x0, y0, x1, y1) || !(width > 0) || !isfinite(width)) return;
  r = width * 0.5 + 0.5;                   /* the reach: coverage is 0 from there on */
  cmax = width < 1 ? width : 1;
  box[0] = c->cx0 - r; box[1] = c->cy0 - r; box[2] = c->cx1 + r; box[3] = c->cy1 + r;
  if (!clipseg(p, box)) return;
  dx = p[2] - p[0];
  dy = p[3] - p[1];
  l2 = dx * dx + dy * dy;
  if (!span(fmin(p[1], p[3]) - r, fmax(p[1], p[3]) + r, c->cy0, c->cy1, &j0, &j1)) return;
  for (j = j0; j <= j1; j++) {
    double yc = j + 0.5, ta = 0, tb = 1, xa, xb;
    int i, i0, i1;
    uint8_t *row = c->px + ((size_t)j * (size_t)c->w) * 4;
    if (dy != 0) {               /* the part of the segment within r of this row, in y */
      ta = (yc - r - p[1]) / dy;
      tb = (yc + r - p[1]) / dy;
      if (ta > tb) { double t = ta; ta = tb; tb = t; }
      if (ta < 0) ta = 0;
      if (tb > 1) tb = 1;
      if (ta > tb) continue;
    }
    xa = p[0] + ta * dx;
    xb = p[0] + tb * dx;
    if (!span(fmin(xa, xb) - r, fmax(xa, xb) + r, c->cx0, c->cx1, &i0, &i1)) continue;
    for (i = i0; i <= i1; i++) {
      double ex = i + 0.5 - p[0], ey = yc - p[1], t = 0, d, cov;
      if (l2 > 0) {
        t = (ex * dx + ey * dy) / l2;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
      }
      d = hypot(ex - t * dx, ey - t * dy);
      cov = r - d;
      if (cov > cmax) cov = cmax;
      if (cov > 0) blend(row + 4 * (size_t)i, pt, (float)cov);
    }
  }
}

void lsys_canvas_line (lsys_canvas *c, double x0, double y0, double x1, double y1,
                       double width, const double rgba[4]) {
  paint p = mkpaint(rgba);
  drawline(c, x0, y0, x1, y1, width, &p);
}

void lsys_canvas_polyline (lsys_canvas *c, const double *xy, size_t n, double width,
                           const double rgba[4]) {
  paint p = mkpaint(rgba);
  size_t k;
  for (k = 1; k < n; k++)
    drawline(c, xy[2 * k - 2], xy[2 * k - 1], xy[2 * k], xy[2 * k + 1], width, &p);
}

/* Fills [x0, x1] x [y0, y1] (x0 <= x1, y0 <= y1), each pixel covered by its
** area inside. */
static void fillbox (lsys_canvas *c, double x0, double y0, double x1, double y1,
                     const paint *p) {
  int i, j, i0, i1, j0, j1;
  /* the pixels that overlap: centres in [x0 - 0.5, x1 + 0.5) */
  if (!span(x0 - 0.5 + 1e-9, x1 + 0.5 - 1e-9, c->cx0, c->cx1, &i0, &i1)) return;
  if (!span(y0 - 0.5 + 1e-9, y1 + 0.5 - 1e-9, c->cy0, c->cy1, &j0, &j1)) return;
  for (j = j0; j <= j1; j++) {
    double cy = fmin(j + 1, y1) - fmax(j, y0);
    uint8_t *row = c->px + ((size_t)j * (size_t)c->w) * 4;
    if (cy <= 0) continue;
    for (i = i0; i <= i1; i++) {
      double cov = (fmin(i + 1, x1) - fmax(i, x0)) * cy;
      if (cov > 0) blend(row + 4 * (size_t)i, p, (float)(cov < 1 ? cov : 1));
    }
  }
}

void lsys_canvas_rect (lsys_canvas *c, double x, double y, double w, double h,
                       const double rgba[4], int fill) {
  paint p = mkpaint(rgba);
  if (!finite4(x, y, w, h) || !(w > 0) || !(h > 0) || !isfinite(x + w) || !isfinite(y + h))
    return;
  if (fill || w <= 2 || h <= 2) {
    fillbox(c, x, y, x + w, y + h, &p);
    return;
  }
  fillbox(c, x, y, x + w, y + 1, &p);                    /* top and bottom, whole width */
  fillbox(c, x, y + h - 1, x + w, y + h, &p);
  fillbox(c, x, y + 1, x + 1, y + h - 1, &p);            /* left and right, between them */
  fillbox(c, x + w - 1, y + 1, x + w, y + h - 1, &p);
}

void lsys_canvas_circle (lsys_canvas *c, double x, double y, double r, const double rgba[4]) {
  paint p = mkpaint(rgba);
  double reach, cmax;
  int i, j, i0, i1, j0, j1;
  if (!finite4(x, y, r, 0) || !(r > 0)) return;
  reach = r + 0.5;
  cmax = 3.14159265358979323846 * r * r;          /* a dot smaller than a pixel */
  if (cmax > 1) cmax = 1;
  if (!span(y - reach, y + reach, c->cy0, c->cy1, &j0, &j1)) return;
  if (!span(x - reach, x + reach, c->cx0, c->cx1, &i0, &i1)) return;
  for (j = j0; j <= j1; j++) {
    uint8_t *row = c->px + ((size_t)j * (size_t)c->w) * 4;
    for (i = i0; i <= i1; i++) {
      double cov = reach - hypot(i + 0.5 - x, j + 0.5 - y);
      if (cov > cmax) cov = cmax;
      if (cov > 0) blend(row + 4 * (size_t)i, &p, (float)cov);
    }
  }
}

long lsys_canvas_text_width (size_t n, int scale) {
  if (n == 0 || scale < 1) return 0;
  if (n > (size_t)(LONG_MAX / 6 / 64)) n = (size_t)(LONG_MAX / 6 / 64);
  return (long)n * 6 * scale - scale;
}

/* One glyph with its top left at the whole pixel (x, y). */
static void glyph (lsys_canvas *c, long x, long y, unsigned char ch, int scale,
                   const paint *p) {
  const unsigned char *g;
  int row, col;
  if (ch < LSYS_FONT_FIRST || ch > LSYS_FONT_LAST) ch = '?';
  g = lsys_font[ch - LSYS_FONT_FIRST];
  for (row = 0; row < LSYS_FONT_H; row++)
    for (col = 0; col < LSYS_FONT_W; col++)
      if (g[row] & (0x10 >> col)) {
        double bx = (double)x + col * scale, by = (double)y + row * scale;
        fillbox(c, bx, by, bx + scale, by + scale, p);
      }
}

int lsys_canvas_text (lsys_canvas *c, double x, double y, const char *s, size_t n, int scale,
                      const double rgba[4]) {
  paint p = mkpaint(rgba);
  long width = lsys_canvas_text_width(n, scale), gx, gy;
  size_t k;
  if (scale < 1 || scale > 64) return 0;
  if (!finite4(x, y, 0, 0) || fabs(x) > 1e9 || fabs(y) > 1e9) return (int)width;
  gx = (long)floor(x + 0.5);
  gy = (long)floor(y + 0.5);
  if (gy >= c->cy1 || gy + (long)LSYS_FONT_H * scale <= c->cy0) return (int)width;
  for (k = 0; k < n; k++, gx += 6L * scale) {
    if (gx >= c->cx1) break;                       /* the rest is right of the clip */
    if (gx + (long)LSYS_FONT_W * scale > c->cx0)
      glyph(c, gx, gy, (unsigned char)s[k], scale, &p);
  }
  return width > INT_MAX ? INT_MAX : (int)width;
}

int lsys_canvas_save (const lsys_canvas *c, const char *path, lsys_error *e) {
  size_t i, n = (size_t)c->w * (size_t)c->h;
  int alpha = 0;
  for (i = 0; i < n && !alpha; i++) alpha = c->px[4 * i + 3] != 255;
  return lsys_pngio_write(path, c->px, c->w, c->h, alpha, e);
}
