/*
** Pictures read back from the viewer window (glfw_viewer.c): what the S key
** saves. A screenshot is the back buffer just drawn; a series (S while
** animating) is every frame of the snapshot, drawn in turn by the caller
** through one camera into the back buffer (never shown) and read back, each
** written as step-NNNN.png into a folder. Plain GL reads through the
** function pointers given and libpng: no window, so a test can fake the GL
** side (tests/c/test_vshot.c).
*/
#ifndef LSYS_VSHOT_H
#define LSYS_VSHOT_H

#include "viewer.h"

typedef struct lsys_vshot {
  void (LSYS_GLAPI *ReadPixels) (int x, int y, int w, int h, unsigned fmt, unsigned type,
                                 void *px);
  void (LSYS_GLAPI *ReadBuffer) (unsigned mode);
  void (LSYS_GLAPI *PixelStorei) (unsigned pname, int v);
  uint8_t *pixels;              /* scratch: a picture and a row */
  size_t cap;
  int seq;                      /* where the next lsys-NNN.png name is looked for */
} lsys_vshot;

/* A file name lsys-NNN.png that does not exist yet in the current directory
** (the next free number, from 001 to 999 and round again) into buf[n]. */
void lsys_vshot_autoname (lsys_vshot *r, char *buf, size_t n);

/* Writes the rectangle rect = {x, y, w, h} of the back buffer (y counted up
** from the bottom, as GL does) to the PNG file 'path' (outfile.h: whole or
** not at all). Returns LSYS_OK, or an error with e->msg. */
int lsys_vshot_png (lsys_vshot *r, const int rect[4], const char *path, lsys_error *e);

/* The screenshot of the whole back buffer (w x h) to 'path' ("": the next
** lsys-NNN.png): fills the SCREENSHOT fields of 'ev' (path, ok, msg). */
void lsys_vshot_screenshot (lsys_vshot *r, const char *path, int w, int h, lsys_vevent *ev);

/* Draws frame k of the snapshot into the back buffer's rectangle r. */
typedef int (*lsys_vshot_draw) (void *ctx, size_t k, const int r[4], lsys_error *e);

/*
** The series of 's': for each frame k, draw(ctx, k) and the rectangle 'rect'
** written to DIR/step-NNNN.png, NNNN the frame's step (k when it has none),
** DIR s->framesdir ("lsys-frames" when empty), made when missing. Stops at
** the first failure. Fills the FRAMES fields of 'ev': path (DIR), ok, count,
** first and step (the first and last steps written), msg.
*/
void lsys_vshot_series (lsys_vshot *r, const lsys_vsnap *s, const int rect[4],
                        lsys_vshot_draw draw, void *ctx, lsys_vevent *ev);

void lsys_vshot_free (lsys_vshot *r);

#endif
