/*
** Snapshots (viewer.h): what the caller builds and hands over to the
** window, which frees it. Plain memory, no window: tested on their own
** (tests/c/test_viewer.c).
*/
#include <stdio.h>
#include <string.h>

#include "population.h"
#include "viewer.h"
#include "vlight.h"

lsys_vsnap *lsys_vsnap_new (size_t n) {
  lsys_vsnap *s = (lsys_vsnap *)LSYS_MALLOC(sizeof *s);
  size_t k;
  if (s == NULL) return NULL;
  memset(s, 0, sizeof *s);
  s->rate = 2;
  s->light = -1;
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
    LSYS_FREE(s->frames[k].partpicks);
    LSYS_FREE(s->frames[k].lines);
    LSYS_FREE(s->frames[k].leafr);
    if (s->frames[k].light != NULL) lsys_vlight_free(s->frames[k].light);
    LSYS_FREE(s->frames[k].light);
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

/* Thousands separated by spaces: 1234567 -> "1 234 567". */
static void count (char *buf, size_t n, size_t x) {
  char tmp[32];
  int len = snprintf(tmp, sizeof tmp, "%zu", x), i, j = 0;
  for (i = 0; i < len && (size_t)j + 2 < n; i++) {
    if (i > 0 && (len - i) % 3 == 0) buf[j++] = ' ';
    buf[j++] = tmp[i];
  }
  buf[j] = '\0';
}

void lsys_vsnap_status (const lsys_vsnap *s, long cur, double fps, int playing, int wireframe,
                        const char *note, char *line, size_t n) {
  const lsys_vframe *f = &s->frames[cur];
  char a[32], b[32], c[32];
  size_t nv, nt, nl;
  int at = 0;
  lsys_population_size(&f->sc, &nv, &nt, &nl);     /* as drawn: a population's instances */
  count(a, sizeof a, f->nmodules);
  count(b, sizeof b, nt);
  count(c, sizeof c, nl);
  if (s->live) {
    snprintf(line, n, "tick %d  %s limbs  %s triangles  %.0f fps%s%s%s", f->step, a, b, fps,
             note[0] ? "  " : "", note, wireframe ? "  wireframe" : "");
    return;
  }
  if (f->sc.ninst > 0) {
    count(a, sizeof a, f->sc.ninst);
    snprintf(line, n, "%s plants  %s triangles  %s lines  %.0f fps%s", a, b, c, fps,
             wireframe ? "  wireframe" : "");
    return;
  }
  if (f->step >= 0 && s->nframes > 1)
    at = snprintf(line, n, "step %d (%ld/%zu)  ", f->step, cur + 1, s->nframes);
  else if (f->step >= 0)
    at = snprintf(line, n, "step %d  ", f->step);
  if (at < 0 || (size_t)at >= n) return;
  snprintf(line + at, n - (size_t)at, "%s modules  %s triangles  %s lines  %.0f fps%s%s", a, b,
           c, fps, playing ? "  playing" : "", wireframe ? "  wireframe" : "");
}

void lsys_vsnap_frame_bounds (lsys_vframe *f, double b[6]) {
  if (!f->hasbounds) {
    double lo[3], hi[3];
    int i;
    lsys_scene_bounds(&f->sc, lo, hi);
    for (i = 0; i < 3; i++) { f->bounds[i] = lo[i]; f->bounds[3 + i] = hi[i]; }
    f->hasbounds = 1;
  }
  memcpy(b, f->bounds, sizeof f->bounds);
}
