/*
** C unit tests for rendering and PNG I/O: camera fitting and projection
** (plain arithmetic, no GL), PNG round trips in several colour types,
** damaged files, and offscreen renders of a small hand-made scene. A build
** without OSMesa runs the PNG tests only. Set LSYS_RENDER_DUMP=dir to keep
** the rendered images.
*/
#define _POSIX_C_SOURCE 200809L
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mesh.h"
#include "pngio.h"
#include "render.h"
#include "texture.h"
#include "testdir.h"

#ifndef LSYS_NO_RENDER

/* A mesh made of the 8 corners of [lo, hi] (vertices only, no triangles). */
static float boxpos[24], boxnrm[24], boxuv[16];
static uint16_t boxcol[8];
static uint8_t boxts[8];

static lsys_mesh boxmesh (const double lo[3], const double hi[3]) {
  lsys_mesh m = {0};
  int i;
  for (i = 0; i < 8; i++) {
    boxpos[3 * i + 0] = (float)((i & 1) ? hi[0] : lo[0]);
    boxpos[3 * i + 1] = (float)((i & 2) ? hi[1] : lo[1]);
    boxpos[3 * i + 2] = (float)((i & 4) ? hi[2] : lo[2]);
  }
  m.pos = boxpos; m.nrm = boxnrm; m.uv = boxuv; m.col = boxcol; m.twosided = boxts;
  m.nv = 8;
  return m;
}

/* ---------------------------------------------------------------------- */

/* The camera these tests were written for: the scene's default, but in
** perspective. */
static void testcam (lsys_camera *c) {
  lsys_scene_camera_defaults(c);
  c->projection = LSYS_PERSPECTIVE;
}

static void project (const double proj[16], const double view[16], int w, int h, double x,
                     double y, double z, double out[3]) {
  double p[3] = {x, y, z};
  assert(lsys_render_project(proj, view, w, h, p, out) == 1);
}

/* Every corner of the box lies inside the viewport with a margin, the box
** fills most of it along one axis, and its centre is in the middle. */
static void checkfit (const lsys_mesh *m, const lsys_camera *cam, int w, int h) {
  double proj[16], view[16], out[3], lo[3], hi[3], minx = 1e9, maxx = -1e9, miny = 1e9,
         maxy = -1e9;
  int i;
  assert(lsys_render_camera(m, cam, w, h, proj, view) == LSYS_OK);
  lsys_mesh_bounds(m, lo, hi);
  for (i = 0; i < 8; i++) {
    project(proj, view, w, h, (i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1],
            (i & 4) ? hi[2] : lo[2], out);
    assert(out[2] > 0 && out[2] < 1);
    minx = fmin(minx, out[0]); maxx = fmax(maxx, out[0]);
    miny = fmin(miny, out[1]); maxy = fmax(maxy, out[1]);
  }
  assert(minx >= 0.04 * w && maxx <= 0.96 * w);
  assert(miny >= 0.04 * h && maxy <= 0.96 * h);
  assert(maxx - minx >= 0.8 * w || maxy - miny >= 0.8 * h);
  project(proj, view, w, h, 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]),
          0.5 * (lo[2] + hi[2]), out);
  assert(fabs(out[0] - 0.5 * w) < 1 && fabs(out[1] - 0.5 * h) < 1);
}

static void test_fit (void) {
  static const double lo[3] = {-1, 0, -0.5}, hi[3] = {1, 4, 0.5};
  static const double dirs[4][3] = {{0, 0, -1}, {1, 0, 0}, {-1, -1, -1}, {0, -1, 0}};
  lsys_mesh m = boxmesh(lo, hi), empty = {0};
  lsys_camera cam;
  int d, p;
  testcam(&cam);
  for (p = 0; p < 2; p++) {
    cam.projection = p ? LSYS_PARALLEL : LSYS_PERSPECTIVE;
    for (d = 0; d < 4; d++) {
      memcpy(cam.dir, dirs[d], sizeof cam.dir);
      checkfit(&m, &cam, 800, 600);
      checkfit(&m, &cam, 300, 900);
      cam.twist = 30;
      checkfit(&m, &cam, 500, 500);
      cam.twist = 0;
    }
    /* a given eye, perspective: the target is the box centre, the frame is not fitted */
    cam.dir[0] = 0; cam.dir[1] = 0; cam.dir[2] = -1;
    checkfit(&m, &cam, 640, 480);
  }
  /* perspective fits the vertices, not the box: a square with points on
  ** the view axis in front of and behind it still fills the image */
  {
    static const double slo[3] = {-1, -1, 0}, shi[3] = {1, 1, 0};
    lsys_mesh sq = boxmesh(slo, shi);
    double proj[16], view[16], out[3];
    boxpos[2] = 1;                      /* vertex 0 -> (0, 0, 1), vertex 7 -> (0, 0, -10) */
    boxpos[0] = boxpos[1] = 0;
    boxpos[21] = boxpos[22] = 0; boxpos[23] = -10;
    testcam(&cam);
    assert(lsys_render_camera(&sq, &cam, 100, 100, proj, view) == LSYS_OK);
    project(proj, view, 100, 100, 1, -1, 0, out);
    assert(out[0] > 90 && out[0] <= 96 && out[1] > 90 && out[1] <= 96);
    project(proj, view, 100, 100, 0, 0, 1, out);
    assert(out[2] > 0 && out[2] < 1);   /* within the near plane */
  }
  /* a flat box (a 2D plant) and an empty scene */
  {
    static const double flo[3] = {-3, 0, 0}, fhi[3] = {3, 10, 0};
    lsys_mesh f = boxmesh(flo, fhi);
    double proj[16], view[16];
    testcam(&cam);
    checkfit(&f, &cam, 400, 400);
    cam.projection = LSYS_PARALLEL;
    checkfit(&f, &cam, 400, 400);
    assert(lsys_render_camera(&empty, &cam, 10, 10, proj, view) == LSYS_OK);
    assert(lsys_render_camera(NULL, &cam, 10, 10, proj, view) == LSYS_OK);
  }
}

/* Known points through a camera with a given eye. */
static void test_project (void) {
  static const double lo[3] = {-1, -1, 0}, hi[3] = {1, 1, 0};
  lsys_mesh m = boxmesh(lo, hi);
  lsys_camera cam;
  double proj[16], view[16], out[3], behind[3] = {0, 0, 20};
  testcam(&cam);
  cam.has_eye = cam.has_target = 1;
  cam.eye[2] = 10;                            /* target: the origin */
  cam.fov = 90;                               /* half height = distance */
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_OK);
  project(proj, view, 100, 100, 0, 0, 0, out);
  assert(fabs(out[0] - 50) < 1e-9 && fabs(out[1] - 50) < 1e-9);
  project(proj, view, 100, 100, 5, 0, 0, out);
  assert(fabs(out[0] - 75) < 1e-9 && fabs(out[1] - 50) < 1e-9);
  project(proj, view, 100, 100, 0, 5, 0, out);  /* y grows downwards */
  assert(fabs(out[0] - 50) < 1e-9 && fabs(out[1] - 25) < 1e-9);
  assert(lsys_render_project(proj, view, 100, 100, behind, out) == 0);
  /* a wide viewport keeps the vertical angle */
  assert(lsys_render_camera(&m, &cam, 200, 100, proj, view) == LSYS_OK);
  project(proj, view, 200, 100, 5, 5, 0, out);
  assert(fabs(out[0] - 125) < 1e-9 && fabs(out[1] - 25) < 1e-9);
  /* twist 90: the picture turns counterclockwise, +x goes up */
  cam.twist = 90;
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_OK);
  project(proj, view, 100, 100, 5, 0, 0, out);
  assert(fabs(out[0] - 50) < 1e-9 && fabs(out[1] - 25) < 1e-9);
  cam.twist = 0;
  cam.zoom = 2;
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_OK);
  project(proj, view, 100, 100, 5, 0, 0, out);
  assert(fabs(out[0] - 100) < 1e-9);
  cam.zoom = 1;
  /* parallel: the box's half height 1 fills 90% of the half image */
  cam.projection = LSYS_PARALLEL;
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_OK);
  project(proj, view, 100, 100, 1, -1, 0, out);
  assert(fabs(out[0] - 95) < 1e-9 && fabs(out[1] - 95) < 1e-9);
  /* an up vector along the view axis is replaced, not an error */
  cam.has_up = 1;
  cam.up[0] = 0; cam.up[1] = 0; cam.up[2] = 1;
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_OK);
  /* degenerate cameras */
  cam.has_up = 0;
  assert(lsys_render_camera(&m, &cam, 0, 100, proj, view) == LSYS_EARG);
  memset(cam.eye, 0, sizeof cam.eye);
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_EARG);
  cam.has_eye = cam.has_target = 0;
  memset(cam.dir, 0, sizeof cam.dir);
  assert(lsys_render_camera(&m, &cam, 100, 100, proj, view) == LSYS_EARG);
}

#endif

/* ---------------------------------------------------------------------- */
/* PNG */

static void pattern (uint8_t *p, int w, int h) {
  int x, y;
  for (y = 0; y < h; y++)
    for (x = 0; x < w; x++) {
      uint8_t *q = p + 4 * (y * w + x);
      q[0] = (uint8_t)(x * 37); q[1] = (uint8_t)(y * 53); q[2] = (uint8_t)(x * y);
      q[3] = (uint8_t)(255 - x - y);
    }
}

static long filesize (const char *path) {
  FILE *f = fopen(path, "rb");
  long n;
  assert(f != NULL);
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fclose(f);
  return n;
}

static void writefile (const char *path, const void *p, size_t n) {
  FILE *f = fopen(path, "wb");
  assert(f != NULL && fwrite(p, 1, n, f) == n);
  fclose(f);
}

static void *readfile (const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  char *p;
  assert(f != NULL);
  fseek(f, 0, SEEK_END);
  *n = (size_t)ftell(f);
  fseek(f, 0, SEEK_SET);
  p = malloc(*n);
  assert(p != NULL && fread(p, 1, *n, f) == *n);
  fclose(f);
  return p;
}

/* Writes a PNG of another colour type directly with libpng. */
static void writeraw (const char *path, int w, int h, int depth, int type, int interlace,
                      const uint8_t *rows, size_t rowbytes, const png_color *plte, int nplte) {
  FILE *f = fopen(path, "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
  png_infop info = png_create_info_struct(png);
  int y, pass, npass;
  assert(f && png && info);
  png_init_io(png, f);
  png_set_IHDR(png, info, w, h, depth, type, interlace, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (plte) png_set_PLTE(png, info, plte, nplte);
  png_write_info(png, info);
  npass = png_set_interlace_handling(png);
  for (pass = 0; pass < npass; pass++)
    for (y = 0; y < h; y++) png_write_row(png, rows + rowbytes * y);
  png_write_end(png, NULL);
  png_destroy_write_struct(&png, &info);
  fclose(f);
}

static void test_png (void) {
  enum { W = 7, H = 5 };
  uint8_t src[W * H * 4], *got = NULL;
  int w, h, i;
  lsys_error e;
  const char *p = testpath("pattern.png");
  pattern(src, W, H);
  /* RGBA round trip */
  assert(lsys_pngio_write(p, src, W, H, 1, &e) == LSYS_OK);
  assert(lsys_pngio_read(p, &got, &w, &h, &e) == LSYS_OK);
  assert(w == W && h == H && memcmp(got, src, sizeof src) == 0);
  free(got);
  /* RGB: alpha dropped on writing, 255 on reading */
  assert(lsys_pngio_write(p, src, W, H, 0, &e) == LSYS_OK);
  assert(lsys_pngio_read(p, &got, &w, &h, &e) == LSYS_OK);
  for (i = 0; i < W * H; i++) {
    assert(memcmp(got + 4 * i, src + 4 * i, 3) == 0);
    assert(got[4 * i + 3] == 255);
  }
  free(got);
  /* 4-bit palette */
  {
    static const png_color plte[3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}};
    uint8_t rows[2][2] = {{0x01, 0x20}, {0x22, 0x10}};     /* 4 pixels a row, 2 rows */
    static const uint8_t want[8] = {0, 1, 2, 0, 2, 2, 1, 0};
    writeraw(p, 4, 2, 4, PNG_COLOR_TYPE_PALETTE, PNG_INTERLACE_NONE, rows[0], 2, plte, 3);
    assert(lsys_pngio_read(p, &got, &w, &h, &e) == LSYS_OK);
    assert(w == 4 && h == 2);
    for (i = 0; i < 8; i++) {
      assert(memcmp(got + 4 * i, &plte[want[i]], 3) == 0);
      assert(got[4 * i + 3] == 255);
    }
    free(got);
  }
  /* 16-bit grey + alpha, interlaced */
  {
    uint8_t rows[9][9 * 4];
    int x, y;
    for (y = 0; y < 9; y++)
      for (x = 0; x < 9; x++) {
        rows[y][4 * x] = (uint8_t)(x * 20 + y); rows[y][4 * x + 1] = 0x55;
        rows[y][4 * x + 2] = (uint8_t)(y * 25); rows[y][4 * x + 3] = 0xaa;
      }
    writeraw(p, 9, 9, 16, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_INTERLACE_ADAM7, rows[0], 36, NULL,
             0);
    assert(lsys_pngio_read(p, &got, &w, &h, &e) == LSYS_OK);
    assert(w == 9 && h == 9);
    for (y = 0; y < 9; y++)
      for (x = 0; x < 9; x++) {
        const uint8_t *q = got + 4 * (9 * y + x);
        assert(q[0] == x * 20 + y && q[1] == q[0] && q[2] == q[0] && q[3] == y * 25);
      }
    free(got);
  }
  /* errors name the file and the reason, and never crash */
  assert(lsys_pngio_write("/nonexistent-dir/x.png", src, W, H, 0, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "cannot open '/nonexistent-dir/x.png' for writing: "
                       "No such file or directory") == 0);
  assert(lsys_pngio_read("/nonexistent-dir/x.png", &got, &w, &h, &e) == LSYS_EARG);
  assert(got == NULL && strstr(e.msg, "cannot open '/nonexistent-dir/x.png' for reading"));
  {
    const char *q = testpath("bad.png");
    size_t n, k;
    uint8_t *good;
    writefile(q, "hello, not a picture", 20);
    assert(lsys_pngio_read(q, &got, &w, &h, &e) == LSYS_ESYNTAX && got == NULL);
    assert(strstr(e.msg, "is not a PNG file") && strstr(e.msg, q));
    writefile(q, "", 0);
    assert(lsys_pngio_read(q, &got, &w, &h, &e) == LSYS_ESYNTAX && got == NULL);
    /* every truncation of a valid file fails cleanly */
    assert(lsys_pngio_write(p, src, W, H, 1, &e) == LSYS_OK);
    good = readfile(p, &n);
    for (k = 0; k < n; k++) {
      writefile(q, good, k);
      assert(lsys_pngio_read(q, &got, &w, &h, &e) != LSYS_OK && got == NULL);
      assert(strstr(e.msg, q) != NULL);
    }
    /* a flipped byte anywhere after the signature: an error or a picture, no crash */
    for (k = 8; k < n; k++) {
      good[k] ^= 0x5a;
      writefile(q, good, n);
      if (lsys_pngio_read(q, &got, &w, &h, &e) == LSYS_OK) free(got);
      else assert(got == NULL && strstr(e.msg, q) != NULL);
      good[k] ^= 0x5a;
    }
    writefile(q, good, n / 2);
    assert(lsys_pngio_read(q, &got, &w, &h, &e) == LSYS_ESYNTAX);
    assert(strstr(e.msg, "unexpected end of file") != NULL);
    free(good);
    remove(q);
  }
  assert(filesize(p) > 0);
  remove(p);
}

/* ---------------------------------------------------------------------- */
/* textures: loading */

static void test_texture_load (void) {
  static const uint8_t grey[2 * 4] = {10, 10, 10, 255, 200, 200, 200, 128};
  static const uint8_t colour[2 * 4] = {10, 10, 10, 255, 200, 201, 200, 255};
  const char *p = testpath("tex.png"), *q = testpath("nottex.png");
  lsys_texture t;
  lsys_error e;
  lsys_texture_init(&t);
  assert(t.rgba == NULL && t.path == NULL && t.mode == LSYS_TEX_MODULATE && !t.intensity);
  assert(!t.mag_linear && !t.min_linear && !t.per_surface);
  /* a grey image sets intensity, a colour one clears it; the path is copied */
  assert(lsys_pngio_write(p, grey, 2, 1, 1, &e) == LSYS_OK);
  t.mode = LSYS_TEX_DECAL;
  t.mag_linear = 1;
  assert(lsys_texture_load(&t, p, &e) == LSYS_OK);
  assert(t.w == 2 && t.h == 1 && t.intensity == 1 && memcmp(t.rgba, grey, 8) == 0);
  assert(t.path != p && strcmp(t.path, p) == 0);
  assert(t.mode == LSYS_TEX_DECAL && t.mag_linear == 1);      /* settings kept */
  assert(lsys_texture_hasalpha(&t) == 1);
  assert(lsys_pngio_write(p, colour, 2, 1, 1, &e) == LSYS_OK);
  assert(lsys_texture_load(&t, p, &e) == LSYS_OK);            /* replaces the pixels */
  assert(t.intensity == 0 && t.rgba[5] == 201 && lsys_texture_hasalpha(&t) == 0);
  /* failures name the file and leave the texture as it was */
  assert(lsys_texture_load(&t, "/nonexistent-dir/t.png", &e) == LSYS_EARG);
  assert(strstr(e.msg, "/nonexistent-dir/t.png") != NULL);
  writefile(q, "GIF89a not a png", 16);
  assert(lsys_texture_load(&t, q, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, q) != NULL && strstr(e.msg, "not a PNG") != NULL);
  assert(t.w == 2 && t.rgba[5] == 201 && strcmp(t.path, p) == 0);
  /* the intensity of §5, rounded */
  {
    static const uint8_t red[3] = {255, 0, 0}, green[3] = {0, 255, 0}, blue[3] = {0, 0, 255};
    static const uint8_t white[3] = {255, 255, 255}, mix[3] = {100, 150, 200};
    assert(lsys_texture_intensity(red) == 76 && lsys_texture_intensity(green) == 150);
    assert(lsys_texture_intensity(blue) == 29 && lsys_texture_intensity(white) == 255);
    assert(lsys_texture_intensity(mix) == 141);     /* 29.9 + 88.05 + 22.8 = 140.75 */
  }
  lsys_texture_free(&t);
  assert(t.rgba == NULL && t.path == NULL && t.w == 0);
  lsys_texture_free(&t);                            /* idempotent */
  remove(p);
  remove(q);
}

/* ---------------------------------------------------------------------- */
/* offscreen rendering */

#ifndef LSYS_NO_RENDER

enum { IW = 64, IH = 64 };

/* A red quad in the upper left (two triangles facing +z), a thick blue
** line in the lower right (drawn as a band) and a thin one in the lower left
** (a GL line). */
static float qpos[12] = {-2, 0.2f, 0, -0.4f, 0.2f, 0, -0.4f, 1.8f, 0, -2, 1.8f, 0};
static float qnrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static float quv[8];
static uint16_t qcol[4];
static uint8_t qts[4];
static uint32_t qtri[6] = {0, 1, 2, 0, 2, 3};
static float lpos[12] = {0.4f, -1.8f, 0, 2, -0.2f, 0, -2, -1.5f, 0, -0.5f, -1.5f, 0};
static float lwid[4] = {4, 4, 1, 1};
static uint16_t lcol[2] = {1, 1};

static lsys_mesh scene (void) {
  lsys_mesh m = {0};
  m.pos = qpos; m.nrm = qnrm; m.uv = quv; m.col = qcol; m.twosided = qts;
  m.nv = 4;
  m.tri = qtri; m.nt = 2;
  m.lpos = lpos; m.lwidth = lwid; m.lcol = lcol; m.nl = 2;
  return m;
}

static const uint8_t *pixel (const uint8_t *img, double x, double y) {
  return img + 4 * ((int)y * IW + (int)x);
}

static void dump (const uint8_t *img, const char *name) {
  const char *dir = getenv("LSYS_RENDER_DUMP");
  char path[512];
  lsys_error e;
  if (dir == NULL) return;
  snprintf(path, sizeof path, "%s/%s", dir, name);
  assert(lsys_pngio_write(path, img, IW, IH, 1, &e) == LSYS_OK);
}

static int brightness (const uint8_t *p) {
  return p[0] + p[1] + p[2];
}

/* The bluest pixel within 'd' pixels of (x, y). */
static const uint8_t *bluest (const uint8_t *img, double x, double y, int d) {
  const uint8_t *best = pixel(img, x, y);
  int i, j;
  for (j = -d; j <= d; j++)
    for (i = -d; i <= d; i++) {
      const uint8_t *p = pixel(img, x + i, y + j);
      if (p[2] - p[0] > best[2] - best[0]) best = p;
    }
  return best;
}

/* The look these tests were written for: the camera of testcam, a white
** background, the light from the upper front left. The scene's arrays are
** the caller's (it is never freed). */
static void testlook (lsys_scene *sc) {
  lsys_scene_init(sc);
  testcam(&sc->cam);
  sc->background[0] = sc->background[1] = sc->background[2] = 1;
  sc->light[0] = -1; sc->light[1] = 1; sc->light[2] = 1;
}

/* Renders mesh 'm' seen as 'sc' says (scene.h: a copy borrowing the arrays). */
static int offscreen (const lsys_mesh *m, const lsys_scene *sc, const lsys_render_opts *o,
                      uint8_t *img, lsys_error *e) {
  lsys_scene v = *sc;
  v.mesh = *m;
  return lsys_render_offscreen(&v, o, img, e);
}

static void test_offscreen (void) {
  lsys_material pal[3];
  lsys_mesh m = scene(), empty = {0};
  lsys_render_opts o;
  lsys_scene sc;
  lsys_error e;
  double proj[16], view[16], q[3];
  double quad[3] = {-1.2, 1.0, 0}, line[3] = {1.2, -1.0, 0}, thin[3] = {-1.25, -1.5, 0};
  uint8_t img[IW * IH * 4];
  const uint8_t *c;
  int ss, i, back[2];
  lsys_mesh_material_color(&pal[0], 1, 0, 0);
  lsys_mesh_material_color(&pal[1], 0, 0, 1);
  lsys_mesh_material_color(&pal[2], 1, 0, 0);
  pal[2].diffuse[3] = 0.5f;                     /* translucent red */
  lsys_render_defaults(&o);
  testlook(&sc);
  o.width = IW; o.height = IH;
  sc.pal = pal; sc.npal = 3;
  assert(lsys_render_camera(&m, &sc.cam, IW, IH, proj, view) == LSYS_OK);
  for (ss = 1; ss <= 3; ss += 2) {
    o.supersample = ss;
    memset(img, 0x33, sizeof img);
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    dump(img, ss == 1 ? "render1.png" : "render3.png");
    /* corners: the white background */
    for (i = 0; i < 4; i++) {
      c = pixel(img, (i & 1) ? IW - 1 : 0, (i & 2) ? IH - 1 : 0);
      assert(c[0] == 255 && c[1] == 255 && c[2] == 255 && c[3] == 255);
    }
    /* the quad is red, in the top half (top row first) */
    lsys_render_project(proj, view, IW, IH, quad, q);
    assert(q[1] < IH / 2);
    c = pixel(img, q[0], q[1]);
    assert(c[0] > 120 && c[1] < 40 && c[2] < 40);
    c = pixel(img, q[0], IH - 1 - q[1]);           /* mirrored: background */
    assert(c[0] == 255 && c[1] == 255 && c[2] == 255);
    /* the lines are blue */
    lsys_render_project(proj, view, IW, IH, line, q);
    c = pixel(img, q[0], q[1]);
    assert(c[2] > 150 && c[0] < 100 && c[1] < 100);
    lsys_render_project(proj, view, IW, IH, thin, q);
    c = bluest(img, q[0], q[1], 1);
    assert(c[2] > 150 && c[0] < 160 && c[1] < 160);
    /* the wide line has a round end: blue 1.5 pixels past its end point,
    ** background past its radius (2 pixels) */
    {
      double a[3] = {lpos[0], lpos[1], lpos[2]}, b[3] = {lpos[3], lpos[4], lpos[5]}, pa[3],
             pb[3], dx, dy, len;
      lsys_render_project(proj, view, IW, IH, a, pa);
      lsys_render_project(proj, view, IW, IH, b, pb);
      dx = pb[0] - pa[0]; dy = pb[1] - pa[1];
      len = sqrt(dx * dx + dy * dy);
      dx /= len; dy /= len;
      c = pixel(img, pb[0] + 1.5 * dx, pb[1] + 1.5 * dy);
      assert(c[2] > c[0] + 60);
      c = pixel(img, pb[0] + 4 * dx, pb[1] + 4 * dy);
      assert(c[0] == 255 && c[1] == 255 && c[2] == 255);
    }
  }
  /* anti-aliasing: with supersampling, edge pixels take in-between values */
  {
    int mixed = 0;
    for (i = 0; i < IW * IH; i++) {
      const uint8_t *p = img + 4 * i;
      if (p[1] > 40 && p[1] < 215 && p[0] > p[1] + 20) mixed++;
    }
    assert(mixed > 10);
  }
  /* a translucent material blends with what is behind it */
  for (i = 0; i < 4; i++) qcol[i] = 2;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  lsys_render_project(proj, view, IW, IH, quad, q);
  c = pixel(img, q[0], q[1]);
  assert(c[0] > 180 && c[1] > 60 && c[1] < 200 && c[1] == c[2]);
  for (i = 0; i < 4; i++) qcol[i] = 0;
  /* a transparent background */
  o.transparent = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  assert(pixel(img, 0, 0)[3] == 0);
  lsys_render_project(proj, view, IW, IH, quad, q);
  assert(pixel(img, q[0], q[1])[3] == 255);
  o.transparent = 0;
  /* two-sided: seen from behind with the light behind, a two-sided quad is
  ** lit on its back face by the key light, a one-sided one only by the fill
  ** opposite it and ambient light */
  sc.cam.dir[2] = 1;
  sc.light[0] = 0; sc.light[1] = 0; sc.light[2] = -1;
  assert(lsys_render_camera(&m, &sc.cam, IW, IH, proj, view) == LSYS_OK);
  lsys_render_project(proj, view, IW, IH, quad, q);
  for (i = 0; i < 2; i++) {
    memset(qts, i, sizeof qts);
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    dump(img, i ? "back2.png" : "back1.png");
    back[i] = brightness(pixel(img, q[0], q[1]));
  }
  memset(qts, 0, sizeof qts);
  assert(back[1] > back[0] + 60);       /* 255 and 167: the key light against the fill */
  /* wireframe still draws, an empty scene is all background */
  lsys_render_defaults(&o);
  testlook(&sc);
  o.width = IW; o.height = IH; o.wireframe = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  o.wireframe = 0;
  assert(offscreen(&empty, &sc, &o, img, &e) == LSYS_OK);
  for (i = 0; i < IW * IH * 4; i++) assert(img[i] == 255);
  /* a wide line through the eye is cut at the near plane */
  {
    static float zpos[6] = {0.1f, 0.1f, -3, 0.1f, 0.1f, 3};
    lsys_mesh z = m;
    z.lpos = zpos; z.nl = 1;
    sc.cam.has_eye = sc.cam.has_target = 1;
    sc.cam.eye[0] = 0; sc.cam.eye[1] = 0; sc.cam.eye[2] = 0.5;
    sc.cam.target[0] = 0; sc.cam.target[1] = 0; sc.cam.target[2] = -1;
    assert(offscreen(&z, &sc, &o, img, &e) == LSYS_OK);
    sc.cam.has_eye = sc.cam.has_target = 0;
  }
  /* coordinates and widths that are not numbers draw nothing useful but
  ** do not crash; the camera falls back to the finite part */
  {
    static float bpos[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0};
    static float bl[12] = {0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0};
    static float bw[4] = {1e30f, -2, 5, 5};
    lsys_mesh b = m;
    bpos[9] = NAN; bl[3] = INFINITY; bl[7] = NAN; bw[2] = NAN;
    b.pos = bpos; b.lpos = bl; b.lwidth = bw;
    assert(offscreen(&b, &sc, &o, img, &e) == LSYS_OK);
    bl[3] = 1; bl[7] = 1;
    assert(offscreen(&b, &sc, &o, img, &e) == LSYS_OK);
  }
  /* a scratch cache kept by the caller */
  {
    lsys_render_cache cache = {0};
    o.cache = &cache;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    lsys_render_cache_free(&cache);
    o.cache = NULL;
  }
  /* errors */
  sc.mesh = m;
  assert(lsys_render_draw(&sc, &o, IW, IH, &e) == LSYS_EARG);     /* no entry points */
  o.width = 0;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_EARG);
  o.width = 1 << 20;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_ELIMIT);
  assert(strstr(e.msg, "exceeds OSMesa's limit") != NULL);
}

/* ---------------------------------------------------------------------- */
/* textured rendering */

/* The square [-1, 1]^2 facing +z, uv (0, 0) at its bottom left corner and
** (1, 1) at its top right; all vertices of colour 0 and texture 'k'. */
static float tpos[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
static float tnrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static float tuv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
static uint16_t tcol[4], ttex[4];
static uint8_t tts[4];
static uint32_t ttri[6] = {0, 1, 2, 0, 2, 3};

static lsys_mesh texquad (unsigned k) {
  lsys_mesh m = {0};
  int i;
  for (i = 0; i < 4; i++) ttex[i] = (uint16_t)k;
  m.pos = tpos; m.nrm = tnrm; m.uv = tuv; m.col = tcol; m.twosided = tts; m.tex = ttex;
  m.nv = 4;
  m.tri = ttri; m.nt = 2;
  return m;
}

/* The 2 x 2 checker, top row first: red green / blue white. */
static uint8_t checker[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};

static lsys_texture maketex (uint8_t *rgba, int w, int h) {
  lsys_texture t;
  lsys_texture_init(&t);
  t.rgba = rgba; t.w = w; t.h = h;
  return t;
}

/* The pixel at world point (x, y, 0). */
static const uint8_t *at (const uint8_t *img, const lsys_mesh *m, const lsys_scene *sc,
                          double x, double y) {
  double proj[16], view[16], p[3] = {x, y, 0}, q[3];
  assert(lsys_render_camera(m, &sc->cam, IW, IH, proj, view) == LSYS_OK);
  assert(lsys_render_project(proj, view, IW, IH, p, q) == 1);
  return pixel(img, q[0], q[1]);
}

static int near (int a, double b, double tol) {
  return fabs(a - b) <= tol;
}

/* Each channel of the pixel is lit * texel / 255 within 'tol'. */
static int modulated (const uint8_t *px, const uint8_t *lit, const uint8_t *texel, double tol) {
  int i;
  for (i = 0; i < 3; i++)
    if (!near(px[i], lit[i] * texel[i] / 255.0, tol)) return 0;
  return 1;
}

static void test_textured (void) {
  /* quadrant centres (world) and the checker texel each shows */
  static const double qx[4] = {-0.5, 0.5, -0.5, 0.5}, qy[4] = {0.5, 0.5, -0.5, -0.5};
  lsys_material pal[2];
  lsys_texture tx = maketex(checker, 2, 2), tx2;
  const lsys_texture *list[3] = {&tx, NULL, NULL};
  lsys_mesh m = texquad(1);
  lsys_render_opts o;
  lsys_scene sc;
  lsys_error e;
  uint8_t ref[IW * IH * 4], img[IW * IH * 4], lit[4];
  int i, k;
  lsys_mesh_material_color(&pal[0], 1, 1, 1);
  lsys_mesh_material_color(&pal[1], 1, 1, 1);
  pal[1].diffuse[3] = 0.5f;
  lsys_render_defaults(&o);
  testlook(&sc);
  o.width = IW; o.height = IH; o.supersample = 1;
  sc.cam.projection = LSYS_PARALLEL;
  sc.pal = pal; sc.npal = 2;
  /* without textures: the lit white square, the same with no texture array */
  assert(offscreen(&m, &sc, &o, ref, &e) == LSYS_OK);
  dump(ref, "tex_none.png");
  memcpy(lit, at(ref, &m, &sc, 0.5, 0.5), 4);
  assert(lit[0] > 100 && lit[0] < 250 && lit[0] == lit[1] && lit[1] == lit[2]);
  for (k = 0; k < 4; k++) assert(memcmp(at(ref, &m, &sc, qx[k], qy[k]), lit, 4) == 0);
  m.tex = NULL;
  sc.tex = list; sc.ntex = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  assert(memcmp(img, ref, sizeof img) == 0);
  /* indices 0, past the end, or of a missing or empty texture draw untextured */
  sc.ntex = 2;
  for (k = 0; k < 4; k++) {
    static const unsigned idx[4] = {0, 3, 2, 2};
    lsys_texture empty;
    lsys_texture_init(&empty);
    list[1] = k == 3 ? &empty : NULL;
    m = texquad(idx[k]);
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(memcmp(img, ref, sizeof img) == 0);
  }
  list[1] = NULL;
  /* modulate, nearest: each quadrant is the lit colour times its texel */
  m = texquad(1);
  sc.ntex = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  dump(img, "tex_modulate.png");
  for (k = 0; k < 4; k++)
    assert(modulated(at(img, &m, &sc, qx[k], qy[k]), lit, checker + 4 * k, 2));
  /* the v axis points up the image: the bottom left quadrant is blue */
  assert(at(img, &m, &sc, -0.5, -0.5)[2] > 100 && at(img, &m, &sc, -0.5, -0.5)[0] == 0);
  /* decal: the texels themselves, unlit */
  tx.mode = LSYS_TEX_DECAL;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  dump(img, "tex_decal.png");
  for (k = 0; k < 4; k++) assert(memcmp(at(img, &m, &sc, qx[k], qy[k]), checker + 4 * k, 3) == 0);
  /* intensity in modulate mode: grey levels I = 0.299 R + 0.587 G + 0.114 B */
  tx.mode = LSYS_TEX_MODULATE;
  tx.intensity = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  dump(img, "tex_intensity.png");
  for (k = 0; k < 4; k++) {
    const uint8_t *px = at(img, &m, &sc, qx[k], qy[k]);
    double want = lit[0] * lsys_texture_intensity(checker + 4 * k) / 255.0;
    assert(near(px[0], want, 2) && px[0] == px[1] && px[1] == px[2]);
  }
  /* intensity is ignored by decal: the colours stay */
  tx.mode = LSYS_TEX_DECAL;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  for (k = 0; k < 4; k++) assert(memcmp(at(img, &m, &sc, qx[k], qy[k]), checker + 4 * k, 3) == 0);
  tx.intensity = 0;
  /* linear magnification (decal still): the centre mixes the four texels, a
  ** texel centre stays pure */
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  {
    const uint8_t *c = at(img, &m, &sc, 0, 0);
    assert(c[0] < 5 || c[0] > 250 || c[1] < 5 || c[1] > 250 || c[2] < 5 || c[2] > 250);
  }
  tx.mag_linear = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  dump(img, "tex_linear.png");
  {
    const uint8_t *c = at(img, &m, &sc, 0.02, 0.02);
    for (i = 0; i < 3; i++) assert(c[i] > 60 && c[i] < 200);
    c = at(img, &m, &sc, -0.5, 0.5);     /* within a pixel (1/58 of the square) of the centre */
    assert(c[0] > 240 && c[1] < 15 && c[2] < 15);
  }
  tx.mag_linear = 0;
  /* alpha: in modulate mode a texel below 1/2 is cut out (the background
  ** shows), in decal mode it lets the lit colour through */
  {
    uint8_t cut[16];
    memcpy(cut, checker, 16);
    cut[7] = 0;                                 /* green, transparent */
    cut[15] = 200;                              /* white, mostly opaque */
    tx2 = maketex(cut, 2, 2);
    list[0] = &tx2;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    dump(img, "tex_cut.png");
    assert(memcmp(at(img, &m, &sc, 0.5, 0.5), "\xff\xff\xff", 3) == 0);
    assert(modulated(at(img, &m, &sc, -0.5, 0.5), lit, checker, 2));
    assert(modulated(at(img, &m, &sc, 0.5, -0.5), lit, checker + 12, 2));
    tx2.mode = LSYS_TEX_DECAL;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(memcmp(at(img, &m, &sc, 0.5, 0.5), lit, 3) == 0);
    assert(memcmp(at(img, &m, &sc, -0.5, 0.5), checker, 3) == 0);
    list[0] = &tx;
  }
  /* a size that is not a power of two: 3 x 1, three vertical bands */
  {
    static uint8_t bands[12] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255};
    tx2 = maketex(bands, 3, 1);
    tx2.mode = LSYS_TEX_DECAL;
    list[0] = &tx2;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    dump(img, "tex_bands.png");
    for (k = 0; k < 3; k++)
      for (i = 0; i < 3; i++)
        assert(memcmp(at(img, &m, &sc, -2.0 / 3 + k * 2.0 / 3, 0.8 - 0.8 * i), bands + 4 * k,
                      3) == 0);
    list[0] = &tx;
  }
  /* wider than OpenGL's largest texture (16384 in Mesa): resampled, red
  ** left of the middle, blue right of it */
  {
    enum { BIG = 20000 };
    uint8_t *wide = malloc(4 * BIG);
    assert(wide != NULL);
    for (i = 0; i < BIG; i++) memcpy(wide + 4 * i, i < BIG / 2 ? checker : checker + 8, 4);
    tx2 = maketex(wide, BIG, 1);
    tx2.mode = LSYS_TEX_DECAL;
    list[0] = &tx2;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(memcmp(at(img, &m, &sc, -0.1, 0.5), checker, 3) == 0);
    assert(memcmp(at(img, &m, &sc, 0.1, -0.5), checker + 8, 3) == 0);
    free(wide);
    list[0] = &tx;
  }
  /* an intensity texture with transparent texels: grey, and cut out */
  {
    uint8_t ga[16] = {100, 100, 100, 255, 200, 200, 200, 0, 50, 50, 50, 255, 0, 0, 0, 255};
    tx2 = maketex(ga, 2, 2);
    tx2.intensity = 1;
    list[0] = &tx2;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(near(at(img, &m, &sc, -0.5, 0.5)[0], lit[0] * 100 / 255.0, 2));
    assert(near(at(img, &m, &sc, -0.5, -0.5)[1], lit[0] * 50 / 255.0, 2));
    assert(memcmp(at(img, &m, &sc, 0.5, 0.5), "\xff\xff\xff", 3) == 0);
    list[0] = &tx;
  }
  /* uv beyond [0, 1] repeats */
  for (i = 0; i < 8; i++) tuv[i] *= 2;
  tx.mode = LSYS_TEX_DECAL;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  assert(memcmp(at(img, &m, &sc, -0.75, 0.75), checker, 3) == 0);
  assert(memcmp(at(img, &m, &sc, -0.25, 0.75), checker + 4, 3) == 0);
  assert(memcmp(at(img, &m, &sc, 0.25, 0.75), checker, 3) == 0);
  assert(memcmp(at(img, &m, &sc, 0.25, 0.25), checker + 8, 3) == 0);
  for (i = 0; i < 8; i++) tuv[i] /= 2;
  tx.mode = LSYS_TEX_MODULATE;
  /* a translucent material keeps its texture and blends with the background */
  for (i = 0; i < 4; i++) tcol[i] = 1;
  assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
  dump(img, "tex_translucent.png");
  {
    const uint8_t *c = at(img, &m, &sc, -0.5, 0.5);    /* red at half: 255 / 2 + lit / 2 */
    assert(near(c[0], 127.5 + lit[0] / 2.0, 3) && near(c[1], 127.5, 3) && c[1] == c[2]);
  }
  for (i = 0; i < 4; i++) tcol[i] = 0;
  /* two textures in one scene, textured and plain triangles mixed in each
  ** material group: the second triangle uses texture 2, a grey ramp */
  {
    static uint8_t g2[4] = {60, 60, 60, 255};
    lsys_texture t2 = maketex(g2, 1, 1);
    list[1] = &t2;
    sc.ntex = 2;
    t2.mode = tx.mode = LSYS_TEX_DECAL;
    ttex[0] = 2;                               /* triangle 0 1 2 (lower right) and 0 2 3 */
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    dump(img, "tex_two.png");
    assert(memcmp(at(img, &m, &sc, 0.6, -0.6), g2, 3) == 0);
    assert(memcmp(at(img, &m, &sc, -0.6, 0.6), g2, 3) == 0);   /* both share vertex 0 */
    ttri[3] = 3; ttri[4] = 0; ttri[5] = 2;     /* the upper left triangle starts at vertex 3 */
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(memcmp(at(img, &m, &sc, 0.6, -0.6), g2, 3) == 0);
    assert(memcmp(at(img, &m, &sc, -0.5, 0.5), checker, 3) == 0);
    ttri[3] = 0; ttri[4] = 2; ttri[5] = 3;
    ttex[0] = 1;
    tx.mode = LSYS_TEX_MODULATE;
    list[1] = NULL;
    sc.ntex = 1;
  }
  /* wireframe ignores textures; a kept cache works across renders */
  {
    lsys_render_cache cache = {0};
    o.wireframe = 1;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    o.wireframe = 0;
    o.cache = &cache;
    assert(offscreen(&m, &sc, &o, img, &e) == LSYS_OK);
    assert(offscreen(&m, &sc, &o, ref, &e) == LSYS_OK);
    assert(memcmp(img, ref, sizeof img) == 0);
    lsys_render_cache_free(&cache);
    o.cache = NULL;
  }
}

#endif

int main (void) {
  test_png();
  test_texture_load();
#ifndef LSYS_NO_RENDER                /* render.c is left out of such a build */
  test_fit();
  test_project();
  test_offscreen();
  test_textured();
  lsys_render_shutdown();
#endif
  printf("test_render: ok\n");
  return 0;
}
