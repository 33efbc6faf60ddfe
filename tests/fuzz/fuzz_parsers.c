/*
** libFuzzer target for the two text parsers of the core: the rule parser
** (lsys_rule_parse, all three modes) and the Lstring text parser. The first
** byte picks the parser; the rest is the text. Crashes, leaks and
** sanitizer reports are failures; syntax errors are expected results.
**
**   clang -g -O1 -fsanitize=fuzzer,address,undefined -Icsrc tests/fuzz/fuzz_parsers.c \
**         csrc/common.c csrc/alphabet.c csrc/lstring.c csrc/grammar.c -lm -o fuzz_parsers
**   ./fuzz_parsers -max_total_time=600 tests/fuzz/corpus
*/
#include <stdint.h>
#include <string.h>

#include "grammar.h"
#include "lstring.h"
#include "turtle.h"

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  lsys_alphabet a;
  lsys_names decl = {0};
  lsys_error e;
  const char *text;
  if (size < 1) return 0;
  if (lsys_alphabet_init(&a) != LSYS_OK) return 0;
  lsys_names_add(&decl, "Apex", 4);
  lsys_names_add(&decl, "Leaf", 4);
  text = (const char *)data + 1;
  size--;
  switch (data[0] % 4) {
    case 0: case 1: case 2: {
      lsys_prule r;
      if (lsys_rule_parse(&r, text, size, data[0] % 4, &a, &decl, &e) == LSYS_OK) {
        size_t k;   /* every span must lie inside the text */
        for (k = 0; k < r.nparams; k++)
          if (r.params[k].off + r.params[k].len > size) __builtin_trap();
        if (r.cond.off + r.cond.len > size || r.weight.off + r.weight.len > size)
          __builtin_trap();
      }
      lsys_prule_free(&r);
      break;
    }
    default: {
      lsys_lstring s;
      lsys_lstring_init(&s);
      if (lsys_lstring_parse(&s, text, size, &a, &decl, &e) == LSYS_OK) {
        lsys_buf b = {0};   /* printing and reparsing gives the same string */
        lsys_lstring t;
        lsys_lstring_init(&t);
        if (lsys_lstring_format(&b, &s, &a, &decl, 0, s.n) != LSYS_OK) __builtin_trap();
        if (lsys_lstring_parse(&t, b.p ? b.p : "", b.n, &a, &decl, &e) != LSYS_OK)
          __builtin_trap();
        if (t.n != s.n || t.npar != s.npar) __builtin_trap();
        lsys_lstring_unbalanced(&s);
        lsys_lstring_free(&t);
        lsys_buf_free(&b);
        {   /* the turtle draws any string in every style without a crash */
          lsys_turtle tu;
          lsys_turtle_opts o;
          lsys_mesh m;
          int style;
          lsys_turtle_defaults(&o);
          o.ntrop = 2;
          o.trop[0].vec[1] = -1; o.trop[0].elasticity = 0.3; o.trop[0].angle = 40;
          o.trop[1].vec[0] = 1; o.trop[1].elasticity = 0.2; o.trop[1].torque = 1;
          o.sides = 3 + data[0] % 7;
          lsys_mesh_init(&m);
          lsys_turtle_init(&tu);
          tu.o = &o;
          tu.mesh = &m;
          for (style = 0; style < 3; style++) {
            o.style = style;
            lsys_turtle_run(&tu, &s, &a);
          }
          tu.mode = LSYS_TURTLE_QUERY;
          lsys_turtle_run(&tu, &s, &a);
          lsys_turtle_free(&tu);
          lsys_mesh_free(&m);
        }
      }
      lsys_lstring_free(&s);
      break;
    }
  }
  lsys_names_free(&decl);
  lsys_alphabet_free(&a);
  return 0;
}
