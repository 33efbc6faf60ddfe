/*
** C unit tests for the frames and the writer of component graphs
** (compgeo.h): the generator's splitmix64 values computed independently; the
** basic-parameter transform, a Tree's branch frame and stems (straight,
** curved, bent by a tropism and a field, the gnarl's draws) by hand; the
** roll-pitch-roll angles turn any orientation onto any other under the
** turtle's conventions; the writer's modules, owners, ranges and nesting; every
** allocation failure reported and nothing leaked.
*/
#undef NDEBUG
#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "talloc.h"
#include "common.c"
#include "lstring.c"
#include "compgeo.c"

static int near (double a, double b, double tol) { return fabs(a - b) <= tol; }
static int vnear (const double *a, double x, double y, double z, double tol) {
  return near(a[0], x, tol) && near(a[1], y, tol) && near(a[2], z, tol);
}

/* the turtle's first frame at the origin: H = +y, U = -z (R = +x, F = +z) */
static lsys_cframe start (double s) {
  lsys_cframe f = {{0, 0, 0}, {0, 1, 0}, {0, 0, -1}, 1, 0};
  f.s = s;
  return f;
}

static void orthonormal (const lsys_cframe *f) {
  assert(near(vdot(f->H, f->H), 1, 1e-12));
  assert(near(vdot(f->U, f->U), 1, 1e-12));
  assert(near(vdot(f->H, f->U), 0, 1e-12));
}

static void random_values (void) {
  lsys_cframes a;
  int k;
  lsys_compgeo_frames_init(&a, 1);
  /* splitmix64 from state 1, top 53 bits / 2^53 (computed apart, in Python) */
  assert(lsys_compgeo_frames_random(&a) == 0.5665615751722809);
  assert(lsys_compgeo_frames_random(&a) == 0.7457817572627011);
  assert(lsys_compgeo_frames_random(&a) == 0.9710027535867962);
  lsys_compgeo_frames_init(&a, -5);
  for (k = 0; k < 1000; k++) {
    double x = lsys_compgeo_frames_random(&a);
    assert(x >= 0 && x < 1);
  }
}

static void transform (void) {
  lsys_cframe f = start(2), g;
  const double t[3] = {1, 2, 3}, z[3] = {0, 0, 0}, rx[3] = {90, 0, 0}, rz[3] = {0, 0, 90};
  double q[3];
  lsys_compgeo_frame_topoint(&f, 1, 2, 3, q);
  assert(vnear(q, 2, 4, 6, 1e-15));                  /* s (x R + y H + z F) */
  lsys_compgeo_frame_transform(&f, t, z, 0.5, &g);
  assert(vnear(g.p, 2, 4, 6, 1e-15) && g.s == 1);
  assert(vnear(g.H, 0, 1, 0, 0) && vnear(g.U, 0, 0, -1, 0));
  lsys_compgeo_frame_transform(&f, z, rx, 1, &g);           /* about the right axis x: H to +z */
  assert(vnear(g.H, 0, 0, 1, 1e-15) && vnear(g.U, 0, 1, 0, 1e-15));
  lsys_compgeo_frame_transform(&f, z, rz, 1, &g);           /* about the front axis z: H to -x */
  assert(vnear(g.H, -1, 0, 0, 1e-15) && vnear(g.U, 0, 0, -1, 0));
  g = f;
  lsys_compgeo_frame_transform(&g, t, rx, 3, &g);           /* in place */
  assert(vnear(g.p, 2, 4, 6, 1e-15) && g.s == 6 && vnear(g.H, 0, 0, 1, 1e-15));
}

static void branch (void) {
  lsys_cframe A = start(2), B = start(2), g;
  B.p[1] = 1;
  lsys_compgeo_frame_branch(&A, &B, 0.5, 0, 90, 0.25, &g);  /* pitched down 90: H = U */
  assert(vnear(g.p, 0, 0.5, 0, 0) && g.s == 0.5);
  assert(vnear(g.H, 0, 0, -1, 1e-15) && vnear(g.U, 0, -1, 0, 1e-15));
  lsys_compgeo_frame_branch(&A, &B, 0, 90, 90, 1, &g);      /* rolled 90 first: U = L = -x */
  assert(vnear(g.H, -1, 0, 0, 1e-15));
  orthonormal(&g);
}

static int fieldcalls;
static double fieldH[3];                             /* the heading of the first call */
static int field (void *ud, int k, const double p[3], const double H[3], double T[3]) {
  (void)ud; (void)p;
  if (fieldcalls++ == 0) { fieldH[0] = H[0]; fieldH[1] = H[1]; fieldH[2] = H[2]; }
  if (k == 0) return 0;                              /* no direction here */
  T[0] = 0; T[1] = -1; T[2] = 0;
  return 1;
}

static void stems (void) {
  lsys_cframes a, b;
  lsys_cframe f = start(2);
  lsys_cstem st;
  size_t base, first, k;
  double trop[8] = {0, -1, 0, 0.1, NAN, 0, 0, 0.1};
  lsys_compgeo_frames_init(&a, 1);
  assert(lsys_compgeo_frames_add(&a, &f, &base) == LSYS_OK && base == 0);
  memset(&st, 0, sizeof st);
  st.len = 2; st.segs = 4;
  assert(lsys_compgeo_frames_stem(&a, base, &st, &first) == LSYS_OK && first == 1 && a.n == 6);
  for (k = 0; k <= 4; k++) {                         /* straight, 2 x 2 long, u = k / 4 */
    assert(vnear(a.f[first + k].p, 0, (double)k, 0, 1e-15));
    assert(a.f[first + k].u == (double)k / 4);
  }
  st.segs = 10; st.curv = 90;                        /* a quarter turn about the right axis */
  assert(lsys_compgeo_frames_stem(&a, base, &st, &first) == LSYS_OK);
  assert(vnear(a.f[first + 10].H, 0, 0, 1, 1e-12));
  orthonormal(&a.f[first + 10]);
  /* a horizontal stem bends down under gravity, more at each segment */
  f.H[0] = 1; f.H[1] = 0; f.H[2] = 0;
  assert(lsys_compgeo_frames_add(&a, &f, &base) == LSYS_OK);
  st.curv = 0; st.ntrop = 1; st.trop = trop;
  assert(lsys_compgeo_frames_stem(&a, base, &st, &first) == LSYS_OK);
  for (k = 1; k <= 10; k++) assert(a.f[first + k].H[1] < a.f[first + k - 1].H[1]);
  {
    double y = a.f[first + 10].H[1];                 /* the field (k = 1) pulls the same way */
    st.ntrop = 2; st.trop = trop + 0; st.field = field;
    trop[4] = NAN;
    trop[0] = NAN;                                   /* tropism 0 asks the field: none there */
    assert(lsys_compgeo_frames_stem(&a, base, &st, &first) == LSYS_OK);
    assert(fieldcalls == 20);
    assert(vnear(fieldH, 1, 0, 0, 1e-15));           /* the base's heading, before a turn */
    assert(near(a.f[first + 10].H[1], y, 1e-12));
  }
  /* the gnarl draws two numbers a segment, in turn with everyone else */
  memset(&st, 0, sizeof st);
  st.len = 1; st.segs = 3; st.gnarl = 20;
  lsys_compgeo_frames_init(&b, 9);
  assert(lsys_compgeo_frames_add(&b, &f, &base) == LSYS_OK);
  assert(lsys_compgeo_frames_stem(&b, base, &st, &first) == LSYS_OK);
  {
    lsys_cframes c;
    double x = lsys_compgeo_frames_random(&b);
    lsys_compgeo_frames_init(&c, 9);
    for (k = 0; k < 6; k++) lsys_compgeo_frames_random(&c);
    assert(lsys_compgeo_frames_random(&c) == x);
  }
  assert(!vnear(b.f[first + 3].H, 1, 0, 0, 1e-3));  /* it did turn */
  orthonormal(&b.f[first + 3]);
  lsys_compgeo_frames_free(&a);
  lsys_compgeo_frames_free(&b);
}

/* roll a, pitch b (degrees) under the turtle's conventions: `/` U1 = U ca - L sa, then
** `&` H' = H cb - U1 sb, U' = U1 cb + H sb (as the writer assumes and the specs measure) */
static void rollpitch (double H[3], double U[3], double a, double b) {
  double L[3], U1[3], H2[3];
  int i;
  vcross(L, H, U);
  a *= RAD; b *= RAD;
  for (i = 0; i < 3; i++) U1[i] = U[i] * cos(a) - L[i] * sin(a);
  for (i = 0; i < 3; i++) H2[i] = H[i] * cos(b) - U1[i] * sin(b);
  for (i = 0; i < 3; i++) U[i] = U1[i] * cos(b) + H[i] * sin(b);
  vcopy(H, H2);
}

static void randframe (lsys_cframes *g, double H[3], double U[3]) {
  double a[3];
  int i;
  for (i = 0; i < 3; i++) H[i] = lsys_compgeo_frames_random(g) * 2 - 1;
  for (i = 0; i < 3; i++) a[i] = lsys_compgeo_frames_random(g) * 2 - 1;
  vnorm(H);
  vcross(U, H, a);
  vnorm(U);
}

static void angles (void) {
  lsys_cframes g;
  int k;
  lsys_compgeo_frames_init(&g, 3);
  for (k = 0; k < 2000; k++) {
    double AH[3], AU[3], BH[3], BU[3], H[3], U[3], an[3];
    randframe(&g, AH, AU);
    randframe(&g, BH, BU);
    if (k == 0) { vcopy(BH, AH); vcopy(BU, AU); }                 /* nothing to do */
    if (k == 1) { vcopy(BH, AH); vset(BU, -AU[0], -AU[1], -AU[2]); }  /* a half roll */
    if (k == 2) { vset(BH, -AH[0], -AH[1], -AH[2]); vcopy(BU, AU); }  /* straight back */
    lsys_compgeo_writer_angles(AH, AU, BH, BU, an);
    vcopy(H, AH); vcopy(U, AU);
    rollpitch(H, U, an[0], an[1]);
    rollpitch(H, U, an[2], 0);
    assert(vnear(H, BH[0], BH[1], BH[2], 1e-9) && vnear(U, BU[0], BU[1], BU[2], 1e-9));
    if (k == 0) assert(fabs(an[0]) < 1e-9 && fabs(an[1]) < 1e-9 && fabs(an[2]) < 1e-9);
    lsys_compgeo_writer_angles(AH, AU, BH, NULL, an);                   /* aim only */
    assert(an[0] > -90 - 1e-9 && an[0] <= 90 + 1e-9 && an[2] == 0);
    vcopy(H, AH); vcopy(U, AU);
    rollpitch(H, U, an[0], an[1]);
    assert(vnear(H, BH[0], BH[1], BH[2], 1e-9));
  }
}

static void writer (void) {
  lsys_lstring s;
  lsys_cwriter w;
  lsys_cframe f = start(1), g = start(1);
  double p[2] = {2, 3};
  size_t k;
  lsys_lstring_init(&s);
  lsys_compgeo_writer_init(&w, &s);
  w.sym_open = 1; w.sym_close = 2; w.sym_roll = 3; w.sym_pitch = 4; w.sym_move = 5;
  w.sym_draw = 6;
  f.p[1] = 1;                          /* straight ahead: `[ f(1)` and nothing to turn */
  assert(lsys_compgeo_writer_open(&w, 1, &f) == LSYS_OK);
  assert(s.n == 2 && LSYS_CSYM(s.code[1]) == 5 && s.par[0] == 1);
  assert(lsys_compgeo_writer_op(&w, 9, p, 2) == LSYS_OK);
  g.p[0] = 1; g.p[1] = 1;              /* one to the right, facing the same way */
  assert(lsys_compgeo_writer_open(&w, 2, &g) == LSYS_OK);
  assert(vnear(w.T.p, 1, 1, 0, 0) && vnear(w.T.H, 0, 1, 0, 1e-15));
  assert(lsys_compgeo_writer_forward(&w, 0.5, 1) == LSYS_OK);
  assert(lsys_compgeo_writer_forward(&w, 1e-16, 1) == LSYS_OK);     /* nothing */
  assert(lsys_compgeo_writer_close(&w) == LSYS_OK);
  assert(vnear(w.T.p, 0, 1, 0, 0) && w.cur == 1);           /* as before its `[` */
  assert(lsys_compgeo_writer_close(&w) == LSYS_OK);
  assert(w.cur == 0 && w.depth == 0);
  assert(lsys_compgeo_writer_close(&w) == LSYS_EARG);               /* nothing open */
  assert(LSYS_CSYM(s.code[0]) == 1 && LSYS_CSYM(s.code[s.n - 1]) == 2);
  {
    /* [ f(1) X(2,3) [ / & f / & / F ] ]: the second instance's modules are its own */
    int32_t own2 = 0;
    for (k = 0; k < s.n; k++) if (w.owner[k] == 2) own2++;
    assert(w.owner[0] == 1 && w.owner[2] == 1 && w.owner[s.n - 1] == 1);
    assert(own2 == (int32_t)(w.range[4] - w.range[3] + 1));
    assert(w.range[0] == 1 && w.range[1] == (int32_t)s.n && w.range[2] == 2);
    assert(LSYS_CSYM(s.code[w.range[4] - 2]) == 6);          /* F(0.5) before its `]` */
  }
  assert(lsys_compgeo_writer_open(&w, 0, &f) == LSYS_EARG);
  lsys_compgeo_writer_free(&w);
  lsys_lstring_free(&s);
}

/* every allocation of the arena and the writer fails once: an error, nothing leaked */
static void failures (void) {
  long k;
  for (k = 0; k < 12; k++) {
    lsys_cframes a;
    lsys_cstem st;
    lsys_lstring s;
    lsys_cwriter w;
    lsys_cframe f = start(1);
    size_t i, first;
    int r = LSYS_OK, j;
    lsys_lstring_init(&s);
    lsys_compgeo_frames_init(&a, 1);
    lsys_compgeo_writer_init(&w, &s);
    w.sym_open = 1; w.sym_close = 2; w.sym_roll = 3; w.sym_pitch = 4; w.sym_move = 5;
    w.sym_draw = 6;
    memset(&st, 0, sizeof st);
    st.len = 1; st.segs = 200;
    failat = nalloc + k;
    for (j = 0; j < 100 && r == LSYS_OK; j++) r = lsys_compgeo_frames_add(&a, &f, &i);
    if (r == LSYS_OK) r = lsys_compgeo_frames_stem(&a, 0, &st, &first);
    for (j = 1; j <= 300 && r == LSYS_OK; j++) {
      f.p[0] = j;
      r = lsys_compgeo_writer_open(&w, j, &f);
    }
    failat = -1;
    assert(r == LSYS_OK || r == LSYS_ENOMEM);
    lsys_compgeo_frames_free(&a);
    lsys_compgeo_writer_free(&w);
    lsys_lstring_free(&s);
    assert(nlive == 0);
  }
}

int main (void) {
  tfree(tmalloc(8));                   /* the files under test allocate by realloc alone */
  random_values();
  transform();
  branch();
  stems();
  angles();
  writer();
  failures();
  assert(nlive == 0);
  printf("test_compgeo: ok\n");
  return 0;
}
