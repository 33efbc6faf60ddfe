/*
** C unit tests for the limb table of incremental growth (grow.h): cylinder
** vertices where the frames put them; a child's frame from its parent's tip
** and its rotation; the parallel tick (reads see the start of the tick, limbs
** made in it neither run nor age, removals and leaves wait for its end);
** colours interned once; removed limbs' and leaves' ranges reused; a tick
** allocates nothing once the arrays have grown; a chain of 200,000 limbs
** removed without recursion; every allocation failure reported without a
** leak; a leaf shape of the caller's placed, scaled and reused.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "mesh.c"
#include "scene.c"
#include "grow.c"

static int near (double a, double b, double tol) { return fabs(a - b) <= tol; }

static const float GREEN[3] = {0.2f, 0.6f, 0.1f}, BROWN[3] = {0.4f, 0.25f, 0.1f};

/* A limb spec: a child of p (or a root of plant 0), 'angle' about z. */
static lsys_limbspec spec (int32_t p, double angle, double len, double r) {
  lsys_limbspec s;
  memset(&s, 0, sizeof s);
  s.parent = p; s.plant = 0; s.at = 1;
  s.axis[2] = 1; s.angle = angle;
  s.length = len; s.radius = r;
  memcpy(s.rgb, GREEN, sizeof s.rgb);
  return s;
}

static void vertex (const lsys_scene *sc, uint32_t v, double p[3]) {
  int k;
  for (k = 0; k < 3; k++) p[k] = sc->mesh.pos[3 * v + k];
}

static void geometry (void) {
  lsys_scene sc;
  lsys_limbs g;
  const double origin[3] = {1, 0, 2};
  int32_t pl, a, b;
  lsys_limbspec s;
  uint32_t k;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 8);
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK && pl == 0);
  s = spec(-1, 0, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &a) == LSYS_OK && a == 0);
  s = spec(a, 90, 0.5, 0.05);                      /* about z (front): H = +y turns to -x */
  assert(lsys_grow_add(&g, &s, &b) == LSYS_OK && b == 1);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(sc.mesh.nv == 2 * 16 && sc.mesh.nt == 2 * 16);
  for (k = 0; k < 8; k++) {                        /* rings at y = 0 and 1, radius 0.1 */
    double p[3], q[3];
    vertex(&sc, g.v0[a] + k, p);
    vertex(&sc, g.v0[a] + 8 + k, q);
    assert(near(p[1], 0, 1e-7) && near(q[1], 1, 1e-6));
    assert(near(hypot(p[0] - 1, p[2] - 2), 0.1, 1e-6));
  }
  assert(near(g.wp[3 * b + 0], 1, 1e-12) && near(g.wp[3 * b + 1], 1, 1e-12));
  assert(near(g.wm[9 * b + 3], -1, 1e-12) && near(g.wm[9 * b + 4], 0, 1e-12));
  {
    double tip[3];
    lsys_grow_tip(&g, b, tip);
    assert(near(tip[0], 0.5, 1e-12) && near(tip[1], 1, 1e-12) && near(tip[2], 2, 1e-12));
  }
  assert(g.level[a] == 1 && g.level[b] == 2 && g.first[a] == b && g.parent[b] == a);
  /* one colour, one palette entry */
  assert(sc.npal == 1 && g.col[a] == g.col[b]);
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

static void ticks (void) {
  lsys_scene sc;
  lsys_limbs g;
  const double origin[3] = {0, 0, 0};
  int32_t pl, a, b, c;
  lsys_limbspec s;
  size_t nv;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 6);
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
  s = spec(-1, 0, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &a) == LSYS_OK);
  s = spec(a, 30, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &b) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(lsys_grow_begin(&g) == LSYS_OK);
  assert(lsys_grow_begin(&g) == LSYS_EBUSY);
  assert(lsys_grow_set_length(&g, a, 2) == LSYS_OK);
  assert(g.len[a] == 1 && g.nlen[a] == 2);         /* the tick still reads the old state */
  assert(lsys_grow_set_color(&g, b, BROWN) == LSYS_OK);
  s = spec(b, -20, 0.5, 0.05);
  assert(lsys_grow_add(&g, &s, &c) == LSYS_OK);   /* exists now, first runs next tick */
  assert(lsys_grow_add_leaves(&g, b, 3, 0.2, GREEN) == LSYS_OK);
  assert(g.nleaves[b] == 0);
  assert(lsys_grow_end(&g) == LSYS_OK);
  assert(lsys_grow_end(&g) == LSYS_EBUSY);
  assert(g.len[a] == 2 && g.age[a] == 1 && g.age[b] == 1 && g.age[c] == 0);
  assert(g.nleaves[b] == 3);
  assert(near(g.wp[3 * b + 1], 2, 1e-12));         /* the child moved with its parent's tip */
  assert(sc.npal == 2 && g.col[b] != g.col[a]);
  {
    double p[3];                                   /* its cylinder was rewritten there */
    vertex(&sc, g.v0[b], p);
    assert(near(p[1], 2, 0.11));
  }
  /* removing b takes c and the leaves; the next limb and leaves reuse their ranges */
  nv = sc.mesh.nv;
  assert(lsys_grow_remove(&g, b) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(!lsys_grow_alive(&g, b) && !lsys_grow_alive(&g, c) && g.nalive == 1);
  assert(g.first[a] == -1 && g.pcount[0] == 1);
  {
    double p[3], q[3];                             /* degenerate: all on its first vertex */
    uint32_t k;
    vertex(&sc, g.lf_v0[g.nl - 1], p);
    for (k = 1; k < 4; k++) {
      vertex(&sc, g.lf_v0[g.nl - 1] + k, q);
      assert(p[0] == q[0] && p[1] == q[1] && p[2] == q[2]);
    }
  }
  s = spec(a, 10, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &b) == LSYS_OK && b == 3);    /* ids are not reused */
  assert(lsys_grow_add_leaves(&g, b, 3, 0.2, GREEN) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(sc.mesh.nv == nv);                        /* ... but their vertices are */
  assert(lsys_grow_set_length(&g, b, -1) == LSYS_EARG);
  assert(lsys_grow_set_radius(&g, b, NAN) == LSYS_EARG);
  assert(lsys_grow_set_length(&g, c, 1) == LSYS_EARG);      /* dead */
  assert(lsys_grow_set_length(&g, 99, 1) == LSYS_EARG);
  s = spec(c, 10, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &b) == LSYS_EARG);            /* a dead parent */
  s = spec(a, 10, 1, 0.1);
  s.axis[0] = s.axis[1] = s.axis[2] = 0;
  assert(lsys_grow_add(&g, &s, &b) == LSYS_EARG);            /* no axis */
  s = spec(-1, 0, 1, 0.1);
  s.plant = 7;
  assert(lsys_grow_add(&g, &s, &b) == LSYS_EARG);            /* no such plant */
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

/* Once the arrays have grown, a tick that changes every limb allocates nothing. */
static void noalloc (void) {
  lsys_scene sc;
  lsys_limbs g;
  const double origin[3] = {0, 0, 0};
  int32_t pl, id, k;
  long before;
  lsys_limbspec s;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 8);
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
  s = spec(-1, 0, 1, 0.1);
  assert(lsys_grow_add(&g, &s, &id) == LSYS_OK);
  for (k = 1; k < 4000; k++) {
    s = spec((k - 1) / 2, k % 2 ? 25 : -25, 0.5, 0.02);
    assert(lsys_grow_add(&g, &s, &id) == LSYS_OK);
  }
  assert(lsys_grow_update(&g) == LSYS_OK);
  for (k = 0; k < 3; k++) {
    int32_t i;
    if (k == 2) before = nalloc;
    assert(lsys_grow_begin(&g) == LSYS_OK);
    for (i = 0; i < 4000; i++) {
      float c[3] = {0.2f + 0.01f * (float)k, 0.5f, 0.1f};
      assert(lsys_grow_set_length(&g, i, g.len[i] * 1.1) == LSYS_OK);
      assert(lsys_grow_set_radius(&g, i, g.rad[i] * 1.05) == LSYS_OK);
      assert(lsys_grow_set_color(&g, i, c) == LSYS_OK);
    }
    assert(lsys_grow_end(&g) == LSYS_OK);
  }
  assert(nalloc == before);
  assert(sc.ndirty == 1 && sc.dirty[0] == 0 && sc.dirty[1] == sc.mesh.nv);
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

/* A chain of 200,000 limbs: its removal walks it without recursion. */
static void chain (void) {
  lsys_scene sc;
  lsys_limbs g;
  const double origin[3] = {0, 0, 0};
  int32_t pl, id = -1, k;
  lsys_limbspec s;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 3);
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
  for (k = 0; k < 200000; k++) {
    s = spec(id, 1, 0.01, 0.001);
    assert(lsys_grow_add(&g, &s, &id) == LSYS_OK);
  }
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(g.level[id] == 65535);                    /* levels saturate */
  assert(lsys_grow_remove(&g, 0) == LSYS_OK && lsys_grow_update(&g) == LSYS_OK);
  assert(g.nalive == 0 && g.nfreelimb == 200000);
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

static void failures (void) {
  long k;
  for (k = 0; k < 40; k++) {
    lsys_scene sc;
    lsys_limbs g;
    const double origin[3] = {0, 0, 0};
    int32_t pl, id = -1, j;
    int r;
    lsys_limbspec s;
    lsys_scene_init(&sc);
    lsys_grow_init(&g, &sc, 5);
    failat = nalloc + k;
    r = lsys_grow_plant(&g, origin, &pl);
    for (j = 0; j < 150 && r == LSYS_OK; j++) {
      s = spec(j == 0 ? -1 : (j - 1) / 2, 20, 1, 0.1);
      s.rgb[0] = (float)j / 150;
      r = lsys_grow_add(&g, &s, &id);
      if (r == LSYS_OK && j % 3 == 0) r = lsys_grow_add_leaves(&g, id, 2, 0.1, GREEN);
    }
    if (r == LSYS_OK) r = lsys_grow_update(&g);
    if (r == LSYS_OK) r = lsys_grow_remove(&g, 1);
    if (r == LSYS_OK) r = lsys_grow_update(&g);
    failat = -1;
    assert(r == LSYS_OK || r == LSYS_ENOMEM);
    lsys_grow_free(&g);
    lsys_scene_free(&sc);
    assert(nlive == 0);
  }
}

/* A failed update keeps what it did not do: the retry makes exactly the leaves asked. */
static void retry (void) {
  long k;
  for (k = 0; k < 12; k++) {
    lsys_scene sc;
    lsys_limbs g;
    const double origin[3] = {0, 0, 0};
    int32_t pl, a;
    lsys_limbspec s = spec(-1, 0, 1, 0.1);
    lsys_scene_init(&sc);
    lsys_grow_init(&g, &sc, 4);
    assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
    assert(lsys_grow_add(&g, &s, &a) == LSYS_OK);
    assert(lsys_grow_update(&g) == LSYS_OK);
    assert(lsys_grow_add_leaves(&g, a, 70, 0.1, BROWN) == LSYS_OK);
    failat = nalloc + k;
    (void)lsys_grow_update(&g);
    failat = -1;
    assert(lsys_grow_update(&g) == LSYS_OK);
    assert(g.nleaves[a] == 70 && g.npend == 0);
    lsys_grow_free(&g);
    lsys_scene_free(&sc);
    assert(nlive == 0);
  }
}

/* A tick of a world without plants or limbs (the plants' counts were
** copied from a NULL array, which UBSan reports). */
static void empty (void) {
  lsys_scene sc;
  lsys_limbs g;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 8);
  assert(lsys_grow_begin(&g) == LSYS_OK);
  assert(lsys_grow_end(&g) == LSYS_OK);
  assert(g.n == 0 && sc.mesh.nv == 0);
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

/* The budget: every growth within max_memory, the caller's
** bytes per limb and plant counted, the settings kept by free; and a limb of
** many children, appended and unlinked in order (no walk along siblings). */
static void budget (void) {
  lsys_scene sc;
  lsys_limbs g;
  const double origin[3] = {0, 0, 0};
  int32_t pl, id, k, n = 0;
  lsys_limbspec s = spec(-1, 0, 1, 0.1);
  int r = LSYS_OK;
  size_t before;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 8);
  g.max_memory = 1 << 20;
  g.held_limb = 100;
  g.held_plant = 1000;
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
  assert(lsys_grow_add(&g, &s, &id) == LSYS_OK && id == 0);
  before = lsys_grow_bytes(&g);
  assert(lsys_grow_update(&g) == LSYS_OK && lsys_grow_bytes(&g) > before);   /* the mesh */
  while (r == LSYS_OK) {                  /* children of the root until the budget ends */
    s = spec(0, 10, 0.5, 0.05);
    if ((r = lsys_grow_add(&g, &s, &id)) == LSYS_OK) n++;
    if (r == LSYS_OK && n % 64 == 0) r = lsys_grow_update(&g);
  }
  assert(r == LSYS_EMEMORY && n > 100);
  assert(lsys_grow_bytes(&g) <= g.max_memory);
  assert(g.n == (size_t)n + 1 && g.first[0] == 1 && g.last[0] == n);
  for (k = 1, id = g.first[0]; id >= 0; id = g.next[id], k++) assert(id == k);   /* in order */
  assert(lsys_grow_remove(&g, 5) == LSYS_EMEMORY);   /* even the deferred ops count */
  g.max_memory = 0;                       /* the process's budget: the rest goes through */
  assert(lsys_grow_remove(&g, 5) == LSYS_OK && lsys_grow_remove(&g, n) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(g.last[0] == n - 1 && g.next[4] == 6 && g.prev[6] == 4);
  for (k = 0, id = g.first[0]; id >= 0; id = g.next[id]) k++;
  assert(k == n - 2);
  g.max_memory = lsys_grow_bytes(&g);    /* a plant that does not fit, then one that does */
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_EMEMORY);
  g.max_memory += 2000;
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK && pl == 1);
  lsys_grow_free(&g);
  assert(g.max_memory > 0 && g.held_limb == 100 && g.held_plant == 1000 && g.n == 0);
  lsys_scene_free(&sc);
}

/* A leaf shape: a pentagon 'roof' of 5 vertices and 3 triangles, one
** vertex off the leaf's plane (z). */
static void pentagon (lsys_mesh *m) {
  static const float P[15] = {0, 0, 0, 0.4f, 0.5f, 0, 0.2f, 1, 0.1f, -0.2f, 1, 0, -0.4f, 0.5f, 0};
  const double up[3] = {0, 0, 1};
  uint32_t k;
  lsys_mesh_init(m);
  assert(lsys_mesh_reserve(m, 5, 3) == LSYS_OK);
  for (k = 0; k < 5; k++) {
    const double p[3] = {P[3 * k], P[3 * k + 1], P[3 * k + 2]};
    lsys_mesh_vertex(m, p, up, k, 0, 0, 0);
  }
  for (k = 0; k < 3; k++) lsys_mesh_tri(m, 0, k + 1, k + 2);
}

static double vdist (const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1])
              + (a[2] - b[2]) * (a[2] - b[2]));
}

static void leafshape (void) {
  lsys_scene sc;
  lsys_limbs g;
  lsys_mesh m;
  const double origin[3] = {0, 0, 0};
  int32_t pl, a;
  lsys_limbspec s = spec(-1, 0, 1, 0.1);
  uint32_t k, v0, nv;
  long f;
  lsys_scene_init(&sc);
  lsys_grow_init(&g, &sc, 8);
  pentagon(&m);
  /* bad shapes are refused and leave the quad */
  m.tri[4] = 5;
  assert(lsys_grow_set_leaf(&g, &m) == LSYS_EARG);
  m.tri[4] = 2;
  m.pos[7] = NAN;
  assert(lsys_grow_set_leaf(&g, &m) == LSYS_EARG);
  m.pos[7] = 1;
  m.nt = 0;
  assert(lsys_grow_set_leaf(&g, &m) == LSYS_EARG && g.sh_nv == 4);
  m.nt = 3;
  for (f = 0; f < 3; f++) {                        /* out of memory: nothing changes */
    failat = nalloc + f;
    if (lsys_grow_set_leaf(&g, &m) == LSYS_OK) break;
    assert(g.sh_nv == 4 && g.sh_mem == NULL);
  }
  failat = -1;
  assert(g.sh_nv == 5 && g.sh_nt == 3);
  assert(lsys_grow_set_leaf(&g, NULL) == LSYS_OK && g.sh_nv == 4);   /* the quad again */
  assert(lsys_grow_set_leaf(&g, &m) == LSYS_OK && g.sh_nv == 5);
  m.pos[0] = 9;                                    /* the shape was copied */
  assert(lsys_grow_plant(&g, origin, &pl) == LSYS_OK);
  assert(lsys_grow_add(&g, &s, &a) == LSYS_OK);
  assert(lsys_grow_add_leaves(&g, a, 2, 0.5, GREEN) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK);
  assert(sc.mesh.nv == 16 + 2 * 5 && sc.mesh.nt == 16 + 2 * 3);
  assert(lsys_grow_set_leaf(&g, NULL) == LSYS_EBUSY);          /* leaves exist */
  for (k = 0; k < 2; k++) {
    double tip[3] = {0, 1, 0}, p[5][3], e1[3], e3[3], nrm[3];
    uint32_t j, t0 = g.lf_t0[k];
    v0 = g.lf_v0[k];
    for (j = 0; j < 5; j++) vertex(&sc, v0 + j, p[j]);
    assert(near(p[0][0], 0, 1e-7) && near(p[0][1], 1, 1e-7) && near(p[0][2], 0, 1e-7));
    /* sizes scale the shape: |P - tip| = 0.5 |shape point| */
    assert(near(vdist(p[1], tip), 0.5 * sqrt(0.16 + 0.25), 1e-6));
    assert(near(vdist(p[2], tip), 0.5 * sqrt(0.04 + 1 + 0.01), 1e-6));
    /* the leaf's y (the midpoint of vertices 2 and 3 minus z) is 50 degrees off +y */
    vlin(e1, p[1], 0.5, p[4], 0.5);
    vlin(e1, e1, 1, tip, -1);
    assert(near(acos(e1[1] / vlen(e1)) * 180 / PI, LEAF_TILT, 1e-4));
    /* z is the normal: vertex 3 lies in the leaf's plane, vertex 2 0.05 off it */
    vlin(e1, p[1], 1, tip, -1);
    vlin(e3, p[3], 1, tip, -1);
    vcross(nrm, e1, e3);
    vnorm(nrm);
    for (j = 0; j < 3; j++) assert(near(sc.mesh.nrm[3 * (v0 + 2) + j], nrm[j], 1e-5));
    vlin(e1, p[2], 1, tip, -1);
    assert(near(vdot(e1, nrm), 0.05, 1e-6));
    for (j = 0; j < 5; j++)
      assert(sc.mesh.uv[2 * (v0 + j)] == (float)j && sc.mesh.twosided[v0 + j]);
    for (j = 0; j < 3; j++) {                      /* the shape's triangles, in its range */
      const uint32_t *t = sc.mesh.tri + 3 * (t0 + j);
      assert(t[0] == v0 && t[1] == v0 + j + 1 && t[2] == v0 + j + 2);
    }
  }
  /* dropped leaves collapse all 5 vertices; new ones take their ranges */
  nv = (uint32_t)sc.mesh.nv;
  v0 = g.lf_v0[0];
  assert(lsys_grow_begin(&g) == LSYS_OK && lsys_grow_drop_leaves(&g, a) == LSYS_OK);
  assert(lsys_grow_end(&g) == LSYS_OK);
  for (k = 1; k < 5; k++) assert(!memcmp(sc.mesh.pos + 3 * v0, sc.mesh.pos + 3 * (v0 + k), 12));
  assert(lsys_grow_add_leaves(&g, a, 2, 0.5, GREEN) == LSYS_OK);
  assert(lsys_grow_update(&g) == LSYS_OK && sc.mesh.nv == nv && g.nleaves[a] == 2);
  lsys_mesh_free(&m);
  lsys_grow_free(&g);
  lsys_scene_free(&sc);
}

int main (void) {
  empty();
  budget();
  geometry();
  leafshape();
  ticks();
  noalloc();
  chain();
  failures();
  retry();
  assert(nlive == 0);
  printf("test_grow: ok\n");
  return 0;
}
