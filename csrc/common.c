/*
** Error record, growable arrays and whole-file reading shared by the core.
*/
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "common.h"

int lsys_seterror (lsys_error *e, int code, size_t pos, const char *fmt, ...) {
  if (e != NULL) {
    va_list ap;
    e->code = code;
    e->pos = pos;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
  }
  return code;
}

int lsys_grow (void **p, size_t *cap, size_t need, size_t elem) {
  size_t ncap = *cap ? *cap : 16;
  void *np;
  if (need <= *cap) return LSYS_OK;
  while (ncap < need) {
    if (ncap > ((size_t)-1 / 2) / elem) return LSYS_ENOMEM;
    ncap *= 2;
  }
  np = LSYS_REALLOC(*p, ncap * elem);
  if (np == NULL) return LSYS_ENOMEM;
  *p = np;
  *cap = ncap;
  return LSYS_OK;
}

char *lsys_readfile (const char *path, size_t max, size_t *len, lsys_error *e) {
  FILE *f = fopen(path, "rb");
  char *buf = NULL, *nb;
  size_t cap = 0, n = 0;
  if (f == NULL) {
    lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot open '%s': %s", path, strerror(errno));
    return NULL;
  }
  for (;;) {
    if (n == cap) {             /* capacity up to max + 1, to see a larger file */
      cap = cap == 0 ? 4096 : 2 * cap > max ? max + 1 : 2 * cap;
      if ((nb = (char *)LSYS_REALLOC(buf, cap)) == NULL) {
        lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
        break;
      }
      buf = nb;
    }
    n += fread(buf + n, 1, cap - n, f);
    if (n > max) {
      lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot read '%s': larger than %lu MiB", path,
                    (unsigned long)(max >> 20));
      break;
    }
    if (ferror(f)) {
      lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot read '%s': %s", path, strerror(errno));
      break;
    }
    if (feof(f)) {
      fclose(f);
      *len = n;
      return buf;
    }
  }
  fclose(f);
  LSYS_FREE(buf);
  return NULL;
}
