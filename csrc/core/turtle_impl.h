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
**   turtle_trop.c     tropisms, torques and twist (cpfg guide §6), the orthonormal frame
** The helpers every module may call (arg, newrec) are static inline here, so
** the interpretation loop pays no call for them.
*/
#ifndef LSYS_TURTLE_IMPL_H
#define LSYS_TURTLE_IMPL_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

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
  size_t recbase;               /* the scene's index of the first record this run writes, */
  size_t linebase, ptbase;      /* of its first line and record end point, */
  size_t shapebase;             /* and of its first shape (0 when its shapes are its own) */
  uint32_t pstiff;              /* the pending segment's stiffness (its record's) */
  float plen;                   /* its length, as its record has it */
  int fixed;                    /* a piece of a parallel run (turtle_par.c): the records and
                                   lines go to places counted beforehand and cannot grow */
};

/* turtle_trop.c: an orthonormal frame from H and an approximate U; the
** smallest rotation of the reference frame to the heading (twist removed); the
** tropisms and torques before a move (§6); cpfg's old-style tropism after it. */
void lsys_turtle_orthonormal (lsys_tstate *st);
void lsys_turtle_untwist (lsys_tstate *st);
void lsys_turtle_tropisms (run *R);
void lsys_turtle_oldbend (run *R);

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

/* The shape cache (scene.h): slots of shape indices, a power of 2. */
#define LSYS_SHASH 1024

/* ALWAYS: inlined where GCC or Clang would not: a record's shape is found on
** every segment, and only inlined does its key stay in registers. */
#if defined(__GNUC__)
#define ALWAYS __attribute__((always_inline))
#else
#define ALWAYS
#endif

/* A shape as the words of its bits: an lsys_rshape's bytes as six 8-byte
** words and the last 4. shapeset makes them in registers and stores each
** whole, and sameshape reads them back in the same widths, so that the
** processor forwards each store to its load. */
typedef struct skey { uint64_t q[6]; uint32_t r; } skey;
_Static_assert(sizeof(lsys_rshape) == 52 && offsetof(lsys_rshape, len) == 24 &&
               offsetof(lsys_rshape, w0) == 28 && offsetof(lsys_rshape, stiff) == 36 &&
               offsetof(lsys_rshape, tri0) == 40 && offsetof(lsys_rshape, color) == 48 &&
               offsetof(lsys_rshape, kind) == 50 && offsetof(lsys_rshape, line) == 51,
               "lsys_rshape is the words shapeset makes");

/* The 8 bytes of a and b, in this order in memory. */
static inline ALWAYS uint64_t pair (const void *a, const void *b) {
  unsigned char x[8];
  uint64_t v;
  memcpy(x, a, 4);
  memcpy(x + 4, b, 4);
  memcpy(&v, x, sizeof v);
  return v;
}

static inline ALWAYS uint64_t fpair (double a, double b) {
  float x = (float)a, y = (float)b;
  return pair(&x, &y);
}

/* Fills a shape's key: its frame and the rest (the fields of lsys_rshape in
** their order). */
static inline ALWAYS void shapeset (skey *h, int kind, const double *H, const double *U,
                                    float len, double w0, double w1, uint32_t stiff,
                                    size_t tri0, size_t ntri, int color, int line) {
  float fw0 = (float)w0, fw1 = (float)w1;
  uint32_t t0 = (uint32_t)tri0, nt = (uint32_t)ntri;
  uint16_t c = (uint16_t)color;
  unsigned char last[4];
  h->q[0] = fpair(H[0], H[1]);
  h->q[1] = fpair(H[2], U[0]);
  h->q[2] = fpair(U[1], U[2]);
  h->q[3] = pair(&len, &fw0);
  h->q[4] = pair(&fw1, &stiff);
  h->q[5] = pair(&t0, &nt);
  memcpy(last, &c, sizeof c);
  last[2] = (unsigned char)kind;
  last[3] = (unsigned char)line;
  memcpy(&h->r, last, sizeof last);
}

/* 1 when shape a has the bits of key h. */
static inline ALWAYS int sameshape (const lsys_rshape *a, const skey *h) {
  const unsigned char *p = (const unsigned char *)a;
  uint64_t d = 0, v;
  uint32_t u;
  int k;
  for (k = 0; k < 6; k++) {         /* one load of 8 bytes each (no copy of the whole) */
    memcpy(&v, p + 8 * k, sizeof v);
    d |= v ^ h->q[k];
  }
  memcpy(&u, p + 48, sizeof u);
  return (d | (u ^ h->r)) == 0;
}

/* The index of a shape equal to h: the one the cache knows, else h appended
** to the run's shapes. The cache holds the shape last seen in each slot (by a
** hash of its words), so that the few frames of a plant's segments are each
** kept once or nearly. LSYS_OK or an error. */
static inline ALWAYS int recshape (run *R, const skey *h, uint32_t *idx) {
  lsys_turtle *t = R->t;
  lsys_scene *S = t->scene;
  unsigned char *d;
  uint64_t y;
  uint32_t x, i;
  y = (h->q[0] * 0x9e3779b97f4a7c15u) ^ (h->q[1] * 0xc2b2ae3d27d4eb4fu) ^
      (h->q[2] * 0x165667b19e3779f9u) ^ ((h->q[3] + h->q[4] + h->q[5]) * 0x27d4eb2f165667c5u);
  x = (uint32_t)(y >> 32) ^ (uint32_t)y;
  x = (x * 0x2c1b3c6du) >> 22;                       /* 10 bits: LSYS_SHASH slots */
  i = t->shash[x];
  if (i == 0 || !sameshape(&S->shape[i - 1], h)) {
    if (S->nshape == S->shapecap) {
      if (t->fixshape)
        return lsys_turtle_fail(R, LSYS_ELIMIT, "internal error: shapes miscounted");
      if (R->shapebase + S->nshape >= UINT32_MAX - 1)
        return lsys_turtle_fail(R, LSYS_ELIMIT, "too many turtle records");
      if (lsys_scene_reserve_shapes(S, 1) != LSYS_OK) return lsys_turtle_nomem(R);
    }
    d = (unsigned char *)&S->shape[S->nshape];
    memcpy(d, h->q, sizeof h->q);
    memcpy(d + sizeof h->q, &h->r, sizeof h->r);
    t->shash[x] = i = (uint32_t)++S->nshape;
  }
  *idx = (uint32_t)(R->shapebase + i - 1);
  return LSYS_OK;
}

/* Starts a record for the current module: its module, its parent and the
** stiffness in effect (*stiff); its shape and end point come with recend.
** Sets *q to it (NULL without records). */
static inline int recstart (run *R, lsys_rec **q, uint32_t *stiff) {
  lsys_turtle *t = R->t;
  lsys_scene *S = t->scene;
  lsys_rec *r;
  *q = NULL;
  *stiff = LSYS_NOREC;
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
  r->shape = LSYS_NOREC;             /* none until recend */
  r->at = 0;
  if (R->st.hasstiff && lsys_scene_add_stiffness(S, R->st.stiff, stiff) != LSYS_OK)
    return lsys_turtle_nomem(R);
  *q = r;
  return LSYS_OK;
}

/* Gives record q its shape h and its end point: line l of the scene when
** 'line' (the shape's flag), else p1, appended to the scene's end points. */
static inline ALWAYS int recend (run *R, lsys_rec *q, const skey *h, int line, size_t l,
                                 const double *p1) {
  lsys_scene *S = R->t->scene;
  if (line) q->at = (uint32_t)(R->linebase + l);
  else {
    float *d;
    if (S->npt == S->ptcap / 3) {
      if (R->fixed) return lsys_turtle_fail(R, LSYS_ELIMIT, "internal error: points miscounted");
      if (R->ptbase + S->npt >= UINT32_MAX)
        return lsys_turtle_fail(R, LSYS_ELIMIT, "too many turtle records");
      if (lsys_scene_reserve_points(S, 1) != LSYS_OK) return lsys_turtle_nomem(R);
    }
    d = S->recpt + 3 * S->npt;
    d[0] = (float)p1[0]; d[1] = (float)p1[1]; d[2] = (float)p1[2];
    q->at = (uint32_t)(R->ptbase + S->npt++);
  }
  return recshape(R, h, &q->shape);
}

/* The length of a segment record from p0 to p1, as a float: sqrt(q) rounded
** to the nearest float, q the squared distance. 'guess' is what the caller
** expects (the step; 0: none): when q is within a factor 1 +- 2^-26 of its
** float f squared, the root is within 1 +- 2^-27 of f, nearer to f than to
** any other float (those are 2^-24 away, or 2^-25 below a power of 2), so f
** is the rounded root and the square root is not taken. */
static inline float reclen (const double *p0, const double *p1, double guess) {
  double d0 = p1[0] - p0[0], d1 = p1[1] - p0[1], d2 = p1[2] - p0[2];
  double q = d0 * d0 + d1 * d1 + d2 * d2, f = guess <= FLT_MAX ? (float)guess : 0, f2 = f * f;
  if (fabs(q - f2) < f2 * 0x1p-26) return (float)f;
  return (float)sqrt(q);
}

/* A whole record of 'kind' for the current module, from p0 to p1 (a gcyl's
** length is their distance), in the frame H, U (NULL: the turtle's present
** one); its triangles are what the module drew so far. Not for segments,
** whose records end when they are drawn (turtle.c, flush). */
static inline int newrecf (run *R, int kind, const double *p0, const double *p1, double w0,
                           double w1, const double *H, const double *U) {
  lsys_turtle *t = R->t;
  lsys_rec *q;
  skey h;
  uint32_t stiff;
  size_t nt = t->mesh != NULL ? t->mesh->nt : 0;
  int s;
  if ((s = recstart(R, &q, &stiff)) != LSYS_OK || q == NULL) return s;
  shapeset(&h, kind, H != NULL ? H : R->st.H, U != NULL ? U : R->st.U,
           kind == LSYS_REC_GCYL ? reclen(p0, p1, 0) : 0.0f, w0, w1, stiff, R->modtri,
           nt > R->modtri ? nt - R->modtri : 0, R->st.color, 0);
  return recend(R, q, &h, 0, 0, p1);
}

static inline int newrec (run *R, int kind, const double *p0, const double *p1, double w0,
                          double w1) {
  return newrecf(R, kind, p0, p1, w0, w1, NULL, NULL);
}

/* turtle.c: runs modules [a, b) of 's' (parameters from 'poff') from the state
** 'start' into t->scene, whose records, lines and record end points have exactly
** the room this piece needs; its first record, line, end point and shape are the
** scene's base[0], base[1], base[2] and base[3]-th. t->op, t->ring and t->o are
** set (borrowed from the turtle that split the run); t->ends may hold the open end
** the start state continues. The pending segment is emitted at the end; t->state
** is the state there. LSYS_OK or an error with t->err set. */
int lsys_turtle_runpiece (lsys_turtle *t, const lsys_lstring *s, const lsys_alphabet *ab,
                          size_t a, size_t b, size_t poff, const lsys_tstate *start,
                          const size_t base[4]);

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
