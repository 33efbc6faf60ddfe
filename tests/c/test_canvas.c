/*
** C unit tests for the 2D canvas (canvas.h): the exact pixels of a
** horizontal 1-pixel line and of a vertical one between two columns, the
** coverage sum of an anti-aliased diagonal against the area of its shape,
** the pixels of a glyph, rectangles, discs, clipping, the arithmetic of
** source-over blending, non-finite and huge coordinates, size limits and a
** failing allocation.
*/
#define _XOPEN_SOURCE 700       /* testdir.h */
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "talloc.h"
#include "testdir.h"
/* canvas.c compiled in with counting allocators (pngio.o comes from the library) */
#include "common.c"
#include "canvas.c"

static const double BLACK[4] = { 0, 0, 0, 1 }, WHITE[4] = { 1, 1, 1, 1 };

static const uint8_t *px (const lsys_canvas *c, int i, int j) {
  return c->px + 4 * ((size_t)j * c->w + i);
}

/* Asserts pixel (i, j) is the grey v (opaque). */
static void grey (const lsys_canvas *c, int i, int j, int v) {
  const uint8_t *p = px(c, i, j);
  if (p[0] != v || p[1] != v || p[2] != v || p[3] != 255) {
    fprintf(stderr, "pixel (%d, %d) is %d %d %d %d, expected grey %d\n", i, j, p[0], p[1],
            p[2], p[3], v);
    assert(0);
  }
}

/* The sum of the red channel / 255 over the canvas: white's coverage on black. */
static double coverage (const lsys_canvas *c) {
  double s = 0;
  int i, j;
  for (j = 0; j < c->h; j++)
    for (i = 0; i < c->w; i++) s += px(c, i, j)[0] / 255.0;
  return s;
}

static int count_lit (const lsys_canvas *c) {
  int i, j, n = 0;
  for (j = 0; j < c->h; j++)
    for (i = 0; i < c->w; i++) n += px(c, i, j)[0] != 0;
  return n;
}

static void fresh (lsys_canvas *c, int w, int h) {
  lsys_error e;
  assert(lsys_canvas_init(c, w, h, &e) == LSYS_OK);
  lsys_canvas_clear(c, BLACK);
}

static void test_hline (void) {
  lsys_canvas c;
  int i, j;
  fresh(&c, 20, 20);
  lsys_canvas_line(&c, 2.5, 10.5, 8.5, 10.5, 1, WHITE);
  for (j = 0; j < 20; j++)
    for (i = 0; i < 20; i++) grey(&c, i, j, j == 10 && i >= 2 && i <= 8 ? 255 : 0);
  /* a vertical line on the border of columns 9 and 10: half of each */
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_line(&c, 10, 3.5, 10, 6.5, 1, WHITE);
  for (j = 0; j < 20; j++)
    for (i = 0; i < 20; i++) grey(&c, i, j, (i == 9 || i == 10) && j >= 3 && j <= 6 ? 128 : 0);
  lsys_canvas_free(&c);
}

/* A width-w segment of length l covers l*w plus its two half-disc caps. */
static void test_diagonal (void) {
  lsys_canvas c;
  double w, area, got;
  fresh(&c, 80, 80);
  for (w = 1; w <= 4; w += 1.5) {
    lsys_canvas_clear(&c, BLACK);
    lsys_canvas_line(&c, 10.2, 12.7, 58.2, 48.7, w, WHITE);  /* 48, 36: length 60 */
    area = 60 * w + 3.14159265358979 * w * w / 4;
    got = coverage(&c);
    if (fabs(got - area) > 0.02 * area) {
      fprintf(stderr, "diagonal width %g: coverage %g, area %g\n", w, got, area);
      assert(0);
    }
    /* (20.5, 20.5) is 0.075 below the line in y, 0.06 from it: 1 - 0.06 of 255 at width 1 */
    assert(px(&c, 20, 20)[0] == (w == 1 ? 240 : 255));
  }
  /* a polyline of the same two halves covers the same (opaque joins overlap) */
  {
    double xy[6] = { 10.2, 12.7, 34.2, 30.7, 58.2, 48.7 };
    double before;
    lsys_canvas_clear(&c, BLACK);
    lsys_canvas_line(&c, 10.2, 12.7, 58.2, 48.7, 2, WHITE);
    before = coverage(&c);
    lsys_canvas_clear(&c, BLACK);
    lsys_canvas_polyline(&c, xy, 3, 2, WHITE);
    assert(fabs(coverage(&c) - before) < 0.5);
  }
  lsys_canvas_free(&c);
}

static void test_text (void) {
  static const char *const A[7] = {
    ".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"
  };
  lsys_canvas c;
  int i, j, r, q;
  fresh(&c, 30, 20);
  assert(lsys_canvas_text(&c, 3, 2, "A", 1, 1, WHITE) == 5);
  for (j = 0; j < 20; j++)
    for (i = 0; i < 30; i++) {
      int on = i >= 3 && i < 8 && j >= 2 && j < 9 && A[j - 2][i - 3] == '#';
      grey(&c, i, j, on ? 255 : 0);
    }
  /* scale 2: each font pixel a 2x2 block; 'A' then a space, at (0.4, 0.6) -> (0, 1) */
  lsys_canvas_clear(&c, BLACK);
  assert(lsys_canvas_text(&c, 0.4, 0.6, "A ", 2, 2, WHITE) == 22);
  for (r = 0; r < 7; r++)
    for (q = 0; q < 5; q++) {
      int v = A[r][q] == '#' ? 255 : 0;
      grey(&c, 2 * q, 1 + 2 * r, v);
      grey(&c, 2 * q + 1, 2 + 2 * r, v);
    }
  assert(count_lit(&c) == 4 * 18);                /* 18 lit font pixels in 'A' */
  assert(lsys_canvas_text_width(0, 3) == 0);
  assert(lsys_canvas_text_width(4, 3) == 4 * 18 - 3);
  /* a control byte is drawn as '?' */
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_text(&c, 0, 0, "\n", 1, 1, WHITE);
  {
    lsys_canvas d;
    fresh(&d, 30, 20);
    lsys_canvas_text(&d, 0, 0, "?", 1, 1, WHITE);
    assert(memcmp(c.px, d.px, 30 * 20 * 4) == 0);
    lsys_canvas_free(&d);
  }
  lsys_canvas_free(&c);
}

static void test_rect_circle (void) {
  lsys_canvas c;
  int i, j;
  fresh(&c, 20, 20);
  lsys_canvas_rect(&c, 2, 3, 4, 5, WHITE, 1);       /* whole pixels 2..5 x 3..7 */
  for (j = 0; j < 20; j++)
    for (i = 0; i < 20; i++) grey(&c, i, j, i >= 2 && i <= 5 && j >= 3 && j <= 7 ? 255 : 0);
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_rect(&c, 2.5, 3, 1, 1, WHITE, 1);     /* half of pixels 2 and 3 */
  grey(&c, 2, 3, 128);
  grey(&c, 3, 3, 128);
  assert(count_lit(&c) == 2);
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_rect(&c, 1, 1, 5, 4, WHITE, 0);       /* outline: 5 + 5 + 2 + 2 pixels */
  assert(count_lit(&c) == 14);
  grey(&c, 1, 1, 255); grey(&c, 5, 4, 255); grey(&c, 3, 2, 0);
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_circle(&c, 10, 10, 4, WHITE);
  assert(fabs(coverage(&c) - 3.14159265358979 * 16) < 0.5);
  grey(&c, 10, 10, 255);
  grey(&c, 10, 15, 0);
  lsys_canvas_free(&c);
}

static void test_clip (void) {
  lsys_canvas c;
  int i, j;
  fresh(&c, 20, 20);
  lsys_canvas_clip(&c, 5, 6, 10, 4);                /* pixels 5..14 x 6..9 */
  lsys_canvas_rect(&c, -100, -100, 300, 300, WHITE, 1);
  for (j = 0; j < 20; j++)
    for (i = 0; i < 20; i++) grey(&c, i, j, i >= 5 && i <= 14 && j >= 6 && j <= 9 ? 255 : 0);
  lsys_canvas_clear(&c, BLACK);                     /* clear ignores the clip */
  lsys_canvas_line(&c, 0, 0, 20, 20, 3, WHITE);
  lsys_canvas_circle(&c, 10, 2, 3, WHITE);
  lsys_canvas_text(&c, 0, 0, "MMMMMMMM", 8, 1, WHITE);
  for (j = 0; j < 20; j++)
    for (i = 0; i < 20; i++)
      if (i < 5 || i > 14 || j < 6 || j > 9) grey(&c, i, j, 0);
  assert(count_lit(&c) > 8);
  lsys_canvas_clip(&c, 0, 0, 0, 10);                /* empty: nothing is drawn */
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_rect(&c, 0, 0, 20, 20, WHITE, 1);
  assert(count_lit(&c) == 0);
  lsys_canvas_unclip(&c);
  lsys_canvas_rect(&c, 0, 0, 20, 20, WHITE, 1);
  assert(count_lit(&c) == 400);
  /* shapes outside the canvas draw nothing; one across it draws its part */
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_line(&c, -10, -10, -2, 30, 2, WHITE);
  lsys_canvas_circle(&c, 25, 10, 3, WHITE);
  lsys_canvas_text(&c, 21, 0, "ABC", 3, 1, WHITE);
  assert(count_lit(&c) == 0);
  lsys_canvas_line(&c, -1e300, 10.5, 1e300, 10.5, 1, WHITE);
  for (i = 0; i < 20; i++) grey(&c, i, 10, 255);
  assert(count_lit(&c) == 20);
  lsys_canvas_free(&c);
}

static void test_blend (void) {
  static const double red50[4] = { 1, 0, 0, 0.5 }, black25[4] = { 0, 0, 0, 0.25 };
  lsys_canvas c;
  lsys_error e;
  const uint8_t *p;
  fresh(&c, 4, 4);
  lsys_canvas_rect(&c, 0, 0, 1, 1, red50, 1);       /* 0.5 * 255 + 0.5 * 0 = 127.5 */
  p = px(&c, 0, 0);
  assert(p[0] == 128 && p[1] == 0 && p[2] == 0 && p[3] == 255);
  lsys_canvas_clear(&c, WHITE);
  lsys_canvas_rect(&c, 0, 0, 1, 1, black25, 1);     /* 0.75 * 255 = 191.25 */
  p = px(&c, 0, 0);
  assert(p[0] == 191 && p[1] == 191 && p[2] == 191 && p[3] == 255);
  lsys_canvas_free(&c);
  /* onto transparent: alpha 0.5 (128), then 0.5 + (128/255) * 0.5 = 0.75098 (192); the
  ** colour stays red */
  assert(lsys_canvas_init(&c, 4, 4, &e) == LSYS_OK);
  p = px(&c, 1, 1);
  assert(p[0] == 0 && p[3] == 0);
  lsys_canvas_rect(&c, 1, 1, 1, 1, red50, 1);
  assert(p[0] == 255 && p[1] == 0 && p[3] == 128);
  lsys_canvas_rect(&c, 1, 1, 1, 1, red50, 1);
  assert(p[0] == 255 && p[3] == 192);
  /* out-of-range components are clamped */
  {
    const double odd[4] = { 2, -1, NAN, 7 };
    lsys_canvas_rect(&c, 1, 1, 1, 1, odd, 1);
    assert(p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255);
  }
  lsys_canvas_free(&c);
}

static void test_limits (void) {
  lsys_canvas c;
  lsys_error e;
  double bad[] = { NAN, INFINITY, -INFINITY };
  int k;
  assert(lsys_canvas_init(&c, 0, 5, &e) == LSYS_EARG && c.px == NULL);
  assert(strstr(e.msg, "0x5") != NULL);
  assert(lsys_canvas_init(&c, 16385, 1, &e) == LSYS_EARG);
  assert(lsys_canvas_init(&c, 5, -1, &e) == LSYS_EARG);
  failat = nalloc;                                  /* the next allocation fails */
  assert(lsys_canvas_init(&c, 5, 5, &e) == LSYS_ENOMEM && c.px == NULL);
  failat = -1;
  lsys_canvas_free(&c);                             /* idempotent on a failed init */
  fresh(&c, 16, 16);
  for (k = 0; k < 3; k++) {
    double v = bad[k];
    lsys_canvas_line(&c, v, 0, 5, 5, 1, WHITE);
    lsys_canvas_line(&c, 0, 0, 5, 5, v, WHITE);
    lsys_canvas_rect(&c, 0, v, 5, 5, WHITE, 1);
    lsys_canvas_rect(&c, 0, 0, 5, v, WHITE, 0);
    lsys_canvas_circle(&c, 5, 5, v, WHITE);
    lsys_canvas_text(&c, v, 0, "A", 1, 1, WHITE);
  }
  lsys_canvas_line(&c, 0, 0, 5, 5, 0, WHITE);       /* zero and negative sizes */
  lsys_canvas_line(&c, 0, 0, 5, 5, -1, WHITE);
  lsys_canvas_rect(&c, 0, 0, -3, 4, WHITE, 1);
  lsys_canvas_circle(&c, 5, 5, 0, WHITE);
  lsys_canvas_line(&c, -1e308, 0, 1e308, 5, 1, WHITE);   /* too far apart to subtract */
  assert(count_lit(&c) == 0);
  /* huge shapes are cut to the canvas: quick, and they fill it */
  lsys_canvas_circle(&c, 1e12, 1e12, 1e15, WHITE);
  assert(count_lit(&c) == 256);
  lsys_canvas_clear(&c, BLACK);
  lsys_canvas_line(&c, -1e9, -1e9, 1e9, 1e9, 1e12, WHITE);
  assert(count_lit(&c) == 256);
  lsys_canvas_free(&c);
  assert(nlive == 0);
}

static void test_save (void) {
  lsys_canvas c;
  lsys_error e;
  uint8_t *rgba;
  int w, h;
  const char *path = testpath("canvas.png");
  fresh(&c, 7, 3);
  lsys_canvas_rect(&c, 1, 1, 2, 1, WHITE, 1);
  assert(lsys_canvas_save(&c, path, &e) == LSYS_OK);
  assert(lsys_pngio_read(path, &rgba, &w, &h, &e) == LSYS_OK);
  assert(w == 7 && h == 3 && memcmp(rgba, c.px, 7 * 3 * 4) == 0);
  free(rgba);                                       /* pngio.o allocates with malloc */
  remove(path);
  assert(lsys_canvas_save(&c, "/nonexistent-dir/x.png", &e) != LSYS_OK);
  assert(strstr(e.msg, "/nonexistent-dir/x.png") != NULL);
  lsys_canvas_free(&c);
}

int main (void) {
  test_hline();
  test_diagonal();
  test_text();
  test_rect_circle();
  test_clip();
  test_blend();
  test_limits();
  test_save();
  assert(nlive == 0);
  printf("test_canvas: ok\n");
  return 0;
}
