/*
** Panes of the viewer window (glfw_viewer.c): the window split into the 3D
** scene's viewport and up to LSYS_VPANES_MAX image panes, each showing an
** RGBA image the caller posts (the sketch window's drawing surface, its
** toolbar, its function plots). A pane reports the pointer in the pixels
** of its image, so the caller never sees the window's size.
**
** The layout is given in fractions of the window (x0, y0, x1, y1; y down),
** so resizing keeps it. An image is drawn as large as fits in its pane,
** keeping its aspect, centred; the rest of the pane is the pane's
** background colour.
**
** Threads: the caller posts layouts, images and status text under the
** panes' own mutex (lsys_vpanes_set_*); the viewer thread takes them at
** the top of its loop (lsys_vpanes_take) and from then on reads its own
** copy without locking. The placement arithmetic is plain (no GL, no
** window) and tested on its own (tests/c/test_vpanes.c).
*/
#ifndef LSYS_VPANES_H
#define LSYS_VPANES_H

#include <pthread.h>

#include "render.h"

#define LSYS_VPANES_MAX 4

/* Where things go: 'on' 0 is the plain viewer (the scene fills the window). */
typedef struct lsys_vlayout {
  int on;
  float scene[4];               /* x0, y0, x1, y1 in [0, 1], y down */
  int npanes;
  float pane[LSYS_VPANES_MAX][4];
  uint8_t bg[LSYS_VPANES_MAX][4];   /* the pane's colour around its image */
} lsys_vlayout;

typedef struct lsys_vimage {
  uint8_t *rgba;                /* owned, w * h * 4 bytes, top row first */
  int w, h;
  int fresh;                    /* changed since it was uploaded */
} lsys_vimage;

typedef struct lsys_vpanes {
  pthread_mutex_t mu;
  /* posted by the caller, under mu */
  int changed;
  lsys_vlayout newlay;
  lsys_vimage newimg[LSYS_VPANES_MAX];
  char newmsg[256], newhelp[1024];
  /* the viewer thread's own */
  lsys_vlayout lay;
  lsys_vimage img[LSYS_VPANES_MAX];
  char msg[256];                /* replaces the status line when not empty */
  char help[1024];              /* replaces the help text when not empty */
  unsigned tex[LSYS_VPANES_MAX];    /* GL texture names (0: none) */
  int texw[LSYS_VPANES_MAX], texh[LSYS_VPANES_MAX];   /* their power-of-two sizes */
  uint8_t *pad;                 /* an image padded to a power-of-two size for uploading */
  size_t padcap;
} lsys_vpanes;

void lsys_vpanes_init (lsys_vpanes *p);

/* Frees the images (textures must have been released). */
void lsys_vpanes_free (lsys_vpanes *p);

/* The caller's side: post a layout, an image for pane k (copied; LSYS_OK,
** LSYS_ENOMEM or LSYS_EARG for a bad pane or size), the status text and
** the help text (NULL leaves one as it is). */
void lsys_vpanes_set_layout (lsys_vpanes *p, const lsys_vlayout *lay);
int lsys_vpanes_set_image (lsys_vpanes *p, int k, const uint8_t *rgba, int w, int h);
void lsys_vpanes_set_text (lsys_vpanes *p, const char *msg, const char *help);

/* The viewer thread: takes what was posted; 1 when something changed. */
int lsys_vpanes_take (lsys_vpanes *p);

/* A rectangle of the window in window coordinates (x, y of the top left
** corner, w, h), from fractions 'r' of a winw x winh window. */
void lsys_vpanes_rect (const float r[4], int winw, int winh, int out[4]);

/* The scene's rectangle in window coordinates: the whole window unless the
** layout is on. */
void lsys_vpanes_scene (const lsys_vpanes *p, int winw, int winh, int out[4]);

/* The scene's rectangle sr (window coordinates, lsys_vpanes_scene) in the
** pixels of a framebuffer fbh high of a window winh high: x, y (counted up
** from the bottom, as GL does), w, h. */
void lsys_vpanes_fbrect (const int sr[4], int winh, int fbh, int r[4]);

/*
** What the window point (x, y) is over: the pane's index (0-based), with
** (*px, *py) the point in the pixels of the pane's image (in the pane's
** own pixels when it has none; outside the image, beyond its edges);
** LSYS_VPANE_SCENE for the scene; LSYS_VPANE_NONE for neither.
*/
#define LSYS_VPANE_SCENE (-1)
#define LSYS_VPANE_NONE (-2)
int lsys_vpanes_hit (const lsys_vpanes *p, int winw, int winh, double x, double y,
                     double *px, double *py);

/* The same mapping for pane k whatever the point (a drag that left the pane). */
void lsys_vpanes_map (const lsys_vpanes *p, int k, int winw, int winh, double x, double y,
                      double *px, double *py);

/* Draws the panes over a fbw x fbh framebuffer of a winw x winh window
** (current context 'gl'), uploading images that changed. */
void lsys_vpanes_draw (lsys_vpanes *p, const lsys_gl *gl, int winw, int winh, int fbw, int fbh);

/* Deletes the textures (the context current). */
void lsys_vpanes_release (lsys_vpanes *p, const lsys_gl *gl);

#endif
