/*
** Allocation hooks for C tests that compile a core file in (#include "x.c"):
** counts live blocks, fills new ones with garbage, and makes allocation
** number 'failat' fail. Include it before the core files.
*/
#ifndef LSYS_TALLOC_H
#define LSYS_TALLOC_H
#include <stdlib.h>
#include <string.h>

static long nalloc, nlive, failat = -1;   /* allocation number 'failat' fails */

static void *tmalloc (size_t n) {
  void *p;
  if (nalloc++ == failat) return NULL;
  if ((p = malloc(n)) != NULL) {
    nlive++;
    memset(p, 0x55, n);                 /* garbage, not zeros */
  }
  return p;
}

static void *trealloc (void *p, size_t n) {
  void *np;
  if (nalloc++ == failat) return NULL;
  np = realloc(p, n);
  if (np != NULL && p == NULL) nlive++;
  return np;
}

static void tfree (void *p) {
  if (p != NULL) nlive--;
  free(p);
}

#define LSYS_MALLOC(n)     tmalloc(n)
#define LSYS_REALLOC(p, n) trealloc((p), (n))
#define LSYS_FREE(p)       tfree(p)

#endif
