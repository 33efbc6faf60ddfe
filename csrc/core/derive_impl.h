/*
** What the derivation engine's files share (not part of the API; see
** derive.h): derive.c rewrites, context.c matches contexts.
*/
#ifndef LSYS_DERIVE_IMPL_H
#define LSYS_DERIVE_IMPL_H

#include "derive.h"

#define NONE UINT32_MAX
/* A stochastic alternative's record in w->alt before its args and vals: rule,
** weight, its produced successor's [b, e) and parameters in m->altdyn, then for
** cpfg's generator whether the rule stopped at its mark (lsys.cpfg_try) and the
** generator's state before it was tried (x48, iset, gset: replayed when chosen). */
#define ALTHEAD 9

/* A view of the string being matched: codes, parameters, and for contexts
** the brackets and parameter offsets of a window (derive.h). */
typedef struct view {
  const uint16_t *code;
  const uint8_t *code8;    /* or, of a string at a byte a module, its symbols (code NULL) */
  const double *par;
  size_t n;
  lsys_brkwin *match;      /* NULL when no context tables were built; the thread's
                              window, made for the modules it rewrites */
  const lsys_skip *skip;
  int ring;
  uint32_t eq;             /* the symbol of '=' (right contexts), or NONE */
  int single;              /* the module is one an expansion made: it has no modules after
                              it in the view, so no predecessor of several modules applies */
} view;

/* The rule chosen for a module: its arguments and values; for a rule
** function, the successor it produced (modules [d0, d1) of 'dyn', their
** parameters from 'dp'). */
typedef struct lsys_pick {
  const lsys_rule *r;
  const double *args, *vals;
  const lsys_lstring *dyn;     /* NULL: the rule's template */
  size_t d0, d1, dp;
} lsys_pick;

/* Strings shorter than this are rewritten on one thread (threads cost more). */
#define LSYS_PARMIN 8192

int lsys_derive_choose (lsys_rules *m, lsys_scratch *w, lsys_ruleset *const *sets, int nsets,
                        const view *v, size_t i, uint16_t code, const double *par, lsys_pick *pk);
int lsys_derive_checkvals (lsys_rules *m, const lsys_scratch *w, const lsys_rule *r, size_t i,
                           const double *vals);
int lsys_derive_needscratch (lsys_scratch *w, size_t nargs);

/*
** The productions of a step on several threads (derive_par.c): 'v' is the
** view of 'src' (its context tables built when a rule has a context), 'sets'
** the production sets of the main L-system. Returns LSYS_OK with 'dst'
** written, or LSYS_PAR_SEQ when the step must run on the calling thread
** instead ('dst' then holds nothing of value): a rule that needs the
** callback, a cut, a sub-L-system, a predecessor of several modules, a
** limit or budget that may be reached, an error (whose message the
** sequential step gives, at the module where it gives it).
*/
#define LSYS_PAR_SEQ 1
int lsys_derive_par_productions (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst, const view *v,
                                 lsys_ruleset *const *sets, int nsets);
void lsys_derive_par_free (lsys_rules *m);
/* The bytes the parallel step keeps between steps (the choices of its chunks). */
size_t lsys_derive_par_bytes (const lsys_rules *m);

/* Makes 's' wide within the running step's budget; exchanges two strings'
** contents (each keeps its meter). */
int lsys_derive_widen (lsys_rules *m, lsys_lstring *s);
void lsys_derive_swapstr (lsys_lstring *a, lsys_lstring *b);

/* The set (kind, sub, group) or NULL; the ignore/consider list of
** sub-L-system 'sub' or NULL; groups the set's rules by predecessor
** (LSYS_OK or LSYS_ENOMEM). derive_rules.c. */
lsys_ruleset *lsys_derive_findset (const lsys_rules *m, int kind, int sub, int group);
lsys_skip *lsys_derive_findskip (const lsys_rules *m, int sub);
int lsys_derive_compileset (lsys_rules *m, lsys_ruleset *s);

/* Whether rule r draws random numbers (ran, nran and what is made of them). */
static inline int lsys_rule_draws (const lsys_rule *r) {
  int k;
  for (k = 0; k < r->nvm; k++)
    if (r->vm[k].op == LSYS_OP_RAN || r->vm[k].op == LSYS_OP_NRAN) return 1;
  return 0;
}

/* The partner of a bracket outside the view's window, or whose partner is
** outside it; the first parameter of module j outside the window. */
uint32_t lsys_context_farpartner (const view *v, size_t j);
size_t lsys_context_farpoff (const view *v, size_t j);

/* The bits set in w (without a popcount instruction, which the build does not assume). */
static inline uint32_t lsys_popcount64 (uint64_t w) {
  w = w - ((w >> 1) & 0x5555555555555555u);             /* the bits counted in pairs, */
  w = (w & 0x3333333333333333u) + ((w >> 2) & 0x3333333333333333u);   /* fours, eights */
  w = (w + (w >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return (uint32_t)((w * 0x0101010101010101u) >> 56);
}

/* The partner of the bracket at j (its position, or NONE). */
static inline uint32_t lsys_view_partner (const view *v, size_t j) {
  const lsys_brkwin *b = v->match;
  size_t k = j - b->wa;
  if (k < b->wn) {
    uint64_t w = b->bits[k >> 6] & ((((uint64_t)1) << (k & 63)) - 1);
    uint32_t p = b->pos[b->cnt[k >> 6] + lsys_popcount64(w)];
    if (p != NONE) return p;
  }
  return lsys_context_farpartner(v, j);
}

/* The offset of module j's first parameter (a string with parameters). */
static inline size_t lsys_view_poff (const view *v, size_t j) {
  const lsys_brkwin *b = v->match;
  size_t k = j - b->wa;
  return k <= b->wn && b->withp ? b->poff[k] : lsys_context_farpoff(v, j);
}

/* Builds the string's part of the context tables of 's' in m->brk (within
** the model's memory budget): LSYS_OK, LSYS_ELIMIT, LSYS_ENOMEM or
** LSYS_EMEMORY. */
int lsys_context_buildtables (lsys_rules *m, const lsys_lstring *s);

/* Makes 'w' the window of view v's modules [a, b) and their margins (v->match
** is w or becomes it): LSYS_OK or LSYS_ENOMEM. lsys_context_ensure makes the
** calling thread's window hold module i, a window of the next modules when
** it does not. */
int lsys_context_window (lsys_brkwin *w, const lsys_brk *g, const view *v, size_t a, size_t b);
int lsys_context_ensure (view *v, size_t i);
void lsys_context_freewin (lsys_brkwin *w);
size_t lsys_context_winbytes (const lsys_brkwin *w);

/* Module j's code in the view, of either representation. */
static inline uint16_t lsys_view_code (const view *v, size_t j) {
  return v->code8 != NULL ? (uint16_t)LSYS_CODE(v->code8[j], 0) : v->code[j];
}

/* The symbol of '=' in the model's alphabet, or NONE. */
uint32_t lsys_context_eqsym (const lsys_rules *m);

/* The modules a context of plain pattern modules (no brackets, no '=')
** compares with, found once for a module and its rules: the nearest NMEMO
** on each side, found as the rules ask for them. */
#define LSYS_NMEMO 8
typedef struct lsys_ctxmemo {
  int nl, nr;                  /* found so far */
  int lend, rend;              /* no more on that side */
  size_t l[LSYS_NMEMO], r[LSYS_NMEMO];
} lsys_ctxmemo;

static inline void lsys_context_memo_init (lsys_ctxmemo *mm) {
  mm->nl = mm->nr = mm->lend = mm->rend = 0;
}

/* The module a left context's plain pattern module compares with, scanning
** left from j (-1: none), and a right context's, scanning right from j (v->n:
** none); not for rings. */
long long lsys_context_leftof (const view *v, long long j);
/* Fills k's tables of what the scans do at each symbol below 256. */
void lsys_context_classes (lsys_skip *k);
size_t lsys_context_rightof (const view *v, size_t j);

/* Whether rule r's left context matches before module i, and its right
** context from module j; they write the contexts' parameters into 'args'
** (left) and 'a' (right). 'mm' (or NULL) keeps what the scans found for
** module i's other rules (the right context's only from j = i + 1). */
int lsys_context_matchleft (const lsys_rules *m, const view *v, size_t i, const lsys_rule *r,
                            double *args, lsys_ctxmemo *mm);
int lsys_context_matchright (const lsys_rules *m, const view *v, size_t j, const lsys_rule *r,
                             double *a, lsys_ctxmemo *mm);

#endif
