/*
** libFuzzer target for reading PNG files (csrc/core/pngio.c lsys_pngio_read) and
** textures (csrc/core/texture.c lsys_texture_load). The input is a PNG file.
** Before it is written to a temporary file the harness repairs what would
** stop libpng at the door: when the first byte is 0x89 the rest of the
** signature is set, an IHDR chunk first gets length 13, and every complete
** chunk gets its CRC recomputed, so that mutations reach the image data.
** Crashes, leaks and sanitizer reports are failures, and so is a reader
** that breaks its contract:
**
**   success: pixels, 1 <= w, h <= LSYS_PNG_MAXSIZE; the texture loader
**   gives the same pixels and sizes, sets 'intensity' exactly for grey
**   images and keeps the path; writing the pixels as PNG and reading them
**   back gives them again (images up to 256 x 256);
**   failure: LSYS_ESYNTAX, LSYS_ELIMIT or LSYS_ENOMEM, e->msg naming the
**   file, no pixels, and the texture unchanged.
**
** Inputs that start with the SGI magic number (0x01 0xDA) are skipped: the
** texture loader reads them as SGI images (fuzz_sgi.c).
**
** Inputs whose IHDR declares more than 4096 x 4096 pixels (width times
** height; a row may be as long as LSYS_PNG_MAXSIZE and beyond) are skipped:
** the reader allocates the whole image before reading a row (by design, up
** to LSYS_PNG_MAXSIZE = 32768 squared: 4 GiB), so a 40-byte file could make
** every run allocate gigabytes. Run with -rss_limit_mb=2048 all the same:
** other declared sizes are not skipped (a 53-byte file whose tEXt chunk
** declared 1.9 GB made libpng allocate that much until pngio.c skipped such
** chunks: corpus_png/text-chunk-declares-1.9GB.png). FUZZ_TRACE=1 in the
** environment prints what the reader says.
**
**   tools/fuzz.sh 600 png          (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_png
**   build-fuzz/fuzz_png -max_total_time=600 -rss_limit_mb=2048 -dict=tests/fuzz/png.dict \
**                       tests/fuzz/corpus_png
*/
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pngio.h"
#include "texture.h"

#define MAXPIXELS ((uint64_t)4096 * 4096)

static uint32_t crctab[256];
static volatile unsigned sink;
static int tracing = -1;

static uint32_t pngcrc (const uint8_t *p, size_t n) {
  uint32_t c = 0xffffffffu;
  size_t i;
  if (crctab[1] == 0) {
    uint32_t k, j;
    for (k = 0; k < 256; k++) {
      uint32_t x = k;
      for (j = 0; j < 8; j++) x = x & 1 ? 0xedb88320u ^ (x >> 1) : x >> 1;
      crctab[k] = x;
    }
  }
  for (i = 0; i < n; i++) c = crctab[(c ^ p[i]) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

static uint32_t get32 (const uint8_t *p) {
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static void put32 (uint8_t *p, uint32_t x) {
  p[0] = (uint8_t)(x >> 24); p[1] = (uint8_t)(x >> 16); p[2] = (uint8_t)(x >> 8); p[3] = (uint8_t)x;
}

/* Repairs the signature, the IHDR length and the CRCs; returns 0 when the
** image is too large to try (see above). */
static int repair (uint8_t *b, size_t n) {
  static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  size_t off = 8;
  if (n < 8 || b[0] != 0x89) return 1;
  memcpy(b, sig, 8);
  while (off + 8 <= n) {
    uint32_t len = get32(b + off);
    if (off == 8 && memcmp(b + off + 4, "IHDR", 4) == 0) {
      if (len != 13 && off + 12 + 13 <= n) put32(b + off, len = 13);
      if (len == 13 && off + 8 + 13 <= n &&
          (uint64_t)get32(b + off + 8) * get32(b + off + 12) > MAXPIXELS)
        return 0;
    }
    if (off + 12 > n || len > n - off - 12) break;   /* a truncated chunk stays as it is */
    put32(b + off + 8 + len, pngcrc(b + off + 4, (size_t)len + 4));
    off += 12 + (size_t)len;
  }
  return 1;
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
  snprintf(path, size, "%s/lsys_fuzz_png_XXXXXX", dir);
  fd = mkstemp(path);
  if (fd < 0) return 0;
  close(fd);
  return 1;
}

/* The failure contract: a known code, a message naming the file, nothing kept. */
static void checkfail (int st, const lsys_error *e, const char *path) {
  if (st != LSYS_ESYNTAX && st != LSYS_ELIMIT && st != LSYS_ENOMEM) __builtin_trap();
  if (e->code != st || strstr(e->msg, path) == NULL) __builtin_trap();
}

/* Writing and reading back the pixels gives them again (RGB: alpha 255). */
static void roundtrip (const char *path, const uint8_t *px, int w, int h) {
  char out[300];
  lsys_error e;
  uint8_t *back;
  int bw, bh, alpha;
  size_t i, n = (size_t)w * (size_t)h;
  snprintf(out, sizeof out, "%s.png", path);
  for (alpha = 0; alpha < 2; alpha++) {
    if (lsys_pngio_write(out, px, w, h, alpha, &e) != LSYS_OK) __builtin_trap();
    if (lsys_pngio_read(out, &back, &bw, &bh, &e) != LSYS_OK) __builtin_trap();
    if (bw != w || bh != h) __builtin_trap();
    for (i = 0; i < n; i++)
      if (memcmp(back + 4 * i, px + 4 * i, 3) != 0 ||
          back[4 * i + 3] != (alpha ? px[4 * i + 3] : 255))
        __builtin_trap();
    free(back);
  }
  remove(out);
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  char path[256];
  uint8_t *b, *px;
  lsys_error e, e2;
  lsys_texture t, c;
  int w, h, st, st2;
  if (size >= 2 && data[0] == 0x01 && data[1] == 0xda) return 0;   /* SGI: fuzz_sgi's */
  b = (uint8_t *)malloc(size ? size : 1);
  if (b == NULL) return 0;
  if (size) memcpy(b, data, size);
  if (!repair(b, size) || !tempname(path, sizeof path)) { free(b); return 0; }
  if (!writefile(path, b, size)) { remove(path); free(b); return 0; }
  free(b);
  st = lsys_pngio_read(path, &px, &w, &h, &e);
  lsys_texture_init(&t);
  t.mag_linear = 1;
  t.mode = LSYS_TEX_DECAL;
  st2 = lsys_texture_load(&t, path, &e2);
  if (tracing < 0) tracing = getenv("FUZZ_TRACE") != NULL;
  if (tracing) fprintf(stderr, "%d: %dx%d %s\n", st, w, h, st == LSYS_OK ? "" : e.msg);
  if (st2 != st) __builtin_trap();
  if (st == LSYS_OK) {
    size_t n = (size_t)w * (size_t)h, i;
    unsigned sum = 0;
    int alpha = 0;
    if (px == NULL || w < 1 || h < 1 || w > LSYS_PNG_MAXSIZE || h > LSYS_PNG_MAXSIZE)
      __builtin_trap();
    for (i = 0; i < 4 * n; i++) sum += px[i];   /* every byte is there */
    for (i = 0; i < n; i++) alpha |= px[4 * i + 3] != 255;
    if (t.w != w || t.h != h || t.rgba == NULL || memcmp(t.rgba, px, 4 * n) != 0)
      __builtin_trap();
    if (t.path == NULL || strcmp(t.path, path) != 0) __builtin_trap();
    if (t.intensity != isgrey(px, n) || lsys_texture_hasalpha(&t) != alpha) __builtin_trap();
    if (t.mag_linear != 1 || t.mode != LSYS_TEX_DECAL) __builtin_trap();
    if (lsys_texture_copy(&c, &t) != LSYS_OK) __builtin_trap();
    if (c.w != w || c.h != h || memcmp(c.rgba, px, 4 * n) != 0 || strcmp(c.path, path) != 0)
      __builtin_trap();
    lsys_texture_free(&c);
    if (n <= 65536) roundtrip(path, px, w, h);
    sink = sum;
    free(px);
  }
  else {
    checkfail(st, &e, path);
    checkfail(st2, &e2, path);
    if (px != NULL || w != 0 || h != 0) __builtin_trap();
    if (t.rgba != NULL || t.path != NULL || t.w != 0 || t.h != 0) __builtin_trap();
  }
  lsys_texture_free(&t);
  lsys_texture_free(&t);                         /* idempotent */
  remove(path);
  return 0;
}
