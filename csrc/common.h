/*
** Shared definitions of the lsys core: status codes, the error record,
** allocation hooks. The core never includes Lua headers (STYLE.md §1).
*/
#ifndef LSYS_COMMON_H
#define LSYS_COMMON_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#define LSYS_OK       0
#define LSYS_ENOMEM  (-1)   /* allocation failed */
#define LSYS_ELIMIT  (-2)   /* a configured limit (max_modules, ...) was hit */
#define LSYS_ESYNTAX (-3)   /* malformed text */
#define LSYS_ERULE   (-4)   /* a rule callback failed or returned bad values */
#define LSYS_EARG    (-5)   /* bad argument or state */
#define LSYS_EBUSY   (-6)   /* the object is in use by a running operation (re-entry) */

/* Allocation goes through these so tests can inject failures. */
#ifndef LSYS_MALLOC
#define LSYS_MALLOC(n)     malloc(n)
#define LSYS_REALLOC(p, n) realloc((p), (n))
#define LSYS_FREE(p)       free(p)
#endif

/* An error record filled by core functions that fail. 'pos' is a byte
** offset into the text being parsed, or a module index, depending on the
** function; it is (size_t)-1 when it does not apply. */
typedef struct lsys_error {
  int code;
  size_t pos;
  char msg[256];
} lsys_error;

int lsys_seterror (lsys_error *e, int code, size_t pos, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 4, 5)))
#endif
  ;

/* Grows '*p' (an array of 'elem'-byte items with capacity '*cap') so that it
** holds at least 'need' items; capacity doubles. Returns LSYS_OK or
** LSYS_ENOMEM (the old block stays valid). */
int lsys_grow (void **p, size_t *cap, size_t need, size_t elem);

/* Reads the whole file 'path' (at most 'max' bytes) into a new block (free
** it with LSYS_FREE; not NUL-terminated) of *len bytes. On failure returns
** NULL with e->msg naming the file ("cannot open 'x': ...", "cannot read
** 'x': larger than N MiB"). */
char *lsys_readfile (const char *path, size_t max, size_t *len, lsys_error *e);

#endif
