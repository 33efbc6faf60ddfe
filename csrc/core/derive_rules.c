/*
** The rules of a derivation model (derive.h): rule storage, rule sets by
** predecessor, ignore and consider lists, expression programs and positional
** functions. derive.c rewrites with them, derive_par.c on several threads.
*/
#include <math.h>
#include <string.h>

#include "derive_impl.h"

int lsys_rules_init (lsys_rules *m, lsys_alphabet *ab) {
  memset(m, 0, sizeof *m);
  m->ab = ab;
  m->max_modules = 50000000;
  m->maxdepth[LSYS_DECOMP] = 1;
  m->maxdepth[LSYS_HOMO] = 1;
  m->cur = &m->rng;
  m->cur_rule = -1;
  m->parmin = LSYS_PARMIN;
  lsys_rng_seed(&m->rng, 0);
  lsys_rng_seed(&m->hrng, 0);
  return LSYS_OK;
}

void lsys_rules_free (lsys_rules *m) {
  size_t i;
  for (i = 0; i < m->nsets; i++) {
    LSYS_FREE(m->sets[i].list);
    LSYS_FREE(m->sets[i].byp);
    LSYS_FREE(m->sets[i].start);
    LSYS_FREE(m->sets[i].plain);
  }
  for (i = 0; i < m->nrules; i++) LSYS_FREE(m->rules[i].vm);
  LSYS_FREE(m->funcs);
  for (i = 0; i < m->nlevels; i++) lsys_lstring_free(&m->levels[i]);
  LSYS_FREE(m->levels);
  LSYS_FREE(m->sets);
  LSYS_FREE(m->skips);
  LSYS_FREE(m->rules);
  LSYS_FREE(m->pat);
  LSYS_FREE(m->tcode);
  LSYS_FREE(m->tsrc);
  LSYS_FREE(m->sc.args);
  LSYS_FREE(m->sc.alt);
  lsys_derive_par_free(m);
  LSYS_FREE(m->brk.far);
  LSYS_FREE(m->brk.pck);
  LSYS_FREE(m->brk.stk);
  lsys_context_freewin(&m->win);
  LSYS_FREE(m->substack);
  LSYS_FREE(m->act);
  lsys_lstring_free(&m->dyn);
  lsys_lstring_free(&m->tmp);
  lsys_lstring_free(&m->altdyn);
  memset(m, 0, sizeof *m);
}

lsys_ruleset *lsys_derive_findset (const lsys_rules *m, int kind, int sub, int group) {
  size_t i;
  for (i = 0; i < m->nsets; i++)
    if (m->sets[i].kind == kind && m->sets[i].sub == sub && m->sets[i].group == group)
      return &m->sets[i];
  return NULL;
}

long lsys_rules_setsize (const lsys_rules *m, int kind, int sub, int group) {
  lsys_ruleset *s = lsys_derive_findset(m, kind, sub, group);
  return s ? (long)s->nlist : -1;
}

lsys_skip *lsys_derive_findskip (const lsys_rules *m, int sub) {
  size_t i;
  for (i = 0; i < m->nskips; i++)
    if (m->skips[i].sub == sub) return &m->skips[i];
  return NULL;
}

/* The error of a change to the rules while the model is busy. */
static int busyerror (lsys_rules *m, lsys_error *e) {
  return lsys_seterror(e != NULL ? e : &m->err, LSYS_EBUSY, (size_t)-1,
                       "the model is deriving: its rules cannot change now");
}

int lsys_rules_skiplist (lsys_rules *m, int sub, int consider,
                         const uint32_t *syms, size_t n) {
  lsys_skip *k = lsys_derive_findskip(m, sub);
  size_t i;
  if (m->busy) return busyerror(m, NULL);
  if (k == NULL) {
    if (lsys_common_grow((void **)&m->skips, &m->skipcap, m->nskips + 1,
                         sizeof *m->skips) != LSYS_OK)
      return LSYS_ENOMEM;
    k = &m->skips[m->nskips++];
  }
  memset(k, 0, sizeof *k);
  k->sub = sub;
  k->consider = consider;
  for (i = 0; i < n; i++)
    if (syms[i] <= LSYS_MAXSYM) k->bits[syms[i] >> 3] |= (uint8_t)(1u << (syms[i] & 7));
  lsys_context_classes(k);
  return LSYS_OK;
}

int lsys_rules_newset (lsys_rules *m, int kind, int sub, int group) {
  lsys_ruleset *set;
  if (m->busy) return busyerror(m, NULL);
  if (lsys_derive_findset(m, kind, sub, group) != NULL) return LSYS_OK;
  if (lsys_common_grow((void **)&m->sets, &m->setcap, m->nsets + 1, sizeof *m->sets) != LSYS_OK)
    return LSYS_ENOMEM;
  set = &m->sets[m->nsets++];
  memset(set, 0, sizeof *set);
  set->kind = kind; set->sub = sub; set->group = group;
  return LSYS_OK;
}

/* The modules after the first of a strict predecessor: no brackets, cuts or
** sub-L-system modules (they would change the rules in force mid-match). */
static int predmodules (const lsys_rulespec *sp, lsys_error *e) {
  uint32_t k;
  for (k = 0; k < sp->nmore; k++) {
    uint32_t s = sp->more[k].sym;
    if (sp->more[k].np > LSYS_MAXPARAMS)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "too many parameters");
    if (s == LSYS_SYM_LBR || s == LSYS_SYM_RBR || s == LSYS_SYM_CUT || s == LSYS_SYM_SUB ||
        s == LSYS_SYM_SUBEND)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "module %u of the predecessor cannot "
                           "be a bracket, a cut or a sub-L-system module", (unsigned)k + 2);
  }
  if (sp->pred.sym == LSYS_SYM_CUT || sp->pred.sym == LSYS_SYM_SUB ||
      sp->pred.sym == LSYS_SYM_SUBEND)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "a predecessor of several modules cannot "
                         "start with a cut or a sub-L-system module");
  return LSYS_OK;
}

long lsys_rules_add (lsys_rules *m, int kind, int sub, int group,
                     const lsys_rulespec *sp, lsys_error *e) {
  lsys_ruleset *set = lsys_derive_findset(m, kind, sub, group);
  lsys_rule *r;
  uint32_t k, nargs = 0, lcargs = 0;
  if (m->busy) return busyerror(m, e);
  if (sp->pred.np > LSYS_MAXPARAMS)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "too many parameters");
  if ((sp->flags & LSYS_RF_DYN) && (sp->flags & LSYS_RF_WEXPR))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "a rule with a function has a number as its weight");
  if (sp->nmore > 0) {       /* cpfg's strict predecessor of several modules */
    if (kind == LSYS_DECOMP)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "a predecessor of several modules is "
                           "for productions and the homomorphism only, not for the "
                           "decomposition");
    int st = predmodules(sp, e);
    if (st != LSYS_OK) return st;
  }
  if (set == NULL) {
    if (lsys_rules_newset(m, kind, sub, group) != LSYS_OK) goto nomem;
    set = lsys_derive_findset(m, kind, sub, group);
  }
  if (lsys_common_grow((void **)&m->rules, &m->rulecap, m->nrules + 1,
                       sizeof *m->rules) != LSYS_OK ||
      lsys_common_grow((void **)&set->list, &set->listcap, set->nlist + 1,
                       sizeof *set->list) != LSYS_OK ||
      lsys_common_grow((void **)&m->pat, &m->patcap, m->npat + sp->nlc + sp->nmore + sp->nrc,
                       sizeof *m->pat) != LSYS_OK ||
      /* + 1: the code array exists once a rule does (no NULL + 0 for empty successors) */
      lsys_common_grow((void **)&m->tcode, &m->tcodecap, m->ntcode + sp->nsucc + 1,
                       sizeof *m->tcode) != LSYS_OK ||
      lsys_common_grow((void **)&m->tsrc, &m->tsrccap, m->ntsrc + sp->nsrc,
                       sizeof *m->tsrc) != LSYS_OK)
    goto nomem;
  r = &m->rules[m->nrules];
  memset(r, 0, sizeof *r);
  r->pred = sp->pred.sym;
  r->pred_np = sp->pred.np;
  r->flags = sp->flags;
  r->weight = sp->weight;
  r->id = sp->id;
  r->nvals = sp->nvals;
  r->lc = (uint32_t)m->npat;
  r->nlc = sp->nlc;
  for (k = 0; k < sp->nlc; k++) { m->pat[m->npat++] = sp->lc[k]; lcargs += sp->lc[k].np; }
  r->more = (uint32_t)m->npat;
  r->nmore = sp->nmore;
  for (k = 0; k < sp->nmore; k++) {
    m->pat[m->npat++] = sp->more[k];
    r->moreargs += sp->more[k].np;
  }
  r->rc = (uint32_t)m->npat;
  r->nrc = sp->nrc;
  for (k = 0; k < sp->nrc; k++) { m->pat[m->npat++] = sp->rc[k]; nargs += sp->rc[k].np; }
  r->lcargs = lcargs;
  r->nargs = lcargs + sp->pred.np + r->moreargs + nargs;
  r->succ = (uint32_t)m->ntcode;
  r->nsucc = sp->nsucc;
  if (sp->nsucc) memcpy(m->tcode + m->ntcode, sp->succ, sp->nsucc * sizeof *sp->succ);
  m->ntcode += sp->nsucc;
  r->src = (uint32_t)m->ntsrc;
  r->nsrc = sp->nsrc;
  for (k = 0; k < sp->nsrc; k++) {
    const lsys_psrc *ps = &sp->src[k];
    if ((ps->kind == LSYS_PS_ARG && ps->idx >= r->nargs) ||
        (ps->kind == LSYS_PS_VAL && ps->idx >= r->nvals) || ps->kind > LSYS_PS_VAL)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "bad parameter source");
    if (ps->kind == LSYS_PS_CONST && !isfinite(ps->value))     /* 1e999 */
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "parameter %u of the successor is %g, "
                           "not a finite number", (unsigned)k + 1, ps->value);
    m->tsrc[m->ntsrc++] = *ps;
  }
  set->list[set->nlist++] = (uint32_t)m->nrules;
  set->compiled = 0;
  if (r->nlc || r->nrc) set->hasctx = 1;
  return (long)m->nrules++;
nomem:
  return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
}

int lsys_rules_setvm (lsys_rules *m, size_t idx, const lsys_ins *code, int n) {
  lsys_rule *r;
  lsys_ins *c = NULL;
  if (m->busy) return busyerror(m, NULL);
  if (idx >= m->nrules) return LSYS_EARG;
  r = &m->rules[idx];
  if (code != NULL) {
    if (!(r->flags & LSYS_RF_CALL) || (r->flags & LSYS_RF_DYN) ||
        lsys_expr_check(code, n, (int)r->nargs, (int)m->nfuncs) != (int)r->nvals)
      return LSYS_EARG;
    c = (lsys_ins *)LSYS_MALLOC((size_t)n * sizeof *c + 1);
    if (c == NULL) return LSYS_ENOMEM;
    memcpy(c, code, (size_t)n * sizeof *c);
  }
  LSYS_FREE(r->vm);
  r->vm = c;
  r->nvm = c ? n : 0;
  memset(&r->fx, 0, sizeof r->fx);
  if (c != NULL && !(r->flags & LSYS_RF_WEXPR)) {
    lsys_expr_fast(c, n, &r->fx);
    if (r->fx.n != (int)r->nvals) r->fx.ok = 0;
  }
  r->vmtry = r->vmtryout = 0;
  if (c != NULL) {          /* the condition ends in COND, the weight in the first RET */
    int pc = 0;
    while (pc < n && c[pc].op != LSYS_OP_COND && c[pc].op != LSYS_OP_RET) pc++;
    if (pc < n && c[pc].op == LSYS_OP_COND) r->vmtry = pc + 1;
    if (r->flags & LSYS_RF_WEXPR) {
      for (pc = r->vmtry; pc < n && c[pc].op != LSYS_OP_RET; pc++) {}
      r->vmtry = pc + 1;
      r->vmtryout = 1;
    }
  }
  return LSYS_OK;
}

int lsys_rules_setfuncs (lsys_rules *m, const lsys_func *const *funcs, size_t n) {
  const lsys_func **t = NULL;
  size_t i;
  if (m->busy) return busyerror(m, NULL);
  if (n > 0) {
    if (n > (size_t)LSYS_EXPR_MAXCODE * 64) return LSYS_EARG;   /* fits an int */
    t = (const lsys_func **)LSYS_MALLOC(n * sizeof *t);
    if (t == NULL) return LSYS_ENOMEM;
    memcpy(t, funcs, n * sizeof *t);
  }
  for (i = 0; i < m->nrules; i++) {
    LSYS_FREE(m->rules[i].vm);
    m->rules[i].vm = NULL;
    m->rules[i].nvm = 0;
  }
  LSYS_FREE(m->funcs);
  m->funcs = t;
  m->nfuncs = n;
  return LSYS_OK;
}

/* Groups the set's rules by predecessor (count, prefix sum, fill). */
int lsys_derive_compileset (lsys_rules *m, lsys_ruleset *s) {
  uint32_t nsym = m->ab->n, i;
  size_t k;
  if (s->compiled && s->nsym == nsym) return LSYS_OK;
  LSYS_FREE(s->start);
  LSYS_FREE(s->byp);
  LSYS_FREE(s->plain);
  s->start = (uint32_t *)LSYS_MALLOC((nsym + 1) * sizeof *s->start);
  s->byp = (uint32_t *)LSYS_MALLOC((s->nlist + 1) * sizeof *s->byp);
  s->plain = (uint32_t *)LSYS_MALLOC((nsym + 1) * sizeof *s->plain);
  if (s->start == NULL || s->byp == NULL || s->plain == NULL) return LSYS_ENOMEM;
  memset(s->start, 0, (nsym + 1) * sizeof *s->start);
  for (k = 0; k < s->nlist; k++) s->start[m->rules[s->list[k]].pred + 1]++;
  for (i = 0; i < nsym; i++) s->start[i + 1] += s->start[i];
  /* stable fill in declaration order */
  {
    uint32_t *next = (uint32_t *)LSYS_MALLOC((nsym + 1) * sizeof *next);
    if (next == NULL) return LSYS_ENOMEM;
    memcpy(next, s->start, (nsym + 1) * sizeof *next);
    for (k = 0; k < s->nlist; k++) s->byp[next[m->rules[s->list[k]].pred]++] = s->list[k];
    LSYS_FREE(next);
  }
  for (i = 0; i < nsym; i++) {         /* rules that always apply when np matches */
    const lsys_rule *r = s->start[i] < s->start[i + 1] ? &m->rules[s->byp[s->start[i]]] : NULL;
    s->plain[i] = (r != NULL && r->nlc == 0 && r->nrc == 0 && r->nmore == 0 &&
                   !(r->flags & (LSYS_RF_CALL | LSYS_RF_DYN | LSYS_RF_STOCH)))
                  ? s->byp[s->start[i]] : NONE;
  }
  for (s->stoch = 0, s->pure = 1, k = 0; k < s->nlist; k++) {
    const lsys_rule *r = &m->rules[s->list[k]];
    if (r->flags & LSYS_RF_STOCH) s->stoch = 1;
    if ((r->flags & (LSYS_RF_DYN | LSYS_RF_STOCH)) || lsys_rule_draws(r) ||
        ((r->flags & LSYS_RF_CALL) && r->vm == NULL))
      s->pure = 0;
  }
  s->nsym = nsym;
  s->compiled = 1;
  return LSYS_OK;
}

