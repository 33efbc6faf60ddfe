/*
** The turtle: the cpfg guide (Měch and Prusinkiewicz), Appendix A
** (interpreted symbols), §6 (tropisms, eq. 1-2; twist response §6.1;
** twist minimisation). See turtle.h. This file keeps the state and
** dispatches the commands, one function each; the geometry is built in
** turtle_*.c, one kind per file (turtle_impl.h).
**
** Rotations, with the frame kept right-handed as L = H x U (cpfg's initial
** frame H = (0,1,0), L = (-1,0,0), U = (0,0,-1)):
**   +  turn left:   H toward L          -  turn right
**   &  pitch down:  H toward U          ^  pitch up:  H toward -U
**   /  roll right:  L toward U          \  roll left
** so that + turns anticlockwise seen from +z, as cpfg does. & is ABOP's R_L(delta)
** (§1.5: [H' L' U'] = [H L U] R_L, H' = H cos + U sin), the direction cpfg's ?H reports
** (&(30) from the initial frame heads (0, 0.866, -0.5)); tests/cpfg_probe_spec.lua
** compares these with cpfg.
*/
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "turtle_impl.h"
#include "polygon.h"

/* ---------------------------------------------------------------------- */

void lsys_turtle_defaults (lsys_turtle_opts *o) {
  memset(o, 0, sizeof *o);
  o->angle = 90;
  o->step = 1;
  o->width = 1; o->dwidth = 1;
  o->color = 1; o->dcolor = 1;
  o->style = LSYS_STYLE_LINE;
  o->sides = 8;
  o->minimize_twist = 1;
  o->otrop[1] = 1;
}

void lsys_turtle_init (lsys_turtle *t) {
  memset(t, 0, sizeof *t);
  lsys_lstring_init(&t->hbuf);
}

void lsys_turtle_free (lsys_turtle *t) {
  size_t k;
  for (k = 0; k < t->polycap; k++) LSYS_FREE(t->polys[k].v);
  LSYS_FREE(t->polys);
  LSYS_FREE(t->stack);
  LSYS_FREE(t->ends);
  LSYS_FREE(t->subscale);
  LSYS_FREE(t->op);
  LSYS_FREE(t->ringbuf);
  LSYS_FREE(t->runbuf);
  LSYS_FREE(t->gcp);
  for (k = 0; k < t->ncs; k++) {
    LSYS_FREE(t->cs[k].v); LSYS_FREE(t->cs[k].n); LSYS_FREE(t->cs[k].cap);
  }
  LSYS_FREE(t->cs);
  LSYS_FREE(t->patch);
  LSYS_FREE(t->surfsym);
  LSYS_FREE(t->shash);
  for (k = 0; k < t->nstess; k++) lsys_mesh_free(&t->stess[k]);
  LSYS_FREE(t->stess);
  LSYS_FREE(t->stessok);
  lsys_lstring_free(&t->hbuf);
  if (t->pw) { lsys_polygon_work_free(t->pw); LSYS_FREE(t->pw); }
  memset(t, 0, sizeof *t);
}

/* ---------------------------------------------------------------------- */
/* the run */

/* Rotates the pair (a, b) in their plane: a toward b by angle 'deg'. */
static void turn (run *R, double *a, double *b, double deg) {
  double c, s, na[3];
  if (deg == R->tdeg) { c = R->tcos; s = R->tsin; }     /* most turns repeat one angle */
  else if (deg == -R->tdeg) { c = R->tcos; s = -R->tsin; }
  else {
    double r = RAD(deg);
    c = cos(r); s = sin(r);
    R->tdeg = deg; R->tcos = c; R->tsin = s;
  }
  vlin(na, a, c, b, s);
  vlin(b, b, c, a, -s);
  vcopy(a, na);
}

/* Turns the pair (a, b) by 'deg' degrees in their plane, a towards b (the
** right-handed turn about a x b). */
static void jointturn (double *a, double *b, double deg) {
  double r = RAD(deg), c = cos(r), s = sin(r), na[3];
  vlin(na, a, c, b, s);
  vlin(b, b, c, a, -s);
  vcopy(a, na);
}

/* The symbol of a command, for messages. */
static const char *opname (int op) {
  const char *name = op >= 0 && op < LSYS_NSYMBOLS ? lsys_symbols[op].name : NULL;
  return name != NULL ? name : "?";
}

/* An error about the current module: "module N: message", or "module N
** 'name': message" with a name, in the core's "where: message" form
** (common.h). */
static int vfail (run *R, int code, const char *name, const char *fmt, va_list ap) {
  char where[sizeof R->t->err.msg];
  if (name != NULL) snprintf(where, sizeof where, "module %zu '%s'", R->mod + 1, name);
  else snprintf(where, sizeof where, "module %zu", R->mod + 1);
  return lsys_vseterror_at(&R->t->err, code, R->mod, where, fmt, ap);
}

int lsys_turtle_fail (run *R, int code, const char *fmt, ...) {
  va_list ap;
  int s;
  va_start(ap, fmt);
  s = vfail(R, code, NULL, fmt, ap);
  va_end(ap);
  return s;
}

int lsys_turtle_failop (run *R, const char *fmt, ...) {
  va_list ap;
  int s;
  va_start(ap, fmt);
  s = vfail(R, LSYS_EARG, opname(R->op), fmt, ap);
  va_end(ap);
  return s;
}


int lsys_turtle_nomem (run *R) {
  lsys_meter *mt = R->t->meter;
  if (mt != NULL && mt->hit) {
    char b[32];
    return lsys_turtle_fail(R, LSYS_EMEMORY, "the interpretation would need more than "
                            "max_memory (%s) (set max_memory in the model, or LSYS_MAX_MEMORY)",
                            lsys_common_fmtsize(b, mt->limit));
  }
  return lsys_turtle_fail(R, LSYS_ENOMEM, "not enough memory");
}

/* --- segments ------------------------------------------------------------ */

/* The cos/sin table of the state's sides, for cylinders, discs and spheres. */
static int setring (run *R) {
  lsys_turtle *t = R->t;
  int n = R->st.sides;
  if (t->nring == n && t->ring) return LSYS_OK;
  if (lsys_common_grow((void **)&t->ringbuf, &t->ringcap, 2 * (size_t)n + 2,
                       sizeof(double)) != LSYS_OK)
    return lsys_turtle_nomem(R);
  lsys_mesh_ringtable(t->ringbuf, n);
  t->ring = t->ringbuf;
  t->nring = n;
  return LSYS_OK;
}

/* Draws the pending segment as a ribbon or a cylinder, in the frame, sides and
** texture it was made with (turns may have come since). */
static int tube (run *R, double w1) {
  lsys_tstate *st = &R->st;
  double H[3], L[3], U[3];
  int s, sides = st->sides, tex = st->texture;
  vcopy(H, st->H); vcopy(L, st->L); vcopy(U, st->U);
  vcopy(st->H, R->pH); vcopy(st->L, R->pL); vcopy(st->U, R->pU);
  st->sides = R->psides;
  st->texture = R->ptex;
  if (R->o->style == LSYS_STYLE_POLYGON)
    s = lsys_turtle_ribbon(R, R->p0, R->p1, R->w0, w1, R->pcol);
  else if ((s = setring(R)) == LSYS_OK)
    s = lsys_turtle_cylinder(R, R->p0, R->p1, R->w0, w1, R->len, R->pcol);
  vcopy(st->H, H); vcopy(st->L, L); vcopy(st->U, U);
  st->sides = sides;
  st->texture = tex;
  return s;
}

/* Emits the pending segment with its final top width, in the line style or as
** a tube, and ends its record: the triangles drawn now are its own (its record
** was begun at its F, before them), so scene:edges and scene:vertices of a tube
** or ribbon give them; a line's second end is the record's end point. */
static int flush (run *R) {
  lsys_mesh *m = R->t->mesh;
  double w1 = R->st.width * R->st.scale;
  int s = LSYS_OK, line = 0;
  size_t nt0;
  if (!R->pending) return LSYS_OK;
  R->pending = 0;
  nt0 = m->nt;
  m->curtex = (unsigned)R->ptex;
  if (R->o->style == LSYS_STYLE_LINE) {
    if (lsys_mesh_line(m, R->p0, R->p1, R->w0, w1, (unsigned)R->pcol) != LSYS_OK)
      return lsys_turtle_nomem(R);
    /* the line keeps the end point when it holds the same float (it clamps at FLT_MAX) */
    line = fabs(R->p1[0]) <= FLT_MAX && fabs(R->p1[1]) <= FLT_MAX && fabs(R->p1[2]) <= FLT_MAX;
  }
  else if ((s = tube(R, w1)) != LSYS_OK) return s;
  if (R->prec != LSYS_NOREC) {
    skey h;
    shapeset(&h, LSYS_REC_SEGMENT, R->pH, R->pU, R->plen, R->w0, w1, R->pstiff, nt0,
             m->nt - nt0, R->pcol, line);
    s = recend(R, &R->t->scene->rec[R->prec - R->recbase], &h, line, line ? m->nl - 1 : 0,
               R->p1);
  }
  return s;
}

/* F f G g: a step of d (the view's step without a parameter) after the
** tropisms bent the heading; the old-style tropism bends it after the step. F and G
** draw a segment, whose top width waits for a following ! or # (the symbol table's
** 'keep'); inside a polygon F and f add a vertex too. */
static int move (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double p0[3], d;
  int s;
  if ((s = arg(R, p, np, 0, R->o->step, &d)) != LSYS_OK) return s;
  if (R->o->ntrop > 0) lsys_turtle_tropisms(R);     /* (ends emitted the pending segment before this) */
  d *= st->scale;
  vcopy(p0, st->pos);
  vlin(st->pos, st->pos, 1, st->H, d);
  if (!isfinite(st->pos[0] + st->pos[1] + st->pos[2]))   /* nothing could draw it */
    return lsys_turtle_failop(R, "the position is no longer finite after a move of %g", d);
  if (st->oelast != 0) lsys_turtle_oldbend(R);
  if (op == OP_f || op == OP_g) {
    st->tip = LSYS_NOREC;
    return op == OP_f && R->t->npolys > 0 ? lsys_turtle_polyvertex(R) : LSYS_OK;
  }
  /* an edge of a polygon: a vertex, and drawn as a segment too, as cpfg draws it (its
  ** F calls StartNode whether or not a polygon is open) */
  if (op == OP_F && R->t->npolys > 0 && (s = lsys_turtle_polyvertex(R)) != LSYS_OK) return s;
  if (!R->draw) return LSYS_OK;
  {
    lsys_rec *q;
    if ((s = recstart(R, &q, &R->pstiff)) != LSYS_OK) return s;
    R->prec = q == NULL ? LSYS_NOREC : (uint32_t)(R->recbase + R->t->scene->nrec - 1);
    if (q != NULL) R->plen = reclen(p0, st->pos, fabs(d));
  }
  st->hasstiff = 0;
  st->last = R->prec;
  R->pending = 1;
  vcopy(R->p0, p0);
  vcopy(R->p1, st->pos);
  R->w0 = st->width * st->scale;
  R->len = fabs(d);
  R->pcol = st->color;
  R->ptex = st->texture;
  R->psides = st->sides;
  vcopy(R->pH, st->H); vcopy(R->pL, st->L); vcopy(R->pU, st->U);
  return LSYS_OK;
}

/* --- stack ------------------------------------------------------------- */

/* Copies the first 'n' bytes of a state: all but the tropisms' elasticities in
** a copy of known size (inlined by the compiler), then the view's share of
** those. */
static void copystate (lsys_tstate *to, const lsys_tstate *from, size_t n) {
  memcpy(to, from, offsetof(lsys_tstate, elast));
  if (n > offsetof(lsys_tstate, elast))
    memcpy(to->elast, from->elast, n - offsetof(lsys_tstate, elast));
}

static int push (run *R) {
  lsys_turtle *t = R->t;
  lsys_tstate *to;
  if (R->depth < NSTACK) to = &R->cstack[R->depth];
  else {
    size_t k = R->depth - NSTACK;
    if (k >= t->stackcap &&
        lsys_common_grow_metered((void **)&t->stack, &t->stackcap, k + 1, sizeof *t->stack,
                                 t->meter) != LSYS_OK)
      return lsys_turtle_nomem(R);
    to = &t->stack[k];
  }
  copystate(to, &R->st, R->stsize);
  R->depth++;
  return LSYS_OK;
}

static int pop (run *R) {
  if (R->depth == 0) return LSYS_OK;         /* unbalanced ']': ignored, as cpfg does */
  R->depth--;
  copystate(&R->st, R->depth < NSTACK ? &R->cstack[R->depth] : &R->t->stack[R->depth - NSTACK],
            R->stsize);
  return R->t->nring == R->st.sides ? LSYS_OK : setring(R);  /* @!(n) in the branch */
}

/* --- the commands ----------------------------------------------------------- */

/* + - & ^ \ /: turns by the parameter, or the view's angle (see the top). */
static int rotate (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double x;
  int s;
  if ((s = arg(R, p, np, 0, R->o->angle, &x)) != LSYS_OK) return s;
  switch (op) {
    case OP_LEFT: turn(R, st->H, st->L, x); break;
    case OP_RIGHT: turn(R, st->H, st->L, -x); break;
    case OP_DOWN: turn(R, st->H, st->U, x); break;
    case OP_UP: turn(R, st->H, st->U, -x); break;
    case OP_ROLLR: turn(R, st->L, st->U, x); break;
    default: turn(R, st->L, st->U, -x); break;
  }
  return LSYS_OK;
}

/* @J(h, u, l): an arranged joint (Power et al. 1999, §3.1; ik.h):
** right-handed turns in degrees about H, then the new U, then the new L,
** where L is taken as U x H; the turtle's own L keeps its orientation to
** it. */
static int joint (run *R, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double a[3], Lr[3], sign;
  int k, s;
  for (k = 0; k < 3; k++)
    if ((s = arg(R, p, np, (uint32_t)k, 0, &a[k])) != LSYS_OK) return s;
  vcross(Lr, st->U, st->H);
  sign = vdot(Lr, st->L) < 0 ? -1 : 1;
  jointturn(Lr, st->U, a[0]);       /* about H: L towards U */
  jointturn(st->H, Lr, a[1]);       /* about U: H towards L */
  jointturn(st->U, st->H, a[2]);    /* about L: U towards H */
  vlin(st->L, Lr, sign, Lr, 0);
  return LSYS_OK;
}

/* |: turns around. */
static int turnaround (run *R) {
  lsys_tstate *st = &R->st;
  vlin(st->H, st->H, -1, st->H, 0);
  vlin(st->L, st->L, -1, st->L, 0);
  return LSYS_OK;
}

/* @v: rolls about H until L is horizontal, L = V x H / |V x H| with V = +y (ABOP's $;
** in our frame, where L = H x U, U = L x H). cpfg does the same: after /(30)&(50)
** its L is (-0.866, 0, -0.5), U (0.321, -0.766, -0.557). */
static int vertical (run *R) {
  lsys_tstate *st = &R->st;
  double V[3] = {0, 1, 0}, l[3];
  vcross(l, V, st->H);
  if (vnorm(l)) { vcopy(st->L, l); vcross(st->U, st->L, st->H); }
  return LSYS_OK;
}

/* @R(hx,hy,hz[,ux,uy,uz]): sets the heading (and up). */
static int setframe (run *R, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double v[6];
  int k, s;
  if (np < 3) return lsys_turtle_fail(R, LSYS_EARG, "%s needs a heading (3 or 6 parameters)",
                                      opname(R->op));
  for (k = 0; k < 6; k++)
    if ((s = arg(R, p, np, (uint32_t)k, k < 3 ? 0 : st->U[k - 3], &v[k])) != LSYS_OK)
      return s;
  vcopy(st->H, v);
  vcopy(st->U, v + 3);
  lsys_turtle_orthonormal(st);
  return LSYS_OK;
}

/* @M(x,y,z): moves there without drawing. */
static int moveto (run *R, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  int k, s;
  for (k = 0; k < 3; k++)
    if ((s = arg(R, p, np, (uint32_t)k, st->pos[k], &st->pos[k])) != LSYS_OK)
      return s;
  st->tip = LSYS_NOREC;
  return LSYS_OK;
}

/* # and !: the width, set or changed by the view's increment. */
static int width (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double x;
  int s;
  if (np > 0) { if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s; }
  else x = st->width + (op == OP_WIDER ? R->o->dwidth : -R->o->dwidth);
  st->width = x < 0 ? 0 : x;
  return LSYS_OK;
}

/* A colour, texture or contour index from a parameter: truncated, kept in
** 0..65535 (a huge parameter must not overflow the conversion to int). */
static int toindex (double x) {
  return x <= 0 ? 0 : x >= 65535 ? 65535 : (int)x;
}

/* ; and ,: the colour (and the second colour), set or changed by the view's
** increment, kept in 0..65535. */
static int colour (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  int dc = R->o->dcolor, s = LSYS_OK;
  double x;
  if (np > 0) {
    if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
    st->color = st->color2 = toindex(x);
    if (np > 1 && (s = arg(R, p, np, 1, 0, &x)) == LSYS_OK) st->color2 = toindex(x);
  }
  else {
    st->color += op == OP_COLINC ? dc : -dc;
    st->color2 += op == OP_COLINC ? dc : -dc;
  }
  if (st->color < 0) st->color = 0;
  if (st->color > 65535) st->color = 65535;
  if (st->color2 < 0) st->color2 = 0;
  if (st->color2 > 65535) st->color2 = 65535;
  return s;
}

/* @Tx(k): texture k of the view (0: none). A texture the view does not define leaves
** what follows untextured, as in cpfg (textures.c, is_valid_texture_index: a texture
** that could not be read is not in its table); the run warns about the first such
** module. */
static int texture (run *R, const double *p, uint32_t np) {
  lsys_turtle *t = R->t;
  double x;
  int k, s;
  if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
  k = toindex(x);
  if (x < 0 || k > R->o->ntex) {
    if (t->warn.code == 0 || R->mod < t->warn.pos)
      lsys_seterror(&t->warn, LSYS_EARG, R->mod, "module %zu '@Tx': texture %g is not defined "
                    "(the view has %d; view.textures); untextured from there, as in cpfg",
                    R->mod + 1, x < 0 ? x : (double)k, R->o->ntex);
    k = 0;
  }
  R->st.texture = k;
  return LSYS_OK;
}

/* @#(id): the contour of the next generalized cylinders (0: the circle). */
static int contour (run *R, const double *p, uint32_t np) {
  const lsys_turtle_opts *o = R->o;
  double x;
  int k, s;
  if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
  k = toindex(x);
  if (x < 0 || (k != 0 && (k >= o->ncontours || o->contours[k] == NULL)))
    return lsys_turtle_failop(R, "contour %g is not defined (view.contours; 0 is the circle)",
                              x < 0 ? x : (double)k);
  R->st.contour = k;
  return LSYS_OK;
}

/* @o, @c, @O: a disc in the xy plane, a disc facing H, a sphere, of the
** parameter's diameter (the width without one). */
static int roundshape (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double x;
  int s;
  if ((s = arg(R, p, np, 0, st->width, &x)) != LSYS_OK) return s;
  x *= st->scale;
  if (!R->draw) return LSYS_OK;
  R->t->mesh->curtex = (unsigned)st->texture;
  if (op == OP_SPHERE) s = lsys_turtle_sphere(R, st->pos, x, st->color);
  else if (op == OP_DISC) s = lsys_turtle_disc(R, st->pos, st->H, st->L, st->U, x, st->color);
  else {
    double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
    s = lsys_turtle_disc(R, st->pos, ex, ey, ez, x, st->color);
  }
  if (s != LSYS_OK) return s;
  return newrec(R, op == OP_SPHERE ? LSYS_REC_SPHERE : LSYS_REC_DISC, st->pos, st->pos, x, x);
}

/* ?P ?H ?U ?L: in QUERY mode, a module of the string itself (not of an
** expansion) gets the turtle's position or vector as its parameters. */
static int query (run *R, int op, double *p, uint32_t np, int original) {
  const double *v = op == OP_QP ? R->st.pos : op == OP_QH ? R->st.H
                  : op == OP_QU ? R->st.U : R->st.L;
  uint32_t k;
  if (!original || R->t->mode != LSYS_TURTLE_QUERY) return LSYS_OK;
  for (k = 0; k < np && k < 3; k++) p[k] = v[k];
  R->t->nqueries++;
  return LSYS_OK;
}

/* @D, @Di, @Dd: sets, multiplies or divides the scale. */
static int scale (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double x;
  int s;
  if ((s = arg(R, p, np, 0, 1, &x)) != LSYS_OK) return s;
  if (op == OP_SCALE) st->scale = x;
  else if (op == OP_SCALEMUL) st->scale *= x;
  else if (x != 0) st->scale /= x;
  else return lsys_turtle_fail(R, LSYS_EARG, "%s: division of the scale by 0", opname(op));
  return LSYS_OK;
}

/* @L, and @S when the model allows system calls: a record at the turtle. */
static int mark (run *R, int kind) {
  return R->draw ? newrec(R, kind, R->st.pos, R->st.pos, 0, 0) : LSYS_OK;
}

static int systemcall (run *R) {
  if (!R->o->allow_system)
    return lsys_seterror(&R->t->err, LSYS_EARG, R->mod,
                         "module %zu '@S' (system call) refused: system calls are off "
                         "unless the model sets allow_system_calls = true", R->mod + 1);
  R->t->nsyscalls++;
  return mark(R, LSYS_REC_SYSTEM);
}

/* Z(sh, su, sl): the stiffness of the next joint (Power et al. 1999); a
** missing one repeats the one before it. */
static int stiffness (run *R, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  int k, s;
  for (k = 0; k < 3; k++)
    if ((s = arg(R, p, np, (uint32_t)k, k == 0 ? 0 : st->stiff[k - 1],
                 &st->stiff[k])) != LSYS_OK)
      return s;
  st->hasstiff = np > 0;
  return LSYS_OK;
}

/* @Ts(i, e), @Ti(i[, d]), @Td(i[, d]): sets, raises or lowers the
** elasticity of the view's tropism i (§6). */
static int elasticity (run *R, int op, const double *p, uint32_t np) {
  lsys_tstate *st = &R->st;
  double x;
  int k, s;
  if (np == 0) return lsys_turtle_fail(R, LSYS_EARG, "%s needs a tropism index", opname(op));
  if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
  if (x < 1 || x > R->o->ntrop || x != floor(x))
    return lsys_turtle_failop(R, "tropism index %g is not one of the view's %d tropisms", x,
                              R->o->ntrop);
  k = (int)x - 1;
  if (op == OP_TSET) {
    if (np < 2)
      return lsys_turtle_fail(R, LSYS_EARG, "%s needs an index and a value", opname(op));
    if ((s = arg(R, p, np, 1, 0, &x)) != LSYS_OK) return s;
    st->elast[k] = x;
  }
  else {
    if ((s = arg(R, p, np, 1, R->o->trop[k].increment, &x)) != LSYS_OK) return s;
    st->elast[k] += op == OP_TINC ? x : -x;
  }
  return LSYS_OK;
}

/* ~X without a surface X in the view: nothing is drawn and the turtle stays, as cpfg
** does (its FindSurfaceIndex finds none and the surface and its end point are skipped);
** the run warns about the first such module. */
static int nosurface (run *R) {
  lsys_turtle *t = R->t;
  if (t->warn.code == 0 || R->mod < t->warn.pos)
    lsys_seterror(&t->warn, LSYS_EARG, R->mod, "module %zu '%s': no such surface in the view "
                  "(view.surfaces); nothing drawn there, as in cpfg", R->mod + 1,
                  lsys_alphabet_name(R->ab, R->sym));
  return LSYS_OK;
}

/* @!(n): the sides of cylinders, discs and spheres from here on (cpfg's blackbox.c: 8
** without a parameter, at least 3); lsys's limit, as the view's, is 1024. */
static int sides (run *R, const double *p, uint32_t np) {
  double x;
  int s, n;
  if ((s = arg(R, p, np, 0, 8, &x)) != LSYS_OK) return s;
  if (x > 1024) return lsys_turtle_failop(R, "%g sides: at most 1024", x);
  n = x < 3 ? 3 : (int)x;
  R->st.sides = n;
  if (n > R->t->maxsides) R->t->maxsides = n;
  return setring(R);
}

/* _(e): sets the elasticity of the old-style tropism; _ adds the view's increment. */
static int oldelast (run *R, const double *p, uint32_t np) {
  double x;
  int s;
  if ((s = arg(R, p, np, 0, R->st.oelast + R->o->oincr, &x)) != LSYS_OK) return s;
  R->st.oelast = x;
  return LSYS_OK;
}

/* @Tf: the twist is forced, not minimised: the frame is the new reference. */
static int forcetwist (run *R) {
  vcopy(R->st.refH, R->st.H); vcopy(R->st.refU, R->st.U);
  return LSYS_OK;
}

/* ?(.., s) and $: a sub-L-system scales by s until its end. */
static int substart (run *R, const double *p, uint32_t np) {
  lsys_turtle *t = R->t;
  double x;
  int s;
  if ((s = arg(R, p, np, 1, 1, &x)) != LSYS_OK) return s;
  if (lsys_common_grow((void **)&t->subscale, &t->subcap, t->nsub + 1, sizeof(double)) != LSYS_OK)
    return lsys_turtle_nomem(R);
  t->subscale[t->nsub++] = R->st.scale;
  R->st.scale *= x;
  return LSYS_OK;
}

static int subend (run *R) {
  if (R->t->nsub > 0) R->st.scale = R->t->subscale[--R->t->nsub];
  return LSYS_OK;
}

/* Emits the pending segment when module 'op' ends it, as cpfg's EndNode comes
** at F f G g [ ] { } ~ and every @ module (interpret.c), and sub-L-system ends
** change the scale; turns, colours, widths and queries leave it open (the
** symbol table's 'keep', symbols.h): a width change before that sets its top
** width. */
static int ends (run *R, int op) {
  R->op = op;
  return R->pending && !lsys_symbols_keep((unsigned)op) ? flush(R) : LSYS_OK;
}

/* Interprets one module, after ends: op, its parameters (overwritten by a
** query) and whether it is the string's own module. */
static int module (run *R, int op, double *p, uint32_t np, int original) {
  R->op = op;
  R->modtri = R->t->mesh != NULL ? R->t->mesh->nt : 0;   /* what this module draws starts here */
  switch (op) {
    case OP_F: case OP_G: case OP_f: case OP_g: return move(R, op, p, np);
    case OP_LEFT: case OP_RIGHT: case OP_DOWN: case OP_UP: case OP_ROLLL: case OP_ROLLR:
      return rotate(R, op, p, np);
    case OP_JOINT: return joint(R, p, np);
    case OP_TURN: return turnaround(R);
    case OP_VERT: return vertical(R);
    case OP_SETFRAME: return setframe(R, p, np);
    case OP_MOVETO: return moveto(R, p, np);
    case OP_PUSH: return push(R);
    case OP_POP: return pop(R);
    case OP_WIDER: case OP_THINNER: return width(R, op, p, np);
    case OP_COLINC: case OP_COLDEC: return colour(R, op, p, np);
    case OP_TEXTURE: return texture(R, p, np);
    case OP_CONTOUR: return contour(R, p, np);
    case OP_GSTART: case OP_GPOINT: case OP_GEND: return lsys_turtle_gcmodule(R, op, p, np);
    case OP_GTAN: case OP_GRAD: return lsys_turtle_gcshape(R, op, p, np);
    case OP_PSTARTP: case OP_PCTRL: case OP_PDRAW: return lsys_turtle_patch(R, op, p, np);
    case OP_SURFACE: return lsys_turtle_surface(R, R->sym, p, np);
    case OP_NOSURFACE: return nosurface(R);
    case OP_DISCZ: case OP_DISC: case OP_SPHERE: return roundshape(R, op, p, np);
    case OP_PSTART: return lsys_turtle_polystart(R);
    case OP_PEND: return lsys_turtle_polyend(R);
    case OP_PVERT: return lsys_turtle_polyvertex(R);
    case OP_QP: case OP_QH: case OP_QU: case OP_QL: return query(R, op, p, np, original);
    case OP_QE: return R->t->envq != NULL ? lsys_turtle_envquery(R, p, np, original) : LSYS_OK;
    case OP_SCALE: case OP_SCALEMUL: case OP_SCALEDIV: return scale(R, op, p, np);
    case OP_LABEL: return mark(R, LSYS_REC_LABEL);
    case OP_SYSTEM: return systemcall(R);
    case OP_STIFF: return stiffness(R, p, np);
    case OP_TSET: case OP_TINC: case OP_TDEC: return elasticity(R, op, p, np);
    case OP_TPREVENT: lsys_turtle_untwist(&R->st); return LSYS_OK;
    case OP_TFORCE: return forcetwist(R);
    case OP_OLDELAST: return oldelast(R, p, np);
    case OP_SIDES: return sides(R, p, np);
    case OP_SUB: return substart(R, p, np);
    case OP_SUBEND: return subend(R);
    default: return LSYS_OK;
  }
}

static int buildops (lsys_turtle *t, const lsys_alphabet *ab) {
  const lsys_turtle_opts *o = t->o;
  uint32_t id;
  int k;
  if (t->nop < ab->n) {
    uint8_t *op = (uint8_t *)LSYS_REALLOC(t->op, ab->n);
    if (op == NULL) return LSYS_ENOMEM;
    t->op = op;
  }
  t->nop = ab->n;
  memset(t->op, 0, ab->n);
  for (k = 0; k < LSYS_NSYMBOLS; k++) {      /* the named rows of the symbol table */
    const char *name = lsys_symbols[k].name;
    uint32_t id = name != NULL ? lsys_alphabet_find(ab, name, strlen(name)) : 0;
    if (id != 0 && id < ab->n) t->op[id] = (uint8_t)k;
  }
  /* ~X: a view surface, or nothing (and a warning) when the view has none called X */
  for (id = 1; id < ab->n; id++)
    if (ab->names[id][0] == '~' && ab->names[id][1] != '\0') t->op[id] = OP_NOSURFACE;
  if (o->nsurfaces > 0) {
    uint32_t *ss = (uint32_t *)LSYS_REALLOC(t->surfsym, (size_t)o->nsurfaces * sizeof *ss);
    if (ss == NULL) return LSYS_ENOMEM;
    t->surfsym = ss;
    for (k = 0; k < o->nsurfaces; k++) {
      char name[16];
      size_t n = strlen(o->surfaces[k].name);
      ss[k] = 0;
      if (n + 2 > sizeof name) continue;
      name[0] = '~';
      memcpy(name + 1, o->surfaces[k].name, n + 1);
      id = lsys_alphabet_find(ab, name, n + 1);
      if (id != 0 && id < ab->n) { t->op[id] = OP_SURFACE; ss[k] = id; }
    }
  }
  return LSYS_OK;
}

/* Empties the record shape cache (made on first use). */
static int clearcache (lsys_turtle *t) {
  if (t->shash == NULL &&
      (t->shash = (uint32_t *)LSYS_MALLOC(LSYS_SHASH * sizeof *t->shash)) == NULL)
    return LSYS_ENOMEM;
  memset(t->shash, 0, LSYS_SHASH * sizeof *t->shash);
  return LSYS_OK;
}

/* Checks the options and readies the run in t->runbuf for 's': the symbol
** table, the first state, the caches of the last run marked stale. */
static int start (lsys_turtle *t, const lsys_alphabet *ab) {
  const lsys_turtle_opts *o = t->o;
  run *R;
  lsys_tstate *st;
  int k;
  if (o == NULL || (t->mode == LSYS_TURTLE_DRAW && t->scene == NULL))
    return lsys_seterror(&t->err, LSYS_EARG, (size_t)-1, "turtle without options or scene");
  if (o->sides < 3 || o->sides > 1024)
    return lsys_seterror(&t->err, LSYS_EARG, (size_t)-1,
                         "contour sides must be between 3 and 1024, got %d", o->sides);
  if (o->ntrop < 0 || o->ntrop > LSYS_MAXTROPISMS)
    return lsys_seterror(&t->err, LSYS_EARG, (size_t)-1, "at most %d tropisms",
                         LSYS_MAXTROPISMS);
  if (buildops(t, ab) != LSYS_OK)
    return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  /* The run lives in the turtle, not on the C stack: its state stack is big,
  ** and a homomorphism rule may raise a Lua error through us (longjmp). */
  if (t->runbuf == NULL && (t->runbuf = LSYS_MALLOC(sizeof *R)) == NULL)
    return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  R = (run *)t->runbuf;
  memset(R, 0, sizeof *R);
  R->tcos = 1;     /* the turn cache starts at angle 0: cos 1, sin 0 (a first +(0) is no turn) */
  R->t = t; R->o = o;
  R->draw = t->mode == LSYS_TURTLE_DRAW;
  R->prec = LSYS_NOREC;
  R->stsize = offsetof(lsys_tstate, elast) + (size_t)o->ntrop * sizeof(double);
  t->mesh = R->draw ? &t->scene->mesh : NULL;
  if (R->draw) {
    lsys_mesh_clear(t->mesh);
    t->scene->nrec = t->scene->nshape = t->scene->npt = t->scene->nstiff = 0;
    if (!o->norecords && clearcache(t) != LSYS_OK)
      return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  }
  st = &R->st;
  memset(st, 0, sizeof *st);
  vset(st->H, 0, 1, 0); vset(st->L, -1, 0, 0); vset(st->U, 0, 0, -1);
  vcopy(st->refH, st->H); vcopy(st->refU, st->U);
  st->width = o->width; st->scale = 1;
  st->color = st->color2 = o->color;
  st->last = st->tip = st->gc = LSYS_NOREC;
  st->gtan[0] = st->gtan[1] = LSYS_GC_TANGENT;
  t->ngcp = 0;
  for (k = 0; (size_t)k < t->ncs; k++) t->cs[k].valid = 0;
  for (k = 0; (size_t)k < t->npatch; k++) t->patch[k].started = 0;
  if (t->nstess > 0) memset(t->stessok, 0, t->nstess);
  R->ab = ab;
  for (k = 0; k < o->ntrop; k++) st->elast[k] = o->trop[k].elasticity;
  st->oelast = o->oelast;
  st->sides = o->sides;
  if (setring(R) != LSYS_OK) return t->err.code;
  return LSYS_OK;
}

/* Interprets modules [a, b) of 's', whose parameters start at 'off'. */
static int loop (lsys_turtle *t, run *R, const lsys_lstring *s, size_t a, size_t b,
                 size_t off) {
  const uint8_t *s8 = s->sym8, *op = t->op;
  size_t i, nop = t->nop;
  int status = LSYS_OK;
  R->s = s;
  for (i = a; i < b && status == LSYS_OK; i++) {
    uint16_t c = s8 != NULL ? (uint16_t)LSYS_CODE(s8[i], 0) : s->code[i];
    uint32_t sym = LSYS_CSYM(c), np = LSYS_CNP(c);
    double *p = s->par != NULL ? s->par + off : NULL;
    R->mod = i;
    off += np;
    R->nextpar = off;
    if (t->expand != NULL) {
      int e = t->expand(t->expandud, i, off - np, &t->hbuf, &t->err);
      if (e < 0) return e;
      if (e > 0) {                      /* interpret the expansion in place of the module */
        size_t j, hoff = 0;
        /* a rule that runs in Lua may name modules the alphabet did not have when the
        ** run started (cpfg's homomorphisms, vlab's paintbrush): classify them now */
        if (R->ab != NULL && R->ab->n > nop) {
          for (j = 0; j < t->hbuf.n; j++)
            if (LSYS_CSYM(t->hbuf.code[j]) >= nop) break;
          if (j < t->hbuf.n) {
            if ((status = buildops(t, R->ab)) != LSYS_OK) return lsys_turtle_nomem(R);
            op = t->op;
            nop = t->nop;
          }
        }
        for (j = 0; j < t->hbuf.n && status == LSYS_OK; j++) {
          uint16_t hc = t->hbuf.code[j];
          uint32_t hs = LSYS_CSYM(hc), hn = LSYS_CNP(hc);
          if (hs < nop && op[hs]) {
            R->sym = hs;
            R->hj = j; R->hnext = hoff + hn;
            if ((status = ends(R, op[hs])) == LSYS_OK)
              status = module(R, op[hs], hn > 0 ? t->hbuf.par + hoff : NULL, hn, 0);
          }
          hoff += hn;
        }
        for (; e > 1 && i + 1 < b; e--) {      /* modules a predecessor of several took */
          i++;
          off += LSYS_CNP(s8 != NULL ? (uint16_t)LSYS_CODE(s8[i], 0) : s->code[i]);
        }
        continue;
      }
    }
    if (sym < nop && op[sym]) {
      R->sym = sym;
      if ((status = ends(R, op[sym])) == LSYS_OK) status = module(R, op[sym], p, np, 1);
    }
  }
  return status;
}

/* The loop without a homomorphism (most runs, and every piece of a parallel
** run): the string's arrays in locals, R's fields set for the modules that do
** something. */
static int plainloop (lsys_turtle *t, run *R, const lsys_lstring *s, size_t a, size_t b,
                      size_t off) {
  const uint8_t *s8 = s->sym8, *op = t->op;
  const uint16_t *code = s->code;
  double *par = s->par;
  size_t i, nop = t->nop;
  int status = LSYS_OK;
  R->s = s;
  for (i = a; i < b; i++) {
    uint32_t c = s8 != NULL ? (uint32_t)LSYS_CODE(s8[i], 0) : code[i];
    uint32_t sym = LSYS_CSYM(c), np = LSYS_CNP(c);
    int o = sym < nop ? op[sym] : 0;
    if (o != 0) {
      R->mod = i;
      R->nextpar = off + np;
      R->sym = sym;
      if ((status = ends(R, o)) != LSYS_OK ||
          (status = module(R, o, par != NULL ? par + off : NULL, np, 1)) != LSYS_OK)
        break;
    }
    off += np;
  }
  return status;
}

int lsys_turtle_finish (lsys_turtle *t) {
  run *R = (run *)t->runbuf;
  int status = lsys_turtle_capends(R);               /* close the open ends */
  if (status == LSYS_OK && t->npolys > 0)
    lsys_seterror(&t->warn, LSYS_EARG, t->polyfrom, "the polygon '{' of module %zu is never "
                  "closed with '}': it is not drawn", t->polyfrom + 1);
  return status;
}

int lsys_turtle_run (lsys_turtle *t, lsys_lstring *s, const lsys_alphabet *ab) {
  run *R;
  size_t n = s->n;
  int status;
  memset(&t->err, 0, sizeof t->err);
  memset(&t->warn, 0, sizeof t->warn);
  t->npolys = 0; t->nends = 0; t->nsub = 0;
  t->nqueries = 0; t->nsyscalls = 0; t->npieces = 0;
  if ((status = start(t, ab)) != LSYS_OK) return status;
  R = (run *)t->runbuf;
  if (R->draw && t->expand == NULL && (status = lsys_turtle_par(t, s, ab)) != 1)
    return status;
  if (t->mode == LSYS_TURTLE_STATE && t->stop < n) n = t->stop;
  status = t->expand != NULL ? loop(t, R, s, 0, n, 0) : plainloop(t, R, s, 0, n, 0);
  if (status == LSYS_OK) status = flush(R);
  if (status == LSYS_OK && R->draw) status = lsys_turtle_finish(t);
  t->state = R->st;
  return status;
}

int lsys_turtle_runpiece (lsys_turtle *t, const lsys_lstring *s, const lsys_alphabet *ab,
                          size_t a, size_t b, size_t poff, const lsys_tstate *start,
                          const size_t base[4]) {
  run *R;
  int status;
  memset(&t->err, 0, sizeof t->err);
  if ((t->runbuf == NULL && (t->runbuf = LSYS_MALLOC(sizeof *R)) == NULL) ||
      (!t->o->norecords && clearcache(t) != LSYS_OK))
    return lsys_seterror(&t->err, LSYS_ENOMEM, a, "not enough memory");
  R = (run *)t->runbuf;
  memset(R, 0, offsetof(run, cstack));
  memset(&R->depth, 0, sizeof *R - offsetof(run, depth));
  R->tcos = 1;
  R->t = t; R->o = t->o; R->ab = ab;
  R->draw = 1;
  R->fixed = 1;
  R->recbase = base[0]; R->linebase = base[1]; R->ptbase = base[2]; R->shapebase = base[3];
  R->prec = LSYS_NOREC;
  R->stsize = offsetof(lsys_tstate, elast) + (size_t)t->o->ntrop * sizeof(double);
  R->st = *start;
  t->mode = LSYS_TURTLE_DRAW;
  t->mesh = &t->scene->mesh;
  t->npolys = 0; t->nsub = 0;
  status = t->nring == R->st.sides ? LSYS_OK : setring(R);   /* started after an @!(n) */
  if (status == LSYS_OK) status = t->expand != NULL ? loop(t, R, s, a, b, poff)
                                                    : plainloop(t, R, s, a, b, poff);
  if (status == LSYS_OK) status = flush(R);
  t->state = R->st;
  return status;
}
