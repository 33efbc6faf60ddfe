/*
** C unit tests for the mesh buffers and the export writers. The writers'
** output is read back here: OBJ and MTL element counts and number
** formatting, the PLY header and byte layout, the GLB container, its JSON
** and its binary data.
**
** The files go to the test's private folder (testdir.h).
** `test_mesh bench` also times each writer on a mesh of 1M triangles.
**
** mesh.c and the writers (export_*.c) are compiled into this test with
** counting allocators, so that test_nomem can make each allocation fail in
** turn (the library's own copies of their objects are then not linked).
*/
#define _XOPEN_SOURCE 700       /* testdir.h */
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static long nalloc, failat = -1;    /* allocation number 'failat' fails */

static void *tmalloc (size_t n) {
  return nalloc++ == failat ? NULL : malloc(n);
}

static void *trealloc (void *p, size_t n) {
  return nalloc++ == failat ? NULL : realloc(p, n);
}

#define LSYS_MALLOC(n)     tmalloc(n)
#define LSYS_REALLOC(p, n) trealloc((p), (n))
#define LSYS_FREE(p)       free(p)
#include "common.c"
#include "mesh.c"
#include "export_write.c"
#include "export_group.c"
#include "export_obj.c"
#include "export_ply.c"
#include "export_glb.c"
#include "pngio.h"

#include "testfile.h"

#include "testdir.h"

#define OUT(suffix) testpath("lsys_test_mesh" suffix)   /* a file in the test's folder */

/* ---- helpers ---- */

static float rdf32 (const unsigned char *p) {
  uint32_t u = rd32(p);
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static const void *findmem (const void *hay, size_t n, const void *needle, size_t k) {
  const char *h = (const char *)hay;
  size_t i;
  for (i = 0; i + k <= n; i++)
    if (memcmp(h + i, needle, k) == 0) return h + i;
  return NULL;
}

/* One triangle of three new vertices around (x, y, z). */
static void addtri (lsys_mesh *m, double x, double y, double z, unsigned col, int two) {
  double p[3], n[3] = { 0, 0, 2 };             /* not unit: the glb writer normalises */
  uint32_t a, b, c;
  assert(lsys_mesh_reserve(m, 3, 1) == LSYS_OK);
  p[0] = x; p[1] = y; p[2] = z;
  a = lsys_mesh_vertex(m, p, n, 0, 0, col, two);
  p[0] = x + 1;
  b = lsys_mesh_vertex(m, p, n, 1, 0, col, two);
  p[1] = y + 1;
  c = lsys_mesh_vertex(m, p, n, 1, 1, col, two);
  lsys_mesh_tri(m, a, b, c);
}

/* The test mesh: triangles of colours 0, 0, 1 (two-sided), 3; segments of
** colours 0, 1, 2. With two materials, colour 3 is material 1 and colour 2
** material 0: material 0 has 2 triangles and 2 segments, material 1 has 2
** triangles (one two-sided) and 1 segment. */
static void testmesh (lsys_mesh *m, lsys_material pal[2]) {
  double a[3] = { 0, 0, 0 }, b[3] = { 0, 0, 5 };
  lsys_mesh_init(m);
  addtri(m, 0, 0, 0, 0, 0);
  addtri(m, 2, 0, 0, 0, 0);
  addtri(m, 0, 2, 0, 1, 1);
  addtri(m, -3, -1, 0.5, 3, 0);
  assert(lsys_mesh_line(m, a, b, 1, 1, 0) == LSYS_OK);
  b[0] = 1;
  assert(lsys_mesh_line(m, a, b, 2, 1, 1) == LSYS_OK);
  a[1] = 7;
  assert(lsys_mesh_line(m, a, b, 1, 1, 2) == LSYS_OK);
  lsys_mesh_material_color(&pal[0], 0.2, 0.6, 0.1);
  lsys_mesh_material_color(&pal[1], 1, 0.5, 0);
  pal[1].specular[0] = pal[1].specular[1] = pal[1].specular[2] = 0.5f;
  pal[1].shininess = 32;
}

/* ---- buffers ---- */

static void test_buffers (void) {
  lsys_mesh m;
  lsys_material mt;
  double lo[3], hi[3], p[3] = { 1, 2, 3 }, q[3] = { -1, 5, 0 }, n[3] = { 0, 0, 1 };
  size_t i, cap;
  lsys_mesh_init(&m);
  assert(lsys_mesh_bounds(&m, lo, hi) == 0);
  assert(lo[0] == 0 && hi[2] == 0);
  for (i = 0; i < 1000; i++) {
    assert(lsys_mesh_reserve(&m, 3, 1) == LSYS_OK);
    assert(m.vcap >= m.nv + 3 && m.tcap >= m.nt + 1);
    lsys_mesh_vertex(&m, p, n, 0, 0, 1, 0);
    lsys_mesh_vertex(&m, q, n, 0, 0, 1, 0);
    lsys_mesh_vertex(&m, p, n, 0, 0, 1, 1);
    lsys_mesh_tri(&m, (uint32_t)(3 * i), (uint32_t)(3 * i + 1), (uint32_t)(3 * i + 2));
  }
  assert(m.nv == 3000 && m.nt == 1000);
  assert(m.vcap == 4096 && m.tcap == 1024);      /* doubling from 16 */
  assert(m.twosided[2] == 1 && m.col[5] == 1 && m.pos[4] == 5.0f);
  for (i = 0; i < 100; i++) assert(lsys_mesh_line(&m, p, q, 1, 2, 7) == LSYS_OK);
  assert(m.nl == 100 && m.lcap == 128 && m.lwidth[1] == 2.0f && m.lcol[99] == 7);
  q[2] = 9;
  assert(lsys_mesh_line(&m, q, q, 1, 1, 0) == LSYS_OK);
  assert(lsys_mesh_bounds(&m, lo, hi) == 1);
  assert(lo[0] == -1 && lo[1] == 2 && lo[2] == 0 && hi[0] == 1 && hi[1] == 5 && hi[2] == 9);
  cap = m.vcap;
  lsys_mesh_clear(&m);
  assert(m.nv == 0 && m.nt == 0 && m.nl == 0 && m.vcap == cap);
  assert(lsys_mesh_bounds(&m, lo, hi) == 0);
  assert(lsys_mesh_reserve(&m, (size_t)UINT32_MAX + 1, 0) == LSYS_ELIMIT);
  assert(lsys_mesh_reserve(&m, (size_t)-1 / 2, 0) == LSYS_ELIMIT);
  assert(lsys_mesh_reserve(&m, 0, (size_t)-1 / 2) != LSYS_OK);
  lsys_mesh_free(&m);
  lsys_mesh_free(&m);                          /* idempotent */
  lsys_mesh_material_color(&mt, 0.5, 2, -1);
  assert(mt.diffuse[0] == 0.5f && mt.diffuse[1] == 1 && mt.diffuse[2] == 0 && mt.diffuse[3] == 1);
  assert(mt.ambient[0] == 0.15f && mt.ambient[3] == 1);
  assert(mt.specular[0] == 0 && mt.emission[0] == 0 && mt.shininess == 0);
}

/* ---- colour counts ---- */

static void test_color_counts (void) {
  static uint32_t count[LSYS_MESH_NCOLORS];
  lsys_mesh m;
  lsys_material pal[2];
  double a[3] = { 0, 0, 0 }, b[3] = { 1, 0, 0 };
  lsys_mesh_init(&m);
  count[5] = 9;                                 /* every entry is written */
  assert(lsys_mesh_color_counts(&m, count) == 0 && count[5] == 0);
  lsys_mesh_free(&m);
  testmesh(&m, pal);                            /* triangles 0, 0, 1, 3; segments 0, 1, 2 */
  assert(lsys_mesh_color_counts(&m, count) == 4);
  assert(count[0] == 3 && count[1] == 2 && count[2] == 1 && count[3] == 1 && count[4] == 0);
  addtri(&m, 0, 0, 0, 65535, 0);                /* the last index; not wrapped */
  assert(lsys_mesh_line(&m, a, b, 1, 1, 65535) == LSYS_OK);
  assert(lsys_mesh_color_counts(&m, count) == 5 && count[65535] == 2);
  lsys_mesh_free(&m);
}

/* ---- OBJ ---- */

static void test_obj (void) {
  lsys_mesh m;
  lsys_material pal[2];
  lsys_error e;
  size_t len;
  char *s, *t;
  testmesh(&m, pal);
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, OUT(".obj"), &e) == LSYS_OK);
  s = slurp(OUT(".obj"), &len);
  assert(countlines(s, "mtllib lsys_test_mesh.mtl\n") == 1);
  assert(countlines(s, "v ") == 12 + 6);
  assert(countlines(s, "vn ") == 12);
  assert(countlines(s, "vt ") == 12);
  assert(countlines(s, "f ") == 4);
  assert(countlines(s, "l ") == 3);
  assert(countlines(s, "usemtl ") == 2);
  assert(strstr(s, "\nv 0 0 0\nv 1 0 0\nv 1 1 0\n") != NULL);
  assert(strstr(s, "\nvn 0 0 2\n") != NULL);
  assert(strstr(s, "\nvt 1 1\n") != NULL);
  /* material 0: triangles 1, 2 and segments 1, 3; material 1: triangles 3, 4, segment 2 */
  t = strstr(s, "usemtl m0\nf 1/1/1 2/2/2 3/3/3\nf 4/4/4 5/5/5 6/6/6\nl 13 14\nl 15 16\n"
                "usemtl m1\nf 7/7/7 8/8/8 9/9/9\nf 10/10/10 11/11/11 12/12/12\nl 17 18\n");
  assert(t != NULL);
  /* the segment vertices in material order: segments 1, 3, then 2 */
  assert(strstr(s, "v -2 0 0.5\nv 0 0 0\nv 0 0 5\nv 0 7 0\nv 1 0 5\nv 0 0 0\nv 1 0 5\n") != NULL);
  free(s);
  s = slurp(OUT(".mtl"), &len);
  assert(countlines(s, "newmtl ") == 2);
  /* colours linear (Blender's reading of MTL): sRGB 0.2 0.6 0.1, 0.5 */
  assert(strstr(s, "newmtl m0\nKa 0.00489631 0.027211783 0.0023219816\n"
                   "Kd 0.033104766 0.3185468 0.010022826\nKs 0 0 0\nKe 0 0 0\nNs 0\nd 1\n"
                   "illum 1\n") != NULL);
  assert(strstr(s, "newmtl m1\nKa 0.07323896 0.01960665 0\nKd 1 0.21404114 0\n"
                   "Ks 0.21404114 0.21404114 0.21404114\nKe 0 0 0\nNs 32\nd 1\nillum 2\n")
         != NULL);
  free(s);
  /* no palette: one grey default */
  assert(lsys_export_obj(&m, NULL, 0, NULL, 0, OUT("_grey.obj"), &e) == LSYS_OK);
  s = slurp(OUT("_grey.mtl"), &len);
  assert(countlines(s, "newmtl ") == 1 && strstr(s, "newmtl m0\n"));
  assert(strstr(s, "Kd 0.60382736 0.60382736 0.60382736\n") != NULL);     /* sRGB 0.8 */
  free(s);
  s = slurp(OUT("_grey.obj"), &len);
  assert(countlines(s, "usemtl ") == 1 && countlines(s, "f ") == 4 && countlines(s, "l ") == 3);
  assert(countlines(s, "mtllib lsys_test_mesh_grey.mtl") == 1);
  free(s);
  remove(OUT("_grey.obj"));
  remove(OUT("_grey.mtl"));
  /* no extension: the .mtl is appended; a dot in a directory name is not one */
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, OUT("_noext"), &e) == LSYS_OK);
  s = slurp(OUT("_noext.mtl"), &len);
  free(s);
  remove(OUT("_noext"));
  remove(OUT("_noext.mtl"));
  lsys_mesh_free(&m);
}

/* Numbers: short forms, %g layout, exact float round trip. */
static void test_numbers (void) {
  static const float vals[] = { 0.1f, 1, -2.5f, 1e-5f, 123456789.0f, 1e10f, 3.4028235e38f,
                                0.0001f, -0.0f, 1.5e-4f, 100, 1234567.0f, 0.30000001f };
  static const char *text[] = { "0.1", "1", "-2.5", "1e-05", "123456790", "1e+10",
                                "3.40282347e+38", "0.0001", "0", "0.00015", "100", "1234567",
                                "0.3" };
  size_t nv = 300000, i, len;
  lsys_mesh m;
  lsys_error e;
  char *s, *p, line[64];
  double pt[3], n[3] = { 0, 0, 0 };
  uint32_t seed = 12345;
  float *want;
  lsys_mesh_init(&m);
  assert(lsys_mesh_reserve(&m, nv, 0) == LSYS_OK);
  for (i = 0; i < 13; i++) {
    pt[0] = vals[i]; pt[1] = pt[2] = 0;
    lsys_mesh_vertex(&m, pt, n, 0, 0, 0, 0);
  }
  pt[0] = NAN; pt[1] = INFINITY; pt[2] = -INFINITY;
  lsys_mesh_vertex(&m, pt, n, 0, 0, 0, 0);
  want = malloc(3 * nv * sizeof *want);
  assert(want != NULL);
  while (m.nv < nv) {                          /* random bit patterns, finite ones */
    int k;
    for (k = 0; k < 3; k++) {
      uint32_t u;
      float f;
      do {
        seed = seed * 1664525u + 1013904223u;
        u = seed ^ (seed >> 13) * 2654435761u;
        memcpy(&f, &u, sizeof f);
      } while (!isfinite(f));
      pt[k] = f;
    }
    lsys_mesh_vertex(&m, pt, n, 0, 0, 0, 0);
  }
  assert(lsys_export_obj(&m, NULL, 0, NULL, 0, OUT("_num.obj"), &e) == LSYS_OK);
  s = slurp(OUT("_num.obj"), &len);
  p = strstr(s, "\nv ");
  assert(p != NULL);
  for (i = 0; i < 13; i++) {
    snprintf(line, sizeof line, "\nv %s 0 0\n", text[i]);
    if (strncmp(p, line, strlen(line)) != 0) {
      fprintf(stderr, "expected %s got %.30s\n", line + 1, p + 1);
      assert(0);
    }
    p = strchr(p + 1, '\n');
  }
  assert(strncmp(p, "\nv 0 0 0\n", 9) == 0);    /* non-finite values are written as 0 */
  p = strchr(p + 1, '\n');
  for (i = 14; i < nv; i++) {                  /* every value reads back exactly */
    int k;
    char *q = p + 3;
    assert(strncmp(p, "\nv ", 3) == 0);
    for (k = 0; k < 3; k++) {
      float f = strtof(q, &q);
      if (f != m.pos[3 * i + k]) {
        fprintf(stderr, "%.9g read back as %.9g\n", m.pos[3 * i + k], f);
        assert(0);
      }
    }
    assert(*q == '\n');
    assert(q - p - 1 <= 3 * 16 + 1);
    p = q;
  }
  free(s);
  free(want);
  remove(OUT("_num.obj"));
  remove(OUT("_num.mtl"));
  lsys_mesh_free(&m);
}

/* ---- PLY ---- */

static void test_ply (void) {
  lsys_mesh m;
  lsys_material pal[2];
  lsys_error e;
  size_t len, hlen;
  char *s, *h;
  const unsigned char *d;
  testmesh(&m, pal);
  assert(lsys_export_ply(&m, pal, 2, NULL, 0, OUT(".ply"), &e) == LSYS_OK);
  s = slurp(OUT(".ply"), &len);
  assert(strncmp(s, "ply\nformat binary_little_endian 1.0\n", 36) == 0);
  h = strstr(s, "end_header\n");
  assert(h != NULL);
  hlen = (size_t)(h - s) + 11;
  *h = '\0';
  assert(strstr(s, "\nelement vertex 18\nproperty float x\nproperty float y\nproperty float z\n"
                   "property float nx\nproperty float ny\nproperty float nz\n"
                   "property float s\nproperty float t\n"
                   "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                   "element face 4\nproperty list uchar uint vertex_indices\n"
                   "element edge 3\nproperty int vertex1\nproperty int vertex2\n") != NULL);
  assert(len == hlen + 18 * 35 + 4 * 13 + 3 * 8);
  d = (const unsigned char *)s + hlen;
  /* vertex 1 of triangle 1: (1, 0, 0), normal (0, 0, 2), uv (1, 0), material 0 */
  d += 35;
  assert(rdf32(d) == 1 && rdf32(d + 4) == 0 && rdf32(d + 8) == 0);
  assert(rdf32(d + 20) == 2 && rdf32(d + 24) == 1 && rdf32(d + 28) == 0);
  assert(d[32] == 51 && d[33] == 153 && d[34] == 26);
  /* vertex 9 (colour 3 -> material 1) */
  d += 8 * 35;
  assert(d[32] == 255 && d[33] == 128 && d[34] == 0);
  /* segment 2's vertices 14, 15: (0,0,0)-(1,0,5), material 1, normal 0 */
  d = (const unsigned char *)s + hlen + 14 * 35;
  assert(rdf32(d) == 0 && rdf32(d + 12) == 0 && rdf32(d + 20) == 0 && d[32] == 255);
  assert(rdf32(d + 35) == 1 && rdf32(d + 35 + 8) == 5);
  /* faces */
  d = (const unsigned char *)s + hlen + 18 * 35;
  assert(d[0] == 3 && rd32(d + 1) == 0 && rd32(d + 5) == 1 && rd32(d + 9) == 2);
  d += 3 * 13;
  assert(d[0] == 3 && rd32(d + 1) == 9 && rd32(d + 9) == 11);
  /* edges */
  d += 13;
  assert(rd32(d) == 12 && rd32(d + 4) == 13 && rd32(d + 16) == 16 && rd32(d + 20) == 17);
  free(s);
  /* without segments: no edge element */
  m.nl = 0;
  assert(lsys_export_ply(&m, NULL, 0, NULL, 0, OUT("_nl.ply"), &e) == LSYS_OK);
  s = slurp(OUT("_nl.ply"), &len);
  assert(strstr(s, "element edge") == NULL && strstr(s, "element vertex 12\n") != NULL);
  h = strstr(s, "end_header\n");
  assert(len == (size_t)(h - s) + 11 + 12 * 35 + 4 * 13);
  assert((unsigned char)h[11 + 32] == 204);      /* default grey 0.8 */
  free(s);
  remove(OUT("_nl.ply"));
  lsys_mesh_free(&m);
}

/* ---- GLB ---- */

/* The numbers that follow each "count": in the JSON, in order. */
static int counts (const char *json, size_t *out, int max) {
  int n = 0;
  const char *p = json;
  while ((p = strstr(p, "\"count\":")) != NULL && n < max) {
    p += 8;
    out[n++] = strtoul(p, NULL, 10);
  }
  return n;
}

static void test_glb (void) {
  lsys_mesh m;
  lsys_material pal[2];
  lsys_error e;
  size_t len, jlen, blen, c[16], i;
  unsigned char *s, *bin;
  char *json;
  testmesh(&m, pal);
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, OUT(".glb"), &e) == LSYS_OK);
  s = (unsigned char *)slurp(OUT(".glb"), &len);
  assert(rd32(s) == 0x46546C67u && rd32(s + 4) == 2 && rd32(s + 8) == len);
  jlen = rd32(s + 12);
  assert(jlen % 4 == 0 && rd32(s + 16) == 0x4E4F534Au);
  json = malloc(jlen + 1);
  assert(json != NULL);
  memcpy(json, s + 20, jlen);
  json[jlen] = '\0';
  blen = rd32(s + 20 + jlen);
  assert(rd32(s + 24 + jlen) == 0x004E4942u);
  assert(blen % 4 == 0 && len == 28 + jlen + blen);
  bin = s + 28 + jlen;
  assert(strncmp(json, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"lsys\"}", 45) == 0);
  assert(strstr(json, "\"byteLength\":") != NULL);
  assert(blen == 12 * 32 + 4 * 12 + 3 * 24);
  /* POSITION, NORMAL, TEXCOORD_0; indices of materials 0 and 1; lines of 0 and 1 */
  assert(counts(json, c, 16) == 7);
  assert(c[0] == 12 && c[1] == 12 && c[2] == 12 && c[3] == 6 && c[4] == 6 && c[5] == 4 && c[6] == 2);
  assert(strstr(json, "\"mode\":4") && strstr(json, "\"mode\":1"));
  assert(strstr(json, "\"min\":[-3,-1,0],\"max\":[3,3,0.5]") != NULL);
  /* linear factors: sRGB 0.5 is 0.21404114 */
  assert(strstr(json, "\"name\":\"m1\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                      "[1,0.21404114,0,1],"
                      "\"metallicFactor\":0,\"roughnessFactor\":0.49247906}") != NULL);
  assert(strstr(json, "\"roughnessFactor\":0.8}") != NULL);   /* (2 / 34)^(1/4) and the cap */
  {                                             /* only material 1 is double-sided */
    char *m0 = strstr(json, "\"name\":\"m0\""), *m1 = strstr(json, "\"name\":\"m1\"");
    char *ds = strstr(json, "\"doubleSided\":true");
    assert(m0 && m1 && ds && m0 < m1 && ds > m1 && strstr(ds + 5, "doubleSided") == NULL);
  }
  for (i = 0; i < 12; i++) {                    /* unit normals, positions as given */
    const unsigned char *v = bin + 32 * i;
    float nx = rdf32(v + 12), ny = rdf32(v + 16), nz = rdf32(v + 20);
    assert(nx == 0 && ny == 0 && nz == 1);
    assert(rdf32(v) == m.pos[3 * i] && rdf32(v + 24) == m.uv[2 * i]);
    assert(rdf32(v + 28) == 1 - m.uv[2 * i + 1]);       /* glTF's v points down */
  }
  /* indices in material order: triangles 0, 1 | 2, 3 */
  assert(rd32(bin + 384) == 0 && rd32(bin + 384 + 20) == 5 && rd32(bin + 384 + 24) == 6);
  assert(rd32(bin + 384 + 44) == 11);
  /* segments in material order: 0, 2 | 1 */
  assert(rdf32(bin + 432 + 20) == 5 && rdf32(bin + 432 + 24 + 4) == 7);
  assert(rdf32(bin + 432 + 48 + 12) == 1);
  free(json);
  free(s);

  /* zero and NaN normals become (0, 0, 1); NaN positions 0 */
  m.nrm[0] = m.nrm[1] = m.nrm[2] = 0;
  m.nrm[3] = NAN;
  m.nrm[6] = 3; m.nrm[7] = 4; m.nrm[8] = 0;
  m.pos[0] = NAN;
  assert(lsys_export_glb(&m, NULL, 0, NULL, 0, OUT("_n.glb"), &e) == LSYS_OK);
  s = (unsigned char *)slurp(OUT("_n.glb"), &len);
  jlen = rd32(s + 12);
  bin = s + 28 + jlen;
  assert(rdf32(bin) == 0 && rdf32(bin + 20) == 1 && rdf32(bin + 32 + 20) == 1);
  assert(rdf32(bin + 64 + 12) == 0.6f && rdf32(bin + 64 + 16) == 0.8f);
  assert(findmem(s + 20, jlen, "\"materials\":[{\"name\":\"m0\"", 25) != NULL);
  free(s);
  remove(OUT("_n.glb"));

  /* only segments */
  m.nt = 0;
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, OUT("_l.glb"), &e) == LSYS_OK);
  s = (unsigned char *)slurp(OUT("_l.glb"), &len);
  jlen = rd32(s + 12);
  assert(rd32(s + 20 + jlen) == 72 && len == 28 + jlen + 72);
  json = malloc(jlen + 1);
  memcpy(json, s + 20, jlen);
  json[jlen] = '\0';
  assert(counts(json, c, 16) == 2 && c[0] == 4 && c[1] == 2);
  assert(strstr(json, "\"mode\":4") == NULL && strstr(json, "TEXCOORD_0") == NULL);
  free(json);
  free(s);
  remove(OUT("_l.glb"));

  /* empty: a JSON chunk only, a scene without nodes */
  lsys_mesh_clear(&m);
  assert(lsys_export_glb(&m, NULL, 0, NULL, 0, OUT("_empty.glb"), &e) == LSYS_OK);
  s = (unsigned char *)slurp(OUT("_empty.glb"), &len);
  jlen = rd32(s + 12);
  assert(rd32(s + 8) == len && len == 20 + jlen && jlen % 4 == 0);
  assert(findmem(s + 20, jlen, "\"scenes\":[{}]", 13) != NULL);
  assert(findmem(s + 20, jlen, "\"asset\"", 7) != NULL);
  free(s);
  lsys_mesh_free(&m);
}

/* ---- errors ---- */

static void test_errors (void) {
  lsys_mesh m;
  lsys_material pal[2];
  lsys_error e;
  FILE *f;
  testmesh(&m, pal);
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, "/nonexistent-lsys/x.obj", &e) ==
         LSYS_EARG);
  assert(strcmp(e.msg, "cannot open '/nonexistent-lsys/x.obj' for writing: "
                       "No such file or directory") == 0);
  assert(lsys_export_ply(&m, pal, 2, NULL, 0, "/nonexistent-lsys/x.ply", &e) ==
         LSYS_EARG);
  assert(strcmp(e.msg, "cannot open '/nonexistent-lsys/x.ply' for writing: "
                       "No such file or directory") == 0);
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, "/nonexistent-lsys/x.glb", &e) ==
         LSYS_EARG);
  assert(strstr(e.msg, "'/nonexistent-lsys/x.glb'") != NULL);
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, testdir(), &e) == LSYS_EARG);   /* a directory */
  assert(strstr(e.msg, "cannot open '") && strstr(e.msg, "' for writing"));
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, OUT("_x.mtl"), &e) ==
         LSYS_EARG);
  assert(strstr(e.msg, "its own material file") != NULL);
  f = fopen("/dev/full", "wb");
  if (f != NULL) {                              /* a full disk: the error comes late */
    fclose(f);
    assert(lsys_export_ply(&m, pal, 2, NULL, 0, "/dev/full", &e) == LSYS_EARG);
    assert(strcmp(e.msg, "cannot write '/dev/full': No space left on device") == 0);
    assert(lsys_export_glb(&m, pal, 2, NULL, 0, "/dev/full", &e) == LSYS_EARG);
    assert(strcmp(e.msg, "cannot write '/dev/full': No space left on device") == 0);
  }
  m.tri[4] = 12;                                 /* a vertex that does not exist */
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, OUT("_bad.glb"), &e) == LSYS_EARG);
  assert(strstr(e.msg, "triangle 2 refers to vertex 12 of 12") != NULL);
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, OUT("_bad.obj"), &e) == LSYS_EARG);
  assert(lsys_export_ply(&m, pal, 2, NULL, 0, OUT("_bad.ply"), &e) == LSYS_EARG);
  f = fopen(OUT("_bad.glb"), "rb");              /* nothing was created */
  assert(f == NULL);
  lsys_mesh_free(&m);
}

/* ---- textures ---- */

/* The test mesh with textures by triangle: 0 -> 1, 1 -> none, 2 -> 2 (the
** two-sided one), 3 -> 1; material slot 0 then has runs (none: triangle 1)
** and (1: triangle 0), slot 1 runs (1: triangle 3) and (2: triangle 2). */
static void test_textures (void) {
  static uint8_t px1[16] = {255, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 255, 9, 9, 9, 255};
  static uint8_t px2[4] = {10, 20, 30, 255};
  const char *p1 = OUT("_tex1.png"), *p2 = OUT("_tex 2.png");
  lsys_texture t1, t2, nopath;
  const lsys_texture *list[3] = {&t1, &t2, &nopath};
  lsys_mesh m;
  lsys_material pal[2];
  lsys_error e;
  size_t len, len2, blen, blen2;
  unsigned char *file, *file2, *bin, *bin2;
  char *s, *s2, *t, *json, *json2, want[3 * TD_PATH];
  int i;
  lsys_texture_init(&t1); lsys_texture_init(&t2); lsys_texture_init(&nopath);
  t1.rgba = px1; t1.w = 2; t1.h = 2; t1.path = (char *)p1;        /* modulate, with alpha */
  t2.rgba = px2; t2.w = 1; t2.h = 1; t2.path = (char *)p2;        /* decal, linear */
  t2.mode = LSYS_TEX_DECAL; t2.mag_linear = t2.min_linear = 1;
  nopath.rgba = px2; nopath.w = 1; nopath.h = 1;
  assert(lsys_pngio_write(p1, px1, 2, 2, 1, &e) == LSYS_OK);
  assert(lsys_pngio_write(p2, px2, 1, 1, 0, &e) == LSYS_OK);
  testmesh(&m, pal);
  /* textures given, none used: the same files as without */
  assert(lsys_export_obj(&m, pal, 2, NULL, 0, OUT(".obj"), &e) == LSYS_OK);
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, OUT(".glb"), &e) == LSYS_OK);
  s = slurp(OUT(".mtl"), &len);
  assert(lsys_export_obj(&m, pal, 2, list, 3, OUT("_t.obj"), &e) == LSYS_OK);
  s2 = slurp(OUT("_t.mtl"), &len2);
  assert(len == len2 && memcmp(s, s2, len) == 0);
  free(s2);
  json = glbjson(OUT(".glb"), &file, &len, &bin, &blen);
  assert(lsys_export_glb(&m, pal, 2, list, 3, OUT("_t.glb"), &e) == LSYS_OK);
  s2 = slurp(OUT("_t.glb"), &len2);
  assert(len == len2 && memcmp(file, s2, len) == 0);
  free(s2); free(s); free(json); free(file);
  /* textured */
  m.tex[0] = 1; m.tex[6] = 2; m.tex[9] = 1;
  m.tex[1] = 2;                                 /* only a triangle's first vertex counts */
  assert(lsys_export_obj(&m, pal, 2, list, 3, OUT("_t.obj"), &e) == LSYS_OK);
  s = slurp(OUT("_t.mtl"), &len);
  assert(countlines(s, "newmtl ") == 5);
  assert(strstr(s, "newmtl m0\n") < strstr(s, "newmtl m0_t1\n"));
  assert(strstr(s, "newmtl m0_t1\n") < strstr(s, "newmtl m1\n"));
  assert(strstr(s, "newmtl m1\n") < strstr(s, "newmtl m1_t1\n"));
  assert(strstr(s, "newmtl m1_t1\n") < strstr(s, "newmtl m1_t2\n"));
  assert(countlines(s, "map_Kd ") == 3);
  snprintf(want, sizeof want, "illum 1\nmap_Kd %s\n", p1);
  assert(strstr(s, want) != NULL);                                   /* after m0_t1 */
  assert(strstr(s, "newmtl m1_t2\nKa 0.07323896 0.01960665 0\nKd 1 1 1\n") != NULL);   /* decal: white */
  snprintf(want, sizeof want, "illum 0\nmap_Kd %s\n", p2);
  assert(strstr(s, want) != NULL);
  assert(countlines(s, "illum 0") == 1);
  free(s);
  s = slurp(OUT("_t.obj"), &len);
  assert(countlines(s, "usemtl ") == 5 && countlines(s, "f ") == 4);
  assert(countlines(s, "vt ") == 12);
  t = strstr(s, "usemtl m0\nf 4/4/4 5/5/5 6/6/6\nl ");        /* plain: triangle 1, segments */
  assert(t != NULL);
  assert(strstr(s, "usemtl m0_t1\nf 1/1/1 2/2/2 3/3/3\nusemtl m1\nl ") != NULL);
  assert(strstr(s, "usemtl m1_t1\nf 10/10/10 ") != NULL && strstr(s, "usemtl m1_t2\nf 7/7/7 "));
  free(s);
  /* glb: 4 triangle primitives, 2 line primitives, 5 materials, 2 images */
  assert(lsys_export_glb(&m, pal, 2, list, 3, OUT("_t.glb"), &e) == LSYS_OK);
  json = glbjson(OUT("_t.glb"), &file, &len, &bin, &blen);
  assert(count(json, "\"mode\":4") == 4 && count(json, "\"mode\":1") == 2);
  assert(count(json, "\"name\":\"m") == 5);
  assert(strstr(json, "\"extensionsUsed\":[\"KHR_materials_unlit\"]") != NULL);
  assert(strstr(json, "\"name\":\"m0_t1\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                      "[0.033104766,0.3185468,0.010022826,1],"
                      "\"baseColorTexture\":{\"index\":0},") != NULL);
  assert(strstr(json, "\"name\":\"m1_t2\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                      "[1,1,1,1],\"baseColorTexture\":{\"index\":1},") != NULL);
  assert(count(json, "\"alphaMode\":\"MASK\"") == 2);          /* m0_t1, m1_t1 */
  assert(count(json, "KHR_materials_unlit\":{}") == 1);        /* m1_t2 */
  {                                             /* doubleSided: only m1_t2 (triangle 2) */
    char *ds = strstr(json, "\"doubleSided\":true");
    assert(count(json, "doubleSided") == 1 && ds > strstr(json, "\"name\":\"m1_t2\""));
  }
  assert(strstr(json, "\"textures\":[{\"sampler\":0,\"source\":0},"
                      "{\"sampler\":1,\"source\":1}]"));
  assert(strstr(json, "\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728,\"wrapS\":10497,"
                      "\"wrapT\":10497},{\"magFilter\":9729,\"minFilter\":9729,"));
  assert(strstr(json, "\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"},"
                      "{\"bufferView\":4,\"mimeType\":\"image/png\"}]"));
  /* primitives by run: m0 (material 0), m0_t1 (1), m1_t1 (3), m1_t2 (4); lines m0, m1 (2) */
  assert(strstr(json, "\"indices\":3,\"material\":0,"));
  assert(strstr(json, "\"indices\":4,\"material\":1,"));
  assert(strstr(json, "\"indices\":5,\"material\":3,"));
  assert(strstr(json, "\"indices\":6,\"material\":4,"));
  assert(strstr(json, "{\"POSITION\":7},\"material\":0,"));
  assert(strstr(json, "{\"POSITION\":8},\"material\":2,"));
  /* the BIN chunk ends with the two PNG files, each padded to 4 bytes */
  {
    size_t f1, f2, pad1;
    unsigned char *png1 = (unsigned char *)slurp(p1, &f1);
    unsigned char *png2 = (unsigned char *)slurp(p2, &f2);
    pad1 = (f1 + 3) & ~(size_t)3;
    assert(blen == 12 * 32 + 4 * 12 + 3 * 24 + pad1 + ((f2 + 3) & ~(size_t)3));
    assert(memcmp(bin + 504, png1, f1) == 0 && memcmp(bin + 504 + pad1, png2, f2) == 0);
    free(png1); free(png2);
  }
  /* indices by run: triangle 1, 0 | 3, 2 */
  assert(rd32(bin + 384) == 3 && rd32(bin + 384 + 12) == 0 && rd32(bin + 384 + 24) == 9);
  assert(rd32(bin + 384 + 36) == 6);
  free(json); free(file);
  /* a texture index past the list, or of a texture without a file: untextured */
  m.tex[0] = 4; m.tex[6] = 3; m.tex[9] = 0;
  assert(lsys_export_glb(&m, pal, 2, list, 3, OUT("_t.glb"), &e) == LSYS_OK);
  assert(lsys_export_glb(&m, pal, 2, NULL, 0, OUT("_t2.glb"), &e) == LSYS_OK);
  json = glbjson(OUT("_t.glb"), &file, &len, &bin, &blen);
  json2 = glbjson(OUT("_t2.glb"), &file2, &len2, &bin2, &blen2);
  assert(strcmp(json, json2) == 0 && blen == blen2 && memcmp(bin, bin2, blen) == 0);
  free(json); free(file); free(json2); free(file2);
  /* a texture file that went missing or changed: an error naming both files */
  m.tex[0] = 1;
  t1.path = (char *)OUT("_missing.png");
  assert(lsys_export_glb(&m, pal, 2, list, 3, OUT("_t.glb"), &e) == LSYS_EARG);
  snprintf(want, sizeof want, "cannot write '%s': cannot read texture '%s'", OUT("_t.glb"),
           OUT("_missing.png"));
  assert(strstr(e.msg, want));
  t1.path = (char *)OUT(".obj");
  assert(lsys_export_glb(&m, pal, 2, list, 3, OUT("_t.glb"), &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, "is no longer a PNG or SGI image") != NULL);
  /* PLY ignores textures */
  t1.path = (char *)p1;
  assert(lsys_export_ply(&m, pal, 2, list, 3, OUT("_t.ply"), &e) == LSYS_OK);
  assert(lsys_export_ply(&m, pal, 2, NULL, 0, OUT("_t2.ply"), &e) == LSYS_OK);
  s = slurp(OUT("_t.ply"), &len);
  s2 = slurp(OUT("_t2.ply"), &len2);
  assert(len == len2 && memcmp(s, s2, len) == 0);
  free(s); free(s2);
  lsys_mesh_free(&m);
  for (i = 0; i < 2; i++) remove(i ? p2 : p1);
  remove(OUT("_t.obj")); remove(OUT("_t.mtl")); remove(OUT("_t.glb")); remove(OUT("_t2.glb"));
  remove(OUT("_t.ply")); remove(OUT("_t2.ply"));
}

/* ---- allocation failures ---- */

/* Every allocation fails in turn: each call gives LSYS_OK or LSYS_ENOMEM
** with a message, and nothing leaks (valgrind). A third of the triangles
** are textured, another third refer to a missing texture. */
static void test_nomem (void) {
  const char *paths[3] = { OUT("_nomem.obj"), OUT("_nomem.ply"), OUT("_nomem.glb") };
  static uint8_t px[4] = { 1, 2, 3, 4 };
  lsys_texture tx;
  const lsys_texture *list[1] = { &tx };
  lsys_error e0;
  long k;
  int f, done = 0;
  lsys_texture_init(&tx);
  tx.rgba = px; tx.w = tx.h = 1; tx.path = (char *)OUT("_nomem.png");
  assert(lsys_pngio_write(tx.path, px, 1, 1, 1, &e0) == LSYS_OK);
  for (k = 0; !done; k++) {
    lsys_mesh m;
    lsys_material pal[2];
    lsys_error e;
    double p[3] = { 0, 0, 0 }, n[3] = { 0, 0, 1 };
    int st = LSYS_OK, i;
    lsys_mesh_init(&m);
    nalloc = 0;
    failat = k;
    for (i = 0; i < 40 && st == LSYS_OK; i++) {
      st = lsys_mesh_reserve(&m, 3, 1);
      m.curtex = (unsigned)(i % 3);
      if (st == LSYS_OK) {
        lsys_mesh_vertex(&m, p, n, 0, 0, (unsigned)i, i % 2);
        p[0] += 1;
        lsys_mesh_vertex(&m, p, n, 0, 0, (unsigned)i, i % 2);
        p[1] += 1;
        lsys_mesh_vertex(&m, p, n, 0, 0, (unsigned)i, i % 2);
        lsys_mesh_tri(&m, m.nv - 3, m.nv - 2, m.nv - 1);
        st = lsys_mesh_line(&m, p, n, 1, 1, (unsigned)i);
      }
    }
    assert(st == LSYS_OK || st == LSYS_ENOMEM);
    lsys_mesh_material_color(&pal[0], 1, 0, 0);
    lsys_mesh_material_color(&pal[1], 0, 1, 0);
    for (f = 0; f < 3 && st == LSYS_OK; f++) {
      st = f == 0 ? lsys_export_obj(&m, pal, 2, list, 1, paths[f], &e)
         : f == 1 ? lsys_export_ply(&m, pal, 2, list, 1, paths[f], &e)
                  : lsys_export_glb(&m, pal, 2, list, 1, paths[f], &e);
      assert(st == LSYS_OK || (st == LSYS_ENOMEM && strstr(e.msg, "out of memory") &&
                               strstr(e.msg, OUT("_nomem."))));
    }
    done = nalloc <= k;                       /* no allocation failed: all paths are done */
    assert(!done || st == LSYS_OK);
    lsys_mesh_free(&m);
  }
  failat = -1;
  assert(k > 20);
  for (f = 0; f < 3; f++) remove(paths[f]);
  remove(OUT("_nomem.mtl"));
  remove(tx.path);
}

/* ---- timing ---- */

static double now (void) {
  struct timespec ts;
  timespec_get(&ts, TIME_UTC);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A grid of 1M triangles (about 500k vertices, like a turtle's cylinders)
** with 8 materials, and 100k segments. */
static void bench (void) {
  size_t side = 708, i, j;
  lsys_mesh m;
  lsys_material pal[8];
  lsys_error e;
  double t0;
  lsys_mesh_init(&m);
  assert(lsys_mesh_reserve(&m, side * side, 2 * (side - 1) * (side - 1)) == LSYS_OK);
  for (i = 0; i < side; i++)
    for (j = 0; j < side; j++) {
      double a = 0.01 * (double)i, p[3] = { cos(a), 0.013 * (double)j, sin(a) };
      double n[3] = { cos(a), 0, sin(a) };
      lsys_mesh_vertex(&m, p, n, (double)i / (double)side, (double)j / (double)side,
                       (unsigned)(j / 90), 0);
    }
  for (i = 0; i + 1 < side; i++)
    for (j = 0; j + 1 < side; j++) {
      uint32_t a = (uint32_t)(i * side + j);
      lsys_mesh_tri(&m, a, a + 1, a + (uint32_t)side);
      lsys_mesh_tri(&m, a + 1, a + 1 + (uint32_t)side, a + (uint32_t)side);
    }
  for (i = 0; i < 100000; i++) {
    double a[3] = { (double)i, 0, 1.5 }, b[3] = { (double)i, 1, 0.25 };
    assert(lsys_mesh_line(&m, a, b, 1, 1, (unsigned)i) == LSYS_OK);
  }
  for (i = 0; i < 8; i++) lsys_mesh_material_color(&pal[i], 0.1 * (double)i, 0.5, 0.2);
  printf("bench: %zu vertices, %zu triangles, %zu segments\n", m.nv, m.nt, m.nl);
  t0 = now();
  assert(lsys_export_obj(&m, pal, 8, NULL, 0, OUT("_bench.obj"), &e) == LSYS_OK);
  printf("  obj %.3f s\n", now() - t0);
  t0 = now();
  assert(lsys_export_ply(&m, pal, 8, NULL, 0, OUT("_bench.ply"), &e) == LSYS_OK);
  printf("  ply %.3f s\n", now() - t0);
  t0 = now();
  assert(lsys_export_glb(&m, pal, 8, NULL, 0, OUT("_bench.glb"), &e) == LSYS_OK);
  printf("  glb %.3f s\n", now() - t0);
  lsys_mesh_free(&m);
}

int main (int argc, char **argv) {
  if (argc > 1 && strcmp(argv[1], "bench") == 0) {
    bench();
    return 0;
  }
  test_buffers();
  test_color_counts();
  test_obj();
  test_numbers();
  test_ply();
  test_glb();
  test_errors();
  test_textures();
  test_nomem();
  printf("test_mesh: ok\n");
  return 0;
}
