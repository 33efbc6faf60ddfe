/*
** What the viewer window draws over the scene (glfw_viewer.c): text in the
** built-in font (core/font.h), laid out as one quad per lit font pixel and drawn
** in one call, and the highlight lines of a frame (viewer.h).
*/
#ifndef LSYS_OVERLAY_H
#define LSYS_OVERLAY_H

#include "viewer.h"

/* Quads in framebuffer pixels (y down), kept between frames so that
** drawing allocates nothing once they are large enough. */
typedef struct lsys_overlay {
  float *v;                     /* 4 corners (x, y) per quad */
  uint8_t *c;                   /* their colours, RGBA */
  uint32_t *i;                  /* two triangles per quad */
  size_t vcap, ccap, icap;
  size_t n;                     /* quads */
} lsys_overlay;

/* Adds a w x h rectangle with its top left corner at (x, y), of colour 'c'.
** Returns LSYS_OK, or LSYS_ENOMEM (nothing added). */
int lsys_overlay_quad (lsys_overlay *t, float x, float y, float w, float h, const uint8_t c[4]);

/* Lays out 's' with its top left corner at (x, y), each font pixel px x px;
** '\n' starts a line below. Font pixels that find no memory are left out. */
void lsys_overlay_text (lsys_overlay *t, const char *s, float x, float y, float px,
                        const uint8_t c[4]);

/* Draws the quads of 't' over a fbw x fbh framebuffer, blended, without
** depth test or lighting, and leaves it at that (nothing when 't' is empty). */
void lsys_overlay_draw (const lsys_overlay *t, const lsys_gl *gl, int fbw, int fbh);

/* The help of the window's keys (the H key, docs/viewer.md). */
extern const char lsys_overlay_help[];

/*
** Lays out and draws what the window writes over its picture (a fbw x fbh
** framebuffer of a window winh high in screen coordinates: 2 framebuffer
** pixels a font pixel on a plain screen, fewer when the status line does
** not fit): the status line 'line' at the bottom with "H: help" at its right
** when there is room, the help text 'help' at the top, and the legend of the
** light colours (vlight.h) at the top right, under the help: a title, the
** ramp from 0 to 1 and 'light' (lsys_vlight_note). NULL leaves each out.
*/
void lsys_overlay_screen (lsys_overlay *t, const lsys_gl *gl, int fbw, int fbh, int winh,
                          const char *line, const char *help, const char *light);

/* Frees the arrays of 't' and leaves it empty. */
void lsys_overlay_free (lsys_overlay *t);

/* Draws the n highlight lines with the matrices loaded (those of the scene,
** as lsys_render_draw leaves them), unlit: first those depth-tested against
** the scene, then those drawn on top. 'scale' is framebuffer pixels per
** window pixel (line widths are in window pixels). */
void lsys_overlay_lines (const lsys_gl *gl, const lsys_vline *lines, size_t n, float scale);

#endif
