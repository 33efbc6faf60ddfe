/*
** C unit tests for the turtle without Lua: records, states, queries, and the
** checks that Lua-level inputs cannot reach (a NaN parameter pushed directly).
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mesh.h"
#include "turtle.h"
#include "vec3.h"

static void parse (lsys_lstring *s, lsys_alphabet *a, const char *text) {
  lsys_error e;
  lsys_lstring_clear(s);
  assert(lsys_lstring_parse(s, text, strlen(text), a, NULL, &e) == LSYS_OK);
}

static int near (double a, double b) { return fabs(a - b) < 1e-9; }

static void test_draw (void) {
  lsys_alphabet a;
  lsys_trec r[3];
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
  lsys_scene_record(&sc, 0, &r[0]);
  lsys_scene_record(&sc, 1, &r[1]);
  lsys_scene_record(&sc, 2, &r[2]);
  assert(r[0].module == 0 && r[1].module == 3 && r[2].module == 6);
  assert(r[1].parent == 0 && r[2].parent == 0);
  assert(near(r[2].p1[1] - r[2].len * r[2].H[1], 2) && near(r[2].p1[1], 3));
  /* F(2) ends at the bracket: top width 1; the last F starts at width 0.5 */
  assert(r[0].w1 == 1.0f && r[2].w0 == 0.5f);
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

/* The least distance from the y axis of the band triangles of sc's mesh (those
** with no vertex on the axis: not caps), sampled on a barycentric grid. */
static double waist (const lsys_scene *sc) {
  const lsys_mesh *m = &sc->mesh;
  double least = INFINITY;
  size_t t;
  for (t = 0; t < m->nt; t++) {
    const float *v[3];
    int k, i, j, cap = 0;
    for (k = 0; k < 3; k++) {
      v[k] = m->pos + 3 * m->tri[3 * t + k];
      if (hypot(v[k][0], v[k][2]) < 1e-6) cap = 1;
    }
    if (cap) continue;
    for (i = 0; i <= 10; i++)
      for (j = 0; i + j <= 10; j++) {
        double a = i / 10.0, b = j / 10.0, c = 1 - a - b;
        double x = c * v[0][0] + a * v[1][0] + b * v[2][0];
        double z = c * v[0][2] + a * v[1][2] + b * v[2][2];
        if (hypot(x, z) < least) least = hypot(x, z);
      }
  }
  return least;
}

/* A roll between two cylinders: the second segment's ring starts at the
** turtle's ring vertex nearest the shared ring's first vertex, so the band
** between them keeps the section (it pinched to 2 % of the radius). */
static void test_roll (void) {
  static const char *const rolls[] = { "F/(137.5)F", "F/(180)F", "F\\(45)F", "F/(90)F",
                                       "F/(10)F/(200)F\\(137.5)F" };
  lsys_alphabet a;
  lsys_lstring s;
  lsys_scene sc;
  lsys_turtle t;
  lsys_turtle_opts o;
  double cs[2 * 8 + 2], L2[3], U2[3], out[3], tw;
  int n, k, steps;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  lsys_scene_init(&sc);
  lsys_turtle_init(&t);
  lsys_turtle_defaults(&o);
  o.style = LSYS_STYLE_CYLINDER;
  t.o = &o;
  t.scene = &sc;
  for (n = 8; n <= 16; n += 2) {
    o.sides = n;
    for (k = 0; k < (int)(sizeof rolls / sizeof *rolls); k++) {
      double w;
      parse(&s, &a, rolls[k]);
      assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
      w = waist(&sc) / 0.5;                      /* width 1: radius 0.5 */
      assert(w >= cos(PI / n) - 1e-6 && w < 1);  /* no nearer than the n-gon's own sides */
    }
  }
  /* the old first vertex 100 degrees round from L: the new ring starts at the
  ** turtle's vertex 2 (90 degrees), 10 degrees short of it */
  lsys_mesh_ringtable(cs, 8);
  {
    const double H[3] = {0, 1, 0}, L[3] = {1, 0, 0}, U[3] = {0, 0, 1};
    double pL[3] = {cos(100 * PI / 180), 0, sin(100 * PI / 180)};
    tw = lsys_mesh_ringmatch(L2, U2, &steps, H, pL, H, L, U, cs, 8);
    assert(steps == 2 && fabs(tw + 10 * PI / 180) < 1e-12);
    assert(fabs(L2[2] - 1) < 1e-12 && fabs(U2[0] + 1) < 1e-12);
    pL[0] = cos(-100 * PI / 180); pL[2] = sin(-100 * PI / 180);   /* vertex 6, 10 past it */
    tw = lsys_mesh_ringmatch(L2, U2, &steps, H, pL, H, L, U, cs, 8);
    assert(steps == 6 && fabs(tw - 10 * PI / 180) < 1e-12);
  }
  {
    /* a bend of 30 degrees about z carries x into the new heading's normal plane
    ** and leaves z alone */
    const double A[3] = {0, 1, 0}, B[3] = {-sin(PI / 6), cos(PI / 6), 0};
    const double X[3] = {1, 0, 0}, Z[3] = {0, 0, 1};
    lsys_mesh_transport(out, X, A, B);
    assert(fabs(out[0] - cos(PI / 6)) < 1e-12 && fabs(out[1] - sin(PI / 6)) < 1e-12);
    assert(fabs(vdot(out, B)) < 1e-12);
    lsys_mesh_transport(out, Z, A, B);
    assert(fabs(out[2] - 1) < 1e-12 && fabs(out[0]) + fabs(out[1]) < 1e-12);
  }
  {
    /* the band's diagonals: base k to top k + 1, or base k + 1 to top k when
    ** the top ring is turned ahead */
    lsys_mesh m;
    lsys_mesh_init(&m);
    assert(lsys_mesh_reserve(&m, 0, 16) == LSYS_OK);
    lsys_mesh_band(&m, 0, 10, 4, -0.1);
    assert(m.tri[0] == 0 && m.tri[1] == 11 && m.tri[2] == 1);
    lsys_mesh_band(&m, 0, 10, 4, 0.1);
    assert(m.tri[24] == 0 && m.tri[25] == 10 && m.tri[26] == 1);
    assert(m.tri[27] == 1 && m.tri[28] == 10 && m.tri[29] == 11);
    lsys_mesh_free(&m);
  }
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
  lsys_trec r[2];
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
  lsys_scene_record(&sc, 0, &r[0]);
  lsys_scene_record(&sc, 1, &r[1]);
  assert(r[0].color == 65535 && r[1].color == 0 && t.state.contour == 0);
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
  test_roll();
  test_state_and_query();
  test_errors();
  printf("test_turtle ok\n");
  return 0;
}
