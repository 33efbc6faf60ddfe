/*
** The module string (docs/manual.md §8): a struct of arrays.
**
** Every module is one 16-bit code, its symbol id (LSYS_SYMBITS bits) and its
** parameter count (LSYS_NPBITS bits); the parameters of all modules follow
** each other in one pool of doubles. Parameter offsets are not stored per
** module: a scan carries them along, and random access goes through a
** checkpoint table (one offset every LSYS_CKSTEP modules) built on demand.
** That keeps a parameterless module at 2 bytes (cpfg spends about 1-2).
**
** A string whose modules have no parameters and whose symbols are all below
** 256 may be narrow: one byte per module, its symbol ('sym8'; 'code' is NULL).
** Only a derivation step makes narrow strings (derive_par.c); whatever else
** reads a string widens it first (lsys_lstring_widen; the bindings do it when
** they take a string), and the functions below that add modules widen it
** themselves.
*/
#ifndef LSYS_LSTRING_H
#define LSYS_LSTRING_H

#include "alphabet.h"

#define LSYS_NPBITS    5
#define LSYS_MAXPARAMS ((1 << LSYS_NPBITS) - 1)     /* 31 parameters */
#define LSYS_CKSTEP    64

#define LSYS_CODE(sym, np) ((uint16_t)(((sym) << LSYS_NPBITS) | (np)))
#define LSYS_CSYM(c)       ((uint32_t)(c) >> LSYS_NPBITS)
#define LSYS_CNP(c)        ((uint32_t)(c) & LSYS_MAXPARAMS)

typedef struct lsys_lstring {
  uint16_t *code;      /* module codes (NULL while narrow) */
  uint8_t *sym8;       /* narrow: the modules' symbols (NULL while wide) */
  size_t n, cap;       /* modules; capacity of 'code' or 'sym8' */
  double *par;         /* parameter pool */
  size_t npar, parcap;
  size_t *ck;          /* ck[k] = offset of the parameters of module k*LSYS_CKSTEP */
  size_t nck, ckcap;   /* nck checkpoints are valid */
  lsys_meter *meter;   /* while an operation fills it: its memory budget (or NULL) */
} lsys_lstring;

/* A growable byte buffer for text output. */
typedef struct lsys_buf {
  char *p;
  size_t n, cap;
} lsys_buf;

void lsys_lstring_init (lsys_lstring *s);
void lsys_lstring_free (lsys_lstring *s);
static inline void lsys_lstring_clear (lsys_lstring *s) { s->n = s->npar = s->nck = 0; }

/* Makes room for 'nmod' more modules and 'npar' more parameters (a narrow
** string is made wide first). Returns
** LSYS_OK, LSYS_ENOMEM, or LSYS_EMEMORY when s->meter's budget is reached
** (push, append and copy return the same). */
int lsys_lstring_reserve (lsys_lstring *s, size_t nmod, size_t npar);

/* The code of module i (either representation). */
static inline uint16_t lsys_lstring_code (const lsys_lstring *s, size_t i) {
  return s->sym8 != NULL ? (uint16_t)LSYS_CODE(s->sym8[i], 0) : s->code[i];
}

/* Makes a narrow string wide (two bytes a module, in place: the array is
** reallocated, within s->meter). LSYS_OK (also for a wide string),
** LSYS_ENOMEM or LSYS_EMEMORY (the string is unchanged then). */
int lsys_lstring_widen (lsys_lstring *s);

/* Grows the arrays of 's' (either representation) to exactly 'nmod' modules
** and 'npar' parameters, keeping what they hold (realloc, within s->meter). */
int lsys_lstring_grow (lsys_lstring *s, size_t nmod, size_t npar);

/* As lsys_lstring_prepare, for a narrow string of 'nmod' modules. */
int lsys_lstring_prepare8 (lsys_lstring *s, size_t nmod);

/* Empties 's' and makes room for 'nmod' modules and 'npar' parameters: a
** smaller array is replaced by one of exactly that size (its contents are
** dropped, not copied). Returns LSYS_OK, LSYS_ENOMEM or LSYS_EMEMORY (as
** reserve); 's' stays valid and empty on failure. */
int lsys_lstring_prepare (lsys_lstring *s, size_t nmod, size_t npar);

/* Bytes held by the string's arrays. */
size_t lsys_lstring_bytes (const lsys_lstring *s);

/* Appends one module. 'np' must be at most LSYS_MAXPARAMS. */
int lsys_lstring_push (lsys_lstring *s, uint32_t sym, const double *p, uint32_t np);

/* Appends modules [i, j) of 'src' (0-based, either representation) whose
** parameters start at 'poff'. */
int lsys_lstring_append (lsys_lstring *dst, const lsys_lstring *src,
                         size_t i, size_t j, size_t poff);

/* Copies 'src' into 'dst' (which is cleared first). */
int lsys_lstring_copy (lsys_lstring *dst, const lsys_lstring *src);

/* Offset in the pool of the parameters of module 'i' (0-based, i <= n). */
size_t lsys_lstring_poff (lsys_lstring *s, size_t i);

/*
** Parses cpfg text notation ("F(1,0.5)[+A]") and appends it to 's'.
** White space between modules is ignored; parameters are numbers.
** On error returns LSYS_ESYNTAX (or LSYS_ELIMIT/LSYS_ENOMEM) with e->pos the
** byte offset of the problem.
*/
int lsys_lstring_parse (lsys_lstring *s, const char *text, size_t len,
                        lsys_alphabet *a, const lsys_names *decl, lsys_error *e);

/* Appends the text notation of modules [i, j) to 'b' (either representation). A space separates
** two modules whose names would otherwise read back as one (with the
** declared names 'decl', which may be NULL). */
int lsys_lstring_format (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a,
                         const lsys_names *decl, size_t i, size_t j);

/* Like lsys_lstring_format, with the parameters rounded to 'digits' significant digits
** (1 to 17; 0 for the shortest text that reads back as the same double; whole numbers
** below 1e15 are always written in full). */
int lsys_lstring_format_digits (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a,
                                const lsys_names *decl, size_t i, size_t j, int digits);

/* Receives the text lsys_lstring_write streams, in pieces of about 64 KiB; returns
** LSYS_OK, or an error code that stops the writing and is returned by it. */
typedef int (*lsys_lstring_sink) (void *ud, const char *p, size_t n);

/* Writes the text of modules [i, j) (as lsys_lstring_format_digits: the same bytes)
** to 'sink' in pieces, never holding more than a piece of it: for strings too big to
** build as one block of text. Returns LSYS_OK, LSYS_ENOMEM, or the sink's error. */
int lsys_lstring_write (lsys_lstring *s, const lsys_alphabet *a, const lsys_names *decl,
                        size_t i, size_t j, int digits, lsys_lstring_sink sink, void *ud);

/* Checks bracket balance; returns -1 when balanced, else the index of the
** first module that is unbalanced (a ']' with no '[' or an unclosed '['). */
long long lsys_lstring_unbalanced (const lsys_lstring *s);

/* Writes the shortest of %.15g/%.16g/%.17g that reads back as 'x' (whole numbers below
** 1e15 in full, as %.0f), the same bytes as printf and strtod would choose, found
** with integer arithmetic where it is exact (lstring_write.c). */
int lsys_lstring_fmtnum (char *buf, size_t size, double x);

/* Writes 'x' with 'digits' significant digits (%.*g; 0: as lsys_lstring_fmtnum). */
int lsys_lstring_fmtnum_digits (char *buf, size_t size, double x, int digits);

int lsys_lstring_buf_add (lsys_buf *b, const char *s, size_t len);
void lsys_lstring_buf_free (lsys_buf *b);

#endif
