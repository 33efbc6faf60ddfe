/*
** The turtle: seed 004 Appendix A (interpreted symbols), §2 (discs and
** spheres), §4.2 (polygons and the polygon stack), §6 (tropisms, eq. 1-2;
** twist response §6.1; twist minimisation). See turtle.h.
**
** Rotations, with the frame kept right-handed as L = H x U (cpfg's initial
** frame H = (0,1,0), L = (-1,0,0), U = (0,0,-1)):
**   +  turn left:   H toward L          -  turn right
**   &  pitch down:  H toward -U         ^  pitch up
**   /  roll right:  L toward U          \  roll left
** so that + turns anticlockwise seen from +z, as cpfg does.
*/
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "turtle.h"
#include "polygon.h"
#include "vec3.h"

#define PI 3.14159265358979323846
#define RAD(a) ((a) * (PI / 180.0))
#define NSTACK 64             /* turtle states kept on the C stack */

/* what a symbol does */
enum {
  OP_NONE = 0,
  OP_F, OP_f, OP_G, OP_g,
  OP_LEFT, OP_RIGHT, OP_DOWN, OP_UP, OP_ROLLL, OP_ROLLR, OP_TURN,
  OP_VERT, OP_SETFRAME, OP_MOVETO,
  OP_PUSH, OP_POP,
  OP_WIDER, OP_THINNER, OP_COLINC, OP_COLDEC, OP_TEXTURE, OP_CONTOUR,
  OP_DISCZ, OP_DISC, OP_SPHERE,
  OP_PSTART, OP_PEND, OP_PVERT,
  OP_QP, OP_QH, OP_QU, OP_QL,
  OP_SCALE, OP_SCALEMUL, OP_SCALEDIV,
  OP_LABEL, OP_SYSTEM, OP_STIFF,
  OP_TSET, OP_TINC, OP_TDEC, OP_TPREVENT, OP_TFORCE,
  OP_SUB, OP_SUBEND,
  OP_GSTART, OP_GPOINT, OP_GEND, OP_GTAN, OP_GRAD,
  OP_PSTARTP, OP_PCTRL, OP_PDRAW, OP_SURFACE, OP_NOSURFACE, OP_JOINT
};

static const struct { const char *name; uint8_t op; } symbols[] = {
  {"F", OP_F}, {"f", OP_f}, {"G", OP_G}, {"g", OP_g},
  {"+", OP_LEFT}, {"-", OP_RIGHT}, {"&", OP_DOWN}, {"^", OP_UP},
  {"\\", OP_ROLLL}, {"/", OP_ROLLR}, {"|", OP_TURN},
  {"@v", OP_VERT}, {"@R", OP_SETFRAME}, {"@M", OP_MOVETO},
  {"[", OP_PUSH}, {"]", OP_POP},
  {"#", OP_WIDER}, {"!", OP_THINNER}, {";", OP_COLINC}, {",", OP_COLDEC},
  {"@Tx", OP_TEXTURE}, {"@#", OP_CONTOUR},
  {"@o", OP_DISCZ}, {"@c", OP_DISC}, {"@O", OP_SPHERE},
  {"{", OP_PSTART}, {"}", OP_PEND}, {".", OP_PVERT},
  {"?P", OP_QP}, {"?H", OP_QH}, {"?U", OP_QU}, {"?L", OP_QL},
  {"@D", OP_SCALE}, {"@Di", OP_SCALEMUL}, {"@Dd", OP_SCALEDIV},
  {"@L", OP_LABEL}, {"@S", OP_SYSTEM}, {"Z", OP_STIFF},
  {"@Ts", OP_TSET}, {"@Ti", OP_TINC}, {"@Td", OP_TDEC}, {"@Tp", OP_TPREVENT},
  {"@Tf", OP_TFORCE},
  {"?", OP_SUB}, {"$", OP_SUBEND},
  {"@Gs", OP_GSTART}, {"@Gc", OP_GPOINT}, {"@Ge", OP_GEND}, {"@Gt", OP_GTAN},
  {"@Gr", OP_GRAD}, {"@PS", OP_PSTARTP}, {"@PC", OP_PCTRL}, {"@PD", OP_PDRAW},
  {"@J", OP_JOINT},
  {NULL, 0}
};

/* A polygon being collected (§4.2): its vertices, 3 doubles each. */
struct lsys_polygon {
  double *v; size_t n, cap;
  double H[3], L[3];      /* the turtle's heading and left at the first vertex (§5.3) */
};

/* An open end of a cylinder: its top ring, so that the next segment can
** continue from it or a cap can close it at the end. */
struct lsys_cylend {
  double c[3], H[3], r;
  uint32_t ring;          /* first vertex of the ring (sides + 1 vertices) */
  int color, continued;
};

/* A contour sampled for this run's number of sides (seed 004 §3.2.3). */
struct lsys_csample {
  double *v, *n;          /* sides + 1 vertices and normals */
  uint32_t *cap;          /* end-cap triangles, anticlockwise in the contour's xy */
  size_t vcap, capcap;
  int ncap, left, closed, valid;
};

/* A patch defined by @PS / @PC (§4.3). */
struct lsys_lpatch {
  lsys_patch p;
  int basis, started;
};

#define MAXPATCHES 1024
#define MAXSTRIPS 10000
#define MAXLINES 256

/* Rebuilds an orthonormal frame from H and an approximate U. */
static void orthonormal (lsys_tstate *st) {
  double d;
  if (!vnorm(st->H)) vset(st->H, 0, 1, 0);
  d = vdot(st->U, st->H);
  vlin(st->U, st->U, 1, st->H, -d);
  if (!vnorm(st->U)) {                  /* U parallel to H: any perpendicular */
    double t[3] = {1, 0, 0};
    if (fabs(st->H[0]) > 0.9) vset(t, 0, 0, 1);
    vcross(st->U, t, st->H);
    vnorm(st->U);
  }
  vcross(st->L, st->H, st->U);
}

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
}

void lsys_turtle_init (lsys_turtle *t) {
  memset(t, 0, sizeof *t);
  lsys_lstring_init(&t->hbuf);
}

void lsys_turtle_free (lsys_turtle *t) {
  size_t k;
  for (k = 0; k < t->polycap; k++) LSYS_FREE(t->polys[k].v);
  LSYS_FREE(t->polys);
  LSYS_FREE(t->rec);
  LSYS_FREE(t->stiff);
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
  for (k = 0; k < t->nstess; k++) lsys_mesh_free(&t->stess[k]);
  LSYS_FREE(t->stess);
  LSYS_FREE(t->stessok);
  lsys_lstring_free(&t->hbuf);
  if (t->pw) { lsys_polywork_free(t->pw); LSYS_FREE(t->pw); }
  memset(t, 0, sizeof *t);
}

/* ---------------------------------------------------------------------- */
/* the run */

typedef struct run run;
struct run {
  lsys_turtle *t;
  const lsys_turtle_opts *o;
  lsys_tstate st;
  lsys_tstate cstack[NSTACK];
  size_t depth;                 /* states pushed */
  size_t mod;                   /* the module being interpreted (original index) */
  size_t modtri;                /* the mesh's triangle count when the module began (after
                                   the segment before it was emitted) */
  int draw;                     /* DRAW mode */
  int op;                       /* the operation being interpreted (messages) */
  double tdeg, tcos, tsin;      /* the last turn angle and its cosine and sine */
  size_t stsize;                /* bytes of the state that [ and ] copy */
  /* a segment whose top width may still change (! or # right after F) */
  int pending;
  uint32_t prec;                /* its record */
  double p0[3], p1[3], w0, len;
  int pcol, ptex;
  uint32_t sym;                 /* the symbol being interpreted */
  const lsys_alphabet *ab;
};

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

/* An error about the current module: "module N: <fmt with what>". */
static int fail (run *R, int code, const char *fmt, const char *what) {
  char msg[200];
  snprintf(msg, sizeof msg, fmt, what);
  return lsys_seterror(&R->t->err, code, R->mod, "module %zu: %s", R->mod + 1, msg);
}

/* A failed allocation: the memory budget, when it was the budget that refused. */
static int nomem (run *R) {
  lsys_meter *mt = R->t->meter;
  if (mt != NULL && mt->hit) {
    char b[32], msg[160];
    snprintf(msg, sizeof msg, "the interpretation would need more than max_memory (%s) (set "
             "max_memory in the model, or LSYS_MAX_MEMORY)", lsys_fmtsize(b, mt->limit));
    return fail(R, LSYS_EMEMORY, "%s", msg);
  }
  return fail(R, LSYS_ENOMEM, "%s", "not enough memory");
}

/* The k-th parameter (0-based) of a module with 'np' parameters, or 'def'. */
static const char *opname (int op) {
  int k;
  for (k = 0; symbols[k].name; k++)
    if (symbols[k].op == op) return symbols[k].name;
  return "?";
}

/* An error about the current module: "module N 'op': <printf fmt>". */
static int failop (run *R, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 2, 3)))
#endif
  ;
static int failop (run *R, const char *fmt, ...) {
  char msg[200];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return lsys_seterror(&R->t->err, LSYS_EARG, R->mod, "module %zu '%s': %s", R->mod + 1,
                       opname(R->op), msg);
}

static inline int arg (run *R, const double *p, uint32_t np, uint32_t k, double def,
                       double *out) {
  if (k >= np) { *out = def; return LSYS_OK; }
  if (!isfinite(p[k])) {
    lsys_seterror(&R->t->err, LSYS_EARG, R->mod,
                  "module %zu '%s': parameter %u is not a finite number", R->mod + 1,
                  opname(R->op), k + 1);
    return LSYS_EARG;
  }
  *out = p[k];
  return LSYS_OK;
}

static int newrec (run *R, int kind, const double *p0, const double *p1, double w0,
                   double w1) {
  lsys_turtle *t = R->t;
  lsys_trec *r;
  int k;
  if (R->o->norecords) return LSYS_OK;
  if (t->nrec == t->reccap &&
      lsys_grow_metered((void **)&t->rec, &t->reccap, t->nrec + 1, sizeof *t->rec, t->meter)
      != LSYS_OK)
    return nomem(R);
  if (t->nrec >= LSYS_NOREC) return fail(R, LSYS_ELIMIT, "%s", "too many turtle records");
  r = &t->rec[t->nrec++];
  r->module = (uint32_t)R->mod;
  r->parent = R->st.last;
  r->kind = (uint8_t)kind;
  r->pad = 0;
  r->color = (uint16_t)R->st.color;
  r->w0 = (float)w0; r->w1 = (float)w1;
  r->len = kind == LSYS_REC_SEGMENT || kind == LSYS_REC_GCYL ? (float)sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) +
           (p1[1] - p0[1]) * (p1[1] - p0[1]) + (p1[2] - p0[2]) * (p1[2] - p0[2])) : 0.0f;
  for (k = 0; k < 3; k++) {
    r->p1[k] = (float)p1[k];
    r->H[k] = (float)R->st.H[k]; r->U[k] = (float)R->st.U[k];
  }
  r->tri0 = (uint32_t)R->modtri;
  r->ntri = t->mesh != NULL && t->mesh->nt > R->modtri ? (uint32_t)(t->mesh->nt - R->modtri) : 0;
  r->stiff = LSYS_NOREC;
  if (R->st.hasstiff) {
    if (lsys_grow_metered((void **)&t->stiff, &t->stiffcap, 3 * (t->nstiff + 1), sizeof(float),
                          t->meter) != LSYS_OK)
      return nomem(R);
    r->stiff = (uint32_t)t->nstiff;
    for (k = 0; k < 3; k++) t->stiff[3 * t->nstiff + k] = (float)R->st.stiff[k];
    t->nstiff++;
  }
  return LSYS_OK;
}

/* --- tropisms (seed 004 §6) ------------------------------------------- */

/* Carries the reference frame to the current heading by the smallest
** rotation, which keeps U free of twist (§3.3), then makes it the
** reference. */
static void untwist (lsys_tstate *st) {
  double axis[3], s, c;
  vcross(axis, st->refH, st->H);
  s = vlen(axis);
  c = vdot(st->refH, st->H);
  vcopy(st->U, st->refU);
  if (s > 1e-12) {
    axis[0] /= s; axis[1] /= s; axis[2] /= s;
    vrotate(st->U, axis, atan2(s, c));
  }
  else if (c < 0) {                      /* reversed: turn about the old U */
    vlin(st->U, st->U, 1, st->H, 0);
  }
  orthonormal(st);
  vcopy(st->refH, st->H);
  vcopy(st->refU, st->U);
}

/* Before each move: bends H toward the tropism vectors (eq. 2, which is
** eq. 1 for gamma = 0), removes the twist the bend would add, then turns
** U about H toward the torque vectors (§6.1). */
static void tropisms (run *R) {
  const lsys_turtle_opts *o = R->o;
  lsys_tstate *st = &R->st;
  double A[3] = {0, 0, 0}, a;
  int k, bent = 0, twisted = 0;
  for (k = 0; k < o->ntrop; k++) {
    const lsys_tropism *tp = &o->trop[k];
    double T[3], hxt[3], s, e = st->elast[k], f;
    if (tp->torque || e == 0) continue;
    vcopy(T, tp->vec);
    if (!vnorm(T)) continue;
    vcross(hxt, st->H, T);
    s = vlen(hxt);
    if (s < 1e-12) continue;               /* H along T: no torque */
    f = e * (cos(RAD(tp->angle)) - sin(RAD(tp->angle)) * vdot(st->H, T) / s);
    vlin(A, A, 1, hxt, f);
    bent = 1;
  }
  if (bent && (a = vlen(A)) > 1e-15) {
    double axis[3];
    vlin(axis, A, 1.0 / a, A, 0);
    if (a > 1) a = 1;                      /* at most one radian per segment */
    vrotate(st->H, axis, a);
  }
  if (bent) untwist(st);
  for (k = 0; k < o->ntrop; k++) {
    const lsys_tropism *tp = &o->trop[k];
    double T[3], V[3], hxt[3], c[3], e = st->elast[k], ang, maxang;
    if (!tp->torque || e == 0) continue;
    vcopy(T, tp->vec);
    if (!vnorm(T)) continue;
    vcross(hxt, st->H, T);
    vcross(V, hxt, st->H);                /* T projected on the plane normal to H */
    if (!vnorm(V)) continue;
    ang = e * vlen(hxt);                  /* alpha = e |T x H| */
    vcross(c, st->U, V);
    maxang = atan2(vlen(c), vdot(st->U, V));
    if (ang > maxang) ang = maxang;       /* do not turn past V */
    if (vdot(c, st->H) < 0) ang = -ang;
    vrotate(st->U, st->H, ang);
    vcross(st->L, st->H, st->U);
    twisted = 1;
  }
  if (!bent || twisted) { vcopy(st->refH, st->H); vcopy(st->refU, st->U); }
}

/* --- geometry ----------------------------------------------------------- */

static int setring (run *R) {
  lsys_turtle *t = R->t;
  int n = R->o->sides, k;
  if (t->nring == n && t->ring) return LSYS_OK;
  if (lsys_grow((void **)&t->ringbuf, &t->ringcap, 2 * (size_t)n + 2, sizeof(double)) != LSYS_OK)
    return nomem(R);
  for (k = 0; k <= n; k++) {
    double a = 2 * PI * k / n;
    t->ringbuf[2 * k] = k == n ? 1 : cos(a);
    t->ringbuf[2 * k + 1] = k == n ? 0 : sin(a);
  }
  t->ring = t->ringbuf;
  t->nring = n;
  return LSYS_OK;
}

/* A ring of sides + 1 vertices (the last repeats the first, for uv) around
** 'c' in the plane of L and U; normals tilted by 'slope' along H (tapers). */
static uint32_t ring (run *R, const double *c, double r, double slope, double v, int col) {
  lsys_mesh *m = R->t->mesh;
  const double *cs = R->t->ring;
  int n = R->o->sides, k;
  uint32_t first = (uint32_t)m->nv;
  for (k = 0; k <= n; k++) {
    double d[3], p[3], nn[3];
    vlin(d, R->st.L, cs[2 * k], R->st.U, cs[2 * k + 1]);
    vlin(p, c, 1, d, r);
    vlin(nn, d, 1, R->st.H, slope);
    if (slope != 0) vnorm(nn);
    lsys_mesh_vertex(m, p, nn, (double)k / n, v, (unsigned)col, 0);
  }
  return first;
}

static int cylend (run *R, const double *c, double r, uint32_t rng, int col) {
  lsys_turtle *t = R->t;
  lsys_cylend *e;
  if (t->nends == t->endcap &&
      lsys_grow((void **)&t->ends, &t->endcap, t->nends + 1, sizeof *t->ends) != LSYS_OK)
    return nomem(R);
  e = &t->ends[t->nends++];
  vcopy(e->c, c);
  vcopy(e->H, R->st.H);
  e->r = r;
  e->ring = rng;
  e->color = col;
  e->continued = 0;
  return LSYS_OK;
}

/* A flat cap: a fan around 'c' with normal 'nn', from a ring's positions.
** Rings turn anticlockwise about -H: 'flip' winds the fan for a top cap. */
static void cap (lsys_mesh *m, const double *c, const double *nn, uint32_t rng, int n,
                 int col, int flip) {
  uint32_t first = (uint32_t)m->nv, k;
  lsys_mesh_vertex(m, c, nn, 0.5, 0.5, (unsigned)col, 0);
  for (k = 0; k < (uint32_t)n; k++) {
    double p[3] = {m->pos[3 * (rng + k)], m->pos[3 * (rng + k) + 1], m->pos[3 * (rng + k) + 2]};
    lsys_mesh_vertex(m, p, nn, m->uv[2 * (rng + k)], 0.5, (unsigned)col, 0);
  }
  for (k = 0; k < (uint32_t)n; k++) {
    uint32_t a = first + 1 + k, b = first + 1 + (k + 1) % n;
    if (flip) lsys_mesh_tri(m, first, b, a);
    else lsys_mesh_tri(m, first, a, b);
  }
}

/* Width over height of the current texture (1 without one): v along a
** stem grows by length x aspect / circumference (seed 004 §5.2). */
static double texaspect (run *R) {
  int k = R->st.texture;
  const lsys_texture *tx;
  if (k <= 0 || k > R->o->ntex || (tx = R->o->tex[k - 1]) == NULL || tx->h <= 0) return 1;
  return (double)tx->w / tx->h;
}

/* A cylinder segment from p0 (width w0) to p1 (width w1) around the
** current frame; continues the open end st.tip when it can. */
static int cylinder (run *R, const double *p0, const double *p1, double w0, double w1,
                     double len, int col) {
  lsys_turtle *t = R->t;
  lsys_mesh *m = t->mesh;
  int n = R->o->sides;
  double r0 = w0 / 2, r1 = w1 / 2, slope = len > 0 ? (r0 - r1) / len : 0, v0 = 0;
  uint32_t base = LSYS_NOREC, top, k;
  lsys_cylend *e = R->st.tip != LSYS_NOREC ? &t->ends[R->st.tip] : NULL;
  if (lsys_mesh_reserve(m, 3 * ((size_t)n + 2), 4 * (size_t)n) != LSYS_OK) return nomem(R);
  if (e != NULL) {
    double d[3];
    vlin(d, e->c, 1, p0, -1);
    if (vdot(d, d) <= 1e-18 * (1 + vdot(p0, p0)) && fabs(e->r - r0) <= 1e-9 * (1 + r0) &&
        vdot(e->H, R->st.H) > 0.866 && e->color == col) {
      base = e->ring;                    /* share the ring: no crack, no cap */
      e->continued = 1;
      v0 = m->uv[2 * base + 1];
    }
  }
  if (base == LSYS_NOREC) {
    double back[3];
    base = ring(R, p0, r0, slope, 0, col);
    vlin(back, R->st.H, -1, R->st.H, 0);
    cap(m, p0, back, base, n, col, 0);
  }
  /* v runs along the stem so that texture pixels keep their aspect (§5.2) */
  top = ring(R, p1, r1, slope, v0 + (r0 + r1 > 0 ? len * texaspect(R) / (PI * (r0 + r1)) : 0),
             col);
  for (k = 0; k < (uint32_t)n; k++) {     /* outward facing */
    lsys_mesh_tri(m, base + k, top + k + 1, base + k + 1);
    lsys_mesh_tri(m, base + k, top + k, top + k + 1);
  }
  if (cylend(R, p1, r1, top, col) != LSYS_OK) return LSYS_ENOMEM;
  R->st.tip = (uint32_t)(t->nends - 1);
  return LSYS_OK;
}

/* A flat ribbon in the plane of H and L (line style 'polygon'). */
static int ribbon (run *R, const double *p0, const double *p1, double w0, double w1, int col) {
  lsys_mesh *m = R->t->mesh;
  double a[3], b[3], c[3], d[3];
  uint32_t i;
  if (lsys_mesh_reserve(m, 4, 2) != LSYS_OK) return nomem(R);
  vlin(a, p0, 1, R->st.L, w0 / 2);
  vlin(b, p0, 1, R->st.L, -w0 / 2);
  vlin(c, p1, 1, R->st.L, -w1 / 2);
  vlin(d, p1, 1, R->st.L, w1 / 2);
  i = lsys_mesh_vertex(m, a, R->st.U, 0, 0, (unsigned)col, 1);
  lsys_mesh_vertex(m, b, R->st.U, 1, 0, (unsigned)col, 1);
  lsys_mesh_vertex(m, c, R->st.U, 1, 1, (unsigned)col, 1);
  lsys_mesh_vertex(m, d, R->st.U, 0, 1, (unsigned)col, 1);
  lsys_mesh_tri(m, i, i + 2, i + 1);      /* facing U */
  lsys_mesh_tri(m, i, i + 3, i + 2);
  return LSYS_OK;
}

/* Emits the pending segment with its final top width. */
static int flush (run *R) {
  lsys_tstate *st = &R->st;
  double w1 = st->width * st->scale;
  int s = LSYS_OK;
  if (!R->pending) return LSYS_OK;
  R->pending = 0;
  R->t->mesh->curtex = (unsigned)R->ptex;
  if (R->prec != LSYS_NOREC) R->t->rec[R->prec].w1 = (float)w1;
  switch (R->o->style) {
    case LSYS_STYLE_LINE:
      if (lsys_mesh_line(R->t->mesh, R->p0, R->p1, R->w0, w1, (unsigned)R->pcol) != LSYS_OK)
        s = nomem(R);
      break;
    case LSYS_STYLE_POLYGON: s = ribbon(R, R->p0, R->p1, R->w0, w1, R->pcol); break;
    default: s = cylinder(R, R->p0, R->p1, R->w0, w1, R->len, R->pcol); break;
  }
  return s;
}

static int disc (run *R, const double *c, const double *a, const double *b,
                 const double *nrm, double d, int col) {
  lsys_mesh *m = R->t->mesh;
  const double *cs = R->t->ring;
  int n = R->o->sides, k;
  uint32_t first;
  double ab[3];
  if (lsys_mesh_reserve(m, (size_t)n + 1, (size_t)n) != LSYS_OK) return nomem(R);
  first = lsys_mesh_vertex(m, c, nrm, 0.5, 0.5, (unsigned)col, 1);
  for (k = 0; k < n; k++) {
    double p[3];
    vlin(p, a, cs[2 * k] * d / 2, b, cs[2 * k + 1] * d / 2);
    vlin(p, p, 1, c, 1);
    lsys_mesh_vertex(m, p, nrm, 0.5 + cs[2 * k] / 2, 0.5 + cs[2 * k + 1] / 2, (unsigned)col, 1);
  }
  vcross(ab, a, b);
  for (k = 0; k < n; k++) {               /* wound to face 'nrm' */
    uint32_t u = first + 1 + (uint32_t)k, v = first + 1 + (uint32_t)((k + 1) % n);
    if (vdot(ab, nrm) >= 0) lsys_mesh_tri(m, first, u, v);
    else lsys_mesh_tri(m, first, v, u);
  }
  return LSYS_OK;
}

/* A sphere of diameter d: 'sides' meridians, sides/2 + 1 parallels, with
** its poles on the turtle's H axis. */
static int sphere (run *R, const double *c, double d, int col) {
  lsys_mesh *m = R->t->mesh;
  const double *cs = R->t->ring;
  int n = R->o->sides, rows = n / 2 < 2 ? 2 : n / 2, i, k;
  uint32_t first;
  if (lsys_mesh_reserve(m, (size_t)(rows + 1) * (n + 1), 2 * (size_t)rows * n) != LSYS_OK)
    return nomem(R);
  first = (uint32_t)m->nv;
  for (i = 0; i <= rows; i++) {
    double th = PI * i / rows, ch = cos(th), sh = sin(th);
    for (k = 0; k <= n; k++) {
      double nn[3], p[3];
      vlin(nn, R->st.L, cs[2 * k] * sh, R->st.U, cs[2 * k + 1] * sh);
      vlin(nn, nn, 1, R->st.H, -ch);
      vlin(p, c, 1, nn, d / 2);
      lsys_mesh_vertex(m, p, nn, (double)k / n, (double)i / rows, (unsigned)col, 0);
    }
  }
  for (i = 0; i < rows; i++)
    for (k = 0; k < n; k++) {
      uint32_t a = first + (uint32_t)(i * (n + 1) + k), b = a + (uint32_t)n + 1;
      if (i > 0) lsys_mesh_tri(m, a, b + 1, a + 1);
      if (i < rows - 1) lsys_mesh_tri(m, a, b, b + 1);
    }
  return LSYS_OK;
}

/* --- polygons (§4.2) ------------------------------------------------------ */

static int polyvertex (run *R) {
  lsys_turtle *t = R->t;
  lsys_polygon *p;
  if (t->npolys == 0 || !R->draw) return LSYS_OK;
  p = &t->polys[t->npolys - 1];
  if (lsys_grow((void **)&p->v, &p->cap, 3 * (p->n + 1), sizeof(double)) != LSYS_OK)
    return nomem(R);
  if (p->n == 0) { vcopy(p->H, R->st.H); vcopy(p->L, R->st.L); }
  vcopy(p->v + 3 * p->n++, R->st.pos);
  return LSYS_OK;
}

static int polystart (run *R) {
  lsys_turtle *t = R->t;
  if (!R->draw) { t->npolys++; return LSYS_OK; }
  if (t->npolys == t->polycap) {
    size_t old = t->polycap;
    if (lsys_grow((void **)&t->polys, &t->polycap, t->npolys + 1, sizeof *t->polys) != LSYS_OK)
      return nomem(R);
    memset(t->polys + old, 0, (t->polycap - old) * sizeof *t->polys);
  }
  t->polys[t->npolys++].n = 0;
  return LSYS_OK;
}

static int polyend (run *R) {
  lsys_turtle *t = R->t;
  lsys_polygon *p;
  const uint32_t *tri;
  double nrm[3];
  long nt, k;
  uint32_t first;
  if (t->npolys == 0) return LSYS_OK;        /* a stray '}' is ignored, as cpfg does */
  t->npolys--;
  if (!R->draw) return LSYS_OK;
  p = &t->polys[t->npolys];
  if (p->n < 3) return LSYS_OK;
  if (t->pw == NULL) {
    t->pw = (struct lsys_polywork *)LSYS_MALLOC(sizeof *t->pw);
    if (t->pw == NULL) return nomem(R);
    memset(t->pw, 0, sizeof *t->pw);
  }
  nt = lsys_polygon_triangulate(t->pw, p->v, p->n, nrm, &tri);
  if (nt < 0) return nomem(R);
  if (lsys_mesh_reserve(t->mesh, p->n, (size_t)nt) != LSYS_OK) return nomem(R);
  first = (uint32_t)t->mesh->nv;
  t->mesh->curtex = (unsigned)R->st.texture;
  {
    /* uv: the coordinates along the right (-L) and heading axes, from the
    ** first vertex, scaled to 0..1 over the polygon (seed 004 §5.3) */
    double lo[2] = {0, 0}, hi[2] = {0, 0}, d[3], c[2];
    for (k = 0; k < (long)p->n; k++) {
      vlin(d, p->v + 3 * k, 1, p->v, -1);
      c[0] = -vdot(d, p->L); c[1] = vdot(d, p->H);
      if (c[0] < lo[0]) lo[0] = c[0];
      if (c[0] > hi[0]) hi[0] = c[0];
      if (c[1] < lo[1]) lo[1] = c[1];
      if (c[1] > hi[1]) hi[1] = c[1];
    }
    for (k = 0; k < (long)p->n; k++) {
      const double *v = p->v + 3 * k;
      vlin(d, v, 1, p->v, -1);
      c[0] = -vdot(d, p->L); c[1] = vdot(d, p->H);
      lsys_mesh_vertex(t->mesh, v, nrm, hi[0] > lo[0] ? (c[0] - lo[0]) / (hi[0] - lo[0]) : 0,
                       hi[1] > lo[1] ? (c[1] - lo[1]) / (hi[1] - lo[1]) : 0,
                       (unsigned)R->st.color, 1);
    }
  }
  for (k = 0; k < nt; k++)
    lsys_mesh_tri(t->mesh, first + tri[3 * k], first + tri[3 * k + 1], first + tri[3 * k + 2]);
  return newrec(R, LSYS_REC_POLYGON, p->v + 3 * (p->n - 1), p->v + 3 * (p->n - 1), 0, 0);
}

/* --- generalized cylinders (§3) -------------------------------------------- */

/* The contour 'id' sampled with this run's sides, computed on first use. */
static const lsys_csample *csample (run *R, int id) {
  lsys_turtle *t = R->t;
  lsys_csample *c;
  int p = R->o->sides, k;
  size_t need = 3 * ((size_t)p + 1);
  if ((size_t)id >= t->ncs) {
    size_t old = t->ncs, cap = t->ncs;
    if (lsys_grow((void **)&t->cs, &cap, (size_t)id + 1, sizeof *t->cs) != LSYS_OK) return NULL;
    memset(t->cs + old, 0, (cap - old) * sizeof *t->cs);
    t->ncs = cap;
  }
  c = &t->cs[id];
  if (c->valid) return c;
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
    if (t->pw == NULL) {
      t->pw = (struct lsys_polywork *)LSYS_MALLOC(sizeof *t->pw);
      if (t->pw == NULL) return NULL;
      memset(t->pw, 0, sizeof *t->pw);
    }
    nt = lsys_polygon_triangulate(t->pw, c->v, (size_t)p, nrm, &tri);
    if (nt < 0) return NULL;
    if (lsys_grow((void **)&c->cap, &c->capcap, 3 * (size_t)(nt + 1), sizeof(uint32_t)) != LSYS_OK)
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
  if (t->ngcp >= UINT32_MAX - 1) return fail(R, LSYS_ELIMIT, "%s", "too many control points");
  if (t->ngcp == t->gcpcap &&
      lsys_grow((void **)&t->gcp, &t->gcpcap, t->ngcp + 1, sizeof *t->gcp) != LSYS_OK)
    return nomem(R);
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

/* @Gs, @Gc(n), @Ge(n) (§3.1): a control point, and the strips from the
** active one (a branch continues from the point active where it began,
** §3.4). */
static int gcmodule (run *R, int op, const double *p, uint32_t np) {
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
      return failop(R, "the number of strips must be from 1 to %d, got %g", MAXSTRIPS, x);
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
  if (sb == NULL) return nomem(R);
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
  if (lsys_gcyl_segment(t->mesh, a, b, &sh, &ca, &cb, R->o->sides) != LSYS_OK) return nomem(R);
  if ((s = newrec(R, LSYS_REC_GCYL, a->pos, b->pos, 2 * a->r, 2 * b->r)) != LSYS_OK) return s;
  if (!R->o->norecords) {                 /* runs along the chord, so that p0 = a */
    lsys_trec *r = &t->rec[t->nrec - 1];
    double c[3], u[3];
    int k;
    vlin(c, b->pos, 1, a->pos, -1);
    if (vnorm(c)) {
      vlin(u, st->U, 1, c, -vdot(st->U, c));
      if (!vnorm(u)) vcopy(u, st->H);
      for (k = 0; k < 3; k++) { r->H[k] = (float)c[k]; r->U[k] = (float)u[k]; }
    }
  }
  st->gc = op == OP_GEND ? LSYS_NOREC : ib;
  return LSYS_OK;
}

/* @Gt(c0[,c1]) and @Gr(flag) / @Gr(a,l) / @Gr(a0,l0,a1,l1) (§3.2.1-2). */
static int gcshape (run *R, int op, const double *p, uint32_t np) {
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
    case 3: return failop(R, "takes 1, 2 or 4 parameters, not 3");
    default: memcpy(st->grad, v, sizeof st->grad); return LSYS_OK;
  }
}

/* --- surfaces (§4.1, §4.3) ---------------------------------------------- */

static void place (run *R, lsys_place *pl, double scale, int tex) {
  lsys_tstate *st = &R->st;
  vcopy(pl->origin, st->pos);
  vcopy(pl->H, st->H); vcopy(pl->L, st->L); vcopy(pl->U, st->U);
  pl->scale = scale;
  pl->color = (unsigned)st->color;
  pl->uv_surface = tex > 0 && tex <= R->o->ntex && R->o->tex[tex - 1]->per_surface;
  R->t->mesh->curtex = (unsigned)tex;
}

/* Surface k of the view tessellated in its own frame (contact point at the
** origin, SIZE 1), once per run and uv mode: every ~X then only turns and
** scales a copy. */
static const lsys_mesh *surftess (run *R, int k, int uvsurf, int *status) {
  lsys_turtle *t = R->t;
  const lsys_surfuse *u = &R->o->surfaces[k];
  size_t slot = 2 * (size_t)k + (size_t)uvsurf;
  lsys_place pl;
  if (slot >= t->nstess) {
    size_t n = 2 * (size_t)R->o->nsurfaces, j;
    lsys_mesh *m = (lsys_mesh *)LSYS_REALLOC(t->stess, n * sizeof *m);
    uint8_t *ok = m ? (uint8_t *)LSYS_REALLOC(t->stessok, n) : NULL;
    if (m) t->stess = m;
    if (ok == NULL) { *status = nomem(R); return NULL; }
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
    if ((s = lsys_surface_mesh(m, u->s, &pl, u->ns, u->nt)) != LSYS_OK) {
      *status = s == LSYS_ENOMEM ? nomem(R) : failop(R, "cannot tessellate the surface");
      return NULL;
    }
    t->stessok[slot] = 1;
  }
  return &t->stess[slot];
}

/* ~X(s): the view's surface X at the turtle, scaled by s; the turtle then
** stands at the surface's end point. */
static int surface (run *R, uint32_t sym, const double *p, uint32_t np) {
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
  if (R->draw) {
    lsys_mesh *m = R->t->mesh;
    const lsys_mesh *tm = surftess(R, k, pl.uv_surface, &s);
    double Rw[3][3], kk = pl.scale / (u->s->size > 0 ? u->s->size : 1), LS[3];
    uint32_t first;
    size_t i;
    int a, b;
    if (tm == NULL) return s;
    if (lsys_mesh_reserve(m, tm->nv, tm->nt) != LSYS_OK) return nomem(R);
    vcross(LS, u->s->heading, u->s->up);
    for (a = 0; a < 3; a++)              /* H_S -> H, U_S -> U, H_S x U_S -> L */
      for (b = 0; b < 3; b++)
        Rw[a][b] = st->L[a] * LS[b] + st->H[a] * u->s->heading[b] + st->U[a] * u->s->up[b];
    first = (uint32_t)m->nv;
    for (i = 0; i < tm->nv; i++) {
      const float *q = tm->pos + 3 * i, *n = tm->nrm + 3 * i;
      double P[3], N[3];
      for (a = 0; a < 3; a++) {
        P[a] = st->pos[a] + kk * (Rw[a][0] * q[0] + Rw[a][1] * q[1] + Rw[a][2] * q[2]);
        N[a] = Rw[a][0] * n[0] + Rw[a][1] * n[1] + Rw[a][2] * n[2];
      }
      lsys_mesh_vertex(m, P, N, tm->uv[2 * i], tm->uv[2 * i + 1], pl.color, 1);
    }
    for (i = 0; i < tm->nt; i++)
      lsys_mesh_tri(m, first + tm->tri[3 * i], first + tm->tri[3 * i + 1], first + tm->tri[3 * i + 2]);
  }
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
  if (!(x >= lo && x <= hi)) return failop(R, "%s must be from %d to %d, got %g", what, lo, hi, x);
  *out = (int)x;
  return LSYS_OK;
}

/* @PS(i[,basis]), @PC(i,r,c), @PD(i,s,t) (§4.3, Appendix A). */
static int patchmodule (run *R, int op, const double *p, uint32_t np) {
  lsys_turtle *t = R->t;
  lsys_lpatch *pt;
  int i, a, b, s;
  if (np == 0) return failop(R, "needs a patch number");
  if ((s = intarg(R, p, np, 0, 0, 0, MAXPATCHES - 1, "the patch number", &i)) != LSYS_OK)
    return s;
  if ((size_t)i >= t->npatch) {
    size_t old = t->npatch, cap = t->npatch;
    if (lsys_grow((void **)&t->patch, &cap, (size_t)i + 1, sizeof *t->patch) != LSYS_OK)
      return nomem(R);
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
      if (np < 3) return failop(R, "needs a patch, a row and a column");
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
        return s == LSYS_ENOMEM ? nomem(R) : fail(R, s, "%s", "the scene is too big");
      return newrec(R, LSYS_REC_SURFACE, R->st.pos, R->st.pos, 0, 0);
    }
  }
  return failop(R, "patch %d was not started with @PS(%d)", i, i);
}

/* --- moves ------------------------------------------------------------- */

static int move (run *R, int op, double d) {
  lsys_tstate *st = &R->st;
  double p0[3];
  int s;
  if ((s = flush(R)) != LSYS_OK) return s;
  if (R->o->ntrop > 0) tropisms(R);
  d *= st->scale;
  vcopy(p0, st->pos);
  vlin(st->pos, st->pos, 1, st->H, d);
  if (op == OP_f || op == OP_g) {
    st->tip = LSYS_NOREC;
    return op == OP_f && R->t->npolys > 0 ? polyvertex(R) : LSYS_OK;
  }
  if (op == OP_F && R->t->npolys > 0)       /* an edge of a polygon, not drawn */
    return polyvertex(R);
  if (!R->draw) return LSYS_OK;
  /* a drawn segment; its top width waits for a following ! or # */
  if ((s = newrec(R, LSYS_REC_SEGMENT, p0, st->pos, st->width * st->scale,
                  st->width * st->scale)) != LSYS_OK)
    return s;
  st->hasstiff = 0;
  R->prec = R->o->norecords ? LSYS_NOREC : (uint32_t)(R->t->nrec - 1);
  st->last = R->prec;
  R->pending = 1;
  vcopy(R->p0, p0);
  vcopy(R->p1, st->pos);
  R->w0 = st->width * st->scale;
  R->len = fabs(d);
  R->pcol = st->color;
  R->ptex = st->texture;
  return LSYS_OK;
}

/* --- stack ------------------------------------------------------------- */

static int push (run *R) {
  lsys_turtle *t = R->t;
  lsys_tstate *to;
  if (R->depth < NSTACK) to = &R->cstack[R->depth];
  else {
    size_t k = R->depth - NSTACK;
    if (k >= t->stackcap &&
        lsys_grow_metered((void **)&t->stack, &t->stackcap, k + 1, sizeof *t->stack, t->meter)
        != LSYS_OK)
      return nomem(R);
    to = &t->stack[k];
  }
  memcpy(to, &R->st, R->stsize);
  R->depth++;
  return LSYS_OK;
}

static void pop (run *R) {
  if (R->depth == 0) return;                 /* unbalanced ']': ignored, as cpfg does */
  R->depth--;
  memcpy(&R->st, R->depth < NSTACK ? &R->cstack[R->depth] : &R->t->stack[R->depth - NSTACK],
         R->stsize);
}

/* --- one module ---------------------------------------------------------- */

static void query (run *R, int op, double *p, uint32_t np) {
  const double *v = op == OP_QP ? R->st.pos : op == OP_QH ? R->st.H
                  : op == OP_QU ? R->st.U : R->st.L;
  uint32_t k;
  for (k = 0; k < np && k < 3; k++) p[k] = v[k];
  R->t->nqueries++;
}

/* A colour, texture or contour index from a parameter: truncated, kept in
** 0..65535 (a huge parameter must not overflow the conversion to int). */
static int toindex (double x) {
  return x <= 0 ? 0 : x >= 65535 ? 65535 : (int)x;
}

static int tropindex (run *R, const double *p, uint32_t np, int *k) {
  *k = 0;
  double x;
  int s;
  if (np == 0) return fail(R, LSYS_EARG, "%s needs a tropism index", opname(R->op));
  if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
  if (x < 1 || x > R->o->ntrop || x != floor(x)) {
    lsys_seterror(&R->t->err, LSYS_EARG, R->mod,
                  "module %zu '%s': tropism index %g is not one of the view's %d tropisms",
                  R->mod + 1, opname(R->op), x, R->o->ntrop);
    return LSYS_EARG;
  }
  *k = (int)x - 1;
  return LSYS_OK;
}

static int module (run *R, int op, double *p, uint32_t np, int original) {
  lsys_tstate *st = &R->st;
  const lsys_turtle_opts *o = R->o;
  double x = 0;
  int s = LSYS_OK, k;
  R->op = op;
  /* width changes right after a segment set its top width */
  if (op != OP_WIDER && op != OP_THINNER && R->pending && (s = flush(R)) != LSYS_OK) return s;
  R->modtri = R->t->mesh != NULL ? R->t->mesh->nt : 0;   /* what this module draws starts here */
  switch (op) {
    case OP_F: case OP_G: case OP_f: case OP_g:
      if ((s = arg(R, p, np, 0, o->step, &x)) != LSYS_OK) return s;
      return move(R, op, x);
    case OP_LEFT: case OP_RIGHT: case OP_DOWN: case OP_UP: case OP_ROLLL: case OP_ROLLR:
      if ((s = arg(R, p, np, 0, o->angle, &x)) != LSYS_OK) return s;
      switch (op) {
        case OP_LEFT: turn(R, st->H, st->L, x); break;
        case OP_RIGHT: turn(R, st->H, st->L, -x); break;
        case OP_DOWN: turn(R, st->H, st->U, -x); break;
        case OP_UP: turn(R, st->H, st->U, x); break;
        case OP_ROLLR: turn(R, st->L, st->U, x); break;
        default: turn(R, st->L, st->U, -x); break;
      }
      return LSYS_OK;
    case OP_JOINT: {
      /* @J(h, u, l): an arranged joint (seed 000 §3.1, ik.h): right-handed
      ** turns in degrees about H, then the new U, then the new L, where L is
      ** taken as U x H; the turtle's own L keeps its orientation to it */
      double a[3], Lr[3], sign;
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
    case OP_TURN:
      vlin(st->H, st->H, -1, st->H, 0);
      vlin(st->L, st->L, -1, st->L, 0);
      return LSYS_OK;
    case OP_VERT: {             /* H and U in a vertical plane, U up (y is up) */
      double V[3] = {0, 1, 0}, l[3];
      vcross(l, st->H, V);
      if (vnorm(l)) { vcopy(st->L, l); vcross(st->U, st->L, st->H); }
      return LSYS_OK;
    }
    case OP_SETFRAME: {
      double v[6];
      if (np < 3) return fail(R, LSYS_EARG, "%s needs a heading (3 or 6 parameters)",
                             opname(op));
      for (k = 0; k < 6; k++)
        if ((s = arg(R, p, np, (uint32_t)k, k < 3 ? 0 : st->U[k - 3], &v[k])) != LSYS_OK)
          return s;
      vcopy(st->H, v);
      vcopy(st->U, v + 3);
      orthonormal(st);
      return LSYS_OK;
    }
    case OP_MOVETO:
      for (k = 0; k < 3; k++)
        if ((s = arg(R, p, np, (uint32_t)k, st->pos[k], &st->pos[k])) != LSYS_OK)
          return s;
      st->tip = LSYS_NOREC;
      return LSYS_OK;
    case OP_PUSH: return push(R);
    case OP_POP: pop(R); return LSYS_OK;
    case OP_WIDER: case OP_THINNER:
      if (np > 0) { if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s; }
      else x = st->width + (op == OP_WIDER ? o->dwidth : -o->dwidth);
      st->width = x < 0 ? 0 : x;
      return LSYS_OK;
    case OP_COLINC: case OP_COLDEC:
      if (np > 0) {
        if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
        st->color = st->color2 = toindex(x);
        if (np > 1 && (s = arg(R, p, np, 1, 0, &x)) == LSYS_OK) st->color2 = toindex(x);
      }
      else {
        st->color += op == OP_COLINC ? o->dcolor : -o->dcolor;
        st->color2 += op == OP_COLINC ? o->dcolor : -o->dcolor;
      }
      if (st->color < 0) st->color = 0;
      if (st->color > 65535) st->color = 65535;
      if (st->color2 < 0) st->color2 = 0;
      if (st->color2 > 65535) st->color2 = 65535;
      return s;
    case OP_TEXTURE:
      if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
      k = toindex(x);
      if (k > o->ntex)
        return failop(R, "texture %d is not defined (the view has %d; view.textures)", k,
                      o->ntex);
      st->texture = k;
      return LSYS_OK;
    case OP_CONTOUR:
      if ((s = arg(R, p, np, 0, 0, &x)) != LSYS_OK) return s;
      k = toindex(x);
      if (k != 0 && (k >= o->ncontours || o->contours[k] == NULL))
        return failop(R, "contour %d is not defined (view.contours; 0 is the circle)", k);
      st->contour = k;
      return LSYS_OK;
    case OP_GSTART: case OP_GPOINT: case OP_GEND: return gcmodule(R, op, p, np);
    case OP_GTAN: case OP_GRAD: return gcshape(R, op, p, np);
    case OP_PSTARTP: case OP_PCTRL: case OP_PDRAW: return patchmodule(R, op, p, np);
    case OP_SURFACE: return surface(R, R->sym, p, np);
    case OP_NOSURFACE:
      return lsys_seterror(&R->t->err, LSYS_EARG, R->mod,
                           "module %zu '%s': no such surface in the view (view.surfaces)",
                           R->mod + 1, lsys_alphabet_name(R->ab, R->sym));
    case OP_DISCZ: case OP_DISC: case OP_SPHERE:
      if ((s = arg(R, p, np, 0, st->width, &x)) != LSYS_OK) return s;
      x *= st->scale;
      if (!R->draw) return LSYS_OK;
      R->t->mesh->curtex = (unsigned)st->texture;
      if (op == OP_SPHERE) s = sphere(R, st->pos, x, st->color);
      else if (op == OP_DISC) s = disc(R, st->pos, st->H, st->L, st->U, x, st->color);
      else {
        double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
        s = disc(R, st->pos, ex, ey, ez, x, st->color);
      }
      if (s != LSYS_OK) return s;
      return newrec(R, op == OP_SPHERE ? LSYS_REC_SPHERE : LSYS_REC_DISC, st->pos, st->pos, x, x);
    case OP_PSTART: return polystart(R);
    case OP_PEND: return polyend(R);
    case OP_PVERT: return polyvertex(R);
    case OP_QP: case OP_QH: case OP_QU: case OP_QL:
      if (original && R->t->mode == LSYS_TURTLE_QUERY) query(R, op, p, np);
      return LSYS_OK;
    case OP_SCALE: case OP_SCALEMUL: case OP_SCALEDIV:
      if ((s = arg(R, p, np, 0, 1, &x)) != LSYS_OK) return s;
      if (op == OP_SCALE) st->scale = x;
      else if (op == OP_SCALEMUL) st->scale *= x;
      else if (x != 0) st->scale /= x;
      else return fail(R, LSYS_EARG, "%s: division of the scale by 0", opname(op));
      return LSYS_OK;
    case OP_LABEL:
      return R->draw ? newrec(R, LSYS_REC_LABEL, st->pos, st->pos, 0, 0) : LSYS_OK;
    case OP_SYSTEM:
      if (!o->allow_system)
        return lsys_seterror(&R->t->err, LSYS_EARG, R->mod,
                             "module %zu '@S' (system call) refused: system calls are off "
                             "unless the model sets allow_system_calls = true", R->mod + 1);
      R->t->nsyscalls++;
      return R->draw ? newrec(R, LSYS_REC_SYSTEM, st->pos, st->pos, 0, 0) : LSYS_OK;
    case OP_STIFF:
      for (k = 0; k < 3; k++)
        if ((s = arg(R, p, np, (uint32_t)k, k == 0 ? 0 : st->stiff[k - 1],
                     &st->stiff[k])) != LSYS_OK)
          return s;
      st->hasstiff = np > 0;
      return LSYS_OK;
    case OP_TSET: case OP_TINC: case OP_TDEC:
      if ((s = tropindex(R, p, np, &k)) != LSYS_OK) return s;
      if (op == OP_TSET) {
        if (np < 2) return fail(R, LSYS_EARG, "%s needs an index and a value", opname(op));
        if ((s = arg(R, p, np, 1, 0, &x)) != LSYS_OK) return s;
        st->elast[k] = x;
      }
      else {
        if ((s = arg(R, p, np, 1, o->trop[k].increment, &x)) != LSYS_OK) return s;
        st->elast[k] += op == OP_TINC ? x : -x;
      }
      return LSYS_OK;
    case OP_TPREVENT: untwist(st); return LSYS_OK;
    case OP_TFORCE: vcopy(st->refH, st->H); vcopy(st->refU, st->U); return LSYS_OK;
    case OP_SUB: {
      lsys_turtle *t = R->t;
      if ((s = arg(R, p, np, 1, 1, &x)) != LSYS_OK) return s;
      if (lsys_grow((void **)&t->subscale, &t->subcap, t->nsub + 1, sizeof(double)) != LSYS_OK)
        return nomem(R);
      t->subscale[t->nsub++] = st->scale;
      st->scale *= x;
      return LSYS_OK;
    }
    case OP_SUBEND:
      if (R->t->nsub > 0) st->scale = R->t->subscale[--R->t->nsub];
      return LSYS_OK;
    default:
      return LSYS_OK;
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
  for (k = 0; symbols[k].name; k++) {
    uint32_t id = lsys_alphabet_find(ab, symbols[k].name, strlen(symbols[k].name));
    if (id != 0 && id < ab->n) t->op[id] = symbols[k].op;
  }
  /* ~X: a view surface, or an error when the view has none called X */
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

int lsys_turtle_run (lsys_turtle *t, lsys_lstring *s, const lsys_alphabet *ab) {
  run *R;
  lsys_tstate *st;
  size_t i, off = 0;
  int k, status = LSYS_OK;
  const lsys_turtle_opts *o = t->o;
  memset(&t->err, 0, sizeof t->err);
  t->nrec = 0; t->nstiff = 0; t->npolys = 0; t->nends = 0; t->nsub = 0; t->nqueries = 0; t->nsyscalls = 0;
  if (o == NULL || (t->mode == LSYS_TURTLE_DRAW && t->mesh == NULL))
    return lsys_seterror(&t->err, LSYS_EARG, (size_t)-1, "turtle without options or mesh");
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
  R->t = t; R->o = o;
  R->draw = t->mode == LSYS_TURTLE_DRAW;
  R->prec = LSYS_NOREC;
  R->stsize = offsetof(lsys_tstate, elast) + (size_t)o->ntrop * sizeof(double);
  if (R->draw) lsys_mesh_clear(t->mesh);
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
  if (setring(R) != LSYS_OK) return t->err.code;
  for (i = 0; i < s->n && status == LSYS_OK; i++) {
    uint16_t c = s->code[i];
    uint32_t sym = LSYS_CSYM(c), np = LSYS_CNP(c);
    double *p = s->par != NULL ? s->par + off : NULL;
    if (t->mode == LSYS_TURTLE_STATE && i >= t->stop) break;
    R->mod = i;
    off += np;
    if (t->expand != NULL) {
      int e = t->expand(t->expandud, i, off - np, &t->hbuf, &t->err);
      if (e < 0) { status = e; break; }
      if (e > 0) {                      /* interpret the expansion in place of the module */
        size_t j, hoff = 0;
        for (j = 0; j < t->hbuf.n && status == LSYS_OK; j++) {
          uint16_t hc = t->hbuf.code[j];
          uint32_t hs = LSYS_CSYM(hc), hn = LSYS_CNP(hc);
          if (hs < t->nop && t->op[hs]) {
            R->sym = hs;
            status = module(R, t->op[hs], hn > 0 ? t->hbuf.par + hoff : NULL, hn, 0);
          }
          hoff += hn;
        }
        goto next;
      }
    }
    if (sym < t->nop && t->op[sym]) {
      R->sym = sym;
      status = module(R, t->op[sym], p, np, 1);
    }
  next:;
  }
  if (status == LSYS_OK) status = flush(R);
  if (status == LSYS_OK && R->draw) {      /* close the open cylinder ends */
    lsys_mesh *m = t->mesh;
    size_t e;
    for (e = 0; e < t->nends && status == LSYS_OK; e++) {
      lsys_cylend *ce = &t->ends[e];
      if (ce->continued) continue;
      if (lsys_mesh_reserve(m, (size_t)o->sides + 1, (size_t)o->sides) != LSYS_OK)
        status = nomem(R);
      else cap(m, ce->c, ce->H, ce->ring, o->sides, ce->color, 1);
    }
  }
  t->state = R->st;
  return status;
}
