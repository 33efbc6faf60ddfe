/*
** C unit tests of the viewer's window-free parts: picking (lsys_viewcam_pick_find)
** through a known camera, snapshots (lsys_vsnap_new/free, with meshes and
** textures copied), lsys_mesh_copy / lsys_texture_copy, the status line,
** and live frames (a grown scene patched into a frame, lsys_vlive). The window
** itself is tested from Lua under Xvfb (tests/viewer_spec.lua).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "mesh.h"
#include "texture.h"
#include "turtle.h"

#ifndef LSYS_NO_VIEWER
#include "viewer.h"

static void setpick (lsys_vpick *p, float x0, float y0, float z0, float x1, float y1,
                     float z1, float r, uint32_t module) {
  p->p0[0] = x0; p->p0[1] = y0; p->p0[2] = z0;
  p->p1[0] = x1; p->p1[1] = y1; p->p1[2] = z1;
  p->radius = r;
  p->module = module;
  p->kind = LSYS_REC_SEGMENT;
}

/* A parallel camera looking down -z at [-1, 1]^2 in a 200 x 200 window:
** world (x, y) is at pixel (100 + 100 x, 100 - 100 y). */
static void camera (double proj[16], double view[16]) {
  memset(proj, 0, 16 * sizeof *proj);
  memset(view, 0, 16 * sizeof *view);
  view[0] = view[5] = view[10] = view[15] = 1;
  view[14] = -5;                          /* eye at z = 5 */
  proj[0] = proj[5] = 1;
  proj[10] = -0.2;                        /* depth: z in [-10, 0] eye space */
  proj[14] = -1;
  proj[15] = 1;
}

static void test_pick (void) {
  lsys_vpick picks[4];
  lsys_vframe f;
  double proj[16], view[16];
  memset(&f, 0, sizeof f);
  f.picks = picks;
  f.npicks = 4;
  camera(proj, view);
  setpick(&picks[0], 0, -1, 0, 0, 0, 0, 0, 10);          /* vertical line x = 0 */
  setpick(&picks[1], 0, 0, 0, 0.5f, 0.5f, 0, 0, 11);     /* diagonal from the origin */
  setpick(&picks[2], -0.5f, 0.5f, 1, 0.5f, 0.5f, 1, 0.1f, 12);   /* thick, in front */
  setpick(&picks[3], -0.5f, 0.5f, -1, 0.5f, 0.5f, -1, 0.1f, 13); /* same, behind */
  /* on the vertical line at y = -0.5: pixel (100, 150) */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 100, 150, 6, NULL) == 0);
  /* 5 pixels off it: still within the tolerance; 8 off: nothing */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 105, 150, 6, NULL) == 0);
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 108, 150, 6, NULL) == -1);
  /* on the diagonal at (0.3, 0.3): pixel (130, 70); the vertical line is 30 px away */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 130, 70, 6, NULL) == 1);
  /* near the origin both thin lines are close: the nearest on screen wins */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 99, 103, 6, NULL) == 0);
  /* the two thick bars overlap on screen at y = 0.5 (pixel row 50), 10 px wide
  ** each side: the one nearer the eye (z = 1) is hit, inside its width and
  ** beyond the thin-line tolerance */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 60, 58, 6, NULL) == 2);
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 60, 62, 6, NULL) == -1);
  /* the diagonal reaches (0.5, 0.5) = pixel (150, 50), where the bars are: a
  ** direct hit on a thick bar beats a thin line passing through */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 150, 50, 6, NULL) == 2);
  /* beyond the near plane (clipped, not drawn): ignored */
  setpick(&picks[0], 0, -1, 10, 0, 0, 10, 0, 10);
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 100, 150, 6, NULL) == -1);
  /* a point (sphere) pick: p0 = p1 */
  setpick(&picks[0], -0.5f, -0.5f, 0, -0.5f, -0.5f, 0, 0.05f, 20);
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 52, 152, 6, NULL) == 0);
  f.npicks = 0;
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 100, 100, 6, NULL) == -1);
  printf("pick: ok\n");
}

/* A population: two parts (picks 0-1 and 2), three instances; each pick is
** tried under its instance's transform and the instance comes back. */
static void test_pick_population (void) {
  lsys_vpick picks[3];
  lsys_part parts[2];
  lsys_instance inst[3];
  size_t partpicks[3] = {0, 2, 3};
  lsys_vframe f;
  lsys_vevent ev;
  double proj[16], view[16];
  long plant;
  int i;
  memset(&f, 0, sizeof f);
  memset(parts, 0, sizeof parts);
  memset(inst, 0, sizeof inst);
  f.picks = picks;
  f.npicks = 3;
  f.partpicks = partpicks;
  f.sc.parts = parts;
  f.sc.nparts = 2;
  f.sc.inst = inst;
  f.sc.ninst = 3;
  camera(proj, view);
  setpick(&picks[0], 0, 0, 0, 0, 0.2f, 0, 0, 1);        /* part 0: a short vertical stick */
  setpick(&picks[1], 0, 0, 0, 0.2f, 0, 0, 0, 2);        /* and a horizontal one */
  setpick(&picks[2], 0, 0, 0, 0, 0.2f, 0, 0.01f, 3);   /* part 1: a thick stick */
  for (i = 0; i < 3; i++) inst[i].m[0] = inst[i].m[5] = inst[i].m[10] = inst[i].m[15] = 1;
  inst[0].part = 0; inst[0].m[12] = -0.5f;              /* at x = -0.5 */
  inst[1].part = 0; inst[1].m[12] = 0.5f;               /* at x = 0.5, scaled 2 */
  inst[1].m[0] = inst[1].m[5] = inst[1].m[10] = 2;
  inst[2].part = 1; inst[2].m[13] = -0.5f;              /* at y = -0.5 */
  /* instance 0's vertical stick: x = -0.5, y 0..0.2 -> pixel (50, 90) */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 50, 90, 3, &plant) == 0 && plant == 0);
  /* instance 1's vertical stick, twice as long: x = 0.5, y 0..0.4 -> (150, 65) */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 150, 65, 3, &plant) == 0 && plant == 1);
  /* its horizontal one: y = 0, x 0.5..0.9 -> (180, 100) */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 180, 100, 3, &plant) == 1 && plant == 1);
  /* instance 2 (part 1): x = 0, y -0.5..-0.3 -> (100, 140) */
  memset(&ev, 0, sizeof ev);
  assert(lsys_viewcam_pick_event(&f, proj, view, 200, 200, 100, 140, 3, &ev) == 1);
  assert(ev.module == 3 && ev.plant == 3 && ev.kind == LSYS_REC_SEGMENT);
  /* nothing there: the prototypes themselves (at the origin) are not drawn */
  assert(lsys_viewcam_pick_find(&f, proj, view, 200, 200, 100, 90, 3, &plant) == -1 && plant == -1);
  assert(lsys_viewcam_pick_event(&f, proj, view, 200, 200, 100, 90, 3, &ev) == 0);
  printf("pick in a population: ok\n");
}

static void test_snapshot (void) {
  lsys_vsnap *s = lsys_vsnap_new(3);
  lsys_mesh m;
  lsys_texture t;
  double a[3] = {0, 0, 0}, b[3] = {1, 2, 3};
  assert(s != NULL && s->nframes == 3 && s->rate == 2);
  assert(s->frames[0].step == -1 && s->frames[2].sc.cam.zoom == 1);
  assert(s->frames[2].sc.npal == 0 && s->frames[2].sc.nrec == 0);   /* an empty scene */
  lsys_mesh_init(&m);
  assert(lsys_mesh_reserve(&m, 3, 1) == LSYS_OK);
  {
    double n[3] = {0, 0, 1}, p[3] = {0, 1, 0};
    assert(lsys_mesh_vertex(&m, a, n, 0, 0, 1, 0) == 0);
    assert(lsys_mesh_vertex(&m, b, n, 0, 0, 2, 0) == 1);
    assert(lsys_mesh_vertex(&m, p, n, 0, 0, 3, 1) == 2);
    lsys_mesh_tri(&m, 0, 1, 2);
  }
  assert(lsys_mesh_line(&m, a, b, 1, 2, 4) == LSYS_OK);
  assert(lsys_mesh_copy(&s->frames[1].sc.mesh, &m) == LSYS_OK);
  assert(s->frames[1].sc.mesh.nv == 3 && s->frames[1].sc.mesh.nt == 1 &&
         s->frames[1].sc.mesh.nl == 1);
  assert(memcmp(s->frames[1].sc.mesh.pos, m.pos, 9 * sizeof(float)) == 0);
  assert(s->frames[1].sc.mesh.col[2] == 3 && s->frames[1].sc.mesh.lcol[0] == 4);
  assert(s->frames[1].sc.mesh.lwidth[1] == 2 && s->frames[1].sc.mesh.tri[2] == 2);
  lsys_mesh_free(&m);
  assert(lsys_mesh_copy(&s->frames[2].sc.mesh, &m) == LSYS_OK);   /* empty */
  assert(s->frames[2].sc.mesh.nv == 0 && s->frames[2].sc.mesh.pos == NULL);
  lsys_texture_init(&t);
  t.w = 2;
  t.h = 1;
  t.rgba = (uint8_t *)malloc(8);
  t.path = (char *)malloc(6);
  memcpy(t.rgba, "\1\2\3\4\5\6\7\10", 8);
  memcpy(t.path, "a.png", 6);
  t.mode = LSYS_TEX_DECAL;
  assert(lsys_vsnap_textures(s, 1) == LSYS_OK && s->ntex == 1 && s->texp[0] == &s->tex[0]);
  assert(lsys_texture_copy(&s->tex[0], &t) == LSYS_OK);
  lsys_texture_free(&t);
  assert(s->tex[0].w == 2 && s->tex[0].rgba[7] == 8 && strcmp(s->tex[0].path, "a.png") == 0);
  assert(s->tex[0].mode == LSYS_TEX_DECAL);
  lsys_vsnap_free(s);
  lsys_vsnap_free(NULL);
  printf("snapshot: ok\n");
}

/* Frame f holds what scene sc holds: every vertex attribute, triangle, line
** and the palette. */
static void same (const lsys_vframe *f, const lsys_scene *sc) {
  const lsys_mesh *a = &f->sc.mesh, *b = &sc->mesh;
  assert(a->nv == b->nv && a->nt == b->nt && a->nl == b->nl);
  assert(b->nv > 0 && memcmp(a->pos, b->pos, 3 * b->nv * sizeof(float)) == 0);
  assert(memcmp(a->nrm, b->nrm, 3 * b->nv * sizeof(float)) == 0);
  assert(memcmp(a->uv, b->uv, 2 * b->nv * sizeof(float)) == 0);
  assert(memcmp(a->col, b->col, b->nv * sizeof(uint16_t)) == 0);
  assert(memcmp(a->twosided, b->twosided, b->nv) == 0);
  assert(memcmp(a->tex, b->tex, b->nv * sizeof(uint16_t)) == 0);
  assert(memcmp(a->tri, b->tri, 3 * b->nt * sizeof(uint32_t)) == 0);
  assert(f->sc.npal == sc->npal && memcmp(f->sc.pal, sc->pal, sc->npal * sizeof *sc->pal) == 0);
}

/* A plant grown tick by tick (lsys_limbs): each tick's changed ranges patched
** into the stage, taken into a frame every tick or every third; the frame
** always ends equal to the scene, and the status line tells the tick. */
static void test_live (void) {
  lsys_scene sc;
  lsys_limbs g;
  lsys_vlive l;
  lsys_vsnap *s = lsys_vsnap_new(1);
  lsys_vframe *f = &s->frames[0];
  size_t r[2 * LSYS_SCENE_NDIRTY], n, moved = 0;
  double pos[3] = {0, 0, 0};
  char note[64], line[256];
  int32_t p, id;
  int t, every;
  lsys_limbspec spec;
  for (every = 1; every <= 3; every += 2) {
    lsys_scene_init(&sc);
    lsys_grow_init(&g, &sc, 6);
    lsys_vlive_init(&l);
    assert(lsys_vlive_patch(&l, &sc, NULL, 0, 0, 0, NULL) == LSYS_EARG);   /* not on */
    lsys_vlive_reset(&l, 1);
    lsys_mesh_free(&f->sc.mesh);
    lsys_mesh_init(&f->sc.mesh);
    assert(lsys_grow_plant(&g, pos, &p) == LSYS_OK);
    memset(&spec, 0, sizeof spec);
    spec.parent = -1; spec.plant = p; spec.at = 1; spec.axis[2] = 1;
    spec.length = 1; spec.radius = 0.1;
    spec.rgb[1] = 0.5f;
    assert(lsys_grow_add(&g, &spec, &id) == LSYS_OK);
    assert(lsys_grow_update(&g) == LSYS_OK);
    for (t = 1; t <= 12; t++) {
      size_t i, n0 = g.n;
      assert(lsys_grow_begin(&g) == LSYS_OK);
      for (i = 0; i < n0; i++) {
        if (!lsys_grow_alive(&g, (int32_t)i)) continue;
        if (g.len[i] < 2) assert(lsys_grow_set_length(&g, (int32_t)i, g.len[i] * 1.1) == 0);
        if (g.age[i] == 2 && g.first[i] < 0 && g.n < 300) {   /* two children */
          spec.parent = (int32_t)i; spec.angle = 30; spec.length = 0.5;
          assert(lsys_grow_add(&g, &spec, &id) == LSYS_OK);
          spec.angle = -30;
          assert(lsys_grow_add(&g, &spec, &id) == LSYS_OK);
        }
        if (t == 8 && g.level[i] == 3) {
          float c[3] = {0.5f, 0.3f, 0.1f};
          assert(lsys_grow_set_color(&g, (int32_t)i, c) == LSYS_OK);
        }
      }
      if (t == 10) assert(lsys_grow_add_leaves(&g, 3, 4, 0.3, spec.rgb) == LSYS_OK);
      if (t == 11) assert(lsys_grow_remove(&g, 2) == LSYS_OK);
      assert(lsys_grow_end(&g) == LSYS_OK);
      n = lsys_scene_take_ranges(&sc, r);
      for (i = 0; i < n; i++) moved += r[2 * i + 1] - r[2 * i];
      assert(lsys_vlive_patch(&l, &sc, r, n, t, g.nalive, t % 2 ? "growing" : NULL) == LSYS_OK);
      if (t % every == 0) {
        assert(lsys_vlive_take(&l, f, note) == 1);
        same(f, &sc);
        assert(lsys_vlive_take(&l, f, note) == 0);          /* nothing new */
        assert(f->step == t && f->nmodules == g.nalive);
        assert(strcmp(note, t % 2 ? "growing" : "") == 0);
      }
    }
    same(f, &sc);
    assert(g.nalive >= 10 && g.nl == 4 && moved > sc.mesh.nv);
    s->live = 1;
    lsys_vsnap_status(s, 0, 59.6, 0, 1, "paused", line, sizeof line);
    assert(strncmp(line, "tick 12  ", 9) == 0 && strstr(line, "limbs  ") != NULL);
    assert(strstr(line, "60 fps  paused  wireframe") != NULL);
    sc.mesh.nv--;                                           /* shrank: not a later state */
    assert(lsys_vlive_patch(&l, &sc, NULL, 0, 13, 0, NULL) == LSYS_EARG);
    sc.mesh.nv++;
    lsys_vlive_reset(&l, 1);                                /* a new post: all again */
    lsys_mesh_free(&f->sc.mesh);
    lsys_mesh_init(&f->sc.mesh);
    assert(lsys_vlive_patch(&l, &sc, NULL, 0, 13, 1, NULL) == LSYS_OK);
    assert(lsys_vlive_take(&l, f, note) == 1);
    same(f, &sc);
    lsys_vlive_free(&l);
    lsys_grow_free(&g);
    lsys_scene_free(&sc);
  }
  s->live = 0;
  lsys_mesh_clear(&f->sc.mesh);
  s->frames[0].step = 4;
  s->frames[0].nmodules = 1234567;
  lsys_vsnap_status(s, 0, 30, 1, 0, "", line, sizeof line);
  assert(strcmp(line, "step 4  1 234 567 modules  0 triangles  0 lines  30 fps  playing") == 0);
  lsys_vsnap_free(s);
  printf("live: ok\n");
}
#endif

int main (void) {
#ifdef LSYS_NO_VIEWER
  printf("built without the viewer: nothing to test\n");
#else
  test_pick();
  test_pick_population();
  test_snapshot();
  test_live();
#endif
  return 0;
}
