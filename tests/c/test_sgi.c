/*
** C unit tests for reading SGI images (sgiio.h) and loading them as textures
** (texture.h): images built in memory, verbatim and RLE, 1 to 5 channels, 1
** and 2 bytes per value, dimensions 1 to 3; the exact pixels of a 3 x 2
** image, top row first; rows that share data or end without a 0 count; and
** every error, with its code, the file's name and the reason in the message,
** no pixels and nothing left allocated.
*/
#define _XOPEN_SOURCE 700
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "talloc.h"
/* sgiio.c and texture.c compiled in with counting allocators (pngio.o comes from the
** library; no PNG is read here: test_render.c loads PNG textures) */
#include "common.c"
#include "sgiio.c"
#include "texture.c"
#include "testdir.h"

#define NAME "mem.rgb"
#define MAXB (1 << 16)

static const char *dir;     /* the test's folder (testdir.h) */

/* ---------------------------------------------------------------------- */
/* writing SGI images */

static void put16 (uint8_t *p, unsigned v) { p[0] = (uint8_t)(v >> 8); p[1] = (uint8_t)v; }

static void put32 (uint8_t *p, uint32_t v) {
  p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16); p[2] = (uint8_t)(v >> 8);
  p[3] = (uint8_t)v;
}

/* The 512-byte header, zeros but for the fields given. */
static void header (uint8_t *b, int storage, int bpc, int dim, int x, int y, int z) {
  memset(b, 0, 512);
  put16(b, 474);
  b[2] = (uint8_t)storage;
  b[3] = (uint8_t)bpc;
  put16(b + 4, (unsigned)dim);
  put16(b + 6, (unsigned)x);
  put16(b + 8, (unsigned)y);
  put16(b + 10, (unsigned)z);
  put32(b + 16, bpc == 1 ? 255 : 65535);          /* pixmax */
  memcpy(b + 24, "test image", 10);
}

/* Value i of row r of channel c of the test pictures (as the file stores them: row 0 at
** the bottom); 'big' makes it a 2-byte value whose high byte is that. */
static unsigned val (int c, int r, int i, int big) {
  unsigned v = (unsigned)((c + 1) * 50 + r * 10 + i) & 0xff;
  return big ? v << 8 | (unsigned)((i * 37 + r) & 0xff) : v;
}

static size_t putval (uint8_t *p, unsigned v, int bpc) {
  if (bpc == 2) put16(p, v);
  else p[0] = (uint8_t)v;
  return (size_t)bpc;
}

/* A verbatim image x * y * z of the values val(); returns its size. */
static size_t verbatim (uint8_t *b, int bpc, int dim, int x, int y, int z) {
  size_t n = 512;
  int c, r, i;
  int ry = dim == 1 ? 1 : y, rz = dim == 3 ? z : 1;
  header(b, 0, bpc, dim, x, y, z);
  for (c = 0; c < rz; c++)
    for (r = 0; r < ry; r++)
      for (i = 0; i < x; i++) n += putval(b + n, val(c, r, i, bpc == 2), bpc);
  return n;
}

/* One row of RLE runs for the 'x' values v[]: a repeat run for 3 or more equal values,
** else literal runs, each at most 127; a 0 count at the end unless 'noend'. */
static size_t rlerun (uint8_t *p, const unsigned *v, int x, int bpc, int noend) {
  size_t n = 0;
  int i = 0;
  while (i < x) {
    int k = 1;
    while (i + k < x && k < 127 && v[i + k] == v[i]) k++;
    if (k >= 3) {
      n += putval(p + n, (unsigned)k, bpc);
      n += putval(p + n, v[i], bpc);
      i += k;
    }
    else {
      int j = i;
      while (j < x && j - i < 127 && !(j + 2 < x && v[j] == v[j + 1] && v[j] == v[j + 2]))
        j++;
      n += putval(p + n, 0x80u | (unsigned)(j - i), bpc);
      for (; i < j; i++) n += putval(p + n, v[i], bpc);
    }
  }
  if (!noend) n += putval(p + n, 0, bpc);
  return n;
}

/* An RLE image of the values 'fn'(c, r, i); identical rows share their data when
** 'share'; the rows end without a 0 count when 'noend'. Returns its size. */
static size_t rle (uint8_t *b, int bpc, int dim, int x, int y, int z,
                   unsigned (*fn) (int, int, int, int), int share, int noend) {
  int ry = dim == 1 ? 1 : y, rz = dim == 3 ? z : 1, c, r, i;
  size_t n = 512 + (size_t)8 * ry * rz, k;
  static unsigned v[70000], prev[70000];
  header(b, 1, bpc, dim, x, y, z);
  for (c = 0; c < rz; c++)
    for (r = 0; r < ry; r++) {
      k = (size_t)r + (size_t)c * ry;
      for (i = 0; i < x; i++) v[i] = fn(c, r, i, bpc == 2);
      if (share && k > 0 && memcmp(v, prev, sizeof v[0] * (size_t)x) == 0) {
        memcpy(b + 512 + 4 * k, b + 512 + 4 * (k - 1), 4);
        memcpy(b + 512 + 4 * ((size_t)ry * rz + k), b + 512 + 4 * ((size_t)ry * rz + k - 1), 4);
        continue;
      }
      put32(b + 512 + 4 * k, (uint32_t)n);
      {
        size_t len = rlerun(b + n, v, x, bpc, noend);
        put32(b + 512 + 4 * ((size_t)ry * rz + k), (uint32_t)len);
        n += len;
      }
      memcpy(prev, v, sizeof v[0] * (size_t)x);
      assert(n < MAXB);
    }
  return n;
}

/* ---------------------------------------------------------------------- */
/* reading them */

static uint8_t buf[MAXB];

/* Decodes b[0..n-1], which must succeed as a w x h image; returns the pixels. */
static uint8_t *ok (const uint8_t *b, size_t n, int w, int h) {
  uint8_t *px;
  int gw, gh;
  lsys_error e;
  int st = lsys_sgiio_decode(b, n, NAME, &px, &gw, &gh, &e);
  if (st != LSYS_OK) fprintf(stderr, "unexpected: %s\n", e.msg);
  assert(st == LSYS_OK && px != NULL && gw == w && gh == h);
  return px;
}

/* Decodes b[0..n-1], which must fail with 'code' and a message naming the file and
** containing 'what', allocating nothing that is left. */
static void bad (const uint8_t *b, size_t n, int code, const char *what) {
  uint8_t *px = (uint8_t *)1;
  int w = -1, h = -1;
  long live = nlive;
  lsys_error e;
  int st = lsys_sgiio_decode(b, n, NAME, &px, &w, &h, &e);
  if (st != code || strstr(e.msg, what) == NULL)
    fprintf(stderr, "expected %d '%s', got %d '%s'\n", code, what, st, st ? e.msg : "");
  assert(st == code && e.code == code);
  assert(strstr(e.msg, what) != NULL && strstr(e.msg, "'" NAME "'") != NULL);
  assert(px == NULL && w == 0 && h == 0 && nlive == live);
}

/* Asserts pixel (i, j) of the w-wide image (top row first) is r g b a. */
static void pixel (const uint8_t *px, int w, int i, int j, int r, int g, int b, int a) {
  const uint8_t *p = px + 4 * ((size_t)j * w + i);
  if (p[0] != r || p[1] != g || p[2] != b || p[3] != a) {
    fprintf(stderr, "pixel (%d, %d) is %d %d %d %d, expected %d %d %d %d\n", i, j, p[0], p[1],
            p[2], p[3], r, g, b, a);
    assert(0);
  }
}

/* Checks the pixels of the w x h picture of val() with 'nch' channels in the file. */
static void checkval (const uint8_t *px, int w, int h, int nch) {
  int i, j;
  for (j = 0; j < h; j++)
    for (i = 0; i < w; i++) {
      int r = h - 1 - j;                          /* the file's row: the bottom first */
      int g0 = (int)val(0, r, i, 0);
      switch (nch) {
        case 1: pixel(px, w, i, j, g0, g0, g0, 255); break;
        case 2: pixel(px, w, i, j, g0, g0, g0, (int)val(1, r, i, 0)); break;
        case 3: pixel(px, w, i, j, g0, (int)val(1, r, i, 0), (int)val(2, r, i, 0), 255); break;
        default:
          pixel(px, w, i, j, g0, (int)val(1, r, i, 0), (int)val(2, r, i, 0),
                (int)val(3, r, i, 0));
      }
    }
}

/* The 3 x 2 RGB picture, pixel by pixel: the file's second row is the top one. */
static void test_exact (void) {
  static const int want[2][3][3] = {
    { {60, 110, 160}, {61, 111, 161}, {62, 112, 162} },  /* top: the file's row 1 */
    { {50, 100, 150}, {51, 101, 151}, {52, 102, 152} },  /* bottom: the file's row 0 */
  };
  int pass, i, j;
  for (pass = 0; pass < 4; pass++) {
    int bpc = 1 + (pass & 1);
    size_t n = pass < 2 ? verbatim(buf, bpc, 3, 3, 2, 3) : rle(buf, bpc, 3, 3, 2, 3, val, 0, 0);
    uint8_t *px = ok(buf, n, 3, 2);
    for (j = 0; j < 2; j++)
      for (i = 0; i < 3; i++) pixel(px, 3, i, j, want[j][i][0], want[j][i][1], want[j][i][2], 255);
    tfree(px);
  }
  /* the verbatim file itself: channel 0's rows, then channel 1's, ... */
  verbatim(buf, 1, 3, 3, 2, 3);
  assert(buf[512] == 50 && buf[515] == 60 && buf[518] == 100 && buf[529] == 162);
}

/* Every channel count, both storages and value sizes, and the dimensions. */
static void test_channels (void) {
  int z, pass;
  for (z = 1; z <= 5; z++)
    for (pass = 0; pass < 4; pass++) {
      int bpc = 1 + (pass & 1), w = 5, h = 4;
      size_t n = pass < 2 ? verbatim(buf, bpc, 3, w, h, z)
                          : rle(buf, bpc, 3, w, h, z, val, 0, 0);
      uint8_t *px = ok(buf, n, w, h);
      checkval(px, w, h, z);                      /* a fifth channel is ignored */
      tfree(px);
    }
  /* dimension 2: one channel whatever zsize says; dimension 1: one row too */
  {
    size_t n = verbatim(buf, 1, 2, 4, 3, 3);
    uint8_t *px = ok(buf, n, 4, 3);
    checkval(px, 4, 3, 1);
    tfree(px);
    n = verbatim(buf, 1, 1, 6, 7, 9);
    px = ok(buf, n, 6, 1);
    checkval(px, 6, 1, 1);
    tfree(px);
    n = rle(buf, 2, 1, 6, 7, 9, val, 0, 0);
    px = ok(buf, n, 6, 1);
    checkval(px, 6, 1, 1);
    tfree(px);
  }
  /* pixmin, pixmax and the name do not matter */
  {
    size_t n = verbatim(buf, 2, 3, 2, 2, 1);
    uint8_t *px = ok(buf, n, 2, 2), *px2;
    put32(buf + 12, 0xffffffffu);
    put32(buf + 16, 7);
    memset(buf + 24, 0xff, 80);
    px2 = ok(buf, n, 2, 2);
    assert(memcmp(px, px2, 16) == 0);
    tfree(px);
    tfree(px2);
  }
}

/* Stripes of 200 equal values and a literal stretch: runs longer than 127. */
static unsigned stripes (int c, int r, int i, int big) {
  unsigned v = (unsigned)(i < 200 ? 7 * (c + 1) : i < 260 ? i * 3 + r : 90 + (r & 1)) & 0xff;
  return big ? v << 8 : v;
}

/* Long runs, rows that share their data, rows without a 0 count at the end. */
static void test_rle (void) {
  int pass;
  for (pass = 0; pass < 8; pass++) {
    int bpc = 1 + (pass & 1), share = (pass >> 1) & 1, noend = pass >> 2, i, j;
    size_t n = rle(buf, bpc, 3, 300, 6, 3, stripes, share, noend);
    uint8_t *px = ok(buf, n, 300, 6);
    for (j = 0; j < 6; j++)
      for (i = 0; i < 300; i += 7)
        pixel(px, 300, i, j, (int)stripes(0, 5 - j, i, 0), (int)stripes(1, 5 - j, i, 0),
              (int)stripes(2, 5 - j, i, 0), 255);
    tfree(px);
  }
  /* every row of every channel the same data: one row in the file */
  {
    static const uint8_t row[] = {0x80 | 2, 9, 8, 0};
    size_t k, n = 512 + 8 * 4 * 2;
    uint8_t *px;
    header(buf, 1, 1, 3, 2, 4, 2);
    for (k = 0; k < 8; k++) {
      put32(buf + 512 + 4 * k, (uint32_t)n);
      put32(buf + 512 + 32 + 4 * k, sizeof row);
    }
    memcpy(buf + n, row, sizeof row);
    px = ok(buf, n + sizeof row, 2, 4);
    for (k = 0; k < 4; k++) {
      pixel(px, 2, 0, (int)k, 9, 9, 9, 9);
      pixel(px, 2, 1, (int)k, 8, 8, 8, 8);
    }
    tfree(px);
  }
  /* a 2-byte count: only its low byte counts */
  {
    static const uint8_t row[] = {0x7f, 0x83, 1, 2, 3, 4, 5, 6, 0xff, 0};
    size_t n = 512 + 8;
    uint8_t *px;
    header(buf, 1, 2, 2, 3, 1, 1);
    put32(buf + 512, (uint32_t)n);
    put32(buf + 516, sizeof row);
    memcpy(buf + n, row, sizeof row);
    px = ok(buf, n + sizeof row, 3, 1);
    pixel(px, 3, 0, 0, 1, 1, 1, 255);
    pixel(px, 3, 1, 0, 3, 3, 3, 255);
    pixel(px, 3, 2, 0, 5, 5, 5, 255);
    tfree(px);
  }
}

/* A small RLE image whose row 1 of channel 0 is 'row' (len bytes); the others are
** 3 literal values and a 0 count. Returns the size. */
static size_t rlewith (const uint8_t *row, size_t len) {
  static const uint8_t good[] = {0x83, 1, 2, 3, 0};
  size_t n = 512 + 8 * 2 * 2, k;
  header(buf, 1, 1, 3, 3, 2, 2);
  for (k = 0; k < 4; k++) {
    const uint8_t *p = k == 1 ? row : good;
    size_t l = k == 1 ? len : sizeof good;
    put32(buf + 512 + 4 * k, (uint32_t)n);
    put32(buf + 512 + 16 + 4 * k, (uint32_t)l);
    memcpy(buf + n, p, l);
    n += l;
  }
  return n;
}

static void test_errors (void) {
  size_t n;
  long before;
  /* not an SGI image */
  bad((const uint8_t *)"GIF89a", 6, LSYS_ESYNTAX, "is not an SGI image");
  bad((const uint8_t *)"", 0, LSYS_ESYNTAX, "is not an SGI image");
  bad((const uint8_t *)"\x01", 1, LSYS_ESYNTAX, "is not an SGI image");
  bad((const uint8_t *)"\xda\x01", 2, LSYS_ESYNTAX, "is not an SGI image");  /* little-endian */
  /* the header */
  n = verbatim(buf, 1, 3, 3, 2, 3);
  bad(buf, 2, LSYS_ESYNTAX, "truncated header (2 of 512 bytes)");
  bad(buf, 511, LSYS_ESYNTAX, "truncated header (511 of 512 bytes)");
  buf[2] = 2;
  bad(buf, n, LSYS_ESYNTAX, "storage 2 (0 verbatim or 1 RLE expected)");
  buf[2] = 0;
  buf[3] = 0;
  bad(buf, n, LSYS_ESYNTAX, "0 bytes per channel (1 or 2 expected)");
  buf[3] = 4;
  bad(buf, n, LSYS_ESYNTAX, "4 bytes per channel");
  buf[3] = 1;
  put16(buf + 4, 0);
  bad(buf, n, LSYS_ESYNTAX, "dimension 0 (1, 2 or 3 expected)");
  put16(buf + 4, 4);
  bad(buf, n, LSYS_ESYNTAX, "dimension 4");
  put16(buf + 4, 3);
  put32(buf + 104, 1);
  bad(buf, n, LSYS_ESYNTAX, "colormap 1 (dithered) is not supported");
  put32(buf + 104, 2);
  bad(buf, n, LSYS_ESYNTAX, "colormap 2 (screen)");
  put32(buf + 104, 3);
  bad(buf, n, LSYS_ESYNTAX, "colormap 3 (a colour map, not an image)");
  put32(buf + 104, 0x01000000);
  bad(buf, n, LSYS_ESYNTAX, "colormap 16777216 (unknown)");
  put32(buf + 104, 0);
  tfree(ok(buf, n, 3, 2));                         /* intact again */
  /* sizes: zero, and larger than the limit (before the data is looked at) */
  header(buf, 0, 1, 3, 0, 2, 3);
  bad(buf, 512, LSYS_ESYNTAX, "empty image (0x2 pixels, 3 channels)");
  header(buf, 1, 1, 3, 4, 0, 3);
  bad(buf, 512, LSYS_ESYNTAX, "empty image (4x0 pixels");
  header(buf, 0, 1, 3, 4, 4, 0);
  bad(buf, 512, LSYS_ESYNTAX, "empty image (4x4 pixels, 0 channels)");
  header(buf, 0, 1, 3, 40000, 2, 3);
  bad(buf, 512, LSYS_ELIMIT, "40000x2 pixels is larger than the limit of 32768");
  header(buf, 1, 2, 3, 1, 65535, 3);
  bad(buf, 512, LSYS_ELIMIT, "1x65535 pixels is larger than the limit");
  /* the largest image with room for no data is refused before anything is allocated */
  before = nalloc;
  header(buf, 0, 2, 3, 32768, 32768, 4);
  bad(buf, 4096, LSYS_ESYNTAX, "truncated: 32768x32768 pixels of 4 channels need "
                               "8589935104 bytes, the file has 4096");
  header(buf, 1, 1, 3, 32768, 32768, 65535);
  bad(buf, 4096, LSYS_ESYNTAX, "truncated: the RLE tables of 2147450880 rows need "
                               "17179607552 bytes, the file has 4096");
  assert(nalloc == before);
  /* verbatim data one byte short; one channel of several */
  n = verbatim(buf, 2, 3, 3, 2, 5);
  bad(buf, n - 1, LSYS_ESYNTAX, "truncated: 3x2 pixels of 5 channels need 572 bytes, "
                                "the file has 571");
  n = verbatim(buf, 1, 2, 3, 2, 1);
  bad(buf, n - 1, LSYS_ESYNTAX, "3x2 pixels of 1 channel need 518 bytes");
  /* RLE tables and offsets */
  n = rle(buf, 1, 3, 3, 2, 3, val, 0, 0);
  bad(buf, 512 + 47, LSYS_ESYNTAX, "the RLE tables of 6 rows need 560 bytes, the file has 559");
  bad(buf, n - 1, LSYS_ESYNTAX, "RLE row 1 of channel 2 runs past the end of the file");
  put32(buf + 512 + 4 * 3, 0x7ffffff0u);          /* row 1 of channel 1 starts far away */
  bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 1 runs past the end of the file (offset "
                            "2147483632, length 5, file 590 bytes)");
  put32(buf + 512 + 4 * 3, 0xffffffffu);
  bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 1 runs past the end of the file");
  put32(buf + 512 + 4 * 3, 585);
  put32(buf + 512 + 24 + 4 * 3, 0xffffffffu);     /* a huge length */
  bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 1 runs past the end of the file (offset "
                            "585, length 4294967295");
  n = rle(buf, 1, 3, 3, 2, 3, val, 0, 0);
  put32(buf + 512, 0);                             /* row 0 of channel 0 in the header */
  bad(buf, n, LSYS_ESYNTAX, "RLE row 0 of channel 0 starts at offset 0, inside the header "
                            "or the tables");
  put32(buf + 512, 559);
  bad(buf, n, LSYS_ESYNTAX, "starts at offset 559, inside the header or the tables");
  /* rows that decode to too many or too few values */
  {
    static const uint8_t longer[] = {0x83, 1, 2, 3, 0x01, 4, 0};
    static const uint8_t longer2[] = {0x02, 7, 0x7f, 8, 0};
    static const uint8_t shorter[] = {0x82, 1, 2, 0};
    static const uint8_t none[] = {0};
    static const uint8_t pastlit[] = {0x85, 1, 2};
    static const uint8_t pastrep[] = {0x03};
    static const uint8_t ok1[] = {0x83, 1, 2, 3};  /* no 0 count: its length ends it */
    n = rlewith(longer, sizeof longer);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 decodes to 4 values, not 3");
    n = rlewith(longer2, sizeof longer2);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 decodes to 129 values, not 3");
    n = rlewith(shorter, sizeof shorter);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 decodes to 2 values, not 3");
    n = rlewith(none, sizeof none);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 decodes to 0 values, not 3");
    n = rlewith(none, 0);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 decodes to 0 values, not 3");
    n = rlewith(pastlit, sizeof pastlit);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 runs past its length (3 bytes)");
    n = rlewith(pastrep, sizeof pastrep);
    bad(buf, n, LSYS_ESYNTAX, "RLE row 1 of channel 0 runs past its length (1 bytes)");
    n = rlewith(ok1, sizeof ok1);
    tfree(ok(buf, n, 3, 2));
  }
  /* 2-byte values: a row of an odd length */
  n = rle(buf, 2, 2, 3, 1, 1, val, 0, 1);
  put32(buf + 516, get32(buf + 516) - 1);
  bad(buf, n, LSYS_ESYNTAX, "RLE row 0 of channel 0 runs past its length (7 bytes)");
  /* the memory budget, and a failing allocation */
  n = verbatim(buf, 1, 3, 64, 64, 3);
  lsys_common_set_memory_limit(4 * 64 * 64 - 1);
  bad(buf, n, LSYS_EMEMORY, "64x64 pixels need 16 KiB, more than max_memory");
  lsys_common_set_memory_limit(0);
  failat = nalloc;
  bad(buf, n, LSYS_ENOMEM, "not enough memory for 64x64 pixels");
  failat = -1;
  tfree(ok(buf, n, 64, 64));
}

/* Every truncation of a valid file and any flipped byte: an error or a picture. */
static void test_damage (void) {
  static uint8_t good[MAXB];
  int pass;
  for (pass = 0; pass < 3; pass++) {
    size_t n = pass == 0 ? verbatim(good, 1, 3, 5, 4, 4)
             : pass == 1 ? rle(good, 1, 3, 40, 3, 3, stripes, 1, 0)
                         : rle(good, 2, 3, 7, 3, 2, val, 0, 0);
    size_t k;
    int bit;
    for (k = 0; k < n; k++) {
      uint8_t *px;
      int w, h;
      lsys_error e;
      memcpy(buf, good, k);
      assert(lsys_sgiio_decode(buf, k, NAME, &px, &w, &h, &e) != LSYS_OK);
      assert(px == NULL && strstr(e.msg, NAME) != NULL);
    }
    for (k = 0; k < n; k++)
      for (bit = 0; bit < 8; bit += 3) {
        uint8_t *px;
        int w, h;
        lsys_error e;
        memcpy(buf, good, n);
        buf[k] ^= (uint8_t)(1u << bit);
        if (lsys_sgiio_decode(buf, n, NAME, &px, &w, &h, &e) == LSYS_OK) {
          assert(px != NULL && w >= 1 && h >= 1);
          tfree(px);
        }
        else
          assert(px == NULL && w == 0 && strstr(e.msg, NAME) != NULL);
      }
  }
  assert(nlive == 0);
}

/* ---------------------------------------------------------------------- */
/* files and textures */

static const char *tmp (const char *name) { return testpath(name); }

static void spit (const char *path, const uint8_t *b, size_t n) {
  FILE *f = fopen(path, "wb");
  assert(f != NULL && fwrite(b, 1, n, f) == n);
  assert(fclose(f) == 0);
}

static void test_files (void) {
  const char *p = tmp("light08.rgb"), *q = tmp("leaf.png"), *r = tmp("picture.rgb");
  uint8_t *px;
  int w, h;
  lsys_error e;
  lsys_texture t;
  size_t n = rle(buf, 1, 3, 5, 4, 3, val, 0, 0);
  spit(p, buf, n);
  assert(lsys_sgiio_read(p, &px, &w, &h, &e) == LSYS_OK && w == 5 && h == 4);
  checkval(px, 5, 4, 3);
  tfree(px);
  /* the texture loader: by the content, whatever the name */
  spit(q, buf, n);
  lsys_texture_init(&t);
  t.mode = LSYS_TEX_DECAL;
  assert(lsys_texture_load(&t, q, &e) == LSYS_OK);
  assert(t.w == 5 && t.h == 4 && t.intensity == 0 && strcmp(t.path, q) == 0);
  assert(t.mode == LSYS_TEX_DECAL && lsys_texture_hasalpha(&t) == 0);
  checkval(t.rgba, 5, 4, 3);
  n = verbatim(buf, 2, 3, 3, 2, 2);                /* grey and alpha */
  spit(p, buf, n);
  assert(lsys_texture_load(&t, p, &e) == LSYS_OK);
  assert(t.w == 3 && t.h == 2 && t.intensity == 1 && lsys_texture_hasalpha(&t) == 1);
  assert(strcmp(t.path, p) == 0);
  checkval(t.rgba, 3, 2, 2);
  /* failures name the file and leave the texture as it was */
  spit(r, (const uint8_t *)"GIF89a", 6);
  assert(lsys_texture_load(&t, r, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, r) && strstr(e.msg, "is not a PNG or SGI image"));
  spit(r, (const uint8_t *)"", 0);
  assert(lsys_texture_load(&t, r, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, "is not a PNG or SGI image"));
  spit(r, buf, 300);                               /* an SGI image cut short */
  assert(lsys_texture_load(&t, r, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, r) && strstr(e.msg, "truncated header (300 of 512 bytes)"));
  assert(lsys_texture_load(&t, tmp("missing.rgb"), &e) == LSYS_EARG);
  assert(strstr(e.msg, "cannot open '") && strstr(e.msg, "missing.rgb' for reading"));
  assert(lsys_texture_load(&t, dir, &e) == LSYS_EARG && strstr(e.msg, dir));
  assert(t.w == 3 && t.h == 2 && strcmp(t.path, p) == 0);
  lsys_texture_free(&t);
  /* the reader's own file errors */
  assert(lsys_sgiio_read(tmp("missing.rgb"), &px, &w, &h, &e) == LSYS_EARG && px == NULL);
  assert(strstr(e.msg, "missing.rgb': No such file or directory"));   /* lsys_common_readfile */
  assert(lsys_sgiio_read(dir, &px, &w, &h, &e) == LSYS_EARG && px == NULL);
  assert(strstr(e.msg, dir) && strstr(e.msg, "Is a directory"));
  assert(lsys_sgiio_read("/dev/null", &px, &w, &h, &e) == LSYS_EARG && px == NULL);
  assert(strstr(e.msg, "'/dev/null': not a regular file"));
  spit(r, (const uint8_t *)"GIF89a", 6);
  assert(lsys_sgiio_read(r, &px, &w, &h, &e) == LSYS_ESYNTAX && px == NULL);
  assert(strstr(e.msg, r) && strstr(e.msg, "is not an SGI image"));
  /* larger than LSYS_SGI_MAXFILE (a sparse file: nothing is read) */
  {
    FILE *f = fopen(r, "wb");
    assert(f != NULL && ftruncate(fileno(f), (off_t)LSYS_SGI_MAXFILE + 1) == 0);
    fclose(f);
    assert(lsys_sgiio_read(r, &px, &w, &h, &e) == LSYS_ELIMIT && px == NULL && w == 0);
    assert(strstr(e.msg, r) && strstr(e.msg, "larger than 1.0 GiB"));
  }
  remove(p);
  remove(q);
  remove(r);
  assert(nlive == 0);
}

int main (void) {
  dir = testdir();
  test_exact();
  test_channels();
  test_rle();
  test_errors();
  test_damage();
  test_files();
  assert(nlive == 0);
  printf("test_sgi: ok\n");
  return 0;
}
