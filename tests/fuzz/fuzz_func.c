/*
** libFuzzer target for the .func / .fset reader (csrc/core/func.c) and the
** evaluation and writing of what it accepts. Crashes, leaks and sanitizer
** reports are failures; syntax errors are expected results. For every
** function read: f(x) is finite and within the control points' y range
** (a B-spline curve stays in the convex hull of its points) at x = 0, 1, a
** few points between and outside [0, 1]; f(NaN) is NaN; the fver 1 1 text
** it is written as reads back to the same points and writes the same text.
**
**   tools/fuzz.sh 600 func      (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_func
**   build-fuzz/fuzz_func -max_total_time=300 tests/fuzz/corpus_func
*/
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "func.h"

static void check (const lsys_func *f) {
  static const double xs[] = { -1, 0, 1e-300, 0.1, 0.25, 1.0 / 3, 0.5, 0.7, 0.999999, 1, 2 };
  double lo = HUGE_VAL, hi = -HUGE_VAL, y;
  size_t i, len, n;
  char *a, *b;
  lsys_func *g;
  lsys_error e;
  if (f->n < 4 || f->pt == NULL || f->bez == NULL) __builtin_trap();
  for (i = 0; i < f->n; i++) {
    if (f->pt[2 * i + 1] < lo) lo = f->pt[2 * i + 1];
    if (f->pt[2 * i + 1] > hi) hi = f->pt[2 * i + 1];
  }
  for (i = 0; i < sizeof xs / sizeof xs[0]; i++) {
    y = lsys_func_eval(f, xs[i]);
    if (!isfinite(y) || y < lo - 1e-9 * (1 + fabs(lo)) || y > hi + 1e-9 * (1 + fabs(hi)))
      __builtin_trap();
  }
  y = lsys_func_eval(f, NAN);
  if (y == y) __builtin_trap();
  len = lsys_func_format(f, NULL, 0);
  a = (char *)malloc(len + 1);
  b = (char *)malloc(len + 1);
  if (a == NULL || b == NULL) __builtin_trap();
  if (lsys_func_format(f, a, len + 1) != len) __builtin_trap();
  if (lsys_func_parse(&g, &n, a, len, "again.func", 0, &e) != LSYS_OK || n != 1) __builtin_trap();
  if (g[0].n != f->n || memcmp(g[0].pt, f->pt, 2 * f->n * sizeof *f->pt) != 0 ||
      g[0].samples != f->samples || strcmp(g[0].name, f->name) != 0)
    __builtin_trap();
  if (lsys_func_format(&g[0], b, len + 1) != len || memcmp(a, b, len) != 0) __builtin_trap();
  lsys_func_free(&g[0]);
  free(g);
  free(a);
  free(b);
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  lsys_func *fs;
  size_t n, k;
  lsys_error e;
  if (lsys_func_parse(&fs, &n, (const char *)data, size, "fuzz.func", 5, &e) == LSYS_OK) {
    if (n == 0 || fs == NULL) __builtin_trap();
    for (k = 0; k < n; k++) {
      check(&fs[k]);
      lsys_func_free(&fs[k]);
    }
    free(fs);
  } else if (fs != NULL || n != 0 ||
             (e.code != LSYS_ENOMEM && strncmp(e.msg, "fuzz.func:", 10) != 0)) {
    __builtin_trap();                     /* nothing returned, and the message names the file */
  }
  return 0;
}
