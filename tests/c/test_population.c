/*
** C unit tests for populations (population.h): prototypes appended as parts
** with their palettes merged and their records moved, instance sizes and
** bounds, the flattened copy (positions, normals under a non-uniform scale,
** the memory budget), the split of a transform into translation, rotation
** and scale, room for the instances within the memory budget, and every
** allocation failing in turn.
**
** The core files are compiled in with counting allocators (talloc.h).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "mesh.c"
#include "scene.c"
#include "population.c"

#define NEAR(a, b) (fabs((double)(a) - (double)(b)) < 1e-5)

/* A plant: a triangle of colour 'col' in the plane z = 0 with normals +z,
** a line from (0,0,0) to (0,2,0), two records (the second the first's
** child, with a stiffness) and a palette of 'npal' grey levels. */
static void plant (lsys_scene *s, unsigned col, size_t npal, float shade) {
  static const double p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, n[3] = {0, 0, 1};
  static const double a[3] = {0, 0, 0}, b[3] = {0, 2, 0}, k[3] = {1, 2, 3};
  lsys_material pal[4];
  lsys_trec r;
  uint32_t st;
  size_t i;
  lsys_scene_init(s);
  for (i = 0; i < npal; i++) lsys_mesh_material_color(&pal[i], shade * (float)i, 0.5, 0.5);
  assert(lsys_scene_set_palette(s, pal, npal) == LSYS_OK);
  assert(lsys_mesh_reserve(&s->mesh, 3, 1) == LSYS_OK);
  for (i = 0; i < 3; i++) lsys_mesh_vertex(&s->mesh, p[i], n, 0, 0, col, 0);
  s->mesh.tex[2] = 1;
  s->ntex = 1;                 /* texture 1 (not looked at here) */
  lsys_mesh_tri(&s->mesh, 0, 1, 2);
  assert(lsys_mesh_line(&s->mesh, a, b, 2, 1, col + 1) == LSYS_OK);
  memset(&r, 0, sizeof r);
  r.parent = LSYS_NOREC; r.stiff = LSYS_NOREC; r.ntri = 1;
  assert(lsys_scene_add_record(s, &r) == LSYS_OK);
  assert(lsys_scene_add_stiffness(s, k, &st) == LSYS_OK);
  r.parent = 0; r.stiff = st; r.module = 7; r.ntri = 0; r.p1[1] = 2;
  assert(lsys_scene_add_record(s, &r) == LSYS_OK);
}

/* The column-major T R S of a translation t, a rotation by 'deg' about +y and
** scales sc. */
static void trs (float m[16], const double t[3], double deg, const double sc[3]) {
  double c = cos(deg * 3.14159265358979 / 180), s = sin(deg * 3.14159265358979 / 180);
  double r[9] = {c, 0, -s, 0, 1, 0, s, 0, c};   /* columns */
  int i, j;
  memset(m, 0, 16 * sizeof *m);
  for (j = 0; j < 3; j++)
    for (i = 0; i < 3; i++) m[4 * j + i] = (float)(r[3 * j + i] * sc[j]);
  for (i = 0; i < 3; i++) m[12 + i] = (float)t[i];
  m[15] = 1;
}

static void build (lsys_scene *pop) {
  lsys_scene a, b;
  const uint16_t texmap[2] = {0, 5};
  size_t k;
  lsys_scene_init(pop);
  plant(&a, 1, 2, 0.25f);
  plant(&b, 3, 4, 0.25f);       /* a's two and two more: not all in dst, appended */
  assert(lsys_population_add(pop, &a, texmap, 1, &k) == LSYS_OK && k == 0);
  assert(lsys_population_add(pop, &b, NULL, 1, &k) == LSYS_OK && k == 1);
  assert(lsys_population_add(pop, &a, texmap, 0, &k) == LSYS_OK && k == 2);
  lsys_scene_free(&a);
  lsys_scene_free(&b);
}

static void prototypes (void) {
  lsys_scene pop;
  build(&pop);
  /* palettes: a's 2 at 0, b's 4 at 2, a's again found at 0 */
  assert(pop.npal == 6);
  assert(pop.nparts == 3 && pop.mesh.nv == 9 && pop.mesh.nt == 3 && pop.mesh.nl == 3);
  assert(pop.parts[1].v0 == 3 && pop.parts[1].nv == 3 && pop.parts[1].t0 == 1);
  assert(pop.parts[1].l0 == 1 && pop.parts[1].r0 == 2 && pop.parts[1].nr == 2);
  assert(pop.parts[2].nr == 0 && pop.nrec == 4 && pop.nstiff == 2);
  /* colours: a's 1 of 2 -> 0 + 1; b's 3 of 4 -> 2 + 3; lines one more, wrapped */
  assert(pop.mesh.col[0] == 1 && pop.mesh.col[3] == 5 && pop.mesh.col[6] == 1);
  assert(pop.mesh.lcol[0] == 0 && pop.mesh.lcol[1] == 2 && pop.mesh.lcol[2] == 0);
  /* textures through the map, or kept */
  assert(pop.mesh.tex[2] == 5 && pop.mesh.tex[5] == 1 && pop.mesh.tex[8] == 5);
  /* triangles, records moved */
  assert(pop.mesh.tri[3] == 3 && pop.mesh.tri[8] == 8);
  {
    lsys_trec r2, r3;
    lsys_scene_record(&pop, 2, &r2);
    lsys_scene_record(&pop, 3, &r3);
    assert(r3.parent == 2 && r3.stiff == 1 && r2.tri0 == 1 && r2.ntri == 1);
    assert(r3.module == 7 && r2.parent == LSYS_NOREC && r3.p1[1] == 2.0f);
  }
  assert(lsys_scene_part_of_record(&pop, 3) == 1);
  lsys_scene_free(&pop);
}

static void palettes (void) {
  lsys_scene pop, a, b;
  size_t k;
  lsys_scene_init(&pop);
  plant(&a, 0, 3, 0.25f);
  plant(&b, 0, 2, 0.25f);      /* the first two of a's: found inside it */
  assert(lsys_population_add(&pop, &a, NULL, 1, &k) == LSYS_OK);
  assert(lsys_population_add(&pop, &b, NULL, 1, &k) == LSYS_OK);
  assert(pop.npal == 3);
  lsys_scene_free(&b);
  lsys_scene_init(&b);         /* no palette: one grey material */
  assert(lsys_population_add(&pop, &b, NULL, 1, &k) == LSYS_OK && pop.npal == 4);
  lsys_scene_free(&a);
  lsys_scene_free(&b);
  lsys_scene_free(&pop);
}

static void instances (void) {
  lsys_scene pop, flat;
  const double t0[3] = {10, 0, 0}, t1[3] = {0, 0, -5}, one[3] = {1, 1, 1}, s2[3] = {2, 1, 3};
  double lo[3], hi[3];
  size_t nv, nt, nl;
  float m[16];
  build(&pop);
  lsys_population_size(&pop, &nv, &nt, &nl);
  assert(nv == 9 && nt == 3 && nl == 3);          /* no instances: the mesh */
  trs(m, t0, 0, one);
  assert(lsys_scene_add_instance(&pop, 0, m) == LSYS_OK);
  trs(m, t1, 90, s2);
  assert(lsys_scene_add_instance(&pop, 0, m) == LSYS_OK);
  assert(lsys_scene_add_instance(&pop, 1, m) == LSYS_OK);
  assert(lsys_scene_add_instance(&pop, 3, m) == LSYS_EARG);
  lsys_population_size(&pop, &nv, &nt, &nl);
  assert(nv == 9 && nt == 3 && nl == 3);
  assert(lsys_population_flatbytes(&pop) == 9 * VBYTES + 3 * TBYTES + 3 * LBYTES);
  /* bounds: (10..11, 0..2, 0) and, turned 90 degrees about y with x scaled by 2,
  ** x -> -z: z from -5 - 2 to -5; y up to 2 (the line) */
  assert(lsys_scene_bounds(&pop, lo, hi));
  assert(NEAR(lo[0], 0) && NEAR(hi[0], 11) && NEAR(lo[1], 0) && NEAR(hi[1], 2));
  assert(NEAR(lo[2], -7) && NEAR(hi[2], 0));
  assert(lsys_scene_bytes(&pop) >= 9 * VBYTES + 3 * sizeof(lsys_instance));
  /* the flattened copy */
  lsys_scene_init(&flat);
  assert(lsys_population_flatten(&flat, &pop, NULL) == LSYS_OK);
  assert(flat.mesh.nv == 9 && flat.mesh.nt == 3 && flat.mesh.nl == 3 && flat.nparts == 0);
  assert(flat.ninst == 0 && flat.nrec == 0 && flat.npal == pop.npal);
  assert(NEAR(flat.mesh.pos[3], 11) && NEAR(flat.mesh.pos[3 * 4 + 2], -7));
  assert(flat.mesh.tri[3] == 3 && flat.mesh.tri[6] == 6 && flat.mesh.col[6] == 5);
  /* the normal +z turned to +x by the rotation, unchanged in length by the scale */
  assert(NEAR(flat.mesh.nrm[3 * 3], 1) && NEAR(flat.mesh.nrm[3 * 3 + 2], 0));
  assert(NEAR(flat.mesh.lpos[6 + 4], 2) && NEAR(flat.mesh.lwidth[2], 2));
  {
    double l2[3], h2[3];
    int k;
    assert(lsys_mesh_bounds(&flat.mesh, l2, h2));
    for (k = 0; k < 3; k++) assert(NEAR(l2[k], lo[k]) && NEAR(h2[k], hi[k]));
  }
  lsys_scene_free(&flat);
  /* the budget, checked before anything is allocated */
  {
    lsys_meter mt = {100, 0, 0, NULL};
    long before = nlive;
    lsys_scene_init(&flat);
    assert(lsys_population_flatten(&flat, &pop, &mt) == LSYS_EMEMORY);
    assert(nlive == before && flat.mesh.nv == 0);
  }
  lsys_scene_free(&pop);
}

/* A non-uniform scale keeps normals perpendicular to the surface: a slanted
** triangle's flattened normal is perpendicular to its flattened edges. */
static void normals (void) {
  static const double p[3][3] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 0}};
  static const double n[3] = {-0.70710678, 0, 0.70710678};
  const double t[3] = {0, 0, 0}, sc[3] = {3, 1, 0.5};
  lsys_scene a, pop, flat;
  float m[16];
  size_t k;
  int i;
  lsys_scene_init(&a);
  assert(lsys_mesh_reserve(&a.mesh, 3, 1) == LSYS_OK);
  for (i = 0; i < 3; i++) lsys_mesh_vertex(&a.mesh, p[i], n, 0, 0, 0, 0);
  lsys_mesh_tri(&a.mesh, 0, 1, 2);
  lsys_scene_init(&pop);
  assert(lsys_population_add(&pop, &a, NULL, 1, &k) == LSYS_OK);
  trs(m, t, 30, sc);
  assert(lsys_scene_add_instance(&pop, 0, m) == LSYS_OK);
  lsys_scene_init(&flat);
  assert(lsys_population_flatten(&flat, &pop, NULL) == LSYS_OK);
  for (i = 1; i < 3; i++) {
    const float *P = flat.mesh.pos, *N = flat.mesh.nrm;
    double e[3] = {P[3 * i] - P[0], P[3 * i + 1] - P[1], P[3 * i + 2] - P[2]};
    assert(fabs(e[0] * N[0] + e[1] * N[1] + e[2] * N[2]) < 1e-5);
  }
  assert(NEAR(flat.mesh.nrm[0] * flat.mesh.nrm[0] + flat.mesh.nrm[1] * flat.mesh.nrm[1] +
              flat.mesh.nrm[2] * flat.mesh.nrm[2], 1));
  lsys_scene_free(&a);
  lsys_scene_free(&pop);
  lsys_scene_free(&flat);
}

static void split (void) {
  const double t[3] = {1, 2, 3}, sc[3] = {2, 0.5, 4}, one[3] = {1, 1, 1};
  float m[16], T[3], Q[4], S[3];
  trs(m, t, 90, sc);
  assert(lsys_population_trs(m, T, Q, S));
  assert(NEAR(T[0], 1) && NEAR(T[1], 2) && NEAR(T[2], 3));
  assert(NEAR(S[0], 2) && NEAR(S[1], 0.5) && NEAR(S[2], 4));
  /* 90 degrees about +y: (0, sin 45, 0, cos 45) */
  assert(NEAR(Q[0], 0) && NEAR(Q[1], sqrt(0.5)) && NEAR(Q[2], 0) && NEAR(Q[3], sqrt(0.5)));
  trs(m, t, 200, one);         /* w >= 0 always */
  assert(lsys_population_trs(m, T, Q, S) && Q[3] >= 0);
  assert(NEAR(Q[1], -sin(100 * 3.14159265358979 / 180)));
  trs(m, t, 0, one);
  assert(lsys_population_trs(m, T, Q, S) && NEAR(Q[3], 1));
  m[4] = 0.5f;                 /* a shear */
  assert(!lsys_population_trs(m, T, Q, S));
  trs(m, t, 0, one);
  m[0] = -1;                   /* a mirror */
  assert(!lsys_population_trs(m, T, Q, S));
  trs(m, t, 0, one);
  m[5] = 0;                    /* a zero scale */
  assert(!lsys_population_trs(m, T, Q, S));
  trs(m, t, 0, one);
  m[3] = 1;                    /* projective */
  assert(!lsys_population_trs(m, T, Q, S));
}

/* Every allocation of adding prototypes and flattening fails in turn: an
** error, nothing leaked, the population as it was. */
static void nomem (void) {
  long k;
  for (k = 0; k < 40; k++) {
    lsys_scene a, pop, flat;
    const double t[3] = {1, 0, 0}, one[3] = {1, 1, 1};
    float m[16];
    size_t part;
    int st;
    plant(&a, 1, 2, 0.25f);
    lsys_scene_init(&pop);
    lsys_scene_init(&flat);
    trs(m, t, 0, one);
    failat = nalloc + k;
    st = lsys_population_add(&pop, &a, NULL, 1, &part);
    if (st == LSYS_OK) st = lsys_scene_add_instance(&pop, 0, m);
    if (st == LSYS_OK) st = lsys_population_flatten(&flat, &pop, NULL);
    failat = -1;
    assert(st == LSYS_OK || st == LSYS_ENOMEM);
    if (st != LSYS_OK) assert(flat.mesh.nv == 0);
    if (pop.nparts == 1) assert(pop.mesh.nv == 3 && pop.nrec == 2);
    else assert(pop.mesh.nv == 0);
    lsys_scene_free(&a);
    lsys_scene_free(&pop);
    lsys_scene_free(&flat);
    assert(nlive == 0);
  }
}

/* Room for n instances, exactly, within the meter (a population
** counts its instances before placing them). */
static void reserve (void) {
  lsys_scene pop;
  lsys_meter mt = {0, 0, 0, NULL};
  const double t[3] = {0, 0, 0}, one[3] = {1, 1, 1};
  float m[16];
  size_t k;
  lsys_scene_init(&pop);
  mt.limit = 1000 * sizeof(lsys_instance);
  assert(lsys_population_reserve(&pop, 1001, &mt) == LSYS_EMEMORY && mt.hit);
  assert(pop.instcap == 0 && pop.inst == NULL && mt.used == 0);
  mt.hit = 0;
  assert(lsys_population_reserve(&pop, 1000, &mt) == LSYS_OK && !mt.hit);
  assert(pop.instcap == 1000 && mt.used == mt.limit);
  assert(lsys_population_reserve(&pop, 10, &mt) == LSYS_OK && pop.instcap == 1000);
  pop.nparts = 1;                        /* placing them grows nothing */
  trs(m, t, 0, one);
  for (k = 0; k < 1000; k++) assert(lsys_scene_add_instance(&pop, 0, m) == LSYS_OK);
  assert(pop.instcap == 1000 && pop.ninst == 1000);
  pop.nparts = 0;
  failat = nalloc;                       /* an allocation failure leaves it as it was */
  assert(lsys_population_reserve(&pop, 2000, NULL) == LSYS_ENOMEM);
  failat = -1;
  assert(pop.instcap == 1000);
  lsys_scene_free(&pop);
  assert(nlive == 0);
}

int main (void) {
  prototypes();
  palettes();
  instances();
  normals();
  split();
  reserve();
  nomem();
  printf("test_population: ok\n");
  return 0;
}
