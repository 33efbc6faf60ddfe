/*
** Textures (seed 004 §5, Appendix B.2): images read with libpng (PNG
** replaces cpfg's rgb/rle/tga), with the filters and environment mode of a
** `texture:` view entry.
*/
#ifndef LSYS_TEXTURE_H
#define LSYS_TEXTURE_H

#include "common.h"

enum { LSYS_TEX_MODULATE = 0, LSYS_TEX_DECAL = 1 };

typedef struct lsys_texture {
  uint8_t *rgba;          /* w x h pixels, 4 bytes each, top row first */
  int w, h;
  int mag_linear;         /* H: magnification filter: 1 linear, 0 nearest (default) */
  int min_linear;         /* L: minification filter: 1 linear, 0 nearest (default) */
  int mode;               /* E: LSYS_TEX_MODULATE (default) or LSYS_TEX_DECAL */
  int per_surface;        /* S: map onto a whole predefined surface, not per patch */
  int intensity;          /* modulate by I = 0.299 R + 0.587 G + 0.114 B (§5), not by RGB */
  char *path;             /* the file, for export writers (may be NULL) */
} lsys_texture;

void lsys_texture_init (lsys_texture *t);
void lsys_texture_free (lsys_texture *t);

/* Reads a PNG file into 't' (filters and mode left as they are). A grey
** image sets 'intensity'. Returns LSYS_OK or an error with e->msg naming
** the file. */
int lsys_texture_load (lsys_texture *t, const char *path, lsys_error *e);

#endif
