/*
** C unit tests for the export of colours and lines (export.h): colour
** factors converted from the palette's sRGB to glTF's and MTL's linear
** values, PLY colours left as they are; line segments exported as tubes
** (lsys_mesh_tubes, mesh_tube.c): exact vertex and triangle counts, bounds,
** outward winding, closed volumes, shared rings, what is left out; and
** lsys_export_scene with tubes in the three formats; a population (a scene
** with instances) as glb with EXT_mesh_gpu_instancing, written out for OBJ
** and PLY, within max_memory.
**
** The core files are compiled in with talloc.h's allocators, so that
** test_nomem makes each allocation fail in turn (run it under valgrind).
*/
#define _XOPEN_SOURCE 700       /* testdir.h */
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "mesh.c"
#include "mesh_tube.c"
#include "export_write.c"
#include "export_group.c"
#include "export_obj.c"
#include "export_ply.c"
#include "export_glb.c"
#include "export.c"
#include "scene.c"
#include "population.c"

#include "testfile.h"
#include "testdir.h"

#define OUT(suffix) testpath("export" suffix)   /* a file in the test's folder */

/* ---- helpers ---- */

/* The JSON chunk of a .glb as a new string. */
static char *json_of (const char *path) {
  unsigned char *file, *bin;
  size_t len, blen;
  char *json = glbjson(path, &file, &len, &bin, &blen);
  free(file);
  return json;
}

static void line (lsys_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1,
                  double w0, double w1, unsigned col) {
  double a[3] = {x0, y0, z0}, b[3] = {x1, y1, z1};
  assert(lsys_mesh_line(m, a, b, w0, w1, col) == LSYS_OK);
}

/* Six times the signed volume enclosed by triangles t0 .. t1 - 1: positive
** when they are closed and wound counterclockwise seen from outside. */
static double volume6 (const lsys_mesh *m, size_t t0, size_t t1) {
  double v = 0;
  size_t t;
  for (t = t0; t < t1; t++) {
    const float *a = m->pos + 3 * m->tri[3 * t], *b = m->pos + 3 * m->tri[3 * t + 1];
    const float *c = m->pos + 3 * m->tri[3 * t + 2];
    v += a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
         a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
         a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
  }
  return v;
}

/* Every triangle t0 .. t1 - 1 faces away from the axis through 'c' along
** 'h' (the band) or along it at the ends (the caps), and its vertex normals
** agree with its face. */
static void outward (const lsys_mesh *m, size_t t0, size_t t1, const double c[3],
                     const double h[3]) {
  size_t t;
  int k;
  for (t = t0; t < t1; t++) {
    const uint32_t *v = m->tri + 3 * t;
    double e1[3], e2[3], fn[3], g[3] = {0, 0, 0}, off[3], along;
    for (k = 0; k < 3; k++) {
      e1[k] = (double)m->pos[3 * v[1] + k] - m->pos[3 * v[0] + k];
      e2[k] = (double)m->pos[3 * v[2] + k] - m->pos[3 * v[0] + k];
      g[k] = ((double)m->pos[3 * v[0] + k] + m->pos[3 * v[1] + k] + m->pos[3 * v[2] + k]) / 3;
    }
    vcross(fn, e1, e2);
    vlin(off, g, 1, c, -1);
    along = vdot(off, h);
    vlin(off, off, 1, h, -along);            /* away from the axis: the band */
    assert(vdot(fn, off) > 0 || fabs(vdot(fn, h)) > 0.99 * vlen(fn));
    if (fabs(vdot(fn, h)) > 0.99 * vlen(fn))  /* a cap: faces away from the middle */
      assert(vdot(fn, h) * along > 0);
    for (k = 0; k < 3; k++) {
      const float *n = m->nrm + 3 * v[k];
      double nn[3] = {n[0], n[1], n[2]};
      assert(vdot(nn, fn) > 0);
    }
  }
}

/* ---- colours ---- */

/* glTF factors are linear: the sRGB transfer function, exactly. */
static void test_linear (void) {
  assert(tolinear(0) == 0 && tolinear(1) == 1);
  assert(tolinear(0.5) == 0.21404114f);
  assert(fabs(tolinear(0.04045) - 0.04045 / 12.92) < 1e-9);  /* the linear piece's end */
  assert(tolinear(0.04) == (float)(0.04 / 12.92));
  assert(fabs(tolinear(0.04046) - pow(0.09546 / 1.055, 2.4)) < 1e-9);
  assert(tolinear(-1) == 0 && tolinear(2) == 1 && tolinear(NAN) == 0);
}

/* A translucent, glowing material: base colour and emission linear, alpha
** as it is; MTL linear too; PLY bytes the sRGB values. */
static void test_factors (void) {
  lsys_mesh m;
  lsys_material pal[1];
  lsys_error e;
  double p[3] = {0, 0, 0}, n[3] = {0, 0, 1};
  uint32_t a, b, c;
  size_t len;
  char *s;
  lsys_mesh_init(&m);
  assert(lsys_mesh_reserve(&m, 3, 1) == LSYS_OK);
  a = lsys_mesh_vertex(&m, p, n, 0, 0, 0, 0);
  p[0] = 1;
  b = lsys_mesh_vertex(&m, p, n, 0, 0, 0, 0);
  p[1] = 1;
  c = lsys_mesh_vertex(&m, p, n, 0, 0, 0, 0);
  lsys_mesh_tri(&m, a, b, c);
  lsys_mesh_material_color(&pal[0], 0.5, 1, 0.04);
  pal[0].diffuse[3] = 0.5f;
  pal[0].emission[0] = 0.5f;
  assert(lsys_export_glb(&m, pal, 1, NULL, 0, OUT(".glb"), &e) == LSYS_OK);
  s = json_of(OUT(".glb"));
  assert(strstr(s, "\"baseColorFactor\":[0.21404114,1,0.0030959751,0.5]") != NULL);
  assert(strstr(s, "\"emissiveFactor\":[0.21404114,0,0]") != NULL);
  assert(strstr(s, "\"alphaMode\":\"BLEND\"") != NULL);
  free(s);
  assert(lsys_export_obj(&m, pal, 1, NULL, 0, OUT(".obj"), &e) == LSYS_OK);
  s = slurp(OUT(".mtl"), &len);
  assert(strstr(s, "\nKd 0.21404114 1 0.0030959751\n") != NULL);
  assert(strstr(s, "\nKe 0.21404114 0 0\n") != NULL);
  assert(strstr(s, "\nd 0.5\n") != NULL);
  free(s);
  assert(lsys_export_ply(&m, pal, 1, NULL, 0, OUT(".ply"), &e) == LSYS_OK);
  s = slurp(OUT(".ply"), &len);
  {                                         /* the last vertex's colour: 128 255 10 */
    const unsigned char *q = (const unsigned char *)s + len - 13 - 3;
    assert(q[0] == 128 && q[1] == 255 && q[2] == 10);
  }
  free(s);
  remove(OUT(".glb")); remove(OUT(".obj")); remove(OUT(".mtl")); remove(OUT(".ply"));
  lsys_mesh_free(&m);
}

/* ---- tubes ---- */

/* One segment along +z: two rings and two caps; its exact bounds (H = z
** makes U = x and L = y); a closed hexagonal prism of the right volume. */
static void test_tube (void) {
  lsys_mesh m, t;
  double lo[3], hi[3], c[3] = {0, 0, 1}, h[3] = {0, 0, 1};
  double r = 0.5, hex = 1.5 * sqrt(3.0) * r * r;
  lsys_mesh_init(&m);
  line(&m, 0, 0, 0, 0, 0, 2, 2, 2, 3);
  assert(lsys_mesh_tubes(&t, &m, 6, 0.5) == LSYS_OK);
  assert(t.nl == 0 && t.nv == 4 * 7 && t.nt == 4 * 6);
  assert(lsys_mesh_bounds(&t, lo, hi));
  assert(lo[1] == -0.5 && hi[1] == 0.5 && lo[2] == 0 && hi[2] == 2);
  assert(fabs(hi[0] - r * sqrt(3.0) / 2) < 1e-6 && fabs(lo[0] + r * sqrt(3.0) / 2) < 1e-6);
  assert(fabs(volume6(&t, 0, t.nt) / 6 - hex * 2) < 1e-5);
  outward(&t, 0, t.nt, c, h);
  assert(t.col[0] == 3 && t.col[t.nv - 1] == 3 && t.tex[0] == 0 && t.twosided[0] == 0);
  lsys_mesh_free(&t);
  /* a taper: radii 0.5 and 0.25, the normals tilted up the cone */
  m.lwidth[1] = 1;
  assert(lsys_mesh_tubes(&t, &m, 6, 0.5) == LSYS_OK);
  assert(lsys_mesh_bounds(&t, lo, hi) && lo[1] == -0.5 && hi[1] == 0.5);
  assert(t.pos[3 * 14 + 1] == 0.25f && t.pos[3 * 14 + 2] == 2);   /* the top ring */
  assert(t.nrm[2] > 0.12 && t.nrm[2] < 0.13);                     /* slope 1/8 */
  outward(&t, 0, t.nt, c, h);
  lsys_mesh_free(&t);
  lsys_mesh_free(&m);
}

/* Runs: a straight run shares its rings; a bend of 30 degrees or more, a new
** colour or width, or a gap starts a new run with caps. */
static void test_runs (void) {
  lsys_mesh m, t;
  double c[3] = {0, 0, 1.5}, h[3] = {0, 0, 1};
  int n = 6;
  size_t run = 4 * ((size_t)n + 1), more = (size_t)n + 1;
  lsys_mesh_init(&m);
  line(&m, 0, 0, 0, 0, 0, 1, 1, 1, 0);
  line(&m, 0, 0, 1, 0, 0, 2, 1, 1, 0);
  line(&m, 0, 0, 2, 0, 0, 3, 1, 1, 0);
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == run + 2 * more && t.nt == 4 * (size_t)n + 2 * 2 * (size_t)n);
  assert(fabs(volume6(&t, 0, t.nt) / 6 - 1.5 * sqrt(3.0) * 0.25 * 3) < 1e-5);
  outward(&t, 0, t.nt, c, h);
  /* v runs on along the stem: length over circumference (the top ring before the cap) */
  assert(fabs(t.uv[2 * (t.nv - 2 * (size_t)n - 2) + 1] - 3 / PI) < 1e-6);
  lsys_mesh_free(&t);
  /* a bend of 29 degrees still joins, with the next ring lined up */
  m.lpos[6 + 3] = (float)sin(29 * PI / 180);
  m.lpos[6 + 5] = (float)(1 + cos(29 * PI / 180));
  m.nl = 2;
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == run + more && t.nt == 6 * (size_t)n);
  assert(volume6(&t, 0, t.nt) > 0);
  lsys_mesh_free(&t);
  /* 31 degrees does not */
  m.lpos[6 + 3] = (float)sin(31 * PI / 180);
  m.lpos[6 + 5] = (float)(1 + cos(31 * PI / 180));
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == 2 * run && t.nt == 8 * (size_t)n);
  lsys_mesh_free(&t);
  /* F+F: two runs at 90 degrees, 48 triangles with 6 sides */
  m.lpos[6 + 0] = 0; m.lpos[6 + 1] = 0; m.lpos[6 + 2] = 1;
  m.lpos[6 + 3] = 1; m.lpos[6 + 4] = 0; m.lpos[6 + 5] = 1;
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == 56 && t.nt == 48);
  lsys_mesh_free(&t);
  /* straight again, but another colour, then another width */
  m.nl = 3;
  m.lcol[1] = 1;
  m.lpos[6 + 3] = 0; m.lpos[6 + 5] = 2;
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == 3 * run && t.nt == 12 * (size_t)n);
  lsys_mesh_free(&t);
  m.lcol[1] = 0;
  m.lwidth[2] = m.lwidth[3] = 2;
  assert(lsys_mesh_tubes(&t, &m, n, 1) == LSYS_OK);
  assert(t.nv == 3 * run && t.nt == 12 * (size_t)n);
  lsys_mesh_free(&t);
  lsys_mesh_free(&m);
}

/* The triangles already there stay first and as they were; segments of
** zero length or with a non-finite end are left out (and break a run);
** thin or bad widths draw 1 pixel wide, huge ones 16384; bad arguments. */
static void test_leftout (void) {
  lsys_mesh m, t;
  double p[3] = {5, 5, 5}, n3[3] = {0, 1, 0}, lo[3], hi[3];
  uint32_t a;
  int n = 4;
  lsys_mesh_init(&m);
  assert(lsys_mesh_reserve(&m, 3, 1) == LSYS_OK);
  m.curtex = 2;
  a = lsys_mesh_vertex(&m, p, n3, 0.25, 0.75, 7, 1);
  lsys_mesh_vertex(&m, p, n3, 0, 0, 7, 1);
  lsys_mesh_vertex(&m, p, n3, 0, 0, 7, 1);
  lsys_mesh_tri(&m, a, a + 2, a + 1);
  line(&m, 0, 0, 0, 1, 0, 0, 0.25, NAN, 0);    /* 1 pixel at both ends */
  line(&m, 1, 0, 0, 1, 0, 0, 1, 1, 0);         /* zero length */
  line(&m, 1, 0, 0, 2, 0, 0, 1, 1, 0);
  line(&m, 2, 0, 0, NAN, 0, 0, 1, 1, 0);
  line(&m, 2, 0, 0, 3, 0, 0, 1e9, 1e9, 0);     /* 16384 */
  assert(lsys_mesh_tubes(&t, &m, n, 0.5) == LSYS_OK);
  assert(t.nv == 3 + 3 * 4 * ((size_t)n + 1) && t.nt == 1 + 3 * 4 * (size_t)n);
  assert(t.tri[0] == 0 && t.tri[1] == 2 && t.tri[2] == 1 && t.tex[0] == 2 && t.tex[3] == 0);
  assert(t.uv[0] == 0.25f && t.twosided[0] == 1 && t.col[2] == 7 && t.nrm[1] == 1);
  assert(lsys_mesh_bounds(&t, lo, hi) && hi[0] == 5 && hi[1] == 16384 * 0.25);
  assert(fabs(t.pos[3 * 3 + 2] - 0.25) < 1e-7);     /* width 0.25 drawn as 1: radius 0.25 */
  lsys_mesh_free(&t);
  assert(lsys_mesh_tubes(&t, &m, 2, 1) == LSYS_EARG && t.nv == 0 && t.pos == NULL);
  assert(lsys_mesh_tubes(&t, &m, 1025, 1) == LSYS_EARG);
  assert(lsys_mesh_tubes(&t, &m, 3, 0) == LSYS_EARG);
  assert(lsys_mesh_tubes(&t, &m, 3, NAN) == LSYS_EARG);
  assert(lsys_mesh_tubes(&t, &m, 3, INFINITY) == LSYS_EARG);
  m.nl = 0;                                    /* no lines: a copy of the triangles */
  assert(lsys_mesh_tubes(&t, &m, 3, 1) == LSYS_OK && t.nv == 3 && t.nt == 1);
  lsys_mesh_free(&t);
  lsys_mesh_free(&m);
}

/* ---- the scene ---- */

/* A scene of one triangle and F+F lines: tubes in every format, the
** default pixel, the options checked. */
static void test_scene (void) {
  lsys_scene s;
  lsys_error e;
  lsys_export_opts o = {1, 6, 0, 0, 0, NULL};
  lsys_export_sizes sz = {0, 0, 0, 0};
  lsys_material pal[2];
  double p[3] = {0, 0, 0}, nn[3] = {0, 0, 1};
  size_t len;
  char *j;
  memset(&s, 0, sizeof s);
  lsys_mesh_material_color(&pal[0], 0.2, 0.6, 0.1);
  lsys_mesh_material_color(&pal[1], 0.5, 0.5, 0.5);
  s.pal = pal;
  s.npal = 2;
  lsys_mesh_init(&s.mesh);
  assert(lsys_mesh_reserve(&s.mesh, 3, 1) == LSYS_OK);
  lsys_mesh_vertex(&s.mesh, p, nn, 0, 0, 0, 1);
  lsys_mesh_vertex(&s.mesh, p, nn, 0, 0, 0, 1);
  lsys_mesh_vertex(&s.mesh, p, nn, 0, 0, 0, 1);
  lsys_mesh_tri(&s.mesh, 0, 1, 2);
  line(&s.mesh, 0, 0, 0, 0, 7.2, 0, 1, 1, 1);
  line(&s.mesh, 0, 7.2, 0, 7.2, 7.2, 0, 1, 1, 1);
  assert(fabs(lsys_export_pixel(&s.mesh) - 0.01) < 1e-9);
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), &o, &e) == LSYS_OK);
  j = json_of(OUT("_s.glb"));
  assert(count(j, "\"mode\":4") == 2 && count(j, "\"mode\":1") == 0);
  assert(strstr(j, "\"count\":59,") != NULL);                  /* 3 + 2 * 4 * 7 vertices */
  assert(strstr(j, "\"count\":3,") != NULL && strstr(j, "\"count\":144,") != NULL);
  /* radius 0.005 (7.2 / 720 / 2), the rings in the planes x = 0 and x = 7.2 */
  assert(strstr(j, "\"min\":[-0.004330127,0,-0.005],\"max\":[7.2,7.20433,0.005]") != NULL);
  free(j);
  assert(lsys_export_scene(&s, LSYS_FORMAT_OBJ, OUT("_s.obj"), &o, &e) == LSYS_OK);
  j = slurp(OUT("_s.obj"), &len);
  assert(countlines(j, "f ") == 49 && countlines(j, "l ") == 0 && countlines(j, "v ") == 59);
  free(j);
  assert(lsys_export_scene(&s, LSYS_FORMAT_PLY, OUT("_s.ply"), &o, &e) == LSYS_OK);
  j = slurp(OUT("_s.ply"), &len);
  assert(strstr(j, "element vertex 59\n") && strstr(j, "element face 49\n"));
  assert(strstr(j, "element edge") == NULL);
  free(j);
  o.sizes = &sz;                               /* what the file holds: the tubes, no lines */
  assert(lsys_export_scene(&s, LSYS_FORMAT_PLY, OUT("_s.ply"), &o, &e) == LSYS_OK);
  assert(sz.nv == 59 && sz.nt == 49 && sz.nl == 0 && sz.ninst == 0);
  o.sizes = NULL;
  o.pixel = 0.5;                               /* radius 0.25: thicker */
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), &o, &e) == LSYS_OK);
  j = json_of(OUT("_s.glb"));
  assert(strstr(j, "\"min\":[-0.21650635,0,-0.25],\"max\":[7.2,7.4165063,0.25]") != NULL);
  free(j);
  o.tubes = 0;                                  /* lines as lines */
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), &o, &e) == LSYS_OK);
  j = json_of(OUT("_s.glb"));
  assert(count(j, "\"mode\":1") == 1);
  free(j);
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), NULL, &e) == LSYS_OK);
  o.tubes = 1;
  o.sides = 2;
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), &o, &e) == LSYS_EARG);
  assert(strstr(e.msg, "3 to 1024 sides, got 2") && strstr(e.msg, OUT("_s.glb")));
  o.sides = 6;
  o.pixel = -1;
  assert(lsys_export_scene(&s, LSYS_FORMAT_GLB, OUT("_s.glb"), &o, &e) == LSYS_EARG);
  assert(strstr(e.msg, "pixel size") != NULL);
  o.pixel = 0;
  assert(lsys_export_scene(&s, -1, OUT("_s.xyz"), &o, &e) == LSYS_EARG);
  lsys_mesh_free(&s.mesh);
  lsys_mesh_init(&s.mesh);
  assert(lsys_export_pixel(&s.mesh) == 1);
  remove(OUT("_s.glb")); remove(OUT("_s.obj")); remove(OUT("_s.mtl")); remove(OUT("_s.ply"));
}

/* ---- populations ---- */

/* Two prototypes -- a triangle, and a triangle with a line -- and three
** instances (T R S), in 'pop' (its palette: pal). */
static void population (lsys_scene *pop, const lsys_material *pal) {
  lsys_scene a;
  double p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, nn[3] = {0, 0, 1};
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  size_t k;
  int i, j;
  lsys_scene_init(pop);
  for (j = 0; j < 2; j++) {
    lsys_scene_init(&a);
    a.pal = (lsys_material *)pal;           /* read, not freed: npal set back below */
    a.npal = 2;
    assert(lsys_mesh_reserve(&a.mesh, 3, 1) == LSYS_OK);
    for (i = 0; i < 3; i++) lsys_mesh_vertex(&a.mesh, p[i], nn, 0, 0, (unsigned)j, j);
    lsys_mesh_tri(&a.mesh, 0, 1, 2);
    if (j == 1) line(&a.mesh, 0, 0, 0, 0, 2, 0, 1, 1, 1);
    assert(lsys_population_add(pop, &a, NULL, 1, &k) == LSYS_OK && k == (size_t)j);
    a.pal = NULL;
    a.npal = 0;
    lsys_scene_free(&a);
  }
  m[12] = 5;
  assert(lsys_scene_add_instance(pop, 0, m) == LSYS_OK);
  m[0] = 0; m[2] = -2; m[8] = 1; m[10] = 0;          /* turned 90 degrees about y, x scaled 2 */
  assert(lsys_scene_add_instance(pop, 1, m) == LSYS_OK);
  m[12] = -5;
  assert(lsys_scene_add_instance(pop, 0, m) == LSYS_OK);
}

static void test_population (void) {
  lsys_scene pop;
  lsys_material pal[2];
  lsys_export_opts o = {0, 0, 0, 0, 0, NULL};
  lsys_error e;
  size_t len;
  char *j;
  lsys_mesh_material_color(&pal[0], 0.2, 0.6, 0.1);
  lsys_mesh_material_color(&pal[1], 0.5, 0.5, 0.5);
  population(&pop, pal);
  assert(lsys_export_scene(&pop, LSYS_FORMAT_GLB, OUT("_p.glb"), NULL, &e) == LSYS_OK);
  j = json_of(OUT("_p.glb"));
  assert(strstr(j, "\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],"
                   "\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"]") != NULL);
  assert(count(j, "\"primitives\"") == 2 && count(j, "\"EXT_mesh_gpu_instancing\":{") == 2);
  assert(strstr(j, "\"name\":\"prototype 1\"") && strstr(j, "\"name\":\"prototype 2\""));
  assert(count(j, "\"mode\":4") == 2 && count(j, "\"mode\":1") == 1);
  /* prototype 1 has two instances, its vertices counted from 0 in its own accessors */
  assert(strstr(j, "\"count\":2,\"type\":\"VEC4\"") != NULL);
  assert(strstr(j, "\"byteOffset\":96,\"componentType\":5126,\"count\":3,") != NULL);
  free(j);
  /* written out: every instance */
  assert(lsys_export_scene(&pop, LSYS_FORMAT_OBJ, OUT("_p.obj"), NULL, &e) == LSYS_OK);
  j = slurp(OUT("_p.obj"), &len);
  assert(countlines(j, "f ") == 3 && countlines(j, "l ") == 1);
  assert(countlines(j, "v ") == 11 && strstr(j, "\nv -5 0 -2\n") != NULL);   /* + 2 line ends */
  free(j);
  o.flatten = 1;
  assert(lsys_export_scene(&pop, LSYS_FORMAT_GLB, OUT("_p.glb"), &o, &e) == LSYS_OK);
  j = json_of(OUT("_p.glb"));
  assert(strstr(j, "EXT_mesh_gpu_instancing") == NULL && count(j, "\"primitives\"") == 1);
  free(j);
  o.max_memory = 100;                                 /* too little to write it out */
  assert(lsys_export_scene(&pop, LSYS_FORMAT_PLY, OUT("_p.ply"), &o, &e) == LSYS_EMEMORY);
  assert(strstr(e.msg, "the population written out needs") && strstr(e.msg, "max_memory"));
  /* tubes: made per prototype, the instances kept */
  o.flatten = 0; o.max_memory = 0; o.tubes = 1; o.sides = 4;
  assert(lsys_export_scene(&pop, LSYS_FORMAT_GLB, OUT("_p.glb"), &o, &e) == LSYS_OK);
  j = json_of(OUT("_p.glb"));
  assert(count(j, "\"mode\":1") == 0 && count(j, "\"EXT_mesh_gpu_instancing\":{") == 2);
  free(j);
  o.tubes = 0;
  pop.inst[1].m[4] = 0.5f;                            /* a shear: no T R S */
  assert(lsys_export_scene(&pop, LSYS_FORMAT_GLB, OUT("_p.glb"), NULL, &e) == LSYS_EARG);
  assert(strstr(e.msg, "instance 2 is not a translation, rotation and positive scale"));
  o.flatten = 1;
  assert(lsys_export_scene(&pop, LSYS_FORMAT_GLB, OUT("_p.glb"), &o, &e) == LSYS_OK);
  lsys_scene_free(&pop);
  remove(OUT("_p.glb")); remove(OUT("_p.obj")); remove(OUT("_p.mtl")); remove(OUT("_p.ply"));
}

/* Every allocation of saving a population fails in turn, as test_nomem. */
static void test_population_nomem (void) {
  lsys_scene pop;
  lsys_material pal[2];
  lsys_export_opts o = {1, 4, 0, 0, 0, NULL};
  lsys_error e;
  long k, live;
  int f, done = 0;
  lsys_mesh_material_color(&pal[0], 0.2, 0.6, 0.1);
  lsys_mesh_material_color(&pal[1], 0.5, 0.5, 0.5);
  population(&pop, pal);
  live = nlive;
  for (k = 0; !done; k++) {
    int st = LSYS_OK;
    nalloc = 0;
    failat = k;
    for (f = 0; f < 4 && st == LSYS_OK; f++) {
      o.tubes = f == 3;
      st = lsys_export_scene(&pop, f < 3 ? f : LSYS_FORMAT_GLB,
                             f == 0 ? OUT("_pn.obj") : f == 1 ? OUT("_pn.ply") : OUT("_pn.glb"), &o,
                             &e);
      assert(st == LSYS_OK || (st == LSYS_ENOMEM && strstr(e.msg, OUT("_pn."))));
    }
    assert(nlive == live);
    done = nalloc <= k;
  }
  failat = -1;
  assert(k > 10);
  lsys_scene_free(&pop);
  remove(OUT("_pn.obj")); remove(OUT("_pn.mtl")); remove(OUT("_pn.ply")); remove(OUT("_pn.glb"));
}

/* ---- allocation failures ---- */

/* Every allocation of a save with tubes fails in turn: LSYS_OK or
** LSYS_ENOMEM with a message naming the file, nothing left allocated. */
static void test_nomem (void) {
  lsys_scene s;
  lsys_error e;
  lsys_export_opts o = {1, 5, 0, 0, 0, NULL};
  long k, live;
  int f, done = 0;
  memset(&s, 0, sizeof s);
  lsys_mesh_init(&s.mesh);
  line(&s.mesh, 0, 0, 0, 0, 1, 0, 1, 1, 0);
  line(&s.mesh, 0, 1, 0, 0, 2, 0, 1, 1, 0);
  line(&s.mesh, 0, 2, 0, 1, 2, 0, 1, 1, 1);
  live = nlive;
  for (k = 0; !done; k++) {
    int st = LSYS_OK;
    nalloc = 0;
    failat = k;
    for (f = 0; f < 3 && st == LSYS_OK; f++) {
      st = lsys_export_scene(&s, f, f == 0 ? OUT("_n.obj") : f == 1 ? OUT("_n.ply") : OUT("_n.glb"),
                             &o, &e);
      assert(st == LSYS_OK || (st == LSYS_ENOMEM && strstr(e.msg, "out of memory") &&
                               strstr(e.msg, OUT("_n."))));
    }
    assert(nlive == live);
    done = nalloc <= k;
  }
  failat = -1;
  assert(k > 10);
  lsys_mesh_free(&s.mesh);
  remove(OUT("_n.obj")); remove(OUT("_n.mtl")); remove(OUT("_n.ply")); remove(OUT("_n.glb"));
}

int main (void) {
  test_linear();
  test_factors();
  test_tube();
  test_runs();
  test_leftout();
  test_scene();
  test_nomem();
  test_population();
  test_population_nomem();
  printf("test_export: ok\n");
  return 0;
}
