/*
** The light environment (docs/architecture.md): how much of the sky each
** point of a plant sees through the plant's geometry, after Měch and
** Prusinkiewicz 1996 (the light a leaf receives) and Palubicki et al. 2009
** (a bud's exposure Q, and the direction of most light that its shoot turns
** to). Rays from the point towards the sky's directions are cast through a
** bounding volume hierarchy over the scene's triangles (and, when asked,
** its line segments as capsules); the core owns a copy of what it needs, so
** the scene may be freed once the light is built.
**
** The sky is a set of K directions d_k with weights w_k summing to 1; a
** point p receives
**
**     E(p) = sum_k w_k c_k V(p, d_k)      in [0, 1]
**
** where V(p, d) is 1 when the ray p + t d, t > offset, hits nothing (with a
** transmittance tau > 0: tau^hits, counting at most max_hits hits) and c_k
** is 1 without a normal (a bud: every direction counts) or, with the unit
** normal n, max(0, n . d_k) (a leaf's irradiance: directions below its
** tangent plane count 0). So an unoccluded bud gets 1; an unoccluded
** horizontal leaf gets the sky's sum_k w_k d_k.y: 1/2 under the uniform
** overcast sky, 2/3 under the cosine sky, 7/12 under the CIE overcast sky,
** cos(zenith angle) under the sun alone.
**
** The world is y up, as the turtle's (it starts heading +y); the overcast
** sky is the upper hemisphere, y > 0.
**
** Triangles occlude from both faces. A line segment occludes as a capsule
** of the line radius (world units, whatever its width in pixels) only from
** outside: a point in it (a bud on a line-style stem) is not shadowed by it.
** A point inside a closed surface (on the axis of a cylinder-style stem) is
** shadowed by that surface: such points are to be moved out of it, or the
** offset set above the stem's radius.
*/
#ifndef LSYS_LIGHT_H
#define LSYS_LIGHT_H

#include "common.h"
#include "scene.h"

#define LSYS_LIGHT_MAXTHREADS 64    /* threads of one query, as derive.h's LSYS_MAXTHREADS */
#define LSYS_LIGHT_MAXSAMPLES 65536 /* directions of the overcast sky */
#define LSYS_LIGHT_MAXHITS 64       /* hits counted along one ray (transmittance) */

/* The sky's kind. */
enum {
  LSYS_LIGHT_OVERCAST = 0,   /* 'samples' directions over the upper hemisphere */
  LSYS_LIGHT_SUN = 1,        /* one direction, plus an 'ambient' fraction of overcast */
  LSYS_LIGHT_DIRS = 2        /* the caller's weighted directions */
};

/* The overcast sky's radiance by zenith angle theta: the weights of its
** directions, which a Fibonacci spiral spreads evenly (equal solid angles)
** over the hemisphere. */
enum {
  LSYS_LIGHT_UNIFORM = 0,    /* equal radiance: the fraction of the open sky */
  LSYS_LIGHT_COSINE = 1,     /* radiance cos theta */
  LSYS_LIGHT_CIE = 2         /* the CIE standard overcast sky (Moon and Spencer): 1 + 2 cos theta */
};

typedef struct lsys_light_opts {
  int kind;                  /* LSYS_LIGHT_OVERCAST (default), _SUN or _DIRS */
  int radiance;              /* the overcast part's: LSYS_LIGHT_UNIFORM (default), ... */
  int samples;               /* overcast directions, 1 .. LSYS_LIGHT_MAXSAMPLES; 0: 64 */
  double sun[3];             /* _SUN: the direction towards the sun (not normalised) */
  double ambient;            /* _SUN: the overcast sky's share of the weight, [0, 1] */
  const double *dirs;        /* _DIRS: x, y, z, w for each of 'ndirs' directions, w >= 0 */
  size_t ndirs;
  double transmittance;      /* the fraction of light a surface lets through, [0, 1): 0 opaque */
  int max_hits;              /* hits counted along a ray, 1 .. LSYS_LIGHT_MAXHITS; 0: 8 */
  double line_radius;        /* >= 0, world units: line segments occlude as capsules of this
                                radius; 0 (default): lines do not occlude */
  double offset;             /* > 0, world units: hits nearer than this to a point are not
                                counted; 0: 1e-4 of the scene's bounding-box diagonal */
  double max_distance;       /* > 0, world units: hits this far or farther along a ray are not
                                counted (ambient occlusion's reach); 0 (default): no limit */
  lsys_meter *meter;         /* the memory budget of the build (NULL: none) */
} lsys_light_opts;

typedef struct lsys_light lsys_light;

/* What a built light holds. */
typedef struct lsys_light_stats {
  size_t triangles, capsules;   /* primitives (degenerate and non-finite ones left out) */
  size_t nodes, depth;          /* of the hierarchy */
  size_t bytes;                 /* the memory the light holds */
  size_t ndirs;                 /* sky directions */
  double offset;                /* in world units */
} lsys_light_stats;

/* Fills 'o' with the defaults: the uniform overcast sky of 64 directions,
** opaque surfaces, lines that do not occlude, no meter. */
void lsys_light_defaults (lsys_light_opts *o);

/*
** Builds the light of scene 's' under the options 'o' (NULL: the defaults)
** into *L. The scene's triangles (and, with a line radius, its line
** segments) are copied, under their instances' transforms when it has
** instances (a population: each instance's part), so 's' may change or be
** freed afterwards. The hierarchy is built by binned surface area
** heuristic in O(n log n). Returns LSYS_OK; LSYS_EARG for a bad option
** (message in e); LSYS_ELIMIT (more than 2^31 primitives); LSYS_EMEMORY
** (the light would exceed the meter: message in e); LSYS_ENOMEM. *L is
** NULL on failure.
*/
int lsys_light_build (lsys_light **L, const lsys_scene *s, const lsys_light_opts *o,
                      lsys_error *e);

void lsys_light_free (lsys_light *L);

/*
** The light E (above) at each of the 'n' points (3 doubles each) into
** out[0 .. n): normals_or_null gives each point's normal (3 doubles each,
** normalised here) or NULL for none; dir_out, when not NULL, gets 3
** doubles a point: the mean unoccluded direction, normalised (sum_k w_k c_k
** V_k d_k; 0, 0, 0 when every direction is blocked). 'threads' workers (1
** to LSYS_LIGHT_MAXTHREADS; out of range is clamped) share the points in
** chunks; the results are the same for every number of threads. Allocates
** per query (the points' order, the normals), nothing per ray. Returns
** LSYS_OK; LSYS_ENOMEM; LSYS_EARG for more than 2^32 points, or a point or
** normal that is not finite or a zero normal (e names it; nothing is
** written).
*/
int lsys_light_query (const lsys_light *L, const double *points, size_t n,
                      const double *normals_or_null, double *out, double *dir_out, int threads,
                      lsys_error *e);

/* The counts and sizes of L. */
void lsys_light_info (const lsys_light *L, lsys_light_stats *st);

/* The sky's directions (unit, 3 doubles each) and weights (summing to 1):
** *dirs and *w point into L, valid while it lives. Returns their number. */
size_t lsys_light_sky (const lsys_light *L, const double **dirs, const double **w);

/*
** The hits along the ray o + t d, offset < t < max_distance (d need not be unit; it is
** used as given), counted up to 'cap' (>= 1): through the hierarchy, or
** with 'brute' by testing every primitive (the reference the tests compare
** the hierarchy with). Both test each primitive the same way, so they agree
** exactly.
*/
int lsys_light_hits (const lsys_light *L, const double o[3], const double d[3], int cap,
                     int brute);

#endif
