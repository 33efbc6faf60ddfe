/*
** Module names <-> symbol ids, and the scanner that splits text into
** module names (docs/manual.md §4.1).
**
** Ids are small integers (at most LSYS_MAXSYM) because the Lstring packs a
** symbol id and a parameter count into 16 bits. A few ids are fixed.
*/
#ifndef LSYS_ALPHABET_H
#define LSYS_ALPHABET_H

#include "common.h"

#define LSYS_SYMBITS   11
#define LSYS_MAXSYM    ((1u << LSYS_SYMBITS) - 1)   /* 2047 names */

enum {
  LSYS_SYM_NONE = 0,
  LSYS_SYM_LBR,      /* [ */
  LSYS_SYM_RBR,      /* ] */
  LSYS_SYM_CUT,      /* % */
  LSYS_SYM_SUB,      /* ?  (sub-L-system start) */
  LSYS_SYM_SUBEND,   /* $ */
  LSYS_SYM_FIRSTFREE
};

typedef struct lsys_names {
  char **v;
  size_t n, cap;
} lsys_names;

typedef struct lsys_alphabet {
  char **names;        /* names[id], NUL-terminated; names[0] = "" */
  uint32_t n;          /* ids in use, including 0 */
  uint32_t cap;
  uint32_t *slots;     /* open-addressing hash: 0 = empty, else id */
  uint32_t nslots;     /* power of two */
} lsys_alphabet;

/* lsys_names: a list of declared multi-character names (a model's `modules`). */

int lsys_alphabet_init (lsys_alphabet *a);
void lsys_alphabet_free (lsys_alphabet *a);

/* Interns 'name' (of 'len' bytes); returns its id, or 0 with 'e' set when
** the alphabet is full (limit LSYS_MAXSYM) or out of memory. */
uint32_t lsys_alphabet_intern (lsys_alphabet *a, const char *name, size_t len,
                               lsys_error *e);

/* Forgets the names of ids >= n (n >= LSYS_SYM_FIRSTFREE; a larger n than in
** use does nothing): for a caller that knows nothing refers to them any more
** (a model whose creation failed). Allocates nothing. */
void lsys_alphabet_truncate (lsys_alphabet *a, uint32_t n);

/* Returns the id of 'name' or 0 when it was never interned. */
uint32_t lsys_alphabet_find (const lsys_alphabet *a, const char *name, size_t len);

static inline const char *lsys_alphabet_name (const lsys_alphabet *a, uint32_t id) {
  return id < a->n ? a->names[id] : "?";
}

/*
** Returns the length in bytes of the module name that starts at 's' (with
** 'len' bytes available), or 0 when no name starts there: at white space,
** '(' ')' '<' '>' ':', or a bad byte. Names: a declared name from 'decl'
** (longest first), '@' followed by a known cpfg name or else by one letter,
** '?' followed by a letter (query modules), '~' followed by one character
** (a predefined surface), one UTF-8 character otherwise.
*/
size_t lsys_alphabet_scan (const char *s, size_t len, const lsys_names *decl);

int lsys_alphabet_names_add (lsys_names *d, const char *name, size_t len);
void lsys_alphabet_names_free (lsys_names *d);

#endif
