/*
** The turtle (docs/drawing.md): interprets an Lstring as drawing commands and
** writes geometry into a scene (scene.h) and one record per drawing module.
**
** Symbols and their meaning follow the cpfg guide of Měch and Prusinkiewicz
** (Appendix A; §2 discs and spheres; §4.2 polygons; §6 tropisms and twist),
** with Z(sh,su,sl) joint stiffness from Power et al. 1999 and @R from
** Anastacio et al. 2009. Conventions as cpfg (docs/drawing.md §1): initial
** H = (0,1,0), L = (-1,0,0), U = (0,0,-1), so that L = H x U and
** U = L x H; angles in degrees.
*/
#ifndef LSYS_TURTLE_H
#define LSYS_TURTLE_H

#include "lstring.h"
#include "mesh.h"
#include "scene.h"
#include "contour.h"
#include "gcyl.h"
#include "surface.h"
#include "texture.h"

#define LSYS_MAXTROPISMS 16

enum { LSYS_STYLE_LINE = 0, LSYS_STYLE_POLYGON = 1, LSYS_STYLE_CYLINDER = 2 };

/* A predefined surface of the view: ~name draws it (cpfg guide §4.1). */
typedef struct lsys_surfuse {
  const char *name;       /* what follows the ~ (one character) */
  const lsys_surface *s;
  double scale;           /* multiplies the surface (and ~X(s) multiplies again) */
  int texture;            /* 0: the turtle's current texture (@Tx) */
  int ns, nt;             /* lines per patch */
} lsys_surfuse;

/* A tropism (cpfg guide §6, eq. 1-2) or a torque (§6.1) from the view. */
typedef struct lsys_tropism {
  double vec[3];          /* the stimulus direction (normalised when used) */
  double angle;           /* diatropism angle gamma, degrees (tropisms only) */
  double elasticity;      /* initial elasticity */
  double increment;       /* for @Ti / @Td without a value */
  int torque;             /* 1: twist response (§6.1) */
  double intensity;       /* cpfg's I:, from -1 to 1: multiplies the elasticity (1) */
} lsys_tropism;

/* The numeric view options the turtle reads. */
typedef struct lsys_turtle_opts {
  double angle;           /* angle increment, degrees (90) */
  double step;            /* step of F f G g without a parameter (1) */
  double width, dwidth;   /* initial line width (1) and its increment (1) */
  int color, dcolor;      /* initial colour index (1) and its increment (1) */
  int style;              /* LSYS_STYLE_* (line) */
  int sides;              /* contour sides of cylinders, discs, spheres (8) */
  int allow_system;       /* @S allowed (0) */
  int norecords;          /* 1: no turtle records (big renders and exports) */
  int minimize_twist;     /* generalized cylinders: rotation-minimising frames (1) */
  lsys_tropism trop[LSYS_MAXTROPISMS];
  int ntrop;
  /* cpfg's old-style tropism (`tropism direction:`, `initial elasticity:`, `elasticity
  ** increment:`): a unit direction (0, 1, 0 by default), the initial elasticity that `_`
  ** changes, and what `_` without a parameter adds */
  double otrop[3], oelast, oincr;
  /* contours[id] for @#(id), 1 <= id < ncontours (NULL: not defined); id 0 is the circle */
  const lsys_contour *const *contours; int ncontours;
  const lsys_texture *const *tex; int ntex;     /* @Tx(k): tex[k - 1] */
  const lsys_surfuse *surfaces; int nsurfaces;
} lsys_turtle_opts;

void lsys_turtle_defaults (lsys_turtle_opts *o);

/* The turtle state (cpfg guide §1), pushed and popped by [ and ]. */
typedef struct lsys_tstate {
  double pos[3], H[3], L[3], U[3];
  double refH[3], refU[3];      /* frame of the last twist minimisation (§3.3, §6) */
  double width, scale;
  double stiff[3];
  int color, color2, texture, contour, hasstiff;
  int sides;                    /* of cylinders, discs and spheres: the view's, or @!(n) */
  uint32_t last;                /* last segment record, or LSYS_NOREC */
  uint32_t tip;                 /* open cylinder end to continue from, or LSYS_NOREC */
  uint32_t gc;                  /* active generalized-cylinder control point (§3.4), or
                                   LSYS_NOREC */
  double gtan[2];               /* @Gt: tangent coefficients of the next segments */
  double grad[4];               /* @Gr: radius tangents (angle, length) x 2 */
  int gadjust;                  /* @Gr(1) */
  double oelast;                /* elasticity of the old-style tropism (`_`) */
  double elast[LSYS_MAXTROPISMS];   /* last: [ and ] copy only the view's tropisms */
} lsys_tstate;

/* Expands module 'i' (parameters at 'poff') by the homomorphism into
** 'out' (cleared by the callee); returns 1 when it did (1 + k when the rule
** took the k modules after i too: the turtle skips them), 0 when the module
** stands for itself, or a negative LSYS_E* code (message in 'e'). */
typedef int (*lsys_expandfn) (void *ud, size_t i, size_t poff, lsys_lstring *out,
                              lsys_error *e);

/*
** ?E: a communication module the interpretation met (open L-systems, docs/open.md), with
** the turtle's state there and the module after it, for the environment to answer.
*/
#define LSYS_ENVQ_MADE ((size_t)-1)     /* mod: a module the homomorphism made */
#define LSYS_ENVQ_NONE ((uint32_t)-1)   /* next: no module follows */

typedef struct lsys_envquery {
  size_t mod;                   /* its index in the string, or LSYS_ENVQ_MADE */
  size_t par;                   /* its parameters: in the string's pool, or (made) the pool's */
  uint32_t np;
  uint32_t next, nextnp;        /* the following module's symbol (or LSYS_ENVQ_NONE) */
  size_t nextpar;               /* its parameters, in the string's pool after a module of
                                   the string, in the pool after a made one */
  double pos[3], H[3], L[3], U[3];
  double width, scale;
  int color;                    /* the colour index there (as a record keeps it: 16 bits) */
} lsys_envquery;

typedef struct lsys_envqueries {
  lsys_envquery *q; size_t n, cap;
  double *pool; size_t npool, poolcap;   /* parameters of modules the homomorphism made */
} lsys_envqueries;

void lsys_turtle_envfree (lsys_envqueries *q);

enum {
  LSYS_TURTLE_DRAW = 0,   /* geometry and records */
  LSYS_TURTLE_QUERY = 1,  /* only fill the parameters of ?P ?H ?U ?L */
  LSYS_TURTLE_STATE = 2   /* only run the first 'stop' modules and keep the state */
};

typedef struct lsys_cylend lsys_cylend;
typedef struct lsys_csample lsys_csample;
typedef struct lsys_lpatch lsys_lpatch;
typedef struct lsys_polygon lsys_polygon;
struct lsys_polywork;

typedef struct lsys_turtle {
  /* inputs */
  const lsys_turtle_opts *o;
  lsys_expandfn expand; void *expandud;
  int mode;
  size_t stop;                  /* LSYS_TURTLE_STATE: modules to interpret */
  lsys_meter *meter;            /* the memory budget of the branch stack (NULL: none); the
                                   scene's mesh and records have theirs (scene->meter,
                                   mesh.meter: lsys_interpret_run sets all three to one) */
  int threads;                  /* DRAW mode: threads for a long string (turtle_par.c; 0 or 1:
                                   the caller's alone) */
  lsys_envqueries *envq;        /* not NULL: the ?E modules met are appended here (any mode;
                                   the caller empties it) */
  size_t piecemin;              /* the smallest branch given a thread of its own (0: the
                                   default; tests set it small to split short strings) */
  /* outputs */
  lsys_scene *scene;            /* DRAW mode: the geometry, records and stiffnesses go here */
  lsys_tstate state;            /* the state when interpretation ended (or stopped) */
  size_t nqueries;              /* query modules filled */
  size_t nsyscalls;             /* @S modules seen (recorded when allowed) */
  int npieces;                  /* DRAW mode: the pieces the string was cut into (0: run
                                   whole, on the caller's thread) */
  lsys_error err;
  lsys_error warn;              /* a warning the run ended with (code 0: none), for the
                                   caller to pass on: a polygon never closed */
  /* scratch, reused across calls */
  lsys_mesh *mesh;              /* &scene->mesh during a DRAW run, else NULL */
  lsys_tstate *stack; size_t nstack, stackcap;
  lsys_polygon *polys; size_t npolys, polycap;
  size_t polyfrom;              /* the module of the outermost open '{' */
  lsys_cylend *ends; size_t nends, endcap;
  double *subscale; size_t nsub, subcap;
  lsys_lstring hbuf;
  struct lsys_polywork *pw;
  uint8_t *op; size_t nop;      /* what each symbol id does */
  const double *ring; int nring;/* cos/sin table for the state's 'sides' */
  int maxsides;                 /* the most sides an @!(n) of the run asked for (0: none) */
  double *ringbuf; size_t ringcap;
  void *runbuf;                 /* the state of a run (kept: a rule error may longjmp out) */
  lsys_gcpoint *gcp; size_t ngcp, gcpcap;     /* generalized-cylinder control points */
  lsys_csample *cs; size_t ncs;               /* sampled contours by id */
  lsys_lpatch *patch; size_t npatch;          /* @PS/@PC/@PD patches by number */
  uint32_t *surfsym;                          /* symbol id of each view surface */
  uint32_t *shash;                            /* the record shape cache (LSYS_SHASH slots:
                                                 shape index + 1, 0 empty) */
  int fixshape;                               /* 1: the scene's shapes cannot grow (a piece
                                                 drawn again to counted places) */
  lsys_mesh *stess; uint8_t *stessok; size_t nstess;  /* surfaces tessellated in their
                                                 own frame: 2 per surface (uv modes) */
} lsys_turtle;

void lsys_turtle_init (lsys_turtle *t);
void lsys_turtle_free (lsys_turtle *t);

/*
** Interprets 's' (symbol names from 'ab'; a narrow string is read as it is). In DRAW mode
** the geometry, the
** records and the stiffnesses go into t->scene (which must be set; they are
** cleared first, its palette, textures, camera and light stay). In QUERY mode the parameters of the query modules of 's'
** are overwritten with the turtle's position or vectors at that point. In
** STATE mode t->state is the state after the first t->stop modules. Returns LSYS_OK
** or an error code with t->err set (t->err.pos = the module index). A long string
** in DRAW mode without a homomorphism runs on t->threads threads, split at its
** big branches (turtle_par.c); the scene is the same for every number of threads.
*/
int lsys_turtle_run (lsys_turtle *t, lsys_lstring *s, const lsys_alphabet *ab);

#endif
