/*
** The expression machine (see expr.h). Arithmetic follows Lua 5.4 on
** floats: '%' is floored modulo, '//' floored division, '^' pow.
*/
#include <math.h>
#include <string.h>

#include "expr.h"

static int effect (int op) {       /* stack change */
  switch (op) {
    case LSYS_OP_K: case LSYS_OP_ARG: return 1;
    case LSYS_OP_UNM: case LSYS_OP_NOT: case LSYS_OP_F1: case LSYS_OP_RAN: case LSYS_OP_FN:
      return 0;
    case LSYS_OP_JF: case LSYS_OP_JT: return -1;   /* on the fall-through path */
    default: return -1;
  }
}

/*
** A forward data flow over the state of a path: stack depth, outputs written
** and conditions passed. Jumps go forward only, so one pass sees every path
** into an instruction before the instruction itself: a jump records its
** state (the kept value included) at its target, and every path reaching
** an instruction must bring the same state. So every run writes exactly the
** outputs the check reports, whichever way its jumps go.
*/
typedef struct pstate { int depth, outs, conds; } pstate;

static int samestate (const pstate *a, const pstate *b) {
  return a->depth == b->depth && a->outs == b->outs && a->conds == b->conds;
}

int lsys_expr_check (const lsys_ins *code, int n, int nargs, int nfuncs) {
  pstate at[LSYS_EXPR_MAXCODE + 1], cur = {0, 0, 0};
  unsigned char seen[LSYS_EXPR_MAXCODE + 1];
  int pc;
  if (n < 0 || n > LSYS_EXPR_MAXCODE || (n > 0 && code == NULL)) return -1;
  memset(seen, 0, (size_t)n + 1);
  for (pc = 0; pc < n; pc++) {
    const lsys_ins *i = &code[pc];
    int need;
    if (seen[pc] && !samestate(&at[pc], &cur)) return -1;
    switch (i->op) {
      case LSYS_OP_K: need = 0; break;
      case LSYS_OP_ARG: if (i->a < 0 || i->a >= nargs) return -1; need = 0; break;
      case LSYS_OP_F1: if (i->a < LSYS_F_ABS || i->a > LSYS_F_ATAN) return -1; need = 1; break;
      case LSYS_OP_F2: if (i->a < LSYS_F_MIN || i->a >= LSYS_F_NFUNCS) return -1; need = 2; break;
      case LSYS_OP_FN: if (i->a < 0 || i->a >= nfuncs) return -1; need = 1; break;
      case LSYS_OP_UNM: case LSYS_OP_NOT: case LSYS_OP_RAN: need = 1; break;
      case LSYS_OP_JF: case LSYS_OP_JT:
        if (i->a <= pc + 1 || i->a > n || cur.depth < 1) return -1;
        if (seen[i->a] && !samestate(&at[i->a], &cur)) return -1;
        at[i->a] = cur;              /* the tested value stays on the taken path */
        seen[i->a] = 1;
        need = 1;
        break;
      case LSYS_OP_RET: case LSYS_OP_COND:
        if (cur.depth != 1) return -1;
        if (i->op == LSYS_OP_COND) {
          if (cur.outs > 0 || cur.conds > 0) return -1;   /* one condition, first */
          cur.conds++;
        }
        else if (++cur.outs > LSYS_EXPR_MAXCODE) return -1;
        cur.depth = 0;
        continue;
      case LSYS_OP_ADD: case LSYS_OP_SUB: case LSYS_OP_MUL: case LSYS_OP_DIV:
      case LSYS_OP_MOD: case LSYS_OP_POW: case LSYS_OP_IDIV: case LSYS_OP_LT: case LSYS_OP_LE:
      case LSYS_OP_GT: case LSYS_OP_GE: case LSYS_OP_EQ: case LSYS_OP_NE: case LSYS_OP_NRAN:
        need = 2;
        break;
      default: return -1;            /* not an opcode */
    }
    if (cur.depth < need) return -1;
    cur.depth += effect(i->op);
    if (cur.depth > LSYS_EXPR_STACK - 1) return -1;
  }
  if (seen[n] && !samestate(&at[n], &cur)) return -1;
  return cur.depth == 0 ? cur.outs : -1;
}

static double fn1 (int f, double x) {
  switch (f) {
    case LSYS_F_ABS: return fabs(x);
    /* Lua's floor and ceil give an integer when it fits: no -0 (ceil(-0.5) is 0) */
    case LSYS_F_FLOOR: x = floor(x); return x == 0 ? 0.0 : x;
    case LSYS_F_CEIL: x = ceil(x); return x == 0 ? 0.0 : x;
    case LSYS_F_SQRT: return sqrt(x);
    case LSYS_F_EXP: return exp(x);
    case LSYS_F_LOG: return log(x);
    case LSYS_F_SIN: return sin(x);
    case LSYS_F_COS: return cos(x);
    case LSYS_F_TAN: return tan(x);
    case LSYS_F_ASIN: return asin(x);
    case LSYS_F_ACOS: return acos(x);
    default: return atan(x);
  }
}

static double fn2 (int f, double x, double y) {
  switch (f) {
    case LSYS_F_MIN: return y < x ? y : x;     /* Lua: the first unless a later is smaller */
    case LSYS_F_MAX: return y > x ? y : x;
    case LSYS_F_FMOD: return fmod(x, y);
    default: return atan2(x, y);
  }
}

int lsys_expr_run (const lsys_ins *code, int n, const double *args, double *out,
                   lsys_rng *rng, const lsys_func *const *funcs) {
  return lsys_expr_span(code, 0, n, args, out, rng, funcs);
}

int lsys_expr_span (const lsys_ins *code, int from, int to, const double *args, double *out,
                    lsys_rng *rng, const lsys_func *const *funcs) {
  double st[LSYS_EXPR_STACK];
  int sp = 0, pc;
  for (pc = from; pc < to; pc++) {
    const lsys_ins *i = &code[pc];
    double y;
    switch (i->op) {
      case LSYS_OP_K: st[sp++] = i->k; break;
      case LSYS_OP_ARG: st[sp++] = args[i->a]; break;
      case LSYS_OP_ADD: y = st[--sp]; st[sp - 1] += y; break;
      case LSYS_OP_SUB: y = st[--sp]; st[sp - 1] -= y; break;
      case LSYS_OP_MUL: y = st[--sp]; st[sp - 1] *= y; break;
      case LSYS_OP_DIV: y = st[--sp]; st[sp - 1] /= y; break;
      case LSYS_OP_MOD: {
        double x = st[sp - 2], m;
        y = st[--sp];
        m = fmod(x, y);
        if ((m > 0) ? y < 0 : (m < 0 && y > 0)) m += y;   /* Lua's luai_nummod: a
                                   remainder of the divisor's sign (-5 % -3 == -2) */
        st[sp - 1] = m;
        break;
      }
      case LSYS_OP_POW: y = st[--sp]; st[sp - 1] = pow(st[sp - 1], y); break;
      case LSYS_OP_IDIV: y = st[--sp]; st[sp - 1] = floor(st[sp - 1] / y); break;
      case LSYS_OP_UNM: st[sp - 1] = -st[sp - 1]; break;
      case LSYS_OP_LT: y = st[--sp]; st[sp - 1] = st[sp - 1] < y; break;
      case LSYS_OP_LE: y = st[--sp]; st[sp - 1] = st[sp - 1] <= y; break;
      case LSYS_OP_GT: y = st[--sp]; st[sp - 1] = st[sp - 1] > y; break;
      case LSYS_OP_GE: y = st[--sp]; st[sp - 1] = st[sp - 1] >= y; break;
      case LSYS_OP_EQ: y = st[--sp]; st[sp - 1] = st[sp - 1] == y; break;
      case LSYS_OP_NE: y = st[--sp]; st[sp - 1] = st[sp - 1] != y; break;
      case LSYS_OP_NOT: st[sp - 1] = st[sp - 1] == 0; break;
      case LSYS_OP_JF: if (st[sp - 1] == 0) pc = i->a - 1; else sp--; break;
      case LSYS_OP_JT: if (st[sp - 1] != 0) pc = i->a - 1; else sp--; break;
      case LSYS_OP_F1: st[sp - 1] = fn1(i->a, st[sp - 1]); break;
      case LSYS_OP_F2: y = st[--sp]; st[sp - 1] = fn2(i->a, st[sp - 1], y); break;
      case LSYS_OP_RAN: st[sp - 1] *= lsys_rng_uniform(rng); break;
      case LSYS_OP_NRAN: y = st[--sp]; st[sp - 1] = lsys_rng_normal(rng, st[sp - 1], y); break;
      case LSYS_OP_FN: st[sp - 1] = lsys_func_eval(funcs[i->a], st[sp - 1]); break;
      case LSYS_OP_RET: *out++ = st[--sp]; break;
      case LSYS_OP_COND: if (st[--sp] == 0) return 0; break;
      default: return 0;
    }
  }
  return 1;
}

/* An operand (K or ARG) into the term's x, y or z (which = 0, 1, 2). */
static int operand (const lsys_ins *i, lsys_xterm *t, int which) {
  uint8_t *isarg = which == 0 ? &t->xa : which == 1 ? &t->ya : &t->za;
  uint8_t *idx = which == 0 ? &t->xi : which == 1 ? &t->yi : &t->zi;
  double *k = which == 0 ? &t->xk : which == 1 ? &t->yk : &t->zk;
  if (i->op == LSYS_OP_K) { *isarg = 0; *k = i->k; return 1; }
  if (i->op != LSYS_OP_ARG || i->a < 0 || i->a > 255) return 0;
  *isarg = 1;
  *idx = (uint8_t)i->a;
  return 1;
}

static int arith (int32_t op) { return op >= LSYS_OP_ADD && op <= LSYS_OP_DIV; }
static int compare (int32_t op) { return op >= LSYS_OP_LT && op <= LSYS_OP_NE; }

/* A term of code[pc..] ending with 'end' (RET or COND): the instructions it
** took, or 0. Its last operation compares for a condition, computes for an
** output. */
static int term (const lsys_ins *code, int pc, int n, int32_t end, lsys_xterm *t) {
  const lsys_ins *c = code + pc;
  int left = n - pc;
  int (*last)(int32_t) = end == LSYS_OP_RET ? arith : compare;
  memset(t, 0, sizeof *t);
  if (left >= 2 && c[1].op == end && operand(&c[0], t, 0)) {
    t->op = LSYS_OP_K;
    return 2;
  }
  if (left < 4 || !operand(&c[0], t, 0) || !operand(&c[1], t, 1)) return 0;
  if (c[3].op == end && last(c[2].op)) {
    t->op = c[2].op;
    return 4;
  }
  if (left >= 6 && c[5].op == end && arith(c[2].op) && last(c[4].op) && operand(&c[3], t, 2)) {
    t->op = c[2].op;
    t->op2 = c[4].op;
    return 6;
  }
  return 0;
}

void lsys_expr_fast (const lsys_ins *code, int n, lsys_xfast *f) {
  int pc = 0, used;
  memset(f, 0, sizeof *f);
  if ((used = term(code, 0, n, LSYS_OP_COND, &f->t[0])) > 0) {
    f->cond = 1;
    pc = used;
  }
  while (pc < n) {
    if (f->n == LSYS_XFAST ||
        (used = term(code, pc, n, LSYS_OP_RET, &f->t[f->cond + f->n])) == 0)
      return;
    pc += used;
    f->n++;
  }
  f->ok = 1;
}
