/*
** C unit tests for the Lstring, the alphabet and the name scanner.
*/
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <string.h>

#include "lstring.h"

static void roundtrip (lsys_alphabet *a, const char *in, const char *out, size_t n) {
  lsys_lstring s;
  lsys_buf b = {0};
  lsys_error e;
  lsys_lstring_init(&s);
  assert(lsys_lstring_parse(&s, in, strlen(in), a, NULL, &e) == LSYS_OK);
  assert(s.n == n);
  assert(lsys_lstring_format(&b, &s, a, NULL, 0, s.n) == LSYS_OK);
  assert(strcmp(b.p ? b.p : "", out) == 0);
  lsys_lstring_buf_free(&b);
  lsys_lstring_free(&s);
}

static void test_text (void) {
  lsys_alphabet a;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  roundtrip(&a, "F(1,0.5)[+A]", "F(1,0.5)[+A]", 5);
  roundtrip(&a, " F ( 1 , 2 ) F1F1 ", "F(1,2)F1F1", 5);
  roundtrip(&a, "A(0.1)B(-0)C(1e300)", "A(0.1)B(-0)C(1e+300)", 3);
  roundtrip(&a, "@Gs@Gc(3)?P(1,2)~l$%", "@Gs@Gc(3)?P(1,2)~l$%", 6);
  roundtrip(&a, "@ G", "@ G", 2);                 /* would read back as @G */
  roundtrip(&a, "", "", 0);
  lsys_alphabet_free(&a);
}

static void test_errors (void) {
  lsys_alphabet a;
  lsys_lstring s;
  lsys_error e;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  assert(lsys_lstring_parse(&s, "F(1", 3, &a, NULL, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, "unbalanced parentheses") != NULL);
  lsys_lstring_clear(&s);
  assert(lsys_lstring_parse(&s, "F(1,,2)", 7, &a, NULL, &e) == LSYS_ESYNTAX);
  assert(e.pos == 4);
  lsys_lstring_clear(&s);
  assert(lsys_lstring_parse(&s, "F(x)", 4, &a, NULL, &e) == LSYS_ESYNTAX);
  assert(strstr(e.msg, "bad number 'x'") != NULL);
  lsys_lstring_clear(&s);
  assert(lsys_lstring_parse(&s, "[(1)", 4, &a, NULL, &e) == LSYS_ESYNTAX);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

static void test_poff (void) {
  lsys_alphabet a;
  lsys_lstring s;
  double p[3] = {1, 2, 3};
  size_t i, off = 0;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  for (i = 0; i < 1000; i++)
    assert(lsys_lstring_push(&s, LSYS_SYM_FIRSTFREE, p, (uint32_t)(i % 4 == 0 ? 0 : i % 3 + 1)) == LSYS_OK);
  for (i = 0; i <= s.n; i++) {        /* checkpoints agree with a plain scan */
    assert(lsys_lstring_poff(&s, i) == off);
    if (i < s.n) off += LSYS_CNP(s.code[i]);
  }
  assert(off == s.npar);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

static void test_alphabet (void) {
  lsys_alphabet a;
  lsys_error e;
  char name[16];
  uint32_t i, first;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  assert(lsys_alphabet_find(&a, "[", 1) == LSYS_SYM_LBR);
  assert(lsys_alphabet_find(&a, "$", 1) == LSYS_SYM_SUBEND);
  first = lsys_alphabet_intern(&a, "Apex", 4, &e);
  assert(first == LSYS_SYM_FIRSTFREE);
  assert(lsys_alphabet_intern(&a, "Apex", 4, &e) == first);
  for (i = 0; a.n <= LSYS_MAXSYM; i++) {
    int n = snprintf(name, sizeof name, "N%u", i);
    assert(lsys_alphabet_intern(&a, name, (size_t)n, &e) != 0);
  }
  assert(lsys_alphabet_intern(&a, "onemore", 7, &e) == 0);
  assert(e.code == LSYS_ELIMIT && strstr(e.msg, "limit is 2047") != NULL);
  assert(lsys_alphabet_find(&a, "N5", 2) != 0);
  lsys_alphabet_truncate(&a, first + 1);          /* only Apex is left of the free ids */
  assert(a.n == first + 1 && lsys_alphabet_find(&a, "N5", 2) == 0);
  assert(lsys_alphabet_find(&a, "Apex", 4) == first && lsys_alphabet_find(&a, "$", 1) != 0);
  assert(lsys_alphabet_intern(&a, "onemore", 7, &e) == first + 1);
  lsys_alphabet_truncate(&a, 1);                  /* below the fixed ids: nothing */
  assert(lsys_alphabet_find(&a, "onemore", 7) == first + 1);
  lsys_alphabet_free(&a);
}

static void test_scan (void) {
  lsys_names d = {0};
  assert(lsys_alphabet_scan("@GsA", 4, NULL) == 3);
  assert(lsys_alphabet_scan("@XY", 3, NULL) == 2);
  assert(lsys_alphabet_scan("?P(1)", 5, NULL) == 2);
  assert(lsys_alphabet_scan("?(1)", 4, NULL) == 1);
  assert(lsys_alphabet_scan("~ab", 3, NULL) == 2);
  assert(lsys_alphabet_scan("(", 1, NULL) == 0);
  assert(lsys_alphabet_scan("\xce\xb1x", 3, NULL) == 2);     /* one UTF-8 character */
  assert(lsys_alphabet_names_add(&d, "Apex", 4) == LSYS_OK);
  assert(lsys_alphabet_scan("Apex(1)", 7, &d) == 4);
  assert(lsys_alphabet_scan("Ape", 3, &d) == 1);
  lsys_alphabet_names_free(&d);
}

/* A string's arrays across the size where they become mappings of their own
** (lstring.c, BIGBLOCK): grown module by module, in place, widened, prepared
** again smaller and larger, their contents kept at every change. */
static void test_blocks (void) {
  lsys_lstring s;
  size_t i, n = 600000;                  /* 1.2 MB of codes, 4.8 MB of parameters */
  lsys_lstring_init(&s);
  for (i = 0; i < n; i++) {
    double p = (double)i;
    assert(lsys_lstring_push(&s, (uint32_t)(i % 200) + 1, &p, i % 2) == LSYS_OK);
  }
  for (i = 0; i < n; i += 997) {
    assert(LSYS_CSYM(s.code[i]) == i % 200 + 1 && LSYS_CNP(s.code[i]) == i % 2);
  }
  assert(s.npar == n / 2 && s.par[0] == 1 && s.par[s.npar - 1] == (double)(n - 1));
  assert(lsys_lstring_grow(&s, 3 * n, 2 * n) == LSYS_OK);     /* larger, in place */
  assert(s.n == n && LSYS_CSYM(s.code[n - 1]) == (n - 1) % 200 + 1);
  assert(s.par[s.npar - 1] == (double)(n - 1));
  assert(lsys_lstring_prepare8(&s, 100) == LSYS_OK);          /* small, narrow */
  for (i = 0; i < 100; i++) s.sym8[i] = (uint8_t)(i + 1);
  s.n = 100;
  assert(lsys_lstring_grow(&s, 2000000, 0) == LSYS_OK);       /* to a mapping */
  for (i = 100; i < 2000000; i++) s.sym8[i] = (uint8_t)(i % 250 + 1);
  s.n = 2000000;
  assert(lsys_lstring_widen(&s) == LSYS_OK && s.sym8 == NULL);
  assert(LSYS_CSYM(s.code[5]) == 6 && LSYS_CSYM(s.code[1999999]) == 1999999 % 250 + 1);
  assert(lsys_lstring_prepare(&s, 10, 10) == LSYS_OK);        /* exact: small again */
  s.code[9] = LSYS_CODE(7, 0);
  s.n = 10;
  assert(lsys_lstring_reserve(&s, 1000000, 0) == LSYS_OK);    /* and back */
  assert(LSYS_CSYM(s.code[9]) == 7);
  lsys_lstring_free(&s);
}

int main (void) {
  test_blocks();
  test_text();
  test_errors();
  test_poff();
  test_alphabet();
  test_scan();
  return 0;
}
