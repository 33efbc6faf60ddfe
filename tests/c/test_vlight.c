/*
** C unit tests of the viewer's light colours (csrc/gl/vlight.h), without a
** window: the leaves found from the records, a leaf in the open at the top
** of the ramp and one under another at its bottom, the face that looks up,
** a vertical leaf at half an open one's light, stems, lines and textures
** keeping their own, the same colours for every number of threads, the
** memory budget, and the frames that get none. The window's side (the L key,
** the legend) is tested from Lua under Xvfb (tests/viewer_spec.lua).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mesh.h"
#include "scene.h"

#ifndef LSYS_NO_RENDER
#include "vlight.h"

/* Appends the square of side 'a' centred at c, in the plane normal to axis
** 'ax' (0 x, 1 y), as two triangles of colour 'col'; 'flip' winds it the
** other way (its normal points down). Returns its first triangle. */
static uint32_t square (lsys_mesh *m, const double c[3], double a, int ax, int flip,
                        unsigned col, int twosided) {
  double p[4][3], n[3] = {0, 0, 0};
  uint32_t v[4], t0 = (uint32_t)m->nt;
  int k;
  assert(lsys_mesh_reserve(m, 4, 2) == LSYS_OK);
  for (k = 0; k < 4; k++) {
    double s = (k == 1 || k == 2) ? a / 2 : -a / 2, u = k >= 2 ? a / 2 : -a / 2;
    memcpy(p[k], c, sizeof p[k]);
    if (ax == 1) { p[k][0] += s; p[k][2] += u; }
    else { p[k][1] += s; p[k][2] += u; }
    v[k] = lsys_mesh_vertex(m, p[k], n, 0, 0, col, twosided);
  }
  if (flip) {
    lsys_mesh_tri(m, v[0], v[1], v[2]);
    lsys_mesh_tri(m, v[0], v[2], v[3]);
  } else {
    lsys_mesh_tri(m, v[0], v[2], v[1]);
    lsys_mesh_tri(m, v[0], v[3], v[2]);
  }
  return t0;
}

/* A record of 'kind' covering triangles t0 .. t0 + n - 1. */
static lsys_trec rec (int kind, uint32_t t0, uint32_t n) {
  lsys_trec r;
  memset(&r, 0, sizeof r);
  r.kind = (uint8_t)kind;
  r.tri0 = t0;
  r.ntri = n;
  return r;
}

/* lsys_vlight_leaves on a scene of the records r[0 .. n). */
static int leavesof (lsys_vframe *f, const lsys_trec *r, size_t n) {
  lsys_scene s;
  size_t k;
  int st;
  lsys_scene_init(&s);
  for (k = 0; k < n; k++) assert(lsys_scene_add_record(&s, &r[k]) == LSYS_OK);
  st = lsys_vlight_leaves(f, &s);
  lsys_scene_free(&s);
  return st;
}

/* The ramp step a vertex of l shows (npal0 the frame's palette size). */
static int step (const lsys_vlight *l, uint32_t v, size_t npal0) {
  return (int)l->col[v] - (int)npal0;
}

static void test_ramp (void) {
  float a[3], b[3], c[3];
  lsys_vlight_ramp(0, a);
  lsys_vlight_ramp(-3, b);
  assert(memcmp(a, b, sizeof a) == 0);           /* clamped */
  assert(fabsf(a[0] - 0.267f) < 1e-6f && fabsf(a[2] - 0.329f) < 1e-6f);
  lsys_vlight_ramp(1, a);
  lsys_vlight_ramp(7, b);
  assert(memcmp(a, b, sizeof a) == 0);
  assert(fabsf(a[0] - 0.993f) < 1e-6f && fabsf(a[1] - 0.906f) < 1e-6f);
  lsys_vlight_ramp(0.5, c);                       /* the middle stop, teal */
  assert(fabsf(c[1] - 0.567f) < 1e-6f);
  printf("ramp: ok\n");
}

static void test_leaves (void) {
  lsys_vframe f;
  lsys_trec r[6];
  memset(&f, 0, sizeof f);
  lsys_scene_init(&f.sc);
  r[0] = rec(LSYS_REC_SEGMENT, 0, 12);            /* a stem: not a leaf */
  r[1] = rec(LSYS_REC_DISC, 12, 8);
  r[2] = rec(LSYS_REC_POLYGON, 20, 2);            /* touches the disc: one range */
  r[3] = rec(LSYS_REC_SPHERE, 22, 40);
  r[4] = rec(LSYS_REC_SURFACE, 62, 30);
  r[5] = rec(LSYS_REC_DISC, 100, 0);              /* nothing drawn */
  assert(leavesof(&f, r, 6) == LSYS_OK);
  assert(f.nleafr == 2);
  assert(f.leafr[0] == 12 && f.leafr[1] == 22 && f.leafr[2] == 62 && f.leafr[3] == 92);
  LSYS_FREE(f.leafr);
  assert(leavesof(&f, r, 1) == LSYS_OK && f.nleafr == 0 && f.leafr == NULL);
  lsys_scene_free(&f.sc);
  printf("leaves: ok\n");
}

/*
** Four leaves and a stem: a big square roof (side 40) at y = 1, a small leaf
** under it at y = 0.9, a leaf in the open far to the side wound face down, a
** vertical leaf in the open, and a one-sided triangle (a stem) in the open.
*/
static void scene (lsys_vframe *f, lsys_trec r[5]) {
  static const double roof[3] = {0, 1, 0}, under[3] = {0, 0.9, 0}, open[3] = {100, 0, 0},
                      side[3] = {-100, 0, 0}, stem[3] = {0, 0, 100};
  static const lsys_material pal[3] = {
    {{0}, {0.1f, 0.2f, 0.3f, 1}, {0}, {0}, 0}, {{0}, {0.2f, 0.6f, 0.2f, 1}, {0}, {0}, 0},
    {{0}, {0.5f, 0.4f, 0.3f, 1}, {0}, {0}, 0}
  };
  double a[3] = {-1, 0, 0}, b[3] = {1, 0, 0};
  memset(f, 0, sizeof *f);
  lsys_scene_init(&f->sc);
  assert(lsys_scene_set_palette(&f->sc, pal, 3) == LSYS_OK);
  r[0] = rec(LSYS_REC_POLYGON, square(&f->sc.mesh, roof, 40, 1, 0, 1, 1), 2);
  r[1] = rec(LSYS_REC_POLYGON, square(&f->sc.mesh, under, 0.2, 1, 0, 4, 1), 2);  /* 4 % 3 */
  r[2] = rec(LSYS_REC_DISC, square(&f->sc.mesh, open, 1, 1, 1, 1, 1), 2);
  r[3] = rec(LSYS_REC_SURFACE, square(&f->sc.mesh, side, 1, 0, 0, 1, 1), 2);
  r[4] = rec(LSYS_REC_SEGMENT, square(&f->sc.mesh, stem, 1, 1, 0, 5, 0), 2);
  f->sc.mesh.tex[0] = 1;                          /* a textured roof */
  f->sc.mesh.tex[16] = 1;                         /* and stem */
  assert(lsys_mesh_line(&f->sc.mesh, a, b, 1, 1, 7) == LSYS_OK);   /* 7 % 3 = 1 */
  assert(leavesof(f, r, 5) == LSYS_OK);
}

static void test_colours (void) {
  lsys_vframe f;
  lsys_trec r[5];
  lsys_vlight l, l1;
  lsys_error e;
  int k, threads[] = {1, 2, 7};
  scene(&f, r);
  assert(lsys_vlight_compute(&l, &f, 0, 1, NULL, &e) == LSYS_OK);
  assert(l.nleaves == 8 && l.msg[0] == '\0');
  assert(l.npal == 3 + LSYS_VLIGHT_BINS);
  for (k = 0; k < 4; k++) {
    assert(step(&l, (uint32_t)k, 3) == LSYS_VLIGHT_BINS - 1);   /* the roof: in the open */
    assert(step(&l, (uint32_t)(4 + k), 3) == 0);                /* under it: full shade */
    assert(step(&l, (uint32_t)(8 + k), 3) == LSYS_VLIGHT_BINS - 1);   /* face down: its
                                                                   other face looks up */
    assert(abs(step(&l, (uint32_t)(12 + k), 3) - 32) <= 2);     /* vertical: about 1/2 */
    assert(l.col[16 + k] == 5 % 3);                             /* the stem keeps its own */
  }
  assert(l.min == 0 && l.max == 1);
  assert(fabs(l.mean - (1600 * 1.0 + 1 + 0.5) / (1600 + 0.04 + 2)) < 0.01);
  {                                               /* the top step is the ramp's top colour */
    float top[3];
    const lsys_material *mt = &l.pal[l.col[0] % l.npal];
    lsys_vlight_ramp(1, top);
    assert(memcmp(top, mt->diffuse, sizeof top) == 0);
    assert(memcmp(&l.pal[0], &f.sc.pal[0], 3 * sizeof l.pal[0]) == 0);
  }
  assert(l.tex != NULL && l.tex[0] == 0 && l.tex[16] == 1);     /* leaves untextured */
  assert(l.lcol != NULL && l.lcol[0] == 1);                     /* the line as before */
  /* the same for every number of threads */
  for (k = 0; k < 3; k++) {
    assert(lsys_vlight_compute(&l1, &f, 0, threads[k], NULL, &e) == LSYS_OK);
    assert(memcmp(l.col, l1.col, f.sc.mesh.nv * sizeof *l.col) == 0);
    assert(l.min == l1.min && l.max == l1.max && l.mean == l1.mean);
    lsys_vlight_free(&l1);
  }
  {                                               /* drawn with them: a borrowed copy */
    lsys_scene sc = f.sc;
    lsys_vlight_apply(&l, &sc);
    assert(sc.mesh.col == l.col && sc.pal == l.pal && sc.npal == l.npal);
    assert(sc.mesh.tex == l.tex && sc.mesh.lcol == l.lcol && sc.mesh.pos == f.sc.mesh.pos);
  }
  {
    char note[96];
    lsys_vlight_note(&l, note, sizeof note);
    assert(strcmp(note, "0.00 - 1.00, mean 1.00") == 0);
    lsys_vlight_note(NULL, note, sizeof note);
    assert(strcmp(note, "computing ...") == 0);
  }
  lsys_vlight_free(&l);
  assert(l.col == NULL && l.pal == NULL);
  LSYS_FREE(f.leafr);
  lsys_scene_free(&f.sc);
  printf("colours: ok\n");
}

static void test_none (void) {
  lsys_vframe f;
  lsys_trec r[5];
  lsys_vlight l;
  lsys_error e;
  lsys_meter mt = {500, 0, 0, NULL};
  char note[96];
  scene(&f, r);
  assert(lsys_vlight_compute(&l, &f, 1, 1, NULL, &e) == LSYS_OK);       /* live */
  assert(l.nleaves == 0 && l.col == NULL && strcmp(l.msg, "not for a growing scene") == 0);
  lsys_vlight_note(&l, note, sizeof note);
  assert(strcmp(note, "not for a growing scene") == 0);
  /* the budget: 500 bytes do not hold the queries (8 leaf triangles, 20 vertices) */
  assert(lsys_vlight_compute(&l, &f, 0, 1, &mt, &e) == LSYS_EMEMORY);
  assert(strcmp(e.msg, "the light colours need 882 bytes, more than max_memory (500 bytes)")
         == 0);
  assert(l.col == NULL && mt.used == 0 && mt.hit);
  mt.limit = 1 << 20;                             /* enough: the meter is given back */
  mt.hit = 0;
  assert(lsys_vlight_compute(&l, &f, 0, 1, &mt, &e) == LSYS_OK && l.nleaves == 8);
  assert(mt.used == 0 && !mt.hit);
  lsys_vlight_free(&l);
  /* no leaves: only the stem's record */
  LSYS_FREE(f.leafr);
  assert(leavesof(&f, r + 4, 1) == LSYS_OK);
  assert(lsys_vlight_compute(&l, &f, 0, 1, NULL, &e) == LSYS_OK);
  assert(l.nleaves == 0 && strcmp(l.msg, "no leaves in this step") == 0);
  /* a population */
  {
    float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    long p = lsys_scene_begin_part(&f.sc);
    assert(p == 0);
    lsys_scene_end_part(&f.sc, (size_t)p);
    assert(lsys_scene_add_instance(&f.sc, 0, id) == LSYS_OK);
    assert(lsys_vlight_compute(&l, &f, 0, 1, NULL, &e) == LSYS_OK);
    assert(l.nleaves == 0 && strcmp(l.msg, "not for a population") == 0);
  }
  lsys_scene_free(&f.sc);
  printf("none: ok\n");
}
#endif

int main (void) {
#ifdef LSYS_NO_RENDER
  printf("built without rendering: nothing to test\n");
#else
  test_ramp();
  test_leaves();
  test_colours();
  test_none();
#endif
  return 0;
}
