/*
** The module string: storage, text notation in and out.
*/
#if defined(__linux__) && !defined(_GNU_SOURCE)
#define _GNU_SOURCE             /* madvise, mremap */
#endif
#ifdef __linux__
#include <sys/mman.h>
#endif
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lstring.h"

/*
** The arrays of a string (codes, symbols, parameters). A block of BIGBLOCK
** bytes or more is a mapping of its own on Linux, grown by mremap (which
** moves pages instead of copying them: a derivation grows its string in
** place) and given back when freed; smaller ones come from malloc, which
** keeps their memory for the next string (a plant made again and again
** faults no fresh pages). A header before the array says which.
*/
#define BIGBLOCK ((size_t)1 << 20)
#define HEAD 16                 /* bytes: the block's size, whether it is mapped */

typedef struct head { size_t size, mapped; } head;

static void *bset (head *h, size_t size, size_t mapped) {
  h->size = size;
  h->mapped = mapped;
  return (char *)h + HEAD;
}

static void *balloc (size_t n) {
  size_t size = n + HEAD;
  head *h;
  if (n > (size_t)-1 - HEAD - 4096) return NULL;
#ifdef __linux__
  if (size >= BIGBLOCK) {
    size = (size + 4095) & ~(size_t)4095;
    h = (head *)mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (h == MAP_FAILED) return NULL;
    lsys_common_hugepages(h, size);
    return bset(h, size, 1);
  }
#endif
  if ((h = (head *)LSYS_MALLOC(size)) == NULL) return NULL;
  return bset(h, size, 0);
}

static void bfree (void *p) {
  head *h;
  if (p == NULL) return;
  h = (head *)(void *)((char *)p - HEAD);
#ifdef __linux__
  if (h->mapped) {
    munmap(h, h->size);
    return;
  }
#endif
  LSYS_FREE(h);
}

static void *brealloc (void *p, size_t n) {
  head *h;
  size_t size = n + HEAD;
  if (p == NULL) return balloc(n);
  if (n > (size_t)-1 - HEAD - 4096) return NULL;
  h = (head *)(void *)((char *)p - HEAD);
#if defined(__linux__) && defined(MREMAP_MAYMOVE)     /* (a file that includes this one */
  if (h->mapped && size >= BIGBLOCK) {            /* may lack it): the pages move */
    head *nh;
    size = (size + 4095) & ~(size_t)4095;
    nh = (head *)mremap(h, h->size, size, MREMAP_MAYMOVE);
    if (nh == MAP_FAILED) return NULL;
    if (size > nh->size) lsys_common_hugepages(nh, size);
    return bset(nh, size, 1);
  }
#endif
#ifdef __linux__
  if (h->mapped || size >= BIGBLOCK) {            /* from one kind to the other */
    void *np = balloc(n);
    if (np == NULL) return NULL;
    memcpy(np, p, (h->size < size ? h->size : size) - HEAD);
    bfree(p);
    return np;
  }
#endif
  if ((h = (head *)LSYS_REALLOC(h, size)) == NULL) return NULL;
  return bset(h, size, 0);
}

/* lsys_common_grow_metered for a string's array: capacity doubled, within the meter. */
static int growm (void **p, size_t *cap, size_t need, size_t elem, lsys_meter *mt) {
  size_t ncap = *cap ? *cap : 16;
  void *np;
  int st;
  if (need <= *cap) return LSYS_OK;
  if (mt != NULL) {
    if ((st = lsys_common_meter_take(mt, *cap, need, elem, &ncap)) != LSYS_OK) return st;
  }
  else
    while (ncap < need) {
      if (ncap > ((size_t)-1 / 2) / elem) return LSYS_ENOMEM;
      ncap *= 2;
    }
  if ((np = brealloc(*p, ncap * elem)) == NULL) return LSYS_ENOMEM;
  *p = np;
  *cap = ncap;
  return LSYS_OK;
}

void lsys_lstring_init (lsys_lstring *s) {
  memset(s, 0, sizeof *s);
}

void lsys_lstring_free (lsys_lstring *s) {
  bfree(s->code);
  bfree(s->sym8);
  bfree(s->par);
  LSYS_FREE(s->ck);
  memset(s, 0, sizeof *s);
}

int lsys_lstring_reserve (lsys_lstring *s, size_t nmod, size_t npar) {
  int st;
  if (s->sym8 != NULL && (st = lsys_lstring_widen(s)) != LSYS_OK) return st;
  if (s->n + nmod > s->cap &&
      (st = growm((void **)&s->code, &s->cap, s->n + nmod, sizeof *s->code, s->meter))
        != LSYS_OK)
    return st;
  if (s->npar + npar > s->parcap &&
      (st = growm((void **)&s->par, &s->parcap, s->npar + npar, sizeof *s->par, s->meter))
        != LSYS_OK)
    return st;
  return LSYS_OK;
}

/* Reallocates '*p' from 'old' to 'new' bytes, keeping its contents, within
** meter 'mt' (whose count includes the old block). */
static int regrow (void **p, size_t old, size_t new, lsys_meter *mt) {
  size_t base = 0;
  void *np;
  if (mt != NULL) {
    base = mt->used > old ? mt->used - old : 0;
    if (base > mt->limit || new > mt->limit - base) {
      mt->hit = 1;
      return LSYS_EMEMORY;
    }
  }
  np = brealloc(*p, new > 0 ? new : 1);
  if (np == NULL) return LSYS_ENOMEM;
  *p = np;
  if (mt != NULL) mt->used = base + new;
  return LSYS_OK;
}

int lsys_lstring_widen (lsys_lstring *s) {
  size_t i, cap = s->n > 0 ? s->n : 1;
  uint16_t *w;
  int st;
  if (s->sym8 == NULL) return LSYS_OK;
  if (cap > ((size_t)-1) / 2) return LSYS_ENOMEM;
  if ((st = regrow((void **)&s->sym8, s->cap, cap * 2, s->meter)) != LSYS_OK) return st;
  w = (uint16_t *)(void *)s->sym8;
  for (i = s->n; i-- > 0;) w[i] = (uint16_t)LSYS_CODE(s->sym8[i], 0);   /* from the end */
  bfree(s->code);            /* no array (a narrow string has none) */
  s->code = w;
  s->sym8 = NULL;
  s->cap = cap;
  s->nck = 0;
  return LSYS_OK;
}

int lsys_lstring_grow (lsys_lstring *s, size_t nmod, size_t npar) {
  int st;
  if (nmod > s->cap) {
    size_t elem = s->sym8 != NULL ? 1 : sizeof *s->code;
    void **p = s->sym8 != NULL ? (void **)&s->sym8 : (void **)&s->code;
    if (nmod > ((size_t)-1 - 16) / elem) return LSYS_ENOMEM;
    if ((st = regrow(p, s->cap * elem, nmod * elem, s->meter)) != LSYS_OK) return st;
    s->cap = nmod;
  }
  if (npar > s->parcap) {
    if (npar > ((size_t)-1 - 16) / sizeof *s->par) return LSYS_ENOMEM;
    if ((st = regrow((void **)&s->par, s->parcap * sizeof *s->par, npar * sizeof *s->par,
                     s->meter)) != LSYS_OK)
      return st;
    s->parcap = npar;
  }
  return LSYS_OK;
}

/* Replaces the array '*p' of '*cap' items by one of exactly 'need' items,
** within meter 'mt' (whose count includes the old array). */
static int exact (void **p, size_t *cap, size_t need, size_t elem, lsys_meter *mt) {
  size_t old = *cap * elem, base = 0;
  void *np;
  if (need <= *cap) return LSYS_OK;
  if (need > ((size_t)-1 - 16) / elem) return LSYS_ENOMEM;
  if (mt != NULL) {
    base = mt->used > old ? mt->used - old : 0;
    if (base > mt->limit || need * elem > mt->limit - base) {
      mt->hit = 1;
      return LSYS_EMEMORY;
    }
  }
  bfree(*p);
  *p = NULL;
  *cap = 0;
  if (mt != NULL) mt->used = base;
  np = balloc(need * elem);
  if (np == NULL) return LSYS_ENOMEM;
  *p = np;
  *cap = need;
  if (mt != NULL) mt->used = base + need * elem;
  return LSYS_OK;
}

/* Drops the array of the other representation ('narrow': the wide one). */
static void dropother (lsys_lstring *s, int narrow) {
  void **p = narrow ? (void **)&s->code : (void **)&s->sym8;
  if (*p == NULL) return;
  if (s->meter != NULL) {
    size_t b = s->cap * (narrow ? sizeof *s->code : 1);
    s->meter->used = s->meter->used > b ? s->meter->used - b : 0;
  }
  bfree(*p);
  *p = NULL;
  s->cap = 0;
}

int lsys_lstring_prepare (lsys_lstring *s, size_t nmod, size_t npar) {
  int st;
  lsys_lstring_clear(s);
  dropother(s, 0);
  if ((st = exact((void **)&s->code, &s->cap, nmod, sizeof *s->code, s->meter)) != LSYS_OK)
    return st;
  return exact((void **)&s->par, &s->parcap, npar, sizeof *s->par, s->meter);
}

int lsys_lstring_prepare8 (lsys_lstring *s, size_t nmod) {
  lsys_lstring_clear(s);
  dropother(s, 1);
  return exact((void **)&s->sym8, &s->cap, nmod > 0 ? nmod : 1, 1, s->meter);
}

size_t lsys_lstring_bytes (const lsys_lstring *s) {
  return s->cap * (s->sym8 != NULL ? 1 : sizeof *s->code) + s->parcap * sizeof *s->par +
         s->ckcap * sizeof *s->ck;
}

int lsys_lstring_push (lsys_lstring *s, uint32_t sym, const double *p, uint32_t np) {
  int st;
  if ((st = lsys_lstring_reserve(s, 1, np)) != LSYS_OK) return st;
  s->code[s->n++] = LSYS_CODE(sym, np);
  if (np > 0) memcpy(s->par + s->npar, p, np * sizeof *p);
  s->npar += np;
  return LSYS_OK;
}

int lsys_lstring_append (lsys_lstring *dst, const lsys_lstring *src,
                         size_t i, size_t j, size_t poff) {
  size_t k, np = 0;
  int st;
  if (src->sym8 == NULL)
    for (k = i; k < j; k++) np += LSYS_CNP(src->code[k]);
  if ((st = lsys_lstring_reserve(dst, j - i, np)) != LSYS_OK) return st;
  if (src->sym8 != NULL)
    for (k = i; k < j; k++) dst->code[dst->n + k - i] = (uint16_t)LSYS_CODE(src->sym8[k], 0);
  else if (j > i) memcpy(dst->code + dst->n, src->code + i, (j - i) * sizeof *src->code);
  if (np > 0) memcpy(dst->par + dst->npar, src->par + poff, np * sizeof *src->par);
  dst->n += j - i;
  dst->npar += np;
  return LSYS_OK;
}

int lsys_lstring_copy (lsys_lstring *dst, const lsys_lstring *src) {
  lsys_lstring_clear(dst);
  return lsys_lstring_append(dst, src, 0, src->n, 0);
}

size_t lsys_lstring_poff (lsys_lstring *s, size_t i) {
  size_t k = i / LSYS_CKSTEP, m, off;
  if (s->sym8 != NULL || s->npar == 0) return 0;      /* no parameters */
  if (k >= s->nck) {            /* extend the checkpoint table up to k */
    size_t need = s->n / LSYS_CKSTEP + 1;
    if (s->ckcap < need &&
        lsys_common_grow((void **)&s->ck, &s->ckcap, need, sizeof *s->ck) != LSYS_OK) {
      for (m = 0, off = 0; m < i; m++) off += LSYS_CNP(s->code[m]);
      return off;               /* no memory for the table: plain scan */
    }
    if (s->nck == 0) { s->ck[0] = 0; s->nck = 1; }
    while (s->nck <= k) {
      size_t from = (s->nck - 1) * LSYS_CKSTEP;
      off = s->ck[s->nck - 1];
      for (m = from; m < from + LSYS_CKSTEP; m++) off += LSYS_CNP(s->code[m]);
      s->ck[s->nck++] = off;
    }
  }
  off = s->ck[k];
  for (m = k * LSYS_CKSTEP; m < i; m++) off += LSYS_CNP(s->code[m]);
  return off;
}

long long lsys_lstring_unbalanced (const lsys_lstring *s) {
  size_t i, depth = 0, first = 0;
  for (i = 0; i < s->n; i++) {
    uint32_t sym = LSYS_CSYM(lsys_lstring_code(s, i));
    if (sym == LSYS_SYM_LBR) { if (depth++ == 0) first = i; }
    else if (sym == LSYS_SYM_RBR) {
      if (depth == 0) return (long long)i;
      depth--;
    }
  }
  return depth ? (long long)first : -1;
}

static int isspacec (int c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

int lsys_lstring_parse (lsys_lstring *s, const char *text, size_t len,
                        lsys_alphabet *a, const lsys_names *decl, lsys_error *e) {
  size_t i = 0;
  double p[LSYS_MAXPARAMS];
  while (i < len) {
    size_t nl, start;
    uint32_t sym, np = 0;
    if (isspacec((unsigned char)text[i])) { i++; continue; }
    start = i;
    nl = lsys_alphabet_scan(text + i, len - i, decl);
    if (nl == 0)
      return lsys_seterror(e, LSYS_ESYNTAX, i, "unexpected '%c'", text[i]);
    sym = lsys_alphabet_intern(a, text + i, nl, e);
    if (sym == 0) { e->pos = i; return e->code; }
    i += nl;
    while (i < len && isspacec((unsigned char)text[i])) i++;
    if (i < len && text[i] == '(') {
      i++;
      for (;;) {
        char num[64], *end;
        size_t k = 0;
        while (i < len && isspacec((unsigned char)text[i])) i++;
        if (i < len && text[i] == ')' && np == 0) { i++; break; }   /* F() */
        while (i < len && k < sizeof num - 1 && text[i] != ',' && text[i] != ')' &&
               !isspacec((unsigned char)text[i]))
          num[k++] = text[i++];
        num[k] = '\0';
        if (k == 0)
          return lsys_seterror(e, LSYS_ESYNTAX, i, "number expected in parameters of '%s'",
                               lsys_alphabet_name(a, sym));
        errno = 0;
        {
          double x = strtod(num, &end);
          if (*end != '\0')
            return lsys_seterror(e, LSYS_ESYNTAX, i - k, "bad number '%s' in parameters of '%s'",
                                 num, lsys_alphabet_name(a, sym));
          if (!isfinite(x))
            return lsys_seterror(e, LSYS_ESYNTAX, i - k,
                                 "'%s' in parameters of '%s' is not a finite number",
                                 num, lsys_alphabet_name(a, sym));
          if (np == LSYS_MAXPARAMS)
            return lsys_seterror(e, LSYS_ESYNTAX, i - k, "too many parameters for '%s' (limit is %d)",
                                 lsys_alphabet_name(a, sym), LSYS_MAXPARAMS);
          p[np++] = x;
        }
        while (i < len && isspacec((unsigned char)text[i])) i++;
        if (i >= len)
          return lsys_seterror(e, LSYS_ESYNTAX, start, "unbalanced parentheses after '%s'",
                               lsys_alphabet_name(a, sym));
        if (text[i] == ',') { i++; continue; }
        if (text[i] == ')') { i++; break; }
        return lsys_seterror(e, LSYS_ESYNTAX, i, "',' or ')' expected in parameters of '%s'",
                             lsys_alphabet_name(a, sym));
      }
      if (np > 0 && (sym == LSYS_SYM_LBR || sym == LSYS_SYM_RBR))
        return lsys_seterror(e, LSYS_ESYNTAX, start, "'%s' takes no parameters",
                             lsys_alphabet_name(a, sym));
    }
    if (lsys_lstring_push(s, sym, p, np) != LSYS_OK)
      return lsys_seterror(e, LSYS_ENOMEM, start, "not enough memory");
  }
  return LSYS_OK;
}

int lsys_lstring_buf_add (lsys_buf *b, const char *s, size_t len) {
  if (lsys_common_grow((void **)&b->p, &b->cap, b->n + len + 1, 1) != LSYS_OK) return LSYS_ENOMEM;
  memcpy(b->p + b->n, s, len);
  b->n += len;
  b->p[b->n] = '\0';
  return LSYS_OK;
}

void lsys_lstring_buf_free (lsys_buf *b) {
  LSYS_FREE(b->p);
  memset(b, 0, sizeof *b);
}
