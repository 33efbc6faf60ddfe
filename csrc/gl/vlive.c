/*
** Live frames (viewer.h, lsys_viewer_patch): the stage between a growing
** scene on the caller's thread and the frame the viewer draws. Plain memory,
** no window, no locking (the viewer holds its mutex around these): tested on
** its own (tests/c/test_viewer.c).
*/
#include <stdio.h>
#include <string.h>

#include "viewer.h"

void lsys_vlive_init (lsys_vlive *l) {
  memset(l, 0, sizeof *l);
  lsys_scene_init(&l->stage);
}

void lsys_vlive_free (lsys_vlive *l) {
  lsys_scene_free(&l->stage);
  lsys_vlive_init(l);
}

void lsys_vlive_reset (lsys_vlive *l, int on) {
  lsys_mesh_clear(&l->stage.mesh);
  l->on = on;
  l->npend = 0;
  l->chg = l->palchg = on;
  l->step = 0;
  l->count = 0;
  l->note[0] = '\0';
}

int lsys_vlive_patch (lsys_vlive *l, const lsys_scene *s, const size_t *r, size_t n,
                      int step, size_t count, const char *note) {
  lsys_scene *st = &l->stage;
  size_t k;
  int rc;
  if (!l->on) return LSYS_EARG;
  if (s->npal != st->npal ||
      (s->npal > 0 && memcmp(s->pal, st->pal, s->npal * sizeof *s->pal) != 0)) {
    if ((rc = lsys_scene_set_palette(st, s->pal, s->npal)) != LSYS_OK) return rc;
    l->palchg = 1;
  }
  if ((rc = lsys_mesh_sync(&st->mesh, &s->mesh, r, n)) != LSYS_OK) return rc;
  for (k = 0; k < n; k++)             /* what the frame lacks: these, on top of the rest */
    lsys_scene_ranges_add(l->pend, &l->npend, LSYS_SCENE_NDIRTY, r[2 * k], r[2 * k + 1]);
  l->chg = 1;
  l->step = step;
  l->count = count;
  snprintf(l->note, sizeof l->note, "%s", note != NULL ? note : "");
  return LSYS_OK;
}

int lsys_vlive_take (lsys_vlive *l, lsys_vframe *f, char note[64]) {
  if (!l->on || !l->chg) return 0;
  if (l->palchg && lsys_scene_set_palette(&f->sc, l->stage.pal, l->stage.npal) != LSYS_OK)
    return 0;
  l->palchg = 0;
  if (lsys_mesh_sync(&f->sc.mesh, &l->stage.mesh, l->pend, l->npend) != LSYS_OK) return 0;
  l->npend = 0;
  l->chg = 0;
  f->step = l->step;
  f->nmodules = l->count;
  memcpy(note, l->note, sizeof l->note);
  return 1;
}
