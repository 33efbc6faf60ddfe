/*
** The frames and the turtle writer of component graphs (compgeo.h).
*/
#include <math.h>
#include <string.h>

#include "compgeo.h"
#include "vec3.h"

/* {======================================================================
** Frames
** ======================================================================= */

#define RAD (PI / 180.0)
#define DEG (180.0 / PI)

void lsys_compgeo_frames_init (lsys_cframes *a, int64_t seed) {
  a->f = NULL;
  a->n = a->cap = 0;
  a->rng = (uint64_t)seed;
}

void lsys_compgeo_frames_free (lsys_cframes *a) {
  LSYS_FREE(a->f);
  a->f = NULL;
  a->n = a->cap = 0;
}

#define grow lsys_common_grow

/* grow, with the new part zeroed */
static int growz (void **p, size_t *cap, size_t need, size_t size) {
  size_t old = *cap;
  if (grow(p, cap, need, size) != LSYS_OK) return LSYS_ENOMEM;
  if (*cap > old) memset((char *)*p + old * size, 0, (*cap - old) * size);
  return LSYS_OK;
}

int lsys_compgeo_frames_add (lsys_cframes *a, const lsys_cframe *f, size_t *idx) {
  lsys_cframe copy = *f;             /* f may point into the arena, which may move */
  if (grow((void **)&a->f, &a->cap, a->n + 1, sizeof *a->f) != LSYS_OK) return LSYS_ENOMEM;
  a->f[a->n] = copy;
  *idx = a->n++;
  return LSYS_OK;
}

/* splitmix64 (Steele, Lea and Flood 2014): the same sequence on every machine. */
double lsys_compgeo_frames_random (lsys_cframes *a) {
  uint64_t z = (a->rng += 0x9E3779B97F4A7C15u);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
  z = z ^ (z >> 31);
  return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* v rotated by 'deg' degrees about the unit axis k (Rodrigues). */
static void rot (double v[3], const double k[3], double deg) {
  double a = deg * RAD, c = cos(a), s = sin(a), kv[3], kd;
  vcross(kv, k, v);
  kd = vdot(k, v) * (1 - c);
  v[0] = v[0] * c + kv[0] * s + k[0] * kd;
  v[1] = v[1] * c + kv[1] * s + k[1] * kd;
  v[2] = v[2] * c + kv[2] * s + k[2] * kd;
}

/* H and U both turned about k. */
static void rot2 (lsys_cframe *g, const double k[3], double deg) {
  double ax[3];
  vcopy(ax, k);                      /* k may be H or U */
  rot(g->H, ax, deg);
  rot(g->U, ax, deg);
}

/* H made unit, and U unit and normal to it (Gram-Schmidt). Every turn ends with this:
** rounding leaves a frame a little off, and a turn about an axis made from such a frame
** (right, -U) scales the error up, so that along a chain of ~50 rotated instances the
** frames shrank geometrically. A degenerate frame is left as it is. */
static void orthonorm (lsys_cframe *g) {
  double d;
  if (!vnorm(g->H)) return;
  d = vdot(g->U, g->H);
  vlin(g->U, g->U, 1, g->H, -d);
  vnorm(g->U);
}

static void right (const lsys_cframe *f, double R[3]) {      /* R = -L = -(H x U) */
  vcross(R, f->H, f->U);
  R[0] = -R[0]; R[1] = -R[1]; R[2] = -R[2];
}

void lsys_compgeo_frame_topoint (const lsys_cframe *f, double x, double y, double z,
                                 double out[3]) {
  double R[3];
  int i;
  right(f, R);
  for (i = 0; i < 3; i++)
    out[i] = f->p[i] + f->s * (x * R[i] + y * f->H[i] + z * -f->U[i]);
}

void lsys_compgeo_frame_transform (const lsys_cframe *f, const double t[3], const double r[3],
                                   double s, lsys_cframe *g) {
  double p[3], ax[3];
  lsys_compgeo_frame_topoint(f, t[0], t[1], t[2], p);
  if (g != f) *g = *f;
  vcopy(g->p, p);
  if (r[0] != 0) { right(g, ax); rot2(g, ax, r[0]); }
  if (r[1] != 0) rot(g->U, g->H, r[1]);
  if (r[2] != 0) { vset(ax, -g->U[0], -g->U[1], -g->U[2]); rot(g->H, ax, r[2]); }
  orthonorm(g);
  g->s = g->s * s;
}

void lsys_compgeo_frame_tropism (lsys_cframe *g, const double T[3], double e) {
  const double *H = g->H;
  double ax[3], m;
  vcross(ax, H, T);
  m = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  if (m > 1e-12) {
    ax[0] /= m; ax[1] /= m; ax[2] /= m;
    rot2(g, ax, (e * m) * DEG);
    orthonorm(g);
  }
}

void lsys_compgeo_frame_branch (const lsys_cframe *A, const lsys_cframe *B, double t, double roll,
                                double angle, double scale, lsys_cframe *g) {
  const double *H = A->H, *U = A->U;
  double L[3], U1[3], r = roll * RAD, c = cos(r), s = sin(r), a = angle * RAD;
  lsys_cframe out;
  int i;
  vcross(L, H, U);
  for (i = 0; i < 3; i++) U1[i] = U[i] * c + L[i] * s;
  c = cos(a); s = sin(a);
  for (i = 0; i < 3; i++) {
    out.p[i] = A->p[i] + t * (B->p[i] - A->p[i]);
    out.H[i] = H[i] * c + U1[i] * s;
    out.U[i] = U1[i] * c - H[i] * s;
  }
  out.s = A->s * scale;
  out.u = 0;
  orthonorm(&out);
  *g = out;
}

/* The stem (Lintermann and Deussen 1999, section "Tree"): at each of segs
** pieces the frame bends by the curvature, twists (a Horn), turns by the gnarl
** (a random angle about a random axis normal to H), by the tropisms, and away
** from every branch it passes (the deviation), then moves a piece along H. */
int lsys_compgeo_frames_stem (lsys_cframes *a, size_t base, const lsys_cstem *st, size_t *first) {
  lsys_cframe g = a->f[base];
  double step = st->len / st->segs, R0[3];
  int k, t, nextb = 0;
  size_t idx;
  right(&g, R0);
  g.u = 0;
  if (lsys_compgeo_frames_add(a, &g, first) != LSYS_OK) return LSYS_ENOMEM;
  for (k = 1; k <= st->segs; k++) {
    double ax[3], s;
    if (st->curv != 0) { right(&g, ax); rot2(&g, ax, st->curv / st->segs); }
    if (st->twist != 0) rot(g.U, g.H, st->twist / st->segs);
    if (st->gnarl != 0) {
      double an = (lsys_compgeo_frames_random(a) * 2 - 1) * st->gnarl;
      right(&g, ax);
      rot(ax, g.H, lsys_compgeo_frames_random(a) * 360);
      rot2(&g, ax, an);
    }
    for (t = 0; t < st->ntrop; t++) {
      const double *tr = st->trop + 4 * t;
      double T[3];
      if (isnan(tr[0])) {
        int r = st->field(st->ud, t, g.p, g.H, T);
        if (r < 0) return r;
        if (r == 0) continue;
      }
      else vcopy(T, tr);
      lsys_compgeo_frame_tropism(&g, T, tr[3]);
    }
    while (nextb < st->nb && st->bu[nextb] <= (double)k / st->segs) {
      if (st->dev != 0) {
        double dir[3];
        vcopy(dir, R0);
        rot(dir, a->f[base].H, st->broll[nextb]);
        vcross(ax, g.H, dir);
        if (vnorm(ax)) rot2(&g, ax, -st->dev);
      }
      nextb++;
    }
    orthonorm(&g);
    s = step * g.s;
    vlin(g.p, g.p, 1, g.H, s);
    g.u = (double)k / st->segs;
    if (lsys_compgeo_frames_add(a, &g, &idx) != LSYS_OK) return LSYS_ENOMEM;
  }
  return LSYS_OK;
}

/* }====================================================================== */

/* {======================================================================
** The writer
** ======================================================================= */

void lsys_compgeo_writer_init (lsys_cwriter *w, lsys_lstring *s) {
  memset(w, 0, sizeof *w);
  w->s = s;
  vset(w->T.H, 0, 1, 0);
  vset(w->T.U, 0, 0, -1);
}

void lsys_compgeo_writer_free (lsys_cwriter *w) {
  LSYS_FREE(w->owner);
  LSYS_FREE(w->stk);
  LSYS_FREE(w->range);
  w->owner = NULL; w->stk = NULL; w->range = NULL;
  w->capo = w->capstk = w->capi = 0;
}

int lsys_compgeo_writer_op (lsys_cwriter *w, uint32_t sym, const double *p, uint32_t np) {
  size_t n = w->s->n;
  uint32_t k;
  int r;
  for (k = 0; k < np; k++)          /* a move to a frame too far away: sqrt overflowed */
    if (!isfinite(p[k])) return LSYS_ESYNTAX;
  if (grow((void **)&w->owner, &w->capo, n + 1, sizeof *w->owner) != LSYS_OK)
    return LSYS_ENOMEM;
  if ((r = lsys_lstring_push(w->s, sym, p, np)) != LSYS_OK) return r;
  w->owner[n] = w->cur;
  return LSYS_OK;
}

static int op1 (lsys_cwriter *w, uint32_t sym, double x) {
  return lsys_compgeo_writer_op(w, sym, &x, 1);
}

/* A rotation unless it is a no-op. */
static int turn (lsys_cwriter *w, uint32_t sym, double a) {
  return (a > 1e-9 || a < -1e-9) ? op1(w, sym, a) : LSYS_OK;
}

void lsys_compgeo_writer_angles (const double AH[3], const double AU[3], const double BH[3],
                                 const double BU[3], double out[3]) {
  double L[3], h, l, u, sb, a, b, g, ca, sa, cb, s2, bl, bu;
  int i;
  vcross(L, AH, AU);
  h = vdot(BH, AH); l = vdot(BH, L); u = vdot(BH, AU);
  sb = sqrt(l * l + u * u);
  a = sb > 1e-12 ? atan2(l, -u) : 0;
  b = atan2(sb, h);
  if (BU == NULL) {
    /* aiming only: a roll past a quarter turn is the opposite roll and a pitch the other way */
    if (a > 0.5 * PI) { a -= PI; b = -b; }
    else if (a <= -0.5 * PI) { a += PI; b = -b; }
    out[0] = a * DEG; out[1] = b * DEG; out[2] = 0;
    return;
  }
  ca = cos(a); sa = sin(a); cb = cos(b); s2 = sin(b);
  /* L1 = L ca + U sa, U1 = U ca - L sa, U2 = U1 cb + H s2 */
  bl = 0; bu = 0;
  for (i = 0; i < 3; i++) {
    bl += BU[i] * (L[i] * ca + AU[i] * sa);
    bu += BU[i] * ((AU[i] * ca - L[i] * sa) * cb + AH[i] * s2);
  }
  g = atan2(-bl, bu);
  /* (a -+ 180, -b, g -+ 180) turns the same way; take it when it needs fewer
  ** modules (a pure pitch up is then one `^`) or smaller rolls */
  if (fabs(a) > 1e-11) {
    double a2 = a > 0 ? a - PI : a + PI, g2 = g > 0 ? g - PI : g + PI;
    int n1 = (fabs(a) > 1e-11) + (fabs(g) > 1e-11), n2 = (fabs(a2) > 1e-11) + (fabs(g2) > 1e-11);
    if (n2 < n1 || (n2 == n1 && fabs(a2) + fabs(g2) < fabs(a) + fabs(g))) {
      a = a2; b = -b; g = g2;
    }
  }
  out[0] = a * DEG; out[1] = b * DEG; out[2] = g * DEG;
}

int lsys_compgeo_writer_orient (lsys_cwriter *w, const double H[3], const double U[3]) {
  double an[3];
  int r;
  lsys_compgeo_writer_angles(w->T.H, w->T.U, H, U, an);
  if ((r = turn(w, w->sym_roll, an[0])) != LSYS_OK ||
      (r = turn(w, w->sym_pitch, an[1])) != LSYS_OK ||
      (r = turn(w, w->sym_roll, an[2])) != LSYS_OK) return r;
  vcopy(w->T.H, H);
  vcopy(w->T.U, U);
  return LSYS_OK;
}

int lsys_compgeo_writer_forward (lsys_cwriter *w, double d, int draw) {
  int r;
  if (d <= 1e-15) return LSYS_OK;
  if ((r = op1(w, draw ? w->sym_draw : w->sym_move, d)) != LSYS_OK) return r;
  vlin(w->T.p, w->T.p, 1, w->T.H, d);
  return LSYS_OK;
}

/* Moves the turtle to f: aims H at f's position with a roll and a pitch, moves
** there with `f`, then takes f's orientation. */
static int moveto (lsys_cwriter *w, const lsys_cframe *f) {
  lsys_cturtle *T = &w->T;
  double d[3], len, bound;
  int r;
  d[0] = f->p[0] - T->p[0]; d[1] = f->p[1] - T->p[1]; d[2] = f->p[2] - T->p[2];
  len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  bound = fabs(f->p[0]) + fabs(f->p[1]) + fabs(f->p[2]);
  if (len > 1e-12 * (bound > 1 ? bound : 1)) {
    double aim[3], an[3], L[3], U1[3], ca, sa, cb, sb;
    int i;
    vset(aim, d[0] / len, d[1] / len, d[2] / len);
    lsys_compgeo_writer_angles(T->H, T->U, aim, NULL, an);
    if ((r = turn(w, w->sym_roll, an[0])) != LSYS_OK ||
        (r = turn(w, w->sym_pitch, an[1])) != LSYS_OK) return r;
    vcross(L, T->H, T->U);
    ca = cos(an[0] * RAD); sa = sin(an[0] * RAD); cb = cos(an[1] * RAD); sb = sin(an[1] * RAD);
    for (i = 0; i < 3; i++) U1[i] = T->U[i] * ca - L[i] * sa;
    for (i = 0; i < 3; i++) {
      double h = T->H[i] * cb - U1[i] * sb;
      T->U[i] = U1[i] * cb + T->H[i] * sb;
      T->H[i] = h;
    }
    if ((r = op1(w, w->sym_move, len)) != LSYS_OK) return r;
  }
  vcopy(T->p, f->p);
  return lsys_compgeo_writer_orient(w, f->H, f->U);
}

int lsys_compgeo_writer_open (lsys_cwriter *w, int32_t inst, const lsys_cframe *f) {
  size_t m0 = w->s->n + 1;
  lsys_cframe fr = *f;               /* f may point into an arena the caller grows */
  int r;
  if (inst < 1) return LSYS_EARG;
  if (grow((void **)&w->stk, &w->capstk, w->depth + 1, sizeof *w->stk) != LSYS_OK ||
      growz((void **)&w->range, &w->capi, 3 * (size_t)inst, sizeof *w->range) != LSYS_OK)
    return LSYS_ENOMEM;
  if (m0 > INT32_MAX - 64) return LSYS_ELIMIT;
  w->stk[w->depth++] = w->T;
  w->T.m0 = m0;
  w->T.inst = inst;
  w->cur = inst;
  if ((r = lsys_compgeo_writer_op(w, w->sym_open, NULL, 0)) != LSYS_OK ||
      (r = moveto(w, &fr)) != LSYS_OK)
    return r;
  w->range[3 * (inst - 1)] = (int32_t)m0;
  w->range[3 * (inst - 1) + 2] = (int32_t)w->s->n;
  return LSYS_OK;
}

int lsys_compgeo_writer_close (lsys_cwriter *w) {
  int32_t inst = w->T.inst;
  int r;
  if (w->depth == 0 || inst < 1) return LSYS_EARG;
  w->cur = inst;
  if ((r = lsys_compgeo_writer_op(w, w->sym_close, NULL, 0)) != LSYS_OK) return r;
  w->range[3 * (inst - 1) + 1] = (int32_t)w->s->n;
  w->T = w->stk[--w->depth];
  w->cur = w->T.inst;
  return LSYS_OK;
}

/* }====================================================================== */
