/*
** The derivation engine. See derive.h for the contract.
**
** A derivation step scans the source string once, carrying the parameter
** offset along. For each module the rules for its symbol (active group
** first, then group 0) are tried in declaration order: parameter count,
** left context, right context, then the callback for conditions. The first
** applicable deterministic rule wins; when the first applicable rule has a
** weight, all applicable weighted rules compete (cpfg: the first whose
** cumulative weight exceeds r * total). Contexts need the bracket-match and
** parameter-offset tables, built once per step only when some active rule
** has a context.
*/
#include <math.h>
#include <string.h>

#include "derive_impl.h"

/* Parameters of strings that have none: a string without parameters may have
** no pool at all, and even 'NULL + 0' is undefined behaviour. */
static const double nopar[1];

static inline const double *parof (const lsys_lstring *s, size_t p) {
  return s->par != NULL ? s->par + p : nopar;
}
#define ACT_SLOW NONE
#define ACT_COPY (NONE - 1)

/* Appends modules [i, j) of 'src' (parameters from 'poff'): a successor a
** function produced. */
static int emitdyn (lsys_rules *m, lsys_lstring *out, const lsys_lstring *src, size_t i,
                    size_t j, size_t poff) {
  size_t p0 = out->npar;
  int st;
  if (out->n + (j - i) > m->max_modules) return LSYS_ELIMIT;
  if ((st = lsys_lstring_append(out, src, i, j, poff)) != LSYS_OK) return st;
  if (m->f32) for (; p0 < out->npar; p0++) out->par[p0] = lsys_round32(out->par[p0]);
  return LSYS_OK;
}

/* Writes the successor of 'r' into 'out'. */
static int emit (lsys_rules *m, lsys_lstring *out, const lsys_rule *r,
                 const double *args, const double *vals) {
  uint32_t k;
  int st;
  if (r->flags & LSYS_RF_DYN) return emitdyn(m, out, &m->dyn, 0, m->dyn.n, 0);
  if (out->n + r->nsucc > m->max_modules) return LSYS_ELIMIT;
  if ((st = lsys_lstring_reserve(out, r->nsucc, r->nsrc)) != LSYS_OK) return st;
  if (r->nsucc > 0)        /* an empty successor may have no array at all */
    memcpy(out->code + out->n, m->tcode + r->succ, r->nsucc * sizeof *out->code);
  out->n += r->nsucc;
  for (k = 0; k < r->nsrc; k++) {
    const lsys_psrc *ps = &m->tsrc[r->src + k];
    out->par[out->npar++] = ps->kind == LSYS_PS_CONST ? ps->value :
                            ps->kind == LSYS_PS_ARG ? args[ps->idx] : vals[ps->idx];
  }
  if (m->f32)               /* cpfg's float32 storage (one test a successor otherwise) */
    for (k = 0; k < r->nsrc; k++) {
      double *q = out->par + out->npar - r->nsrc + k;
      *q = lsys_round32(*q);
    }
  return LSYS_OK;
}

/* The values the expression machine computed for rule 'r' at module 'i' must
** be finite (the Lua callback checks its own). A worker only reports. */
int lsys_derive_checkvals (lsys_rules *m, const lsys_scratch *w, const lsys_rule *r, size_t i,
                           const double *vals) {
  uint32_t k;
  for (k = 0; k < r->nvals; k++)
    if (!isfinite(vals[k])) {
      if (w->worker) return LSYS_ERULE;
      m->cur_rule = (long)(r - m->rules);
      m->cur_index = i;
      return lsys_seterror(&m->err, LSYS_ERULE, i, "value %u is %s, not a finite number",
                           (unsigned)k + 1, vals[k] != vals[k] ? "nan" : "infinite");
    }
  return LSYS_OK;
}

int lsys_derive_needscratch (lsys_scratch *w, size_t nargs) {
  if (w->argscap < nargs &&
      lsys_common_grow((void **)&w->args, &w->argscap, nargs, sizeof *w->args) != LSYS_OK)
    return LSYS_ENOMEM;
  return LSYS_OK;
}

/* Do the modules after i match the rest of r's predecessor (symbol and
** parameter count, one after the other, as cpfg's PredDiff)? Copies their
** parameters (following 'par', the module's own np of them) into 'args'. */
static int matchmore (const lsys_rules *m, const view *v, size_t i, const lsys_rule *r,
                      const double *par, double *args) {
  uint32_t k, np = LSYS_CNP(lsys_view_code(v, i));
  if (i + r->nmore >= v->n) return 0;
  for (k = 0; k < r->nmore; k++) {
    const lsys_patmod *pm = &m->pat[r->more + k];
    if (lsys_view_code(v, i + 1 + k) != LSYS_CODE(pm->sym, pm->np)) return 0;
  }
  if (r->moreargs) memcpy(args, par + np, r->moreargs * sizeof *args);
  return 1;
}

/* Keeps a stochastic alternative in w->alt: rule, weight, where its produced
** successor is in m->altdyn (modules [b, e), parameters from p), args, vals. */
static int keepalt (lsys_rules *m, lsys_scratch *w, const lsys_rule *r, double wt,
                    const double *args, size_t *altn) {
  size_t need = *altn + ALTHEAD + r->nargs + r->nvals;
  double *a;
  int st;
  if (w->altcap < need &&
      lsys_common_grow((void **)&w->alt, &w->altcap, need, sizeof *w->alt) != LSYS_OK)
    return LSYS_ENOMEM;
  a = w->alt + *altn;
  a[0] = (double)(r - m->rules);
  a[1] = wt;
  a[2] = (double)m->altdyn.n;
  a[4] = (double)m->altdyn.npar;
  if ((r->flags & LSYS_RF_DYN) &&      /* the function ran: keep what it produced */
      (st = lsys_lstring_append(&m->altdyn, &m->dyn, 0, m->dyn.n, 0)) != LSYS_OK)
    return st;
  a[3] = (double)m->altdyn.n;
  a[5] = 0;
  memcpy(a + ALTHEAD, args, (r->nargs + r->nvals) * sizeof *args);
  *altn = need;
  return LSYS_OK;
}

/*
** cpfg's SelectProd (generate.c): the weights as floats, their float sum t, then
** x = (float)(t * u) with u this module's drand48 number, and the first
** alternative that brings x - w1 - ... - wk (float arithmetic) to 0 or below;
** when rounding leaves x above 0, the last one. Returns its offset in w->alt.
*/
static size_t cpfgpick (lsys_rules *m, lsys_scratch *w, size_t nalt) {
  volatile float total = 0, x;     /* volatile: every step rounded to float */
  size_t at = 0, k, last = 0;
  double u = m->choice_ready ? m->choice_u : lsys_drand48(&m->choice48);
  m->choice_ready = 0;
  for (k = 0; k < nalt; k++) {
    const lsys_rule *r = &m->rules[(size_t)w->alt[at]];
    total = total + (float)w->alt[at + 1];
    at += ALTHEAD + r->nargs + r->nvals;
  }
  x = (float)((double)total * u);
  for (k = 0, at = 0; k < nalt; k++) {
    const lsys_rule *r = &m->rules[(size_t)w->alt[at]];
    x = x - (float)w->alt[at + 1];
    if (x <= 0) return at;
    last = at;
    at += ALTHEAD + r->nargs + r->nvals;
  }
  return last;
}

/* The first alternative in w->alt whose cumulative weight exceeds u * total
** (u drawn when there are several); the last one of positive weight when
** rounding leaves none. Returns its offset in w->alt. */
static size_t lsyspick (lsys_rules *m, lsys_scratch *w, size_t nalt, double total) {
  double target = nalt > 1 ? lsys_rng_uniform(w->rng) * total : 0, cum = 0;
  size_t at = 0, k, last = 0;
  for (k = 0; k < nalt; k++) {
    const lsys_rule *r = &m->rules[(size_t)w->alt[at]];
    if (w->alt[at + 1] > 0) {
      last = at;
      cum += w->alt[at + 1];
      if (cum > target) return at;
    }
    at += ALTHEAD + r->nargs + r->nvals;
  }
  return last;
}

/* The chosen alternative into *pk. */
static void pickalt (lsys_rules *m, lsys_scratch *w, size_t nalt, double total, lsys_pick *pk) {
  size_t at = m->cpfg ? cpfgpick(m, w, nalt) : lsyspick(m, w, nalt, total);
  const lsys_rule *r = &m->rules[(size_t)w->alt[at]];
  pk->r = r;
  pk->args = w->alt + at + ALTHEAD;
  pk->vals = pk->args + r->nargs;
  if (r->flags & LSYS_RF_DYN) {
    pk->dyn = &m->altdyn;
    pk->d0 = (size_t)w->alt[at + 2];
    pk->d1 = (size_t)w->alt[at + 3];
    pk->dp = (size_t)w->alt[at + 4];
  }
}

/* Runs rule r's condition and values: the expression machine, or the
** callback (never on a worker). 1 applies, 0 does not, or an error. */
static int evalrule (lsys_rules *m, lsys_scratch *w, const lsys_rule *r, size_t i,
                     const double *args, double *vals) {
  int st;
  if (r->vm != NULL && m->cpfg && (r->flags & LSYS_RF_STOCH))   /* the rest: cpfgvalues */
    return lsys_expr_span(r->vm, 0, r->vmtry, args, vals, w->rng, m->funcs);
  if (r->vm != NULL) {
    if (!lsys_expr_run(r->vm, r->nvm, args, vals, w->rng, m->funcs)) return 0;
    return (st = lsys_derive_checkvals(m, w, r, i, vals)) != LSYS_OK ? st : 1;
  }
  if (!(r->flags & (LSYS_RF_CALL | LSYS_RF_DYN))) return 1;
  if (w->worker) return LSYS_ERULE;
  m->cur_rule = (long)(r - m->rules);
  m->cur_index = i;
  if (r->flags & LSYS_RF_DYN) lsys_lstring_clear(&m->dyn);
  st = m->fn(m->fnud, m, r, args, vals);
  m->cur_rule = -1;
  return st;
}

int lsys_derive_cpfg_mark (lsys_rules *m) {
  if (m->cpfgtry == 1) {
    m->cpfgtried = 1;
    return 1;
  }
  lsys_derive_cpfg_resume(m);
  return 0;
}

int lsys_derive_cpfg_resume (lsys_rules *m) {
  if (m->cpfgtry != 2) return 0;
  m->cur->x48 = m->cpfgz.x48;
  m->cur->iset = m->cpfgz.iset;
  m->cur->gset = m->cpfgz.gset;
  m->cpfgtry = 0;
  return 1;
}

/* Tries weighted rule r that runs in Lua under cpfg's generator: up to its mark
** when it has one (a[5] = 1 and the state before it in a[6..8] once kept). */
static int cpfgtry (lsys_rules *m, lsys_scratch *w, const lsys_rule *r, size_t i,
                    const double *args, double *vals, double keep[3]) {
  int st;
  keep[0] = (double)w->rng->x48;        /* 48 bits: exact in a double */
  keep[1] = w->rng->iset;
  keep[2] = w->rng->gset;
  m->cpfgtry = 1;
  m->cpfgtried = 0;
  st = evalrule(m, w, r, i, args, vals);
  m->cpfgtry = 0;
  return st;
}

/* Runs the chosen rule that stopped at its mark again, from the state it was
** tried in; at the mark the state becomes the one after every try. */
static int cpfgreplay (lsys_rules *m, lsys_scratch *w, const lsys_rule *r, size_t i,
                       const double *a, lsys_pick *pk) {
  int st;
  m->cpfgz = *w->rng;
  w->rng->x48 = (uint64_t)a[6];
  w->rng->iset = (int)a[7];
  w->rng->gset = a[8];
  m->cpfgtry = 2;
  st = evalrule(m, w, r, i, pk->args, (double *)pk->vals);
  if (m->cpfgtry == 2) *w->rng = m->cpfgz;     /* no mark this time: as after the tries */
  m->cpfgtry = 0;
  if (st < 0) return st;
  if (st == 0)
    return lsys_seterror(&m->err, LSYS_ERULE, i, "the chosen rule did not apply when it ran "
                         "again (cpfg's generator runs a rule's condition twice)");
  if (r->flags & LSYS_RF_DYN) { pk->dyn = &m->dyn; pk->d0 = 0; pk->d1 = m->dyn.n; pk->dp = 0; }
  return LSYS_OK;
}

/* cpfg evaluates the condition and the probability of every production that
** may apply, chooses, and only then the successor of the chosen one
** (generate.c: FindApplProductions, SelectProd, ApplyProd): the values of a
** weighted rule's program are run once it is chosen, drawing their numbers
** after every alternative's condition. (A rule that runs in Lua draws them
** when it is tried.) */
static int cpfgvalues (lsys_rules *m, lsys_scratch *w, const lsys_rule *r, size_t i,
                       lsys_pick *pk) {
  double *vals = (double *)pk->vals;
  lsys_expr_span(r->vm, r->vmtry, r->nvm, pk->args, vals + r->vmtryout, w->rng, m->funcs);
  return lsys_derive_checkvals(m, w, r, i, vals);
}

/*
** Chooses the rule of 'sets' for the module 'code' with parameters 'par'
** whose context is position 'i' of 'v', drawing from w->rng. Returns the
** number of modules the rule rewrites (1, or more for a predecessor of
** several modules) with the rule, its arguments and values in *pk (valid
** until the next call; the successor a function produced in pk->dyn), 0
** when no rule applies, or an error code.
*/
int lsys_derive_choose (lsys_rules *m, lsys_scratch *w, lsys_ruleset *const *sets, int nsets,
                        const view *v, size_t i, uint16_t code, const double *par, lsys_pick *pk) {
  uint32_t sym = LSYS_CSYM(code), np = LSYS_CNP(code);
  size_t nalt = 0, altn = 0;   /* alternatives and doubles used in w->alt */
  double total = 0, keep[3];
  int si, st, tried;
  lsys_ctxmemo mm;
  lsys_context_memo_init(&mm);
  pk->dyn = NULL;
  if (!w->worker) lsys_lstring_clear(&m->altdyn);
  for (si = 0; si < nsets; si++) {
    const lsys_ruleset *s = sets[si];
    uint32_t b, e;
    if (s == NULL || sym >= s->nsym) continue;
    for (b = s->start[sym], e = s->start[sym + 1]; b < e; b++) {
      const lsys_rule *r = &m->rules[s->byp[b]];
      double *args, *vals, wt;
      if (r->pred_np != np) continue;
      if (lsys_derive_needscratch(w, r->nargs + r->nvals + 1) != LSYS_OK) return LSYS_ENOMEM;
      args = w->args;
      vals = args + r->nargs;
      if (r->nmore && (v->single || !matchmore(m, v, i, r, par, args + r->lcargs + np)))
        continue;
      if (r->nlc && (v->match == NULL || !lsys_context_matchleft(m, v, i, r, args, &mm)))
        continue;
      if (r->nrc && (v->match == NULL ||
                     !lsys_context_matchright(m, v, i + 1 + r->nmore, r,
                                              args + r->lcargs + np + r->moreargs,
                                              r->nmore == 0 ? &mm : NULL)))
        continue;
      if (np) memcpy(args + r->lcargs, par, np * sizeof *args);
      tried = m->cpfg && (r->flags & LSYS_RF_STOCH) && r->vm == NULL;
      st = tried ? cpfgtry(m, w, r, i, args, vals, keep) : evalrule(m, w, r, i, args, vals);
      if (st <= 0) {
        if (st < 0) return st;
        continue;
      }
      if (!(r->flags & LSYS_RF_STOCH)) {
        if (nalt > 0) break;                  /* weighted alternatives came first */
        pk->r = r;
        pk->args = args;
        pk->vals = vals;
        if (r->flags & LSYS_RF_DYN) { pk->dyn = &m->dyn; pk->d0 = 0; pk->d1 = m->dyn.n; pk->dp = 0; }
        return 1 + (int)r->nmore;
      }
      wt = (r->flags & LSYS_RF_WEXPR) ? vals[0] : r->weight;
      if (!(wt >= 0) || isinf(wt)) {
        if (w->worker) return LSYS_ERULE;
        m->cur_index = i;
        m->cur_rule = (long)(r - m->rules);
        return lsys_seterror(&m->err, LSYS_ERULE, i, "weight is %g, not a finite number >= 0", wt);
      }
      if ((st = keepalt(m, w, r, wt, args, &altn)) != LSYS_OK) return st;
      if (tried && m->cpfgtried) {
        double *a = w->alt + altn - (ALTHEAD + r->nargs + r->nvals);
        a[5] = 1;
        memcpy(a + 6, keep, sizeof keep);
      }
      nalt++;
      total += wt;
    }
    if (b < e) break;
  }
  /* only weight 0 applies: nothing is chosen (cpfg takes the first) */
  if (nalt == 0 || (!(total > 0) && !m->cpfg)) return 0;
  pickalt(m, w, nalt, total, pk);
  if (m->cpfg) {
    const double *a = pk->args - ALTHEAD;
    if (pk->r->vm != NULL) st = cpfgvalues(m, w, pk->r, i, pk);
    else st = a[5] != 0 ? cpfgreplay(m, w, pk->r, i, a, pk) : LSYS_OK;
    if (st != LSYS_OK) return st;
  }
  return 1 + (int)pk->r->nmore;
}

/* Rewrites the module (see lsys_derive_choose) into 'out' on the calling thread. */
static int rewrite (lsys_rules *m, lsys_ruleset *const *sets, int nsets, const view *v,
                    size_t i, uint16_t code, const double *par, lsys_lstring *out) {
  lsys_pick pk;
  int st;
  m->sc.rng = m->cur;
  st = lsys_derive_choose(m, &m->sc, sets, nsets, v, i, code, par, &pk);
  if (st <= 0) return st;
  st = pk.dyn != NULL ? emitdyn(m, out, pk.dyn, pk.d0, pk.d1, pk.dp)
                      : emit(m, out, pk.r, pk.args, pk.vals);
  return st == LSYS_OK ? (int)(1 + pk.r->nmore) : st;
}

static int pushsub (lsys_rules *m, uint32_t id) {
  if (lsys_common_grow((void **)&m->substack, &m->subcap, m->nsub + 1,
                       sizeof *m->substack) != LSYS_OK)
    return LSYS_ENOMEM;
  m->substack[m->nsub++] = id;
  return LSYS_OK;
}

/* The production sets for sub-L-system 'sub': the active group, then 0. */
static int prodsets (lsys_rules *m, int sub, lsys_ruleset **sets) {
  int n = 0;
  if (m->group != 0 && (sets[n] = lsys_derive_findset(m, LSYS_PROD, sub, m->group)) != NULL) n++;
  if ((sets[n] = lsys_derive_findset(m, LSYS_PROD, sub, 0)) != NULL) n++;
  return n;
}

static int compileall (lsys_rules *m, int kind, int *hasctx) {
  size_t k;
  *hasctx = 0;
  for (k = 0; k < m->nsets; k++)
    if (m->sets[k].kind == kind) {
      if (lsys_derive_compileset(m, &m->sets[k]) != LSYS_OK) return LSYS_ENOMEM;
      if (m->sets[k].hasctx) *hasctx = 1;
    }
  return LSYS_OK;
}

static int limiterror (lsys_rules *m, size_t i) {
  return lsys_seterror(&m->err, LSYS_ELIMIT, i,
                       "the string would exceed max_modules (%zu modules)", m->max_modules);
}

static int fail (lsys_rules *m, int st, size_t i) {
  if (st == LSYS_ELIMIT) return limiterror(m, i);
  if (st == LSYS_ENOMEM) return lsys_seterror(&m->err, st, i, "not enough memory");
  if (st == LSYS_EMEMORY) {
    char b[32];
    return lsys_seterror(&m->err, st, i, "the derivation would need more than max_memory (%s) "
                         "at module %zu (set max_memory in the model, or LSYS_MAX_MEMORY)",
                         lsys_common_fmtsize(b, m->meter.limit), i + 1);
  }
  return st;
}

/* The calling thread's context window of the string whose tables were just
** built: none yet, made when the loop reaches a module (lsys_context_ensure). */
static void newwin (lsys_rules *m) {
  m->win.g = &m->brk;
  m->win.wn = m->win.ca = m->win.cb = 0;
}

/* The view of 'src' a step reads, with the context tables when its rules have contexts. */
static int setview (lsys_rules *m, const lsys_lstring *src, int hasctx, view *v) {
  int st;
  memset(v, 0, sizeof *v);
  v->code = src->code; v->code8 = src->sym8; v->par = src->par; v->n = src->n;
  v->ring = m->ring;
  v->eq = lsys_context_eqsym(m);
  v->skip = lsys_derive_findskip(m, 0);
  if (hasctx) {
    if ((st = lsys_context_buildtables(m, src)) != LSYS_OK) return st;
    newwin(m);
    v->match = &m->win;
  }
  return LSYS_OK;
}

/*
** The fast loop's table for 'productions' (one entry per symbol, when a
** single rule set applies): ACT_COPY copies the module, a rule index copies
** that rule's template or runs its expression program, ACT_SLOW takes the
** full path (contexts, stochastic or several rules, cut, sub-L-systems).
** Sets *nact to the table's length (0: no table).
*/
static int fasttable (lsys_rules *m, lsys_ruleset *const *sets, int nsets, size_t *nact) {
  const lsys_ruleset *s0 = nsets ? sets[0] : NULL;
  uint32_t k;
  *nact = 0;
  if (nsets > 1) return LSYS_OK;
  if (m->actcap < m->ab->n &&
      lsys_common_grow((void **)&m->act, &m->actcap, m->ab->n, sizeof *m->act) != LSYS_OK)
    return LSYS_ENOMEM;
  *nact = m->ab->n;
  for (k = 0; k < *nact; k++) {
    int hasrules = s0 != NULL && k < s0->nsym && s0->start[k] != s0->start[k + 1];
    if (k == LSYS_SYM_CUT || k == LSYS_SYM_SUB || k == LSYS_SYM_SUBEND) m->act[k] = ACT_SLOW;
    else if (!hasrules) m->act[k] = ACT_COPY;
    else if (s0->plain[k] != NONE)
      m->act[k] = s0->plain[k];
    else {       /* the only rule for k, computed by the expression machine */
      const lsys_rule *r = &m->rules[s0->byp[s0->start[k]]];
      m->act[k] = (s0->start[k + 1] - s0->start[k] == 1 && r->vm != NULL && r->nlc == 0 &&
                   r->nrc == 0 && r->nmore == 0 && !(r->flags & (LSYS_RF_STOCH | LSYS_RF_DYN)))
                  ? s0->byp[s0->start[k]] : ACT_SLOW;
      if (m->act[k] != ACT_SLOW && lsys_derive_needscratch(&m->sc, r->nvals + 1) != LSYS_OK)
        return LSYS_ENOMEM;
    }
  }
  return LSYS_OK;
}

/* A cut % at module i: skips to the unmatched ']' or the '$' that closes
** the sub-L-system the cut is in (either kept; as cpfg, a '$' with no
** '?(...)' after the cut ends it even outside a sub-L-system), or the end of
** 'src', advancing *p over the parameters; returns the index before the
** stop (the loop's increment lands on it). */
static size_t skipcut (const lsys_lstring *src, size_t i, size_t *p) {
  size_t depth = 0, subs = 0, n = src->n;
  *p += LSYS_CNP(src->code[i]);
  for (i++; i < n; i++) {
    uint32_t s = LSYS_CSYM(src->code[i]);
    if (s == LSYS_SYM_LBR) depth++;
    else if (s == LSYS_SYM_RBR && depth-- == 0) break;
    else if (s == LSYS_SYM_SUB && LSYS_CNP(src->code[i]) > 0) subs++;
    else if (s == LSYS_SYM_SUBEND && subs-- == 0) break;
    *p += LSYS_CNP(src->code[i]);
  }
  return i - 1;
}

/* Module i enters a sub-L-system (?(id, scale), 'idd' its first parameter)
** or leaves one ($): the rule sets and the ignore list switch to it. */
static int subswitch (lsys_rules *m, uint32_t sym, double idd, size_t i, lsys_ruleset **sets,
                      int *nsets, view *v) {
  int sub;
  size_t k;
  if (sym == LSYS_SYM_SUB) {
    sub = (idd >= 0 && idd < 1e9) ? (int)idd : -1;
    if (sub < 0 || (lsys_derive_findset(m, LSYS_PROD, sub, 0) == NULL && sub != 0))
      return lsys_seterror(&m->err, LSYS_ERULE, i,
                           "sub-L-system %g is not defined (module %zu)", idd, i + 1);
    for (k = 0; k < m->nsub && (uint32_t)sub != m->substack[k]; k++) {}
    if (sub == 0 || k < m->nsub)      /* as cpfg: an active L-system is not entered again */
      return lsys_seterror(&m->err, LSYS_ERULE, i, "recursive call to sub-L-system %d "
                           "(module %zu): it is active already%s", sub, i + 1,
                           sub == 0 ? " (0 is the main L-system)" : "");
    if (pushsub(m, (uint32_t)sub) != LSYS_OK) return fail(m, LSYS_ENOMEM, i);
  }
  else
    sub = --m->nsub > 0 ? (int)m->substack[m->nsub - 1] : 0;
  *nsets = prodsets(m, sub, sets);
  v->skip = lsys_derive_findskip(m, sub);
  return LSYS_OK;
}

/* The productions of one step on the calling thread: the module loop. */
/* cpfg draws the number that chooses a production for every module it visits
** in a stochastic L-system, whether a rule applies to it or not (generate.c). */
static void cpfgdraw (lsys_rules *m, lsys_ruleset *const *sets, int nsets) {
  int k;
  m->choice_ready = 0;
  for (k = 0; k < nsets; k++) {
    if (sets[k] != NULL && sets[k]->stoch) {
      m->choice_u = lsys_drand48(&m->choice48);
      m->choice_ready = 1;
      return;
    }
  }
}

static int seqloop (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst, view *vp,
                    lsys_ruleset **sets, int nsets) {
  int st;
  size_t i, p = 0, n = src->n, lim, nact;
  const double *spar = parof(src, 0);
  view v = *vp;
  /* room for at least a copy of the source */
  if ((st = lsys_lstring_reserve(dst, n < m->max_modules ? n : m->max_modules, src->npar))
      != LSYS_OK)
    return fail(m, st, 0);
  if ((st = fasttable(m, sets, nsets, &nact)) != LSYS_OK) return fail(m, st, 0);
  lim = dst->cap < m->max_modules ? dst->cap : m->max_modules;
  for (i = 0; i < n; i++) {
    uint16_t c = src->code[i];
    uint32_t sym = LSYS_CSYM(c), np = LSYS_CNP(c);
    const lsys_ruleset *s0 = nsets ? sets[nsets - 1] : NULL;
    int done = 0;
    if (m->cpfg) cpfgdraw(m, sets, nsets);
    if (sym < nact && m->nsub == 0) {     /* the fast loop */
      uint32_t a = m->act[sym];
      if (a == ACT_COPY && dst->n < lim) {
        if (np == 0) {
          dst->code[dst->n++] = c;
          continue;
        }
        if (dst->npar + np <= dst->parcap) {
          const double *q = src->par + p;
          double *o = dst->par + dst->npar;
          uint32_t k;
          for (k = 0; k < np; k++) o[k] = q[k];
          dst->npar += np;
          dst->code[dst->n++] = c;
          p += np;
          continue;
        }
      }
      if (a < ACT_COPY) {
        const lsys_rule *r = &m->rules[a];
        if (r->pred_np == np && r->vm == NULL && r->nsrc == 0 && dst->n + r->nsucc <= lim) {
          const uint16_t *t = m->tcode + r->succ;
          uint16_t *o = dst->code + dst->n;
          uint32_t k;
          for (k = 0; k < r->nsucc; k++) o[k] = t[k];
          dst->n += r->nsucc;
          p += np;
          continue;
        }
        if (r->pred_np == np && r->vm != NULL) {   /* the only rule: no need to look further */
          lsys_rng_at(m->cur, i);
          if (lsys_expr_run(r->vm, r->nvm, spar + p, m->sc.args, m->cur, m->funcs)) {
            /* a bad value is reported here: running the program again in the full
            ** path would draw its random numbers again */
            if ((st = lsys_derive_checkvals(m, &m->sc, r, i, m->sc.args)) != LSYS_OK) return st;
            if ((st = emit(m, dst, r, spar + p, m->sc.args)) != LSYS_OK) return fail(m, st, i);
            p += np;
            lim = dst->cap < m->max_modules ? dst->cap : m->max_modules;
            continue;
          }
          else {                           /* condition false: the module stays */
            if (dst->n >= m->max_modules) return limiterror(m, i);
            if ((st = lsys_lstring_push(dst, sym, spar + p, np)) != LSYS_OK) return fail(m, st, i);
            p += np;
            lim = dst->cap < m->max_modules ? dst->cap : m->max_modules;
            continue;
          }
        }
        else if (r->pred_np == np && r->nsrc > 0) {
          if ((st = emit(m, dst, r, spar + p, NULL)) != LSYS_OK) return fail(m, st, i);
          p += np;
          lim = dst->cap < m->max_modules ? dst->cap : m->max_modules;
          continue;
        }
      }
    }
    if (nsets > 1 || (s0 != NULL && sym < s0->nsym && s0->start[sym] != s0->start[sym + 1])) {
      lsys_rng_at(m->cur, i);
      (void)lsys_context_ensure(&v, i);   /* (without one the string's tables answer) */
      done = rewrite(m, sets, nsets, &v, i, c, spar + p, dst);
      if (done < 0) return fail(m, done, i);
      for (; done > 1; done--) {      /* the predecessor's other modules are rewritten too */
        p += np;
        c = src->code[++i];
        np = LSYS_CNP(c);
      }
    }
    if (!done) {
      if (sym == LSYS_SYM_CUT) {
        i = skipcut(src, i, &p);
        continue;
      }
      if (dst->n >= m->max_modules) return limiterror(m, i);
      if (dst->n == dst->cap || dst->npar + np > dst->parcap) {
        if ((st = lsys_lstring_reserve(dst, 1, np)) != LSYS_OK) return fail(m, st, i);
      }
      dst->code[dst->n++] = c;
      if (np) {
        memcpy(dst->par + dst->npar, src->par + p, np * sizeof(double));
        dst->npar += np;
      }
    }
    if ((sym == LSYS_SYM_SUB && np >= 1) || (sym == LSYS_SYM_SUBEND && m->nsub > 0)) {
      double idd = sym == LSYS_SYM_SUB ? src->par[p] : 0;
      if ((st = subswitch(m, sym, idd, i, sets, &nsets, &v)) != LSYS_OK) return st;
    }
    p += np;
    lim = dst->cap < m->max_modules ? dst->cap : m->max_modules;
  }
  return LSYS_OK;
}

/* Makes 's' wide within the step's budget (a narrow string, lstring.h). */
int lsys_derive_widen (lsys_rules *m, lsys_lstring *s) {
  lsys_meter *keep = s->meter;
  int st;
  if (s->sym8 == NULL) return LSYS_OK;
  s->meter = &m->meter;
  st = lsys_lstring_widen(s);
  s->meter = keep;
  return st;
}

/* Exchanges the contents of two strings (each keeps its meter). */
void lsys_derive_swapstr (lsys_lstring *a, lsys_lstring *b) {
  lsys_lstring t = *a;
  lsys_meter *ma = a->meter, *mb = b->meter;
  *a = *b;
  *b = t;
  a->meter = ma;
  b->meter = mb;
  a->nck = b->nck = 0;
}

/* The productions of a step; 'dst' may be 'src' (rewritten in place, or
** into m->tmp and exchanged). */
static int productions (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst) {
  lsys_ruleset *sets[2];
  int nsets, hasctx, st;
  lsys_lstring *out = dst == src ? &m->tmp : dst;
  view v;
  m->nsub = 0;
  if (compileall(m, LSYS_PROD, &hasctx) != LSYS_OK) return fail(m, LSYS_ENOMEM, 0);
  if ((st = setview(m, src, hasctx, &v)) != LSYS_OK) return fail(m, st, 0);   /* narrow or */
  nsets = prodsets(m, 0, sets);
  if ((st = lsys_derive_par_productions(m, src, dst, &v, sets, nsets)) != LSYS_PAR_SEQ) return st;
  if ((st = lsys_derive_widen(m, src)) != LSYS_OK) return fail(m, st, 0);
  v.code = src->code;                                   /* the tables stay as they are */
  v.code8 = NULL;
  lsys_lstring_clear(out);
  st = seqloop(m, src, out, &v, sets, nsets);
  m->choice_ready = 0;
  if (st != LSYS_OK) return st;
  if (out != dst) lsys_derive_swapstr(src, out);
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* Decomposition and homomorphism: recursive rewriting of single modules. */

static int needlevels (lsys_rules *m, size_t n) {
  if (m->nlevels < n) {
    lsys_lstring *lv = (lsys_lstring *)LSYS_REALLOC(m->levels, n * sizeof *lv);
    if (lv == NULL) return LSYS_ENOMEM;
    m->levels = lv;
    while (m->nlevels < n) {               /* under the running operation's budget */
      lsys_lstring_init(&m->levels[m->nlevels]);
      if (m->busy) m->levels[m->nlevels].meter = &m->meter;
      m->nlevels++;
    }
  }
  return LSYS_OK;
}

/* Expands module i (or, at depth 0, the modules a predecessor of several
** modules starting at i takes) into 'out'. Returns the number of modules
** after i that the rule took as well (0 but at depth 0), or an error code. */
static int expandone (lsys_rules *m, int kind, lsys_ruleset *const *sets, int nsets,
                      const view *v, size_t i, uint16_t code, const double *par, int depth,
                      lsys_lstring *out) {
  uint32_t np = LSYS_CNP(code);
  if (depth < m->maxdepth[kind]) {
    lsys_lstring *lv = &m->levels[depth];
    int st;
    lsys_lstring_clear(lv);
    st = rewrite(m, sets, nsets, v, i, code, par, lv);
    if (st < 0) return st;
    if (st >= 1) {
      size_t k, p = 0;
      view made = *v;          /* what the rule made has no modules after it in v */
      int more = st - 1;
      made.single = 1;
      for (k = 0; k < lv->n; k++) {
        st = expandone(m, kind, sets, nsets, &made, i, lv->code[k], parof(lv, p), depth + 1,
                       out);
        if (st < 0) return st;
        p += LSYS_CNP(lv->code[k]);
      }
      return more;
    }
  }
  else if (!m->depth_hit) {        /* could a rule go deeper? (for the warning; */
    int k;                           /* nothing is evaluated: no side effects) */
    uint32_t sym = LSYS_CSYM(code);
    for (k = 0; k < nsets; k++) {
      const lsys_ruleset *s = sets[k];
      uint32_t b;
      if (s == NULL || sym >= s->nsym) continue;
      for (b = s->start[sym]; b < s->start[sym + 1]; b++)
        if (m->rules[s->byp[b]].pred_np == np) m->depth_hit = 1;
    }
  }
  if (out->n >= m->max_modules) return LSYS_ELIMIT;
  return lsys_lstring_push(out, LSYS_CSYM(code), par, np);
}

/* Whether no rule of set s applies to module 'code' (parameters 'par') for
** certain: every rule for it without contexts or weights, its condition of
** lsys_expr_fast's form and false. (0: it may apply, or cannot be told so.) */
static int nonefast (const lsys_rules *m, const lsys_ruleset *s, uint16_t code,
                     const double *par) {
  uint32_t sym = LSYS_CSYM(code), np = LSYS_CNP(code), b;
  for (b = s->start[sym]; b < s->start[sym + 1]; b++) {
    const lsys_rule *r = &m->rules[s->byp[b]];
    if (r->pred_np != np) continue;
    if (r->vm == NULL || !r->fx.ok || !r->fx.cond || r->nlc || r->nrc || r->nmore ||
        (r->flags & (LSYS_RF_STOCH | LSYS_RF_DYN)) || lsys_expr_term(&r->fx.t[0], par) != 0)
      return 0;
  }
  return 1;
}

/* The first module of 'src' a rule of sets[0] rewrites (src->n: none), *p
** its first parameter; a rule's error is left for the full loop to give. */
static size_t firstchange (lsys_rules *m, lsys_ruleset *const *sets, const view *v,
                           const lsys_lstring *src, size_t *p) {
  const lsys_ruleset *s = sets[0];
  size_t i;
  lsys_pick pk;
  for (i = 0, *p = 0; i < src->n; *p += LSYS_CNP(src->code[i]), i++) {
    uint16_t c = src->code[i];
    uint32_t sym = LSYS_CSYM(c);
    if (sym >= s->nsym || s->start[sym] == s->start[sym + 1] || nonefast(m, s, c, parof(src, *p)))
      continue;
    lsys_rng_at(m->cur, i);
    m->sc.rng = m->cur;
    if (lsys_derive_choose(m, &m->sc, sets, 1, v, i, c, parof(src, *p), &pk) != 0) return i;
  }
  return src->n;
}

/* Expands every module of 'src' into 'dst'. With 'same' (not NULL), a string
** no rule rewrites is not copied: *same = 1, and 'dst' is left empty. */
static int expandall (lsys_rules *m, int kind, lsys_lstring *src, lsys_lstring *dst, int *same) {
  lsys_ruleset *sets[1];
  int hasctx, st;
  size_t i, p = 0;
  view v;
  if (same != NULL) *same = 0;
  lsys_lstring_clear(dst);
  if ((st = lsys_derive_widen(m, src)) != LSYS_OK) return fail(m, st, 0);
  if (compileall(m, kind, &hasctx) != LSYS_OK) return fail(m, LSYS_ENOMEM, 0);
  if ((sets[0] = lsys_derive_findset(m, kind, 0, 0)) == NULL || sets[0]->nlist == 0)
    return (st = lsys_lstring_copy(dst, src)) == LSYS_OK ? LSYS_OK : fail(m, st, 0);
  if (needlevels(m, (size_t)m->maxdepth[kind] + 1) != LSYS_OK) return fail(m, LSYS_ENOMEM, 0);
  if ((st = setview(m, src, hasctx, &v)) != LSYS_OK) return fail(m, st, 0);
  i = 0;
  if (same != NULL && !hasctx && sets[0]->pure) {   /* (a decomposition rewrites few */
    i = firstchange(m, sets, &v, src, &p);                /* modules, and often none) */
    if (i == src->n) {
      *same = 1;
      return LSYS_OK;
    }
    if (i > 0 && (st = lsys_lstring_append(dst, src, 0, i, 0)) != LSYS_OK) return fail(m, st, i);
  }
  for (; i < src->n; i++) {
    const lsys_ruleset *s = sets[0];
    size_t e = i, q = p;
    while (e < src->n && (LSYS_CSYM(src->code[e]) >= s->nsym ||     /* modules no rule of */
           s->start[LSYS_CSYM(src->code[e])] == s->start[LSYS_CSYM(src->code[e]) + 1] ||
           nonefast(m, s, src->code[e], parof(src, q)))) {          /* the set applies to: */
      q += LSYS_CNP(src->code[e]);                                  /* copied as they are */
      e++;
    }
    if (e > i && dst->n + (e - i) <= m->max_modules) {
      if ((st = lsys_lstring_append(dst, src, i, e, p)) != LSYS_OK) return fail(m, st, i);
      i = e - 1;
      p = q;
      continue;
    }
    lsys_rng_at(m->cur, i);      /* one stream of draws for a module and what it becomes */
    (void)lsys_context_ensure(&v, i);
    st = expandone(m, kind, sets, 1, &v, i, src->code[i], parof(src, p), 0, dst);
    if (st < 0) return fail(m, st, i);
    p += LSYS_CNP(src->code[i]);
    for (; st > 0 && i + 1 < src->n; st--) {    /* taken by a predecessor of several */
      i++;
      p += LSYS_CNP(src->code[i]);
    }
  }
  return LSYS_OK;
}

/*
** The budget of one operation: everything the model holds for it (the
** strings it reads and writes, the scratch strings, the context tables) is
** counted, and the strings that grow are attached to the meter until the
** operation ends. Returns LSYS_EMEMORY when the budget is spent already.
*/
static int meter (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst) {
  size_t k, used = lsys_lstring_bytes(src) + lsys_lstring_bytes(&m->dyn) +
                   lsys_lstring_bytes(&m->tmp) + lsys_lstring_bytes(&m->altdyn) +
                   m->brk.farcap * sizeof *m->brk.far + m->brk.pckcap * sizeof *m->brk.pck +
                   m->brk.stkcap * sizeof *m->brk.stk + lsys_context_winbytes(&m->win) +
                   lsys_derive_par_bytes(m);
  if (dst != NULL && dst != src) used += lsys_lstring_bytes(dst);
  for (k = 0; k < m->nlevels; k++) used += lsys_lstring_bytes(&m->levels[k]);
  m->meter.limit = m->max_memory > 0 ? m->max_memory : lsys_common_memory_limit();
  m->meter.used = used;
  if (used > m->meter.limit) return fail(m, LSYS_EMEMORY, 0);
  if (dst != NULL) dst->meter = &m->meter;
  m->tmp.meter = m->dyn.meter = m->altdyn.meter = &m->meter;
  for (k = 0; k < m->nlevels; k++) m->levels[k].meter = &m->meter;
  return LSYS_OK;
}

static void unmeter (lsys_rules *m, lsys_lstring *dst) {
  size_t k;
  if (dst != NULL) dst->meter = NULL;
  m->tmp.meter = m->dyn.meter = m->altdyn.meter = NULL;
  for (k = 0; k < m->nlevels; k++) m->levels[k].meter = NULL;
}

/* The error of the operation 'what' started while the model is busy. */
static int reentered (lsys_rules *m, const char *what) {
  return lsys_seterror(&m->err, LSYS_EBUSY, (size_t)-1,
                       "a rule called %s on the model it belongs to", what);
}

/* The homomorphism draws from its own generator; cpfg's nrand keeps one pair
** for the process, which the homomorphism's generator shares. */
static void usehrng (lsys_rules *m) {
  m->cur = &m->hrng;
  if (m->cpfg) { m->hrng.iset = m->rng.iset; m->hrng.gset = m->rng.gset; }
}

static void leavehrng (lsys_rules *m) {
  if (m->cpfg) { m->rng.iset = m->hrng.iset; m->rng.gset = m->hrng.gset; }
}

int lsys_derive_expand (lsys_rules *m, int kind, lsys_lstring *src, lsys_lstring *dst) {
  int st;
  lsys_rng *keep = m->cur;
  if (m->busy) return reentered(m, "expand");
  if (kind != LSYS_HOMO && kind != LSYS_DECOMP)
    return lsys_seterror(&m->err, LSYS_EARG, (size_t)-1, "bad rule kind");
  if (src == dst) return lsys_seterror(&m->err, LSYS_EARG, (size_t)-1, "expand in place");
  m->depth_hit = 0;
  if ((st = meter(m, src, dst)) != LSYS_OK) return st;
  if (kind == LSYS_HOMO && !m->hshare) usehrng(m);
  m->busy = 1;
  st = expandall(m, kind, src, dst, NULL);
  lsys_context_freewin(&m->win);      /* the operation's scratch, not the model's */
  m->busy = 0;
  if (kind == LSYS_HOMO && !m->hshare) leavehrng(m);
  unmeter(m, dst);
  m->cur = keep;
  return st;
}

/* Streaming homomorphism: the turtle asks for one module at a time. */
int lsys_derive_homo_begin (lsys_rules *m, lsys_lstring *src) {
  lsys_ruleset *set;
  int hasctx = 0;
  int st;
  if (m->busy) return reentered(m, "interpret");
  m->hsrc = NULL;
  m->depth_hit = 0;
  if (compileall(m, LSYS_HOMO, &hasctx) != LSYS_OK) return fail(m, LSYS_ENOMEM, 0);
  set = lsys_derive_findset(m, LSYS_HOMO, 0, 0);
  if (set == NULL || set->nlist == 0 || m->maxdepth[LSYS_HOMO] < 1) return 0;
  if (lsys_lstring_widen(src) != LSYS_OK) return fail(m, LSYS_ENOMEM, 0);
  if (needlevels(m, (size_t)m->maxdepth[LSYS_HOMO] + 1) != LSYS_OK)
    return fail(m, LSYS_ENOMEM, 0);
  if ((st = meter(m, src, NULL)) != LSYS_OK) return st;   /* until lsys_derive_homo_end */
  if (hasctx && (st = lsys_context_buildtables(m, src)) != LSYS_OK) {
    unmeter(m, NULL);
    return fail(m, st, 0);
  }
  newwin(m);
  m->hsrc = src;
  m->hctx = hasctx;
  m->hkeep = m->cur;
  if (!m->hshare) usehrng(m);
  m->busy = 1;                 /* until lsys_derive_homo_end */
  return 1;
}

int lsys_derive_homo_module (lsys_rules *m, size_t i, size_t poff, lsys_lstring *out) {
  lsys_ruleset *sets[1];
  const lsys_lstring *src = m->hsrc;
  uint16_t code;
  uint32_t sym;
  view v;
  int st;
  if (src == NULL || i >= src->n) return 0;
  code = src->code[i];
  sym = LSYS_CSYM(code);
  sets[0] = lsys_derive_findset(m, LSYS_HOMO, 0, 0);
  if (sym >= sets[0]->nsym || sets[0]->start[sym] == sets[0]->start[sym + 1]) return 0;
  memset(&v, 0, sizeof v);
  v.code = src->code; v.par = src->par; v.n = src->n; v.ring = m->ring;
  v.eq = lsys_context_eqsym(m);
  v.skip = lsys_derive_findskip(m, 0);
  if (m->hctx) {
    v.match = &m->win;
    (void)lsys_context_ensure(&v, i);
  }
  lsys_lstring_clear(out);
  lsys_rng_at(m->cur, i);
  st = expandone(m, LSYS_HOMO, sets, 1, &v, i, code, parof(src, poff), 0, out);
  if (st < 0) return fail(m, st, i);
  return 1 + st;
}

void lsys_derive_homo_end (lsys_rules *m) {
  lsys_context_freewin(&m->win);
  if (m->hsrc != NULL) {
    if (m->cur == &m->hrng) leavehrng(m);
    m->cur = m->hkeep;
    m->busy = 0;
    unmeter(m, NULL);
  }
  m->hsrc = NULL;
}

static int derivestep (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst) {
  int st;
  long sz;
  lsys_rng_stream(&m->rng, m->rng.step + 1, LSYS_RNG_PROD);
  if ((st = productions(m, src, dst)) != LSYS_OK) return st;
  sz = lsys_rules_setsize(m, LSYS_DECOMP, 0, 0);
  if (sz > 0) {
    int same;
    lsys_rng_stream(&m->rng, m->rng.step, LSYS_RNG_DECOMP);
    if ((st = expandall(m, LSYS_DECOMP, dst, &m->tmp, &same)) != LSYS_OK) return st;
    if (!same) lsys_derive_swapstr(dst, &m->tmp);
  }
  return LSYS_OK;
}

int lsys_derive_step (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst) {
  int st;
  if (m->busy) return reentered(m, "step");
  m->depth_hit = 0;
  m->cur = &m->rng;
  if ((st = meter(m, src, dst)) != LSYS_OK) return st;
  m->busy = 1;
  st = derivestep(m, src, dst);
  lsys_context_freewin(&m->win);      /* the operation's scratch, not the model's */
  lsys_rng_stream(&m->rng, m->rng.step, LSYS_RNG_BETWEEN);
  m->busy = 0;
  unmeter(m, dst);
  if (src == dst) {          /* the string before the step is not kept */
    lsys_lstring_free(&m->tmp);
    if (st != LSYS_OK) lsys_lstring_clear(src);
  }
  return st;
}
