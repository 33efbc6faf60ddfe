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

#endif
