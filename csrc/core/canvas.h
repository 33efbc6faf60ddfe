/*
** A 2D RGBA8 canvas: anti-aliased lines and polylines, rectangles, dots and
** text in the 5x7 font (font.h), blended source-over, clipped to the canvas
** and to a clip rectangle, and written as PNG. The function plots and the
** sketch drawings of lsys.sketch.plot (docs/sketch.md) are drawn here, so a
** picture is the same in a file and in the sketch window, which uploads the
** pixels as a texture.
**
** Coordinates are pixels, float, x to the right and y down, with pixel (i, j)
** covering [i, i+1) x [j, j+1): its centre is (i + 0.5, j + 0.5), so a
** 1-pixel line along y = j + 0.5 lights row j alone. Colours are straight
** (not premultiplied) RGBA in [0, 1]; out-of-range components are clamped.
**
** Drawing allocates nothing; each primitive touches only the pixels its
** shape (cut to the clip rectangle) covers, so its cost is bounded by the
** canvas whatever its coordinates. A primitive with a NaN or infinite
** coordinate, or a size that is not a positive finite number, draws
** nothing.
*/
#ifndef LSYS_CANVAS_H
#define LSYS_CANVAS_H

#include "common.h"

#define LSYS_CANVAS_MAXSIZE 16384   /* largest width or height */

typedef struct lsys_canvas {
  uint8_t *px;                /* w * h * 4 bytes, RGBA, top row first; NULL once freed */
  int w, h;
  int cx0, cy0, cx1, cy1;     /* the clip rectangle in whole pixels, [cx0, cx1) x [cy0, cy1) */
} lsys_canvas;

/* Makes a w x h canvas of transparent black (the clip rectangle is the
** whole canvas). Returns LSYS_OK; LSYS_EARG for a size outside
** [1, LSYS_CANVAS_MAXSIZE], LSYS_EMEMORY when the pixels would not fit the
** memory budget (lsys_common_memory_limit), LSYS_ENOMEM; e->msg says which. On
** failure c->px is NULL. */
int lsys_canvas_init (lsys_canvas *c, int w, int h, lsys_error *e);

/* Frees the pixels; idempotent. */
void lsys_canvas_free (lsys_canvas *c);

/* Sets every pixel (the clip rectangle does not apply) to 'rgba'. */
void lsys_canvas_clear (lsys_canvas *c, const double rgba[4]);

/* Restricts drawing to the pixels whose centres lie in [x, x+w) x [y, y+h),
** cut to the canvas (an empty or non-finite rectangle clips everything). */
void lsys_canvas_clip (lsys_canvas *c, double x, double y, double w, double h);

/* Clips to the whole canvas again. */
void lsys_canvas_unclip (lsys_canvas *c);

/* A line from (x0, y0) to (x1, y1), 'width' pixels wide, with round caps:
** a pixel is covered by max(0, min(1, width, width/2 + 0.5 - d)) where d is
** the distance from its centre to the segment. */
void lsys_canvas_line (lsys_canvas *c, double x0, double y0, double x1, double y1,
                       double width, const double rgba[4]);

/* The segments between consecutive points of xy[0..2n) (x, y pairs), each a
** line with round caps (which make round joins); a segment with a
** non-finite end is left out. Translucent joins are blended twice. */
void lsys_canvas_polyline (lsys_canvas *c, const double *xy, size_t n, double width,
                           const double rgba[4]);

/* The rectangle [x, x+w] x [y, y+h] (w, h > 0): filled, each pixel covered
** by the fraction of its area inside; or, not filled, a 1-pixel outline
** along the inside of its edges. */
void lsys_canvas_rect (lsys_canvas *c, double x, double y, double w, double h,
                       const double rgba[4], int fill);

/* A filled disc of radius r (> 0) centred at (x, y), anti-aliased. */
void lsys_canvas_circle (lsys_canvas *c, double x, double y, double r, const double rgba[4]);

/* Draws n bytes of 's' in the 5x7 font, each font pixel a scale x scale
** block (scale in [1, 64]), the top left of the first glyph at (x, y)
** rounded to whole pixels. Bytes outside printable ASCII are drawn as '?'.
** Returns the width of the text (lsys_canvas_text_width). */
int lsys_canvas_text (lsys_canvas *c, double x, double y, const char *s, size_t n, int scale,
                      const double rgba[4]);

/* The width in pixels of n characters at 'scale': 6 * scale per character
** (5 columns and a gap) less the last gap; 0 for no text. The height is
** 7 * scale (LSYS_FONT_H). */
long lsys_canvas_text_width (size_t n, int scale);

/* Writes the canvas to 'path' as PNG (RGB when every pixel is opaque, else
** RGBA), replacing the file atomically (pngio.h, outfile.h). Returns
** LSYS_OK or LSYS_EARG with e->msg naming the file. */
int lsys_canvas_save (const lsys_canvas *c, const char *path, lsys_error *e);

#endif
