/*
** libFuzzer target for the contour file parser and the sampling of what it
** accepts. Crashes, leaks and sanitizer reports are failures; syntax errors
** are expected results. A parsed contour is sampled with p = 3, 7 and 32:
** every vertex and normal must be finite, normals of unit length, V_0 on
** the +x axis (or at the origin), and V_p = V_0 for a closed contour.
**
**   tools/fuzz.sh 600 contour      (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_contour
**   build-fuzz/fuzz_contour -max_total_time=300 tests/fuzz/corpus_contour
*/
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "contour.h"

static void check (const lsys_contour *c, int p) {
  static double v[3 * 33], n[3 * 33];
  int i;
  if (lsys_contour_sample(c, p, v, n) != LSYS_OK) __builtin_trap();
  for (i = 0; i < 3 * (p + 1); i++)
    if (!isfinite(v[i]) || !isfinite(n[i])) __builtin_trap();
  for (i = 0; i <= p; i++)
    if (fabs(hypot(n[3 * i], n[3 * i + 1]) - 1) > 1e-9 || n[3 * i + 2] != 0) __builtin_trap();
  if (v[1] != 0 || v[0] < 0) __builtin_trap();
  if (c->closed && memcmp(v, v + 3 * p, 3 * sizeof *v) != 0) __builtin_trap();
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  lsys_contour c;
  lsys_error e;
  lsys_contour_init(&c);
  if (lsys_contour_parse(&c, (const char *)data, size, "fuzz.con", &e) == LSYS_OK) {
    if (c.n < 3 || c.pt == NULL || (c.dim != 2 && c.dim != 3)) __builtin_trap();
    check(&c, 3);
    check(&c, 7);
    check(&c, 32);
  } else if (c.pt != NULL || c.n != 0 ||
             (e.code != LSYS_ENOMEM && strncmp(e.msg, "fuzz.con:", 9) != 0)) {
    __builtin_trap();                     /* emptied, and the message names the file */
  }
  lsys_contour_free(&c);
  return 0;
}
