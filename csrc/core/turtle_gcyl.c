/*
** The turtle's generalized cylinders (cpfg guide §3): @Gs, @Gc and @Ge place
** control points; each @Gc or @Ge draws the strips from the active point
** (gcyl.h does the sweep), a branch continuing from the point that was
** active where it began (§3.4). @Gt and @Gr set the shape of the next
** segments (§3.2.1-2). See turtle_impl.h.
*/
#include <string.h>

#include "turtle_impl.h"
#include "polygon.h"

#define MAXSTRIPS 10000

/* The contour 'id' sampled with this run's sides, computed on first use. */
static const lsys_csample *csample (run *R, int id) {
  lsys_turtle *t = R->t;
  lsys_csample *c;
  int p = R->st.sides, k;
  size_t need = 3 * ((size_t)p + 1);
  if ((size_t)id >= t->ncs) {
    size_t old = t->ncs, cap = t->ncs;
    if (lsys_common_grow((void **)&t->cs, &cap, (size_t)id + 1, sizeof *t->cs) != LSYS_OK)
      return NULL;
    memset(t->cs + old, 0, (cap - old) * sizeof *t->cs);
    t->ncs = cap;
  }
  c = &t->cs[id];
  if (c->valid && c->sides == p) return c;
  if (c->vcap < need) {
    double *v = (double *)LSYS_REALLOC(c->v, need * sizeof(double));
    double *n = v ? (double *)LSYS_REALLOC(c->n, need * sizeof(double)) : NULL;
    if (v) c->v = v;
    if (n == NULL) return NULL;
    c->n = n;
    c->vcap = need;
  }
  if (id == 0) { lsys_contour_circle(p, c->v, c->n); c->closed = 1; }
  else {
    const lsys_contour *ct = R->o->contours[id];
    if (lsys_contour_sample(ct, p, c->v, c->n) != LSYS_OK) return NULL;
    c->closed = ct->closed;
  }
  {   /* which side of the direction of travel the normals are on */
    double side = 0;
    for (k = 0; k < p; k++) {
      const double *a = c->v + 3 * k, *b = a + 3, *nn = c->n + 3 * k;
      side += -(b[1] - a[1]) * nn[0] + (b[0] - a[0]) * nn[1];
    }
    c->left = side > 0;
  }
  c->ncap = 0;
  if (c->closed) {          /* the cap: the contour's xy polygon, ear-clipped */
    const uint32_t *tri;
    double nrm[3];
    long nt;
    if (lsys_turtle_polywork(t) == NULL) return NULL;
    nt = lsys_polygon_triangulate(t->pw, c->v, (size_t)p, nrm, &tri);
    if (nt < 0) return NULL;
    if (lsys_common_grow((void **)&c->cap, &c->capcap, 3 * (size_t)(nt + 1),
                         sizeof(uint32_t)) != LSYS_OK)
      return NULL;
    for (k = 0; k < nt; k++) {
      const uint32_t *q = tri + 3 * k;
      const double *a = c->v + 3 * q[0], *b = c->v + 3 * q[1], *d = c->v + 3 * q[2];
      double z = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
      c->cap[3 * k] = q[0];
      c->cap[3 * k + 1] = z >= 0 ? q[1] : q[2];
      c->cap[3 * k + 2] = z >= 0 ? q[2] : q[1];
    }
    c->ncap = (int)nt;
  }
  c->valid = 1;
  c->sides = p;
  return c;
}

static void gccontour (lsys_gccontour *g, const lsys_csample *c) {
  g->v = c->v; g->n = c->n;
  g->left = c->left; g->closed = c->closed;
  g->cap = c->ncap > 0 ? c->cap : NULL;
  g->ncap = c->ncap;
}

/* A new control point from the turtle's state; returns its index. */
static int gcpoint (run *R, uint32_t *idx) {
  lsys_turtle *t = R->t;
  lsys_tstate *st = &R->st;
  lsys_gcpoint *g;
  if (t->ngcp >= UINT32_MAX - 1)
    return lsys_turtle_fail(R, LSYS_ELIMIT, "too many control points");
  if (t->ngcp == t->gcpcap &&
      lsys_common_grow((void **)&t->gcp, &t->gcpcap, t->ngcp + 1, sizeof *t->gcp) != LSYS_OK)
    return lsys_turtle_nomem(R);
  g = &t->gcp[t->ngcp];
  vcopy(g->pos, st->pos); vcopy(g->H, st->H); vcopy(g->U, st->U); vcopy(g->V, st->U);
  g->r = st->width * st->scale / 2;
  g->v = 0;
  g->contour = st->contour; g->color = st->color; g->texture = st->texture;
  g->first = 0;
  g->ring = LSYS_NOREC;
  *idx = (uint32_t)t->ngcp++;
  return LSYS_OK;
}

/* The frame of the record of a segment from 'a' to 'b': along the chord, so
** that its p0 is 'a' (the turtle's when the chord is empty). */
static void chordframe (run *R, const lsys_gcpoint *a, const lsys_gcpoint *b, double H[3],
                        double U[3]) {
  double c[3], u[3];
  vcopy(H, R->st.H); vcopy(U, R->st.U);
  vlin(c, b->pos, 1, a->pos, -1);
  if (vnorm(c)) {
    vlin(u, R->st.U, 1, c, -vdot(R->st.U, c));
    if (!vnorm(u)) vcopy(u, R->st.H);
    vcopy(H, c); vcopy(U, u);
  }
}

/* @Gs, @Gc(n), @Ge(n) (§3.1): a control point, and the strips from the
** active one (a branch continues from the point active where it began,
** §3.4). */
int lsys_turtle_gcmodule (run *R, int op, const double *p, uint32_t np) {
  lsys_turtle *t = R->t;
  lsys_tstate *st = &R->st;
  lsys_gcpoint *a, *b;
  lsys_gcshape sh;
  lsys_gccontour ca, cb;
  const lsys_csample *sa, *sb;
  uint32_t ib;
  double x = 1;
  int s;
  if (op != OP_GSTART) {
    if ((s = arg(R, p, np, 0, 1, &x)) != LSYS_OK) return s;
    if (x < 1 || x > MAXSTRIPS)
      return lsys_turtle_failop(R, "the number of strips must be from 1 to %d, got %g",
                                MAXSTRIPS, x);
  }
  if (!R->draw) return LSYS_OK;
  if (op == OP_GSTART || st->gc == LSYS_NOREC) {   /* @Gc without @Gs starts one */
    if (op == OP_GEND) return LSYS_OK;
    if ((s = gcpoint(R, &st->gc)) != LSYS_OK) return s;
    t->gcp[st->gc].first = 1;
    return LSYS_OK;
  }
  if ((s = gcpoint(R, &ib)) != LSYS_OK) return s;
  a = &t->gcp[st->gc]; b = &t->gcp[ib];
  sa = csample(R, a->contour);
  sb = sa != NULL ? csample(R, b->contour) : NULL;
  if (sb == NULL) return lsys_turtle_nomem(R);
  sa = &t->cs[a->contour];                /* csample may have moved the array */
  gccontour(&ca, sa); gccontour(&cb, sb);
  sh.tan0 = st->gtan[0]; sh.tan1 = st->gtan[1];
  memcpy(sh.rtan, st->grad, sizeof sh.rtan);
  sh.adjust = st->gadjust;
  sh.strips = (int)x;
  sh.minimize = R->o->minimize_twist;
  sh.aspect = b->texture > 0 && b->texture <= R->o->ntex && R->o->tex[b->texture - 1]->h > 0
              ? (double)R->o->tex[b->texture - 1]->w / R->o->tex[b->texture - 1]->h : 1;
  sh.capstart = a->first;
  sh.capend = op == OP_GEND;
  if (lsys_gcyl_segment(t->mesh, a, b, &sh, &ca, &cb, R->st.sides) != LSYS_OK)
    return lsys_turtle_nomem(R);
  {
    double H[3], U[3];
    chordframe(R, a, b, H, U);
    if ((s = newrecf(R, LSYS_REC_GCYL, a->pos, b->pos, 2 * a->r, 2 * b->r, H, U)) != LSYS_OK)
      return s;
  }
  if (!R->o->norecords)
    st->last = (uint32_t)(R->t->scene->nrec - 1);   /* the next segment's parent */
  st->gc = op == OP_GEND ? LSYS_NOREC : ib;
  return LSYS_OK;
}

/* @Gt(c0[,c1]) and @Gr(flag) / @Gr(a,l) / @Gr(a0,l0,a1,l1) (§3.2.1-2). */
int lsys_turtle_gcshape (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double v[4];
  uint32_t k;
  int s;
  for (k = 0; k < np && k < 4; k++)
    if ((s = arg(R, p, np, k, 0, &v[k])) != LSYS_OK) return s;
  if (op == OP_GTAN) {
    if (np == 0) { st->gtan[0] = st->gtan[1] = LSYS_GC_TANGENT; return LSYS_OK; }
    st->gtan[0] = v[0];
    st->gtan[1] = np > 1 ? v[1] : v[0];
    return LSYS_OK;
  }
  switch (np) {
    case 0: memset(st->grad, 0, sizeof st->grad); return LSYS_OK;   /* back to linear */
    case 1: st->gadjust = v[0] != 0; return LSYS_OK;
    case 2: st->grad[0] = st->grad[2] = v[0]; st->grad[1] = st->grad[3] = v[1]; return LSYS_OK;
    case 3: return lsys_turtle_failop(R, "takes 1, 2 or 4 parameters, not 3");
    default: memcpy(st->grad, v, sizeof st->grad); return LSYS_OK;
  }
}
