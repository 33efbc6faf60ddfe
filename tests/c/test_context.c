/*
** C unit tests for the context tables (context.c): every bracket's partner
** and every module's first parameter, asked of windows of every size and
** place (a window of one module too), against a plain scan. The answers come
** from the window, from the string's far brackets, or from a scan near the
** bracket; all three must agree with the plain scan everywhere.
*/
#define _POSIX_C_SOURCE 200809L
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "derive_impl.h"

static uint32_t lcg = 1;
static uint32_t rnd (uint32_t k) {
  lcg = lcg * 1103515245u + 12345u;
  return (lcg >> 8) % k;
}

/* A random bracketed string of about n modules: runs nested deep, branches
** of every span, unmatched brackets at both ends; parameters when 'withp'. */
static void build (lsys_lstring *s, uint32_t A, size_t n, int withp) {
  double p[3] = {1, 2, 3};
  size_t k, depth = 0;
  lsys_lstring_clear(s);
  assert(lsys_lstring_push(s, LSYS_SYM_RBR, NULL, 0) == LSYS_OK);   /* unmatched */
  while (s->n < n) {
    uint32_t r = rnd(100);
    if (r < 15 || r == 30)                      /* r == 30: nested 700 deep */
      for (k = 0; k < (r == 30 ? 700u : 1u); k++, depth++)
        assert(lsys_lstring_push(s, LSYS_SYM_LBR, NULL, 0) == LSYS_OK);
    else if (r < 29 || r == 31)                 /* r == 31: out of 700 */
      for (k = 0; k < (r == 31 ? 700u : 1u) && depth > 0; k++, depth--)
        assert(lsys_lstring_push(s, LSYS_SYM_RBR, NULL, 0) == LSYS_OK);
    else assert(lsys_lstring_push(s, A, p, withp ? rnd(4) : 0) == LSYS_OK);
  }
  assert(lsys_lstring_push(s, LSYS_SYM_LBR, NULL, 0) == LSYS_OK);   /* unmatched */
}

static uint16_t code (const lsys_lstring *s, size_t i) { return lsys_lstring_code(s, i); }

/* The partner of the bracket at j by a plain scan, or NONE. */
static uint32_t partner (const lsys_lstring *s, size_t j) {
  size_t k, depth = 0;
  if (LSYS_CSYM(code(s, j)) == LSYS_SYM_LBR) {
    for (k = j + 1; k < s->n; k++) {
      uint32_t c = LSYS_CSYM(code(s, k));
      if (c == LSYS_SYM_LBR) depth++;
      else if (c == LSYS_SYM_RBR && depth-- == 0) return (uint32_t)k;
    }
  }
  else
    for (k = j; k-- > 0;) {
      uint32_t c = LSYS_CSYM(code(s, k));
      if (c == LSYS_SYM_RBR) depth++;
      else if (c == LSYS_SYM_LBR && depth-- == 0) return (uint32_t)k;
    }
  return NONE;
}

static void check (lsys_rules *m, const lsys_lstring *s, const uint32_t *want, const size_t *off,
                   size_t a, size_t b) {
  lsys_brkwin w;
  view v;
  size_t j;
  memset(&w, 0, sizeof w);
  memset(&v, 0, sizeof v);
  v.code = s->code; v.code8 = s->sym8; v.par = s->par; v.n = s->n;
  v.match = &w;
  assert(lsys_context_window(&w, &m->brk, &v, a, b) == LSYS_OK);
  for (j = 0; j < s->n; j++) {
    uint32_t c = LSYS_CSYM(code(s, j));
    if (c == LSYS_SYM_LBR || c == LSYS_SYM_RBR) {
      if (lsys_view_partner(&v, j) != want[j]) {
        fprintf(stderr, "window [%zu, %zu): partner of %zu is %u, not %u\n", a, b, j,
                lsys_view_partner(&v, j), want[j]);
        abort();
      }
    }
    if (off != NULL) assert(lsys_view_poff(&v, j) == off[j]);
  }
  if (off != NULL) assert(lsys_view_poff(&v, s->n) == off[s->n]);
  lsys_context_freewin(&w);
}

static void test_windows (int withp) {
  lsys_alphabet ab;
  lsys_rules m;
  lsys_lstring s;
  uint32_t A, *want;
  size_t j, *off = NULL, nfar = 0, nnear = 0, n = 30000;
  static const size_t sizes[] = {1, 2, 63, 64, 65, 700, 1024, 1025, 5000, 30000};
  assert(lsys_alphabet_init(&ab) == LSYS_OK);
  assert(lsys_rules_init(&m, &ab) == LSYS_OK);
  A = lsys_alphabet_intern(&ab, "A", 1, NULL);
  assert(A > 0 && A < 256);
  lsys_lstring_init(&s);
  build(&s, A, n, withp);
  if (!withp) {                               /* a byte a module, as a step makes it */
    lsys_lstring s8;
    lsys_lstring_init(&s8);
    assert(lsys_lstring_prepare8(&s8, s.n) == LSYS_OK && s8.sym8 != NULL);
    for (j = 0; j < s.n; j++) s8.sym8[j] = (uint8_t)LSYS_CSYM(s.code[j]);
    s8.n = s.n;
    lsys_lstring_free(&s);
    s = s8;
  }
  m.meter.limit = (size_t)-1;
  assert(lsys_context_buildtables(&m, &s) == LSYS_OK);
  assert((want = malloc(s.n * sizeof *want)) != NULL);
  for (j = 0; j < s.n; j++) want[j] = partner(&s, j);
  for (j = 0; j < s.n; j++) {
    uint32_t c = LSYS_CSYM(code(&s, j));
    if ((c == LSYS_SYM_LBR || c == LSYS_SYM_RBR) &&
        (want[j] == NONE || (want[j] > j ? want[j] - j : j - want[j]) > LSYS_BRK_NEAR))
      nfar++;
    else if (c == LSYS_SYM_LBR || c == LSYS_SYM_RBR) nnear++;
  }
  assert(nfar > 100 && nnear > 1000);          /* the far list is used, and the scans */
  assert(m.brk.nfar == nfar);                  /* it lists those and only those */
  if (withp) {
    assert((off = malloc((s.n + 1) * sizeof *off)) != NULL);
    for (off[0] = 0, j = 0; j < s.n; j++) off[j + 1] = off[j] + LSYS_CNP(s.code[j]);
    assert(off[s.n] == s.npar && s.npar > 1000);
  }
  for (j = 0; j < sizeof sizes / sizeof *sizes; j++) {
    size_t at;
    for (at = 0; at + sizes[j] <= s.n; at += sizes[j] > 4000 ? 3001 : 4999)
      check(&m, &s, want, off, at, at + sizes[j]);
    check(&m, &s, want, off, s.n - sizes[j], s.n);
  }
  free(want);
  free(off);
  lsys_lstring_free(&s);
  lsys_rules_free(&m);
  lsys_alphabet_free(&ab);
}

int main (void) {
  test_windows(0);
  test_windows(1);
  printf("test_context: ok\n");
  return 0;
}
