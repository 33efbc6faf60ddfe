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

/* Appends a copy of surface k's tessellation (surftess), turned to the
** turtle's frame and scaled to the placement 'pl'. */
static int surfcopy (run *R, int k, const lsys_place *pl) {
  const lsys_surface *S = R->o->surfaces[k].s;
  lsys_tstate *st = &R->st;
  lsys_mesh *m = R->t->mesh;
  double Rw[3][3], kk = pl->scale / (S->size > 0 ? S->size : 1), LS[3];
  uint32_t first;
  size_t i;
  const lsys_mesh *tm = NULL;
  int a, b, s;
  if ((s = surftess(R, k, pl->uv_surface, &tm)) != LSYS_OK) return s;
  if (lsys_mesh_reserve(m, tm->nv, tm->nt) != LSYS_OK) return lsys_turtle_nomem(R);
  vcross(LS, S->heading, S->up);
  for (a = 0; a < 3; a++)              /* H_S -> H, U_S -> U, H_S x U_S -> L */
    for (b = 0; b < 3; b++)
      Rw[a][b] = st->L[a] * LS[b] + st->H[a] * S->heading[b] + st->U[a] * S->up[b];
  first = (uint32_t)m->nv;
  for (i = 0; i < tm->nv; i++) {
    const float *q = tm->pos + 3 * i, *n = tm->nrm + 3 * i;
    double P[3], N[3];
    for (a = 0; a < 3; a++) {
      P[a] = st->pos[a] + kk * (Rw[a][0] * q[0] + Rw[a][1] * q[1] + Rw[a][2] * q[2]);
      N[a] = Rw[a][0] * n[0] + Rw[a][1] * n[1] + Rw[a][2] * n[2];
    }
    lsys_mesh_vertex(m, P, N, tm->uv[2 * i], tm->uv[2 * i + 1], pl->color, 1);
  }
  for (i = 0; i < tm->nt; i++) {
    const uint32_t *q = tm->tri + 3 * i;
    lsys_mesh_tri(m, first + q[0], first + q[1], first + q[2]);
  }
  return LSYS_OK;
}

/* ~X(s): the view's surface X at the turtle, scaled by s; the turtle then
** stands at the surface's end point. */
int lsys_turtle_surface (run *R, uint32_t sym, const double *p, uint32_t np) {
  const lsys_turtle_opts *o = R->o;
  lsys_tstate *st = &R->st;
  const lsys_surfuse *u = NULL;
  lsys_place pl;
  double x, p0[3];
  int k, s, tex;
  for (k = 0; k < o->nsurfaces; k++)
    if (R->t->surfsym[k] == sym) { u = &o->surfaces[k]; break; }
  if (u == NULL) return LSYS_OK;
  if ((s = arg(R, p, np, 0, 1, &x)) != LSYS_OK) return s;
  tex = u->texture > 0 ? u->texture : st->texture;
  place(R, &pl, u->scale * x * st->scale, tex);
  vcopy(p0, st->pos);
  if (R->draw && (s = surfcopy(R, k, &pl)) != LSYS_OK) return s;
  lsys_surface_endpoint(u->s, &pl, st->pos);
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
    if (lsys_grow((void **)&t->patch, &cap, (size_t)i + 1, sizeof *t->patch) != LSYS_OK)
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
      if ((s = lsys_patch_mesh(t->mesh, pt->basis, &pt->p, &pl, a, b)) != LSYS_OK)
        return s == LSYS_ENOMEM ? lsys_turtle_nomem(R)
                                : lsys_turtle_fail(R, s, "the scene is too big");
      return newrec(R, LSYS_REC_SURFACE, R->st.pos, R->st.pos, 0, 0);
    }
  }
  return lsys_turtle_failop(R, "patch %d was not started with @PS(%d)", i, i);
}
