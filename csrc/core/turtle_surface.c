/*
** The turtle's surfaces: ~X(s) places the view's predefined surface X
** (cpfg guide §4.1), which is tessellated once per run in its own frame and
** then turned and scaled to the turtle; @PS, @PC and @PD define and draw
** bicubic patches from the turtle's positions (§4.3, Appendix A). The
** tessellation itself is surface.c's. See turtle_impl.h.
*/
#include <string.h>

#include "turtle_impl.h"

#define MAXPATCHES 1024
#define MAXLINES 256

/* The turtle's frame, 'scale' and colour as the placement of a surface,
** with texture 'tex' for the mesh. */
static void place (run *R, lsys_place *pl, double scale, int tex) {
  lsys_tstate *st = &R->st;
  vcopy(pl->origin, st->pos);
  vcopy(pl->H, st->H); vcopy(pl->L, st->L); vcopy(pl->U, st->U);
  pl->scale = scale;
  pl->color = (unsigned)st->color;
  pl->uv_surface = tex > 0 && tex <= R->o->ntex && R->o->tex[tex - 1]->per_surface;
  if (R->draw) R->t->mesh->curtex = (unsigned)tex;   /* a query or state run has no mesh */
}

/* Surface k of the view tessellated in its own frame (contact point at the
** origin, SIZE 1), once per run and uv mode: every ~X then only turns and
** scales a copy. */
static int surftess (run *R, int k, int uvsurf, const lsys_mesh **out) {
  lsys_turtle *t = R->t;
  const lsys_surfuse *u = &R->o->surfaces[k];
  size_t slot = 2 * (size_t)k + (size_t)uvsurf;
  lsys_place pl;
  if (slot >= t->nstess) {
    size_t n = 2 * (size_t)R->o->nsurfaces, j;
    lsys_mesh *m = (lsys_mesh *)LSYS_REALLOC(t->stess, n * sizeof *m);
    uint8_t *ok = m ? (uint8_t *)LSYS_REALLOC(t->stessok, n) : NULL;
    if (m) t->stess = m;
    if (ok == NULL) return lsys_turtle_nomem(R);
    t->stessok = ok;
    for (j = t->nstess; j < n; j++) { lsys_mesh_init(&t->stess[j]); ok[j] = 0; }
    t->nstess = n;
  }
  if (!t->stessok[slot]) {
    lsys_mesh *m = &t->stess[slot];
    int s;
    memset(&pl, 0, sizeof pl);
    vcopy(pl.H, u->s->heading); vcopy(pl.U, u->s->up);
    vcross(pl.L, pl.H, pl.U);
    pl.scale = u->s->size > 0 ? u->s->size : 1;
    pl.uv_surface = uvsurf;
    lsys_mesh_clear(m);
    if ((s = lsys_surface_mesh(m, u->s, &pl, u->ns, u->nt)) != LSYS_OK)
      return s == LSYS_ENOMEM ? lsys_turtle_nomem(R)
                              : lsys_turtle_failop(R, "cannot tessellate the surface");
    t->stessok[slot] = 1;
  }
  *out = &t->stess[slot];
  return LSYS_OK;
}

/* The turn from surface space (contact point at the origin) to the world
** that cpfg applies (patches.c): a point (x, y, z) first becomes x l + y h +
** z u, where h and u are the file's HEADING and UP and l = h x u, and that
** is then read as coordinates along the turtle's L, H and U. (The turn that
** maps h to H and u to U is the transpose of the first step; the two agree
** only when HEADING and UP lie on the axes.) */
static void surfturn (const lsys_tstate *st, const lsys_surface *S, const double sc[3],
                      double Rw[3][3]) {
  double LS[3];
  int a, b;
  vcross(LS, S->heading, S->up);
  for (a = 0; a < 3; a++)
    for (b = 0; b < 3; b++) {
      const double *col = b == 0 ? LS : b == 1 ? S->heading : S->up;
      Rw[a][b] = st->L[a] * sc[0] * col[0] + st->H[a] * sc[1] * col[1] +
                 st->U[a] * sc[2] * col[2];
    }
}

/* Appends a copy of surface k's tessellation (surftess), turned to the
** turtle's frame (surfturn), scaled to the placement 'pl' and along L, H and U
** by 'sc' (cpfg's ~X(sx, sy, sz), relative to sx: its glScaled after the turn
** by M); normals by the inverse scales. */
static int surfcopy (run *R, int k, const lsys_place *pl, const double sc[3]) {
  const lsys_surface *S = R->o->surfaces[k].s;
  lsys_tstate *st = &R->st;
  lsys_mesh *m = R->t->mesh;
  double Rw[3][3], Rn[3][3], kk = pl->scale / (S->size > 0 ? S->size : 1);
  double inv[3] = {1 / sc[0], 1 / sc[1], 1 / sc[2]};
  uint32_t first;
  size_t i;
  const lsys_mesh *tm = NULL;
  int a, s;
  if ((s = surftess(R, k, pl->uv_surface, &tm)) != LSYS_OK) return s;
  if (lsys_mesh_reserve(m, tm->nv, tm->nt) != LSYS_OK) return lsys_turtle_nomem(R);
  surfturn(st, S, sc, Rw);
  surfturn(st, S, inv, Rn);
  first = (uint32_t)m->nv;
  for (i = 0; i < tm->nv; i++) {
    const float *q = tm->pos + 3 * i, *n = tm->nrm + 3 * i;
    double P[3], N[3];
    for (a = 0; a < 3; a++) {
      P[a] = st->pos[a] + kk * (Rw[a][0] * q[0] + Rw[a][1] * q[1] + Rw[a][2] * q[2]);
      N[a] = Rn[a][0] * n[0] + Rn[a][1] * n[1] + Rn[a][2] * n[2];
    }
    vnorm(N);
    lsys_mesh_vertex(m, P, N, tm->uv[2 * i], tm->uv[2 * i + 1], pl->color, 1);
  }
  for (i = 0; i < tm->nt; i++) {
    const uint32_t *q = tm->tri + 3 * i;
    lsys_mesh_tri(m, first + q[0], first + q[1], first + q[2]);
  }
  return LSYS_OK;
}

/* Where the turtle stands after ~X: the surface's END POINT turned as its
** points are (surfturn; cpfg's transform_end_point, which scales by the first
** parameter only). */
static void surfend (const lsys_tstate *st, const lsys_surface *S, double scale,
                     double out[3]) {
  static const double one[3] = {1, 1, 1};
  double Rw[3][3], d[3], kk = scale / (S->size > 0 ? S->size : 1);
  int a;
  surfturn(st, S, one, Rw);
  for (a = 0; a < 3; a++) d[a] = S->end[a] - S->contact[a];
  for (a = 0; a < 3; a++)
    out[a] = st->pos[a] + kk * (Rw[a][0] * d[0] + Rw[a][1] * d[1] + Rw[a][2] * d[2]);
}

/* ~X(s) or ~X(sx, sy, sz): the view's surface X at the turtle, scaled by s, or
** by sx along L, sy along H and sz along U (cpfg's interpret.c: fewer than three
** parameters scale it uniformly by the first; a scale of 0 draws nothing); the
** turtle then stands at the surface's end point, scaled by the first. */
int lsys_turtle_surface (run *R, uint32_t sym, const double *p, uint32_t np) {
  const lsys_turtle_opts *o = R->o;
  lsys_tstate *st = &R->st;
  const lsys_surfuse *u = NULL;
  lsys_place pl;
  double x, y = 0, z = 0, p0[3], sc[3] = {1, 1, 1};
  int k, s, tex;
  for (k = 0; k < o->nsurfaces; k++)
    if (R->t->surfsym[k] == sym) { u = &o->surfaces[k]; break; }
  if (u == NULL) return LSYS_OK;
  if ((s = arg(R, p, np, 0, 1, &x)) != LSYS_OK) return s;
  if (np >= 3) {
    if ((s = arg(R, p, np, 1, 1, &y)) != LSYS_OK || (s = arg(R, p, np, 2, 1, &z)) != LSYS_OK)
      return s;
    if (x != 0) { sc[1] = y / x; sc[2] = z / x; }
  }
  tex = u->texture > 0 ? u->texture : st->texture;
  place(R, &pl, u->scale * x * st->scale, tex);
  vcopy(p0, st->pos);
  if (R->draw && x != 0 && (np < 3 || (y != 0 && z != 0)) &&
      (s = surfcopy(R, k, &pl, sc)) != LSYS_OK)
    return s;
  surfend(st, u->s, pl.scale, st->pos);
  st->tip = LSYS_NOREC;
  return R->draw ? newrec(R, LSYS_REC_SURFACE, p0, st->pos, 0, 0) : LSYS_OK;
}

/* A whole-number parameter in lo..hi, with a message naming 'what'. */
static int intarg (run *R, const double *p, uint32_t np, uint32_t k, double def, int lo,
                   int hi, const char *what, int *out) {
  double x;
  int s;
  if ((s = arg(R, p, np, k, def, &x)) != LSYS_OK) return s;
  if (!(x >= lo && x <= hi))
    return lsys_turtle_failop(R, "%s must be from %d to %d, got %g", what, lo, hi, x);
  *out = (int)x;
  return LSYS_OK;
}

/* @PS(i[,basis]), @PC(i,r,c), @PD(i,s,t) (§4.3, Appendix A). */
int lsys_turtle_patch (run *R, int op, const double *p, uint32_t np) {
  lsys_turtle *t = R->t;
  lsys_lpatch *pt;
  int i, a, b, s;
  if (np == 0) return lsys_turtle_failop(R, "needs a patch number");
  if ((s = intarg(R, p, np, 0, 0, 0, MAXPATCHES - 1, "the patch number", &i)) != LSYS_OK)
    return s;
  if ((size_t)i >= t->npatch) {
    size_t old = t->npatch, cap = t->npatch;
    if (lsys_common_grow((void **)&t->patch, &cap, (size_t)i + 1, sizeof *t->patch) != LSYS_OK)
      return lsys_turtle_nomem(R);
    memset(t->patch + old, 0, (cap - old) * sizeof *t->patch);
    t->npatch = cap;
  }
  pt = &t->patch[i];
  switch (op) {
    case OP_PSTARTP:
      if ((s = intarg(R, p, np, 1, LSYS_BASIS_BEZIER, 1, 3, "the basis (1 Bezier, 2 B-spline, "
                      "3 Cardinal)", &a)) != LSYS_OK)
        return s;
      memset(pt->p.ctrl, 0, sizeof pt->p.ctrl);
      pt->basis = a;
      pt->started = 1;
      return LSYS_OK;
    case OP_PCTRL:
      if (np < 3) return lsys_turtle_failop(R, "needs a patch, a row and a column");
      if ((s = intarg(R, p, np, 1, 0, 0, 3, "the row", &a)) != LSYS_OK ||
          (s = intarg(R, p, np, 2, 0, 0, 3, "the column", &b)) != LSYS_OK)
        return s;
      if (!pt->started) break;
      vcopy(pt->p.ctrl + 3 * (4 * a + b), R->st.pos);
      return LSYS_OK;
    default: {
      lsys_place pl;
      if ((s = intarg(R, p, np, 1, 4, 1, MAXLINES, "the number of lines", &a)) != LSYS_OK ||
          (s = intarg(R, p, np, 2, a, 1, MAXLINES, "the number of lines", &b)) != LSYS_OK)
        return s;
      if (!pt->started) break;
      if (!R->draw) return LSYS_OK;
      place(R, &pl, 1, R->st.texture);
      if ((s = lsys_surface_patch_mesh(t->mesh, pt->basis, &pt->p, &pl, a, b)) != LSYS_OK)
        return s == LSYS_ENOMEM ? lsys_turtle_nomem(R)
                                : lsys_turtle_fail(R, s, "the scene is too big");
      return newrec(R, LSYS_REC_SURFACE, R->st.pos, R->st.pos, 0, 0);
    }
  }
  return lsys_turtle_failop(R, "patch %d was not started with @PS(%d)", i, i);
}
