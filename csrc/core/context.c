/*
** Context matching for the derivation engine (derive_impl.h): the
** bracket-match tables of a string, and left and right contexts as cpfg
** matches them (cpfg guide, Appendix A; the manual's 6.3, docs/manual.md).
*/
#include <pthread.h>
#include <string.h>

#include "derive_impl.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* Grows the array *p of *cap entries of 'elem' bytes to exactly 'need'
** within the model's budget: a table made again at each step, for a string
** that grows by less than doubling. */
static int exact (lsys_rules *m, void **p, size_t *cap, size_t need, size_t elem) {
  void *np;
  if (*cap >= need) return LSYS_OK;
  if (need > (size_t)-1 / elem) return LSYS_ENOMEM;
  if (!lsys_common_meter_fits(&m->meter, (need - *cap) * elem)) {
    m->meter.hit = 1;
    return LSYS_EMEMORY;
  }
  if ((np = LSYS_REALLOC(*p, need * elem)) == NULL) return LSYS_ENOMEM;
  lsys_common_hugepages(np, need * elem);
  m->meter.used += (need - *cap) * elem;
  *p = np;
  *cap = need;
  return LSYS_OK;
}

static inline uint16_t scode (const lsys_lstring *s, size_t i) {
  return s->sym8 != NULL ? (uint16_t)LSYS_CODE(s->sym8[i], 0) : s->code[i];
}

/* Appends a far bracket at 'at' whose partner is 'p'. */
static int addfar (lsys_rules *m, lsys_brk *g, size_t at, uint32_t p) {
  int st;
  if (g->nfar == g->farcap &&
      (st = lsys_common_grow_metered((void **)&g->far, &g->farcap, g->nfar + 1, sizeof *g->far,
                                     &m->meter)) != LSYS_OK)
    return st;
  g->far[g->nfar++] = (uint64_t)at << 32 | p;
  return LSYS_OK;
}

static int cmpfar (const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return x < y ? -1 : x > y;
}

/* One pass over the string with a stack of the open brackets: the far ones and
** the parameter offsets. */
int lsys_context_buildtables (lsys_rules *m, const lsys_lstring *s) {
  lsys_brk *g = &m->brk;
  size_t i, n = s->n, off = 0, depth = 0;
  int st;
  if (n >= NONE) return LSYS_ELIMIT;
  g->nfar = 0;
  g->withp = s->sym8 == NULL && s->npar > 0;
  if (g->withp &&
      (st = exact(m, (void **)&g->pck, &g->pckcap, n / LSYS_BRK_PSTEP + 1, sizeof *g->pck))
        != LSYS_OK)
    return st;
  for (i = 0; i < n; i++) {
    uint32_t sym;
    if (s->sym8 != NULL) {
      uint8_t c = s->sym8[i];
      if (c != LSYS_SYM_LBR && c != LSYS_SYM_RBR) continue;
      sym = c;
    }
    else {
      uint16_t cd = s->code[i];
      if (g->withp) {
        if (i % LSYS_BRK_PSTEP == 0) {
          if (off >= NONE) return LSYS_ELIMIT;
          g->pck[i / LSYS_BRK_PSTEP] = (uint32_t)off;
        }
        off += LSYS_CNP(cd);
      }
      sym = LSYS_CSYM(cd);
      if (sym != LSYS_SYM_LBR && sym != LSYS_SYM_RBR) continue;
    }
    if (sym == LSYS_SYM_LBR) {
      if (depth == g->stkcap &&
          (st = lsys_common_grow_metered((void **)&g->stk, &g->stkcap, depth + 1, sizeof *g->stk,
                                         &m->meter)) != LSYS_OK)
        return st;
      g->stk[depth++] = (uint32_t)i;
    }
    else if (depth == 0) {
      if ((st = addfar(m, g, i, NONE)) != LSYS_OK) return st;
    }
    else if (i - g->stk[--depth] > LSYS_BRK_NEAR &&
             ((st = addfar(m, g, i, g->stk[depth])) != LSYS_OK ||
              (st = addfar(m, g, g->stk[depth], (uint32_t)i)) != LSYS_OK))
      return st;
  }
  if (g->withp && n % LSYS_BRK_PSTEP == 0) g->pck[n / LSYS_BRK_PSTEP] = (uint32_t)off;
  while (depth > 0)
    if ((st = addfar(m, g, g->stk[--depth], NONE)) != LSYS_OK) return st;
  if (g->nfar > 1) qsort(g->far, g->nfar, sizeof *g->far, cmpfar);
  return LSYS_OK;
}

/* Grows a window's array (the worker threads' windows are not metered: the
** chunk's share of the string, counted by lsys_context_winbytes). */
static int wgrow (void **p, size_t *cap, size_t need, size_t elem) {
  return *cap >= need ? LSYS_OK : lsys_common_grow(p, cap, need, elem);
}

/* Module j's first parameter from the string's offsets. */
static size_t gpoff (const lsys_brk *g, const uint16_t *code, size_t j) {
  size_t k = j / LSYS_BRK_PSTEP * LSYS_BRK_PSTEP, off;
  if (!g->withp) return 0;
  for (off = g->pck[j / LSYS_BRK_PSTEP]; k < j; k++) off += LSYS_CNP(code[k]);
  return off;
}

size_t lsys_context_farpoff (const view *v, size_t j) {
  return gpoff(v->match->g, v->code, j);
}

uint32_t lsys_context_farpartner (const view *v, size_t j) {
  const lsys_brk *g = v->match->g;
  size_t lo = 0, hi = g->nfar, k, depth = 0;
  uint64_t key = (uint64_t)j << 32;
  while (lo < hi) {                        /* the first entry at or after j */
    size_t mid = lo + (hi - lo) / 2;
    if (g->far[mid] < key) lo = mid + 1;
    else hi = mid;
  }
  if (lo < g->nfar && g->far[lo] >> 32 == j) return (uint32_t)g->far[lo];
  /* a near one: within LSYS_BRK_NEAR modules */
  if (LSYS_CSYM(lsys_view_code(v, j)) == LSYS_SYM_LBR) {
    for (k = j + 1; k < v->n && k <= j + LSYS_BRK_NEAR; k++) {
      uint32_t sym = LSYS_CSYM(lsys_view_code(v, k));
      if (sym == LSYS_SYM_LBR) depth++;
      else if (sym == LSYS_SYM_RBR && depth-- == 0) return (uint32_t)k;
    }
  }
  else
    for (k = j; k-- > 0 && j - k <= LSYS_BRK_NEAR;) {
      uint32_t sym = LSYS_CSYM(lsys_view_code(v, k));
      if (sym == LSYS_SYM_RBR) depth++;
      else if (sym == LSYS_SYM_LBR && depth-- == 0) return (uint32_t)k;
    }
  return NONE;                             /* (not reached: the far ones are listed) */
}

/* The bits of the brackets among n <= 64 symbols. */
static inline uint64_t bracketbits (const uint8_t *c, size_t n) {
  uint64_t bits = 0;
  size_t i = 0;
#if defined(__SSE2__)
  const __m128i l = _mm_set1_epi8((char)LSYS_SYM_LBR), r = _mm_set1_epi8((char)LSYS_SYM_RBR);
  for (; i + 16 <= n; i += 16) {
    __m128i x = _mm_loadu_si128((const __m128i *)(const void *)(c + i));
    unsigned mk = (unsigned)_mm_movemask_epi8(_mm_or_si128(_mm_cmpeq_epi8(x, l),
                                                             _mm_cmpeq_epi8(x, r)));
    bits |= (uint64_t)mk << i;
  }
#endif
  for (; i < n; i++)
    if (c[i] == LSYS_SYM_LBR || c[i] == LSYS_SYM_RBR) bits |= (uint64_t)1 << i;
  return bits;
}

int lsys_context_window (lsys_brkwin *b, const lsys_brk *g, const view *v, size_t a, size_t c) {
  size_t wa = a > LSYS_BRK_NEAR ? a - LSYS_BRK_NEAR : 0;
  size_t we = c + LSYS_BRK_NEAR < v->n ? c + LSYS_BRK_NEAR : v->n;
  size_t i, w, wn = we - wa, nw = wn / 64 + 1, nb = 0, depth = 0, off = 0;
  int withp = g->withp && v->code != NULL;
  b->g = g;
  b->ca = a; b->cb = c;
  b->wa = wa; b->wn = 0;
  b->withp = 0;                /* until made: the string's tables answer */
  if (wgrow((void **)&b->bits, &b->bitscap, nw, sizeof *b->bits) != LSYS_OK ||
      wgrow((void **)&b->cnt, &b->cntcap, nw, sizeof *b->cnt) != LSYS_OK ||
      (withp && wgrow((void **)&b->poff, &b->poffcap, wn + 1, sizeof *b->poff) != LSYS_OK))
    return LSYS_ENOMEM;
  if (withp) off = gpoff(g, v->code, wa);
  /* the brackets' bits and counts, the parameters' offsets */
  for (w = 0; w < nw; w++) {
    size_t e = w * 64 + 64 < wn ? w * 64 + 64 : wn;
    uint64_t bits = 0;
    b->cnt[w] = (uint32_t)nb;
    if (v->code8 != NULL)
      bits = bracketbits(v->code8 + wa + w * 64, e - w * 64);
    else
      for (i = w * 64; i < e; i++) {
        uint16_t cd = v->code[wa + i];
        uint32_t sym = LSYS_CSYM(cd);
        if (withp) {
          b->poff[i] = (uint32_t)off;
          off += LSYS_CNP(cd);
        }
        if (sym == LSYS_SYM_LBR || sym == LSYS_SYM_RBR) bits |= (uint64_t)1 << (i & 63);
      }
    b->bits[w] = bits;
    nb += lsys_popcount64(bits);
  }
  if (withp) b->poff[wn] = (uint32_t)off;
  b->withp = withp;
  /* the partners, by rank: the open brackets wait on a stack of (rank, position) */
  if (wgrow((void **)&b->pos, &b->poscap, nb + 1, sizeof *b->pos) != LSYS_OK) return LSYS_ENOMEM;
  nb = 0;
  for (w = 0; w < nw; w++) {
    uint64_t bits = b->bits[w];
    while (bits != 0) {
#if defined(__GNUC__)
      size_t at = w * 64 + (size_t)__builtin_ctzll(bits);
#else
      size_t at = w * 64, k;
      for (k = 0; !((bits >> k) & 1); k++) at++;
#endif
      bits &= bits - 1;
      b->pos[nb] = NONE;
      if (LSYS_CSYM(lsys_view_code(v, wa + at)) == LSYS_SYM_LBR) {
        if (wgrow((void **)&b->stk, &b->stkcap, 2 * depth + 2, sizeof *b->stk) != LSYS_OK)
          return LSYS_ENOMEM;
        b->stk[2 * depth] = (uint32_t)nb;
        b->stk[2 * depth + 1] = (uint32_t)(wa + at);
        depth++;
      }
      else if (depth > 0) {
        depth--;
        b->pos[b->stk[2 * depth]] = (uint32_t)(wa + at);
        b->pos[nb] = b->stk[2 * depth + 1];
      }
      nb++;
    }
  }
  b->wn = wn;
  return LSYS_OK;
}

/* The calling thread's windows: LSYS_SEQWIN modules at a time. */
#define LSYS_SEQWIN 65536
int lsys_context_ensure (view *v, size_t i) {
  lsys_brkwin *b = v->match;
  if (b == NULL || (i >= b->ca && i < b->cb && b->wn > 0)) return LSYS_OK;
  return lsys_context_window(b, b->g, v, i, i + LSYS_SEQWIN < v->n ? i + LSYS_SEQWIN : v->n);
}

void lsys_context_freewin (lsys_brkwin *b) {
  LSYS_FREE(b->bits); LSYS_FREE(b->cnt); LSYS_FREE(b->pos); LSYS_FREE(b->stk);
  LSYS_FREE(b->poff);
  memset(b, 0, sizeof *b);
}

size_t lsys_context_winbytes (const lsys_brkwin *b) {
  return b->bitscap * sizeof *b->bits + b->cntcap * sizeof *b->cnt +
         b->poscap * sizeof *b->pos + b->stkcap * sizeof *b->stk +
         b->poffcap * sizeof *b->poff;
}

uint32_t lsys_context_eqsym (const lsys_rules *m) {
  uint32_t e = lsys_alphabet_find(m->ab, "=", 1);
  return e ? e : NONE;
}

/* Is 'sym' ignored by the contexts (on the ignore list, or off the consider list)? A
** bracket can be: cpfg's consider list ignores every module it does not name, brackets
** included (lsys_input.y, Consider). Only the right context skips an ignored bracket
** (cpfg's RconDiff tests its ignore table first); the left context keeps the branch
** structure (LconDiff handles brackets first). */
static inline int skipped (const view *v, uint32_t sym) {
  int in;
  if (v->skip == NULL) return 0;
  in = (v->skip->bits[sym >> 3] >> (sym & 7)) & 1;
  return v->skip->consider ? !in : in;
}

/* The module a left context compares with, scanning left from j (cpfg's
** way: whole branches to the left skipped, out of the current one, ignored
** modules passed), or -1. Not for rings. */
enum { SC_STOP, SC_PASS, SC_JUMP };

/* What the scans do at each symbol with the ignore or consider list k (NULL:
** none): the left one jumps back over a branch at ']', passes '[' and ignored
** modules; the right one passes ignored modules (brackets too), jumps over a
** branch at '[' (a plain pattern module's scan). */
static void classes (const lsys_skip *k, uint8_t *lcls, uint8_t *rcls) {
  uint32_t sym;
  for (sym = 0; sym < 256; sym++) {
    int in = k != NULL && ((k->bits[sym >> 3] >> (sym & 7)) & 1), sk = k != NULL &&
             (k->consider ? !in : in);
    lcls[sym] = sym == LSYS_SYM_RBR ? SC_JUMP : sym == LSYS_SYM_LBR || sk ? SC_PASS : SC_STOP;
    rcls[sym] = sk ? SC_PASS : sym == LSYS_SYM_LBR ? SC_JUMP : SC_STOP;
  }
}

void lsys_context_classes (lsys_skip *k) { classes(k, k->lcls, k->rcls); }

static uint8_t nolcls[256], norcls[256];   /* without a list: made once */
static pthread_once_t noonce = PTHREAD_ONCE_INIT;
static void nolists (void) { classes(NULL, nolcls, norcls); }

long long lsys_context_leftof (const view *v, long long j) {
  if (v->code8 != NULL) {                      /* a byte a module: by the tables */
    const uint8_t *c8 = v->code8, *cls;
    if (v->skip == NULL) pthread_once(&noonce, nolists);
    cls = v->skip != NULL ? v->skip->lcls : nolcls;
    for (; j >= 0; j--) {
      uint8_t k = cls[c8[j]];
      if (k == SC_STOP) return j;
      if (k == SC_JUMP) {
        uint32_t p = lsys_view_partner(v, (size_t)j);
        if (p == NONE) return -1;
        j = (long long)p;
      }
    }
    return -1;
  }
  for (; j >= 0; j--) {
    uint32_t sym = LSYS_CSYM(lsys_view_code(v, j));
    if (sym == LSYS_SYM_RBR) {
      uint32_t p = lsys_view_partner(v, (size_t)j);
      if (p == NONE) return -1;
      j = (long long)p;
    }
    else if (sym != LSYS_SYM_LBR && !skipped(v, sym)) return j;
  }
  return -1;
}

/* The module a right context's plain pattern module compares with, from j
** (ignored modules passed, whole branches skipped), or v->n. Not for rings. */
size_t lsys_context_rightof (const view *v, size_t j) {
  if (v->code8 != NULL) {
    const uint8_t *c8 = v->code8, *cls;
    if (v->skip == NULL) pthread_once(&noonce, nolists);
    cls = v->skip != NULL ? v->skip->rcls : norcls;
    while (j < v->n) {
      uint8_t k = cls[c8[j]];
      if (k == SC_STOP) return j;
      if (k == SC_PASS) j++;
      else {
        uint32_t p = lsys_view_partner(v, j);
        if (p == NONE) return v->n;
        j = (size_t)p + 1;
      }
    }
    return v->n;
  }
  while (j < v->n) {
    uint32_t sym = LSYS_CSYM(lsys_view_code(v, j));
    if (skipped(v, sym)) j++;
    else if (sym == LSYS_SYM_LBR) {
      uint32_t p = lsys_view_partner(v, j);
      if (p == NONE) return v->n;
      j = (size_t)p + 1;
    }
    else return j;
  }
  return v->n;
}

/* Whether the pattern modules [p, p + n) are plain: no brackets, no '='. */
static int plain (const lsys_rules *m, const view *v, uint32_t p, uint32_t n) {
  uint32_t k;
  for (k = 0; k < n; k++) {
    uint32_t sym = m->pat[p + k].sym;
    if (sym == LSYS_SYM_LBR || sym == LSYS_SYM_RBR || sym == v->eq) return 0;
  }
  return n <= LSYS_NMEMO;
}

/* Left context: scans left from 'i', skipping whole branches to the left
** and climbing out of the current one; fills the lc parameters of 'args'. */
int lsys_context_matchleft (const lsys_rules *m, const view *v, size_t i, const lsys_rule *r,
                            double *args, lsys_ctxmemo *mm) {
  long long j = (long long)i - 1;
  size_t steps = 0;
  double *a = args + r->lcargs;
  uint32_t k;
  if (mm != NULL && !v->ring && plain(m, v, r->lc, r->nlc)) {   /* the scans of the other */
    int q;                                                     /* rules, kept */
    for (q = 0; q < (int)r->nlc; q++) {
      const lsys_patmod *pm = &m->pat[r->lc + r->nlc - 1 - q];
      size_t at;
      while (mm->nl <= q && !mm->lend) {
        long long x = lsys_context_leftof(v, mm->nl == 0 ? j : (long long)mm->l[mm->nl - 1] - 1);
        if (x < 0) mm->lend = 1;
        else mm->l[mm->nl++] = (size_t)x;
      }
      if (mm->nl <= q) return 0;
      at = mm->l[q];
      if (lsys_view_code(v, at) != LSYS_CODE(pm->sym, pm->np)) return 0;
      a -= pm->np;
      if (pm->np) memcpy(a, v->par + lsys_view_poff(v, at), pm->np * sizeof *a);
    }
    return 1;
  }
  for (k = r->nlc; k-- > 0;) {
    const lsys_patmod *pm = &m->pat[r->lc + k];
    for (;;) {
      uint32_t sym;
      if (j < 0) {
        if (!v->ring || v->n == 0) return 0;
        j = (long long)v->n - 1;
      }
      if (++steps > v->n) return 0;
      sym = LSYS_CSYM(lsys_view_code(v, j));
      if (sym == LSYS_SYM_RBR) {
        uint32_t p = lsys_view_partner(v, (size_t)j);
        if (p == NONE) return 0;
        j = (long long)p - 1;
      }
      else if (sym == LSYS_SYM_LBR || skipped(v, sym)) j--;
      else break;
    }
    if (lsys_view_code(v, j) != LSYS_CODE(pm->sym, pm->np)) return 0;
    a -= pm->np;
    if (pm->np) memcpy(a, v->par + lsys_view_poff(v, (size_t)j), pm->np * sizeof *a);
    j--;
  }
  return 1;
}

/* The index of the ']' that ends the branch containing position 'j' (or
** v->n when there is none): cpfg's '=' in a right context. */
static size_t branchend (const view *v, size_t j) {
  while (j < v->n) {
    uint32_t sym = LSYS_CSYM(lsys_view_code(v, j));
    if (sym == LSYS_SYM_RBR) return j;
    if (sym == LSYS_SYM_LBR) {
      uint32_t p = lsys_view_partner(v, j);
      if (p == NONE) return v->n;
      j = p;
    }
    j++;
  }
  return v->n;
}

/*
** Right context from string position 'j', as cpfg's one linear scan
** (RconDiff in its generate.c; docs/manual.md §6.3): each pattern module is
** compared with the next module that is not skipped, and a branch is
** skipped whole when the pattern module is not a '['. So a '[' in the
** pattern matches only the next branch there (no search among siblings), a
** ']' matches a literal ']' (it does not skip the rest of a branch), and a
** pattern module never matches past the ']' that ends the predecessor's
** branch. '=' (without parameters) moves to the ']' ending the current
** branch. Ignored modules are skipped, before anything else: an ignored
** bracket is stepped over as any module (cpfg's consider list that does not
** name the brackets). 'a' receives the pattern's parameters.
*/
int lsys_context_matchright (const lsys_rules *m, const view *v, size_t j, const lsys_rule *r,
                             double *a, lsys_ctxmemo *mm) {
  size_t steps = 0;
  uint32_t k;
  if (mm != NULL && !v->ring && plain(m, v, r->rc, r->nrc)) {   /* as the left context */
    int q;
    for (q = 0; q < (int)r->nrc; q++) {
      const lsys_patmod *pm = &m->pat[r->rc + q];
      size_t at;
      while (mm->nr <= q && !mm->rend) {
        size_t x = lsys_context_rightof(v, mm->nr == 0 ? j : mm->r[mm->nr - 1] + 1);
        if (x >= v->n) mm->rend = 1;
        else mm->r[mm->nr++] = x;
      }
      if (mm->nr <= q) return 0;
      at = mm->r[q];
      if (lsys_view_code(v, at) != LSYS_CODE(pm->sym, pm->np)) return 0;
      if (pm->np) memcpy(a, v->par + lsys_view_poff(v, at), pm->np * sizeof *a);
      a += pm->np;
    }
    return 1;
  }
  for (k = 0; k < r->nrc; k++) {
    const lsys_patmod *pm = &m->pat[r->rc + k];
    if (pm->sym == v->eq && pm->np == 0) {
      j = branchend(v, j);
      continue;
    }
    for (;;) {
      uint32_t sym;
      if (j >= v->n) {
        if (!v->ring || v->n == 0) return 0;
        j = 0;                            /* a ring: on from the start */
      }
      if (++steps > 2 * v->n + 2) return 0;
      sym = LSYS_CSYM(lsys_view_code(v, j));
      if (skipped(v, sym)) j++;            /* first, as cpfg: an ignored bracket too */
      else if (sym == LSYS_SYM_LBR && pm->sym != LSYS_SYM_LBR) {
        uint32_t p = lsys_view_partner(v, j);
        if (p == NONE) return 0;
        j = (size_t)p + 1;
      }
      else break;
    }
    if (lsys_view_code(v, j) != LSYS_CODE(pm->sym, pm->np)) return 0;
    if (pm->np) memcpy(a, v->par + lsys_view_poff(v, (size_t)j), pm->np * sizeof *a);
    a += pm->np;
    j++;
  }
  return 1;
}
