/*
** Reading SGI image files (.rgb, .rgba, .bw, .sgi, .int, .inta): the format
** of Paul Haeberli's "SGI Image File Format" (version 1.0), which cpfg
** models use for textures. Read only; lsys writes PNG (pngio.h).
*/
#ifndef LSYS_SGIIO_H
#define LSYS_SGIIO_H

#include "common.h"

/* The first two bytes of every SGI image, big-endian. */
#define LSYS_SGI_MAGIC 474

/* Largest file read by lsys_sgiio_read (the whole file is read into memory). */
#define LSYS_SGI_MAXFILE ((size_t)1 << 30)

/*
** Reads the SGI image file 'path' as 8-bit RGBA, top row first (as
** lsys_pngio_read), into a new block *rgba (free it with LSYS_FREE) of *w x *h
** pixels: verbatim or RLE storage, 1 or 2 bytes per channel, 1 to 4
** channels (grey, grey and alpha, RGB, RGBA; channels after the fourth are
** ignored). Returns LSYS_OK; LSYS_ESYNTAX for a file that is not an SGI
** image, is damaged or is not a normal image (colormap field not 0);
** LSYS_EARG when it cannot be opened or read; LSYS_ELIMIT when a side is
** larger than LSYS_PNG_MAXSIZE or the file larger than LSYS_SGI_MAXFILE;
** LSYS_EMEMORY when the pixels would exceed the memory budget
** (lsys_common_memory_limit); LSYS_ENOMEM. e->msg names the file. On failure
** *rgba is NULL and *w = *h = 0.
*/
int lsys_sgiio_read (const char *path, uint8_t **rgba, int *w, int *h, lsys_error *e);

/*
** The same from the n bytes of a file in memory; 'name' names it in the
** messages. Reads nothing outside bytes[0 .. n-1] whatever they hold.
*/
int lsys_sgiio_decode (const uint8_t *bytes, size_t n, const char *name, uint8_t **rgba,
                       int *w, int *h, lsys_error *e);

#endif
