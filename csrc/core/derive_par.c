/*
** The productions of a derivation step on several threads (derive_impl.h;
** docs/architecture.md, "The parallel step").
**
** A step is count, prefix sum, fill. The source string is cut into chunks at
** module boundaries; worker threads take chunks in turn and count the
** modules and parameters of their successors; a prefix sum over the chunks
** gives each chunk its place in the new string, which is allocated once at
** its exact size; the workers then fill their chunks in place. A module is
** rewritten the same way on every thread: the rule chosen, the expression
** machine's values and the generator's numbers depend only on the module and
** its position (rng.h), so the string is the same for every number of
** threads, and the same as the sequential step's (derive.c), which runs
** instead whenever the step needs what only the calling thread may do: a
** rule that calls back into Lua, a cut or a sub-L-system (they change how
** the modules after them are rewritten), a predecessor of several modules,
** or an error message (the sequential step finds the module it names).
*/
#ifdef __linux__
#define _GNU_SOURCE             /* sched_getaffinity, CPU_COUNT */
#include <sched.h>
#endif
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "derive_impl.h"

#define MAXCHUNKS 256
#define CHUNKMIN 2048             /* modules: smaller chunks cost more than they share */

/* What a worker does with a module of a symbol. */
enum {
  PC_COPY,      /* no rule: copied */
  PC_PLAIN,     /* one rule that always applies: its template */
  PC_VM,        /* one rule on the expression machine, no condition */
  PC_VMC,       /* the same with a condition */
  PC_GEN,       /* contexts, weights, several rules, groups: lsys_choose */
  PC_SEQ        /* the sequential step must run */
};

/* What a symbol's modules become: the rule (when one) whose successor has
** 'nsucc' modules and 'nsrc' parameters for modules of 'pnp' parameters
** (NOPNP: none); modules of other counts are copied. */
typedef struct pent {
  uint8_t cls, pnp;
  uint32_t nsucc, nsrc, rule;
  const uint16_t *t;
} pent;

#define NOPNP 0xFF

/* The workers' scratch, kept by the model between steps. */
typedef struct lsys_par {
  lsys_scratch ws[LSYS_MAXTHREADS];
  pent *pe; size_t npe;        /* per symbol */
} lsys_par;

typedef struct chunk {
  size_t a, b;                /* source modules [a, b) */
  size_t sp, nsp;             /* its first parameter, its parameters */
  size_t cnt, pcnt;           /* modules and parameters of its successors */
  size_t o, po;               /* where they go in the new string */
  int bad;
} chunk;

enum { PH_NP, PH_COUNT, PH_FILL };

typedef struct job {
  lsys_model *m;
  const lsys_lstring *src;
  lsys_lstring *dst;
  const double *spar;
  const view *v;
  lsys_ruleset *const *sets;
  int nsets, phase, withnp;
  const pent *pe;
  lsys_rng rng;               /* each worker draws from a copy */
  chunk ch[MAXCHUNKS];
  size_t nch;
  atomic_size_t next;
} job;

typedef struct worker { job *j; lsys_scratch *w; lsys_rng rng; pthread_t t; } worker;

static const double nopar[1];

void lsys_par_free (lsys_model *m) {
  int k;
  if (m->par == NULL) return;
  for (k = 0; k < LSYS_MAXTHREADS; k++) {
    LSYS_FREE(m->par->ws[k].args);
    LSYS_FREE(m->par->ws[k].alt);
  }
  LSYS_FREE(m->par->pe);
  LSYS_FREE(m->par);
  m->par = NULL;
}

int lsys_default_threads (void) {
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

/* Whether rule r runs without the callback, as one module. */
static int cruns (const lsys_rule *r) {
  return r->nmore == 0 && !(r->flags & LSYS_RF_DYN) && (r->vm != NULL || !(r->flags & LSYS_RF_CALL));
}

static int hascond (const lsys_rule *r) {
  int k;
  for (k = 0; k < r->nvm; k++)
    if (r->vm[k].op == LSYS_OP_COND) return 1;
  return 0;
}

/*
** The class of every symbol (as the sequential step's fast loop, derive.c's
** fasttable, with rules on the expression machine and contexts besides).
** Returns 0 when a rule of the sets needs the calling thread, else 1 with
** *needsp set when counting reads parameters; grows the workers' scratch.
*/
static int classify (lsys_model *m, lsys_ruleset *const *sets, int nsets, int *needsp) {
  lsys_par *P = m->par;
  uint32_t k, n = m->ab->n, nvals = 1;
  int si;
  *needsp = 0;
  if (P->npe < n) {
    LSYS_FREE(P->pe);
    P->npe = 0;
    if ((P->pe = (pent *)LSYS_MALLOC(n * sizeof *P->pe)) == NULL) return 0;
    P->npe = n;
  }
  for (k = 0; k < n; k++) {
    uint32_t nr = 0, b, first = NONE;
    pent *e = &P->pe[k];
    for (si = 0; si < nsets; si++) {
      const lsys_ruleset *s = sets[si];
      if (s == NULL || k >= s->nsym) continue;
      for (b = s->start[k]; b < s->start[k + 1]; b++) {
        const lsys_rule *r = &m->rules[s->byp[b]];
        if (!cruns(r)) return 0;
        if (r->nvals + 1 > nvals) nvals = r->nvals + 1;
        if (first == NONE) first = s->byp[b];
        nr++;
      }
    }
    memset(e, 0, sizeof *e);
    e->pnp = NOPNP;
    e->rule = first;
    if (k == LSYS_SYM_CUT || k == LSYS_SYM_SUB) e->cls = PC_SEQ;
    else if (nr == 0) e->cls = PC_COPY;
    else {
      const lsys_rule *r = &m->rules[first];
      int simple = nr == 1 && r->nlc == 0 && r->nrc == 0 && !(r->flags & LSYS_RF_STOCH);
      if (simple && r->vm == NULL) e->cls = PC_PLAIN;
      else if (simple) e->cls = hascond(r) ? PC_VMC : PC_VM;
      else e->cls = PC_GEN;
      if (e->cls == PC_PLAIN || e->cls == PC_VM) {
        e->pnp = (uint8_t)r->pred_np;
        e->nsucc = r->nsucc;
        e->nsrc = r->nsrc;
        e->t = m->tcode + r->succ;
      }
    }
    if (e->cls == PC_VMC || e->cls == PC_GEN) *needsp = 1;
  }
  for (k = 0; k < LSYS_MAXTHREADS; k++) {
    P->ws[k].worker = 1;
    if (lsys_needscratch(&P->ws[k], nvals) != LSYS_OK) return 0;
  }
  return 1;
}

/* The rule that rewrites module i ('cd', parameters *args), or NULL when it
** is copied (classes PC_VM, PC_VMC, PC_GEN); *vals gets its values and *args
** its arguments. Returns -1 when the step must run sequentially. */
static int pick (job *j, lsys_scratch *w, size_t i, uint16_t cd, const double **args,
                 const double **vals, const lsys_rule **rule) {
  lsys_model *m = j->m;
  const pent *e = &j->pe[LSYS_CSYM(cd)];
  const lsys_rule *r = &m->rules[e->rule];
  lsys_pick pk;
  int st;
  *rule = NULL;
  if (e->cls == PC_VM || e->cls == PC_VMC) {
    if (r->pred_np != LSYS_CNP(cd)) return 0;
    lsys_rng_at(w->rng, i);
    if (!lsys_expr_run(r->vm, r->nvm, *args, w->args, w->rng, m->funcs)) return 0;
    if (lsys_checkvals(m, w, r, i, w->args) != LSYS_OK) return -1;
    *vals = w->args;
    *rule = r;
    return 0;
  }
  if (e->cls != PC_GEN) return -1;
  lsys_rng_at(w->rng, i);
  st = lsys_choose(m, w, j->sets, j->nsets, j->v, i, cd, *args, &pk);
  if (st < 0 || st > 1 || (st == 1 && pk.dyn != NULL)) return -1;
  if (st == 1) { *rule = pk.r; *args = pk.args; *vals = pk.vals; }
  return 0;
}

/* Sums the parameters of the chunk's modules. */
static void npchunk (job *j, chunk *c) {
  const uint16_t *code = j->src->code;
  size_t i, nsp = 0;
  for (i = c->a; i < c->b; i++) nsp += LSYS_CNP(code[i]);
  c->nsp = nsp;
}

/* Counts the modules and parameters of the chunk's successors (and its
** parameters, when the job says so). */
static void countchunk (job *j, lsys_scratch *w, chunk *c) {
  const uint16_t *code = j->src->code;
  const pent *pe = j->pe;
  size_t i, sp = c->sp, cnt = 0, pcnt = 0;
  for (i = c->a; i < c->b; i++) {
    uint16_t cd = code[i];
    uint32_t np = LSYS_CNP(cd);
    const pent *e = &pe[LSYS_CSYM(cd)];
    if (e->pnp == np) { cnt += e->nsucc; pcnt += e->nsrc; }
    else if (e->cls <= PC_VM) { cnt++; pcnt += np; }
    else {
      const double *args = j->spar + sp, *vals = NULL;
      const lsys_rule *r;
      if (pick(j, w, i, cd, &args, &vals, &r) < 0) { c->bad = 1; return; }
      if (r != NULL) { cnt += r->nsucc; pcnt += r->nsrc; }
      else { cnt++; pcnt += np; }
    }
    sp += np;
  }
  c->cnt = cnt;
  c->pcnt = pcnt;
  if (j->withnp) c->nsp = sp - c->sp;
}

/* Writes the successor of rule r (arguments 'args', values 'vals') at oc, op. */
static void put (const lsys_model *m, const lsys_rule *r, const double *args,
                 const double *vals, uint16_t *oc, double *op) {
  const uint16_t *t = m->tcode + r->succ;
  const lsys_psrc *ps = m->tsrc + r->src;
  uint32_t k;
  for (k = 0; k < r->nsucc; k++) oc[k] = t[k];
  for (k = 0; k < r->nsrc; k++) {
    double x = ps[k].kind == LSYS_PS_CONST ? ps[k].value :
               ps[k].kind == LSYS_PS_ARG ? args[ps[k].idx] : vals[ps[k].idx];
    op[k] = m->f32 ? lsys_round32(x) : x;
  }
}

/* Writes the chunk's successors at their place in the new string. */
static void fillchunk (job *j, lsys_scratch *w, chunk *c) {
  const lsys_model *m = j->m;
  const uint16_t *code = j->src->code;
  const pent *pe = j->pe;
  const double *spar = j->spar;
  uint16_t *oc = j->dst->code + c->o, *oe = oc + c->cnt;
  double *op = j->dst->par + c->po, *ope = op + c->pcnt;
  size_t i, sp = c->sp;
  uint32_t k;
  for (i = c->a; i < c->b; i++) {
    uint16_t cd = code[i];
    uint32_t np = LSYS_CNP(cd);
    const pent *e = &pe[LSYS_CSYM(cd)];
    const lsys_rule *r = NULL;
    const double *args = spar + sp, *vals = NULL;
    if (e->pnp == np && e->cls == PC_PLAIN && e->nsrc == 0) {     /* a template */
      if ((size_t)(oe - oc) < e->nsucc) { c->bad = 1; return; }
      for (k = 0; k < e->nsucc; k++) oc[k] = e->t[k];
      oc += e->nsucc;
      sp += np;
      continue;
    }
    if (e->pnp == np && e->cls == PC_PLAIN) r = &m->rules[e->rule];
    else if (e->cls > PC_PLAIN && pick(j, w, i, cd, &args, &vals, &r) < 0) {
      c->bad = 1;
      return;
    }
    if (r == NULL) {                                               /* a copy */
      if (oc == oe || (size_t)(ope - op) < np) { c->bad = 1; return; }
      *oc++ = cd;
      for (k = 0; k < np; k++) op[k] = args[k];
      op += np;
    }
    else {
      if ((size_t)(oe - oc) < r->nsucc || (size_t)(ope - op) < r->nsrc) { c->bad = 1; return; }
      put(m, r, args, vals, oc, op);
      oc += r->nsucc;
      op += r->nsrc;
    }
    sp += np;
  }
  if (oc != oe || op != ope) c->bad = 1;
}

static void *work (void *arg) {
  worker *wk = (worker *)arg;
  job *j = wk->j;
  size_t c;
  wk->w->rng = &wk->rng;
  while ((c = atomic_fetch_add(&j->next, 1)) < j->nch) {
    chunk *ch = &j->ch[c];
    wk->rng = j->rng;
    if (j->phase == PH_NP) npchunk(j, ch);
    else if (j->phase == PH_COUNT) countchunk(j, wk->w, ch);
    else fillchunk(j, wk->w, ch);
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

/* Totals of the chunks, and their places: source parameters (PH_NP) or
** successors (PH_COUNT). Returns 0 when a chunk failed. */
static int prefix (job *j, int phase, size_t *n, size_t *np) {
  size_t c, o = 0, po = 0;
  for (c = 0; c < j->nch; c++) {
    chunk *ch = &j->ch[c];
    if (ch->bad) return 0;
    if (phase == PH_NP) { ch->sp = o; o += ch->nsp; continue; }
    ch->o = o; ch->po = po;
    o += ch->cnt; po += ch->pcnt;
  }
  *n = o;
  *np = po;
  return 1;
}

/* Cuts [0, n) into chunks for 'nt' threads. */
static void cut (job *j, size_t n, int nt) {
  size_t nch = (size_t)nt * 8, c;
  if (nch > MAXCHUNKS) nch = MAXCHUNKS;
  if (nch > n / CHUNKMIN) nch = n / CHUNKMIN;
  if (nch < (size_t)nt) nch = (size_t)nt;
  if (nch > n) nch = n > 0 ? n : 1;
  for (c = 0; c < nch; c++) {
    memset(&j->ch[c], 0, sizeof j->ch[c]);
    j->ch[c].a = n / nch * c + (c < n % nch ? c : n % nch);
    j->ch[c].b = j->ch[c].a + n / nch + (c < n % nch);
  }
  j->nch = nch;
}

/* Whether the sequential step could certainly hold a string of n modules
** and np parameters within the budget (it grows its arrays by doubling):
** only then may this step succeed where it would not fail. */
static int roomy (lsys_model *m, lsys_lstring *dst, size_t n, size_t np) {
  size_t dbytes = lsys_lstring_bytes(dst), base, need;
  if (n > m->max_modules) return 0;
  base = m->meter.used > dbytes ? m->meter.used - dbytes : 0;
  if (n > ((size_t)-1 / 8) || np > ((size_t)-1 / 32)) return 0;
  need = 2 * (n * sizeof *dst->code + np * sizeof *dst->par);
  return base <= m->meter.limit && need <= m->meter.limit - base;
}

int lsys_par_productions (lsys_model *m, lsys_lstring *src, lsys_lstring *dst, const view *v,
                          lsys_ruleset *const *sets, int nsets) {
  int nt = m->threads > 0 ? m->threads : lsys_default_threads(), needsp;
  size_t n = src->n, tot, ptot;
  job *j;
  if (n < m->parmin || n < 2) return LSYS_PAR_SEQ;      /* never on the thread count: the
                                    ** strings it makes are kept in other buffers */
  if (m->par == NULL) {
    m->par = (lsys_par *)LSYS_MALLOC(sizeof *m->par);
    if (m->par == NULL) return LSYS_PAR_SEQ;
    memset(m->par, 0, sizeof *m->par);
  }
  if (!classify(m, sets, nsets, &needsp)) return LSYS_PAR_SEQ;
  j = (job *)LSYS_MALLOC(sizeof *j);
  if (j == NULL) return LSYS_PAR_SEQ;
  memset(j, 0, sizeof *j);
  j->m = m; j->src = src; j->dst = dst; j->v = v;
  j->spar = src->par != NULL ? src->par : nopar;
  j->sets = sets; j->nsets = nsets;
  j->pe = m->par->pe;
  j->rng = *m->cur;
  cut(j, n, nt);
  if (needsp && src->npar > 0) {        /* counting reads parameters: find them first */
    if (v->poff != NULL) {
      size_t c;
      for (c = 0; c < j->nch; c++) j->ch[c].sp = v->poff[j->ch[c].a];
    }
    else {
      runphase(j, PH_NP, nt);
      prefix(j, PH_NP, &tot, &ptot);
    }
  }
  else j->withnp = src->npar > 0;
  runphase(j, PH_COUNT, nt);
  if (!prefix(j, PH_COUNT, &tot, &ptot)) goto seq;
  if (j->withnp) {
    size_t c, sp = 0;
    for (c = 0; c < j->nch; c++) { j->ch[c].sp = sp; sp += j->ch[c].nsp; }
  }
  if (tot == 0 || !roomy(m, dst, tot, ptot) ||
      lsys_lstring_prepare(dst, tot, ptot > 0 ? ptot : 1) != LSYS_OK)  /* no NULL + 0 */
    goto seq;
  runphase(j, PH_FILL, nt);
  if (!prefix(j, PH_COUNT, &tot, &ptot)) goto seq;
  dst->n = tot;
  dst->npar = ptot;
  LSYS_FREE(j);
  return LSYS_OK;
seq:
  LSYS_FREE(j);
  lsys_lstring_clear(dst);
  return LSYS_PAR_SEQ;
}
