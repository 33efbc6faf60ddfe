/*
** The productions of a derivation step on several threads (derive_impl.h;
** docs/architecture.md, "The parallel step").
**
** A step is count, prefix sum, fill. The source string is cut into chunks at
** module boundaries; worker threads take chunks in turn and count the
** modules and parameters of their successors; a prefix sum over the chunks
** gives each chunk its place in the new string, which is allocated once at
** its exact size; the workers then fill their chunks, each from its end. A
** module is rewritten the same way on every thread: the rule chosen, the
** expression machine's values and the generator's numbers depend only on the
** module and its position (rng.h), so the string is the same for every
** number of threads, and the same as the sequential step's (derive.c), which
** runs instead whenever the step needs what only the calling thread may do:
** a rule that calls back into Lua, a cut or a sub-L-system (they change how
** the modules after them are rewritten), a predecessor of several modules,
** or an error message (the sequential step finds the module it names).
**
** Memory. The new string is narrow (lstring.h: a byte a module) when no
** module of it has parameters. When the caller rewrites a string in place
** (derive's own strings) and no successor is shorter than its module (in
** modules and in parameters), the string grows to its new size and every
** chunk is filled from its end: a module's successor then starts at or after
** the module, so a chunk overwrites only modules already rewritten, its own
** or those of the chunks after it, which it waits for.
*/
#ifdef __linux__
#define _GNU_SOURCE             /* sched_getaffinity, CPU_COUNT */
#include <sched.h>
#endif
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "derive_impl.h"

#define MAXCHUNKS 256
#define CHUNKMIN 2048             /* modules: smaller chunks cost more than they share */

#define NFAST 4                   /* rules of a symbol of class PC_FAST, at most */
#define NORULE 0xFFFF             /* no rule (a copy) */
#define NCTAB 16                  /* symbols of class PC_CTAB, at most */
#define CTN 257                   /* a context table's side: symbols below 256, and none */

/* What a worker does with a module of a symbol. */
enum {
  PC_COPY,      /* no rule: copied */
  PC_PLAIN,     /* one rule that always applies: its template */
  PC_VM,        /* one rule on the expression machine, no condition */
  PC_VMC,       /* the same with a condition */
  PC_FAST,      /* up to NFAST rules without contexts or weights, each a program of
                ** lsys_expr_fast's form (or a template): the first that applies */
  PC_CTAB,      /* rules of templates with a context of at most one module each side,
                ** of symbols without parameters: the rule by those two symbols */
  PC_GEN,       /* contexts, weights, several rules, groups: lsys_derive_choose */
  PC_SEQ        /* the sequential step must run */
};

/* What a symbol's modules become: the rule (when one) whose successor has
** 'nsucc' modules and 'nsrc' parameters for modules of 'pnp' parameters
** (NOPNP: none of PC_PLAIN or PC_VM); modules of other counts are copied. */
typedef struct pent {
  uint8_t cls, pnp, nar;      /* nar: the rule's successor fits a narrow string */
  uint8_t fl;                 /* what the rule's successor asks of the string (FL_*) */
  uint8_t pargs;              /* the successor takes parameters of the module's own */
  uint32_t nsucc, nsrc, rule;
  const uint16_t *t;
  const uint8_t *t8;          /* the template as symbols (when nar) */
  lsys_xfast fx;              /* PC_VM: the values without the stack machine (fx.ok) */
  uint32_t nfr, fr[NFAST];    /* PC_FAST: the rules, in the order they are tried */
  uint16_t *ctab;             /* PC_CTAB: the rule (or NORULE) by left and right symbol */
} pent;

#define NOPNP 0xFF

/* What a module's successor asks of the new string (chunk flags). */
enum { FL_WIDE = 1, FL_GEN = 2, FL_SHRINK = 4 };

#define CW_SLOW ((uint64_t)1 << 63)
#define CW(n, np, fl) ((uint64_t)(n) | (uint64_t)(np) << 24 | (uint64_t)(fl) << 48)

/* The modules of a narrow string, by symbol: copied (NK_COPY), replaced by
** a template of at most NTPL symbols that fits a narrow string (NK_TPL), or
** the general path (NK_SLOW). */
enum { NK_COPY, NK_TPL, NK_SLOW };
#define NTPL 32

/* A chunk's choices: what counting found for each module of class PC_GEN
** (its rule, NORULE when it is copied, and the parameters of its successor),
** so that filling writes them without choosing again. */
typedef struct gcache {
  uint16_t *rid; size_t rcap;
  double *par; size_t pcap;
} gcache;


/* The workers' scratch, kept by the model between steps. */
typedef struct lsys_par {
  lsys_scratch ws[LSYS_MAXTHREADS];
  gcache gc[MAXCHUNKS];       /* by chunk; sized from the step before (gneed*) */
  size_t gneedr, gneedp;      /* the most choices and parameters a chunk needed */
  pent *pe; size_t npe;       /* per symbol */
  uint8_t *t8; size_t nt8;    /* m->tcode as symbols */
  uint8_t *rnar; size_t nrnar;  /* per rule: its successor fits a narrow string */
  lsys_xfast *rfx; size_t nrfx; /* per rule: its program without the stack machine */
  uint16_t *ctab;             /* NCTAB tables of CTN * CTN rules (PC_CTAB) */
  uint8_t nkind[256], nlen[256];
  uint64_t wcount[256 << LSYS_NPBITS];  /* codes of symbols below 256: CW_SLOW, or the
                              ** successor's modules, parameters << 24 and FL_* << 48 */
  uint8_t ntpl[256][NTPL];    /* NK_TPL: the template at the end (filling goes backwards) */
} lsys_par;

typedef struct chunk {
  size_t a, b;                /* source modules [a, b) */
  size_t sp, nsp;             /* its first parameter, its parameters */
  size_t cnt, pcnt;           /* modules and parameters of its successors */
  size_t o, po;               /* where they go in the new string */
  size_t lo;                  /* filling: modules [lo, b) are written */
  size_t fail;                /* filling: the module whose values failed, or SIZE_MAX */
  int bad, wide, gen, shrink; /* counting: failed; needs a wide string; lsys_derive_choose ran; a
                              ** successor shorter than its module */
  size_t nr, npc;             /* choices kept in the chunk's gcache: entries, parameters */
  size_t upto;                /* modules [a, upto) have their choices kept */
  size_t needr, needp;        /* the choices and parameters the whole chunk had */
} chunk;

enum { PH_NP, PH_COUNT, PH_FILL };

typedef struct job {
  lsys_rules *m;
  const uint16_t *code;       /* the source: wide, */
  const uint8_t *code8;       /* or narrow */
  const double *spar;
  lsys_lstring *out;
  const view *v;
  lsys_ruleset *const *sets;
  int nsets, phase, withnp, narrow, inplace, keep;   /* keep: choices go in gcaches */
  const lsys_par *P;
  lsys_rng rng;               /* each worker draws from a copy */
  chunk ch[MAXCHUNKS];
  atomic_int done[MAXCHUNKS]; /* filling in place: chunk written */
  atomic_int stop;
  size_t nch;
  atomic_size_t next;
} job;

typedef struct worker { job *j; lsys_scratch *w; lsys_rng rng; pthread_t t; } worker;

static const double nopar[1];

void lsys_derive_par_free (lsys_rules *m) {
  int k;
  if (m->par == NULL) return;
  for (k = 0; k < LSYS_MAXTHREADS; k++) {
    LSYS_FREE(m->par->ws[k].args);
    LSYS_FREE(m->par->ws[k].alt);
  }
  for (k = 0; k < MAXCHUNKS; k++) {
    LSYS_FREE(m->par->gc[k].rid);
    LSYS_FREE(m->par->gc[k].par);
  }
  LSYS_FREE(m->par->pe);
  LSYS_FREE(m->par->t8);
  LSYS_FREE(m->par->rnar);
  LSYS_FREE(m->par->rfx);
  LSYS_FREE(m->par->ctab);
  LSYS_FREE(m->par);
  m->par = NULL;
}

size_t lsys_derive_par_bytes (const lsys_rules *m) {
  size_t k, n = 0;
  if (m->par == NULL) return 0;
  for (k = 0; k < MAXCHUNKS; k++)
    n += m->par->gc[k].rcap * sizeof *m->par->gc[k].rid +
         m->par->gc[k].pcap * sizeof *m->par->gc[k].par;
  return n;
}

int lsys_derive_default_threads (void) {
  static atomic_int cached;
  int n = atomic_load(&cached);
  const char *e;
  if (n > 0) return n;
  e = getenv("LSYS_THREADS");
  if (e != NULL && *e != '\0') {
    char *end;
    long x = strtol(e, &end, 10);
    if (*end == '\0' && x >= 1) n = x > LSYS_MAXTHREADS ? LSYS_MAXTHREADS : (int)x;
  }
  if (n <= 0) {
#ifdef __linux__
    cpu_set_t cs;
    if (sched_getaffinity(0, sizeof cs, &cs) == 0) n = CPU_COUNT(&cs);
#endif
    if (n <= 0) {
      long c = sysconf(_SC_NPROCESSORS_ONLN);
      n = c > 0 ? (c > LSYS_MAXTHREADS ? LSYS_MAXTHREADS : (int)c) : 1;
    }
    if (n > LSYS_MAXTHREADS) n = LSYS_MAXTHREADS;
  }
  atomic_store(&cached, n);
  return n;
}

static inline uint16_t srccode (const job *j, size_t i) {
  return j->code8 != NULL ? (uint16_t)LSYS_CODE(j->code8[i], 0) : j->code[i];
}

/* Whether rule r runs without the callback, as one module. */
static int cruns (const lsys_rule *r) {
  return r->nmore == 0 && !(r->flags & LSYS_RF_DYN) && (r->vm != NULL || !(r->flags & LSYS_RF_CALL));
}

/* Whether rule r draws random numbers (ran, nran and what is made of them). */
static int draws (const lsys_rule *r) {
  int k;
  for (k = 0; k < r->nvm; k++)
    if (r->vm[k].op == LSYS_OP_RAN || r->vm[k].op == LSYS_OP_NRAN) return 1;
  return 0;
}

static int hascond (const lsys_rule *r) {
  int k;
  for (k = 0; k < r->nvm; k++)
    if (r->vm[k].op == LSYS_OP_COND) return 1;
  return 0;
}

/* Grows an array of bytes to at least n. */
static int bytes (uint8_t **p, size_t *cap, size_t n) {
  if (*cap >= n) return 1;
  LSYS_FREE(*p);
  *cap = 0;
  if ((*p = (uint8_t *)LSYS_MALLOC(n)) == NULL) return 0;
  *cap = n;
  return 1;
}

/* The templates as symbols, whether each rule's successor fits a narrow
** string, and the workers' scratch, large enough that filling never
** allocates (lsys_derive_choose included). */
static int prepare (lsys_rules *m, lsys_par *P, int nt) {
  size_t k, nargs = 1, nalt = 1;
  uint32_t q;
  if (!bytes(&P->t8, &P->nt8, m->ntcode + 1) || !bytes(&P->rnar, &P->nrnar, m->nrules + 1))
    return 0;
  if (P->nrfx < m->nrules + 1) {
    LSYS_FREE(P->rfx);
    P->nrfx = 0;
    if ((P->rfx = (lsys_xfast *)LSYS_MALLOC((m->nrules + 1) * sizeof *P->rfx)) == NULL) return 0;
    P->nrfx = m->nrules + 1;
  }
  for (k = 0; k < m->ntcode; k++) P->t8[k] = (uint8_t)LSYS_CSYM(m->tcode[k]);
  for (k = 0; k < m->nrules; k++) {
    const lsys_rule *r = &m->rules[k];
    int nar = r->nsrc == 0;
    for (q = 0; q < r->nsucc && nar; q++) {
      uint16_t c = m->tcode[r->succ + q];
      nar = LSYS_CNP(c) == 0 && LSYS_CSYM(c) < 256;
    }
    P->rnar[k] = (uint8_t)nar;
    memset(&P->rfx[k], 0, sizeof P->rfx[k]);
    if (r->vm != NULL) lsys_expr_fast(r->vm, r->nvm, &P->rfx[k]);
    else P->rfx[k].ok = !(r->flags & (LSYS_RF_CALL | LSYS_RF_DYN));     /* a template */
    if (P->rfx[k].ok && P->rfx[k].n != (int)r->nvals) P->rfx[k].ok = 0;
    if (r->nargs + r->nvals + 1 > nargs) nargs = r->nargs + r->nvals + 1;
    nalt += ALTHEAD + r->nargs + r->nvals;
  }
  for (k = 0; k < (size_t)nt; k++) {
    lsys_scratch *w = &P->ws[k];
    w->worker = 1;
    if (lsys_derive_needscratch(w, nargs) != LSYS_OK ||
        (w->altcap < nalt && lsys_common_grow((void **)&w->alt, &w->altcap, nalt, sizeof *w->alt)
                             != LSYS_OK))
      return 0;
  }
  return 1;
}

/* Whether pattern module pm is one a context table can hold: a symbol below
** 256 without parameters that is neither a bracket nor '='. */
static int ctsym (const lsys_patmod *pm, uint32_t eq) {
  return pm->np == 0 && pm->sym < 256 && pm->sym != LSYS_SYM_LBR &&
         pm->sym != LSYS_SYM_RBR && pm->sym != eq;
}

/* Makes symbol k's context table in e->ctab when its rules allow one (all of
** them templates, not weighted, for modules without parameters, with at most
** one plain module of context each side) and there is room for one more:
** the first rule that applies for each pair of neighbours, the rules tried
** in the order lsys_derive_choose tries them. */
static int ctabfor (lsys_rules *m, lsys_ruleset *const *sets, int nsets, uint32_t k,
                    int *nctab, pent *e) {
  lsys_par *P = m->par;
  uint32_t eq = lsys_context_eqsym(m), b, l, r;
  uint16_t *t;
  int si;
  if (k >= 256 || *nctab >= NCTAB || m->ring || m->nrules >= NORULE) return 0;
  for (si = 0; si < nsets; si++) {
    const lsys_ruleset *s = sets[si];
    if (s == NULL || k >= s->nsym) continue;
    for (b = s->start[k]; b < s->start[k + 1]; b++) {
      const lsys_rule *ru = &m->rules[s->byp[b]];
      if (ru->vm != NULL || (ru->flags & (LSYS_RF_STOCH | LSYS_RF_CALL | LSYS_RF_DYN)) ||
          ru->nmore || ru->pred_np != 0 || ru->nlc > 1 || ru->nrc > 1 ||
          (ru->nlc && !ctsym(&m->pat[ru->lc], eq)) || (ru->nrc && !ctsym(&m->pat[ru->rc], eq)))
        return 0;
    }
  }
  if (P->ctab == NULL &&
      (P->ctab = (uint16_t *)LSYS_MALLOC((size_t)NCTAB * CTN * CTN * sizeof *P->ctab)) == NULL)
    return 0;
  t = P->ctab + (size_t)*nctab * CTN * CTN;
  for (l = 0; l < CTN * CTN; l++) t[l] = NORULE;
  for (si = nsets; si-- > 0;) {          /* the last rule first: the first one tried */
    const lsys_ruleset *s = sets[si];      /* is written last */
    if (s == NULL || k >= s->nsym) continue;
    for (b = s->start[k + 1]; b-- > s->start[k];) {
      const lsys_rule *ru = &m->rules[s->byp[b]];
      uint32_t l0 = ru->nlc ? m->pat[ru->lc].sym : 0, l1 = ru->nlc ? l0 + 1 : CTN;
      uint32_t r0 = ru->nrc ? m->pat[ru->rc].sym : 0, r1 = ru->nrc ? r0 + 1 : CTN;
      for (l = l0; l < l1; l++)
        for (r = r0; r < r1; r++) t[l * CTN + r] = (uint16_t)s->byp[b];
    }
  }
  e->ctab = t;
  (*nctab)++;
  return 1;
}

/*
** The class of every symbol (as the sequential step's fast loop, derive.c's
** fasttable, with rules on the expression machine and contexts besides).
** Returns 0 when a rule of the sets needs the calling thread, else 1 with
** *needsp set when counting reads parameters and *genp when a symbol is of
** class PC_GEN.
*/
static int classify (lsys_rules *m, lsys_ruleset *const *sets, int nsets, int *needsp,
                     int *genp) {
  lsys_par *P = m->par;
  uint32_t k, n = m->ab->n;
  int si, nctab = 0;
  *needsp = *genp = 0;
  if (P->npe < n) {
    LSYS_FREE(P->pe);
    P->npe = 0;
    if ((P->pe = (pent *)LSYS_MALLOC(n * sizeof *P->pe)) == NULL) return 0;
    P->npe = n;
  }
  for (si = 0; si < nsets && m->cpfg; si++)    /* cpfg's numbers come in the order of a */
    if (sets[si] != NULL && sets[si]->stoch) return 0;     /* scan: rules that draw them too */
  for (k = 0; k < n; k++) {
    uint32_t nr = 0, b, q, first = NONE;
    int fast = 1;
    pent *e = &P->pe[k];
    memset(e, 0, sizeof *e);
    for (si = 0; si < nsets; si++) {
      const lsys_ruleset *s = sets[si];
      if (s == NULL || k >= s->nsym) continue;
      for (b = s->start[k]; b < s->start[k + 1]; b++) {
        const lsys_rule *r = &m->rules[s->byp[b]];
        if (!cruns(r) || (m->cpfg && draws(r))) return 0;
        if (first == NONE) first = s->byp[b];
        if (nr < NFAST) e->fr[nr] = s->byp[b];
        if (r->nlc || r->nrc || (r->flags & LSYS_RF_STOCH) || !P->rfx[s->byp[b]].ok) fast = 0;
        nr++;
      }
    }
    e->pnp = NOPNP;
    e->rule = first;
    if (k == LSYS_SYM_CUT || k == LSYS_SYM_SUB) e->cls = PC_SEQ;
    else if (nr == 0) e->cls = PC_COPY;
    else {
      const lsys_rule *r = &m->rules[first];
      int simple = nr == 1 && r->nlc == 0 && r->nrc == 0 && !(r->flags & LSYS_RF_STOCH);
      if (simple && r->vm == NULL) e->cls = PC_PLAIN;
      else if (simple && !hascond(r)) e->cls = PC_VM;
      else if (fast && nr <= NFAST) e->cls = PC_FAST;
      else if (ctabfor(m, sets, nsets, k, &nctab, e)) e->cls = PC_CTAB;
      else if (simple) e->cls = PC_VMC;
      else e->cls = PC_GEN;
      e->nfr = e->cls == PC_FAST ? nr : 0;
      if (e->cls == PC_PLAIN || e->cls == PC_VM) {
        e->pnp = (uint8_t)r->pred_np;
        e->nsucc = r->nsucc;
        e->nsrc = r->nsrc;
        e->t = m->tcode + r->succ;
        e->t8 = P->t8 + r->succ;
        e->nar = P->rnar[first];
        for (q = 0; q < r->nsrc && !e->pargs; q++)
          e->pargs = m->tsrc[r->src + q].kind == LSYS_PS_ARG;
        if (e->cls == PC_VM) e->fx = P->rfx[first];
        e->fl = (uint8_t)((e->nar ? 0 : FL_WIDE) |
                          (r->nsucc == 0 || r->nsrc < r->pred_np ? FL_SHRINK : 0));
      }
    }
    if (e->cls == PC_VMC || e->cls == PC_FAST || e->cls == PC_CTAB || e->cls == PC_GEN)
      *needsp = 1;
    if (e->cls == PC_GEN) *genp = 1;
    if (k < 256) {               /* narrow modules; wide ones, counted */
      for (q = 0; q <= LSYS_MAXPARAMS; q++)
        P->wcount[k << LSYS_NPBITS | q] =
          e->pnp == q ? (e->nsucc < (1u << 24) && e->nsrc < (1u << 24) ?
                           CW(e->nsucc, e->nsrc, e->fl) : CW_SLOW)
          : e->cls == PC_COPY || e->cls == PC_PLAIN || e->cls == PC_VM ?
              CW(1, q, q > 0 ? FL_WIDE : 0)
          : CW_SLOW;
      P->nkind[k] = e->cls == PC_COPY || (e->cls == PC_PLAIN && e->pnp != 0) ? NK_COPY
                  : e->cls == PC_PLAIN && e->nar && e->nsucc > 0 && e->nsucc <= NTPL ? NK_TPL
                  : NK_SLOW;
      P->nlen[k] = (uint8_t)(P->nkind[k] == NK_TPL ? e->nsucc : 1);
      if (P->nkind[k] == NK_TPL)
        memcpy(P->ntpl[k] + NTPL - e->nsucc, e->t8, e->nsucc);
    }
  }
  return 1;
}

/* The rule that rewrites module i ('cd', parameters *args; classes PC_VM,
** PC_VMC, PC_FAST and PC_GEN), or NULL when the module is copied; *vals gets its
** values and *args its arguments. Returns -1 when the step must run
** sequentially (a value that is not finite, an error of lsys_derive_choose). */
static int pick (job *j, lsys_scratch *w, size_t i, uint16_t cd, const double **args,
                 const double **vals, const lsys_rule **rule) {
  lsys_rules *m = j->m;
  const pent *e = &j->P->pe[LSYS_CSYM(cd)];
  lsys_pick pk;
  int st;
  *rule = NULL;
  if (e->cls == PC_VM || e->cls == PC_VMC) {   /* (e->rule is NONE for the other classes) */
    const lsys_rule *r = &m->rules[e->rule];
    if (r->pred_np != LSYS_CNP(cd)) return 0;
    lsys_rng_at(w->rng, i);
    if (!lsys_expr_run(r->vm, r->nvm, *args, w->args, w->rng, m->funcs)) return 0;
    if (lsys_derive_checkvals(m, w, r, i, w->args) != LSYS_OK) return -1;
    *vals = w->args;
    *rule = r;
    return 0;
  }
  if (e->cls == PC_FAST) {
    uint32_t q;
    for (q = 0; q < e->nfr; q++) {
      const lsys_rule *r = &m->rules[e->fr[q]];
      if (r->pred_np != LSYS_CNP(cd) || !lsys_expr_runfast(&j->P->rfx[e->fr[q]], *args, w->args))
        continue;
      if (lsys_derive_checkvals(m, w, r, i, w->args) != LSYS_OK) return -1;
      *vals = w->args;
      *rule = r;
      return 0;
    }
    return 0;
  }
  if (e->cls == PC_CTAB) {              /* the neighbours' symbols: 256 when none */
    const view *v = j->v;
    long long l = lsys_context_leftof(v, (long long)i - 1);
    size_t r = lsys_context_rightof(v, i + 1);
    uint32_t ls = l < 0 ? 256 : LSYS_CSYM(lsys_view_code(v, (size_t)l));
    uint32_t rs = r >= v->n ? 256 : LSYS_CSYM(lsys_view_code(v, r));
    uint16_t id;
    if (LSYS_CNP(cd) != 0) return 0;
    if (l >= 0 && LSYS_CNP(lsys_view_code(v, (size_t)l)) != 0) ls = 256;  /* never a pattern's */
    if (r < v->n && LSYS_CNP(lsys_view_code(v, r)) != 0) rs = 256;
    if (ls > 256) ls = 256;
    if (rs > 256) rs = 256;
    id = e->ctab[ls * CTN + rs];
    if (id != NORULE) *rule = &m->rules[id];
    return 0;
  }
  if (e->cls != PC_GEN) return -1;
  lsys_rng_at(w->rng, i);
  st = lsys_derive_choose(m, w, j->sets, j->nsets, j->v, i, cd, *args, &pk);
  if (st < 0 || st > 1 || (st == 1 && pk.dyn != NULL)) return -1;
  if (st == 1) { *rule = pk.r; *args = pk.args; *vals = pk.vals; }
  return 0;
}

/* Sums the parameters of the chunk's modules. */
static void npchunk (job *j, chunk *c) {
  size_t i, nsp = 0;
  for (i = c->a; i < c->b; i++) nsp += LSYS_CNP(j->code[i]);
  c->nsp = nsp;
}

/* The parameters of rule r's successor (arguments 'args', values 'vals') into op. */
static void succpar (const lsys_rules *m, const lsys_rule *r, const double *args,
                     const double *vals, double *op) {
  uint32_t k;
  for (k = 0; k < r->nsrc; k++) {   /* (no parameter sources at all: m->tsrc is NULL) */
    const lsys_psrc *ps = &m->tsrc[r->src + k];
    double x = ps->kind == LSYS_PS_CONST ? ps->value :
               ps->kind == LSYS_PS_ARG ? args[ps->idx] : vals[ps->idx];
    op[k] = m->f32 ? lsys_round32(x) : x;
  }
}

/* Keeps the choice for module i of class PC_GEN in the chunk's gcache, while
** there is room: the first that finds none sets c->upto, and filling
** chooses again from there on. */
static void keepchoice (job *j, chunk *c, size_t i, const lsys_rule *r, const double *args,
                        const double *vals) {
  const lsys_rules *m = j->m;
  const gcache *g = &j->P->gc[c - j->ch];
  uint32_t nsrc = r != NULL ? r->nsrc : 0;
  c->needr++;
  c->needp += nsrc;
  if (c->upto < c->b) return;
  if (c->nr >= g->rcap || g->pcap - c->npc < nsrc) {
    c->upto = i;
    return;
  }
  g->rid[c->nr++] = r != NULL ? (uint16_t)(r - m->rules) : NORULE;
  if (nsrc > 0) succpar(m, r, args, vals, g->par + c->npc);
  c->npc += nsrc;
}

/* Counts module i (parameters from 'sp') the general way: adds to *cnt,
** *pcnt and *fl. Returns 0 when the step must run sequentially. */
static int countslow (job *j, lsys_scratch *w, chunk *c, size_t i, uint16_t cd, size_t sp,
                      size_t *cnt, size_t *pcnt, int *fl) {
  uint32_t np = LSYS_CNP(cd);
  const pent *e = &j->P->pe[LSYS_CSYM(cd)];
  const double *args = j->spar + sp, *vals = NULL;
  const lsys_rule *r;
  if (e->cls <= PC_VM && e->pnp != np) r = NULL;        /* a copy */
  else if (pick(j, w, i, cd, &args, &vals, &r) < 0) return 0;
  if (e->cls == PC_GEN) {
    *fl |= FL_GEN;
    if (j->keep) keepchoice(j, c, i, r, args, vals);
  }
  if (r != NULL) {
    *cnt += r->nsucc;
    *pcnt += r->nsrc;
    if (!j->P->rnar[r - j->m->rules]) *fl |= FL_WIDE;
    if (r->nsucc == 0 || r->nsrc < np) *fl |= FL_SHRINK;
  }
  else {
    *cnt += 1;
    *pcnt += np;
    if (np > 0 || LSYS_CSYM(cd) > 255) *fl |= FL_WIDE;
  }
  return 1;
}

/* Counts the modules and parameters of the chunk's successors (and its
** parameters, when the job says so), and what the string they make needs. */
static void countchunk (job *j, lsys_scratch *w, chunk *c) {
  const pent *pe = j->P->pe;
  size_t i, sp = c->sp, cnt = 0, pcnt = 0;
  int fl = 0;
  c->nr = c->npc = c->needr = c->needp = 0;
  c->upto = c->b;
  if (j->code8 != NULL) {                 /* narrow: no parameters */
    const uint8_t *code8 = j->code8, *nkind = j->P->nkind, *nlen = j->P->nlen;
    for (i = c->a; i < c->b; i++) {
      uint8_t b = code8[i];
      if (nkind[b] != NK_SLOW) cnt += nlen[b];
      else if (!countslow(j, w, c, i, (uint16_t)LSYS_CODE(b, 0), 0, &cnt, &pcnt, &fl)) {
        c->bad = 1;
        return;
      }
    }
  }
  else {
    const uint16_t *code = j->code;
    const uint64_t *wcount = j->P->wcount;
    for (i = c->a; i < c->b; i++) {
      uint16_t cd = code[i];
      uint32_t np = LSYS_CNP(cd);
      const pent *e;
      if (cd < (256 << LSYS_NPBITS) && !(wcount[cd] & CW_SLOW)) {    /* the usual case */
        uint64_t x = wcount[cd];
        cnt += x & 0xFFFFFF;
        pcnt += (x >> 24) & 0xFFFFFF;
        fl |= (int)(x >> 48);
        sp += np;
        continue;
      }
      e = &pe[LSYS_CSYM(cd)];
      if (e->pnp == np) {                 /* a rule that always applies */
        cnt += e->nsucc;
        pcnt += e->nsrc;
        fl |= e->fl;
      }
      else if (e->cls == PC_COPY) {
        cnt++;
        pcnt += np;
        fl |= np > 0 || LSYS_CSYM(cd) > 255;
      }
      else if (!countslow(j, w, c, i, cd, sp, &cnt, &pcnt, &fl)) {
        c->bad = 1;
        return;
      }
      sp += np;
    }
  }
  c->cnt = cnt;
  c->pcnt = pcnt;
  c->wide = fl & FL_WIDE;
  c->gen = (fl & FL_GEN) != 0;
  c->shrink = (fl & FL_SHRINK) != 0;
  if (j->withnp) c->nsp = sp - c->sp;
}

/* Writes the successor of rule r (arguments 'args', values 'vals') at oc, op. */
static void put (const lsys_rules *m, const lsys_rule *r, const double *args,
                 const double *vals, uint16_t *oc, double *op) {
  const uint16_t *t = m->tcode + r->succ;
  uint32_t k;
  for (k = 0; k < r->nsucc; k++) oc[k] = t[k];
  succpar(m, r, args, vals, op);
}

/* A module's values failed (or the chunk went wrong, 'bad'): every worker
** stops; modules [i + 1, b) of the chunk are written. */
static void halt (job *j, chunk *c, size_t i, int bad) {
  if (bad) c->bad = 1;
  else c->fail = i;
  c->lo = i + 1;
  atomic_store(&j->stop, 1);
}

/* The output of a chunk being filled, from its end: codes down to o0,
** parameters down to p0. */
typedef struct wout {
  uint16_t *o0, *oc; double *p0, *op;
  const uint16_t *rid; const double *cp;   /* the chunk's kept choices, */
  size_t nr, npc, upto;                    /* taken from the end */
} wout;

/* Sets the cursor of the choices kept for chunk c (none when not kept). */
static void keptchoices (const job *j, const chunk *c, wout *o) {
  const gcache *g = &j->P->gc[c - j->ch];
  o->rid = g->rid; o->cp = g->par;
  o->nr = c->nr; o->npc = c->npc;
  o->upto = j->keep ? c->upto : c->a;
}

/* The kept choice of module i of class PC_GEN: 1 with *r (NULL: a copy) and
** *kp, the successor's parameters; 0 when it was not kept. */
static int kept (wout *o, const lsys_rules *m, size_t i, const lsys_rule **r,
                 const double **kp) {
  uint16_t id;
  if (i >= o->upto || o->nr == 0) return 0;
  id = o->rid[--o->nr];
  *r = id == NORULE ? NULL : &m->rules[id];
  if (*r != NULL) o->npc -= (*r)->nsrc;
  *kp = o->cp + o->npc;
  return 1;
}

/* Writes the successor of module i (parameters at 'args') the general way.
** Returns 1, 0 when its values failed, -1 when it does not fit (a bug). */
static int fillslow (job *j, lsys_scratch *w, wout *o, size_t i, uint16_t cd,
                     const double *args) {
  const lsys_rules *m = j->m;
  uint32_t np = LSYS_CNP(cd), k;
  const pent *e = &j->P->pe[LSYS_CSYM(cd)];
  const lsys_rule *r = NULL;
  const double *vals = NULL;
  const double *kp;
  double a[LSYS_MAXPARAMS];
  if (e->pnp == np && e->cls == PC_PLAIN) r = &m->rules[e->rule];
  else if (e->cls == PC_GEN && kept(o, m, i, &r, &kp)) {
    if (r != NULL) {                               /* counting chose it */
      if ((size_t)(o->oc - o->o0) < r->nsucc || (size_t)(o->op - o->p0) < r->nsrc) return -1;
      o->oc -= r->nsucc;
      o->op -= r->nsrc;
      memcpy(o->oc, m->tcode + r->succ, r->nsucc * sizeof *o->oc);
      if (r->nsrc > 0) memcpy(o->op, kp, r->nsrc * sizeof *o->op);
      return 1;
    }
  }
  else if (e->cls > PC_PLAIN && pick(j, w, i, cd, &args, &vals, &r) < 0) return 0;
  if (r == NULL) {                                               /* a copy */
    if (o->oc == o->o0 || (size_t)(o->op - o->p0) < np) return -1;
    *--o->oc = cd;
    o->op -= np;
    for (k = np; k-- > 0;) o->op[k] = args[k];      /* from the end: op >= args */
    return 1;
  }
  if ((size_t)(o->oc - o->o0) < r->nsucc || (size_t)(o->op - o->p0) < r->nsrc) return -1;
  if (j->inplace && np > 0 && e->cls != PC_GEN) {  /* the module's own parameters may be */
    memcpy(a, args, np * sizeof *a);              /* where its successor's go */
    args = a;
  }
  o->oc -= r->nsucc;
  o->op -= r->nsrc;
  put(m, r, args, vals, o->oc, o->op);
  return 1;
}

/* Writes the chunk's successors into a wide string, from its end. */
static void fillwide (job *j, lsys_scratch *w, chunk *c) {
  const pent *pe = j->P->pe;
  const double *spar = j->spar;
  wout o;
  size_t i, sp = c->sp + c->nsp;
  int st;
  o.o0 = j->out->code + c->o;
  o.oc = o.o0 + c->cnt;
  o.p0 = j->out->par + c->po;
  o.op = o.p0 + c->pcnt;
  keptchoices(j, c, &o);
  for (i = c->b; i-- > c->a;) {
    uint16_t cd = srccode(j, i);
    uint32_t np = LSYS_CNP(cd), k;
    const pent *e = &pe[LSYS_CSYM(cd)];
    sp -= np;
    if (e->cls == PC_COPY && o.oc > o.o0 && (size_t)(o.op - o.p0) >= np) {   /* a copy */
      const double *q = spar + sp;
      *--o.oc = cd;
      o.op -= np;
      for (k = np; k-- > 0;) o.op[k] = q[k];        /* from the end: op >= q */
      continue;
    }
    if (e->pnp == np && e->cls == PC_PLAIN && e->nsrc == 0 &&
        (size_t)(o.oc - o.o0) >= e->nsucc) {                       /* a template */
      const uint16_t *t = e->t;
      uint32_t n = e->nsucc;
      o.oc -= n;
      for (k = 0; k < n; k++) o.oc[k] = t[k];
      continue;
    }
    if (e->pnp == np && e->cls == PC_VM && (size_t)(o.oc - o.o0) >= e->nsucc &&
        (size_t)(o.op - o.p0) >= e->nsrc) {           /* the expression machine, no condition */
      const lsys_rule *r = &j->m->rules[e->rule];
      const double *args = spar + sp;
      double a[LSYS_MAXPARAMS];
      uint32_t v;
      if (j->inplace && e->pargs) {       /* its own parameters may be where its successor's go */
        for (k = 0; k < np; k++) a[k] = args[k];
        args = a;
      }
      if (e->fx.ok && !e->fx.cond) lsys_expr_runfast(&e->fx, args, w->args);
      else {
        lsys_rng_at(w->rng, i);
        lsys_expr_run(r->vm, r->nvm, args, w->args, w->rng, j->m->funcs);
      }
      for (v = 0; v < r->nvals && isfinite(w->args[v]); v++) {}
      if (v < r->nvals) { halt(j, c, i, 0); return; }
      o.oc -= e->nsucc;
      o.op -= e->nsrc;
      put(j->m, r, args, w->args, o.oc, o.op);
      continue;
    }
    if ((i & 1023) == 0 && atomic_load_explicit(&j->stop, memory_order_relaxed)) {
      c->lo = i + 1;
      return;
    }
    if ((st = fillslow(j, w, &o, i, cd, spar + sp)) <= 0) {
      halt(j, c, i, st < 0);
      return;
    }
  }
  if (o.oc != o.o0 || o.op != o.p0) { halt(j, c, c->a, 1); return; }
  c->lo = c->a;
}

/* Writes the chunk's successors into a narrow string, from its end. */
static void fillnarrow (job *j, lsys_scratch *w, chunk *c) {
  const lsys_par *P = j->P;
  const pent *pe = P->pe;
  const uint8_t *code8 = j->code8;
  uint8_t *base = j->out->sym8, *o0 = base + c->o, *oc = o0 + c->cnt;
  size_t i, sp = c->sp + c->nsp;
  wout ko;
  keptchoices(j, c, &ko);
  for (i = c->b; i-- > c->a;) {
    uint16_t cd;
    if (code8 != NULL) {                  /* narrow to narrow: the usual case */
      uint8_t b = code8[i], kind = P->nkind[b];
      if (kind == NK_COPY && oc > o0) {
        *--oc = b;
        continue;
      }
      if (kind == NK_TPL && (size_t)(oc - o0) >= NTPL && (size_t)(oc - base) >= i + NTPL) {
        memcpy(oc - NTPL, P->ntpl[b], NTPL);   /* what comes before the template is
                             ** written again by the modules before this one */
        oc -= P->nlen[b];
        continue;
      }
    }
    cd = srccode(j, i);
    uint32_t np = LSYS_CNP(cd), k;
    const pent *e = &pe[LSYS_CSYM(cd)];
    const lsys_rule *r = NULL;
    const double *args, *vals = NULL;
    sp -= np;
    if (e->pnp == np && e->cls == PC_PLAIN) {                      /* a template */
      if ((size_t)(oc - o0) < e->nsucc) { halt(j, c, i, 1); return; }
      oc -= e->nsucc;
      for (k = 0; k < e->nsucc; k++) oc[k] = e->t8[k];
      continue;
    }
    if (e->cls == PC_COPY || e->cls == PC_PLAIN) {                 /* a copy */
      if (oc == o0) { halt(j, c, i, 1); return; }
      *--oc = (uint8_t)LSYS_CSYM(cd);
      continue;
    }
    args = j->spar + sp;
    if ((i & 1023) == 0 && atomic_load_explicit(&j->stop, memory_order_relaxed)) {
      c->lo = i + 1;
      return;
    }
    if (e->cls == PC_GEN && kept(&ko, j->m, i, &r, &vals)) {}    /* counting chose it */
    else if (pick(j, w, i, cd, &args, &vals, &r) < 0) { halt(j, c, i, 0); return; }
    if (r == NULL) {
      if (oc == o0) { halt(j, c, i, 1); return; }
      *--oc = (uint8_t)LSYS_CSYM(cd);
      continue;
    }
    if ((size_t)(oc - o0) < r->nsucc) { halt(j, c, i, 1); return; }
    oc -= r->nsucc;
    for (k = 0; k < r->nsucc; k++) oc[k] = j->P->t8[r->succ + k];
  }
  if (oc != o0) { halt(j, c, c->a, 1); return; }
  c->lo = c->a;
}

/* Filling in place: waits until the chunks whose modules chunk c overwrites
** are written. Returns 0 when the workers stop. */
static int await (job *j, size_t c) {
  const chunk *ch = j->ch;
  size_t lim = ch[c].o + ch[c].cnt, plim = ch[c].po + ch[c].pcnt, d;
  for (d = c + 1; d < j->nch && (ch[d].a < lim || ch[d].sp < plim); d++) {
    if (ch[d].b <= ch[c].o && ch[d].sp + ch[d].nsp <= ch[c].po) continue;   /* below it */
    while (!atomic_load_explicit(&j->done[d], memory_order_acquire)) {
      if (atomic_load(&j->stop)) return 0;
      sched_yield();
    }
  }
  return 1;
}

static void *work (void *arg) {
  worker *wk = (worker *)arg;
  job *j = wk->j;
  size_t k;
  wk->w->rng = &wk->rng;
  while ((k = atomic_fetch_add(&j->next, 1)) < j->nch) {
    chunk *ch;
    wk->rng = j->rng;
    if (j->phase == PH_NP) npchunk(j, &j->ch[k]);
    else if (j->phase == PH_COUNT) countchunk(j, wk->w, &j->ch[k]);
    else {                                 /* the last chunk first */
      ch = &j->ch[j->nch - 1 - k];
      if (atomic_load(&j->stop) || (j->inplace && !await(j, j->nch - 1 - k))) continue;
      if (j->narrow) fillnarrow(j, wk->w, ch);
      else fillwide(j, wk->w, ch);
      if (ch->lo == ch->a) atomic_store_explicit(&j->done[j->nch - 1 - k], 1, memory_order_release);
    }
  }
  return NULL;
}

/* Runs a phase over the job's chunks on up to 'nt' threads (the caller's
** one of them). */
static void runphase (job *j, int phase, int nt) {
  worker wk[LSYS_MAXTHREADS];
  int k, started = 1;
  j->phase = phase;
  atomic_store(&j->next, 0);
  if ((size_t)nt > j->nch) nt = (int)j->nch;
  for (k = 0; k < nt; k++) {
    wk[k].j = j;
    wk[k].w = &j->m->par->ws[k];
  }
  for (k = 1; k < nt; k++, started++)      /* no thread for one: the caller works alone */
    if (pthread_create(&wk[k].t, NULL, work, &wk[k]) != 0) break;
  work(&wk[0]);
  for (k = 1; k < started; k++) pthread_join(wk[k].t, NULL);
}

/* Cuts [0, n) into chunks for 'nt' threads. */
static void cut (job *j, size_t n, int nt) {
  size_t nch = (size_t)nt * 8, c;
  if (nch > MAXCHUNKS) nch = MAXCHUNKS;
  if (nch > n / CHUNKMIN) nch = n / CHUNKMIN;
  if (nch < (size_t)nt) nch = (size_t)nt;
  if (nch > n) nch = n > 0 ? n : 1;
  for (c = 0; c < nch; c++) {
    chunk *ch = &j->ch[c];
    memset(ch, 0, sizeof *ch);
    ch->a = n / nch * c + (c < n % nch ? c : n % nch);
    ch->b = ch->a + n / nch + (c < n % nch);
    ch->lo = ch->b;
    ch->fail = (size_t)-1;
    atomic_init(&j->done[c], 0);
  }
  j->nch = nch;
}

/* The totals of the counts and the places of the chunks; *flags gets what
** the chunks need (bit 0 wide, 1 lsys_derive_choose ran, 2 shorter successors).
** Returns 0 when a chunk failed. */
static int prefix (job *j, size_t *n, size_t *np, int *flags) {
  size_t c, o = 0, po = 0;
  *flags = 0;
  for (c = 0; c < j->nch; c++) {
    chunk *ch = &j->ch[c];
    if (ch->bad) return 0;
    ch->o = o; ch->po = po;
    o += ch->cnt; po += ch->pcnt;
    *flags |= ch->wide | ch->gen << 1 | ch->shrink << 2;
  }
  *n = o;
  *np = po;
  return 1;
}

/* The chunks' first parameters, from their counts (PH_NP or counted). */
static void paroffsets (job *j) {
  size_t c, sp = 0;
  for (c = 0; c < j->nch; c++) { j->ch[c].sp = sp; sp += j->ch[c].nsp; }
}

/* Whether the sequential step could certainly hold a string of n modules
** and np parameters within the budget (it grows its arrays by doubling,
** into 'out', and a narrow source is made wide first): only then may this
** step succeed where that one would fail. */
static int roomy (lsys_rules *m, const lsys_lstring *src, lsys_lstring *out, size_t n,
                  size_t np) {
  size_t obytes = lsys_lstring_bytes(out), base, need;
  if (n > m->max_modules) return 0;
  if (src->n > n) n = src->n < m->max_modules ? src->n : m->max_modules;
  if (src->npar > np) np = src->npar;
  base = m->meter.used > obytes ? m->meter.used - obytes : 0;
  if (n > ((size_t)-1 / 16) || np > ((size_t)-1 / 32)) return 0;
  need = 2 * (n * sizeof(uint16_t) + np * sizeof(double)) +
         (src->sym8 != NULL ? src->n * sizeof(uint16_t) : 0);
  return base <= m->meter.limit && need <= m->meter.limit - base;
}

/* Filling in place failed at a module whose values are not finite: its
** message is that of the first such module in the string (the modules
** rewritten so far had none; the others are as they were). */
static int firsterror (job *j) {
  lsys_rules *m = j->m;
  lsys_rng rng = j->rng;
  size_t c, i;
  m->sc.rng = &rng;
  for (c = 0; c < j->nch; c++) {
    const chunk *ch = &j->ch[c];
    size_t sp = ch->sp;
    for (i = ch->a; i < ch->lo; i++) {
      uint16_t cd = srccode(j, i);
      const pent *e = &j->P->pe[LSYS_CSYM(cd)];
      if (e->cls == PC_VM && e->pnp == LSYS_CNP(cd)) {
        const lsys_rule *r = &m->rules[e->rule];
        lsys_rng_at(&rng, i);
        if (lsys_derive_needscratch(&m->sc, r->nvals + 1) != LSYS_OK) return LSYS_ENOMEM;
        if (lsys_expr_run(r->vm, r->nvm, j->spar + sp, m->sc.args, &rng, m->funcs) &&
            lsys_derive_checkvals(m, &m->sc, r, i, m->sc.args) != LSYS_OK)
          return LSYS_ERULE;
      }
      sp += LSYS_CNP(cd);
    }
  }
  return lsys_seterror(&m->err, LSYS_ERULE, (size_t)-1, "a step on several threads failed");
}

/* Room in each chunk's gcache for the choices counting finds, as many a
** module as the chunks of the step before needed (a quarter the first time)
** and a quarter more; none when the budget has no room for it (filling then
** chooses again). */
static void keeproom (job *j, const lsys_lstring *src) {
  lsys_rules *m = j->m;
  lsys_par *P = m->par;
  size_t c, len = j->ch[0].b - j->ch[0].a + 1;
  size_t wr = P->gneedr > 0 ? P->gneedr : len / 4;    /* per chunk of this step's size */
  size_t wp = P->gneedp > 0 || src->npar == 0 ? P->gneedp : len / 4;
  j->keep = m->nrules < NORULE;
  wr += wr / 4 + 16;
  wp += wp > 0 ? wp / 4 + 16 : 0;
  for (c = 0; c < j->nch && j->keep; c++) {
    gcache *g = &P->gc[c];
    if ((g->rcap < wr && !lsys_common_meter_fits(&m->meter, (wr - g->rcap) * sizeof *g->rid)) ||
        (g->pcap < wp && !lsys_common_meter_fits(&m->meter, (wp - g->pcap) * sizeof *g->par)) ||
        lsys_common_grow_metered((void **)&g->rid, &g->rcap, wr, sizeof *g->rid, &m->meter)
          != LSYS_OK ||
        lsys_common_grow_metered((void **)&g->par, &g->pcap, wp, sizeof *g->par, &m->meter)
          != LSYS_OK)
      j->keep = 0;
  }
}

/* What the chunks' gcaches needed, scaled to the next step's string of n
** modules (its chunks are larger by as much). */
static void keptneed (job *j, size_t n) {
  lsys_par *P = j->m->par;
  size_t c, r = 0, p = 0;
  double grow = j->nch > 0 && j->ch[j->nch - 1].b > 0 ? (double)n / j->ch[j->nch - 1].b : 1;
  for (c = 0; c < j->nch; c++) {
    if (j->ch[c].needr > r) r = j->ch[c].needr;
    if (j->ch[c].needp > p) p = j->ch[c].needp;
  }
  if (grow < 1) grow = 1;
  P->gneedr = (size_t)(r * grow);
  P->gneedp = (size_t)(p * grow);
}

/* Counts: the chunks' parameters when counting reads them, then the
** successors. Returns 0 when the step must run sequentially. */
static int count (job *j, const lsys_lstring *src, int needsp, int nt) {
  size_t c;
  if (needsp && src->npar > 0) {        /* counting reads parameters: find them first */
    if (j->v->poff != NULL)            /* the context tables have them */
      for (c = 0; c < j->nch; c++) {
        j->ch[c].sp = j->v->poff[j->ch[c].a];
        j->ch[c].nsp = j->v->poff[j->ch[c].b] - j->ch[c].sp;
      }
    else {
      runphase(j, PH_NP, nt);
      paroffsets(j);
    }
  }
  else j->withnp = src->npar > 0 && src->sym8 == NULL;
  runphase(j, PH_COUNT, nt);
  for (c = 0; c < j->nch; c++)
    if (j->ch[c].bad) return 0;
  if (j->withnp) paroffsets(j);
  return 1;
}

/* Makes room for the new string: 'src' grown in place, or 'out' made anew. */
static int room (job *j, lsys_lstring *src, lsys_lstring *out, size_t tot, size_t ptot) {
  if (out == src)                                                         /* no NULL + 0 */
    return lsys_lstring_grow(src, tot, j->narrow ? 0 : ptot > 0 ? ptot : 1) == LSYS_OK;
  if (j->narrow) return lsys_lstring_prepare8(out, tot) == LSYS_OK;
  return lsys_lstring_prepare(out, tot, ptot > 0 ? ptot : 1) == LSYS_OK;  /* no NULL + 0 */
}

int lsys_derive_par_productions (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst, const view *v,
                                 lsys_ruleset *const *sets, int nsets) {
  int nt = m->threads > 0 ? m->threads : lsys_derive_default_threads(), needsp, gen, flags;
  int st = LSYS_OK;
  size_t n = src->n, tot, ptot, c;
  lsys_lstring *seqout = dst == src ? &m->tmp : dst, *out;
  job *j;
  if (n < m->parmin || n < 2) return LSYS_PAR_SEQ;      /* never on the thread count: the
                                    ** strings it makes are kept in other buffers */
  if (m->par == NULL) {
    if ((m->par = (lsys_par *)LSYS_MALLOC(sizeof *m->par)) == NULL) return LSYS_PAR_SEQ;
    memset(m->par, 0, sizeof *m->par);
  }
  if (!prepare(m, m->par, nt) || !classify(m, sets, nsets, &needsp, &gen)) return LSYS_PAR_SEQ;
  if ((j = (job *)LSYS_MALLOC(sizeof *j)) == NULL) return LSYS_PAR_SEQ;
  memset(j, 0, sizeof *j);
  j->m = m; j->v = v; j->P = m->par;
  j->code = src->code; j->code8 = src->sym8;
  j->spar = src->par != NULL ? src->par : nopar;
  j->sets = sets; j->nsets = nsets;
  j->rng = *m->cur;
  atomic_init(&j->stop, 0);
  cut(j, n, nt);
  if (gen) keeproom(j, src);
  if (!count(j, src, needsp, nt) || !prefix(j, &tot, &ptot, &flags)) goto seq;
  if (j->keep) keptneed(j, tot);
  j->narrow = !(flags & 1) && lsys_rules_setsize(m, LSYS_DECOMP, 0, 0) <= 0;
  j->inplace = dst == src && v->match == NULL && !(flags & 4) &&
               j->narrow == (src->sym8 != NULL);
  out = j->inplace ? src : seqout;
  if (tot == 0 || !roomy(m, src, seqout, tot, ptot) || !room(j, src, out, tot, ptot)) goto seq;
  if (j->inplace) {                       /* the arrays may have moved */
    j->code = src->code; j->code8 = src->sym8;
    j->spar = src->par != NULL ? src->par : nopar;
  }
  j->out = out;
  runphase(j, PH_FILL, nt);
  for (c = 0; c < j->nch && st == LSYS_OK; c++)
    if (j->ch[c].bad || j->ch[c].fail != (size_t)-1) st = LSYS_ERULE;
  if (st != LSYS_OK && !j->inplace) goto seq;
  if (st != LSYS_OK) st = firsterror(j);     /* the string is lost (derive's own) */
  else {
    out->n = tot;
    out->npar = j->narrow ? 0 : ptot;
    out->nck = 0;
    if (out != dst) lsys_derive_swapstr(src, out);
  }
  LSYS_FREE(j);
  return st;
seq:
  if (seqout != src) lsys_lstring_clear(seqout);
  LSYS_FREE(j);
  return LSYS_PAR_SEQ;
}
