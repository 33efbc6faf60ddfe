/*
** SGI image files (sgiio.h), written from Paul Haeberli's description of the
** format (version 1.0). Every number is big-endian. The 512-byte header:
**
**     0  magic       2 bytes  474
**     2  storage     1        0 verbatim, 1 RLE
**     3  bpc         1        bytes per value: 1 or 2
**     4  dimension   2        1: one row of one channel; 2: one channel;
**                             3: zsize channels
**     6  xsize, ysize, zsize  2 each, unsigned
**    12  pixmin, pixmax       4 each (not used, see below)
**    20  dummy 4, image name 80
**   104  colormap    4        0 normal; 1 dithered, 2 screen, 3 a colour map
**                             (the obsolete kinds: refused)
**   108  padding to 512
**
** Verbatim storage: the channels one after the other, each as ysize rows of
** xsize values, bottom row first. RLE: a table of ysize * zsize 4-byte file
** offsets of rows (row r of channel c at index r + c * ysize), a table of as
** many 4-byte lengths, then the rows' data anywhere after the tables (rows
** may share data). A row is a series of runs, each opened by a count (a
** byte; with 2-byte values a 2-byte word of which only the low byte counts,
** as SGI's own library reads it): bit 0x80 set, the next (count & 0x7f)
** values are copied; clear, the next one value is repeated that many
** times. A count of 0 ends the row; so does the end of its length.
** Messages number rows as the file stores them, from 0 at the bottom.
**
** Channels: 1 is grey (R = G = B, alpha 255), 2 grey and alpha, 3 RGB,
** 4 RGBA; of more, the first four are read and the others ignored (an
** image with extra channels, a mask or a depth, is still a picture).
**
** 2-byte values: the high byte is kept, as pngio.c keeps it of 16-bit PNGs
** (png_set_strip_16), so that both formats give the same 8 bits of the same
** data. pixmax does not scale them: the format does not make writers set it
** (many leave 0 or 255 whatever the data), and a wrong one would make the
** texture black or saturated without a word.
**
** The file is untrusted: every offset and length is checked against its
** size before it is followed, a row must decode to exactly xsize values,
** and the sizes are checked before anything is allocated: each side at most
** LSYS_PNG_MAXSIZE, the pixels within the memory budget, and verbatim data
** no longer than the file. Each run gives at least one value, so a row that
** decodes to xsize values reads at most 2 xsize + 1 counts and values, and
** the first row that does not is an error: the time is bounded by the
** pixels plus the file.
*/
#include <stdio.h>
#include <string.h>

#include "pngio.h"
#include "sgiio.h"

#define HEADER 512

typedef struct sgi {
  const uint8_t *b;       /* the file */
  size_t n;
  const char *name;
  unsigned x, y, z;       /* the sizes; z: the channels the file holds */
  unsigned bpc;           /* bytes per value */
  size_t tables;          /* RLE: where the tables end */
  lsys_error *e;
} sgi;

static unsigned get16 (const uint8_t *p) {
  return (unsigned)p[0] << 8 | p[1];
}

static uint32_t get32 (const uint8_t *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The byte of channel c in an RGBA pixel: grey and alpha go to R and A. */
static unsigned slot (unsigned c, unsigned nch) {
  return nch == 2 && c == 1 ? 3 : c;
}

/* Row r of channel c, verbatim, into every 4th byte from 'out'. */
static void rawrow (const sgi *s, unsigned r, unsigned c, uint8_t *out) {
  const uint8_t *p = s->b + HEADER + ((size_t)c * s->y + r) * s->x * s->bpc;
  unsigned i;
  for (i = 0; i < s->x; i++, p += s->bpc) out[4 * (size_t)i] = *p;
}

/* The offset and length of RLE row r of channel c. */
static void rlespan (const sgi *s, unsigned r, unsigned c, uint32_t *start, uint32_t *len) {
  size_t k = (size_t)r + (size_t)c * s->y;
  *start = get32(s->b + HEADER + 4 * k);
  *len = get32(s->b + HEADER + 4 * ((size_t)s->y * s->z + k));
}

/* Checks that RLE row r of channel c lies in the file after the tables. */
static int rlecheck (const sgi *s, unsigned r, unsigned c) {
  uint32_t start, len;
  rlespan(s, r, c, &start, &len);
  if (start < s->tables)
    return lsys_seterror(s->e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': RLE row %u of "
                         "channel %u starts at offset %lu, inside the header or the tables",
                         s->name, r, c, (unsigned long)start);
  if ((uint64_t)start + len > s->n)
    return lsys_seterror(s->e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': RLE row %u of "
                         "channel %u runs past the end of the file (offset %lu, length %lu, "
                         "file %zu bytes)", s->name, r, c, (unsigned long)start,
                         (unsigned long)len, s->n);
  return LSYS_OK;
}

/* Decodes RLE row r of channel c (checked by rlecheck) into every 4th byte
** from 'out'. Values past the xsize-th are counted, not stored, so that the
** message can say how many the row holds. */
static int rlerow (const sgi *s, unsigned r, unsigned c, uint8_t *out) {
  const unsigned bpc = s->bpc;
  const uint8_t *p, *end;
  uint64_t count = 0;
  uint32_t start, len;
  rlespan(s, r, c, &start, &len);
  p = s->b + start;
  end = p + len;
  for (;;) {
    unsigned head, m, i;
    if (p == end) break;                          /* the end of its length ends the row */
    if ((size_t)(end - p) < bpc) goto past;
    head = p[bpc - 1];
    p += bpc;
    if ((m = head & 0x7f) == 0) break;
    if (head & 0x80) {                            /* m values copied */
      if ((size_t)(end - p) < (size_t)m * bpc) goto past;
      for (i = 0; i < m; i++, p += bpc, count++)
        if (count < s->x) out[4 * (size_t)count] = *p;
    }
    else {                                        /* one value, m times */
      if ((size_t)(end - p) < bpc) goto past;
      for (i = 0; i < m && count < s->x; i++, count++) out[4 * (size_t)count] = *p;
      count += m - i;
      p += bpc;
    }
  }
  if (count != s->x)
    return lsys_seterror(s->e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': RLE row %u of "
                         "channel %u decodes to %llu values, not %u", s->name, r, c,
                         (unsigned long long)count, s->x);
  return LSYS_OK;
past:
  return lsys_seterror(s->e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': RLE row %u of "
                       "channel %u runs past its length (%lu bytes)", s->name, r, c,
                       (unsigned long)len);
}

int lsys_sgiio_decode (const uint8_t *bytes, size_t n, const char *name, uint8_t **rgba,
                       int *w, int *h, lsys_error *e) {
  sgi s;
  unsigned storage, dim, nch, c, r;
  uint32_t cmap;
  uint64_t npix;
  uint8_t *px;
  *rgba = NULL;
  *w = *h = 0;
  if (n < 2 || get16(bytes) != LSYS_SGI_MAGIC)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "'%s' is not an SGI image", name);
  if (n < HEADER)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': truncated header "
                         "(%zu of %d bytes)", name, n, HEADER);
  s.b = bytes;
  s.n = n;
  s.name = name;
  s.e = e;
  storage = bytes[2];
  s.bpc = bytes[3];
  dim = get16(bytes + 4);
  cmap = get32(bytes + 104);
  if (storage > 1)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': storage %u (0 "
                         "verbatim or 1 RLE expected)", name, storage);
  if (s.bpc != 1 && s.bpc != 2)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': %u bytes per "
                         "channel (1 or 2 expected)", name, s.bpc);
  if (dim < 1 || dim > 3)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': dimension %u (1, "
                         "2 or 3 expected)", name, dim);
  if (cmap != 0)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': colormap %lu (%s) "
                         "is not supported, only normal images (colormap 0)", name,
                         (unsigned long)cmap, cmap == 1 ? "dithered" : cmap == 2 ? "screen"
                         : cmap == 3 ? "a colour map, not an image" : "unknown");
  /* dimension 1 is one row of one channel, 2 one channel, whatever ysize and zsize say */
  s.x = get16(bytes + 6);
  s.y = dim == 1 ? 1 : get16(bytes + 8);
  s.z = dim == 3 ? get16(bytes + 10) : 1;
  if (s.x == 0 || s.y == 0 || s.z == 0)
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': empty image (%ux%u "
                         "pixels, %u channels)", name, s.x, s.y, s.z);
  if (s.x > LSYS_PNG_MAXSIZE || s.y > LSYS_PNG_MAXSIZE)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot read '%s': %ux%u pixels is "
                         "larger than the limit of %d", name, s.x, s.y, LSYS_PNG_MAXSIZE);
  npix = (uint64_t)s.x * s.y;
  if (npix * 4 > SIZE_MAX / 2)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot read '%s': %ux%u pixels is "
                         "too large for this machine", name, s.x, s.y);
  if ((double)npix * 4 > (double)lsys_common_memory_limit()) {
    char b1[32], b2[32];
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "cannot read '%s': %ux%u pixels need "
                         "%s, more than max_memory (%s)", name, s.x, s.y,
                         lsys_common_fmtsize(b1, (size_t)(npix * 4)),
                         lsys_common_fmtsize(b2, lsys_common_memory_limit()));
  }
  nch = s.z < 4 ? s.z : 4;
  /* what the file must hold, before anything is allocated */
  if (storage == 0) {
    uint64_t need = HEADER + npix * s.z * s.bpc;
    if (need > n)
      return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': truncated: %ux%u "
                           "pixels of %u channel%s need %llu bytes, the file has %zu", name,
                           s.x, s.y, s.z, s.z == 1 ? "" : "s", (unsigned long long)need, n);
    s.tables = HEADER;
  }
  else {
    uint64_t need = HEADER + (uint64_t)8 * s.y * s.z;
    if (need > n)
      return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot read '%s': truncated: the "
                           "RLE tables of %u rows need %llu bytes, the file has %zu", name,
                           s.y * s.z, (unsigned long long)need, n);
    s.tables = (size_t)need;
    for (c = 0; c < nch; c++)
      for (r = 0; r < s.y; r++) {
        int st = rlecheck(&s, r, c);
        if (st != LSYS_OK) return st;
      }
  }
  px = (uint8_t *)LSYS_MALLOC((size_t)npix * 4);
  if (px == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot read '%s': not enough memory "
                         "for %ux%u pixels", name, s.x, s.y);
  /* the file's bottom row is the picture's last */
  for (c = 0; c < nch; c++)
    for (r = 0; r < s.y; r++) {
      uint8_t *out = px + (size_t)4 * s.x * (s.y - 1 - r) + slot(c, nch);
      int st = LSYS_OK;
      if (storage == 0) rawrow(&s, r, c, out);
      else st = rlerow(&s, r, c, out);
      if (st != LSYS_OK) {
        LSYS_FREE(px);
        return st;
      }
    }
  {
    size_t i;
    for (i = 0; i < npix; i++) {
      uint8_t *q = px + 4 * i;
      if (nch <= 2) q[1] = q[2] = q[0];
      if (nch == 1 || nch == 3) q[3] = 255;
    }
  }
  *rgba = px;
  *w = (int)s.x;
  *h = (int)s.y;
  return LSYS_OK;
}

int lsys_sgiio_read (const char *path, uint8_t **rgba, int *w, int *h, lsys_error *e) {
  size_t n;
  int code;
  char *buf;
  *rgba = NULL;
  *w = *h = 0;
  if ((buf = lsys_common_readfile(path, LSYS_SGI_MAXFILE, &n, e)) == NULL) return e->code;
  code = lsys_sgiio_decode((const uint8_t *)buf, n, path, rgba, w, h, e);
  LSYS_FREE(buf);
  return code;
}
