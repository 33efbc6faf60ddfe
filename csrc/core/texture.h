/*
** Textures (cpfg guide §5, Appendix B.2): PNG images (read with libpng,
** pngio.h) and SGI images (cpfg's .rgb and its kin, sgiio.h), told apart by
** their first bytes, with the filters and environment mode of a `texture:`
** view entry. cpfg's Utah RLE and Targa files are not read.
**
** Texture coordinates follow OpenGL (and cpfg, and OBJ): (0, 0) is the
** bottom left corner of the image, u grows to the right, v upwards, and
** both repeat outside [0, 1]. The pixels are kept top row first, as a PNG
** stores them (an SGI image's rows, stored bottom first, are turned over);
** the renderer and the glTF writer, whose images start at the top, flip v
** themselves.
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

/* An empty texture (no pixels, no path) with the default settings. */
void lsys_texture_init (lsys_texture *t);
/* Frees the pixels and the path and leaves 't' empty (idempotent). */
void lsys_texture_free (lsys_texture *t);

/* Reads a PNG or SGI image file into 't' (filters and mode left as they
** are): a file starting with the PNG signature goes to lsys_pngio_read, one
** starting with the SGI magic number to lsys_sgiio_read, whatever its name.
** A grey image (every pixel has R = G = B) sets 'intensity', any other
** clears it. On failure 't' is unchanged. Returns LSYS_OK, or the code of
** the reader (LSYS_EARG: cannot open; LSYS_ESYNTAX: damaged, or "not a PNG
** or SGI image"; LSYS_ELIMIT; LSYS_EMEMORY; LSYS_ENOMEM) with e->msg naming
** the file. */
int lsys_texture_load (lsys_texture *t, const char *path, lsys_error *e);

/* Makes 'dst' a copy of 's' (pixels, path, settings). Returns LSYS_OK, or
** LSYS_ENOMEM leaving 'dst' empty. */
int lsys_texture_copy (lsys_texture *dst, const lsys_texture *s);

/* 1 when some pixel of 't' is not fully opaque (alpha < 255), else 0. */
int lsys_texture_hasalpha (const lsys_texture *t);

/* The intensity of an RGB pixel (§5), rounded: (299 R + 587 G + 114 B) / 1000. */
static inline uint8_t lsys_texture_intensity (const uint8_t *px) {
  return (uint8_t)((299u * px[0] + 587u * px[1] + 114u * px[2] + 500u) / 1000u);
}

#endif
