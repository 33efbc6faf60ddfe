/*
** C unit tests for the turtle's symbol table (symbols.h): one row per operation,
** unique names that the scanner reads as one module each, and the parallel split's
** default: an operation the table does not list as safe keeps the string on one
** thread, and only the documented ones cross branches.
*/
#undef NDEBUG
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "turtle_impl.h"

/* The named symbols whose effect crosses branches outside the turtle state (the
** polygon stack, sub-L-systems, generalized cylinders, patches, @S), as
** docs/architecture.md lists them; the ~X surfaces have no name of their own. */
static const char *const crossing[] = {
  "{", "}", ".", "?", "$", "@Gs", "@Gc", "@Ge", "@Gt", "@Gr", "@PS", "@PC", "@PD", "@S",
  "?E"                                   /* the environment's queries, in string order */
};

/* The symbols that leave a pending segment open, and the query modules. */
static const char *const keeping[] = {
  "+", "-", "&", "^", "\\", "/", "|", "#", "!", ";", ",", ".", "?P", "?H", "?U", "?L", "Z",
  "_", "?E"
};
static const char *const queries[] = {"?P", "?H", "?U", "?L"};

static int listed (const char *const *list, size_t n, const char *name) {
  size_t k;
  for (k = 0; k < n; k++)
    if (name != NULL && strcmp(list[k], name) == 0) return 1;
  return 0;
}
#define LISTED(list, name) listed((list), sizeof (list) / sizeof (list)[0], (name))

static void test_rows (void) {
  size_t j, k, named = 0;
  assert((int)LSYS_NSYMBOLS == (int)OP_COUNT);           /* every operation has a row */
  assert(lsys_symbols[OP_NONE].name == NULL && lsys_symbols[OP_SURFACE].name == NULL);
  assert(strcmp(lsys_symbols[OP_F].name, "F") == 0 && strcmp(lsys_symbols[OP_F].op, "F") == 0);
  assert(strcmp(lsys_symbols[OP_ROLLL].name, "\\") == 0);
  assert(strcmp(lsys_symbols[OP_JOINT].name, "@J") == 0);
  assert(lsys_symbols[OP_PUSH].split == LSYS_SPLIT_OPEN);
  assert(lsys_symbols[OP_POP].split == LSYS_SPLIT_CLOSE);
  for (k = 0; k < LSYS_NSYMBOLS; k++) {
    const lsys_symbol *r = &lsys_symbols[k];
    assert(r->op != NULL && r->op[0] != '\0');
    assert(r->split <= LSYS_SPLIT_RECORD && r->keep <= 1 && r->query <= 1);
    for (j = 0; j < k; j++) {                            /* unique operations and names */
      assert(strcmp(lsys_symbols[j].op, r->op) != 0);
      assert(r->name == NULL || lsys_symbols[j].name == NULL ||
             strcmp(lsys_symbols[j].name, r->name) != 0);
    }
    if (r->name == NULL) continue;
    named++;
    {                                                    /* one module, as the scanner reads */
      size_t n = strlen(r->name);
      char text[16];
      assert(n > 0 && n + 4 < sizeof text);
      assert(lsys_alphabet_scan(r->name, n, NULL) == n);
      snprintf(text, sizeof text, "%s(1)", r->name);
      assert(lsys_alphabet_scan(text, strlen(text), NULL) == n);
      assert(r->name[0] != '@' || lsys_symbols_match(text, strlen(text), '@') == n);
    }
    assert(r->keep == (unsigned)LISTED(keeping, r->name));
    assert(r->query == (unsigned)LISTED(queries, r->name));
  }
  assert(named == LSYS_NSYMBOLS - 3);                    /* but NONE, SURFACE, NOSURFACE */
  /* '@' and a letter the table does not have is still one module (cpfg's @H) */
  assert(lsys_alphabet_scan("@H(1)", 5, NULL) == 2 && lsys_alphabet_scan("@Dx", 3, NULL) == 2);
  assert(lsys_alphabet_scan("@Dix", 4, NULL) == 3 && lsys_alphabet_scan("@1", 2, NULL) == 1);
  assert(lsys_symbols_match("@Dd", 3, '@') == 3 && lsys_symbols_match("@Q", 2, '@') == 0);
}

/* The split: crossing is the default, safe only what the table says. */
static void test_split (void) {
  unsigned op;
  for (op = 0; op < 1024; op++) {
    int c = lsys_symbols_split(op);
    if (op >= LSYS_NSYMBOLS) { assert(c == LSYS_SPLIT_CROSS); continue; }
    assert(c == lsys_symbols[op].split);
    if (lsys_symbols[op].name != NULL)
      assert((c == LSYS_SPLIT_CROSS) == LISTED(crossing, lsys_symbols[op].name));
  }
  assert(lsys_symbols_split(OP_NONE) == LSYS_SPLIT_STATE);   /* unknown modules do nothing */
  assert(lsys_symbols_split(OP_SURFACE) == LSYS_SPLIT_CROSS);
  assert(lsys_symbols_split(OP_NOSURFACE) == LSYS_SPLIT_CROSS);
  assert(lsys_symbols_split(OP_F) == LSYS_SPLIT_SEGMENT);
  assert(lsys_symbols_split(OP_SPHERE) == LSYS_SPLIT_SHAPE);
  assert(lsys_symbols_split(OP_LABEL) == LSYS_SPLIT_RECORD);
  assert(!lsys_symbols_keep(OP_COUNT) && !lsys_symbols_keep(OP_F) && lsys_symbols_keep(OP_LEFT));
}

/* A tree of branches, with 'sym' between its two halves: on two threads, it is cut
** into pieces unless the symbol crosses branches. */
static void test_runs (void) {
  static const char tree[] = "F[+F[+F]F[-F]F]F[-F[+F]F[-F]F]F";
  lsys_alphabet a;
  lsys_lstring s;
  size_t k;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  for (k = 0; k < LSYS_NSYMBOLS; k++) {
    const lsys_symbol *r = &lsys_symbols[k];
    char text[2 * sizeof tree + 16];
    lsys_turtle_opts o;
    lsys_scene sc;
    lsys_turtle t;
    lsys_error e;
    if (r->name == NULL || r->split == LSYS_SPLIT_OPEN || r->split == LSYS_SPLIT_CLOSE)
      continue;
    snprintf(text, sizeof text, "%s %s %s", tree, r->name, tree);
    lsys_lstring_clear(&s);
    assert(lsys_lstring_parse(&s, text, strlen(text), &a, NULL, &e) == LSYS_OK);
    lsys_turtle_defaults(&o);
    lsys_scene_init(&sc);
    lsys_turtle_init(&t);
    t.o = &o; t.scene = &sc; t.threads = 2; t.piecemin = 2;
    (void)lsys_turtle_run(&t, &s, &a);      /* some fail without parameters: no matter */
    assert((t.npieces == 0) == (r->split == LSYS_SPLIT_CROSS));
    lsys_turtle_free(&t);
    lsys_scene_free(&sc);
  }
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

int main (void) {
  test_rows();
  test_split();
  test_runs();
  printf("test_symbols: ok\n");
  return 0;
}
