/*
** C unit tests for the derivation engine: context matching, cut,
** stochastic choice, decomposition depth, limits, the expression machine.
** Rules are parsed with the core's rule parser; successor parameters are
** numbers or formal names (no Lua here).
*/
#define _POSIX_C_SOURCE 200809L
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "derive.h"
#include "grammar.h"

static lsys_alphabet ab;

static void addrule (lsys_rules *m, int kind, const char *text) {
  lsys_prule r;
  lsys_error e;
  lsys_patmod lc[16], rc[16], more[16];
  uint16_t succ[64];
  lsys_psrc src[64];
  lsys_rulespec sp;
  char names[32][16];
  uint32_t k, j, nf = 0, ns = 0;
  int st = lsys_grammar_rule_parse(&r, text, strlen(text), 0, &ab, NULL, &e);
  if (st != LSYS_OK) { fprintf(stderr, "%s: %s\n", text, e.msg); abort(); }
  memset(&sp, 0, sizeof sp);
  for (k = 0; k < r.nlc + r.npred + r.nrc; k++) {  /* formal names in order */
    const lsys_pmod *pm = &r.mods[k];
    lsys_patmod p = {pm->sym, pm->np};
    if (k < r.nlc) lc[k] = p;
    else if (k == r.nlc) sp.pred = p;
    else if (k < r.nlc + r.npred) more[k - r.nlc - 1] = p;
    else rc[k - r.nlc - r.npred] = p;
    for (j = 0; j < pm->np; j++) {
      const lsys_span *s = &r.params[pm->first + j];
      snprintf(names[nf++], sizeof names[0], "%.*s", (int)s->len, text + s->off);
    }
  }
  for (k = r.nmods - r.nsucc; k < r.nmods; k++) {
    const lsys_pmod *pm = &r.mods[k];
    succ[sp.nsucc++] = LSYS_CODE(pm->sym, pm->np);
    for (j = 0; j < pm->np; j++) {
      const lsys_span *s = &r.params[pm->first + j];
      char buf[32], *end;
      uint32_t f;
      snprintf(buf, sizeof buf, "%.*s", (int)s->len, text + s->off);
      src[ns].kind = LSYS_PS_CONST;
      src[ns].value = strtod(buf, &end);
      for (f = 0; f < nf; f++)
        if (strcmp(names[f], buf) == 0) { src[ns].kind = LSYS_PS_ARG; src[ns].idx = f; }
      ns++;
    }
  }
  sp.lc = lc; sp.nlc = r.nlc; sp.rc = rc; sp.nrc = r.nrc;
  sp.more = more; sp.nmore = r.npred - 1;
  sp.succ = succ; sp.src = src; sp.nsrc = ns;
  if (r.weight.len) { sp.flags |= LSYS_RF_STOCH; sp.weight = atof(text + r.weight.off); }
  assert(lsys_rules_add(m, kind, 0, 0, &sp, &e) >= 0);
  lsys_grammar_prule_free(&r);
}

static void setstr (lsys_lstring *s, const char *text) {
  lsys_error e;
  lsys_lstring_clear(s);
  assert(lsys_lstring_parse(s, text, strlen(text), &ab, NULL, &e) == LSYS_OK);
}

static void expect (lsys_lstring *s, const char *want) {
  lsys_buf b = {0};
  assert(lsys_lstring_format(&b, s, &ab, NULL, 0, s->n) == LSYS_OK);
  if (strcmp(b.p ? b.p : "", want) != 0) {
    fprintf(stderr, "expected %s, got %s\n", want, b.p ? b.p : "");
    abort();
  }
  lsys_lstring_buf_free(&b);
}

/* one step of 'rules' (one per line) on 'axiom' must give 'want' */
static void step (const char *rules, const char *ignore, const char *axiom, const char *want) {
  lsys_rules m;
  lsys_lstring a, b;
  char buf[512], *line, *save;
  lsys_rules_init(&m, &ab);
  snprintf(buf, sizeof buf, "%s", rules);
  for (line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save))
    addrule(&m, LSYS_PROD, line);
  if (ignore) {
    uint32_t syms[16];
    size_t n = 0;
    for (; *ignore; ignore++) syms[n++] = lsys_alphabet_intern(&ab, ignore, 1, NULL);
    lsys_rules_skiplist(&m, 0, 0, syms, n);
  }
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  setstr(&a, axiom);
  assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
  expect(&b, want);
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  lsys_rules_free(&m);
}

static void test_context (void) {
  step("A < C --> X", NULL, "A[B]C", "A[B]X");          /* skips the branch on the left */
  step("A < B --> X", NULL, "A[B]", "A[X]");            /* climbs out of its branch */
  step("B > C --> X", NULL, "A[B]C", "A[B]C");          /* fails at the end of its branch */
  step("A > B --> X", NULL, "A[C]B", "X[C]B");          /* skips branches it does not name */
  step("A > [B]C --> X", NULL, "A[B]C", "X[B]C");       /* names a branch */
  step("A > [B]C --> X", NULL, "A[D][B]C", "A[D][B]C"); /* only the next branch (cpfg) */
  step("A > [B]C --> X", NULL, "A[B][D]C", "X[B][D]C"); /* unnamed [D] skipped */
  step("B > C]D --> X", NULL, "A[BCE]D", "A[BCE]D");    /* ] is literal */
  step("B > C=]D --> X", NULL, "A[BCE]D", "A[XCE]D");   /* = to the branch's end */
  step("S > G[H]M --> X", NULL, "SG[H]M", "XG[H]M");
  step("S > G[H]M --> X", NULL, "SG[H]N", "SG[H]N");
  step("A < B > C --> X", "+", "A+B+C", "A+X+C");       /* ignore list */
  step("A < B > C --> X", NULL, "A+B+C", "A+B+C");
  step("A(x) < B(y) --> B(x)", NULL, "A(3)B(1)", "A(3)B(3)");
  step("A B < C --> X", NULL, "AB[Q]C", "AB[Q]X");      /* multi-module left context */
}

/* a strict predecessor of several modules (cpfg's PredDiff): consecutive
** modules, symbol and parameter count, no skipping; the rule rewrites them all */
static void test_predecessor (void) {
  step("A B --> X", NULL, "ABAB CAB", "XXCX");
  step("A(x)B(y) --> X(y,x)", NULL, "A(1)B(2)A(3)C", "X(2,1)A(3)C");
  step("A < BC > D --> X", NULL, "ABCDBCD", "AXDBCD");   /* contexts around the whole */
  step("BC --> X\nB --> Y", NULL, "BCBD", "XYD");
  step("AB --> X", "+", "A+B", "A+B");                   /* ignored modules not skipped */
  step("AB --> X", NULL, "AB(1)", "AB(1)");              /* parameter counts must match */
  step("AB --> X\nBC --> Y", NULL, "ABC", "XC");         /* left to right, no overlap */
  step("A --> Q\nAB --> X", NULL, "ABC", "QBC");         /* the first rule that applies */
  step("ABB --> X\nB --> Y", NULL, "ABBB", "XY");
  step("X < AB > Y --> Z", NULL, "XABY", "XZY");
  step("AB --> X", NULL, "A", "A");                      /* the string ends first */
  {                  /* decomposition: one module; the homomorphism: several too */
    lsys_rules m;
    lsys_rulespec sp;
    lsys_patmod more[1];
    lsys_error e;
    lsys_rules_init(&m, &ab);
    memset(&sp, 0, sizeof sp);
    sp.pred.sym = lsys_alphabet_intern(&ab, "A", 1, NULL);
    more[0].sym = lsys_alphabet_intern(&ab, "B", 1, NULL);
    more[0].np = 0;
    sp.more = more; sp.nmore = 1;
    assert(lsys_rules_add(&m, LSYS_DECOMP, 0, 0, &sp, &e) == LSYS_EARG);
    assert(strstr(e.msg, "not for the decomposition") != NULL);
    assert(lsys_rules_add(&m, LSYS_HOMO, 0, 0, &sp, &e) >= 0);
    more[0].sym = LSYS_SYM_LBR;
    assert(lsys_rules_add(&m, LSYS_PROD, 0, 0, &sp, &e) == LSYS_EARG);
    assert(strstr(e.msg, "module 2 of the predecessor") != NULL);
    lsys_rules_free(&m);
  }
}

static void test_cut (void) {
  step("A --> A", NULL, "A[B%CD]E", "A[B]E");
  step("A --> A", NULL, "AB%C[D]E", "AB");
  step("A --> A", NULL, "AB%C$E", "AB$E");               /* a $ stops it, as in cpfg */
  step("A --> A", NULL, "AB%C?(2,1)D$E$F", "AB$F");      /* a ? ... $ pair is cut whole */
  step("% --> F", NULL, "A[B%CD]E", "A[BFCD]E");         /* a rule on % prevents the cut */
}

static void test_stochastic (void) {
  lsys_rules m;
  lsys_lstring a, b;
  int k, nfb = 0;
  lsys_rules_init(&m, &ab);
  addrule(&m, LSYS_PROD, "B --> F : 1");
  addrule(&m, LSYS_PROD, "B --> G : 3");
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  lsys_rng_seed(&m.rng, 42);
  for (k = 0; k < 4000; k++) {
    setstr(&a, "B");
    assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
    nfb += LSYS_CSYM(b.code[0]) == lsys_alphabet_find(&ab, "F", 1);
  }
  assert(nfb > 1000 - 110 && nfb < 1000 + 110);          /* 4 standard deviations */
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  lsys_rules_free(&m);
}

static void test_limits (void) {
  lsys_rules m;
  lsys_lstring a, b;
  lsys_rules_init(&m, &ab);
  addrule(&m, LSYS_PROD, "F --> FF");
  m.max_modules = 100;
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  setstr(&a, "FFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFFF");
  assert(lsys_derive_step(&m, &a, &b) == LSYS_ELIMIT);
  assert(strstr(m.err.msg, "max_modules") != NULL);
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  lsys_rules_free(&m);
}

/* A rule callback that calls the engine on its own model: every entry point
** refuses with LSYS_EBUSY and leaves the running step intact. */
static int reenter (void *ud, lsys_rules *m, const lsys_rule *r, const double *args,
                    double *vals) {
  lsys_lstring *other = (lsys_lstring *)ud;
  lsys_rulespec sp;
  lsys_error e;
  (void)r; (void)args;
  memset(&sp, 0, sizeof sp);
  assert(lsys_derive_step(m, other, other + 1) == LSYS_EBUSY);
  assert(strcmp(m->err.msg, "a rule called step on the model it belongs to") == 0);
  assert(lsys_derive_expand(m, LSYS_HOMO, other, other + 1) == LSYS_EBUSY);
  assert(strcmp(m->err.msg, "a rule called expand on the model it belongs to") == 0);
  assert(lsys_derive_homo_begin(m, other) == LSYS_EBUSY);
  assert(strcmp(m->err.msg, "a rule called interpret on the model it belongs to") == 0);
  assert(lsys_rules_add(m, LSYS_PROD, 0, 0, &sp, &e) == LSYS_EBUSY);
  assert(lsys_rules_setvm(m, 0, NULL, 0) == LSYS_EBUSY);
  assert(lsys_rules_newset(m, LSYS_PROD, 5, 0) == LSYS_EBUSY);
  vals[0] = 7;
  return 1;
}

static void test_reentry (void) {
  lsys_rules m;
  lsys_lstring a, b, other[2];
  lsys_rulespec sp;
  lsys_psrc src = {LSYS_PS_VAL, 0, 0};
  uint16_t succ = LSYS_CODE(LSYS_SYM_LBR, 0);
  lsys_error e;
  lsys_rules_init(&m, &ab);
  memset(&sp, 0, sizeof sp);
  sp.pred.sym = lsys_alphabet_intern(&ab, "A", 1, &e);
  succ = LSYS_CODE(sp.pred.sym, 1);                /* A --> A(value 0) */
  sp.succ = &succ; sp.nsucc = 1;
  sp.src = &src; sp.nsrc = 1;
  sp.flags = LSYS_RF_CALL; sp.nvals = 1;
  assert(lsys_rules_add(&m, LSYS_PROD, 0, 0, &sp, &e) == 0);
  lsys_lstring_init(&a); lsys_lstring_init(&b);
  lsys_lstring_init(&other[0]); lsys_lstring_init(&other[1]);
  m.fn = reenter;
  m.fnud = other;
  setstr(&a, "AA");
  setstr(&other[0], "A");
  assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
  expect(&b, "A(7)A(7)");
  assert(m.busy == 0);
  lsys_lstring_free(&a); lsys_lstring_free(&b);
  lsys_lstring_free(&other[0]); lsys_lstring_free(&other[1]);
  lsys_rules_free(&m);
}

/* The memory budget: a step whose strings would outgrow max_memory fails with
** LSYS_EMEMORY before allocating, and a refused expansion leaves the model as
** it was (its generator included: a fuzzing finding). */
static void test_budget (void) {
  lsys_rules m;
  lsys_lstring a, b;
  char axiom[301];
  lsys_rules_init(&m, &ab);
  addrule(&m, LSYS_PROD, "F --> FF");
  addrule(&m, LSYS_HOMO, "F --> G");
  lsys_lstring_init(&a); lsys_lstring_init(&b);
  memset(axiom, 'F', 300); axiom[300] = '\0';
  setstr(&a, axiom);
  m.max_memory = 2048;                            /* the source alone takes 600+ bytes */
  assert(lsys_derive_step(&m, &a, &b) == LSYS_EMEMORY);
  assert(strstr(m.err.msg, "max_memory (2 KiB)") != NULL);
  assert(b.meter == NULL && m.busy == 0);
  m.max_memory = 700;
  assert(lsys_derive_expand(&m, LSYS_HOMO, &a, &b) == LSYS_EMEMORY);
  assert(m.cur == &m.rng && m.busy == 0);         /* not left on the homomorphism's generator */
  m.max_memory = 0;                               /* the process default */
  assert(lsys_derive_step(&m, &a, &b) == LSYS_OK && b.n == 600 && b.meter == NULL);
  lsys_lstring_free(&a); lsys_lstring_free(&b);
  lsys_rules_free(&m);
}

static void test_decomposition (void) {
  lsys_rules m;
  lsys_lstring a, b;
  lsys_rules_init(&m, &ab);
  addrule(&m, LSYS_PROD, "A --> AB");
  addrule(&m, LSYS_DECOMP, "B --> CD");
  addrule(&m, LSYS_DECOMP, "C --> E");
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  setstr(&a, "A");
  assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
  expect(&b, "ACD");                                     /* default depth 1 */
  assert(m.depth_hit == 1);
  m.maxdepth[LSYS_DECOMP] = 3;
  assert(lsys_derive_step(&m, &a, &b) == LSYS_OK);
  expect(&b, "AED");
  assert(m.depth_hit == 0);
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  lsys_rules_free(&m);
}

/* Every path through a checked program writes the outputs the check reports:
** a jump over a RET (or a COND) is refused, a jump that meets the fall-through
** with the same state is accepted. */
static void test_expr_paths (void) {
  /* K 1; JT ->5; K 2; RET; K 3; [5] RET: the taken jump writes one output,
  ** the fall-through two (the audit's reproducer, reachable by setvm) */
  lsys_ins over[] = {
    {LSYS_OP_K, 0, 1}, {LSYS_OP_JT, 5, 0}, {LSYS_OP_K, 0, 2}, {LSYS_OP_RET, 0, 0},
    {LSYS_OP_K, 0, 3}, {LSYS_OP_RET, 0, 0},
  };
  /* K 0; JF ->4; K 1; COND; [4] ... a jump past the condition */
  lsys_ins cond[] = {
    {LSYS_OP_K, 0, 0}, {LSYS_OP_JF, 4, 0}, {LSYS_OP_K, 0, 1}, {LSYS_OP_COND, 0, 0},
    {LSYS_OP_K, 0, 1}, {LSYS_OP_RET, 0, 0},
  };
  /* x > 1 and x < 3: both paths reach the RET with one value */
  lsys_ins ok[] = {
    {LSYS_OP_ARG, 0, 0}, {LSYS_OP_K, 0, 1}, {LSYS_OP_GT, 0, 0}, {LSYS_OP_JF, 7, 0},
    {LSYS_OP_ARG, 0, 0}, {LSYS_OP_K, 0, 3}, {LSYS_OP_LT, 0, 0}, {LSYS_OP_RET, 0, 0},
  };
  lsys_ins bad[] = {{LSYS_OP_NOPS, 0, 0}, {LSYS_OP_RET, 0, 0}};
  lsys_rng rng;
  double x = 2, out[3] = {-7, -7, -7};
  lsys_rng_seed(&rng, 1);
  assert(lsys_expr_check(over, 6, 0, 0) == -1);
  assert(lsys_expr_check(cond, 6, 0, 0) == -1);
  assert(lsys_expr_check(ok, 8, 1, 0) == 1);
  assert(lsys_expr_run(ok, 8, &x, out, &rng, NULL) == 1 && out[0] == 1 && out[1] == -7);
  x = 0;
  assert(lsys_expr_run(ok, 8, &x, out, &rng, NULL) == 1 && out[0] == 0 && out[1] == -7);
  assert(lsys_expr_check(bad, 2, 0, 0) == -1);
  {   /* x % y with the signs of Lua: -5 % -3 == -2, 5 % -3 == -1, -5 % 3 == 1; ceil gives no -0 */
    lsys_ins mod[] = {{LSYS_OP_ARG, 0, 0}, {LSYS_OP_ARG, 1, 0}, {LSYS_OP_MOD, 0, 0},
                      {LSYS_OP_RET, 0, 0}, {LSYS_OP_K, 0, -0.5}, {LSYS_OP_F1, LSYS_F_CEIL, 0},
                      {LSYS_OP_RET, 0, 0}};
    double a[2], o[2];
    assert(lsys_expr_check(mod, 7, 2, 0) == 2);
    a[0] = -5; a[1] = -3;
    assert(lsys_expr_run(mod, 7, a, o, &rng, NULL) == 1 && o[0] == -2);
    assert(o[1] == 0 && !signbit(o[1]));
    a[0] = 5; a[1] = -3;
    assert(lsys_expr_run(mod, 7, a, o, &rng, NULL) == 1 && o[0] == -1);
    a[0] = -5; a[1] = 3;
    assert(lsys_expr_run(mod, 7, a, o, &rng, NULL) == 1 && o[0] == 1);
    a[0] = -1e-320; a[1] = -1;
    assert(lsys_expr_run(mod, 7, a, o, &rng, NULL) == 1 && o[0] == -1e-320);
  }
  assert(lsys_expr_check(NULL, 0, 0, 0) == 0);
  assert(lsys_expr_check(NULL, 1, 0, 0) == -1);
}

static void test_expr (void) {
  /* (x + 2) * 3 > 10 and not (x == 4) -> condition; then x % -3, 2 ^ x // 1 */
  lsys_ins c[] = {
    {LSYS_OP_ARG, 0, 0}, {LSYS_OP_K, 0, 2}, {LSYS_OP_ADD, 0, 0}, {LSYS_OP_K, 0, 3},
    {LSYS_OP_MUL, 0, 0}, {LSYS_OP_K, 0, 10}, {LSYS_OP_GT, 0, 0}, {LSYS_OP_JF, 13, 0},
    {LSYS_OP_ARG, 0, 0}, {LSYS_OP_K, 0, 4}, {LSYS_OP_EQ, 0, 0}, {LSYS_OP_NOT, 0, 0},
    {LSYS_OP_K, 0, 1} /* unreachable filler replaced below */, {LSYS_OP_COND, 0, 0},
    {LSYS_OP_ARG, 0, 0}, {LSYS_OP_K, 0, -3}, {LSYS_OP_MOD, 0, 0}, {LSYS_OP_RET, 0, 0},
    {LSYS_OP_K, 0, 2}, {LSYS_OP_ARG, 0, 0}, {LSYS_OP_POW, 0, 0}, {LSYS_OP_K, 0, 1},
    {LSYS_OP_IDIV, 0, 0}, {LSYS_OP_RET, 0, 0},
  };
  lsys_rng rng;
  double x, out[2];
  int n = (int)(sizeof c / sizeof c[0]);
  lsys_rng_seed(&rng, 1);
  /* the JF target must be the COND (index 13); drop the filler */
  memmove(&c[12], &c[13], (size_t)(n - 13) * sizeof c[0]);
  n--;
  c[7].a = 12;
  assert(lsys_expr_check(c, n, 1, 0) == 2);
  x = 5;
  assert(lsys_expr_run(c, n, &x, out, &rng, NULL) == 1);
  assert(out[0] == -1 && out[1] == 32);                  /* Lua: 5 % -3 == -1 */
  x = 4;
  assert(lsys_expr_run(c, n, &x, out, &rng, NULL) == 0);
  x = 1;
  assert(lsys_expr_run(c, n, &x, out, &rng, NULL) == 0);
  c[0].a = 1;
  assert(lsys_expr_check(c, n, 1, 0) == -1);                /* argument out of range */
  c[0].a = 0;
  c[7].a = 3;
  assert(lsys_expr_check(c, n, 1, 0) == -1);                /* backward jump */
  test_expr_paths();
}

int main (void) {
  assert(lsys_alphabet_init(&ab) == LSYS_OK);
  test_context();
  test_predecessor();
  test_cut();
  test_stochastic();
  test_limits();
  test_reentry();
  test_budget();
  test_decomposition();
  test_expr();
  lsys_alphabet_free(&ab);
  return 0;
}
