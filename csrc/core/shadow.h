/*
** The shadow-propagation grid (docs/open.md, "Built-in environments"): the
** other way of Palubicki, Horel, Longay, Runions, Lane, Měch and
** Prusinkiewicz 2009 ("Self-organizing tree models for image synthesis",
** §4.1) to tell a bud how much light reaches it, without casting rays. Space
** is cut into cubic voxels, each with a shadow value s, 0 at first. Every
** shadow caster (a bud, a piece of leaf) in voxel (I, J, K), J vertical (the
** world is y up, as the turtle's), darkens the pyramid of voxels below it:
**
**     s[I + p, J - q, K + r] += w a b^-q      q = 0 .. depth, |p| <= q, |r| <= q
**
** with its weight w (1 for a bud), a > 0 and b > 1. A bud then sees the
** exposure
**
**     Q = max(C - s + a, 0)
**
** where C is the exposure in full light and the + a takes away what the bud
** cast into its own voxel, and grows towards the voxel of least shadow
** within its perception cone (a half-angle around its heading and a radius
** in voxels).
**
** The grid is the box lo .. hi with its high corner moved up to whole voxels
** (hi' = lo + n voxel on each axis). Voxel (i, j, k) is the half-open box
** lo + [i, i + 1) voxel, ...; a point on a high face of the grid belongs to
** the last voxel. A caster outside the grid casts the part of its pyramid
** that falls inside; a query outside the grid reads the shadow 0.
**
** Adding casters is shared by worker threads layer by layer: each layer of
** the grid is written by one worker, which sums into each voxel the casters
** in a fixed order (by level q, then in the order given), so the values are
** the same bits for every number of threads. Nothing is allocated per
** caster: one add sorts its casters by layer in two blocks it frees after.
*/
#ifndef LSYS_SHADOW_H
#define LSYS_SHADOW_H

#include "common.h"
#include "scene.h"

#define LSYS_SHADOW_MAXTHREADS 64   /* threads of one call, as light.h's */
#define LSYS_SHADOW_MAXDEPTH 64     /* the deepest pyramid (levels 0 .. depth) */
#define LSYS_SHADOW_MAXAXIS (1 << 24)   /* voxels along one axis */
#define LSYS_SHADOW_MAXRADIUS 32    /* the perception radius, in voxels */

typedef struct lsys_shadow_opts {
  double lo[3], hi[3];        /* the box, lo <= hi on each axis, finite */
  double voxel;               /* the voxel's edge, world units, > 0 */
  int depth;                  /* the pyramid's last level, 0 .. LSYS_SHADOW_MAXDEPTH (4) */
  double a;                   /* the shadow a caster puts in its own voxel, > 0 (1) */
  double b;                   /* the fall-off per level down, > 1 (2) */
  lsys_meter *meter;          /* the memory budget (NULL: none): the grid is counted in it
                                 while the grid lives, an add's blocks while it runs; it
                                 must outlive the grid */
} lsys_shadow_opts;

typedef struct lsys_shadow lsys_shadow;

/* What a grid is. */
typedef struct lsys_shadow_stats {
  int n[3];                   /* voxels along x, y, z */
  size_t voxels;              /* n[0] n[1] n[2] */
  size_t bytes;               /* the memory the grid holds */
  double voxel;               /* the edge */
  double lo[3], hi[3];        /* the box it covers: hi rounded up to whole voxels */
  int depth;
  double a, b;
} lsys_shadow_stats;

/* Fills 'o' with the defaults: the unit box at the origin, voxel 1, depth 4,
** a = 1, b = 2, no meter. */
void lsys_shadow_defaults (lsys_shadow_opts *o);

/*
** Makes the grid of the options 'o' into *S, every shadow 0. Returns LSYS_OK;
** LSYS_EARG for a bad option (e names it); LSYS_EMEMORY when the grid would
** exceed the meter or LSYS_SHADOW_MAXAXIS voxels along an axis (e says how
** big it would be); LSYS_ENOMEM. *S is NULL on failure.
*/
int lsys_shadow_new (lsys_shadow **S, const lsys_shadow_opts *o, lsys_error *e);

/* Frees S (NULL: nothing), and gives its bytes back to the meter. */
void lsys_shadow_free (lsys_shadow *S);

/* Every shadow back to 0. */
void lsys_shadow_clear (lsys_shadow *S);

/*
** Adds the 'n' casters at 'points' (3 doubles each) of the weights
** 'weights' (NULL: 1 each), finite numbers; a negative weight takes back
** what the same weight cast. 'threads' workers (clamped to 1 ..
** LSYS_SHADOW_MAXTHREADS) share the layers. Returns LSYS_OK; LSYS_EARG for a
** point or weight that is not finite (e names it; nothing is added);
** LSYS_EMEMORY when the sorting blocks (16 bytes a caster) exceed the meter;
** LSYS_ENOMEM.
*/
int lsys_shadow_add (lsys_shadow *S, const double *points, const double *weights, size_t n,
                     int threads, lsys_error *e);

/*
** Adds the triangles of scene 'sc' as casters (under its instances'
** transforms when it has instances, as drawn): each at its centroid, of the
** weight 'weight' times its area over the voxel's face (a triangle as big
** as a voxel's face weighs 'weight'). Degenerate and non-finite triangles
** are left out. Returns as lsys_shadow_add (48 bytes a triangle for the
** blocks); LSYS_EARG when 'weight' is not finite.
*/
int lsys_shadow_add_scene (lsys_shadow *S, const lsys_scene *sc, double weight, int threads,
                           lsys_error *e);

/*
** Adds 'value' to every voxel that the box lo .. hi overlaps (an obstacle):
** those whose inside it meets, or the one holding a flat box's face. A box
** beside the grid changes nothing. Returns LSYS_OK; LSYS_EARG when a corner
** or the value is not finite, or lo > hi on an axis.
*/
int lsys_shadow_add_box (lsys_shadow *S, const double lo[3], const double hi[3], double value,
                         lsys_error *e);

/*
** The shadow s at each of the 'n' points into out[0 .. n) (0 outside the
** grid). With 'exposure', max(C - s + a, 0) instead. Returns LSYS_OK;
** LSYS_EARG for a point that is not finite, or C not finite (nothing is
** written).
*/
int lsys_shadow_query (const lsys_shadow *S, const double *points, size_t n, int exposure,
                       double C, double *out, lsys_error *e);

/*
** The direction of least shadow for each of the 'n' points with the
** 'headings' (3 doubles each, not zero; normalised here): out gets 3 doubles
** a point, the unit vector from the point to the centre of the voxel of
** least shadow among the grid's voxels (not the point's own) whose centres
** lie within 'radius' voxels of the point and within 'angle' degrees of the
** heading. Of equal shadows, the one nearest the heading wins, then the
** first in the order of the grid (x fastest, then z, then y). A point
** outside the grid, or one that sees no such voxel, gets its heading.
** 'threads' workers share the points. Returns LSYS_OK; LSYS_EARG for a point
** that is not finite, a heading that is not a finite non-zero vector, an
** angle not in (0, 180] or a radius not in (0, LSYS_SHADOW_MAXRADIUS].
*/
int lsys_shadow_direction (const lsys_shadow *S, const double *points, const double *headings,
                           size_t n, double angle, double radius, double *out, int threads,
                           lsys_error *e);

/* The shadow of voxel (i, j, k); 0 outside the grid. */
double lsys_shadow_voxel (const lsys_shadow *S, long i, long j, long k);

/* The sizes of S. */
void lsys_shadow_info (const lsys_shadow *S, lsys_shadow_stats *st);

#endif
