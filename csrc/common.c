/*
** Error record and growable arrays shared by the core.
*/
#include <stdarg.h>
#include <stdio.h>

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
