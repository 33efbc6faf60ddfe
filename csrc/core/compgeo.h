/*
** The numeric side of component graphs (lsys.components; Lintermann and
** Deussen 1999, "Interactive Modeling of Plants", sections "Modeling with
** components" and "A geometry generation example").
**
** The expansion of a p-graph gives every instance a frame; Horns and Trees
** also a stem of frames. Those frames live here, in one growable arena
** (lsys_cframes), so a plant of 60,000 instances is 60,000 records of 11
** doubles rather than a quarter of a million Lua tables. The arena also holds
** the expansion's seeded generator (splitmix64), which parameter functions and
** the stem's gnarl draw from in turn.
**
** The writer (lsys_cwriter) turns the frames into one Lstring of relative
** turtle modules: every instance is a branch `[` ... `]` that rolls, pitches
** and moves (`/ & f`) from where its parent left the turtle to its frame, and
** rolls, pitches and rolls to take its orientation. It records which instance
** wrote each module and each instance's module range, for picking and for the
** deformations applied after the turtle has drawn.
**
** Conventions are the turtle's (turtle.h): L = H x U; a frame's own axes are
** right R = -L, heading H and front F = -U, scaled by s: the local point
** (x, y, z) is at p + s (x R + y H + z F). Angles are in degrees.
*/
#ifndef LSYS_COMPGEO_H
#define LSYS_COMPGEO_H

#include "common.h"
#include "lstring.h"

typedef struct lsys_cframe {
  double p[3], H[3], U[3];
  double s;                   /* uniform scale */
  double u;                   /* a stem frame: its place along the stem, 0 to 1 */
} lsys_cframe;

typedef struct lsys_cframes {
  lsys_cframe *f;
  size_t n, cap;
  uint64_t rng;               /* splitmix64 state */
} lsys_cframes;

void lsys_compgeo_frames_init (lsys_cframes *a, int64_t seed);
void lsys_compgeo_frames_free (lsys_cframes *a);

/* Appends a frame (copied; f may point into the arena). Returns LSYS_OK and
** its index in *idx, or LSYS_ENOMEM. */
int lsys_compgeo_frames_add (lsys_cframes *a, const lsys_cframe *f, size_t *idx);

/* The next number of the generator, in [0, 1): splitmix64's output, top 53 bits. */
double lsys_compgeo_frames_random (lsys_cframes *a);

/* The world position of the local point (x, y, z) of f. */
void lsys_compgeo_frame_topoint (const lsys_cframe *f, double x, double y, double z, double out[3]);

/* g = f moved by the basic parameters: translate t (local), rotate r (about
** the local x, then y, then z axes), scale s. g may be f. */
void lsys_compgeo_frame_transform (const lsys_cframe *f, const double t[3], const double r[3],
                                   double s, lsys_cframe *g);

/* H turned towards direction T by the angle e |H x T| radians (cpfg's tropism,
** ABOP section 2.3), U with it. */
void lsys_compgeo_frame_tropism (lsys_cframe *g, const double T[3], double e);

/* A Tree's branch between stem frames A and B at t (0 at A): A's orientation
** rolled by 'roll' about H and pitched down by 'angle'; scale A.s * scale. */
void lsys_compgeo_frame_branch (const lsys_cframe *A, const lsys_cframe *B, double t, double roll,
                                double angle, double scale, lsys_cframe *g);

/* A direction field (a World's field given as a function) at position p for a
** stem heading H: sets T and returns 1, returns 0 for "no direction here", or
** LSYS_ERULE. */
typedef int (*lsys_cfield) (void *ud, int k, const double p[3], const double H[3],
                            double T[3]);

typedef struct lsys_cstem {
  double len;                 /* along the stem, in units of the base frame's scale */
  int segs;                   /* equal pieces, >= 1 */
  double curv, twist, gnarl;  /* degrees over the whole stem (gnarl: per segment, random) */
  int ntrop;                  /* tropisms: direction (NaN x: ask field) and strength */
  const double *trop;         /* ntrop x 4 */
  lsys_cfield field;
  void *ud;
  double dev;                 /* the deviation from each branch (degrees) */
  int nb;                     /* branches: place along the stem and roll about H */
  const double *bu, *broll;
} lsys_cstem;

/* The stem from frame 'base': segs + 1 frames appended (the first a copy of
** the base, u = k / segs), the index of the first in *first. Returns LSYS_OK,
** LSYS_ENOMEM or the field's error. */
int lsys_compgeo_frames_stem (lsys_cframes *a, size_t base, const lsys_cstem *st, size_t *first);

/* The writer ------------------------------------------------------------ */

typedef struct lsys_cturtle {
  double p[3], H[3], U[3];
  size_t m0;                  /* the module index of the instance's `[` */
  int32_t inst;               /* the instance that opened the branch */
} lsys_cturtle;

typedef struct lsys_cwriter {
  lsys_lstring *s;            /* the string written (the caller owns it) */
  int32_t *owner;             /* owner[k]: the instance that wrote module k */
  size_t capo;
  int32_t cur;                /* the instance writing now (0: none) */
  lsys_cturtle T;             /* where the modules written so far leave the turtle */
  lsys_cturtle *stk;          /* saved at each `[` */
  size_t depth, capstk;
  int32_t *range;             /* per instance: m0, m1, at (module indices, 1-based) */
  size_t capi;
  uint32_t sym_open, sym_close, sym_roll, sym_pitch, sym_move, sym_draw;  /* [ ] / ^ f F */
} lsys_cwriter;

/* A writer into s, the turtle at the origin with H = +y, U = -z. */
void lsys_compgeo_writer_init (lsys_cwriter *w, lsys_lstring *s);
void lsys_compgeo_writer_free (lsys_cwriter *w);

/* Appends a module written by instance w->cur; LSYS_ESYNTAX for a parameter that is not
** finite (a move to a frame so far away that its length overflowed). */
int lsys_compgeo_writer_op (lsys_cwriter *w, uint32_t sym, const double *p, uint32_t np);

/* Opens instance 'inst' (>= 1): `[`, then the modules that take the turtle to f. */
int lsys_compgeo_writer_open (lsys_cwriter *w, int32_t inst, const lsys_cframe *f);

/* Closes the innermost open instance with `]`; the turtle is as before its `[`. */
int lsys_compgeo_writer_close (lsys_cwriter *w);

/* Turns the turtle to (H, U) with a roll, a pitch and a roll (no-ops left out). */
int lsys_compgeo_writer_orient (lsys_cwriter *w, const double H[3], const double U[3]);

/* Moves the turtle d along H with `F` (draw) or `f`; nothing for d <= 1e-15. */
int lsys_compgeo_writer_forward (lsys_cwriter *w, double d, int draw);

/* The angles (degrees) of a roll `/`, a pitch `^` (H toward -U) and a roll `/` that turn the
** orientation (AH, AU) onto (BH, BU); with BU NULL only the first two (aim H at
** BH), out[2] = 0. */
void lsys_compgeo_writer_angles (const double AH[3], const double AU[3], const double BH[3],
                                 const double BU[3], double out[3]);

#endif
