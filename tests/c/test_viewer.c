/*
** C unit tests of the viewer's window-free parts: picking (lsys_vpick_find)
** through a known camera, snapshots (lsys_vsnap_new/free, with meshes and
** textures copied), and lsys_mesh_copy / lsys_texture_copy. The window
** itself is tested from Lua under Xvfb (tests/viewer_spec.lua).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 100, 150, 6) == 0);
  /* 5 pixels off it: still within the tolerance; 8 off: nothing */
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 105, 150, 6) == 0);
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 108, 150, 6) == -1);
  /* on the diagonal at (0.3, 0.3): pixel (130, 70); the vertical line is 30 px away */
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 130, 70, 6) == 1);
  /* near the origin both thin lines are close: the nearest on screen wins */
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 99, 103, 6) == 0);
  /* the two thick bars overlap on screen at y = 0.5 (pixel row 50), 10 px wide
  ** each side: the one nearer the eye (z = 1) is hit, inside its width and
  ** beyond the thin-line tolerance */
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 60, 58, 6) == 2);
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 60, 62, 6) == -1);
  /* the diagonal reaches (0.5, 0.5) = pixel (150, 50), where the bars are: a
  ** direct hit on a thick bar beats a thin line passing through */
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 150, 50, 6) == 2);
  /* beyond the near plane (clipped, not drawn): ignored */
  setpick(&picks[0], 0, -1, 10, 0, 0, 10, 0, 10);
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 100, 150, 6) == -1);
  /* a point (sphere) pick: p0 = p1 */
  setpick(&picks[0], -0.5f, -0.5f, 0, -0.5f, -0.5f, 0, 0.05f, 20);
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 52, 152, 6) == 0);
  f.npicks = 0;
  assert(lsys_vpick_find(&f, proj, view, 200, 200, 100, 100, 6) == -1);
  printf("pick: ok\n");
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
#endif

int main (void) {
#ifdef LSYS_NO_VIEWER
  printf("built without the viewer: nothing to test\n");
#else
  test_pick();
  test_snapshot();
#endif
  return 0;
}
