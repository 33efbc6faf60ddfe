/*
** C unit tests of the pictures the viewer reads back (vshot.h) with the GL
** side faked: the rectangle read and its rows turned top side up, the
** S key's series (one file per frame, named by step, in a folder made for
** it; the first failure stops it and says why), and lsys-NNN.png names.
** The window itself is tested from Lua under Xvfb (tests/frames_spec.lua).
*/
#define _XOPEN_SOURCE 700       /* testdir.h */
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef LSYS_NO_RENDER
#include <GL/gl.h>

#include "pngio.h"
#include "vshot.h"
#include "testdir.h"

/* The fake back buffer: W x H, rows from the bottom (GL's order); pixel
** (x, y) = {x, y, frame, 255}. */
enum { W = 8, H = 6 };
static int frame = -1, readbuf, align, reads, fails_at = -1;
static int rx, ry, rw, rh;

static void LSYS_GLAPI readpixels (int x, int y, int w, int h, unsigned fmt, unsigned type,
                                   void *px) {
  uint8_t *p = (uint8_t *)px;
  int i, j;
  assert(fmt == GL_RGBA && type == GL_UNSIGNED_BYTE);
  rx = x; ry = y; rw = w; rh = h;
  reads++;
  for (j = 0; j < h; j++)
    for (i = 0; i < w; i++, p += 4) {
      p[0] = (uint8_t)(x + i); p[1] = (uint8_t)(y + j); p[2] = (uint8_t)frame; p[3] = 255;
    }
}

static void LSYS_GLAPI readbuffer (unsigned mode) { readbuf = (int)mode; }
static void LSYS_GLAPI pixelstorei (unsigned pname, int v) {
  if (pname == GL_PACK_ALIGNMENT) align = v;
}

static int draw (void *ctx, size_t k, const int r[4], lsys_error *e) {
  assert(ctx == (void *)&frame);
  assert(r[0] == 2 && r[1] == 1 && r[2] == 4 && r[3] == 3);
  if ((int)k == fails_at) return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot draw %d", (int)k);
  frame = (int)k;
  return LSYS_OK;
}

static lsys_vshot newshot (void) {
  lsys_vshot r;
  memset(&r, 0, sizeof r);
  r.ReadPixels = readpixels;
  r.ReadBuffer = readbuffer;
  r.PixelStorei = pixelstorei;
  return r;
}

/* Pixel (x, y) of a PNG (top row first). */
static const uint8_t *at (const uint8_t *px, int w, int x, int y) {
  return px + 4 * ((size_t)y * w + x);
}

static void test_png (const char *dir) {
  lsys_vshot r = newshot();
  lsys_error e;
  uint8_t *px;
  int w, h, rect[4] = {2, 1, 4, 3};
  char path[512];
  snprintf(path, sizeof path, "%s/one.png", dir);
  frame = 7;
  assert(lsys_vshot_png(&r, rect, path, &e) == LSYS_OK);
  assert(readbuf == GL_BACK && align == 1);
  assert(rx == 2 && ry == 1 && rw == 4 && rh == 3);
  assert(lsys_pngio_read(path, &px, &w, &h, &e) == LSYS_OK);
  assert(w == 4 && h == 3);
  /* the top row of the PNG is the highest row read (y = 1 + 2) */
  assert(at(px, w, 0, 0)[0] == 2 && at(px, w, 0, 0)[1] == 3 && at(px, w, 0, 0)[2] == 7);
  assert(at(px, w, 3, 2)[0] == 5 && at(px, w, 3, 2)[1] == 1);
  free(px);
  rect[2] = 0;
  assert(lsys_vshot_png(&r, rect, path, &e) != LSYS_OK);
  assert(strstr(e.msg, "the window is empty") != NULL);
  lsys_vshot_free(&r);
}

static void test_series (const char *dir) {
  lsys_vshot r = newshot();
  lsys_vsnap *s = lsys_vsnap_new(3);
  lsys_vevent ev;
  lsys_error e;
  uint8_t *px;
  int w, h, rect[4] = {2, 1, 4, 3};
  char path[600];
  assert(s != NULL);
  s->frames[0].step = 0;
  s->frames[1].step = 2;
  s->frames[2].step = 5;
  snprintf(s->framesdir, sizeof s->framesdir, "%s/frames", dir);
  memset(&ev, 0, sizeof ev);
  reads = 0;
  lsys_vshot_series(&r, s, rect, draw, &frame, &ev);
  assert(ev.type == LSYS_VEV_FRAMES && ev.ok && ev.count == 3);
  assert(ev.first == 0 && ev.step == 5 && reads == 3);
  assert(strcmp(ev.path, s->framesdir) == 0);
  snprintf(path, sizeof path, "%s/frames/step-0002.png", dir);
  assert(lsys_pngio_read(path, &px, &w, &h, &e) == LSYS_OK);
  assert(w == 4 && h == 3 && px[2] == 1);     /* frame 1 drawn for step 2 */
  free(px);
  snprintf(path, sizeof path, "%s/frames/step-0001.png", dir);
  assert(access(path, F_OK) != 0);

  /* again into the same folder; a frame that cannot be drawn stops the series */
  fails_at = 1;
  memset(&ev, 0, sizeof ev);
  lsys_vshot_series(&r, s, rect, draw, &frame, &ev);
  assert(!ev.ok && ev.count == 1 && ev.first == 0);
  assert(strcmp(ev.msg, "cannot draw 1") == 0);
  fails_at = -1;

  /* a file where the folder goes */
  snprintf(s->framesdir, sizeof s->framesdir, "%s/one.png", dir);
  memset(&ev, 0, sizeof ev);
  lsys_vshot_series(&r, s, rect, draw, &frame, &ev);
  assert(!ev.ok && ev.count == 0);
  assert(strstr(ev.msg, "one.png: a file is in the way") != NULL);
  lsys_vsnap_free(s);
  lsys_vshot_free(&r);
}

static void test_autoname (const char *dir) {
  lsys_vshot r = newshot();
  char cwd[512], name[64];
  FILE *f;
  assert(getcwd(cwd, sizeof cwd) != NULL);
  assert(chdir(dir) == 0);
  lsys_vshot_autoname(&r, name, sizeof name);
  assert(strcmp(name, "lsys-001.png") == 0);
  f = fopen("lsys-003.png", "w");
  assert(f != NULL);
  fclose(f);
  lsys_vshot_autoname(&r, name, sizeof name);
  assert(strcmp(name, "lsys-002.png") == 0);
  lsys_vshot_autoname(&r, name, sizeof name);     /* 003 is taken */
  assert(strcmp(name, "lsys-004.png") == 0);
  assert(chdir(cwd) == 0);
}

int main (void) {
  const char *dir = testdir();                  /* removed at exit, with what is in it */
  test_png(dir);
  test_series(dir);
  test_autoname(dir);
  printf("test_vshot: ok\n");
  return 0;
}
#else
int main (void) {
  printf("test_vshot: skipped (built without rendering)\n");
  return 0;
}
#endif
