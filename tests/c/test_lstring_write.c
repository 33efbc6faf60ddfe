/*
** C unit tests for the text writer (lstring_write.c): its numbers against printf and strtod
** (the way they were formatted before it), its names against the separating scan it
** replaced, and the streamed text against the text in one buffer.
** LSYS_FMT_CASES sets the number of random doubles (default 1000000).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lstring.h"

/* ---------------------------------------------------------------------- */
/* the reference: the writer as it was, with printf and strtod */

static int old_fmtnum (char *buf, size_t size, double x) {
  int prec;
  if (x == 0) return snprintf(buf, size, signbit(x) ? "-0" : "0");
  if (x == trunc(x) && fabs(x) < 1e15) return snprintf(buf, size, "%.0f", x);
  for (prec = 15; prec <= 17; prec++) {
    snprintf(buf, size, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) break;
  }
  return (int)strlen(buf);
}

static int old_format (lsys_buf *b, lsys_lstring *s, const lsys_alphabet *a,
                       const lsys_names *decl, size_t i, size_t j) {
  size_t rs[16], rl[16], nr = 0, k, off = lsys_lstring_poff(s, i), window = 4, q;
  if (decl != NULL)
    for (q = 0; q < decl->n; q++)
      if (strlen(decl->v[q]) + 1 > window) window = strlen(decl->v[q]) + 1;
  if (window > 16) window = 16;
  for (k = i; k < j; k++) {
    uint32_t c = lsys_lstring_code(s, k), np = LSYS_CNP(c), m;
    const char *name = lsys_alphabet_name(a, LSYS_CSYM(c));
    size_t len = strlen(name), start = b->n;
    if (lsys_lstring_buf_add(b, name, len) != LSYS_OK) return LSYS_ENOMEM;
    for (q = 0; q < nr; q++)
      if (lsys_alphabet_scan(b->p + rs[q], b->n - rs[q], decl) != rl[q]) break;
    if (q == nr && nr > 0 && np == 0 && lsys_alphabet_scan(b->p + start, len, decl) != len)
      q = 0;
    if (q < nr) {
      b->n = start;
      if (lsys_lstring_buf_add(b, " ", 1) != LSYS_OK ||
          lsys_lstring_buf_add(b, name, len) != LSYS_OK)
        return LSYS_ENOMEM;
      nr = 0;
      start++;
    }
    if (np > 0) nr = 0;
    else {
      if (nr == window) { memmove(rs, rs + 1, (nr - 1) * sizeof *rs);
                          memmove(rl, rl + 1, (nr - 1) * sizeof *rl); nr--; }
      rs[nr] = start; rl[nr] = len; nr++;
    }
    if (np == 0) continue;
    for (m = 0; m < np; m++) {
      char num[40];
      int n = old_fmtnum(num, sizeof num, s->par[off + m]);
      if (lsys_lstring_buf_add(b, m == 0 ? "(" : ",", 1) != LSYS_OK ||
          lsys_lstring_buf_add(b, num, (size_t)n) != LSYS_OK)
        return LSYS_ENOMEM;
    }
    off += np;
    if (lsys_lstring_buf_add(b, ")", 1) != LSYS_OK) return LSYS_ENOMEM;
  }
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static uint64_t next (void) {                 /* splitmix64 */
  uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
static double unit (void) { return (double)(next() >> 11) / 9007199254740992.0; }

/* A random double of one of several kinds: any bits, log-uniform over the exact range and
** past it, short decimals, quotients like a parametric model's, near powers of two and ten. */
static double randnum (void) {
  uint64_t bits;
  double x;
  char t[40];
  switch (next() % 8) {
    case 0: bits = next(); memcpy(&x, &bits, sizeof x); break;
    case 1: x = pow(10, -8 + 24 * unit()); break;
    case 2: x = pow(10, -6 + 21 * unit()); break;
    case 3: snprintf(t, sizeof t, "%.*g", (int)(1 + next() % 17), pow(10, -7 + 22 * unit()));
            x = strtod(t, NULL); break;
    case 4: x = pow(1.456, -(double)(next() % 40)) * (double)(1 + next() % 9); break;
    case 5: x = ldexp(1.0, (int)(next() % 120) - 70); break;
    case 6: bits = next(); memcpy(&x, &bits, sizeof x);
            x = pow(10, (double)(int)(next() % 22) - 7) * (1 + ldexp((double)(next() % 5) - 2, -52));
            break;
    default: x = (double)(next() % 100000) / (double)(1 + next() % 1000); break;
  }
  if (!isfinite(x)) x = 0.5;
  return next() & 1 ? -x : x;
}

static void test_numbers (void) {
  const char *env = getenv("LSYS_FMT_CASES");
  long n = env ? atol(env) : 1000000, i;
  static const double fixed[] = {
    0.1, 0.2, 0.3, 1.0 / 3, 2.0 / 3, 1e-5, 1.5e-5, 9.9999999999999995e-7, 1e-6, 123456.789,
    0.6868131868131868, 999999999999999.9, 99999999999999.99, 0.99999999999999999, 5e-324,
    1e15 + 0.5, 4503599627370495.5, 1e300, -1e-300, 0.5, 0.25, 0.125, 1.7976931348623157e308,
    2.2250738585072014e-308, 0.30000000000000004, 1e-7, 123e-20, 3.14159265358979
  };
  char a[64], b[64];
  for (i = 0; i < (long)(sizeof fixed / sizeof *fixed) + n; i++) {
    double x = i < (long)(sizeof fixed / sizeof *fixed) ? fixed[i] : randnum();
    int la = lsys_lstring_fmtnum(a, sizeof a, x), lb = old_fmtnum(b, sizeof b, x);
    if (la != lb || strcmp(a, b) != 0) {
      fprintf(stderr, "%.17g: new '%s', old '%s'\n", x, a, b);
      assert(0);
    }
    assert(strtod(a, NULL) == x);
  }
}

/* ---------------------------------------------------------------------- */
/* names */

static const char *NAMES[] = {
  "F", "A", "B", "+", "-", "[", "]", "@", "G", "O", "@O", "@Gs", "@Gc", "s", "c", "?", "P",
  "?P", "~", "l", "~l", "AB", "ABC", "Apex", "x", "\xce\xb1", "\xe2\x82\xac", "FF", "%", "$",
  "@v", "v"
};
#define NNAMES (sizeof NAMES / sizeof *NAMES)

static int collect (void *ud, const char *p, size_t n) {
  lsys_buf *b = (lsys_buf *)ud;
  assert(n > 0);
  return lsys_lstring_buf_add(b, p, n);
}

static int failing (void *ud, const char *p, size_t n) {
  (void)p; (void)n;
  return ++*(int *)ud >= 2 ? LSYS_EARG : LSYS_OK;
}

/* Formats 's' four ways (old, buffer, stream, and ranges) and checks they agree. */
static void agree (lsys_lstring *s, lsys_alphabet *a, const lsys_names *decl) {
  lsys_buf old = {0}, buf = {0}, str = {0};
  assert(old_format(&old, s, a, decl, 0, s->n) == LSYS_OK);
  assert(lsys_lstring_format(&buf, s, a, decl, 0, s->n) == LSYS_OK);
  assert(lsys_lstring_write(s, a, decl, 0, s->n, 0, collect, &str) == LSYS_OK);
  assert(old.n == buf.n && (old.n == 0 || memcmp(old.p, buf.p, old.n) == 0));
  assert(buf.p == NULL || buf.p[buf.n] == '\0');
  assert(str.n == buf.n && (buf.n == 0 || memcmp(str.p, buf.p, buf.n) == 0));
  if (s->n > 3) {                     /* a range from the middle */
    size_t i = s->n / 3, j = s->n - 1;
    old.n = buf.n = 0;
    assert(old_format(&old, s, a, decl, i, j) == LSYS_OK);
    assert(lsys_lstring_format(&buf, s, a, decl, i, j) == LSYS_OK);
    assert(old.n == buf.n && memcmp(old.p, buf.p, old.n) == 0);
  }
  lsys_lstring_buf_free(&old);
  lsys_lstring_buf_free(&buf);
  lsys_lstring_buf_free(&str);
}

static void test_names (void) {
  lsys_alphabet a;
  lsys_names decl = {0};
  lsys_lstring s;
  lsys_error e;
  uint32_t ids[NNAMES];
  size_t k, t, round;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  for (k = 0; k < NNAMES; k++) {
    ids[k] = lsys_alphabet_intern(&a, NAMES[k], strlen(NAMES[k]), &e);
    assert(ids[k] != 0);
  }
  assert(lsys_alphabet_names_add(&decl, "AB", 2) == LSYS_OK);
  assert(lsys_alphabet_names_add(&decl, "Apex", 4) == LSYS_OK);
  lsys_lstring_init(&s);
  for (round = 0; round < 400; round++) {       /* short strings of names that merge */
    size_t n = 1 + next() % (round < 300 ? 12 : 3000), sub = next() % 4;
    lsys_lstring_clear(&s);
    for (k = 0; k < n; k++) {
      double p[3] = { randnum(), (double)(next() % 7), 0.5 };
      uint32_t sym = sub == 0 ? ids[next() % 8] : ids[next() % NNAMES];
      uint32_t np = next() % 5 == 0 ? (uint32_t)(next() % 3 + 1) : 0;
      if (sym == LSYS_SYM_LBR || sym == LSYS_SYM_RBR) np = 0;
      assert(lsys_lstring_push(&s, sym, p, np) == LSYS_OK);
    }
    agree(&s, &a, NULL);
    agree(&s, &a, &decl);
  }
  for (t = 0; t < 3; t++) {                   /* narrow strings across many chunks */
    size_t n = 500000;
    assert(lsys_lstring_prepare8(&s, n) == LSYS_OK);
    for (k = 0; k < n; k++) {
      uint32_t pick = t == 0 ? (uint32_t)(next() % 5) : t == 1 ? (uint32_t)(next() % NNAMES)
                    : (k % 1000 == 999 ? 7u : (uint32_t)(next() % 5));
      s.sym8[k] = (uint8_t)ids[pick];
    }
    s.n = n;
    agree(&s, &a, NULL);
    agree(&s, &a, &decl);
  }
  {                                           /* a sink's error stops the writing */
    int calls = 0;
    assert(lsys_lstring_write(&s, &a, NULL, 0, s.n, 0, failing, &calls) == LSYS_EARG);
    assert(calls == 2);
  }
  lsys_lstring_free(&s);
  lsys_alphabet_names_free(&decl);
  lsys_alphabet_free(&a);
}

int main (void) {
  test_numbers();
  test_names();
  return 0;
}
