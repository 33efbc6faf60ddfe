/*
** A small stack machine for rule expressions, so that conditions and
** parameter expressions made of arithmetic, comparisons, logic, the usual
** math functions and ran/nran run without entering Lua (docs/manual.md §5,
** "The expression machine"). The Lua side compiles an expression to this
** code only when its meaning is exactly Lua's (lua/lsys/compile.lua);
** anything else stays a Lua closure.
*/
#ifndef LSYS_EXPR_H
#define LSYS_EXPR_H

#include "func.h"
#include "rng.h"

enum {
  LSYS_OP_K,      /* push k */
  LSYS_OP_ARG,    /* push args[a] */
  LSYS_OP_ADD, LSYS_OP_SUB, LSYS_OP_MUL, LSYS_OP_DIV, LSYS_OP_MOD, LSYS_OP_POW,
  LSYS_OP_IDIV, LSYS_OP_UNM,
  LSYS_OP_LT, LSYS_OP_LE, LSYS_OP_GT, LSYS_OP_GE, LSYS_OP_EQ, LSYS_OP_NE, LSYS_OP_NOT,
  LSYS_OP_JF,     /* and: if top is 0 jump to a (keeping it), else pop */
  LSYS_OP_JT,     /* or: if top is not 0 jump to a (keeping it), else pop */
  LSYS_OP_F1,     /* top = f_a(top) */
  LSYS_OP_F2,     /* top = f_a(below, top) */
  LSYS_OP_RAN,    /* top = top * uniform */
  LSYS_OP_NRAN,   /* top = normal(below, top) */
  LSYS_OP_RET,    /* end of one expression: pop into the next output */
  LSYS_OP_COND,   /* end of the condition: pop; stop with 0 when false */
  LSYS_OP_FN,     /* top = funcs[a](top): a positional function (func.h) */
  LSYS_OP_NOPS
};

enum { LSYS_F_ABS, LSYS_F_FLOOR, LSYS_F_CEIL, LSYS_F_SQRT, LSYS_F_EXP, LSYS_F_LOG,
       LSYS_F_SIN, LSYS_F_COS, LSYS_F_TAN, LSYS_F_ASIN, LSYS_F_ACOS, LSYS_F_ATAN,
       LSYS_F_MIN, LSYS_F_MAX, LSYS_F_FMOD, LSYS_F_ATAN2, LSYS_F_NFUNCS };

typedef struct lsys_ins { int32_t op, a; double k; } lsys_ins;

#define LSYS_EXPR_STACK 64
#define LSYS_EXPR_MAXCODE 1024

/*
** Checks a program: opcodes, argument indices below 'nargs', function
** indices below 'nfuncs', jumps forward and inside, the stack within LSYS_EXPR_STACK, and that every path
** through it (whichever way each jump goes) writes the same number of
** outputs and passes the same conditions. Returns that number of outputs,
** or -1 when it is malformed.
*/
int lsys_expr_check (const lsys_ins *code, int n, int nargs, int nfuncs);

/* Runs a checked program; 'funcs' is the table of positional functions its
** LSYS_OP_FN indices refer to (as many as the check was given). Returns 1
** and fills 'out', or 0 when the condition is false. */
int lsys_expr_run (const lsys_ins *code, int n, const double *args, double *out,
                   lsys_rng *rng, const lsys_func *const *funcs);

/* Runs instructions [from, to) of a checked program, where from and to are 0,
** n or just after a COND or RET (the stack is empty there): a program run in
** parts draws its numbers when each part runs. */
int lsys_expr_span (const lsys_ins *code, int from, int to, const double *args, double *out,
                    lsys_rng *rng, const lsys_func *const *funcs);

/* A program whose condition (if it has one) and outputs are each one
** operation on two operands, arguments or constants, or one operand alone,
** or one more operation on the result and a third operand (A(t) : t < D -->
** A(t + 1), A(t) : t - 1 > 0 --> ...), as most programs of a successor are:
** run without the stack machine, with the same results. */
#define LSYS_XFAST 8
typedef struct lsys_xterm {
  int32_t op;                  /* LSYS_OP_ADD ... DIV, LT ... NE; LSYS_OP_K: x alone */
  int32_t op2;                 /* 0, or the operation on op's result and z */
  uint8_t xa, ya, za, xi, yi, zi;   /* xa: x is args[xi], else xk (y, z alike) */
  double xk, yk, zk;
} lsys_xterm;

typedef struct lsys_xfast {
  int ok;                      /* the program has this form */
  int cond;                    /* it starts with a condition, t[0]; the outputs follow */
  int n;                       /* the outputs */
  lsys_xterm t[LSYS_XFAST + 1];
} lsys_xfast;

/* Fills *f from a checked program of 'n' instructions (f->ok = 0 when it
** has another form). */
void lsys_expr_fast (const lsys_ins *code, int n, lsys_xfast *f);

static inline double lsys_expr_op (int32_t op, double x, double y) {
  switch (op) {
    case LSYS_OP_ADD: return x + y;
    case LSYS_OP_SUB: return x - y;
    case LSYS_OP_MUL: return x * y;
    case LSYS_OP_DIV: return x / y;
    case LSYS_OP_LT: return x < y;
    case LSYS_OP_LE: return x <= y;
    case LSYS_OP_GT: return x > y;
    case LSYS_OP_GE: return x >= y;
    case LSYS_OP_EQ: return x == y;
    default: return x != y;
  }
}

static inline double lsys_expr_term (const lsys_xterm *t, const double *args) {
  double x = t->xa ? args[t->xi] : t->xk, r;
  if (t->op == LSYS_OP_K) return x;
  r = lsys_expr_op(t->op, x, t->ya ? args[t->yi] : t->yk);
  return t->op2 == 0 ? r : lsys_expr_op(t->op2, r, t->za ? args[t->zi] : t->zk);
}

/* Runs a program of that form: 0 when its condition is false, else 1 with
** the outputs in 'out'. */
static inline int lsys_expr_runfast (const lsys_xfast *f, const double *args, double *out) {
  const lsys_xterm *t = f->t;
  int k;
  if (f->cond && lsys_expr_term(t++, args) == 0) return 0;
  for (k = 0; k < f->n; k++) out[k] = lsys_expr_term(t + k, args);
  return 1;
}

#endif
