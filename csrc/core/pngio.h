/*
** Reading and writing PNG images with libpng (rendered pictures, textures).
**
** The file pair is pngio.[ch], not png.[ch]: csrc/ is on the include path,
** and a csrc/png.h would hide libpng's own <png.h>.
*/
#ifndef LSYS_PNGIO_H
#define LSYS_PNGIO_H

#include "common.h"

/* Largest width or height accepted when reading. */
#define LSYS_PNG_MAXSIZE 32768

/*
** Writes the w x h image 'rgba' (4 bytes per pixel, top row first) to
** 'path' as an 8-bit PNG: RGBA when 'alpha' is nonzero, else RGB (the
** alpha bytes are dropped). The file is replaced atomically (outfile.h):
** a failure leaves what was at 'path' as it was. Returns LSYS_OK, or
** LSYS_EARG with e->msg naming the file and the reason.
*/
int lsys_pngio_write (const char *path, const uint8_t *rgba, int w, int h, int alpha,
                      lsys_error *e);

/*
** Encodes the w x h image 'rgba' as lsys_pngio_write does, into a new block
** *out (free it with LSYS_FREE) of *len bytes: a .glb embeds an SGI
** texture so. Returns LSYS_OK, or LSYS_ENOMEM / LSYS_EARG with e->msg.
*/
int lsys_pngio_encode (const uint8_t *rgba, int w, int h, int alpha, unsigned char **out,
                       size_t *len, lsys_error *e);

/*
** Reads any PNG (grey, palette, 16-bit, interlaced, with or without alpha)
** as 8-bit RGBA, top row first, into a new block *rgba (free it with
** LSYS_FREE) of *w x *h pixels. Returns LSYS_OK; LSYS_ESYNTAX for a file
** that is not a PNG or is damaged, LSYS_EARG when it cannot be opened,
** LSYS_ELIMIT when it is larger than LSYS_PNG_MAXSIZE, LSYS_ENOMEM; e->msg
** names the file. On failure *rgba is NULL.
*/
int lsys_pngio_read (const char *path, uint8_t **rgba, int *w, int *h, lsys_error *e);

#endif
