/*
** Texture images (texture.h): a PNG or SGI image file read into RGBA
** pixels, with the settings of a cpfg `texture:` entry.
*/
#define _XOPEN_SOURCE 700       /* fileno, fstat */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "pngio.h"
#include "sgiio.h"
#include "texture.h"

void lsys_texture_init (lsys_texture *t) {
  memset(t, 0, sizeof *t);
  t->mode = LSYS_TEX_MODULATE;
}

void lsys_texture_free (lsys_texture *t) {
  LSYS_FREE(t->rgba);
  LSYS_FREE(t->path);
  t->rgba = NULL;
  t->path = NULL;
  t->w = t->h = 0;
}

int lsys_texture_copy (lsys_texture *dst, const lsys_texture *s) {
  size_t n = (size_t)s->w * (size_t)s->h * 4;
  *dst = *s;
  dst->rgba = NULL;
  dst->path = NULL;
  if (s->rgba != NULL && n > 0) {
    if ((dst->rgba = (uint8_t *)LSYS_MALLOC(n)) == NULL) goto fail;
    memcpy(dst->rgba, s->rgba, n);
  }
  if (s->path != NULL) {
    size_t len = strlen(s->path) + 1;
    if ((dst->path = (char *)LSYS_MALLOC(len)) == NULL) goto fail;
    memcpy(dst->path, s->path, len);
  }
  return LSYS_OK;
fail:
  lsys_texture_free(dst);
  return LSYS_ENOMEM;
}

/* Every pixel has equal red, green and blue: a single-channel image (§5). */
static int isgrey (const uint8_t *px, size_t n) {
  size_t i;
  for (i = 0; i < n; i++, px += 4)
    if (px[0] != px[1] || px[1] != px[2]) return 0;
  return 1;
}

enum { NOTIMAGE, PNG, SGI };

/* Sets *kind to what the file 'path' holds, by its first bytes (not by its
** name: cpfg's models name SGI images .rgb, .rgba, .bw, .sgi, .int or
** .inta). Returns LSYS_OK, or LSYS_EARG when it cannot be opened or read
** (the messages of lsys_pngio_read). */
static int sniff (const char *path, int *kind, lsys_error *e) {
  static const uint8_t pngsig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  uint8_t b[8];
  size_t n;
  struct stat st;
  FILE *f = fopen(path, "rb");
  int err;
  if (f == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s' for reading: %s", path,
                         strerror(errno));
  if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
    const char *why = fstat(fileno(f), &st) != 0 ? strerror(errno)
                      : S_ISDIR(st.st_mode) ? strerror(EISDIR) : "not a regular file";
    fclose(f);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path, why);
  }
  n = fread(b, 1, sizeof b, f);
  err = ferror(f) ? errno : 0;
  fclose(f);
  if (err) return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path,
                                strerror(err));
  *kind = n == sizeof b && memcmp(b, pngsig, sizeof b) == 0 ? PNG
          : n >= 2 && (b[0] << 8 | b[1]) == LSYS_SGI_MAGIC ? SGI : NOTIMAGE;
  return LSYS_OK;
}

int lsys_texture_load (lsys_texture *t, const char *path, lsys_error *e) {
  uint8_t *px = NULL;
  char *copy;
  size_t len = strlen(path);
  int w, h, kind = NOTIMAGE, st = sniff(path, &kind, e);
  if (st != LSYS_OK) return st;
  if (kind == NOTIMAGE)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "'%s' is not a PNG or SGI image", path);
  st = kind == PNG ? lsys_pngio_read(path, &px, &w, &h, e) : lsys_sgiio_read(path, &px, &w, &h, e);
  if (st != LSYS_OK) return st;
  copy = (char *)LSYS_MALLOC(len + 1);
  if (copy == NULL) {
    LSYS_FREE(px);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot read '%s': out of memory", path);
  }
  memcpy(copy, path, len + 1);
  LSYS_FREE(t->rgba);
  LSYS_FREE(t->path);
  t->rgba = px;
  t->w = w;
  t->h = h;
  t->path = copy;
  t->intensity = isgrey(px, (size_t)w * (size_t)h);
  return LSYS_OK;
}

int lsys_texture_hasalpha (const lsys_texture *t) {
  size_t i, n = t->rgba ? (size_t)t->w * (size_t)t->h : 0;
  for (i = 0; i < n; i++)
    if (t->rgba[4 * i + 3] != 255) return 1;
  return 0;
}
