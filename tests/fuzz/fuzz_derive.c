/*
** libFuzzer target for the derivation engine (csrc/core/derive.c): a model is
** built from the input text, derived for a few steps, then decomposed and
** interpreted by the homomorphism, both as a whole (lsys_derive_expand) and one
** module at a time (lsys_derive_homo_begin/module/end). Crashes, leaks, sanitizer
** reports and the invariants below are failures; rule errors (a sub-L-system
** that is not defined, a bad weight, a value that is not finite) and the
** module limit are expected results.
**
** The input is lines (see tests/fuzz/corpus_derive for examples):
**   o <options>      r ring, g<d> group, D<d> decomposition depth, H<d>
**                    homomorphism depth, m<d> module limit (100, 2000,
**                    10000, 30), M<d> memory budget (max_memory: default,
**                    2 KiB, 16 KiB, 128 KiB, 1 MiB), n<d> steps, S<d> seed,
**                    C cpfg's generator (C1: the homomorphism shares it)
**   a <Lstring>      the axiom (text notation; several lines append)
**   p|d|h[mods] <rule>   a production, decomposition or homomorphism rule
**                    in the rule language; mods: g<d> group, s<d>
**                    sub-L-system, v the expression machine (setvm) instead
**                    of the callback, y the callback produces the successor
**                    (LSYS_RF_DYN)
**   i|c[<d>] <names> the ignore or consider list of sub-L-system d
**   n<d>             an empty sub-L-system d (a set without rules)
**   x <bytes>        a raw expression program for the rule before (3 bytes
**                    an instruction, as in fuzz_expr.c; setvm refuses what
**                    the checker refuses)
**   # ...            a comment
** Conditions, computed parameters and weight expressions are compiled by a
** small compiler here to the expression machine (csrc/core/expr.h); the rule
** then runs either in C (setvm, mod v) or through a C callback that runs
** the same program (LSYS_RF_CALL), as the Lua binding does. The callback
** first tries to re-enter the model (a step, an expansion, a streamed
** homomorphism, changes to the rules): each must be refused with
** LSYS_EBUSY and change nothing.
**
** FUZZ_TRACE=1 in the environment prints the rules refused and the strings.
**
** Invariants: a step or an expansion returns LSYS_OK, LSYS_ELIMIT,
** LSYS_EMEMORY or LSYS_ERULE (with m->err set to it), leaves the model idle
** and 'ran' on the derivation's generator (m->cur); the homomorphism draws
** from its own generator, never the derivation's (but with C1); lsys_rules_add refuses a
** constant parameter that is not finite (1e999); a result has at most
** max_modules modules, its parameter counts add up to npar, every parameter
** is finite, and formatting and reparsing it gives the same string; the
** streaming homomorphism gives what lsys_derive_expand gives (same seeds).
**
**   tools/fuzz.sh 600 derive       (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_derive
**   build-fuzz/fuzz_derive -max_total_time=600 -dict=tests/fuzz/derive.dict \
**                          tests/fuzz/corpus_derive
*/
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "derive.h"
#include "grammar.h"

#define MAXRULES 32
#define MAXCODE 256            /* compiled program length */

/* What the harness keeps per model rule: the program the callback runs. */
typedef struct hrule {
  lsys_ins code[MAXCODE];
  int n;                       /* instructions; 0: none */
  int nout;                    /* lsys_expr_check's answer */
} hrule;

static hrule hrules[MAXRULES];
static int tracing = -1;       /* FUZZ_TRACE set: print what happens */

/* ---------------------------------------------------------------------- */
/* A compiler for Lua-like expressions over the formal parameters:
**   or and, < <= > >= == ~=, + -, * / // %, unary - not, ^, calls
**   (abs floor ceil sqrt exp log sin cos tan asin acos atan min max fmod
**   atan2 ran nran), numbers, names, parentheses. */

typedef struct cc {
  const char *s, *e;           /* the text */
  char names[64][16];          /* formal parameter names */
  int nnames;
  lsys_ins *code;
  int n, err, depth;
} cc;

static void skipws (cc *c) {
  while (c->s < c->e && (*c->s == ' ' || *c->s == '\t')) c->s++;
}

static int accept (cc *c, const char *tok) {
  size_t n = strlen(tok);
  skipws(c);
  if ((size_t)(c->e - c->s) < n || memcmp(c->s, tok, n) != 0) return 0;
  if ((tok[0] >= 'a' && tok[0] <= 'z') && c->s + n < c->e &&
      (isalnum((unsigned char)c->s[n]) || c->s[n] == '_'))
    return 0;                  /* 'or' is not the start of 'order' */
  c->s += n;
  return 1;
}

static int emit1 (cc *c, int op, int a, double k) {
  if (c->n >= MAXCODE) { c->err = 1; return 0; }
  c->code[c->n].op = op;
  c->code[c->n].a = a;
  c->code[c->n].k = k;
  return c->n++;
}

static void expr (cc *c);

static const char *const fnames[] = {
  "abs", "floor", "ceil", "sqrt", "exp", "log", "sin", "cos", "tan", "asin", "acos", "atan",
  "min", "max", "fmod", "atan2", "ran", "nran", NULL
};

static void primary (cc *c) {
  skipws(c);
  if (c->s >= c->e) { c->err = 1; return; }
  if (accept(c, "(")) {
    expr(c);
    if (!accept(c, ")")) c->err = 1;
    return;
  }
  if (isdigit((unsigned char)*c->s) || *c->s == '.') {
    char buf[64], *end;
    size_t k = 0;
    while (c->s < c->e && k < sizeof buf - 1 &&
           (isalnum((unsigned char)*c->s) || *c->s == '.' ||
            ((*c->s == '+' || *c->s == '-') && k > 0 && (buf[k - 1] == 'e' || buf[k - 1] == 'E'))))
      buf[k++] = *c->s++;
    buf[k] = '\0';
    emit1(c, LSYS_OP_K, 0, strtod(buf, &end));
    if (*end != '\0') c->err = 1;
    return;
  }
  if (isalpha((unsigned char)*c->s) || *c->s == '_') {
    const char *b = c->s;
    int k;
    size_t len;
    while (c->s < c->e && (isalnum((unsigned char)*c->s) || *c->s == '_')) c->s++;
    len = (size_t)(c->s - b);
    for (k = c->nnames - 1; k >= 0; k--)       /* the last of equal names, as Lua */
      if (strlen(c->names[k]) == len && memcmp(c->names[k], b, len) == 0) {
        emit1(c, LSYS_OP_ARG, k, 0);
        return;
      }
    for (k = 0; fnames[k] != NULL; k++)
      if (strlen(fnames[k]) == len && memcmp(fnames[k], b, len) == 0) break;
    if (fnames[k] == NULL || !accept(c, "(")) { c->err = 1; return; }
    expr(c);
    if (k >= LSYS_F_MIN && k != 16) {          /* two arguments */
      if (!accept(c, ",")) { c->err = 1; return; }
      expr(c);
    }
    if (!accept(c, ")")) { c->err = 1; return; }
    if (k == 16) emit1(c, LSYS_OP_RAN, 0, 0);
    else if (k == 17) emit1(c, LSYS_OP_NRAN, 0, 0);
    else emit1(c, k >= LSYS_F_MIN ? LSYS_OP_F2 : LSYS_OP_F1, k, 0);
    return;
  }
  c->err = 1;
}

static void unary (cc *c);

static void power (cc *c) {
  primary(c);
  if (accept(c, "^")) {
    unary(c);                  /* right associative, binds tighter than unary minus */
    emit1(c, LSYS_OP_POW, 0, 0);
  }
}

static void unary (cc *c) {
  if (++c->depth > 200) { c->err = 1; return; }
  if (accept(c, "-")) { unary(c); emit1(c, LSYS_OP_UNM, 0, 0); }
  else if (accept(c, "not")) { unary(c); emit1(c, LSYS_OP_NOT, 0, 0); }
  else power(c);
  c->depth--;
}

static void mul (cc *c) {
  unary(c);
  for (;;) {
    int op;
    if (accept(c, "//")) op = LSYS_OP_IDIV;
    else if (accept(c, "*")) op = LSYS_OP_MUL;
    else if (accept(c, "/")) op = LSYS_OP_DIV;
    else if (accept(c, "%")) op = LSYS_OP_MOD;
    else return;
    unary(c);
    emit1(c, op, 0, 0);
  }
}

static void add (cc *c) {
  mul(c);
  for (;;) {
    int op;
    if (accept(c, "+")) op = LSYS_OP_ADD;
    else if (accept(c, "-")) op = LSYS_OP_SUB;
    else return;
    mul(c);
    emit1(c, op, 0, 0);
  }
}

static void cmp (cc *c) {
  add(c);
  for (;;) {
    int op;
    if (accept(c, "<=")) op = LSYS_OP_LE;
    else if (accept(c, ">=")) op = LSYS_OP_GE;
    else if (accept(c, "==")) op = LSYS_OP_EQ;
    else if (accept(c, "~=")) op = LSYS_OP_NE;
    else if (accept(c, "<")) op = LSYS_OP_LT;
    else if (accept(c, ">")) op = LSYS_OP_GT;
    else return;
    add(c);
    emit1(c, op, 0, 0);
  }
}

/* 'a and b': a; JF L; b; L:  (the jump keeps the false value) */
static void andexpr (cc *c) {
  cmp(c);
  while (accept(c, "and")) {
    int j = emit1(c, LSYS_OP_JF, 0, 0);
    cmp(c);
    if (!c->err) c->code[j].a = c->n;
  }
}

static void expr (cc *c) {
  if (++c->depth > 200) { c->err = 1; return; }
  andexpr(c);
  while (accept(c, "or")) {
    int j = emit1(c, LSYS_OP_JT, 0, 0);
    andexpr(c);
    if (!c->err) c->code[j].a = c->n;
  }
  c->depth--;
}

/* Compiles text [b, b + len) followed by 'endop' (RET or COND); 0 on error. */
static int compile (cc *c, const char *b, size_t len, int endop) {
  c->s = b;
  c->e = b + len;
  c->depth = 0;
  expr(c);
  skipws(c);
  if (c->s != c->e) c->err = 1;
  emit1(c, endop, 0, 0);
  return !c->err;
}

/* ---------------------------------------------------------------------- */
/* The callback */

/* Everything that would change the model or its scratch is refused while
** a rule runs, and changes nothing. */
static void reenter (lsys_rules *m, const lsys_rule *r) {
  lsys_lstring a, b;
  lsys_rulespec sp;
  lsys_error e;
  lsys_ins ret[2] = {{LSYS_OP_K, 0, 1}, {LSYS_OP_RET, 0, 0}};
  uint32_t sym = LSYS_SYM_FIRSTFREE;
  size_t nrules = m->nrules, nsets = m->nsets, nskips = m->nskips;
  lsys_rng rng = m->rng, hrng = m->hrng, *cur = m->cur;
  lsys_error keep = m->err;
  lsys_lstring_init(&a);
  lsys_lstring_init(&b);
  memset(&sp, 0, sizeof sp);
  sp.pred.sym = LSYS_SYM_FIRSTFREE;
  if (lsys_derive_step(m, &a, &b) != LSYS_EBUSY) __builtin_trap();
  if (lsys_derive_expand(m, LSYS_HOMO, &a, &b) != LSYS_EBUSY) __builtin_trap();
  if (lsys_derive_expand(m, LSYS_DECOMP, &a, &b) != LSYS_EBUSY) __builtin_trap();
  if (lsys_derive_homo_begin(m, &a) != LSYS_EBUSY) __builtin_trap();
  if (lsys_rules_add(m, LSYS_PROD, 0, 0, &sp, &e) != LSYS_EBUSY) __builtin_trap();
  if (lsys_rules_setvm(m, (size_t)(r - m->rules), ret, 2) != LSYS_EBUSY) __builtin_trap();
  if (lsys_rules_skiplist(m, 0, 1, &sym, 1) != LSYS_EBUSY) __builtin_trap();
  if (lsys_rules_newset(m, LSYS_PROD, 9, 9) != LSYS_EBUSY) __builtin_trap();
  if (m->nrules != nrules || m->nsets != nsets || m->nskips != nskips || m->cur != cur ||
      memcmp(&rng, &m->rng, sizeof rng) != 0 || memcmp(&hrng, &m->hrng, sizeof hrng) != 0 ||
      !m->busy || a.n != 0 || b.n != 0)
    __builtin_trap();
  lsys_lstring_free(&a);
  lsys_lstring_free(&b);
  m->err = keep;
}

/* Runs the rule's program (condition, weight, values); for LSYS_RF_DYN
** rules produces the successor template itself, once to three times
** depending on the first argument. */
static int rulefn (void *ud, lsys_rules *m, const lsys_rule *r, const double *args,
                   double *vals) {
  const hrule *h = &hrules[r - m->rules];
  double out[MAXCODE + 1];
  uint32_t k;
  (void)ud;
  reenter(m, r);
  if (h->n > 0) {
    if (h->nout != (int)r->nvals)
      return lsys_seterror(&m->err, LSYS_ERULE, m->cur_index, "rule %d: bad program", r->id);
    uint32_t nv = r->nvals;
    if (r->flags & LSYS_RF_STOCH) {  /* as a Lua closure: cpfg's mark after the weight */
      int at = 0, wout = (r->flags & LSYS_RF_WEXPR) ? 1 : 0;
      while (at < h->n && h->code[at].op != LSYS_OP_COND && h->code[at].op != LSYS_OP_RET) at++;
      at = at < h->n && h->code[at].op == LSYS_OP_COND ? at + 1 : 0;
      if (wout) { while (at < h->n && h->code[at].op != LSYS_OP_RET) at++; at++; }
      if (!lsys_expr_span(h->code, 0, at, args, out, m->cur, m->funcs)) return 0;
      if (lsys_derive_cpfg_mark(m)) nv = (uint32_t)wout;
      else lsys_expr_span(h->code, at, h->n, args, out + wout, m->cur, m->funcs);
    }
    else if (!lsys_expr_run(h->code, h->n, args, out, m->cur, m->funcs)) return 0;
    for (k = 0; k < nv; k++) {
      if (!isfinite(out[k]))
        return lsys_seterror(&m->err, LSYS_ERULE, m->cur_index,
                             "rule %d: value %u is not a finite number", r->id, k + 1);
      vals[k] = out[k];
    }
  }
  else if (r->nvals > 0)
    return lsys_seterror(&m->err, LSYS_ERULE, m->cur_index, "rule %d: no program", r->id);
  if (r->flags & LSYS_RF_DYN) {
    int rep = 1 + (r->nargs > 0 ? (int)fmod(fabs(args[0]), 3.0) : 0), t;
    for (t = 0; t < rep; t++) {
      uint32_t q = r->src;           /* m->tsrc may be NULL: no pointer arithmetic on it */
      for (k = 0; k < r->nsucc; k++) {
        uint16_t c = m->tcode[r->succ + k];
        double p[LSYS_MAXPARAMS];
        uint32_t j;
        int st;
        for (j = 0; j < LSYS_CNP(c); j++) {
          const lsys_psrc *ps = &m->tsrc[q++];
          p[j] = ps->kind == LSYS_PS_CONST ? ps->value :
                 ps->kind == LSYS_PS_ARG ? args[ps->idx] : vals[ps->idx];
        }
        st = lsys_lstring_push(&m->dyn, LSYS_CSYM(c), p, LSYS_CNP(c));
        if (st != LSYS_OK)           /* m->dyn is within the step's memory budget */
          return lsys_seterror(&m->err, st, m->cur_index, "rule %d: %s", r->id,
                               st == LSYS_EMEMORY ? "over max_memory" : "not enough memory");
      }
    }
  }
  return 1;
}

/* ---------------------------------------------------------------------- */
/* Building the model */

typedef struct harness {
  lsys_alphabet ab;
  lsys_names decl;
  lsys_rules m;
  lsys_lstring s[2], t, u, w;
  lsys_buf b;
  long last;                   /* the index of the last rule added, or -1 */
  int steps;
  uint64_t seed;
} harness;

static void trace (harness *H, const char *what, lsys_lstring *s, int st) {
  if (!tracing) return;
  H->b.n = 0;
  if (s != NULL) lsys_lstring_format(&H->b, s, &H->ab, &H->decl, 0, s->n);
  fprintf(stderr, "%s: %d %.*s%s%s\n", what, st, H->b.n > 200 ? 200 : (int)H->b.n,
          H->b.p ? H->b.p : "", H->b.n > 200 ? "..." : "", st < 0 ? H->m.err.msg : "");
}

/* A number, as grammar.lua's isnumber: a constant successor parameter
** (1e999 too, which lsys_rules_add must refuse). */
static int isnum (const char *s, size_t len, double *x) {
  char buf[64], *end;
  if (len == 0 || len >= sizeof buf) return 0;
  memcpy(buf, s, len);
  buf[len] = '\0';
  if (!(isdigit((unsigned char)buf[0]) || buf[0] == '.' ||
        ((buf[0] == '-' || buf[0] == '+') && len > 1)))
    return 0;
  *x = strtod(buf, &end);
  return *end == '\0';
}

/* Adds the rule 'text' of 'kind' with the modifiers [mb, me). */
static void addrule (harness *H, int kind, const char *mb, const char *me, const char *text,
                     size_t len, int id) {
  lsys_prule r;
  lsys_error e;
  lsys_patmod lc[16], rc[16];
  uint16_t succ[64];
  lsys_psrc src[64];
  lsys_rulespec sp;
  cc c;
  hrule *h;
  uint32_t k, j;
  int sub = 0, group = 0, vm = 0, nvals = 0, nonfinite = 0;
  long idx;
  H->last = -1;
  if (H->m.nrules >= MAXRULES) return;
  for (; mb < me; mb++) {
    if (*mb == 'g' && mb + 1 < me && isdigit((unsigned char)mb[1])) group = *++mb - '0';
    else if (*mb == 's' && mb + 1 < me && isdigit((unsigned char)mb[1])) sub = *++mb - '0';
    else if (*mb == 'v') vm = 1;
    else if (*mb == 'y') vm = 2;
  }
  if (lsys_grammar_rule_parse(&r, text, len, 0, &H->ab, &H->decl, &e) != LSYS_OK ||
      r.nlc > 16 || r.nrc > 16 || r.nsucc > 64 || r.nparams > 64) {
    if (tracing) fprintf(stderr, "rule %d: not parsed\n", id);
    lsys_grammar_prule_free(&r);
    return;
  }
  memset(&sp, 0, sizeof sp);
  memset(&c, 0, sizeof c);
  h = &hrules[H->m.nrules];
  c.code = h->code;
  for (k = 0; k < r.nlc + 1 + r.nrc; k++) {         /* formal names in order */
    const lsys_pmod *pm = &r.mods[k];
    lsys_patmod p = {pm->sym, pm->np};
    if (k < r.nlc) lc[k] = p;
    else if (k == r.nlc) sp.pred = p;
    else rc[k - r.nlc - 1] = p;
    for (j = 0; j < pm->np && c.nnames < 64; j++) {
      const lsys_span *s = &r.params[pm->first + j];
      snprintf(c.names[c.nnames++], sizeof c.names[0], "%.*s", (int)s->len, text + s->off);
    }
  }
  if (r.cond.len > 0) {
    compile(&c, text + r.cond.off, r.cond.len, LSYS_OP_COND);
    sp.flags |= LSYS_RF_CALL;
  }
  if (r.weight.len > 0) {
    double x;
    sp.flags |= LSYS_RF_STOCH;
    if (isnum(text + r.weight.off, r.weight.len, &x) && isfinite(x)) sp.weight = x;
    else {
      compile(&c, text + r.weight.off, r.weight.len, LSYS_OP_RET);
      sp.flags |= LSYS_RF_CALL | LSYS_RF_WEXPR;
      nvals++;
    }
  }
  for (k = r.nmods - r.nsucc; k < r.nmods; k++) {
    const lsys_pmod *pm = &r.mods[k];
    succ[sp.nsucc++] = LSYS_CODE(pm->sym, pm->np);
    for (j = 0; j < pm->np; j++) {
      const lsys_span *s = &r.params[pm->first + j];
      lsys_psrc *ps = &src[sp.nsrc++];
      int f;
      memset(ps, 0, sizeof *ps);
      if (isnum(text + s->off, s->len, &ps->value)) {
        nonfinite |= !isfinite(ps->value);
        continue;
      }
      for (f = c.nnames - 1; f >= 0; f--)
        if (strlen(c.names[f]) == s->len && memcmp(c.names[f], text + s->off, s->len) == 0)
          break;
      if (f >= 0) { ps->kind = LSYS_PS_ARG; ps->idx = (uint32_t)f; continue; }
      compile(&c, text + s->off, s->len, LSYS_OP_RET);
      ps->kind = LSYS_PS_VAL;
      ps->idx = (uint32_t)nvals++;
      sp.flags |= LSYS_RF_CALL;
    }
  }
  if (vm == 2) sp.flags |= LSYS_RF_DYN;
  sp.lc = lc; sp.nlc = r.nlc; sp.rc = rc; sp.nrc = r.nrc;
  sp.succ = succ; sp.src = src;
  sp.nvals = (uint32_t)nvals;
  sp.id = id;
  h->n = c.err ? 0 : c.n;
  lsys_grammar_prule_free(&r);
  if (c.err) {                                       /* the model would not load */
    if (tracing) fprintf(stderr, "rule %d: expression not compiled\n", id);
    return;
  }
  idx = lsys_rules_add(&H->m, kind, sub, group, &sp, &e);
  if (tracing) fprintf(stderr, "rule %d: %ld, %d instructions, %d values\n", id, idx, h->n, nvals);
  if (idx < 0) {
    if (idx != LSYS_EARG) __builtin_trap();          /* DYN with a weight, 1e999 */
    return;
  }
  if (nonfinite) __builtin_trap();                   /* a constant inf was accepted */
  /* the program reads the rule's formal parameters: lc, predecessor, rc */
  h->nout = h->n > 0 ? lsys_expr_check(h->code, h->n, (int)H->m.rules[idx].nargs, 0) : 0;
  if (h->n > 0 && h->nout != (int)H->m.rules[idx].nvals) __builtin_trap();
  if (vm == 1 && h->n > 0 &&
      lsys_rules_setvm(&H->m, (size_t)idx, h->code, h->n) != LSYS_OK)
    __builtin_trap();                                /* a checked program is accepted */
  H->last = idx;
}

/* A raw program for the last rule: 3 bytes an instruction (fuzz_expr.c). */
static void rawvm (harness *H, const uint8_t *p, size_t n) {
  static const double ks[8] = {0, 1, -1, 0.5, 2, 3, 1e300, -0.0};
  lsys_ins code[128];
  int k = 0, st, nout;
  const lsys_rule *r;
  if (H->last < 0) return;
  r = &H->m.rules[H->last];
  for (; n >= 3 && k < 128; p += 3, n -= 3, k++) {
    code[k].op = p[0] % (LSYS_OP_NOPS + 1);
    code[k].a = (code[k].op == LSYS_OP_JF || code[k].op == LSYS_OP_JT) ? k + 2 + p[1] % 8 :
                p[1] < 0xf0 ? p[1] % 20 : (int8_t)p[1];
    code[k].k = ks[p[2] % 8] * (1 + (p[2] >> 3));
  }
  nout = lsys_expr_check(code, k, (int)r->nargs, (int)H->m.nfuncs);
  st = lsys_rules_setvm(&H->m, (size_t)H->last, code, k);
  if (tracing) fprintf(stderr, "raw program: %d instructions, %d outputs, setvm %d\n", k, nout, st);
  if (st == LSYS_OK && (nout != (int)r->nvals || !(r->flags & LSYS_RF_CALL) ||
                        (r->flags & LSYS_RF_DYN)))
    __builtin_trap();                                /* setvm takes only what fits */
  if (st != LSYS_OK && st != LSYS_EARG) __builtin_trap();
}

static void skiplist (harness *H, int sub, int consider, const char *s, size_t len) {
  uint32_t syms[64];
  size_t n = 0, i = 0;
  while (i < len && n < 64) {
    size_t nl;
    if (s[i] == ' ') { i++; continue; }
    nl = lsys_alphabet_scan(s + i, len - i, &H->decl);
    if (nl == 0) { i++; continue; }
    syms[n] = lsys_alphabet_intern(&H->ab, s + i, nl, NULL);
    if (syms[n] != 0) n++;
    i += nl;
  }
  if (lsys_rules_skiplist(&H->m, sub, consider, syms, n) != LSYS_OK) __builtin_trap();
}

static void options (harness *H, const char *s, size_t len) {
  static const size_t limits[4] = {100, 2000, 10000, 30};
  static const size_t budgets[5] = {0, 2048, 16384, 131072, 1 << 20};
  size_t i;
  for (i = 0; i < len; i++) {
    int d = i + 1 < len && isdigit((unsigned char)s[i + 1]) ? s[i + 1] - '0' : -1;
    switch (s[i]) {
      case 'r': H->m.ring = 1; break;
      case 'g': if (d >= 0) H->m.group = d; break;
      case 'D': if (d >= 0) H->m.maxdepth[LSYS_DECOMP] = d; break;
      case 'H': if (d >= 0) H->m.maxdepth[LSYS_HOMO] = d; break;
      case 'm': if (d >= 0) H->m.max_modules = limits[d % 4]; break;
      case 'M': if (d >= 0) H->m.max_memory = budgets[d % 5]; break;
      case 'n': if (d >= 0) H->steps = d > 6 ? 6 : d; break;
      case 'S': if (d >= 0) H->seed = (uint64_t)d; break;
      case 'C':                       /* cpfg's generator; C1: the homomorphism shares it */
        H->m.cpfg = H->m.rng.cpfg = H->m.hrng.cpfg = 1;
        if (d == 1) H->m.hshare = 1;
        break;
      default: break;
    }
  }
}

/* ---------------------------------------------------------------------- */
/* Checking results */

static void checkstring (harness *H, lsys_lstring *s) {
  lsys_error e;
  size_t i, np = 0;
  if (s->n > H->m.max_modules) __builtin_trap();
  if (s->sym8 != NULL) {             /* narrow: parameterless, and so once wide */
    if (s->npar != 0 || lsys_lstring_widen(s) != LSYS_OK || s->sym8 != NULL) __builtin_trap();
  }
  for (i = 0; i < s->n; i++) {
    if (LSYS_CSYM(s->code[i]) == 0 || LSYS_CSYM(s->code[i]) >= H->ab.n) __builtin_trap();
    np += LSYS_CNP(s->code[i]);
  }
  if (np != s->npar) __builtin_trap();
  for (i = 0; i < s->npar; i++)
    if (!isfinite(s->par[i])) __builtin_trap();
  /* formatting and reparsing gives the same string */
  H->b.n = 0;
  if (lsys_lstring_format(&H->b, s, &H->ab, &H->decl, 0, s->n) != LSYS_OK) __builtin_trap();
  lsys_lstring_clear(&H->u);
  if (lsys_lstring_parse(&H->u, H->b.p ? H->b.p : "", H->b.n, &H->ab, &H->decl, &e) != LSYS_OK)
    __builtin_trap();
  if (H->u.n != s->n || H->u.npar != s->npar) __builtin_trap();
  if (s->n > 0 && memcmp(H->u.code, s->code, s->n * sizeof *s->code) != 0) __builtin_trap();
  if (s->npar > 0 && memcmp(H->u.par, s->par, s->npar * sizeof *s->par) != 0) __builtin_trap();
}

/* After an operation, 'ran' uses the derivation's generator again and the
** model is idle (also when the memory budget refused the operation). */
static void checkcur (harness *H) {
  if (H->m.cur != &H->m.rng || H->m.busy) __builtin_trap();
}

/* A failed step or expansion: a limit or a rule error, and a message. */
static void checkfail (harness *H, int st) {
  if (st != LSYS_ELIMIT && st != LSYS_EMEMORY && st != LSYS_ERULE) __builtin_trap();
  if (H->m.err.code != st || H->m.err.msg[0] == '\0') __builtin_trap();
}

static int same (const lsys_lstring *a, const lsys_lstring *b) {
  return a->n == b->n && a->npar == b->npar &&
         (a->n == 0 || memcmp(a->code, b->code, a->n * sizeof *a->code) == 0) &&
         (a->npar == 0 || memcmp(a->par, b->par, a->npar * sizeof *a->par) == 0);
}

/* The homomorphism one module at a time into H->w, as the turtle asks for
** it; it must give what lsys_derive_expand gave ('whole', when 'ok'). */
static void streaming (harness *H, lsys_lstring *s, const lsys_lstring *whole, int ok) {
  size_t i, poff = 0;
  int st;
  lsys_rng_seed(&H->m.rng, H->seed);
  lsys_rng_seed(&H->m.hrng, H->seed + 1);
  st = lsys_derive_homo_begin(&H->m, s);
  if (st <= 0) checkcur(H);
  if (st < 0) {
    checkfail(H, st);
    if (ok) __builtin_trap();
    return;
  }
  lsys_lstring_clear(&H->w);
  for (i = 0; i < s->n; i++) {
    uint32_t np = LSYS_CNP(s->code[i]);
    int r = st == 1 ? lsys_derive_homo_module(&H->m, i, poff, &H->t) : 0;
    if (r < 0) {
      checkfail(H, r);
      if (ok) __builtin_trap();
      break;
    }
    if (r == 1) {
      checkstring(H, &H->t);
      if (H->t.n > 0 && lsys_lstring_append(&H->w, &H->t, 0, H->t.n, 0) != LSYS_OK)
        __builtin_trap();
    }
    else if (lsys_lstring_append(&H->w, s, i, i + 1, poff) != LSYS_OK) __builtin_trap();
    poff += np;
    if (H->w.n > H->m.max_modules) {   /* lsys_derive_expand would have stopped */
      if (ok) __builtin_trap();
      break;
    }
  }
  lsys_derive_homo_end(&H->m);
  checkcur(H);
  if (ok && i == s->n && !same(&H->w, whole)) __builtin_trap();
}

static void run (harness *H) {
  lsys_lstring *src = &H->s[0], *dst = &H->s[1], *tmp;
  int k, st;
  lsys_rng_seed(&H->m.rng, H->seed);
  lsys_rng_seed(&H->m.hrng, H->seed + 1);
  H->m.choice48 = H->seed;
  checkstring(H, src);
  for (k = 0; k < H->steps; k++) {
    st = lsys_derive_step(&H->m, src, dst);
    checkcur(H);
    trace(H, "step", st == LSYS_OK ? dst : NULL, st);
    if (st != LSYS_OK) {
      checkfail(H, st);
      break;
    }
    checkstring(H, dst);
    tmp = src; src = dst; dst = tmp;
  }
  /* decomposition and homomorphism of the last string */
  st = lsys_derive_expand(&H->m, LSYS_DECOMP, src, &H->t);
  checkcur(H);
  trace(H, "decomposition", st == LSYS_OK ? &H->t : NULL, st);
  if (st != LSYS_OK) checkfail(H, st);
  else checkstring(H, &H->t);
  lsys_rng_seed(&H->m.rng, H->seed);
  lsys_rng_seed(&H->m.hrng, H->seed + 1);
  st = lsys_derive_expand(&H->m, LSYS_HOMO, src, dst);
  checkcur(H);
  trace(H, "homomorphism", st == LSYS_OK ? dst : NULL, st);
  if (st != LSYS_OK) checkfail(H, st);
  else checkstring(H, dst);
  {                         /* the derivation's generator is not the homomorphism's */
    lsys_rng r0 = H->m.rng;   /* (unless it is cpfg's and shared; nrand's pair always is) */
    lsys_rng_seed(&r0, H->seed);
    if (H->m.cpfg) { r0.iset = H->m.rng.iset; r0.gset = H->m.rng.gset; }
    if (!H->m.hshare && memcmp(&r0, &H->m.rng, sizeof r0) != 0) __builtin_trap();
  }
  streaming(H, src, dst, st == LSYS_OK);
  if (lsys_derive_expand(&H->m, LSYS_PROD, src, dst) != LSYS_EARG) __builtin_trap();
  {                         /* a step in place gives what a step into another string gives */
    lsys_rng keep;
    int s1, s2;
    char msg[sizeof H->m.err.msg];
    lsys_rng_seed(&H->m.rng, H->seed);
    H->m.choice48 = H->seed;
    keep = H->m.rng;
    if (lsys_lstring_copy(&H->w, src) != LSYS_OK) __builtin_trap();
    s1 = lsys_derive_step(&H->m, src, &H->t);
    memcpy(msg, H->m.err.msg, sizeof msg);
    H->m.rng = keep;
    H->m.choice48 = H->seed;
    s2 = lsys_derive_step(&H->m, &H->w, &H->w);
    checkcur(H);
    if (lsys_lstring_widen(&H->t) != LSYS_OK || lsys_lstring_widen(&H->w) != LSYS_OK)
      __builtin_trap();
    if (s1 != LSYS_EMEMORY && s2 != LSYS_EMEMORY &&   /* the strings' capacities differ */
        (s1 != s2 || (s1 == LSYS_OK && !same(&H->t, &H->w)) ||
         (s1 != LSYS_OK && (strcmp(msg, H->m.err.msg) != 0 || H->w.n != 0))))
      __builtin_trap();
  }
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  harness *H = (harness *)calloc(1, sizeof *H);
  const char *p = (const char *)data, *end = p + size;
  lsys_error e;
  int line = 0;
  if (H == NULL) return 0;
  if (tracing < 0) tracing = getenv("FUZZ_TRACE") != NULL;
  if (lsys_alphabet_init(&H->ab) != LSYS_OK) { free(H); return 0; }
  lsys_alphabet_names_add(&H->decl, "Apex", 4);
  lsys_alphabet_names_add(&H->decl, "Leaf", 4);
  lsys_rules_init(&H->m, &H->ab);
  H->m.max_modules = 2000;
  H->m.parmin = 16;             /* the workers' step (derive_par.c) from 16 modules, */
  H->m.threads = 3;             /* narrow strings and steps in place included */
  H->m.fn = rulefn;
  H->m.fnud = H;
  H->steps = 3;
  H->last = -1;
  memset(hrules, 0, sizeof hrules);
  lsys_lstring_init(&H->s[0]); lsys_lstring_init(&H->s[1]);
  lsys_lstring_init(&H->t); lsys_lstring_init(&H->u); lsys_lstring_init(&H->w);
  while (p < end) {
    const char *nl = memchr(p, '\n', (size_t)(end - p)), *le = nl ? nl : end;
    const char *sp = memchr(p, ' ', (size_t)(le - p)), *body = sp ? sp + 1 : le;
    const char *me = sp ? sp : le;
    size_t blen = (size_t)(le - body);
    int d = p + 1 < me && isdigit((unsigned char)p[1]) ? p[1] - '0' : 0;
    line++;
    switch (p < le ? *p : '#') {
      case 'o': options(H, body, blen); break;
      case 'a':
        if (lsys_lstring_parse(&H->s[0], body, blen, &H->ab, &H->decl, &e) != LSYS_OK)
          lsys_lstring_clear(&H->s[0]);
        break;
      case 'p': addrule(H, LSYS_PROD, p + 1, me, body, blen, line); break;
      case 'd': addrule(H, LSYS_DECOMP, p + 1, me, body, blen, line); break;
      case 'h': addrule(H, LSYS_HOMO, p + 1, me, body, blen, line); break;
      case 'i': skiplist(H, d, 0, body, blen); break;
      case 'c': skiplist(H, d, 1, body, blen); break;
      case 'n': if (lsys_rules_newset(&H->m, LSYS_PROD, d, 0) != LSYS_OK) __builtin_trap(); break;
      case 'x': rawvm(H, (const uint8_t *)body, blen); break;
      default: break;
    }
    p = nl ? nl + 1 : end;
  }
  trace(H, "axiom", &H->s[0], 0);
  if (H->s[0].n <= H->m.max_modules) run(H);
  lsys_lstring_free(&H->s[0]); lsys_lstring_free(&H->s[1]);
  lsys_lstring_free(&H->t); lsys_lstring_free(&H->u); lsys_lstring_free(&H->w);
  lsys_lstring_buf_free(&H->b);
  lsys_rules_free(&H->m);
  lsys_alphabet_names_free(&H->decl);
  lsys_alphabet_free(&H->ab);
  free(H);
  return 0;
}
