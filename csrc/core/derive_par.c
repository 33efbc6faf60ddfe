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

#include "derive_par_impl.h"


static const double nopar[1];



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











/* Sums the parameters of the chunk's modules. */
static void npchunk (job *j, chunk *c) {
  size_t i, nsp = 0;
  for (i = c->a; i < c->b; i++) nsp += LSYS_CNP(j->code[i]);
  c->nsp = nsp;
}



/* The rule of class PC_FAST that rewrites a module (parameters 'args') or
** NULL, by the conditions alone: counting needs no values (filling computes
** and checks them; firsterror finds a failure there). */
static const lsys_rule *fastrule (const job *j, const pent *e, uint16_t cd, const double *args) {
  uint32_t q;
  for (q = 0; q < e->nfr; q++) {
    const lsys_rule *r = &j->m->rules[e->fr[q]];
    const lsys_xfast *fx = &j->P->rfx[e->fr[q]];
    if (r->pred_np == LSYS_CNP(cd) && (!fx->cond || lsys_expr_term(&fx->t[0], args) != 0))
      return r;
  }
  return NULL;
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
  else if (e->cls == PC_FAST) r = fastrule(j, e, cd, args);
  else if (lsys_derive_par_pick(j, w, i, cd, &args, &vals, &r) < 0) return 0;
  if (e->cls == PC_CTAB) *fl |= FL_CTX;
  if (e->cls == PC_GEN) {
    *fl |= FL_GEN;
    if (j->keep) lsys_derive_par_keepchoice(j, c, i, r, args, vals);
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
  c->ctx = (fl & FL_CTX) != 0;
  if (j->withnp) c->nsp = sp - c->sp;
}

/* Writes the successor of rule r (arguments 'args', values 'vals') at oc, op. */
static void put (const lsys_rules *m, const lsys_rule *r, const double *args,
                 const double *vals, uint16_t *oc, double *op) {
  const uint16_t *t = m->tcode + r->succ;
  uint32_t k;
  for (k = 0; k < r->nsucc; k++) oc[k] = t[k];
  lsys_derive_par_succpar(m, r, args, vals, op);
}

/* A module's values failed (or the chunk went wrong, 'bad'): every worker
** stops; modules [i + 1, b) of the chunk are written. */
static void halt (job *j, chunk *c, size_t i, int bad) {
  if (bad) c->bad = 1;
  else c->fail = i;
  c->lo = i + 1;
  atomic_store(&j->stop, 1);
}




/* Whether n parameters at p and m at q share memory (filling in place: a
** module's own and its successor's, which come close only where the string
** has not grown yet; a copy of a few doubles costs more than the test). */
static inline int overlap (const double *p, size_t n, const double *q, size_t m) {
  uintptr_t x = (uintptr_t)p, y = (uintptr_t)q;
  return x < y + m * sizeof *q && y < x + n * sizeof *p;
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
  else if (e->cls == PC_GEN && lsys_derive_par_kept(o, m, i, &r, &kp)) {
    if (r != NULL) {                               /* counting chose it */
      if ((size_t)(o->oc - o->o0) < r->nsucc || (size_t)(o->op - o->p0) < r->nsrc) return -1;
      o->oc -= r->nsucc;
      o->op -= r->nsrc;
      memcpy(o->oc, m->tcode + r->succ, r->nsucc * sizeof *o->oc);
      if (r->nsrc > 0) memcpy(o->op, kp, r->nsrc * sizeof *o->op);
      return 1;
    }
  }
  else if (e->cls > PC_PLAIN && lsys_derive_par_pick(j, w, i, cd, &args, &vals, &r) < 0) return 0;
  if (r == NULL) {                                               /* a copy */
    if (o->oc == o->o0 || (size_t)(o->op - o->p0) < np) return -1;
    *--o->oc = cd;
    o->op -= np;
    for (k = np; k-- > 0;) o->op[k] = args[k];      /* from the end: op >= args */
    return 1;
  }
  if ((size_t)(o->oc - o->o0) < r->nsucc || (size_t)(o->op - o->p0) < r->nsrc) return -1;
  if (j->inplace && np > 0 && e->cls != PC_GEN &&  /* the module's own parameters may be */
      overlap(args, np, o->op - r->nsrc, r->nsrc)) {   /* where its successor's go */
    memcpy(a, args, np * sizeof *a);
    args = a;
  }
  o->oc -= r->nsucc;
  o->op -= r->nsrc;
  put(m, r, args, vals, o->oc, o->op);
  return 1;
}

/* Where filling reads a chunk's source: the string, or the side copy of
** the worker that filled it (indices from the chunk's first module and
** parameter). */
typedef struct srcv {
  const uint16_t *code; const uint8_t *code8; const double *par;
  size_t ia, pa;
} srcv;

static srcv source (const job *j, const chunk *c) {
  srcv v;
  if (c->side > 0) {
    const struct side *sd = &j->P->side[c->side - 1];
    v.code = j->code8 != NULL ? NULL : sd->code;
    v.code8 = j->code8 != NULL ? sd->code8 : NULL;
    v.par = sd->par != NULL ? sd->par : nopar;
    v.ia = c->a; v.pa = c->sp;
  }
  else {
    v.code = j->code; v.code8 = j->code8; v.par = j->spar;
    v.ia = v.pa = 0;
  }
  return v;
}

static inline uint16_t vcode (const srcv *v, size_t i) {
  return v->code8 != NULL ? (uint16_t)LSYS_CODE(v->code8[i - v->ia], 0) : v->code[i - v->ia];
}

/* Copies chunk c's source to worker k's side copy (room made by sideroom). */
static void copyside (job *j, chunk *c, int k) {
  struct side *sd = &j->m->par->side[k];
  size_t n = c->b - c->a;
  if (j->code8 != NULL) memcpy(sd->code8, j->code8 + c->a, n);
  else memcpy(sd->code, j->code + c->a, n * sizeof *sd->code);
  if (c->nsp > 0) memcpy(sd->par, j->spar + c->sp, c->nsp * sizeof *sd->par);
  c->side = k + 1;
}

/* Writes the chunk's successors into a wide string, from its end. */
static void fillwide (job *j, lsys_scratch *w, chunk *c) {
  const pent *pe = j->P->pe;
  const srcv sv = source(j, c);
  const double *spar = sv.par;
  wout o;
  size_t i, sp = c->sp + c->nsp - sv.pa;   /* (relative to sv.par) */
  int st;
  o.o0 = j->out->code + c->o;
  o.oc = o.o0 + c->cnt;
  o.p0 = j->out->par + c->po;
  o.op = o.p0 + c->pcnt;
  lsys_derive_par_keptchoices(j, c, &o);
  for (i = c->b; i-- > c->a;) {
    uint16_t cd = vcode(&sv, i);
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
      if (j->inplace && e->pargs &&       /* its own parameters may be where its successor's go */
          overlap(args, np, o.op - e->nsrc, e->nsrc)) {
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
  const srcv sv = source(j, c);
  const uint8_t *code8 = sv.code8;
  uint8_t *base = j->out->sym8, *o0 = base + c->o, *oc = o0 + c->cnt;
  size_t i, sp = c->sp + c->nsp - sv.pa, ia = sv.ia;
  wout ko;
  lsys_derive_par_keptchoices(j, c, &ko);
  for (i = c->b; i-- > c->a;) {
    uint16_t cd;
    if (code8 != NULL) {                  /* narrow to narrow: the usual case */
      uint8_t b = code8[i - ia], kind = P->nkind[b];
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
    cd = vcode(&sv, i);
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
    args = sv.par + sp;
    if ((i & 1023) == 0 && atomic_load_explicit(&j->stop, memory_order_relaxed)) {
      c->lo = i + 1;
      return;
    }
    if (e->cls == PC_GEN && lsys_derive_par_kept(&ko, j->m, i, &r, &vals)) {}  /* counted */
    else if (lsys_derive_par_pick(j, w, i, cd, &args, &vals, &r) < 0) { halt(j, c, i, 0); return; }
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
** are written, or (copy) their sources copied aside. Returns 0 when the
** workers stop. */
static int await (job *j, size_t c) {
  const chunk *ch = j->ch;
  size_t lim = ch[c].o + ch[c].cnt, plim = ch[c].po + ch[c].pcnt, d;
  for (d = c + 1; d < j->nch && (ch[d].a < lim || ch[d].sp < plim); d++) {
    if (ch[d].b <= ch[c].o && ch[d].sp + ch[d].nsp <= ch[c].po) continue;   /* below it */
    while (!atomic_load_explicit(j->copy ? &j->copied[d] : &j->done[d], memory_order_acquire)) {
      if (atomic_load(&j->stop)) return 0;
      sched_yield();
    }
  }
  return 1;
}

/* The worker's context window for chunk c (when the rules have contexts; a
** window that could not be made leaves the string's tables to answer). */
static void window (job *j, worker *wk, const chunk *c) {
  view *v = &j->wv[wk->id];
  if (v->match == NULL) return;
  (void)lsys_context_window(v->match, j->v->match->g, v, c->a, c->b);
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
    else if (j->phase == PH_COUNT) {
      window(j, wk, &j->ch[k]);
      countchunk(j, wk->w, &j->ch[k]);
    }
    else {                                 /* the last chunk first */
      ch = &j->ch[j->nch - 1 - k];
      if (atomic_load(&j->stop)) continue;
      if (j->copy) {
        copyside(j, ch, wk->id);
        atomic_store_explicit(&j->copied[j->nch - 1 - k], 1, memory_order_release);
      }
      if (j->inplace && !await(j, j->nch - 1 - k)) continue;
      if (!j->inplace) window(j, wk, ch);   /* (in place, filling reads no neighbours) */
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
    wk[k].id = k;
    j->wv[k] = *j->v;
    if (j->v->match != NULL) j->wv[k].match = &j->m->par->win[k];
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
    atomic_init(&j->copied[c], 0);
  }
  j->nch = nch;
}

/* The totals of the counts and the places of the chunks; *flags gets what
** the chunks need (bit 0 wide, 1 lsys_derive_choose ran, 2 shorter successors,
** 3 filling reads neighbours, 4 a choice was not kept).
** Returns 0 when a chunk failed. */
static int prefix (job *j, size_t *n, size_t *np, int *flags) {
  size_t c, o = 0, po = 0;
  *flags = 0;
  for (c = 0; c < j->nch; c++) {
    chunk *ch = &j->ch[c];
    if (ch->bad) return 0;
    ch->o = o; ch->po = po;
    o += ch->cnt; po += ch->pcnt;
    *flags |= ch->wide | ch->gen << 1 | ch->shrink << 2 | ch->ctx << 3;
    if (ch->upto < ch->b) *flags |= 16;
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
    const srcv sv = source(j, ch);     /* (a worker's side copy is of the chunk it
                                       ** stopped in: it takes no other after that) */
    size_t sp = ch->sp - sv.pa;
    for (i = ch->a; i < ch->lo; i++) {
      uint16_t cd = vcode(&sv, i);
      const pent *e = &j->P->pe[LSYS_CSYM(cd)];
      if (e->cls == PC_VM && e->pnp == LSYS_CNP(cd)) {
        const lsys_rule *r = &m->rules[e->rule];
        lsys_rng_at(&rng, i);
        if (lsys_derive_needscratch(&m->sc, r->nvals + 1) != LSYS_OK) return LSYS_ENOMEM;
        if (lsys_expr_run(r->vm, r->nvm, sv.par + sp, m->sc.args, &rng, m->funcs) &&
            lsys_derive_checkvals(m, &m->sc, r, i, m->sc.args) != LSYS_OK)
          return LSYS_ERULE;
      }
      else if (e->cls == PC_FAST) {      /* (counted by its conditions alone) */
        const lsys_rule *r = fastrule(j, e, cd, sv.par + sp);
        if (r != NULL && r->vm != NULL) {
          if (lsys_derive_needscratch(&m->sc, r->nvals + 1) != LSYS_OK) return LSYS_ENOMEM;
          lsys_expr_runfast(&j->P->rfx[r - m->rules], sv.par + sp, m->sc.args);
          if (lsys_derive_checkvals(m, &m->sc, r, i, m->sc.args) != LSYS_OK) return LSYS_ERULE;
        }
      }
      sp += LSYS_CNP(cd);
    }
  }
  return lsys_seterror(&m->err, LSYS_ERULE, (size_t)-1, "a step on several threads failed");
}



/* Counts: the chunks' parameters when counting reads them, then the
** successors. Returns 0 when the step must run sequentially. */
static int count (job *j, const lsys_lstring *src, int needsp, int nt) {
  size_t c;
  if (needsp && src->npar > 0) {        /* counting reads parameters: find them first */
    if (j->v->match != NULL && j->v->match->g->withp)   /* the context tables have them */
      for (c = 0; c < j->nch; c++) {
        j->ch[c].sp = lsys_context_farpoff(j->v, j->ch[c].a);
        j->ch[c].nsp = lsys_context_farpoff(j->v, j->ch[c].b) - j->ch[c].sp;
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

/* Room in the side copies of the first nt workers for the largest chunk; 0
** when there is none. They are the step's scratch, freed when it ends and not
** counted against max_memory (nor are the workers' context windows), so that
** where a step meets it never depends on the number of threads (an eighth of
** a string of 16,384 modules a thread or more: nt of its 8 nt chunks). */
static int sideroom (job *j, int nt) {
  lsys_rules *m = j->m;
  size_t c, n = 0, np = 0;
  int k;
  for (c = 0; c < j->nch; c++) {
    if (j->ch[c].b - j->ch[c].a > n) n = j->ch[c].b - j->ch[c].a;
    if (j->ch[c].nsp > np) np = j->ch[c].nsp;
  }
  for (k = 0; k < nt && (size_t)k < j->nch; k++) {
    struct side *sd = &m->par->side[k];
    if ((j->code8 != NULL
           ? lsys_common_grow((void **)&sd->code8, &sd->code8cap, n, 1)
           : lsys_common_grow((void **)&sd->code, &sd->codecap, n, sizeof *sd->code)) != LSYS_OK ||
        (np > 0 && lsys_common_grow((void **)&sd->par, &sd->parcap, np, sizeof *sd->par)
                     != LSYS_OK))
      return 0;
  }
  return 1;
}

static void freeside (lsys_rules *m) {
  int k;
  for (k = 0; k < LSYS_MAXTHREADS; k++) {
    struct side *sd = &m->par->side[k];
    LSYS_FREE(sd->code); LSYS_FREE(sd->code8); LSYS_FREE(sd->par);
    memset(sd, 0, sizeof *sd);
  }
}

/* The workers' context windows, freed when the step ends as the side copies
** are (their sizes depend on the number of threads). */
static void freewins (lsys_rules *m) {
  int k;
  for (k = 0; k < LSYS_MAXTHREADS; k++) lsys_context_freewin(&m->par->win[k]);
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
  if (!lsys_derive_par_prepare(m, m->par, nt) ||
      !lsys_derive_par_classify(m, sets, nsets, &needsp, &gen))
    return LSYS_PAR_SEQ;
  if ((j = (job *)LSYS_MALLOC(sizeof *j)) == NULL) return LSYS_PAR_SEQ;
  memset(j, 0, sizeof *j);
  j->m = m; j->v = v; j->P = m->par;
  j->code = src->code; j->code8 = src->sym8;
  j->spar = src->par != NULL ? src->par : nopar;
  j->sets = sets; j->nsets = nsets;
  j->rng = *m->cur;
  atomic_init(&j->stop, 0);
  cut(j, n, nt);
  if (gen) lsys_derive_par_keeproom(j, src);
  if (!count(j, src, needsp, nt) || !prefix(j, &tot, &ptot, &flags)) goto seq;
  if (j->keep) lsys_derive_par_keptneed(j, tot);
  j->narrow = !(flags & 1) && lsys_rules_setsize(m, LSYS_DECOMP, 0, 0) <= 0;
  /* in place: filling writes over modules rewritten already, so it must not read
  ** their neighbours: no contexts, or every choice of contexts kept by counting */
  j->inplace = dst == src && !(flags & 4) && j->narrow == (src->sym8 != NULL) &&
               (v->match == NULL || (j->keep && !(flags & (8 | 16))));
  out = j->inplace ? src : seqout;
  /* on several threads, a chunk filled in place would wait for the chunks after it
  ** (its successors go where their modules are) unless they copy their sources first */
  j->copy = j->inplace && nt > 1 && j->nch > 1;
  if (j->copy && !sideroom(j, nt)) {
    freeside(m);
    j->copy = 0;
  }
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
  if (j->copy) freeside(m);
  if (v->match != NULL) freewins(m);
  LSYS_FREE(j);
  return st;
seq:
  if (j->copy) freeside(m);
  if (v->match != NULL) freewins(m);
  if (seqout != src) lsys_lstring_clear(seqout);
  LSYS_FREE(j);
  return LSYS_PAR_SEQ;
}
