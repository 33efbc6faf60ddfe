/*
** libFuzzer target for the expression checker and machine (csrc/core/expr.c).
** The input is a program: the first byte gives the number of arguments
** (0-8), the next bytes their values, then 3 bytes an instruction (opcode,
** operand, constant; decoded below so that most jumps and operands are in
** range). Crashes and sanitizer reports are failures, and so is a run that
** breaks the checker's promise:
**
**   n = lsys_expr_check(code, len, nargs, 2) >= 0 means every run writes
**   exactly n outputs when it returns 1, and none when it returns 0 (a
**   false condition); the stack stays within LSYS_EXPR_STACK.
**
** The outputs go to an array of LSYS_EXPR_MAXCODE + 1 slots filled with a
** canary NaN, compared bit for bit (the program cannot make that NaN: its
** constants and arguments never have that bit pattern with either sign,
** and arithmetic on a signalling NaN quietens it). A second run with the same seed must give
** the same bits, and a program of lsys_expr_fast's form the same bits (and the
** same answer to its condition) run without the stack. FUZZ_TRACE=1 in the environment prints what the checker and
** the machine say.
**
**   tools/fuzz.sh 600 expr         (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_expr
**   build-fuzz/fuzz_expr -max_total_time=600 tests/fuzz/corpus_expr
*/
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"

#define CANARY 0x7ff4dead0000beefull
#define NOUT (LSYS_EXPR_MAXCODE + 1)

/* Interesting constants: the low 4 bits pick one, the high 4 scale it. */
static const double ks[16] = {
  0, 1, -1, 0.5, 2, 3, -0.0, 1e300, -1e-300, 4.9e-324, 1.5, 10, 100, -7, 0.1, 1e-8
};

static double konst (const uint8_t *p, size_t n, size_t *used) {
  double x;
  uint64_t u;
  if (n == 0) return 0;
  if (p[0] != 0xff || n < 9) {
    *used = 1;
    return ks[p[0] & 15] * (1 + (p[0] >> 4));
  }
  memcpy(&u, p + 1, 8);          /* 0xff: the next 8 bytes are the double */
  if ((u & ~(1ull << 63)) == CANARY) u ^= 1;   /* not even after UNM or ABS */
  memcpy(&x, &u, 8);
  *used = 9;
  return x;
}

static int tracing = -1;

/* The positional functions LSYS_OP_FN calls: two, made at the first input. */
static const lsys_func *const *functions (void) {
  static lsys_func f[2];
  static const lsys_func *t[2];
  static const double p0[] = { 0, 0, 1.0 / 3, 1, 2.0 / 3, 1, 1, 0 };
  static const double p1[] = { 0, -2, 0.5, -2, 0.5, 3, 0.5, 3, 0.75, 1e6, 1, 0 };
  lsys_error e;
  if (t[0] == NULL) {
    if (lsys_func_set(&f[0], p0, 4, "bump", 0, &e) != LSYS_OK ||
        lsys_func_set(&f[1], p1, 6, "steep", 7, &e) != LSYS_OK)
      __builtin_trap();
    t[0] = &f[0]; t[1] = &f[1];
  }
  return t;
}

static int canary (const double *d) {
  uint64_t u;
  memcpy(&u, d, sizeof u);
  return u == CANARY;
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  static lsys_ins code[LSYS_EXPR_MAXCODE + 8];
  static double out[NOUT], out2[NOUT];
  double args[8];
  lsys_rng rng;
  size_t used;
  int nargs, n = 0, nout, k, st, st2;
  if (size < 1) return 0;
  nargs = data[0] % 9;
  data++; size--;
  for (k = 0; k < nargs; k++) {
    used = 0;
    args[k] = konst(data, size, &used);
    data += used; size -= used;
  }
  for (; size >= 3 && n < LSYS_EXPR_MAXCODE + 8; data += 3, size -= 3, n++) {
    lsys_ins *i = &code[n];
    int raw = data[1] >= 0xf0;    /* operands as they come: negative, far */
    i->op = data[0] % (LSYS_OP_NOPS + 1);
    if (data[0] == 0xff) i->op = -1 - (data[1] & 3);
    switch (i->op) {
      case LSYS_OP_JF: case LSYS_OP_JT: i->a = raw ? (int8_t)data[1] : n + 2 + data[1] % 16; break;
      case LSYS_OP_ARG: i->a = raw ? (int8_t)data[1] : data[1] % (nargs + 1); break;
      case LSYS_OP_F1: case LSYS_OP_F2:
        i->a = raw ? (int8_t)data[1] : data[1] % (LSYS_F_NFUNCS + 1);
        break;
      case LSYS_OP_FN: i->a = raw ? (int8_t)data[1] : data[1] % 3; break;   /* 2: out of range */
      default: i->a = (int8_t)data[1]; break;
    }
    used = 0;
    i->k = konst(data + 2, 1, &used);
  }
  if (tracing < 0) tracing = getenv("FUZZ_TRACE") != NULL;
  nout = lsys_expr_check(code, n, nargs, 2);
  if (tracing) fprintf(stderr, "%d arguments, %d instructions: check %d\n", nargs, n, nout);
  if (nout > NOUT - 1) __builtin_trap();
  if (nout < 0) return 0;
  for (k = 0; k < NOUT; k++) {
    uint64_t u = CANARY;
    memcpy(&out[k], &u, sizeof u);
    memcpy(&out2[k], &u, sizeof u);
  }
  lsys_rng_seed(&rng, 7);
  st = lsys_expr_run(code, n, args, out, &rng, functions());
  if (tracing) {
    fprintf(stderr, "run %d:", st);
    for (k = 0; st == 1 && k < nout && k < 16; k++) fprintf(stderr, " %.17g", out[k]);
    fprintf(stderr, "\n");
  }
  if (st != 0 && st != 1) __builtin_trap();
  for (k = 0; k < NOUT; k++)
    if (canary(&out[k]) != (st == 0 || k >= nout)) __builtin_trap();
  /* deterministic: the same seed gives the same bits */
  lsys_rng_seed(&rng, 7);
  st2 = lsys_expr_run(code, n, args, out2, &rng, functions());
  if (st2 != st || memcmp(out, out2, sizeof out) != 0) __builtin_trap();
  /* the short form, where the program has it: the same answer and bits */
  {
    lsys_xfast f;
    lsys_expr_fast(code, n, &f);
    if (f.ok) {
      static double out3[NOUT];
      if (f.n != nout) __builtin_trap();
      for (k = 0; k < NOUT; k++) out3[k] = out2[k];
      if (lsys_expr_runfast(&f, args, out3) != st) __builtin_trap();
      if (st == 1 && memcmp(out3, out, nout * sizeof *out) != 0) __builtin_trap();
    }
  }
  /* more arguments never make a program invalid */
  if (nargs < 8 && lsys_expr_check(code, n, 8, 2) != nout) __builtin_trap();
  /* more functions neither; fewer only when the program calls one beyond them */
  if (lsys_expr_check(code, n, nargs, 9) != nout) __builtin_trap();
  return 0;
}
