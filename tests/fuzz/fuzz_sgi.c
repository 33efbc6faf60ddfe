/*
** libFuzzer target for reading SGI images (csrc/core/sgiio.c lsys_sgiio_decode
** and lsys_sgiio_read) and textures (csrc/core/texture.c lsys_texture_load).
** The input is an SGI image file. When its first byte is 0x01 the harness
** sets the second to 0xDA, completing the magic number, so that mutations
** reach the header and the data. Crashes, leaks and sanitizer reports are
** failures, and so is a reader that breaks its contract:
**
**   success: pixels, 1 <= w, h <= LSYS_PNG_MAXSIZE, w the header's xsize and
**   h its ysize (1 for dimension 1); grey images (one channel) have
**   R = G = B and alpha 255, grey and alpha ones R = G = B, RGB ones alpha
**   255; the pixels are those of a plain second decoder in this file; the
**   file reader and the texture loader give the same pixels and sizes, the
**   loader sets 'intensity' exactly for grey pictures and keeps the path
**   and the settings;
**   failure: LSYS_ESYNTAX, LSYS_ELIMIT, LSYS_EMEMORY or LSYS_ENOMEM, e->msg
**   naming the file, no pixels, w = h = 0; the file reader fails with the
**   same code and message, the texture loader with the same code and the
**   texture unchanged;
**   not an SGI image (no magic number): the loader says "not a PNG or SGI
**   image" (inputs that start with the PNG signature are fuzz_png's and
**   skipped).
**
** Inputs whose header declares more than 4096 x 4096 pixels are skipped: an
** RLE image whose rows all share one run of data may be a few kilobytes and
** declare 32768 x 32768 pixels, which the reader allocates (4 GiB, within
** the memory budget, by design, like lsys_pngio_read). Run with
** -rss_limit_mb=2048. FUZZ_TRACE=1 in the environment prints what the
** reader says.
**
**   tools/fuzz.sh 600 sgi          (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_sgi
**   build-fuzz/fuzz_sgi -max_total_time=600 -rss_limit_mb=2048 tests/fuzz/corpus_sgi
*/
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pngio.h"
#include "sgiio.h"
#include "texture.h"

#define MAXPIXELS ((uint64_t)4096 * 4096)

static volatile unsigned sink;
static int tracing = -1;

static unsigned get16 (const uint8_t *p) { return (unsigned)p[0] << 8 | p[1]; }

static uint32_t get32 (const uint8_t *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The header's sizes as the reader takes them (dimension 1: one row, 1 and 2: one
** channel). */
static void sizes (const uint8_t *b, unsigned *x, unsigned *y, unsigned *z) {
  unsigned dim = get16(b + 4);
  *x = get16(b + 6);
  *y = dim == 1 ? 1 : get16(b + 8);
  *z = dim == 3 ? get16(b + 10) : 1;
}

/* The x values of row r of channel c into v[] (-1: not there): a second decoder, as
** plain as can be. */
static void rowvalues (const uint8_t *b, size_t n, unsigned r, unsigned c, int *v) {
  unsigned x, y, z, bpc = b[3], i;
  sizes(b, &x, &y, &z);
  for (i = 0; i < x; i++) v[i] = -1;
  if (b[2] == 0) {
    for (i = 0; i < x; i++) {
      uint64_t off = 512 + (((uint64_t)c * y + r) * x + i) * bpc;
      if (off + bpc <= n) v[i] = b[off];
    }
  }
  else {
    uint64_t k = (uint64_t)r + (uint64_t)c * y, t = 512 + 4 * k;
    uint64_t u = 512 + 4 * ((uint64_t)y * z + k), start, len, p, got = 0;
    if (u + 4 > n) return;
    start = get32(b + t);
    len = get32(b + u);
    for (p = start; p + bpc <= start + len && p + bpc <= n;) {
      unsigned head = b[p + bpc - 1], m = head & 0x7f, j;
      p += bpc;
      if (m == 0) break;
      for (j = 0; j < m; j++, got++) {
        uint64_t q = head & 0x80 ? p + (uint64_t)j * bpc : p;
        if (q + bpc > n) return;
        if (got < x) v[got] = b[q];
      }
      p += head & 0x80 ? (uint64_t)m * bpc : bpc;
    }
  }
}

static int isgrey (const uint8_t *px, size_t n) {
  size_t i;
  for (i = 0; i < n; i++, px += 4)
    if (px[0] != px[1] || px[1] != px[2]) return 0;
  return 1;
}

static int writefile (const char *path, const uint8_t *b, size_t n) {
  FILE *f = fopen(path, "wb");
  int ok;
  if (f == NULL) return 0;
  ok = fwrite(b, 1, n, f) == n;
  return fclose(f) == 0 && ok;
}

/* A fresh temporary file name in /dev/shm (memory) or the temporary directory. */
static int tempname (char *path, size_t size) {
  const char *dir = getenv("TMPDIR");
  struct stat st;
  int fd;
  if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0)
    dir = "/dev/shm";
  else if (dir == NULL)
    dir = "/tmp";
  snprintf(path, size, "%s/lsys_fuzz_sgi_XXXXXX", dir);
  fd = mkstemp(path);
  if (fd < 0) return 0;
  close(fd);
  return 1;
}

/* The failure contract: a known code, a message naming the file. */
static void checkfail (int st, const lsys_error *e, const char *path) {
  if (st != LSYS_ESYNTAX && st != LSYS_ELIMIT && st != LSYS_EMEMORY && st != LSYS_ENOMEM)
    __builtin_trap();
  if (e->code != st || strstr(e->msg, path) == NULL) __builtin_trap();
}

/* The pixels px (w x h) against the header and the second decoder. */
static void checkpixels (const uint8_t *b, size_t n, const uint8_t *px, int w, int h) {
  unsigned x, y, z, nch, r, c, i;
  int *v;
  sizes(b, &x, &y, &z);
  nch = z < 4 ? z : 4;
  if ((unsigned)w != x || (unsigned)h != y) __builtin_trap();
  if ((v = (int *)malloc(sizeof *v * x)) == NULL) return;
  for (c = 0; c < nch; c++)
    for (r = 0; r < y; r++) {
      rowvalues(b, n, r, c, v);
      for (i = 0; i < x; i++) {
        const uint8_t *q = px + 4 * ((size_t)(y - 1 - r) * x + i);
        if (v[i] < 0 || q[nch == 2 && c == 1 ? 3 : c] != v[i]) __builtin_trap();
        if (c == 0 && nch <= 2 && (q[1] != q[0] || q[2] != q[0])) __builtin_trap();
        if (c == 0 && (nch == 1 || nch == 3) && q[3] != 255) __builtin_trap();
      }
    }
  free(v);
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  static const uint8_t pngsig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  char path[256];
  uint8_t *b, *px, *px2;
  lsys_error e, e2, e3;
  lsys_texture t;
  int w, h, w2, h2, st, st2, st3, sgi;
  if (size >= 8 && memcmp(data, pngsig, 8) == 0) return 0;   /* fuzz_png's */
  b = (uint8_t *)malloc(size ? size : 1);
  if (b == NULL) return 0;
  if (size) memcpy(b, data, size);
  if (size >= 2 && b[0] == 0x01) b[1] = 0xda;
  sgi = size >= 2 && b[0] == 0x01;
  if (sgi && size >= 12) {
    unsigned x, y, z;
    sizes(b, &x, &y, &z);
    if ((uint64_t)x * y > MAXPIXELS) { free(b); return 0; }
  }
  if (!tempname(path, sizeof path)) { free(b); return 0; }
  if (!writefile(path, b, size)) { remove(path); free(b); return 0; }
  if (tracing < 0) tracing = getenv("FUZZ_TRACE") != NULL;
  /* in memory, from the file, as a texture */
  st = lsys_sgiio_decode(b, size, path, &px, &w, &h, &e);
  if (tracing) fprintf(stderr, "%d: %dx%d %s\n", st, w, h, st == LSYS_OK ? "" : e.msg);
  st2 = lsys_sgiio_read(path, &px2, &w2, &h2, &e2);
  lsys_texture_init(&t);
  t.mag_linear = 1;
  t.mode = LSYS_TEX_DECAL;
  st3 = lsys_texture_load(&t, path, &e3);
  if (st2 != st) __builtin_trap();
  if (st == LSYS_OK) {
    size_t n = (size_t)w * (size_t)h, i;
    unsigned sum = 0;
    int alpha = 0;
    if (px == NULL || w < 1 || h < 1 || w > LSYS_PNG_MAXSIZE || h > LSYS_PNG_MAXSIZE)
      __builtin_trap();
    for (i = 0; i < 4 * n; i++) sum += px[i];   /* every byte is there */
    for (i = 0; i < n; i++) alpha |= px[4 * i + 3] != 255;
    checkpixels(b, size, px, w, h);
    if (px2 == NULL || w2 != w || h2 != h || memcmp(px2, px, 4 * n) != 0) __builtin_trap();
    if (st3 != LSYS_OK || t.w != w || t.h != h || t.rgba == NULL ||
        memcmp(t.rgba, px, 4 * n) != 0)
      __builtin_trap();
    if (t.path == NULL || strcmp(t.path, path) != 0) __builtin_trap();
    if (t.intensity != isgrey(px, n) || lsys_texture_hasalpha(&t) != alpha) __builtin_trap();
    if (t.mag_linear != 1 || t.mode != LSYS_TEX_DECAL) __builtin_trap();
    sink = sum;
    free(px);
    free(px2);
  }
  else {
    checkfail(st, &e, path);
    if (px != NULL || w != 0 || h != 0) __builtin_trap();
    if (px2 != NULL || w2 != 0 || h2 != 0 || strcmp(e.msg, e2.msg) != 0) __builtin_trap();
    if (sgi) {
      if (st3 != st || e3.code != st || strcmp(e3.msg, e.msg) != 0) __builtin_trap();
    }
    else if (st3 != LSYS_ESYNTAX || strstr(e3.msg, path) == NULL ||
             strstr(e3.msg, "is not a PNG or SGI image") == NULL)
      __builtin_trap();
    if (t.rgba != NULL || t.path != NULL || t.w != 0 || t.h != 0) __builtin_trap();
  }
  lsys_texture_free(&t);
  lsys_texture_free(&t);                         /* idempotent */
  remove(path);
  free(b);
  return 0;
}
