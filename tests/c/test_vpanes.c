/*
** C unit tests of the viewer's panes without a window (vpanes.h): the
** rectangles of a layout, which pane a window point is over and where it
** falls in the pane's image (aspect kept, centred), and images posted and
** taken across the two sides.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef LSYS_NO_RENDER
#include "vpanes.h"

static int near (double a, double b) {
  return fabs(a - b) < 1e-9;
}

/* The sketch window's layout: a pane on the left half, the scene on the right. */
static void halves (lsys_vpanes *p) {
  lsys_vlayout lay;
  memset(&lay, 0, sizeof lay);
  lay.on = 1;
  lay.scene[0] = 0.5f; lay.scene[1] = 0; lay.scene[2] = 1; lay.scene[3] = 1;
  lay.npanes = 1;
  lay.pane[0][0] = 0; lay.pane[0][1] = 0; lay.pane[0][2] = 0.5f; lay.pane[0][3] = 1;
  lsys_vpanes_set_layout(p, &lay);
}

static void test_rects (void) {
  lsys_vpanes p;
  int r[4];
  const float q[4] = {0.25f, 0.5f, 0.75f, 1};
  lsys_vpanes_init(&p);
  lsys_vpanes_rect(q, 800, 600, r);
  assert(r[0] == 200 && r[1] == 300 && r[2] == 400 && r[3] == 300);
  lsys_vpanes_scene(&p, 800, 600, r);                /* no layout: the whole window */
  assert(r[0] == 0 && r[1] == 0 && r[2] == 800 && r[3] == 600);
  halves(&p);
  lsys_vpanes_scene(&p, 800, 600, r);
  assert(r[0] == 0 && r[2] == 800);                  /* not taken yet */
  assert(lsys_vpanes_take(&p) == 1);
  assert(lsys_vpanes_take(&p) == 0);
  lsys_vpanes_scene(&p, 800, 600, r);
  assert(r[0] == 400 && r[1] == 0 && r[2] == 400 && r[3] == 600);
  lsys_vpanes_free(&p);
}

static void test_hits (void) {
  lsys_vpanes p;
  double x, y;
  uint8_t px[200 * 100 * 4];
  lsys_vpanes_init(&p);
  halves(&p);
  lsys_vpanes_take(&p);
  /* no image: the pane's own pixels */
  assert(lsys_vpanes_hit(&p, 800, 600, 10, 20, &x, &y) == 0 && near(x, 10) && near(y, 20));
  /* the scene: relative to its corner */
  assert(lsys_vpanes_hit(&p, 800, 600, 500, 20, &x, &y) == LSYS_VPANE_SCENE);
  assert(near(x, 100) && near(y, 20));
  /* a 200 x 100 image in a 400 x 600 pane: scale 2, 400 x 200, from y = 200 */
  memset(px, 7, sizeof px);
  assert(lsys_vpanes_set_image(&p, 0, px, 200, 100) == LSYS_OK);
  assert(lsys_vpanes_set_image(&p, 4, px, 200, 100) == LSYS_EARG);
  assert(lsys_vpanes_set_image(&p, 0, px, 0, 100) == LSYS_EARG);
  assert(lsys_vpanes_take(&p) == 1);
  assert(p.img[0].w == 200 && p.img[0].h == 100 && p.img[0].fresh && p.img[0].rgba[5] == 7);
  assert(lsys_vpanes_hit(&p, 800, 600, 100, 300, &x, &y) == 0);
  assert(near(x, 50) && near(y, 50));
  assert(lsys_vpanes_hit(&p, 800, 600, 0, 0, &x, &y) == 0);   /* above the image */
  assert(near(x, 0) && near(y, -100));
  lsys_vpanes_map(&p, 0, 800, 600, 600, 600, &x, &y);         /* a drag that left it */
  assert(near(x, 300) && near(y, 200));
  /* nothing: a layout whose panes and scene leave a gap */
  {
    lsys_vlayout lay = p.lay;
    lay.scene[0] = 0.6f;
    lsys_vpanes_set_layout(&p, &lay);
    lsys_vpanes_take(&p);
    assert(lsys_vpanes_hit(&p, 1000, 600, 550, 10, &x, &y) == LSYS_VPANE_NONE);
  }
  lsys_vpanes_set_text(&p, "no stem yet", NULL);
  assert(lsys_vpanes_take(&p) == 1 && strcmp(p.msg, "no stem yet") == 0 && p.help[0] == '\0');
  lsys_vpanes_free(&p);
}

int main (void) {
  test_rects();
  test_hits();
  printf("test_vpanes: ok\n");
  return 0;
}
#else
int main (void) {
  printf("test_vpanes: skipped (built without rendering)\n");
  return 0;
}
#endif
