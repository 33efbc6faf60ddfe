/*
** C unit tests for the derivation step on several threads (derive_par.c):
** the same string for 1, 2, 3 and 8 threads with templates, the expression
** machine (values, conditions, ran and nran), weights, contexts and groups;
** the same errors at the same modules; the sequential step where it must run.
** Run it under ThreadSanitizer too (-DLSYS_TSAN=ON, CONTRIBUTING.md).
*/
#define _POSIX_C_SOURCE 200809L
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "derive.h"
#include "grammar.h"

static lsys_alphabet ab;

/* Adds the rule 'text' (successor parameters: numbers, formal names, or $k
** for value k of the rule's program 'code', which may be NULL). */
static long addrule (lsys_rules *m, int group, const char *text, const lsys_ins *code,
                     int ncode, uint32_t nvals) {
  lsys_prule r;
  lsys_error e;
  lsys_patmod lc[8], rc[8];
  uint16_t succ[32];
  lsys_psrc src[32];
  lsys_rulespec sp;
  char names[16][8];
  uint32_t k, j, nf = 0, ns = 0;
  long idx;
  assert(lsys_grammar_rule_parse(&r, text, strlen(text), 0, &ab, NULL, &e) == LSYS_OK);
  memset(&sp, 0, sizeof sp);
  for (k = 0; k < r.nlc + r.npred + r.nrc; k++) {
    const lsys_pmod *pm = &r.mods[k];
    lsys_patmod p = {pm->sym, pm->np};
    if (k < r.nlc) lc[k] = p;
    else if (k == r.nlc) sp.pred = p;
    else rc[k - r.nlc - 1] = p;
    for (j = 0; j < pm->np; j++) {
      const lsys_span *s = &r.params[pm->first + j];
      snprintf(names[nf++], sizeof names[0], "%.*s", (int)s->len, text + s->off);
    }
  }
  for (k = r.nmods - r.nsucc; k < r.nmods; k++) {
    const lsys_pmod *pm = &r.mods[k];
    succ[sp.nsucc++] = LSYS_CODE(pm->sym, pm->np);
    for (j = 0; j < pm->np; j++, ns++) {
      const lsys_span *s = &r.params[pm->first + j];
      char buf[16];
      uint32_t f;
      snprintf(buf, sizeof buf, "%.*s", (int)s->len, text + s->off);
      src[ns].kind = LSYS_PS_CONST;
      src[ns].value = atof(buf);
      if (buf[0] == '$') { src[ns].kind = LSYS_PS_VAL; src[ns].idx = (uint32_t)atoi(buf + 1); }
      for (f = 0; f < nf; f++)
        if (strcmp(names[f], buf) == 0) { src[ns].kind = LSYS_PS_ARG; src[ns].idx = f; }
    }
  }
  sp.lc = lc; sp.nlc = r.nlc; sp.rc = rc; sp.nrc = r.nrc;
  sp.succ = succ; sp.src = src; sp.nsrc = ns;
  sp.nvals = nvals;
  if (code != NULL) sp.flags |= LSYS_RF_CALL;
  if (r.weight.len) {
    sp.flags |= LSYS_RF_STOCH;
    sp.weight = atof(text + r.weight.off);
  }
  idx = lsys_rules_add(m, LSYS_PROD, 0, group, &sp, &e);
  assert(idx >= 0);
  if (code != NULL) assert(lsys_rules_setvm(m, (size_t)idx, code, ncode) == LSYS_OK);
  lsys_grammar_prule_free(&r);
  return idx;
}

#define I(op, a, k) {LSYS_OP_##op, a, k}

/* The model of the tests: every kind of rule a worker runs. */
static void rules (lsys_rules *m) {
  /* A(s) --> F(s)[+A(s*ran(1) + 0.5)][-A(nran(s, 0.1))] */
  static const lsys_ins a[] = {I(ARG, 0, 0), I(K, 0, 1), I(RAN, 0, 0), I(MUL, 0, 0),
                               I(K, 0, 0.5), I(ADD, 0, 0), I(RET, 0, 0),
                               I(ARG, 0, 0), I(K, 0, 0.1), I(NRAN, 0, 0), I(RET, 0, 0)};
  /* F(x) : ran(1) < 0.5 --> F(x + 1) G */
  static const lsys_ins f[] = {I(K, 0, 1), I(RAN, 0, 0), I(K, 0, 0.5), I(LT, 0, 0),
                               I(COND, 0, 0), I(ARG, 0, 0), I(K, 0, 1), I(ADD, 0, 0),
                               I(RET, 0, 0)};
  addrule(m, 0, "A(s) --> F(s)[+A($0)][-A($1)]", a, 11, 2);
  addrule(m, 0, "F(x) --> F($0)G", f, 9, 1);
  addrule(m, 0, "G --> GH : 1", NULL, 0, 0);              /* weights */
  addrule(m, 0, "G --> H : 2", NULL, 0, 0);
  addrule(m, 0, "H < H --> K", NULL, 0, 0);              /* contexts */
  addrule(m, 0, "K > H --> KL", NULL, 0, 0);
  addrule(m, 1, "L --> LL", NULL, 0, 0);                 /* a group */
}

/* 'steps' steps from 'axiom' on 'threads' threads into 'out' (parmin 1, so
** that every step runs on the workers when it can; threads 0: the sequential
** step only), in place when 'inplace'. Returns the status. */
static int derive (const char *axiom, int steps, int threads, int group, lsys_lstring *out,
                   char *msg, int inplace) {
  lsys_rules m;
  lsys_lstring a, b, *s = &a, *d = &b, *t;
  lsys_error e;
  int k, st = LSYS_OK;
  lsys_rules_init(&m, &ab);
  rules(&m);
  m.threads = threads > 0 ? threads : 1;
  m.parmin = threads > 0 ? 1 : (size_t)-1;
  m.group = group;
  m.max_modules = 200000;
  lsys_rng_seed(&m.rng, 42);
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  assert(lsys_lstring_parse(&a, axiom, strlen(axiom), &ab, NULL, &e) == LSYS_OK);
  for (k = 0; k < steps && st == LSYS_OK; k++) {
    st = lsys_derive_step(&m, s, inplace ? s : d);
    if (!inplace) { t = s; s = d; d = t; }
  }
  if (st != LSYS_OK) strcpy(msg, m.err.msg);
  else assert(lsys_lstring_copy(out, s) == LSYS_OK);        /* wide */
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  lsys_rules_free(&m);
  return st;
}

static int same (const lsys_lstring *a, const lsys_lstring *b) {
  return a->n == b->n && a->npar == b->npar &&
         (a->n == 0 || memcmp(a->code, b->code, a->n * sizeof *a->code) == 0) &&
         (a->npar == 0 || memcmp(a->par, b->par, a->npar * sizeof *a->par) == 0);
}

static void test_same_string (void) {
  static const int threads[] = {1, 2, 3, 8};
  static const char *const axioms[] = {"A(1)", "A(1)HHHHH[A(2)]HKH", "F(0)A(1)GHHGK"};
  size_t x, k;
  int group;
  for (group = 0; group < 2; group++)
    for (x = 0; x < 3; x++) {
      lsys_lstring one, many;
      char msg[256];
      lsys_lstring_init(&one);
      lsys_lstring_init(&many);
      assert(derive(axioms[x], 9, 0, group, &one, msg, 0) == LSYS_OK);
      assert(one.n > 1000);
      for (k = 0; k < 8; k++) {
        assert(derive(axioms[x], 9, threads[k / 2], group, &many, msg, k % 2) == LSYS_OK);
        assert(same(&one, &many));
      }
      lsys_lstring_free(&one);
      lsys_lstring_free(&many);
    }
}

/* Strings without parameters are narrow (a byte a module), also in place, and
** the same as the sequential step's: templates, weights, a condition. */
static void test_narrow (void) {
  static const lsys_ins g[] = {I(K, 0, 1), I(RAN, 0, 0), I(K, 0, 0.5), I(LT, 0, 0),
                               I(COND, 0, 0)};
  lsys_lstring ref, s, t;
  lsys_error e;
  int threads, inplace, k;
  lsys_lstring_init(&ref);
  lsys_lstring_init(&s);
  lsys_lstring_init(&t);
  for (threads = 0; threads <= 8; threads += threads < 2 ? 1 : 6)
    for (inplace = 0; inplace < 2; inplace++) {
      lsys_rules m;
      lsys_lstring *a = &s, *b = inplace ? &s : &t, *x;
      lsys_rules_init(&m, &ab);
      addrule(&m, 0, "F --> F[+F]F[-F]F", NULL, 0, 0);
      addrule(&m, 0, "X --> F[-X][+X]FX : 1", NULL, 0, 0);
      addrule(&m, 0, "X --> FX : 2", NULL, 0, 0);
      addrule(&m, 0, "G --> GG", g, 5, 0);
      m.threads = threads > 0 ? threads : 1;
      m.parmin = threads > 0 ? 64 : (size_t)-1;
      lsys_rng_seed(&m.rng, 3);
      lsys_lstring_clear(&s);
      assert(lsys_lstring_parse(&s, "XGF", 3, &ab, NULL, &e) == LSYS_OK);
      for (k = 0; k < 6; k++) {
        assert(lsys_derive_step(&m, a, b) == LSYS_OK);
        if (!inplace) { x = a; a = b; b = x; }
      }
      assert(threads == 0 || a->sym8 != NULL);
      assert(a->n > 10000 && a->npar == 0);
      if (threads == 0) assert(lsys_lstring_copy(&ref, a) == LSYS_OK);
      else {
        assert(lsys_lstring_widen(a) == LSYS_OK);
        assert(a->sym8 == NULL && same(&ref, a));
      }
      lsys_rules_free(&m);
    }
  lsys_lstring_free(&ref);
  lsys_lstring_free(&s);
  lsys_lstring_free(&t);
}

/* The errors of a step on several threads are the sequential step's, at
** the same module: a value that is not finite, max_modules, max_memory. */
static void test_same_errors (void) {
  char one[256], many[256];
  lsys_lstring s;
  lsys_rules m;
  lsys_lstring a, b;
  lsys_error e;
  /* A(s) --> A(1 / (s - 3)) ... at the module A(3) */
  static const lsys_ins inv[] = {I(K, 0, 1), I(ARG, 0, 0), I(K, 0, 3), I(SUB, 0, 0),
                                 I(DIV, 0, 0), I(RET, 0, 0)};
  const char *axiom = "A(1)A(2)A(1)A(3)A(1)A(3)A(3)A(1)A(1)A(1)A(1)A(1)A(1)A(1)";
  int k;
  lsys_lstring_init(&s);
  for (k = 1; k <= 8; k *= 2) {
    lsys_rules_init(&m, &ab);
    addrule(&m, 0, "A(s) --> A($0)", inv, 6, 1);
    m.threads = k;
    m.parmin = 1;
    lsys_lstring_init(&a);
    lsys_lstring_init(&b);
    assert(lsys_lstring_parse(&a, axiom, strlen(axiom), &ab, NULL, &e) == LSYS_OK);
    assert(lsys_derive_step(&m, &a, k > 2 ? &a : &b) == LSYS_ERULE);  /* also in place */
    assert(m.err.pos == 3 && m.cur_rule == 0 && m.cur_index == 3);
    assert(k <= 2 || a.n == 0);
    strcpy(k == 1 ? one : many, m.err.msg);
    if (k > 1) assert(strcmp(one, many) == 0);
    lsys_lstring_free(&a);
    lsys_lstring_free(&b);
    lsys_rules_free(&m);
  }
  for (k = 1; k <= 8; k *= 2) {               /* max_modules: 200000 */
    assert(derive("A(1)", 20, k, 0, &s, k == 1 ? one : many, k > 2) == LSYS_ELIMIT);
    if (k > 1) assert(strcmp(one, many) == 0);
  }
  lsys_lstring_free(&s);
}

/* Rules the workers cannot run leave the step to the calling thread: the
** callback, a cut, a sub-L-system. */
static int calls;
static int rulefn (void *ud, lsys_rules *m, const lsys_rule *r, const double *args,
                   double *vals) {
  (void)ud; (void)m; (void)r; (void)args; (void)vals;
  calls++;
  return 1;
}

static void test_sequential (void) {
  static const char *const axioms[] = {"BBBBBBBB", "BBB%BBBB[BB%B]B", "BB?(1,1)BB$B"};
  size_t x;
  for (x = 0; x < 3; x++) {
    lsys_rules m;
    lsys_lstring a, b;
    lsys_error e;
    lsys_rulespec sp;
    uint16_t succ[2];
    lsys_rules_init(&m, &ab);
    m.threads = 4;
    m.parmin = 1;
    m.fn = rulefn;
    memset(&sp, 0, sizeof sp);
    sp.pred.sym = lsys_alphabet_intern(&ab, "B", 1, &e);
    succ[0] = succ[1] = LSYS_CODE(sp.pred.sym, 0);
    sp.succ = succ;
    sp.nsucc = 2;
    sp.flags = x == 0 ? LSYS_RF_CALL : 0;     /* a condition in the callback */
    assert(lsys_rules_add(&m, LSYS_PROD, 0, 0, &sp, &e) >= 0);
    if (x == 2) assert(lsys_rules_newset(&m, LSYS_PROD, 1, 0) == LSYS_OK);
    lsys_lstring_init(&a);
    lsys_lstring_init(&b);
    assert(lsys_lstring_parse(&a, axioms[x], strlen(axioms[x]), &ab, NULL, &e) == LSYS_OK);
    calls = 0;
    assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
    assert(x != 0 || calls == 8);
    assert(b.n == (x == 0 ? 16u : x == 1 ? 6u : 10u));
    lsys_lstring_free(&a);
    lsys_lstring_free(&b);
    lsys_rules_free(&m);
  }
}

int main (void) {
  assert(lsys_alphabet_init(&ab) == LSYS_OK);
  assert(lsys_derive_default_threads() >= 1 && lsys_derive_default_threads() <= LSYS_MAXTHREADS);
  test_same_string();
  test_narrow();
  test_same_errors();
  test_sequential();
  lsys_alphabet_free(&ab);
  printf("test_derive_par: ok\n");
  return 0;
}
