/*
** C unit tests of the branch-path IK (ik.h; Power et al. 1999): the
** analytic gradient of objective (1) against central differences on random
** chains, chains set up from drawn frames, convergence of a planar chain to
** a reachable target, and the qualitative results of figures 3 and 4 as
** numbers.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ik.h"

#define PI 3.14159265358979323846

static unsigned long seed = 12345;

static double rnd (void) {          /* uniform in [0, 1), a fixed LCG */
  seed = seed * 6364136223846793005ul + 1442695040888963407ul;
  return (double)((seed >> 11) & ((1ul << 53) - 1)) / (double)(1ul << 53);
}

static double urand (double lo, double hi) { return lo + (hi - lo) * rnd(); }

static void identity (double M[9]) {
  memset(M, 0, 9 * sizeof *M);
  M[0] = M[4] = M[8] = 1;
}

/* A random rotation: a random frame from two random vectors. */
static void randrot (double M[9]) {
  double h[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)};
  double u[3] = {urand(-1, 1), urand(-1, 1), urand(-1, 1)};
  lsys_ik_frame(M, h, u);
}

static void randchain (lsys_ikchain *c, lsys_ikjoint *j, int n) {
  int i, k;
  c->n = n;
  c->j = j;
  randrot(c->base);
  for (k = 0; k < 3; k++) c->root[k] = urand(-2, 2);
  for (i = 0; i < n; i++) {
    randrot(j[i].pre);
    for (k = 0; k < 3; k++) {
      j[i].off[k] = rnd() < 0.3 ? urand(-0.5, 0.5) : 0;
      j[i].alpha[k] = urand(-1, 1);
      j[i].rest[k] = urand(-0.3, 0.3);
      j[i].stiff[k] = urand(0.1, 3);
    }
    j[i].len = urand(0.2, 2);
    j[i].free = 7;
  }
}

static void randgoal (lsys_ikgoal *G) {
  int k;
  for (k = 0; k < 3; k++) {
    G->p[k] = urand(-3, 3);
    G->s[k] = urand(-1, 1);
    G->t[k] = urand(-1, 1);
  }
  G->wp = urand(0.5, 2);
  G->wt = urand(0.5, 2);
  G->we = urand(0.01, 1);
  G->ws = urand(0.01, 1);
}

static void test_gradient (void) {
  lsys_ikjoint j[12];
  lsys_ikchain c;
  lsys_ikgoal G;
  double a[36], g[36], worst = 0;
  int trial, i, n;
  for (trial = 0; trial < 20; trial++) {
    n = 1 + trial % 12;
    randchain(&c, j, n);
    randgoal(&G);
    for (i = 0; i < 3 * n; i++) a[i] = urand(-PI, PI);
    if (trial % 4 == 3) j[n / 2].free = 5;           /* a fixed U axis: zero gradient */
    lsys_ik_objective(&c, &G, a, g, NULL);
    for (i = 0; i < 3 * n; i++) {
      double h = 1e-6, x = a[i], fp, fm, num, err;
      a[i] = x + h; fp = lsys_ik_objective(&c, &G, a, NULL, NULL);
      a[i] = x - h; fm = lsys_ik_objective(&c, &G, a, NULL, NULL);
      a[i] = x;
      num = (fp - fm) / (2 * h);
      if (!(j[i / 3].free & (1u << (i % 3)))) {
        assert(g[i] == 0);
        continue;
      }
      err = fabs(num - g[i]) / fmax(1, fabs(num));
      if (err > worst) worst = err;
      assert(err < 1e-6);
    }
  }
  printf("gradient: ok (largest relative error %.1e)\n", worst);
}

/* A chain set up from the frames it draws reproduces them. */
static void test_setjoint (void) {
  lsys_ikjoint j[6], j2[6];
  lsys_ikchain c, c2;
  double frames[54], pts[36], p[3], s[3], t[3], p2[3], s2[3], t2[3];
  int i, k;
  randchain(&c, j, 6);
  lsys_ik_forward(&c, NULL, p, s, t, frames, pts);
  c2 = c;
  c2.j = j2;
  for (i = 0; i < 6; i++) {
    const double *prev = i == 0 ? c.base : frames + 9 * (i - 1);
    const double *prevend = i == 0 ? c.root : pts + 6 * (i - 1) + 3;
    memset(&j2[i], 0, sizeof j2[i]);
    for (k = 0; k < 3; k++) j2[i].alpha[k] = j[i].alpha[k];
    lsys_ik_setjoint(&j2[i], prev, prevend, frames + 9 * i, pts + 6 * i, pts + 6 * i + 3);
    assert(fabs(j2[i].len - j[i].len) < 1e-12);
    for (k = 0; k < 9; k++) assert(fabs(j2[i].pre[k] - j[i].pre[k]) < 1e-9);
    for (k = 0; k < 3; k++) assert(fabs(j2[i].off[k] - j[i].off[k]) < 1e-12);
  }
  lsys_ik_forward(&c2, NULL, p2, s2, t2, NULL, NULL);
  for (k = 0; k < 3; k++) {
    assert(fabs(p[k] - p2[k]) < 1e-9);
    assert(fabs(s[k] - s2[k]) < 1e-9 && fabs(t[k] - t2[k]) < 1e-9);
  }
  printf("setjoint: ok\n");
}

/*
** A straight planar chain of n unit segments up +y (H = +y, U = +z), only
** the U axes free: it bends in the xy plane. Stiffness per joint from 'st'.
*/
static void planar (lsys_ikchain *c, lsys_ikjoint *j, int n, const double *st) {
  double H[3] = {0, 1, 0}, U[3] = {0, 0, 1};
  int i;
  c->n = n;
  c->j = j;
  lsys_ik_frame(c->base, H, U);
  memset(c->root, 0, sizeof c->root);
  for (i = 0; i < n; i++) {
    memset(&j[i], 0, sizeof j[i]);
    identity(j[i].pre);
    j[i].len = 1;
    j[i].stiff[0] = j[i].stiff[2] = 1;
    j[i].stiff[1] = st ? st[i] : 1;
    j[i].free = 2;
  }
}

static void test_reach (void) {
  lsys_ikjoint j[5];
  lsys_ikchain c;
  lsys_ikgoal G;
  lsys_ik_result r;
  lsys_error e;
  double p[3], pts[30];
  int i;
  planar(&c, j, 5, NULL);
  memset(&G, 0, sizeof G);
  G.p[0] = 2; G.p[1] = 3;            /* |p^| = 3.6 < 5: reachable */
  G.wp = 1;
  G.we = 1e-5;
  assert(lsys_ik_solve(&c, &G, NULL, NULL, &r, &e) == LSYS_OK);
  lsys_ik_forward(&c, NULL, p, NULL, NULL, NULL, pts);
  assert(r.dist < 1e-3);
  assert(fabs(p[0] - 2) < 1e-3 && fabs(p[1] - 3) < 1e-3);
  for (i = 0; i < 5; i++) {
    assert(fabs(pts[6 * i + 2]) < 1e-12 && fabs(pts[6 * i + 5]) < 1e-12);   /* planar */
    assert(j[i].alpha[0] == 0 && j[i].alpha[2] == 0);                        /* fixed axes */
  }
  printf("reach: ok (%d iterations, %d evaluations, |p - p^| = %.1e)\n", r.cg.iterations,
         r.cg.evaluations, r.dist);
}

/* Where along the chain the bend is: sum of i |delta_i| / sum |delta_i| (joints from 0). */
static double bendcentre (const lsys_ikjoint *j, int n) {
  double num = 0, den = 0;
  int i;
  for (i = 0; i < n; i++) {
    num += i * fabs(j[i].alpha[1]);
    den += fabs(j[i].alpha[1]);
  }
  return num / den;
}

/* Figure 3: 11 segments pulled sideways; where the bend concentrates
** depends on how the stiffness varies along the branch. */
static void test_figure3 (void) {
  lsys_ikjoint j[11];
  lsys_ikchain c;
  lsys_ikgoal G;
  lsys_ik_result r;
  lsys_error e;
  double inc[11], dec[11], centre[3];
  int i, kind;
  for (i = 0; i < 11; i++) {
    inc[i] = 1 + i;              /* stiffer towards the tip */
    dec[i] = 11 - i;             /* more flexible towards the tip */
  }
  for (kind = 0; kind < 3; kind++) {
    planar(&c, j, 11, kind == 0 ? NULL : kind == 1 ? inc : dec);
    memset(&G, 0, sizeof G);
    G.p[0] = 5; G.p[1] = 9;
    G.wp = 10;
    G.we = 1;
    assert(lsys_ik_solve(&c, &G, NULL, NULL, &r, &e) == LSYS_OK);
    assert(r.dist < 0.5);
    centre[kind] = bendcentre(j, 11);
    for (i = 1; i < 11; i++) assert(j[i].alpha[1] < 0);   /* bent to the right (-x is left) */
  }
  /* stiffer tips push the bend down towards the base, softer tips up */
  assert(centre[1] < centre[0] - 0.5);
  assert(centre[2] > centre[0] + 0.5);
  printf("figure 3: ok (bend centre: constant %.2f, increasing %.2f, decreasing %.2f)\n",
         centre[0], centre[1], centre[2]);
}

static double roughness (const lsys_ikjoint *j, int n) {
  double r = 0;
  int i;
  for (i = 0; i + 1 < n; i++) r += pow(j[i + 1].alpha[1] - j[i].alpha[1], 2);
  return r;
}

/* Figure 4: one manipulation with no stiffness, with smoothness, with stiffness. */
static void test_figure4 (void) {
  lsys_ikjoint j[8];
  lsys_ikchain c;
  lsys_ikgoal G;
  lsys_ik_result r;
  lsys_error e;
  double st[8] = {50, 50, 50, 50, 0.5, 50, 50, 50}, rough[2], share;
  int i;
  for (i = 0; i < 3; i++) {
    planar(&c, j, 8, i == 2 ? st : NULL);
    /* a start that is not straight, so the unconstrained solve keeps an uneven bend */
    j[1].alpha[1] = 0.4;
    j[5].alpha[1] = -0.3;
    memset(&G, 0, sizeof G);
    G.p[0] = 3; G.p[1] = 7;
    G.wp = 10;
    G.ws = i == 1 ? 1 : 0;
    G.we = i == 2 ? 1 : 0;
    assert(lsys_ik_solve(&c, &G, NULL, NULL, &r, &e) == LSYS_OK);
    assert(r.dist < (i == 2 ? 0.1 : 1e-2));     /* stiff joints give a little */
    if (i < 2) rough[i] = roughness(j, 8);
  }
  /* with smoothness the bend is spread evenly */
  assert(rough[1] < 0.2 * rough[0]);
  /* with stiffness the flexible joint (4) takes most of the bend */
  share = fabs(j[4].alpha[1]);
  for (i = 0; i < 8; i++) if (i != 4) assert(fabs(j[i].alpha[1]) < 0.2 * share);
  printf("figure 4: ok (roughness: none %.3f, smooth %.4f; flexible joint %.2f rad)\n",
         rough[0], rough[1], share);
}

int main (void) {
  test_gradient();
  test_setjoint();
  test_reach();
  test_figure3();
  test_figure4();
  return 0;
}
