/*
** C unit tests for the turtle on several threads (turtle_par.c): a string cut
** into pieces at its branches gives exactly the one-thread scene (every
** vertex, triangle, line, record and stiffness, the final state), for 1, 2
** and 3 threads and pieces of every size; errors name the module one thread
** names; modules whose effect crosses branches keep the string whole.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "turtle.h"

/* 'axiom' after 'n' steps of the one rule F -> succ, as text. */
static char *expand (const char *axiom, const char *succ, int n) {
  char *s = strdup(axiom);
  size_t ls = strlen(succ);
  assert(s != NULL);
  while (n-- > 0) {
    size_t k, len = 0, nf = 0;
    char *d;
    for (k = 0; s[k]; k++) nf += s[k] == 'F';
    d = (char *)malloc(strlen(s) + nf * ls + 1);
    assert(d != NULL);
    for (k = 0; s[k]; k++) {
      if (s[k] == 'F') { memcpy(d + len, succ, ls); len += ls; }
      else d[len++] = s[k];
    }
    d[len] = '\0';
    free(s);
    s = d;
  }
  return s;
}

static void parse (lsys_lstring *s, lsys_alphabet *a, const char *text) {
  lsys_error e;
  lsys_lstring_clear(s);
  if (lsys_lstring_parse(s, text, strlen(text), a, NULL, &e) != LSYS_OK) {
    fprintf(stderr, "%s: %.40s\n", e.msg, text + (e.pos < strlen(text) ? e.pos : 0));
    assert(0);
  }
}

#define SAME(x, y, n) assert((n) == 0 || memcmp((x), (y), (n)) == 0)

/* The two scenes hold the same geometry, records and stiffnesses. */
static void same (const lsys_scene *x, const lsys_scene *y) {
  const lsys_mesh *a = &x->mesh, *b = &y->mesh;
  assert(a->nv == b->nv && a->nt == b->nt && a->nl == b->nl);
  SAME(a->pos, b->pos, 3 * a->nv * sizeof(float));
  SAME(a->nrm, b->nrm, 3 * a->nv * sizeof(float));
  SAME(a->uv, b->uv, 2 * a->nv * sizeof(float));
  SAME(a->col, b->col, a->nv * sizeof(uint16_t));
  SAME(a->twosided, b->twosided, a->nv);
  SAME(a->tex, b->tex, a->nv * sizeof(uint16_t));
  SAME(a->tri, b->tri, 3 * a->nt * sizeof(uint32_t));
  SAME(a->lpos, b->lpos, 6 * a->nl * sizeof(float));
  SAME(a->lwidth, b->lwidth, 2 * a->nl * sizeof(float));
  SAME(a->lcol, b->lcol, a->nl * sizeof(uint16_t));
  assert(x->nrec == y->nrec && x->nstiff == y->nstiff);
  {                                   /* as they read: their shapes may be kept otherwise */
    size_t k;
    for (k = 0; k < x->nrec; k++) {
      lsys_trec p, q;
      lsys_scene_record(x, k, &p);
      lsys_scene_record(y, k, &q);
      SAME(&p, &q, sizeof p);
    }
  }
  SAME(x->stiff, y->stiff, 3 * x->nstiff * sizeof(float));
}

static void samestate (const lsys_tstate *a, const lsys_tstate *b) {
  SAME(a->pos, b->pos, sizeof a->pos);
  SAME(a->H, b->H, sizeof a->H);
  SAME(a->U, b->U, sizeof a->U);
  assert(a->width == b->width && a->color == b->color && a->last == b->last);
}

/* Runs 's' on one thread, then in pieces of at least 'minsize' modules on
** 1, 2 and 3 threads; every run gives the first one's scene (or error). */
static int check (lsys_lstring *s, lsys_alphabet *a, lsys_turtle_opts *o, size_t minsize) {
  lsys_scene one, sc;
  lsys_turtle t;
  int st1, th, pieces = 0;
  lsys_scene_init(&one);
  lsys_turtle_init(&t);
  t.o = o; t.scene = &one; t.threads = 1;
  st1 = lsys_turtle_run(&t, s, a);
  for (th = 1; th <= 3; th++) {
    lsys_turtle u;
    int st;
    lsys_scene_init(&sc);
    lsys_turtle_init(&u);
    u.o = o; u.scene = &sc; u.threads = th; u.piecemin = minsize;
    st = lsys_turtle_run(&u, s, a);
    assert(st == st1);
    assert(th == 1 || u.npieces == pieces);
    pieces = u.npieces;
    if (st == LSYS_OK) {
      same(&one, &sc);
      samestate(&t.state, &u.state);
    }
    else {
      assert(u.err.pos == t.err.pos);
      assert(strcmp(u.err.msg, t.err.msg) == 0);
      assert(sc.nrec == 0 && sc.mesh.nl == 0 && sc.mesh.nt == 0);
    }
    lsys_turtle_free(&u);
    lsys_scene_free(&sc);
  }
  assert(t.npieces == 0);
  lsys_turtle_free(&t);
  lsys_scene_free(&one);
  return pieces;
}

static const char *const models[][2] = {
  {"F", "F[+F]F[-F]F"},                                  /* ABOP fig. 1.24a */
  {"F", "F[+F]F[-F][F]"},                                /* a branch ends the string */
  {"!(1)F", "F(0.5)[;+(20)!(0.4)F]F[-F]#F"},              /* widths after F, colours */
  {"F", "F[&F@O(0.3)][^F@c(0.2)]/(137)F[@L]"},           /* discs, spheres, labels */
  {"F", "FZ(1,2,3)[+F][Z(4)-FF]F"},                      /* stiffnesses in records */
  {"F", "F[F][+F]F"},                                    /* branches continue their
                                                           parent's cylinder ring */
  {"F", "F[[+F]-F][[F]F]"},                              /* nested brackets at once */
  {"F", "F@D(0.9)[+F@Di(0.8)]@Dd(1.1)F]"},              /* an unbalanced ']' */
};

static void test_models (void) {
  static const int styles[] = {LSYS_STYLE_LINE, LSYS_STYLE_POLYGON, LSYS_STYLE_CYLINDER};
  lsys_alphabet a;
  lsys_lstring s;
  size_t k;
  int y;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  for (k = 0; k < sizeof models / sizeof models[0]; k++) {
    char *text = expand(models[k][0], models[k][1], 4);
    parse(&s, &a, text);
    free(text);
    for (y = 0; y < 3; y++) {
      lsys_turtle_opts o;
      size_t m;
      lsys_turtle_defaults(&o);
      o.angle = 25.7;
      o.style = styles[y];
      o.sides = 5;
      for (m = 2; m <= 2048; m *= 8) {
        int np = check(&s, &a, &o, m);
        assert(m > 2 ? np >= 1 : np > 20);           /* cut small, or less */
      }
      o.norecords = 1;
      assert(check(&s, &a, &o, 3) > 20);
      o.norecords = 0;
      o.ntrop = 1;                                   /* a tropism bends every segment */
      o.trop[0].vec[1] = -1;
      o.trop[0].elasticity = 0.2;
      assert(check(&s, &a, &o, 5) > 20);
    }
  }
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

/* A narrow string (a derivation step's) is read as it is. */
static void test_narrow (void) {
  lsys_alphabet a;
  lsys_lstring s, w;
  lsys_turtle_opts o;
  char *text = expand("F", "F[+F]F[-F]F", 5);
  size_t k;
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  lsys_lstring_init(&w);
  parse(&w, &a, text);
  free(text);
  assert(lsys_lstring_prepare8(&s, w.n) == LSYS_OK);
  for (k = 0; k < w.n; k++) s.sym8[k] = (uint8_t)LSYS_CSYM(w.code[k]);
  s.n = w.n;
  lsys_turtle_defaults(&o);
  o.angle = 25.7;
  assert(check(&s, &a, &o, 64) > 20);
  {                                               /* and as the wide string is */
    lsys_scene x, y;
    lsys_turtle t;
    lsys_scene_init(&x); lsys_scene_init(&y);
    lsys_turtle_init(&t);
    t.o = &o; t.scene = &x; t.threads = 2; t.piecemin = 100;
    assert(lsys_turtle_run(&t, &s, &a) == LSYS_OK);
    t.scene = &y;
    assert(lsys_turtle_run(&t, &w, &a) == LSYS_OK);
    same(&x, &y);
    assert(x.nrec == 3125 && x.mesh.nl == 3125);
    lsys_turtle_free(&t);
    lsys_scene_free(&x); lsys_scene_free(&y);
  }
  lsys_lstring_free(&s);
  lsys_lstring_free(&w);
  lsys_alphabet_free(&a);
}

/* An error names the module one thread names, also when several pieces fail;
** a polygon keeps the string on one thread (the same scene either way). */
static void test_errors (void) {
  lsys_alphabet a;
  lsys_lstring s;
  lsys_turtle_opts o;
  char *tree = expand("F", "F[+F]F[-F]F", 4), *text = expand(tree, "F(1)", 1);
  size_t k, np = 0;
  free(tree);
  assert(lsys_alphabet_init(&a) == LSYS_OK);
  lsys_lstring_init(&s);
  parse(&s, &a, text);
  free(text);
  lsys_turtle_defaults(&o);
  for (k = 0; k < s.n; k++) {                       /* parameters 300 and 900: not finite */
    if (LSYS_CNP(s.code[k]) > 0 && (np == 300 || np == 900)) s.par[np] = NAN;
    np += LSYS_CNP(s.code[k]);
  }
  assert(check(&s, &a, &o, 16) > 20);
  text = expand("F", "F[+F{.F.F}]F[-F]F", 3);
  parse(&s, &a, text);
  free(text);
  assert(check(&s, &a, &o, 4) == 0);
  lsys_lstring_free(&s);
  lsys_alphabet_free(&a);
}

int main (void) {
  test_models();
  test_narrow();
  test_errors();
  printf("test_turtle_par: ok\n");
  return 0;
}
