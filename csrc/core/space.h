/*
** Space (docs/open.md, built-in environments): which points are near which,
** for the crowding and collision tests of open L-systems and for space
** colonisation.
**
** A space is a spatial hash over a set of points: uniform cubic cells of
** side c (the space's radius), the cell of p being (floor(p.x / c),
** floor(p.y / c), floor(p.z / c)), hashed into a table of about twice as
** many buckets as points. Each point has an integer group and a real
** vigour. The queries, from a query point q and a radius r (at most
** LSYS_SPACE_MAXSPAN c), look at the cells within ceil(r / c) cells of q's
** and take the points p with |p - q|^2 <= r^2, the squared distance summed
** as dx*dx + dy*dy + dz*dz:
**
**   count    the number of such points;
**   density  the sum over them of the biweight kernel (1 - |p - q|^2 / r^2)^2:
**            1 for a point at q, falling smoothly (with a zero slope) to 0 at
**            the radius, so a point entering or leaving the neighbourhood
**            changes the density by nothing;
**   nearest  the distance to the nearest one, HUGE_VAL when there is none;
**   free     Honda's collision test (Honda 1981, as vlab's honda81 program
**            and lsys.environment.collision answer it): 1 when no point of
**            q's group with a vigour >= q's lies within r, else 0.
**
** Queried with its own points, each point leaves itself out (not another
** point at the same place). The scene's points a space may take besides
** the listed ones (each line segment's end and each triangle's centroid, as
** drawn: a population's instances placed) are of group 0 and vigour
** HUGE_VAL, obstacles to group 0; a query may leave out those nearer than
** an offset (the end of the segment a bud stands on).
**
** Markers (space colonisation: Runions, Lane and Prusinkiewicz 2007,
** "Modeling trees with a space colonization algorithm", §3; Palubicki et
** al. 2009, "Self-organizing tree models for image synthesis", §4.2) are a
** set of points, the attraction points, that buds perceive and remove. In
** one pass over buds b (positions and headings h_b):
**
**   1. every marker m within the kill (occupancy) radius of some bud,
**      |m - b| <= kill, is removed (for good: the set shrinks);
**   2. every other marker is associated with the nearest bud that
**      perceives it: |m - b| <= perception, m != b, and within the cone of
**      half-angle a around h_b, (m - b) . h_b >= cos(a) |m - b| (a = 180
**      degrees: the whole sphere); of two buds at one distance the first;
**   3. a bud's answer is the number of its markers and the normalised sum
**      of the unit vectors from it to them (0, 0, 0 when it has none): the
**      direction its shoot grows in.
**
** The sums are taken in the markers' order and each association depends on
** the marker alone, so every result is the same for every number of
** threads. Queries and passes allocate per call (their scratch), never per
** point; every block is counted against a meter (max_memory).
*/
#ifndef LSYS_SPACE_H
#define LSYS_SPACE_H

#include "common.h"
#include "scene.h"

#define LSYS_SPACE_MAXTHREADS 64     /* as derive.h's LSYS_MAXTHREADS */
#define LSYS_SPACE_MAXSPAN 16        /* a query's radius is at most this many cells */
#define LSYS_SPACE_MAXPOINTS 0xfffffff0u   /* points of a space, markers, buds */

/* What a query asks (above). */
enum {
  LSYS_SPACE_COUNT = 0,
  LSYS_SPACE_DENSITY = 1,
  LSYS_SPACE_NEAREST = 2,
  LSYS_SPACE_FREE = 3
};

typedef struct lsys_space lsys_space;

typedef struct lsys_space_opts {
  double radius;            /* > 0, finite: the cells' side and the queries' default radius */
  const int64_t *groups;    /* one a listed point, or NULL: all 0 */
  const double *vigour;     /* one a listed point (any number: NaN is nobody's match, as
                               in the comparisons of collision.lua), or NULL: all 0 */
  const lsys_scene *scene;  /* NULL, or a scene whose points are added after the listed */
  lsys_meter *meter;        /* the memory budget (NULL: none) */
} lsys_space_opts;

typedef struct lsys_space_ask {
  int kind;                 /* LSYS_SPACE_COUNT, ... */
  double radius;            /* > 0, at most LSYS_SPACE_MAXSPAN times the space's; 0: the
                               space's radius */
  const double *points;     /* 'n' query points, 3 doubles each; NULL: the listed points of
                               the space, each leaving itself out (out gets 'listed' values) */
  size_t n;
  const int64_t *groups;    /* LSYS_SPACE_FREE with points: each query's group (NULL: 0) */
  const double *vigour;     /* and vigour (NULL: 0) */
  double offset;            /* >= 0: the scene's points nearer a query than this are left
                               out (0: none) */
  int threads;              /* 1 .. LSYS_SPACE_MAXTHREADS; out of range is clamped */
} lsys_space_ask;

typedef struct lsys_space_stats {
  size_t points, listed;    /* all, and those listed (the rest are the scene's) */
  size_t cells, buckets;
  size_t bytes;             /* what the space holds */
  double radius;
} lsys_space_stats;

/*
** Builds the space of the 'n' points (3 doubles each) and, with o->scene,
** the scene's points, into *S. Everything is copied. Returns LSYS_OK;
** LSYS_EARG for a bad radius, a point that is not finite or too far from
** the origin for the cells (|x / c| >= 2^52), or more than
** LSYS_SPACE_MAXPOINTS points (e names it); LSYS_EMEMORY when it would
** exceed the meter (message in e); LSYS_ENOMEM. *S is NULL on failure.
*/
int lsys_space_build (lsys_space **S, const double *points, size_t n,
                      const lsys_space_opts *o, lsys_error *e);

void lsys_space_free (lsys_space *S);

/*
** Answers the query q: one double a query point into out (the count, the
** density, the nearest distance or HUGE_VAL, or 1 / 0 for free). Allocates
** nothing. Returns LSYS_OK; LSYS_EARG for a bad kind or radius, or a query
** point that is not finite or too far (e names it; nothing is written).
*/
int lsys_space_query (const lsys_space *S, const lsys_space_ask *q, double *out,
                      lsys_error *e);

void lsys_space_info (const lsys_space *S, lsys_space_stats *st);

/* The number of points the scene 's' adds to a space (its segments and
** triangles, under its instances). */
size_t lsys_space_scenepoints (const lsys_scene *s);

/* ---------------------------------------------------------------------- */
/* markers */

typedef struct lsys_markers lsys_markers;

typedef struct lsys_markers_opts {
  double perception;        /* > 0: the radius buds perceive markers within */
  double angle;             /* the perception cone's half-angle, degrees, (0, 180] */
  double kill;              /* >= 0, at most LSYS_SPACE_MAXSPAN times the perception: markers
                               within this of a bud are removed first (0: none) */
  int threads;              /* clamped to 1 .. LSYS_SPACE_MAXTHREADS */
} lsys_markers_opts;

/*
** A set of the 'n' markers (3 doubles each, copied) into *M, counted in the
** meter 'mt' (NULL: none), which the markers keep (it must outlive them)
** and which their passes' scratch is counted against too. Returns LSYS_OK;
** LSYS_EARG (a marker not finite, too many); LSYS_EMEMORY; LSYS_ENOMEM.
*/
int lsys_space_markers_new (lsys_markers **M, const double *points, size_t n,
                            lsys_meter *mt, lsys_error *e);

void lsys_space_markers_free (lsys_markers *M);

/* The markers left, and their positions (3 doubles each, valid until the
** next pass or removal). */
size_t lsys_space_markers_count (const lsys_markers *M);
const double *lsys_space_markers_points (const lsys_markers *M);

/*
** One pass (above) over the 'nb' buds (3 doubles each) with their headings
** (3 doubles each, normalised here): counts[b] the markers of bud b,
** dirs (NULL: not wanted) 3 doubles a bud, its direction. Returns LSYS_OK;
** LSYS_EARG for a bad option, a bud that is not finite or a zero heading
** (nothing is changed); LSYS_EMEMORY (the scratch would exceed the meter);
** LSYS_ENOMEM. Removed markers are gone only when it returns LSYS_OK.
*/
int lsys_space_markers_perceive (lsys_markers *M, const double *buds,
                                 const double *headings, size_t nb,
                                 const lsys_markers_opts *o, size_t *counts, double *dirs,
                                 lsys_error *e);

/*
** Removes the markers within 'radius' (> 0) of any of the 'n' points;
** *removed (may be NULL) gets how many. Returns as lsys_space_markers_perceive.
*/
int lsys_space_markers_remove (lsys_markers *M, const double *points, size_t n,
                               double radius, int threads, size_t *removed, lsys_error *e);

/* ---------------------------------------------------------------------- */
/*
** A resource field (docs/open.md): an amount (soil water, a nutrient) in
** each cell of a grid of cubic cells of side h over a box, spreading by
** diffusion, fed by sources and taken by the plant. Cell (i, j, k) covers
** lo + h [i, i + 1) x [j, j + 1) x [k, k + 1); n_a = ceil((hi_a - lo_a) / h)
** cells along each axis (at least 1: one cell across an axis makes the
** field 2D, or 1D). The amounts are stored x fastest.
**
** Diffusion over a time t with coefficient D (units^2 a unit of time) is the
** explicit scheme on the grid's graph, m substeps of
**
**     q_c <- q_c + a sum_{c' next to c} (q_c' - q_c),   a = D t / (m h^2),
**
** (the neighbours along the axes of more than one cell; none beyond the box:
** nothing flows out), with m the least that keeps a <= 1 / (2 d), d the
** number of such axes: each new amount is then a weighted mean of old ones,
** so none goes negative and the total stays what it was.
*/
typedef struct lsys_field lsys_field;

#define LSYS_FIELD_MAXCELLS ((size_t)1 << 30)
#define LSYS_FIELD_MAXSUBSTEPS 100000

/* A field over the box lo .. hi (lo < hi, or equal for one cell) of cells of
** side 'cell', every amount 0, counted in the meter 'mt' (NULL: none: it
** must outlive the field). Returns LSYS_OK; LSYS_EARG (a bad box or cell,
** more than LSYS_FIELD_MAXCELLS cells); LSYS_EMEMORY; LSYS_ENOMEM. */
int lsys_space_field_new (lsys_field **F, const double lo[3], const double hi[3],
                          double cell, lsys_meter *mt, lsys_error *e);

void lsys_space_field_free (lsys_field *F);

/* The cells along each axis into n; the side of a cell. */
double lsys_space_field_dims (const lsys_field *F, size_t n[3]);

/* The amounts, n[0] n[1] n[2] of them (x fastest), to read or write (write
** finite amounts >= 0). */
double *lsys_space_field_values (lsys_field *F);

/* The index of the cell of p, or -1 outside the grid (or p not finite). */
long long lsys_space_field_cell (const lsys_field *F, const double p[3]);

/*
** Diffuses over the time t (>= 0) with the coefficient D (>= 0), on
** 'threads' workers (the same amounts for every number); *substeps (may be
** NULL) gets m. Returns LSYS_OK; LSYS_EARG (D or t not finite and >= 0, or
** more than LSYS_FIELD_MAXSUBSTEPS substeps: e says so).
*/
int lsys_space_field_diffuse (lsys_field *F, double D, double t, int threads, long *substeps,
                              lsys_error *e);

/*
** The n points (3 doubles each) take from the cells they are in: point i
** asks for want[i] (>= 0, finite) and gets it into got[i] when its cell has
** enough for all who ask there, else its share want[i] q / (the sum asked
** there), so the answer does not depend on the points' order; the cells
** lose what was given. A point outside the grid gets 0. Returns LSYS_OK;
** LSYS_EARG (a point not finite, a bad amount: nothing is taken).
*/
int lsys_space_field_take (lsys_field *F, const double *points, const double *want, size_t n,
                           double *got, lsys_error *e);

/* Adds amount[i] to the cell of point i (an amount < 0 takes, down to 0);
** points outside the grid add nothing. Returns how many were inside, or -1
** for a point or amount not finite (e says which; nothing is added). */
long long lsys_space_field_add (lsys_field *F, const double *points, const double *amount,
                                size_t n, lsys_error *e);

/* The gradient of the amounts at p into g (central differences between the
** neighbouring cells, one-sided at the box's faces; 0 across an axis of one
** cell and outside the grid), amount per unit length. */
void lsys_space_field_gradient (const lsys_field *F, const double p[3], double g[3]);

/* The sum of the amounts. */
double lsys_space_field_total (const lsys_field *F);

#endif
