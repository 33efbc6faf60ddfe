/*
** Snapshots (viewer.h): what the caller builds and hands over to the
** window, which frees it. Plain memory, no window: tested on their own
** (tests/c/test_viewer.c).
*/
#include <string.h>

#include "viewer.h"

lsys_vsnap *lsys_vsnap_new (size_t n) {
  lsys_vsnap *s = (lsys_vsnap *)LSYS_MALLOC(sizeof *s);
  size_t k;
  if (s == NULL) return NULL;
  memset(s, 0, sizeof *s);
  s->rate = 2;
  if (n > 0) {
    s->frames = (lsys_vframe *)LSYS_MALLOC(n * sizeof *s->frames);
    if (s->frames == NULL) { LSYS_FREE(s); return NULL; }
    memset(s->frames, 0, n * sizeof *s->frames);
    for (k = 0; k < n; k++) {
      lsys_scene_init(&s->frames[k].sc);
      s->frames[k].step = -1;
    }
  }
  s->nframes = n;
  return s;
}

void lsys_vsnap_free (lsys_vsnap *s) {
  size_t k;
  if (s == NULL) return;
  for (k = 0; k < s->nframes; k++) {
    lsys_scene_free(&s->frames[k].sc);
    LSYS_FREE(s->frames[k].picks);
    LSYS_FREE(s->frames[k].lines);
  }
  LSYS_FREE(s->frames);
  for (k = 0; k < (size_t)s->ntex; k++) lsys_texture_free(&s->tex[k]);
  LSYS_FREE(s->tex);
  LSYS_FREE(s->texp);
  LSYS_FREE(s);
}

int lsys_vsnap_textures (lsys_vsnap *s, int n) {
  int k;
  if (n <= 0) return LSYS_OK;
  s->tex = (lsys_texture *)LSYS_MALLOC((size_t)n * sizeof *s->tex);
  s->texp = (const lsys_texture **)LSYS_MALLOC((size_t)n * sizeof *s->texp);
  if (s->tex == NULL || s->texp == NULL) {
    LSYS_FREE(s->tex);
    LSYS_FREE(s->texp);
    s->tex = NULL;
    s->texp = NULL;
    return LSYS_ENOMEM;
  }
  memset(s->tex, 0, (size_t)n * sizeof *s->tex);
  for (k = 0; k < n; k++) s->texp[k] = &s->tex[k];
  s->ntex = n;
  return LSYS_OK;
}
