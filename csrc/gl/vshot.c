/*
** Pictures read back from the viewer window (vshot.h).
*/
#define _POSIX_C_SOURCE 200809L
#include <GL/gl.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "pngio.h"
#include "vshot.h"

void lsys_vshot_autoname (lsys_vshot *r, char *buf, size_t n) {
  int k;
  for (k = 0; k < 1000; k++) {
    snprintf(buf, n, "lsys-%03d.png", (r->seq + k) % 1000 + 1);
    if (access(buf, F_OK) != 0) break;
  }
  r->seq = (r->seq + k + 1) % 1000;
}

int lsys_vshot_png (lsys_vshot *r, const int rect[4], const char *path, lsys_error *e) {
  int w = rect[2], h = rect[3];
  size_t row = 4 * (size_t)w, y;
  if (w <= 0 || h <= 0)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': the window is empty",
                         path);
  if (lsys_common_grow((void **)&r->pixels, &r->cap, row * (size_t)h + row, 1) != LSYS_OK)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1,
                         "not enough memory for a %dx%d picture", w, h);
  r->ReadBuffer(GL_BACK);
  r->PixelStorei(GL_PACK_ALIGNMENT, 1);
  r->ReadPixels(rect[0], rect[1], w, h, GL_RGBA, GL_UNSIGNED_BYTE, r->pixels);
  for (y = 0; y < (size_t)h / 2; y++) {               /* GL rows go up; PNG rows go down */
    uint8_t *a = r->pixels + y * row, *b = r->pixels + ((size_t)h - 1 - y) * row;
    uint8_t *t = r->pixels + (size_t)h * row;
    memcpy(t, a, row);
    memcpy(a, b, row);
    memcpy(b, t, row);
  }
  return lsys_pngio_write(path, r->pixels, w, h, 0, e);
}

void lsys_vshot_screenshot (lsys_vshot *r, const char *path, int w, int h, lsys_vevent *ev) {
  lsys_error e;
  int all[4];
  all[0] = all[1] = 0;
  all[2] = w;
  all[3] = h;
  if (path[0] == '\0') lsys_vshot_autoname(r, ev->path, sizeof ev->path);
  else snprintf(ev->path, sizeof ev->path, "%s", path);
  ev->ok = lsys_vshot_png(r, all, ev->path, &e) == LSYS_OK;
  if (!ev->ok) snprintf(ev->msg, sizeof ev->msg, "%s", e.msg);
}

void lsys_vshot_series (lsys_vshot *r, const lsys_vsnap *s, const int rect[4],
                        lsys_vshot_draw draw, void *ctx, lsys_vevent *ev) {
  struct stat st;
  lsys_error e;
  size_t k;
  ev->type = LSYS_VEV_FRAMES;
  ev->ok = 0;
  ev->count = 0;
  snprintf(ev->path, sizeof ev->path, "%s", s->framesdir[0] != '\0' ? s->framesdir
                                                                    : "lsys-frames");
  if (mkdir(ev->path, 0777) != 0 && !(errno == EEXIST && stat(ev->path, &st) == 0 &&
                                      S_ISDIR(st.st_mode))) {
    snprintf(ev->msg, sizeof ev->msg, "cannot make the directory %.200s: %s", ev->path,
             errno == EEXIST ? "a file is in the way" : strerror(errno));
    return;
  }
  for (k = 0; k < s->nframes; k++) {
    char path[600];
    long step = s->frames[k].step >= 0 ? s->frames[k].step : (long)k;
    snprintf(path, sizeof path, "%s/step-%04ld.png", ev->path, step);
    if (draw(ctx, k, rect, &e) != LSYS_OK || lsys_vshot_png(r, rect, path, &e) != LSYS_OK) {
      snprintf(ev->msg, sizeof ev->msg, "%s", e.msg);
      return;
    }
    if (ev->count++ == 0) ev->first = step;
    ev->step = step;
  }
  ev->ok = 1;
}

void lsys_vshot_free (lsys_vshot *r) {
  LSYS_FREE(r->pixels);
  r->pixels = NULL;
  r->cap = 0;
}
