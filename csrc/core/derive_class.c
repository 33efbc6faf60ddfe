/*
** What each symbol's modules become in the parallel step (derive_par.c;
** docs/architecture.md, "The parallel step"): the classes of the symbols, the
** short programs and context tables they are rewritten by, the rule a module
** takes, and the choices counting keeps for filling.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "derive_par_impl.h"

void lsys_derive_par_free (lsys_rules *m) {
  int k;
  if (m->par == NULL) return;
  for (k = 0; k < LSYS_MAXTHREADS; k++) {
    LSYS_FREE(m->par->ws[k].args);
    LSYS_FREE(m->par->ws[k].alt);
    lsys_context_freewin(&m->par->win[k]);
    LSYS_FREE(m->par->side[k].code);
    LSYS_FREE(m->par->side[k].code8);
    LSYS_FREE(m->par->side[k].par);
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

/* Whether rule r runs without the callback, as one module. */
static int cruns (const lsys_rule *r) {
  return r->nmore == 0 && !(r->flags & LSYS_RF_DYN) &&
         (r->vm != NULL || !(r->flags & LSYS_RF_CALL));
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
int lsys_derive_par_prepare (lsys_rules *m, lsys_par *P, int nt) {
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
int lsys_derive_par_classify (lsys_rules *m, lsys_ruleset *const *sets, int nsets, int *needsp,
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
        if (!cruns(r) || (m->cpfg && lsys_rule_draws(r))) return 0;
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
int lsys_derive_par_pick (job *j, lsys_scratch *w, size_t i, uint16_t cd, const double **args,
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
    const view *v = wview(j, w);
    uint32_t ls = 256, rs = 256;
    uint16_t id;
    if (LSYS_CNP(cd) != 0) return 0;
    if (v->match != NULL) {             /* (without context tables, as lsys_derive_choose, no
                                        ** context matches: the rules without one apply) */
      long long l = lsys_context_leftof(v, (long long)i - 1);
      size_t r = lsys_context_rightof(v, i + 1);
      if (l >= 0 && LSYS_CNP(lsys_view_code(v, (size_t)l)) == 0)   /* never a pattern's */
        ls = LSYS_CSYM(lsys_view_code(v, (size_t)l));
      if (r < v->n && LSYS_CNP(lsys_view_code(v, r)) == 0) rs = LSYS_CSYM(lsys_view_code(v, r));
      if (ls > 256) ls = 256;
      if (rs > 256) rs = 256;
    }
    id = e->ctab[ls * CTN + rs];
    if (id != NORULE) *rule = &m->rules[id];
    return 0;
  }
  if (e->cls != PC_GEN) return -1;
  lsys_rng_at(w->rng, i);
  st = lsys_derive_choose(m, w, j->sets, j->nsets, wview(j, w), i, cd, *args, &pk);
  if (st < 0 || st > 1 || (st == 1 && pk.dyn != NULL)) return -1;
  if (st == 1) { *rule = pk.r; *args = pk.args; *vals = pk.vals; }
  return 0;
}

/* The parameters of rule r's successor (arguments 'args', values 'vals') into op. */
void lsys_derive_par_succpar (const lsys_rules *m, const lsys_rule *r, const double *args,
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
void lsys_derive_par_keepchoice (job *j, chunk *c, size_t i, const lsys_rule *r, const double *args,
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
  if (nsrc > 0) lsys_derive_par_succpar(m, r, args, vals, g->par + c->npc);
  c->npc += nsrc;
}

/* Sets the cursor of the choices kept for chunk c (none when not kept). */
void lsys_derive_par_keptchoices (const job *j, const chunk *c, wout *o) {
  const gcache *g = &j->P->gc[c - j->ch];
  o->rid = g->rid; o->cp = g->par;
  o->nr = c->nr; o->npc = c->npc;
  o->upto = j->keep ? c->upto : c->a;
}

/* The kept choice of module i of class PC_GEN: 1 with *r (NULL: a copy) and
** *kp, the successor's parameters; 0 when it was not kept. */
int lsys_derive_par_kept (wout *o, const lsys_rules *m, size_t i, const lsys_rule **r,
                          const double **kp) {
  uint16_t id;
  if (i >= o->upto || o->nr == 0) return 0;
  id = o->rid[--o->nr];
  *r = id == NORULE ? NULL : &m->rules[id];
  if (*r != NULL) o->npc -= (*r)->nsrc;
  *kp = o->cp != NULL ? o->cp + o->npc : NULL;   /* (no parameters kept: none) */
  return 1;
}

/* Room in each chunk's gcache for the choices counting finds, as many a
** module as the chunks of the step before needed (a quarter the first time)
** and a quarter more; none when the budget has no room for it (filling then
** chooses again). */
void lsys_derive_par_keeproom (job *j, const lsys_lstring *src) {
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
void lsys_derive_par_keptneed (job *j, size_t n) {
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
