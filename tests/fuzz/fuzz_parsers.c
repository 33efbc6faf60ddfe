/*
** libFuzzer target for the two text parsers of the core: the rule parser
** (lsys_grammar_rule_parse, all three modes) and the Lstring text parser. The first
** byte picks the parser; the rest is the text. A parsed Lstring is then
** drawn by the turtle in every style, with two contours (closed and open),
** a predefined surface ~L and a texture in the view, twist minimisation on
** or off. Crashes, leaks and sanitizer reports are failures; syntax and
** turtle errors are expected results.
**
**   tools/fuzz.sh 600 parsers      (or, by hand:)
**   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF
**   cmake --build build-fuzz --target fuzz_parsers
**   build-fuzz/fuzz_parsers -max_total_time=600 tests/fuzz/corpus_parsers
*/
#include <stdint.h>
#include <string.h>

#include "grammar.h"
#include "lstring.h"
#include "turtle.h"

/* a view with contours 1 (closed) and 2 (open), surface ~L and one texture */
static const double star[] = {1, 0, 0, 0.3, 0.3, 0, 0, 1, 0, -0.3, 0.3, 0, -1, 0, 0,
                              -0.3, -0.3, 0, 0, -1, 0, 0.3, -0.3, 0};
static const double blade[] = {-1, 0, 0, -1, 0, 0, -1, 0, 0, 0, 0.3, 0, 1, 0, 0, 1, 0, 0,
                               1, 0, 0};
static const char leaf[] =
  "-1 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n"
  "HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\nblade\n"
  "TOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\nAL: ~ A: ~ AR: ~\nL: ~ R: ~\n"
  "BL: ~ B: ~ BR: ~\n0 0 0 0 0 0 0 0 0 0 0 0\n-1 .3 .1 -.3 .3 0 .3 .3 0 1 .3 .1\n"
  "-1 .7 .1 -.3 .7 0 .3 .7 0 1 .7 .1\n0 1 0 0 1 0 0 1 0 0 1 0\n";

static void view (lsys_turtle_opts *o, lsys_contour c[2], const lsys_contour *cp[3],
                  lsys_surface *sf, lsys_surfuse *su, lsys_texture *tx,
                  const lsys_texture **tp) {
  lsys_error e;
  lsys_contour_init(&c[0]); lsys_contour_init(&c[1]);
  lsys_contour_set(&c[0], star, 8, 1, 2, &e);
  lsys_contour_set(&c[1], blade, 7, 0, 2, &e);
  cp[0] = NULL; cp[1] = &c[0]; cp[2] = &c[1];
  o->contours = cp; o->ncontours = 3;
  lsys_surface_init(sf);
  lsys_surface_parse(sf, leaf, sizeof leaf - 1, "leaf.s", &e);
  su->name = "L"; su->s = sf; su->scale = 1; su->texture = 0; su->ns = 3; su->nt = 4;
  o->surfaces = su; o->nsurfaces = sf->npatch > 0;
  lsys_texture_init(tx);
  tx->w = 4; tx->h = 2; tx->per_surface = 1;
  tp[0] = tx;
  o->tex = tp; o->ntex = 1;
}

int LLVMFuzzerTestOneInput (const uint8_t *data, size_t size) {
  lsys_alphabet a;
  lsys_names decl = {0};
  lsys_error e;
  const char *text;
  if (size < 1) return 0;
  if (lsys_alphabet_init(&a) != LSYS_OK) return 0;
  lsys_alphabet_names_add(&decl, "Apex", 4);
  lsys_alphabet_names_add(&decl, "Leaf", 4);
  text = (const char *)data + 1;
  size--;
  switch (data[0] % 4) {
    case 0: case 1: case 2: {
      lsys_prule r;
      if (lsys_grammar_rule_parse(&r, text, size, data[0] % 4, &a, &decl, &e) == LSYS_OK) {
        size_t k;   /* every span must lie inside the text */
        for (k = 0; k < r.nparams; k++)
          if (r.params[k].off + r.params[k].len > size) __builtin_trap();
        if (r.cond.off + r.cond.len > size || r.weight.off + r.weight.len > size)
          __builtin_trap();
      }
      lsys_grammar_prule_free(&r);
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
        lsys_lstring_buf_free(&b);
        {   /* the turtle draws any string in every style without a crash */
          lsys_turtle tu;
          lsys_turtle_opts o;
          lsys_scene sc;
          lsys_contour c[2];
          const lsys_contour *cp[3];
          lsys_surface sf;
          lsys_surfuse su;
          lsys_texture tx;
          const lsys_texture *tp[1];
          int style;
          lsys_turtle_defaults(&o);
          view(&o, c, cp, &sf, &su, &tx, tp);
          o.minimize_twist = data[0] & 8 ? 0 : 1;
          o.ntrop = 2;
          o.trop[0].vec[1] = -1; o.trop[0].elasticity = 0.3; o.trop[0].angle = 40;
          o.trop[1].vec[0] = 1; o.trop[1].elasticity = 0.2; o.trop[1].torque = 1;
          o.sides = 3 + data[0] % 7;
          lsys_scene_init(&sc);
          lsys_turtle_init(&tu);
          tu.o = &o;
          tu.scene = &sc;
          for (style = 0; style < 3; style++) {
            o.style = style;
            lsys_turtle_run(&tu, &s, &a);
          }
          tu.mode = LSYS_TURTLE_QUERY;
          lsys_turtle_run(&tu, &s, &a);
          lsys_turtle_free(&tu);
          lsys_scene_free(&sc);
          lsys_contour_free(&c[0]); lsys_contour_free(&c[1]);
          lsys_surface_free(&sf);
        }
      }
      lsys_lstring_free(&s);
      break;
    }
  }
  lsys_alphabet_names_free(&decl);
  lsys_alphabet_free(&a);
  return 0;
}
