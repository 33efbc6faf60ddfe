/*
** C unit tests for the turtle without Lua: records, states, queries, and the
** checks that Lua-level inputs cannot reach (a NaN parameter pushed directly).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "turtle.h"

static void parse (lsys_lstring *s, lsys_alphabet *a, const char *text) {
  lsys_error e;
  lsys_lstring_clear(s);
  assert(lsys_lstring_parse(s, text, strlen(text), a, NULL, &e) == LSYS_OK);
}

static int near (double a, double b) { return fabs(a - b) < 1e-9; }

static void test_draw (void) {
  lsys_alphabet a;
  lsys_lstring s;
  lsys_scene sc;
  lsys_turtle t;
  lsys_turtle_opts o;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  lsys_scene_init(&sc);
  lsys_turtle_init(&t);
  lsys_turtle_defaults(&o);
  o.style = LSYS_STYLE_CYLINDER;
  o.sides = 4;
  t.o = &o;
  t.scene = &sc;
  parse(&s, &a, "F(2)[+F]!(0.5)F");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
  assert(sc.nrec == 3);
  assert(sc.rec[0].module == 0 && sc.rec[1].module == 3 && sc.rec[2].module == 6);
  assert(sc.rec[1].parent == 0 && sc.rec[2].parent == 0);
  assert(near(sc.rec[2].p1[1] - sc.rec[2].len * sc.rec[2].H[1], 2) && near(sc.rec[2].p1[1], 3));
  /* F(2) ends at the bracket: top width 1; the last F starts at width 0.5 */
  assert(sc.rec[0].w1 == 1.0f && sc.rec[2].w0 == 0.5f);
  /* three cylinders of 4 sides, none sharing a ring (a width step and a turn), six caps */
  assert(sc.mesh.nt == 3 * 8 + 6 * 4);
  /* a second run reuses the buffers and starts from a cleared mesh */
  parse(&s, &a, "F");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
  assert(sc.nrec == 1 && sc.mesh.nt == 8 + 2 * 4);
  lsys_turtle_free(&t);
  lsys_scene_free(&sc);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

static void test_state_and_query (void) {
  lsys_alphabet a;
  lsys_lstring s;
  lsys_turtle t;
  lsys_turtle_opts o;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  lsys_turtle_init(&t);
  lsys_turtle_defaults(&o);
  t.o = &o;
  parse(&s, &a, "F(3)+F(2)?P(0,0,0)?H(0,0,0)");
  t.mode = LSYS_TURTLE_STATE;
  t.stop = 2;                         /* after F(3) + */
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
  assert(near(t.state.pos[1], 3) && near(t.state.H[0], -1) && t.mesh == NULL);
  t.mode = LSYS_TURTLE_QUERY;
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
  assert(t.nqueries == 2);
  assert(near(s.par[2], -2) && near(s.par[3], 3) && near(s.par[4], 0));   /* ?P */
  assert(near(s.par[5], -1) && near(s.par[6], 0));                        /* ?H */
  lsys_turtle_free(&t);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

static void test_errors (void) {
  lsys_alphabet a;
  lsys_lstring s;
  lsys_scene sc;
  lsys_turtle t;
  lsys_turtle_opts o;
  lsys_error e;
  double nan = NAN;
  uint32_t F;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  lsys_scene_init(&sc);
  lsys_turtle_init(&t);
  lsys_turtle_defaults(&o);
  t.o = &o;
  t.scene = &sc;
  parse(&s, &a, "FF");
  F = lsys_alphabet_intern(&a, "F", 1, &e);
  assert(lsys_lstring_push(&s, F, &nan, 1) == LSYS_OK);
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  assert(t.err.pos == 2);
  assert(strstr(t.err.msg, "module 3 'F': parameter 1 is not a finite number") != NULL);
  parse(&s, &a, "F@S");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  assert(strstr(t.err.msg, "refused") != NULL);
  o.allow_system = 1;
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && t.nsyscalls == 1);
  o.sides = 2;
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  o.sides = 8;
  /* found by the fuzzer: huge indices were converted to int unchecked */
  parse(&s, &a, ";(3.3e18)F,(-1e300)F@Tx(0)@#(0)F");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
  assert(sc.rec[0].color == 65535 && sc.rec[1].color == 0 && t.state.contour == 0);
  parse(&s, &a, "F@#(-4e9)F");                   /* a negative number names no contour */
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  assert(strstr(t.err.msg, "module 2 '@#': contour -4e+09 is not defined") != NULL);
  parse(&s, &a, "F(1e308)F(1e308)");             /* nothing could draw an infinite position */
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  assert(strstr(t.err.msg, "module 2 'F': the position is no longer finite") != NULL);
  parse(&s, &a, "F{.f.+f.");                     /* never closed: a warning, not an error */
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && t.warn.code != 0);
  assert(strstr(t.warn.msg, "polygon '{' of module 2 is never closed") != NULL);
  parse(&s, &a, "F");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && t.warn.code == 0);
  /* a texture the view does not define: a warning, and untextured (cpfg); contours the
  ** view does not define are errors */
  parse(&s, &a, "F@Tx(1e30)F@Tx(-1)");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && t.warn.code != 0 && t.warn.pos == 1);
  assert(strstr(t.warn.msg, "module 2 '@Tx': texture 65535 is not defined (the view has 0; "
                "view.textures); untextured from there") != NULL);
  parse(&s, &a, "F@#(4e9)");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG);
  assert(strstr(t.err.msg, "module 2 '@#': contour 65535 is not defined") != NULL);
  /* the two forms of a module's message, "module N: ..." and "module N 'symbol': ...",
  ** with the module's index as the position */
  parse(&s, &a, "F@Dd(0)");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG && t.err.pos == 1);
  assert(strcmp(t.err.msg, "module 2: @Dd: division of the scale by 0") == 0);
  parse(&s, &a, "FF@Gr(1,2,3)");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_EARG && t.err.pos == 2);
  assert(strcmp(t.err.msg, "module 3 '@Gr': takes 1, 2 or 4 parameters, not 3") == 0);
  /* a ~X the view has no surface for: nothing drawn, a warning naming its own symbol */
  parse(&s, &a, "F~QF~R");
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && t.warn.pos == 1 && sc.nrec == 2);
  assert(strcmp(t.warn.msg, "module 2 '~Q': no such surface in the view (view.surfaces); "
                            "nothing drawn there, as in cpfg") == 0);
  parse(&s, &a, "]]}F[[{");                  /* unbalanced: ignored, as cpfg does */
  assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK && sc.nrec == 1);
  lsys_turtle_free(&t);
  lsys_scene_free(&sc);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

int main (void) {
  test_draw();
  test_state_and_query();
  test_errors();
  printf("test_turtle ok\n");
  return 0;
}
