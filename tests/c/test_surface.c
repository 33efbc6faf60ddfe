/*
** C unit tests for bicubic surfaces (csrc/core/surface.c): patch evaluation in
** the three bases against hand-computed points and finite differences; the
** surface file reader on the files in tests/data/surfaces, on variants of the format
** and on malformed files (exact messages); tessellation counts, placement,
** normals, winding, texture coordinates; allocation failures and balance.
**
** surface.c, mesh.c and common.c are compiled into this test with counting
** allocators, so that every allocation can be made to fail in turn.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long nalloc, failat = -1;    /* allocation number 'failat' fails */
static long live;                   /* blocks allocated and not freed */

static void *tmalloc (size_t n) {
  void *p = nalloc++ == failat ? NULL : malloc(n);
  if (p != NULL) live++;
  return p;
}

static void *trealloc (void *p, size_t n) {
  void *q = nalloc++ == failat ? NULL : realloc(p, n);
  if (q != NULL && p == NULL) live++;
  return q;
}

static void tfree (void *p) {
  if (p != NULL) live--;
  free(p);
}

#define LSYS_MALLOC(n)     tmalloc(n)
#define LSYS_REALLOC(p, n) trealloc((p), (n))
#define LSYS_FREE(p)       tfree(p)
#include "common.c"
#include "mesh.c"
#include "surface.c"

#define LEAF  "tests/data/surfaces/leaf.s"
#define PETAL "tests/data/surfaces/petal.s"

static int near (double a, double b, double tol) {
  return fabs(a - b) <= tol;
}

static void nearv (const double *a, double x, double y, double z, double tol) {
  if (!near(a[0], x, tol) || !near(a[1], y, tol) || !near(a[2], z, tol)) {
    fprintf(stderr, "got (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)\n", a[0], a[1],
            a[2], x, y, z);
    assert(0);
  }
}

static char *slurp (const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  char *s;
  long n;
  assert(f != NULL);
  assert(fseek(f, 0, SEEK_END) == 0);
  n = ftell(f);
  assert(n > 0);
  rewind(f);
  s = malloc((size_t)n);          /* no terminating NUL: the parser must not need one */
  assert(s != NULL);
  assert(fread(s, 1, (size_t)n, f) == (size_t)n);
  fclose(f);
  *len = (size_t)n;
  return s;
}

static void loadfile (lsys_surface *s, const char *path) {
  size_t len;
  char *text = slurp(path, &len);
  lsys_error e;
  int st = lsys_surface_parse(s, text, len, path, &e);
  if (st != LSYS_OK) fprintf(stderr, "%s\n", e.msg);
  assert(st == LSYS_OK);
  free(text);
}

static void setctrl (lsys_patch *p, int r, int c, double x, double y, double z) {
  double *g = p->ctrl + 3 * (4 * r + c);
  g[0] = x; g[1] = y; g[2] = z;
}

static const double *ctrl (const lsys_patch *p, int r, int c) {
  return p->ctrl + 3 * (4 * r + c);
}

/* A reproducible patch of values in [-1, 1]. */
static void randpatch (lsys_patch *p, unsigned seed) {
  int k;
  for (k = 0; k < 48; k++) {
    seed = seed * 1103515245u + 12345u;
    p->ctrl[k] = ((seed >> 8) & 0xffff) / 32767.5 - 1;
  }
}

/* ---- evaluation ---- */

static void test_bezier (void) {
  lsys_patch p;
  double pos[3], ds[3], dt[3];
  int r, c, i, j;
  /* a flat grid: Bernstein polynomials reproduce linear functions */
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) setctrl(&p, r, c, c, r, 0);
  for (i = 0; i <= 4; i++)
    for (j = 0; j <= 4; j++) {
      double s = i / 4.0, t = j / 4.0;
      lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, s, t, pos, ds, dt);
      nearv(pos, 3 * s, 3 * t, 0, 1e-14);
      nearv(ds, 3, 0, 0, 1e-13);
      nearv(dt, 0, 3, 0, 1e-13);
    }
  /* corners interpolate: s runs across columns, t across rows */
  randpatch(&p, 7);
  lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 0, 0, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 0, 0)[0], ctrl(&p, 0, 0)[1], ctrl(&p, 0, 0)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 1, 0, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 0, 3)[0], ctrl(&p, 0, 3)[1], ctrl(&p, 0, 3)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 0, 1, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 3, 0)[0], ctrl(&p, 3, 0)[1], ctrl(&p, 3, 0)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 1, 1, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 3, 3)[0], ctrl(&p, 3, 3)[1], ctrl(&p, 3, 3)[2], 1e-15);
  /* one raised control point, row 1 column 2: z = B1(t) B2(s) at (0.5, 0.25) */
  memset(&p, 0, sizeof p);
  setctrl(&p, 1, 2, 0, 0, 1);
  lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 0.5, 0.25, pos, NULL, NULL);
  nearv(pos, 0, 0, (3 * 0.25 * 0.75 * 0.75) * (3 * 0.25 * 0.5), 1e-15);
  /* an unknown basis is Bézier */
  randpatch(&p, 9);
  {
    double q[3];
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &p, 0.3, 0.7, pos, NULL, NULL);
    lsys_surface_patch_eval(42, &p, 0.3, 0.7, q, NULL, NULL);
    nearv(q, pos[0], pos[1], pos[2], 0);
  }
}

static void test_bspline (void) {
  lsys_patch p;
  double pos[3], w[4] = {1.0 / 6, 4.0 / 6, 1.0 / 6, 0}, z = 0;
  int r, c;
  /* unit grid with random heights: at (0,0) the weights are (1,4,1,0)/6 */
  randpatch(&p, 3);
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) {
      setctrl(&p, r, c, c, r, ctrl(&p, r, c)[2]);
      z += w[r] * w[c] * ctrl(&p, r, c)[2];
    }
  lsys_surface_patch_eval(LSYS_BASIS_BSPLINE, &p, 0, 0, pos, NULL, NULL);
  nearv(pos, 1, 1, z, 1e-14);
  /* at (1,1) the weights are (0,1,4,1)/6: x = y = 2 */
  lsys_surface_patch_eval(LSYS_BASIS_BSPLINE, &p, 1, 1, pos, NULL, NULL);
  assert(near(pos[0], 2, 1e-14) && near(pos[1], 2, 1e-14));
  /* (s, t) = (1, 0): x from the columns' weights (0,1,4,1)/6, y from (1,4,1,0)/6 */
  lsys_surface_patch_eval(LSYS_BASIS_BSPLINE, &p, 1, 0, pos, NULL, NULL);
  assert(near(pos[0], 2, 1e-14) && near(pos[1], 1, 1e-14));
  /* linear precision in the middle too */
  lsys_surface_patch_eval(LSYS_BASIS_BSPLINE, &p, 0.25, 0.5, pos, NULL, NULL);
  assert(near(pos[0], 1.25, 1e-14) && near(pos[1], 1.5, 1e-14));
}

static void test_cardinal (void) {
  lsys_patch p;
  double pos[3];
  randpatch(&p, 5);
  /* the corners of the parameter square are control points (1,1) (1,2) (2,1) (2,2) */
  lsys_surface_patch_eval(LSYS_BASIS_CARDINAL, &p, 0, 0, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 1, 1)[0], ctrl(&p, 1, 1)[1], ctrl(&p, 1, 1)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_CARDINAL, &p, 1, 0, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 1, 2)[0], ctrl(&p, 1, 2)[1], ctrl(&p, 1, 2)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_CARDINAL, &p, 0, 1, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 2, 1)[0], ctrl(&p, 2, 1)[1], ctrl(&p, 2, 1)[2], 1e-15);
  lsys_surface_patch_eval(LSYS_BASIS_CARDINAL, &p, 1, 1, pos, NULL, NULL);
  nearv(pos, ctrl(&p, 2, 2)[0], ctrl(&p, 2, 2)[1], ctrl(&p, 2, 2)[2], 1e-15);
  /* Catmull-Rom tangent at a corner: (P(1,2) - P(1,0)) / 2 along s */
  {
    double ds[3], dt[3];
    const double *a = ctrl(&p, 1, 2), *b = ctrl(&p, 1, 0), *c = ctrl(&p, 2, 1),
                 *d = ctrl(&p, 0, 1);
    lsys_surface_patch_eval(LSYS_BASIS_CARDINAL, &p, 0, 0, pos, ds, dt);
    nearv(ds, (a[0] - b[0]) / 2, (a[1] - b[1]) / 2, (a[2] - b[2]) / 2, 1e-14);
    nearv(dt, (c[0] - d[0]) / 2, (c[1] - d[1]) / 2, (c[2] - d[2]) / 2, 1e-14);
  }
}

/* Derivatives against central differences, every basis, several points. */
static void test_derivatives (void) {
  static const double pts[5][2] = {{0.1, 0.2}, {0.5, 0.5}, {0.9, 0.3}, {0.33, 0.77}, {0.6, 0.05}};
  int basis, k, c;
  for (basis = 1; basis <= 3; basis++) {
    lsys_patch p;
    randpatch(&p, 11u * (unsigned)basis);
    for (k = 0; k < 5; k++) {
      double s = pts[k][0], t = pts[k][1], h = 1e-6, pos[3], ds[3], dt[3], a[3], b[3];
      lsys_surface_patch_eval(basis, &p, s, t, pos, ds, dt);
      lsys_surface_patch_eval(basis, &p, s + h, t, a, NULL, NULL);
      lsys_surface_patch_eval(basis, &p, s - h, t, b, NULL, NULL);
      for (c = 0; c < 3; c++) assert(near(ds[c], (a[c] - b[c]) / (2 * h), 1e-7));
      lsys_surface_patch_eval(basis, &p, s, t + h, a, NULL, NULL);
      lsys_surface_patch_eval(basis, &p, s, t - h, b, NULL, NULL);
      for (c = 0; c < 3; c++) assert(near(dt[c], (a[c] - b[c]) / (2 * h), 1e-7));
    }
  }
}

/* ---- the reader ---- */

static void test_leaf (void) {
  lsys_surface s;
  int d;
  loadfile(&s, LEAF);
  assert(s.npatch == 1);
  assert(s.basis == LSYS_BASIS_BEZIER);
  assert(s.precision_s == 5 && s.precision_t == 8);
  nearv(s.contact, 0, 0, 0, 0);
  nearv(s.end, 0, 1, 0, 0);
  nearv(s.heading, 0, 1, 0, 0);
  nearv(s.up, 0, 0, 1, 0);
  assert(s.size == 1);
  nearv(s.lo, -0.45, 0, 0, 0);
  nearv(s.hi, 0.45, 1, 0.1, 0);
  assert(strcmp(s.info[0].name, "blade") == 0);
  for (d = 0; d < 8; d++) assert(s.info[0].nb[d] == -1);
  nearv(ctrl(&s.patch[0], 1, 0), -0.45, 0.25, 0.1, 0);
  nearv(ctrl(&s.patch[0], 2, 2), 0.15, 0.8, 0.02, 0);
  nearv(ctrl(&s.patch[0], 3, 3), 0, 1, 0, 0);
  lsys_surface_free(&s);
  assert(s.npatch == 0 && s.patch == NULL && s.info == NULL);
}

static void test_petal (void) {
  lsys_surface s;
  int d;
  loadfile(&s, PETAL);
  assert(s.npatch == 2);
  assert(s.precision_s == 4 && s.precision_t == 4);
  assert(s.size == 1.1);
  assert(strcmp(s.info[0].name, "base") == 0 && strcmp(s.info[1].name, "tip") == 0);
  for (d = 0; d < 8; d++) {
    assert(s.info[0].nb[d] == (d == LSYS_NB_B ? 1 : -1));
    assert(s.info[1].nb[d] == (d == LSYS_NB_A ? 0 : -1));
  }
  /* the shared edge: row 3 of "base" is row 0 of "tip" */
  assert(memcmp(s.patch[0].ctrl + 36, s.patch[1].ctrl, 12 * sizeof(double)) == 0);
  nearv(s.lo, -0.35, 0, 0, 0);
  nearv(s.hi, 0.35, 1.1, 0.32, 0);
  lsys_surface_free(&s);
}

/* A file in the layout of the editors' output, without PRECISION, with a
** heading and up to be normalised, colours, and neighbour names. */
static const char EDITOR[] =
  "-1.00 1.00   0.00 2.00   -0.50 0.50\n"
  "CONTACT POINT  X: 0.00 Y: -1.00 Z: 0.00\n"
  "END POINT  X: 0.00 Y: 1.00 Z: 0.00\n"
  "HEADING  X: 0.00 Y: 2.00 Z: 0.00\n"
  "UP  X: 0.00 Y: 1.00 Z: 1.00\n"
  "SIZE: 2.000000\n"
  "Patch_0\n"
  "TOP COLOR: 12 DIFFUSE: 0.50 BOTTOM COLOR: 7 DIFFUSE: 0.25\n"
  "AL: ~ A: ~ AR: ~ \n"
  "L: ~ R: Patch_1 \n"
  "BL: ~ B: ~ BR: ~ \n"
  "-1.00 0.00 0.00  -0.70 0.00 0.10  -0.30 0.00 0.10  0.00 0.00 0.00  \n"
  "-1.00 0.70 0.00  -0.70 0.70 0.20  -0.30 0.70 0.20  0.00 0.70 0.00  \n"
  "-1.00 1.30 0.00  -0.70 1.30 0.20  -0.30 1.30 0.20  0.00 1.30 0.00  \n"
  "-1.00 2.00 0.00  -0.70 2.00 0.10  -0.30 2.00 0.10  0.00 2.00 0.00  \n"
  "Patch_1\n"
  "TOP COLOR: 12 DIFFUSE: 0.50 BOTTOM COLOR: 7 DIFFUSE: 0.25\n"
  "AL: ~ A: ~ AR: ~ \n"
  "L: Patch_0 R: ~ \n"
  "BL: ~ B: ~ BR: ~ \n"
  "0.00 0.00 0.00  0.30 0.00 0.10  0.70 0.00 0.10  1.00 0.00 0.00  \n"
  "0.00 0.70 0.00  0.30 0.70 0.20  0.70 0.70 0.20  1.00 0.70 0.00  \n"
  "0.00 1.30 0.00  0.30 1.30 0.20  0.70 1.30 0.20  1.00 1.30 0.00  \n"
  "0.00 2.00 0.00  0.30 2.00 0.10  0.70 2.00 0.10  1.00 2.00 0.00  \n";

static void test_editor_layout (void) {
  lsys_surface s;
  lsys_error e;
  assert(lsys_surface_parse(&s, EDITOR, sizeof EDITOR - 1, "ed.s", &e) == LSYS_OK);
  assert(s.npatch == 2);
  assert(s.precision_s == 5 && s.precision_t == 5);     /* default */
  nearv(s.contact, 0, -1, 0, 0);
  nearv(s.heading, 0, 1, 0, 1e-15);
  nearv(s.up, 0, 0, 1, 1e-15);                           /* made orthogonal to HEADING */
  assert(s.size == 2);
  assert(s.info[0].color[0] == 12 && s.info[0].color[1] == 7);
  assert(s.info[0].diffuse[0] == 0.5 && s.info[0].diffuse[1] == 0.25);
  assert(s.info[0].nb[LSYS_NB_R] == 1 && s.info[1].nb[LSYS_NB_L] == 0);
  assert(s.info[0].nb[LSYS_NB_L] == -1 && s.info[1].nb[LSYS_NB_R] == -1);
  lsys_surface_free(&s);
}

/* Spacing: labels glued to numbers, tabs, CRLF, blank lines, no final newline. */
static void test_spacing (void) {
  static const char T[] =
    "\r\n0 1 0 1 0 0\r\n\r\n"
    "PRECISION\tS:3 T:\t7\r\n"
    "CONTACT POINT X:0.5 Y:0 Z:0\r\n"
    "END POINT X: 0.5 Y: 1 Z: 0\r\n"
    "HEADING X: 0 Y: 1 Z: 0\r\n"
    "  UP X: 0 Y: 0 Z: -1  \r\n"
    "SIZE:1\r\n"
    "\r\n"
    "p\r\n"
    "TOP COLOR:0 DIFFUSE:0 BOTTOM COLOR:0 DIFFUSE:0\r\n"
    "AL:~ A:~ AR:~\r\nL:~ R:~\r\nBL:~ B:~ BR:~\r\n"
    "0 0 0 0.333 0 0 0.667 0 0 1 0 0\r\n"
    "0 0.333 0 0.333 0.333 0 0.667 0.333 0 1 0.333 0\r\n"
    "0 0.667 0 0.333 0.667 0 0.667 0.667 0 1 0.667 0\r\n"
    "0 1 0 0.333 1 0 0.667 1 0 1 1 0";
  lsys_surface s;
  lsys_error e;
  int st = lsys_surface_parse(&s, T, sizeof T - 1, "sp.s", &e);
  if (st != LSYS_OK) fprintf(stderr, "%s\n", e.msg);
  assert(st == LSYS_OK);
  assert(s.npatch == 1 && s.precision_s == 3 && s.precision_t == 7);
  nearv(s.contact, 0.5, 0, 0, 0);
  nearv(s.up, 0, 0, -1, 0);
  nearv(ctrl(&s.patch[0], 3, 3), 1, 1, 0, 0);
  lsys_surface_free(&s);
}

/* The header of the malformed cases: 6 lines (bounding box .. SIZE). */
#define HEAD \
  "0 1 0 1 0 0\n" \
  "CONTACT POINT X: 0 Y: 0 Z: 0\n" \
  "END POINT X: 0 Y: 1 Z: 0\n" \
  "HEADING X: 0 Y: 1 Z: 0\n" \
  "UP X: 0 Y: 0 Z: 1\n" \
  "SIZE: 1\n"
#define NONB "AL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: ~ BR: ~\n"
#define COLORS "TOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\n"
#define ROW "0 0 0 1 0 0 2 0 0 3 0 0\n"
#define PATCH(name, nb) name "\n" COLORS nb ROW ROW ROW ROW

static void bad (const char *text, const char *msg) {
  lsys_surface s;
  lsys_error e;
  size_t len = strlen(text);
  char *copy = malloc(len ? len : 1);     /* exactly len bytes: reads past the end show */
  int st;
  assert(copy != NULL);
  memcpy(copy, text, len);
  memset(&e, 0, sizeof e);
  st = lsys_surface_parse(&s, copy, len, "t.s", &e);
  free(copy);
  if (st != LSYS_ESYNTAX || strcmp(e.msg, msg) != 0) {
    fprintf(stderr, "status %d, message:\n  %s\nexpected:\n  %s\n", st, e.msg, msg);
    assert(0);
  }
  assert(e.code == LSYS_ESYNTAX);
  assert(s.npatch == 0 && s.patch == NULL && s.info == NULL);
}

static void test_malformed (void) {
  bad("", "t.s:1: expected 'n n n n n n', found the end of the file");
  bad("\n  \n", "t.s:3: expected 'n n n n n n', found the end of the file");
  bad("0 1 0 1 0\n", "t.s:1: bad bounding box line: expected a number, found end of line");
  bad("0 1 0 1 0 0 7\n", "t.s:1: bad bounding box line: unexpected '7' at the end");
  bad("0 1 0 1 0 x\n", "t.s:1: bad bounding box line: 'x' is not a number");
  bad("0 1 0 1 0 0\nEND POINT X: 0 Y: 1 Z: 0\n",
      "t.s:2: expected 'CONTACT POINT X: n Y: n Z: n', found 'END'");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0\n",
      "t.s:2: bad CONTACT POINT line: expected 'Z:', found end of line");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0 W: 1\n",
      "t.s:2: bad CONTACT POINT line: unexpected 'W:' at the end");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 W: 0\n",
      "t.s:2: bad CONTACT POINT line: expected 'Z:', found 'W:'");
  bad("0 1 0 1 0 0\nPRECISION S: 0 T: 4\n",
      "t.s:2: PRECISION S must be from 1 to 256, not 0");
  bad("0 1 0 1 0 0\nPRECISION S: 4 T: 4.5\n",
      "t.s:2: bad PRECISION line: '4.5' is not an integer");
  bad("0 1 0 1 0 0\nPRECISION S: 4 T: 4\n",
      "t.s:3: expected 'CONTACT POINT X: n Y: n Z: n', found the end of the file");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: nan Y: 1 Z: 0\n", "t.s:4: bad HEADING line: 'nan' is not a finite number");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: -Inf Y: 1 Z: 0\n", "t.s:4: bad HEADING line: '-Inf' is not a finite number");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 1e999 Y: 0 Z: 0\n",
      "t.s:2: bad CONTACT POINT line: '1e999' is out of range (limit 1e30)");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 1.2.3 Y: 0 Z: 0\n",
      "t.s:2: bad CONTACT POINT line: '1.2.3' is not a number");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0x10 Y: 0 Z: 0\n",
      "t.s:2: bad CONTACT POINT line: '0x10' is not a number");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 0 Z: 0\n", "t.s:4: HEADING is the zero vector");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: -2 Z: 0\n", "t.s:5: UP is parallel to HEADING");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 0\n", "t.s:5: UP is the zero vector");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 0\n", "t.s:6: SIZE must be from 1e-30 to 1e30, not 0");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1e-31\n",
      "t.s:6: SIZE must be from 1e-30 to 1e30, not 1e-31");
  bad("0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
      "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE 1\n",
      "t.s:6: expected 'SIZE: n', found 'SIZE'");
  bad(HEAD, "t.s:7: expected a patch, found the end of the file");
  bad(HEAD "p\n", "t.s:8: patch 'p' ends early: expected "
      "'TOP COLOR: n DIFFUSE: n BOTTOM COLOR: n DIFFUSE: n'");
  bad(HEAD "p q\n", "t.s:7: expected a patch name (one word), found 'p q'");
  bad(HEAD "\t p  q \r\n", "t.s:7: expected a patch name (one word), found 'p  q'");
  bad(HEAD "abcdefghijabcdefghijabcdefghijabcdefghijabcdefghijabcdefghij1234\n",
      "t.s:7: patch name 'abcdefghijab...' is longer than 63 bytes");
  bad(HEAD "p\nTOP COLOR: -1 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\n",
      "t.s:8: TOP COLOR must be from 0 to 65535, not -1");
  bad(HEAD "p\n" COLORS "AL: ~ A: ~ AR: ~\nL: ~\n",
      "t.s:10: bad neighbour line: expected 'R:', found end of line");
  bad(HEAD "p\n" COLORS NONB ROW ROW,
      "t.s:14: patch 'p' ends early: expected row 2 of control points");
  bad(HEAD "p\n" COLORS NONB ROW "0 0 0 1 0 0 2 0 0 3 0\n" ROW ROW,
      "t.s:13: row 1 of patch 'p' has 11 numbers, expected 12 (x y z of 4 points)");
  bad(HEAD "p\n" COLORS NONB ROW ROW "0 0 0 1 0 0 2 0 0 3 0 0 4\n" ROW,
      "t.s:14: row 2 of patch 'p' has more than 12 numbers");
  bad(HEAD "p\n" COLORS NONB ROW ROW ROW "0 0 0 1 0 0 2 0 0 3 0 nan\n",
      "t.s:15: bad control point row 3 line: 'nan' is not a finite number");
  bad(HEAD PATCH("p", "AL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: q BR: ~\n"),
      "t.s:11: patch 'p': no patch named 'q' (its B neighbour)");
  bad(HEAD PATCH("a", "AL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: b BR: ~\n") PATCH("b", NONB),
      "t.s:11: patch 'a' has 'b' as its B neighbour, but 'b' has none as its A");
  bad(HEAD PATCH("a", "AL: ~ A: ~ AR: ~\nL: ~ R: b\nBL: ~ B: ~ BR: ~\n")
      PATCH("b", "AL: ~ A: ~ AR: ~\nL: c R: ~\nBL: ~ B: ~ BR: ~\n") PATCH("c", NONB),
      "t.s:10: patch 'a' has 'b' as its R neighbour, but 'b' has 'c' as its L");
  {   /* too many patches */
    size_t one = strlen(PATCH("p", NONB)), k, n = strlen(HEAD);
    char *t = malloc(n + 4097 * one + 1);
    char msg[64];
    assert(t != NULL);
    memcpy(t, HEAD, n);
    for (k = 0; k < 4097; k++) memcpy(t + n + k * one, PATCH("p", NONB), one);
    t[n + 4097 * one] = '\0';
    snprintf(msg, sizeof msg, "t.s:%d: too many patches (limit is 4096)", 6 + 4096 * 9 + 1);
    bad(t, msg);
    t[n + 4096 * one] = '\0';        /* 4096 is fine */
    {
      lsys_surface s;
      lsys_error e;
      assert(lsys_surface_parse(&s, t, strlen(t), "t.s", &e) == LSYS_OK);
      assert(s.npatch == 4096);
      lsys_surface_free(&s);
    }
    free(t);
  }
}

/* Text after 'len' is not read, and NUL bytes are ordinary bytes. */
static void test_length (void) {
  static const char T[] = HEAD PATCH("p", NONB) "garbage that would be a bad patch";
  lsys_surface s;
  lsys_error e;
  size_t n = strlen(HEAD PATCH("p", NONB));
  assert(lsys_surface_parse(&s, T, n, "t.s", &e) == LSYS_OK);
  assert(s.npatch == 1);
  lsys_surface_free(&s);
  assert(lsys_surface_parse(&s, T, sizeof T - 1, "t.s", &e) == LSYS_ESYNTAX);
  assert(strcmp(e.msg, "t.s:16: expected a patch name (one word), found "
                       "'garbage that...'") == 0);
  {
    char z[] = HEAD "p\0q\n";
    assert(lsys_surface_parse(&s, z, sizeof z - 1, "t.s", &e) == LSYS_ESYNTAX);
    assert(strcmp(e.msg, "t.s:7: patch name 'p?q' has a control character") == 0);
  }
  assert(lsys_surface_parse(&s, NULL, 0, NULL, &e) == LSYS_ESYNTAX);
  assert(strcmp(e.msg, "?:1: expected 'n n n n n n', found the end of the file") == 0);
}

/* ---- tessellation ---- */

static lsys_place defplace (void) {
  lsys_place pl;
  memset(&pl, 0, sizeof pl);
  vset(pl.H, 0, 1, 0);
  vset(pl.L, -1, 0, 0);
  vset(pl.U, 0, 0, -1);
  pl.scale = 1;
  return pl;
}

static void vtx (const lsys_mesh *m, size_t i, double out[3]) {
  vset(out, m->pos[3 * i], m->pos[3 * i + 1], m->pos[3 * i + 2]);
}

/* Every triangle is wound counter-clockwise seen from its vertices' normal
** side, and every normal is a finite unit vector. */
static void check_mesh (const lsys_mesh *m, size_t v0, size_t t0) {
  size_t i;
  for (i = v0; i < m->nv; i++) {
    const float *n = m->nrm + 3 * i;
    double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    assert(isfinite(m->pos[3 * i]) && isfinite(m->pos[3 * i + 1]) && isfinite(m->pos[3 * i + 2]));
    assert(near(l, 1, 1e-5));
    assert(m->twosided[i] == 1);
  }
  for (i = t0; i < m->nt; i++) {
    const uint32_t *t = m->tri + 3 * i;
    double a[3], b[3], c[3], g[3], avg[3] = {0, 0, 0};
    int k;
    assert(t[0] >= v0 && t[0] < m->nv && t[1] < m->nv && t[2] < m->nv);
    vtx(m, t[0], a); vtx(m, t[1], b); vtx(m, t[2], c);
    vlin(b, b, 1, a, -1);
    vlin(c, c, 1, a, -1);
    vcross(g, b, c);
    if (vlen(g) < 1e-9) continue;             /* a sliver at a collapsed edge */
    for (k = 0; k < 3; k++) {
      const float *n = m->nrm + 3 * t[k];
      avg[0] += n[0]; avg[1] += n[1]; avg[2] += n[2];
    }
    assert(vdot(g, avg) > 0);
  }
}

static void test_counts (void) {
  lsys_surface leaf, petal;
  lsys_mesh m;
  lsys_place pl = defplace();
  size_t i;
  loadfile(&leaf, LEAF);
  loadfile(&petal, PETAL);
  lsys_mesh_init(&m);
  m.curtex = 3;
  pl.color = 7;
  assert(lsys_surface_mesh(&m, &leaf, &pl, 5, 8) == LSYS_OK);
  assert(m.nv == 6 * 9 && m.nt == 2 * 5 * 8);
  check_mesh(&m, 0, 0);
  assert(lsys_surface_mesh(&m, &petal, &pl, 3, 3) == LSYS_OK);
  assert(m.nv == 54 + 2 * 16 && m.nt == 80 + 2 * 18);
  check_mesh(&m, 54, 80);
  for (i = 0; i < m.nv; i++) assert(m.col[i] == 7 && m.tex[i] == 3);
  for (i = 80; i < m.nt; i++) assert(m.tri[3 * i] >= 54);
  /* bad divisions change nothing */
  assert(lsys_surface_mesh(&m, &leaf, &pl, 0, 4) == LSYS_EARG);
  assert(lsys_surface_mesh(&m, &leaf, &pl, 4, LSYS_SURFACE_MAXDIV + 1) == LSYS_EARG);
  assert(m.nv == 86 && m.nt == 116);
  lsys_mesh_free(&m);
  lsys_surface_free(&leaf);
  lsys_surface_free(&petal);
}

static void test_placement (void) {
  lsys_surface leaf, petal;
  lsys_mesh m;
  lsys_place pl = defplace();
  double p[3], q[3], e[3];
  size_t i;
  loadfile(&leaf, LEAF);
  loadfile(&petal, PETAL);
  lsys_mesh_init(&m);
  /* turtle at (1,2,3) heading +z with up +x: L = H x U = +y */
  vset(pl.origin, 1, 2, 3);
  vset(pl.H, 0, 0, 1);
  vset(pl.U, 1, 0, 0);
  vset(pl.L, 0, 1, 0);
  pl.scale = 2;
  assert(lsys_surface_mesh(&m, &leaf, &pl, 4, 4) == LSYS_OK);
  /* row t = 0 collapses on the contact point: on the turtle */
  for (i = 0; i <= 4; i++) {
    vtx(&m, i, p);
    nearv(p, 1, 2, 3, 1e-6);
  }
  /* the tip (surface (0,1,0), one SIZE along H_S) is 2 along H */
  vtx(&m, 4 * 5 + 2, p);
  nearv(p, 1, 2, 5, 1e-6);
  /* any point: x along L (= H_S x U_S = +x), y along H, z along U */
  for (i = 0; i < m.nv; i++) {
    double sp[3];
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &leaf.patch[0], (double)(i % 5) / 4,
                            (double)(i / 5) / 4, sp, NULL, NULL);
    vtx(&m, i, p);
    nearv(p, 1 + 2 * sp[2], 2 + 2 * sp[0], 3 + 2 * sp[1], 1e-6);
  }
  /* the cupped leaf's normals point to the U side */
  for (i = 0; i < m.nv; i++) assert(m.nrm[3 * i] > 0.5);
  check_mesh(&m, 0, 0);
  lsys_surface_endpoint(&leaf, &pl, e);
  nearv(e, 1, 2, 5, 1e-12);
  /* SIZE divides: the petal (SIZE 1.1) at scale 2.2 is twice its file size */
  lsys_mesh_clear(&m);
  vset(pl.origin, 0, 0, 0);
  pl.scale = 2.2;
  assert(lsys_surface_mesh(&m, &petal, &pl, 2, 2) == LSYS_OK);
  vtx(&m, 9 + 8, q);                      /* patch "tip", s = t = 1: file (0.2, 1.05, 0.32)? */
  {
    double sp[3];
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &petal.patch[1], 1, 1, sp, NULL, NULL);
    nearv(sp, 0.2, 1.05, 0.32, 1e-12);
    nearv(q, 2 * 0.32, 2 * 0.2, 2 * 1.05, 1e-5);
  }
  lsys_surface_endpoint(&petal, &pl, e);
  nearv(e, 0, 0, 0, 0);
  /* a contact point off the origin and a tilted file frame */
  {
    lsys_surface s;
    lsys_error err;
    double cp[3], H[3] = {1, 2, 2}, U[3] = {0, -1, 1}, sp[3];
    assert(lsys_surface_parse(&s, EDITOR, sizeof EDITOR - 1, "ed.s", &err) == LSYS_OK);
    vset(s.heading, 1.0 / 3, 2.0 / 3, 2.0 / 3);   /* an orthonormal pair, set by hand */
    vnorm(H);
    vnorm(U);
    vcopy(s.heading, H);
    vcopy(s.up, U);
    vset(s.contact, 0.3, 0.4, 0.5);
    lsys_mesh_clear(&m);
    pl = defplace();
    pl.scale = 2;                                 /* SIZE is 2: factor 1 */
    assert(lsys_surface_mesh(&m, &s, &pl, 3, 3) == LSYS_OK);
    /* every vertex: its (x - contact) components along L_S, H_S, U_S become
    ** components along L, H, U */
    for (i = 0; i < 16; i++) {
      double d[3], LS[3];
      lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &s.patch[0], (double)(i % 4) / 3,
                              (double)(i / 4) / 3, sp, NULL, NULL);
      vlin(d, sp, 1, s.contact, -1);
      vcross(LS, H, U);
      vtx(&m, i, p);
      nearv(p, -vdot(d, LS), vdot(d, H), -vdot(d, U), 1e-6);
    }
    vcopy(cp, s.contact);
    check_mesh(&m, 0, 0);
    /* the endpoint likewise */
    lsys_surface_endpoint(&s, &pl, e);
    {
      double d[3], LS[3];
      vlin(d, s.end, 1, cp, -1);
      vcross(LS, H, U);
      nearv(e, -vdot(d, LS), vdot(d, H), -vdot(d, U), 1e-12);
    }
    lsys_surface_free(&s);
  }
  lsys_mesh_free(&m);
  lsys_surface_free(&leaf);
  lsys_surface_free(&petal);
}

static void test_normals (void) {
  lsys_surface leaf, petal;
  lsys_mesh m;
  lsys_place pl = defplace();
  int i;
  loadfile(&leaf, LEAF);
  loadfile(&petal, PETAL);
  lsys_mesh_init(&m);
  /* identity frame: H = H_S = +y, U = U_S = +z, L = +x */
  vset(pl.L, 1, 0, 0);
  vset(pl.U, 0, 0, 1);
  assert(lsys_surface_mesh(&m, &leaf, &pl, 4, 6) == LSYS_OK);
  /* the base row (t = 0) is one point: ds = 0 there; its normals come from
  ** inside the patch and lean towards +z; the midrib's normal is +z */
  for (i = 0; i <= 4; i++) assert(m.nrm[3 * i + 2] > 0.5);
  for (i = 0; i < 5 * 7; i++) assert(m.nrm[3 * i + 2] > 0.5);
  assert(near(m.nrm[3 * (3 * 5 + 2)], 0, 1e-6) && near(m.nrm[3 * (3 * 5 + 2) + 2], 1, 1e-6));
  /* symmetric leaf: mirrored vertices have mirrored normals */
  for (i = 0; i < 5 * 7; i++) {
    int j = (i / 5) * 5 + (4 - i % 5);
    assert(near(m.nrm[3 * i], -m.nrm[3 * j], 1e-6));
    assert(near(m.nrm[3 * i + 2], m.nrm[3 * j + 2], 1e-6));
  }
  /* petal: the shared edge has one normal on both sides */
  lsys_mesh_clear(&m);
  assert(lsys_surface_mesh(&m, &petal, &pl, 4, 4) == LSYS_OK);
  for (i = 0; i <= 4; i++) {
    const float *a = m.nrm + 3 * (4 * 5 + i), *b = m.nrm + 3 * (25 + i);
    assert(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
    assert(m.pos[3 * (4 * 5 + i) + 1] == m.pos[3 * (25 + i) + 1]);
  }
  check_mesh(&m, 0, 0);
  /* four patches in a 2 x 2 grid: edges and corners named in all eight
  ** directions; a shared edge has one normal (a kink is smoothed) */
  {
    lsys_surface g;
    lsys_patchinfo *keep;
    const float *n;
    loadfile(&g, "tests/data/surfaces/grid4.s");
    assert(g.npatch == 4);
    assert(g.info[0].nb[LSYS_NB_R] == 1 && g.info[0].nb[LSYS_NB_B] == 2 &&
           g.info[0].nb[LSYS_NB_BR] == 3 && g.info[3].nb[LSYS_NB_AL] == 0 &&
           g.info[1].nb[LSYS_NB_BL] == 2 && g.info[2].nb[LSYS_NB_AR] == 1);
    lsys_mesh_clear(&m);
    assert(lsys_surface_mesh(&m, &g, &pl, 3, 3) == LSYS_OK);
    check_mesh(&m, 0, 0);
    for (i = 0; i < 3; i++) {                /* a's column 3 = b's column 0, rows 0..2 */
      const float *x = m.nrm + 3 * (4 * i + 3), *y = m.nrm + 3 * (16 + 4 * i);
      assert(x[0] == y[0] && x[1] == y[1] && x[2] == y[2]);
      assert(near(x[0], 0, 1e-6) && near(x[2], 1, 1e-6));   /* the kink averaged away */
    }
    n = m.nrm + 3 * 15;                      /* a's corner (3,3) = d's corner (0,0) */
    assert(n[0] == m.nrm[3 * 48] && n[1] == m.nrm[3 * 48 + 1] && n[2] == m.nrm[3 * 48 + 2]);
    /* without the neighbour links the kink stays */
    keep = g.info;
    g.info = NULL;
    lsys_mesh_clear(&m);
    assert(lsys_surface_mesh(&m, &g, &pl, 3, 3) == LSYS_OK);
    assert(m.nrm[3 * 3] < -0.05 && m.nrm[3 * 16] > 0.05);
    g.info = keep;
    lsys_surface_free(&g);
  }
  /* a patch collapsed to a point: every normal is the fallback, U */
  {
    lsys_surface s = leaf;
    lsys_patch dot;
    memset(&dot, 0, sizeof dot);
    s.patch = &dot;
    s.info = NULL;
    lsys_mesh_clear(&m);
    assert(lsys_surface_mesh(&m, &s, &pl, 2, 2) == LSYS_OK);
    for (i = 0; i < 9; i++) assert(m.nrm[3 * i + 2] == 1);
  }
  lsys_mesh_free(&m);
  lsys_surface_free(&leaf);
  lsys_surface_free(&petal);
}

static void test_uv (void) {
  lsys_surface leaf;
  lsys_mesh m;
  lsys_place pl = defplace();
  double ulo = 1, uhi = 0, vlo = 1, vhi = 0;
  size_t i;
  loadfile(&leaf, LEAF);
  lsys_mesh_init(&m);
  assert(lsys_surface_mesh(&m, &leaf, &pl, 4, 5) == LSYS_OK);
  for (i = 0; i < m.nv; i++) {
    assert(m.uv[2 * i] == (float)((double)(i % 5) / 4));
    assert(m.uv[2 * i + 1] == (float)((double)(i / 5) / 5));
  }
  lsys_mesh_clear(&m);
  pl.uv_surface = 1;
  assert(lsys_surface_mesh(&m, &leaf, &pl, 4, 4) == LSYS_OK);
  for (i = 0; i < m.nv; i++) {
    double u = m.uv[2 * i], v = m.uv[2 * i + 1], sp[3], x0, x1;
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &leaf.patch[0], (double)(i % 5) / 4,
                            (double)(i / 5) / 4, sp, NULL, NULL);
    if (u < ulo) ulo = u;
    if (u > uhi) uhi = u;
    if (v < vlo) vlo = v;
    if (v > vhi) vhi = v;
    assert(near(v, sp[1], 1e-6));           /* y spans 0..1 exactly */
    /* x spans the widest row of the tessellation */
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &leaf.patch[0], 0, 0.5, sp + 0, NULL, NULL);
    x0 = sp[0];
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &leaf.patch[0], 1, 0.5, sp, NULL, NULL);
    x1 = sp[0];
    lsys_surface_patch_eval(LSYS_BASIS_BEZIER, &leaf.patch[0], (double)(i % 5) / 4,
                            (double)(i / 5) / 4, sp, NULL, NULL);
    assert(near(u, (sp[0] - x0) / (x1 - x0), 1e-6));
  }
  assert(ulo == 0 && uhi == 1 && vlo == 0 && vhi == 1);
  lsys_mesh_free(&m);
  lsys_surface_free(&leaf);
}

static void test_patch_mesh (void) {
  lsys_patch p;
  lsys_mesh m;
  lsys_place pl = defplace();
  int r, c;
  size_t i;
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) setctrl(&p, r, c, 10 + c, 20 + r, 5);
  lsys_mesh_init(&m);
  pl.color = 4;
  vset(pl.origin, 100, 100, 100);            /* not used */
  pl.scale = 50;
  for (r = LSYS_BASIS_BEZIER; r <= LSYS_BASIS_CARDINAL; r++) {
    lsys_mesh_clear(&m);
    assert(lsys_surface_patch_mesh(&m, r, &p, &pl, 3, 2) == LSYS_OK);
    assert(m.nv == 12 && m.nt == 12);
    check_mesh(&m, 0, 0);
    for (i = 0; i < 12; i++) {
      double s = (double)(i % 4) / 3, t = (double)(i / 4) / 2, x, y;
      /* Bézier spans columns 0..3; B-spline and Cardinal 1..2 of a unit grid */
      x = r == LSYS_BASIS_BEZIER ? 10 + 3 * s : 11 + s;
      y = r == LSYS_BASIS_BEZIER ? 20 + 3 * t : 21 + t;
      assert(near(m.pos[3 * i], x, 1e-5) && near(m.pos[3 * i + 1], y, 1e-5));
      assert(m.pos[3 * i + 2] == 5);
      assert(m.nrm[3 * i + 2] == 1 && m.col[i] == 4);
      assert(m.uv[2 * i] == (float)s && m.uv[2 * i + 1] == (float)t);
    }
  }
  /* planar texture coordinates of a skewed flat patch: from its own plane */
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) setctrl(&p, r, c, c, 0, r);   /* in the xz plane */
  lsys_mesh_clear(&m);
  pl.uv_surface = 1;
  assert(lsys_surface_patch_mesh(&m, LSYS_BASIS_BEZIER, &p, &pl, 2, 4) == LSYS_OK);
  for (i = 0; i < m.nv; i++) {
    assert(near(m.uv[2 * i], (double)(i % 3) / 2, 1e-6));
    assert(near(m.uv[2 * i + 1], (double)(i / 3) / 4, 1e-6));
    assert(m.nrm[3 * i + 1] == -1);          /* x cross z = -y */
  }
  /* a degenerate patch (a line) falls back to (s, t) and the default normal */
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) setctrl(&p, r, c, c, 0, 0);
  lsys_mesh_clear(&m);
  assert(lsys_surface_patch_mesh(&m, LSYS_BASIS_BEZIER, &p, &pl, 2, 2) == LSYS_OK);
  for (i = 0; i < m.nv; i++) {
    assert(m.uv[2 * i] == (float)((double)(i % 3) / 2));
    assert(m.nrm[3 * i + 2] == 1);
  }
  assert(lsys_surface_patch_mesh(&m, LSYS_BASIS_BEZIER, &p, &pl, 1, 0) == LSYS_EARG);
  /* huge coordinates stay finite in the float mesh */
  for (r = 0; r < 4; r++)
    for (c = 0; c < 4; c++) setctrl(&p, r, c, 1e300 * c, 1e300 * r, -1e300);
  lsys_mesh_clear(&m);
  assert(lsys_surface_patch_mesh(&m, LSYS_BASIS_CARDINAL, &p, &pl, 2, 2) == LSYS_OK);
  for (i = 0; i < 3 * m.nv; i++) assert(isfinite(m.pos[i]) && isfinite(m.nrm[i]));
  lsys_mesh_free(&m);
}

/* ---- memory ---- */

static void test_nomem (void) {
  size_t len;
  char *text = slurp(PETAL, &len);
  long k;
  int done = 0;
  for (k = 0; !done; k++) {
    lsys_surface s;
    lsys_error e;
    int st;
    nalloc = 0;
    failat = k;
    live = 0;
    st = lsys_surface_parse(&s, text, len, "petal.s", &e);
    done = nalloc <= k;
    if (done) assert(st == LSYS_OK && s.npatch == 2);
    else {
      assert(st == LSYS_ENOMEM && strcmp(e.msg, "not enough memory") == 0);
      assert(s.npatch == 0 && s.patch == NULL);
    }
    lsys_surface_free(&s);
    assert(live == 0);
  }
  assert(k > 3);
  /* meshing: a failure leaves the mesh as it was */
  {
    lsys_surface s;
    lsys_mesh m;
    lsys_place pl = defplace();
    lsys_error e;
    failat = -1;
    assert(lsys_surface_parse(&s, text, len, "petal.s", &e) == LSYS_OK);
    done = 0;
    for (k = 0; !done; k++) {
      int st;
      lsys_mesh_init(&m);
      nalloc = 0;
      failat = k;
      st = lsys_surface_mesh(&m, &s, &pl, 4, 4);
      done = nalloc <= k;
      if (done) assert(st == LSYS_OK && m.nv == 50);
      else assert(st == LSYS_ENOMEM && m.nv == 0 && m.nt == 0);
      lsys_mesh_free(&m);
    }
    failat = -1;
    lsys_surface_free(&s);
  }
  free(text);
  assert(live == 0);
}

/* ---- editing and writing ---- */

/* with_points copies the patches and their links with new control points and
** bounds; format writes a text that reads back to the same surface; a
** failed allocation leaves the destination as it was. */
static void test_edit_format (void) {
  lsys_surface s, t, u;
  lsys_error e;
  double pt[96];
  size_t len, n, i;
  char *text;
  int d;
  failat = -1;
  loadfile(&s, PETAL);
  assert(s.npatch == 2);
  for (i = 0; i < 2; i++) memcpy(pt + 48 * i, s.patch[i].ctrl, sizeof s.patch[i].ctrl);
  pt[3 * 5 + 2] = 7.5;                          /* patch 0, point 5: z */
  lsys_surface_init(&t);
  assert(lsys_surface_with_points(&t, &s, pt, &e) == LSYS_OK);
  assert(t.npatch == 2 && t.patch != s.patch && t.info != s.info);
  assert(t.patch[0].ctrl[17] == 7.5 && s.patch[0].ctrl[17] != 7.5);
  assert(t.hi[2] == 7.5 && s.hi[2] < 7.5);
  for (d = 0; d < 8; d++) assert(t.info[1].nb[d] == s.info[1].nb[d]);
  assert(strcmp(t.info[1].name, s.info[1].name) == 0);
  pt[4] = NAN;
  assert(lsys_surface_with_points(&t, &s, pt, &e) == LSYS_EARG);
  assert(strcmp(e.msg, "point 2: coordinate 2 is not finite") == 0);
  assert(t.patch[0].ctrl[17] == 7.5);           /* unchanged */
  failat = nalloc;                              /* the next allocation fails */
  assert(lsys_surface_with_points(&t, &s, s.patch[0].ctrl, &e) == LSYS_ENOMEM);
  failat = -1;
  assert(t.patch[0].ctrl[17] == 7.5);
  len = lsys_surface_format(&t, NULL, 0);
  text = malloc(len + 1);
  assert(text != NULL);
  n = lsys_surface_format(&t, text, len + 1);
  assert(n == len && text[len] == '\0' && strlen(text) == len);
  assert(strstr(text, "\nPRECISION S: ") != NULL && strstr(text, "\nSIZE: ") != NULL);
  assert(lsys_surface_parse(&u, text, len, "t.s", &e) == LSYS_OK);
  assert(u.npatch == t.npatch && u.size == t.size);
  assert(u.precision_s == t.precision_s && u.precision_t == t.precision_t);
  for (i = 0; i < u.npatch; i++) {
    assert(memcmp(u.patch[i].ctrl, t.patch[i].ctrl, sizeof u.patch[i].ctrl) == 0);
    assert(strcmp(u.info[i].name, t.info[i].name) == 0);
    assert(u.info[i].color[0] == t.info[i].color[0]);
    assert(u.info[i].diffuse[1] == t.info[i].diffuse[1]);
    for (d = 0; d < 8; d++) assert(u.info[i].nb[d] == t.info[i].nb[d]);
  }
  for (d = 0; d < 3; d++) {
    assert(u.contact[d] == t.contact[d] && u.end[d] == t.end[d]);
    assert(fabs(u.heading[d] - t.heading[d]) < 1e-15 && fabs(u.up[d] - t.up[d]) < 1e-15);
  }
  free(text);
  lsys_surface_free(&u);
  lsys_surface_free(&t);
  lsys_surface_free(&s);
}

int main (void) {
  test_bezier();
  test_bspline();
  test_cardinal();
  test_derivatives();
  test_leaf();
  test_petal();
  test_editor_layout();
  test_spacing();
  test_malformed();
  test_length();
  test_counts();
  test_placement();
  test_normals();
  test_uv();
  test_patch_mesh();
  test_nomem();
  test_edit_format();
  assert(live == 0);
  printf("test_surface: all passed\n");
  return 0;
}
