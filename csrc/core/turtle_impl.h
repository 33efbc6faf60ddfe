/*
** What the turtle's files share (not part of the API; see turtle.h). The
** turtle (turtle.c) keeps the state and dispatches the commands; each
** geometry kind is built in a file of its own (a reader finds each
** geometry kind in one file; docs/architecture.md):
**   turtle_cyl.c      cylinder segments, their rings and end caps (line style cylinder)
**   turtle_ribbon.c   flat ribbons (line style polygon)
**   turtle_disc.c     discs, @c and @o (cpfg guide §2)
**   turtle_sphere.c   spheres, @O (cpfg guide §2)
**   turtle_polygon.c  polygons and the polygon stack, { . } (cpfg guide §4.2)
**   turtle_gcyl.c     generalized cylinders, @Gs @Gc @Ge @Gt @Gr (cpfg guide §3)
**   turtle_surface.c  predefined surfaces ~X and patches @PS @PC @PD (cpfg guide §4.1, §4.3)
** The helpers every module may call (arg, newrec) are static inline here, so
** the interpretation loop pays no call for them.
*/
#ifndef LSYS_TURTLE_IMPL_H
#define LSYS_TURTLE_IMPL_H

#include <math.h>

#include "symbols.h"
#include "turtle.h"
#include "vec3.h"

#define PI 3.14159265358979323846
#define RAD(a) ((a) * (PI / 180.0))
#define NSTACK 64             /* turtle states kept on the C stack */

/* what a symbol does: OP_<op> for each row of the symbol table (symbols.h) */
#define OP_ENUM(op, name, split, keep, query) OP_##op,
enum { LSYS_SYMBOLS(OP_ENUM) OP_COUNT };
#undef OP_ENUM

/* A polygon being collected (§4.2): its vertices, 3 doubles each. */
struct lsys_polygon {
  double *v; size_t n, cap;
  double H[3], L[3];      /* the turtle's heading and left at the first vertex (§5.3) */
};

/* An open end of a cylinder: its top ring, so that the next segment can
** continue from it or a cap can close it at the end. */
struct lsys_cylend {
  double c[3], H[3], r;
  double L[3];            /* where the ring's first vertex points from c (unit) */
  double u0, v;           /* the ring's texture coordinates: u of its first vertex, v */
  uint32_t ring;          /* first vertex of the ring (sides + 1 vertices) */
  int color, continued;
  int sides;              /* the state's sides when it was drawn */
};

/* A contour sampled for this run's number of sides (cpfg guide §3.2.3). */
struct lsys_csample {
  double *v, *n;          /* sides + 1 vertices and normals */
  uint32_t *cap;          /* end-cap triangles, anticlockwise in the contour's xy */
  size_t vcap, capcap;
  int ncap, left, closed, valid;
  int sides;              /* the sides it was sampled with */
};

/* A patch defined by @PS / @PC (§4.3). */
struct lsys_lpatch {
  lsys_patch p;
  int basis, started;
};

/* One interpretation: the turtle state and what the current module needs. */
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
  /* a segment whose top width may still change: cpfg ends a segment at the next
  ** F f G g [ ] { } ~ or @ module (its EndNode), so a ! or # before that sets the
  ** top width; the frame and sides are the segment's own */
  int pending;
  uint32_t prec;                /* its record */
  double p0[3], p1[3], w0, len;
  double pH[3], pL[3], pU[3];
  int pcol, ptex, psides;
  uint32_t sym;                 /* the symbol being interpreted */
  /* what follows the module being interpreted (a ?E sends it): the string's next module,
  ** or, inside an expansion, the expansion's next (hj < hbuf.n: j, with its parameters at
  ** hnext of hbuf) */
  const lsys_lstring *s;
  size_t nextpar;               /* the string's next module's parameters */
  size_t hj, hnext;             /* in an expansion: the module's place, the next's parameters */
  const lsys_alphabet *ab;
  size_t recbase;               /* the scene's index of the first record this run writes */
  int fixed;                    /* a piece of a parallel run (turtle_par.c): the records and
                                   lines go to places counted beforehand and cannot grow */
};

/* turtle_env.c: ?E, a query of the environment appended to t->envq. */
int lsys_turtle_envquery (run *R, const double *p, uint32_t np, int original);

/* turtle.c: errors about the current module, "module N: <fmt>" and
** "module N 'op': <fmt>" (code LSYS_EARG), and a failed allocation (the
** memory budget's message when the budget refused). */
int lsys_turtle_fail (run *R, int code, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 3, 4)))
#endif
  ;
int lsys_turtle_failop (run *R, const char *fmt, ...)
#if defined(__GNUC__)
  __attribute__((format(printf, 2, 3)))
#endif
  ;
int lsys_turtle_nomem (run *R);

/* The k-th parameter (0-based) of a module with 'np' parameters, or 'def'. */
static inline int arg (run *R, const double *p, uint32_t np, uint32_t k, double def,
                       double *out) {
  if (k >= np) { *out = def; return LSYS_OK; }
  if (!isfinite(p[k])) {
    lsys_turtle_failop(R, "parameter %u is not a finite number", k + 1);
    return LSYS_EARG;
  }
  *out = p[k];
  return LSYS_OK;
}

/* A record of 'kind' for the current module, from p0 to p1 (a segment's
** length is their distance), in the turtle's present frame. */
static inline int newrec (run *R, int kind, const double *p0, const double *p1, double w0,
                          double w1) {
  lsys_turtle *t = R->t;
  lsys_scene *S = t->scene;
  lsys_trec *r;
  int k;
  if (R->o->norecords) return LSYS_OK;
  if (S->nrec == S->reccap) {
    if (R->fixed) return lsys_turtle_fail(R, LSYS_ELIMIT, "internal error: records miscounted");
    if (lsys_scene_reserve_records(S, 1) != LSYS_OK) return lsys_turtle_nomem(R);
  }
  if (R->recbase + S->nrec >= LSYS_NOREC)
    return lsys_turtle_fail(R, LSYS_ELIMIT, "too many turtle records");
  r = &S->rec[S->nrec++];
  r->module = (uint32_t)R->mod;
  r->parent = R->st.last;
  r->kind = (uint8_t)kind;
  r->pad = 0;
  r->color = (uint16_t)R->st.color;
  r->w0 = (float)w0; r->w1 = (float)w1;
  r->len = kind == LSYS_REC_SEGMENT || kind == LSYS_REC_GCYL
           ? (float)sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                         (p1[2] - p0[2]) * (p1[2] - p0[2]))
           : 0.0f;
  for (k = 0; k < 3; k++) {
    r->p1[k] = (float)p1[k];
    r->H[k] = (float)R->st.H[k]; r->U[k] = (float)R->st.U[k];
  }
  r->tri0 = (uint32_t)R->modtri;
  r->ntri = t->mesh != NULL && t->mesh->nt > R->modtri ? (uint32_t)(t->mesh->nt - R->modtri) : 0;
  r->stiff = LSYS_NOREC;
  if (R->st.hasstiff) {
    if (lsys_scene_add_stiffness(S, R->st.stiff, &r->stiff) != LSYS_OK)
      return lsys_turtle_nomem(R);
  }
  return LSYS_OK;
}

/* turtle.c: runs modules [a, b) of 's' (parameters from 'poff') from the state
** 'start' into t->scene, whose records and lines have exactly the room this piece
** needs; its first record is the scene's 'recbase'-th. t->op, t->ring and t->o are
** set (borrowed from the turtle that split the run); t->ends may hold the open end
** the start state continues. The pending segment is emitted at the end; t->state
** is the state there. LSYS_OK or an error with t->err set. */
int lsys_turtle_runpiece (lsys_turtle *t, const lsys_lstring *s, const lsys_alphabet *ab,
                          size_t a, size_t b, size_t poff, const lsys_tstate *start,
                          size_t recbase);

/* turtle_par.c: lsys_turtle_run's DRAW mode on t->threads threads, after start()
** readied t->runbuf. Returns 1 when the string is not for it (too short, or a
** module whose effect crosses branches: polygons, generalized cylinders, patches,
** surfaces, sub-L-systems, @S), else LSYS_OK or an error with t->err set. */
int lsys_turtle_par (lsys_turtle *t, const lsys_lstring *s, const lsys_alphabet *ab);

/* turtle.c: closes the ends nothing continued (the end of lsys_turtle_run). */
int lsys_turtle_finish (lsys_turtle *t);

/* turtle_cyl.c: a cylinder from p0 (width w0) to p1 (width w1) around the
** turtle's frame, continuing the open end st.tip when it can; and the caps
** that close the ends nothing continued (at the end of the run). */
int lsys_turtle_cylinder (run *R, const double *p0, const double *p1, double w0, double w1,
                          double len, int col);
int lsys_turtle_capends (run *R);

/* turtle_ribbon.c: a flat ribbon from p0 to p1 in the plane of H and L. */
int lsys_turtle_ribbon (run *R, const double *p0, const double *p1, double w0, double w1,
                        int col);

/* turtle_disc.c: a disc of diameter d around 'c' in the plane of 'a' and 'b',
** facing 'nrm'. */
int lsys_turtle_disc (run *R, const double *c, const double *a, const double *b,
                      const double *nrm, double d, int col);

/* turtle_sphere.c: a sphere of diameter d around 'c', poles on H. */
int lsys_turtle_sphere (run *R, const double *c, double d, int col);

/* turtle_polygon.c: { starts a polygon, . and moves inside one add the
** turtle's position, } fills it (§4.2). The work space of the polygon
** triangulation, made on first use (NULL when out of memory). */
int lsys_turtle_polystart (run *R);
int lsys_turtle_polyvertex (run *R);
int lsys_turtle_polyend (run *R);
struct lsys_polywork *lsys_turtle_polywork (lsys_turtle *t);

/* turtle_gcyl.c: @Gs, @Gc, @Ge (a control point and the strips from the
** active one) and @Gt, @Gr (the shape of the next segments), §3. */
int lsys_turtle_gcmodule (run *R, int op, const double *p, uint32_t np);
int lsys_turtle_gcshape (run *R, int op, const double *p, uint32_t np);

/* turtle_surface.c: ~X(s), the view's surface at the turtle (§4.1), and
** @PS @PC @PD, bicubic patches (§4.3). */
int lsys_turtle_surface (run *R, uint32_t sym, const double *p, uint32_t np);
int lsys_turtle_patch (run *R, int op, const double *p, uint32_t np);

#endif
