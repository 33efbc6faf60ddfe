/*
** Shadows and ambient occlusion baked into a scene's vertices (docs/drawing.md
** "Shadows, ambient occlusion, ground and sky"). The fixed-function renderer
** lights each vertex with the key light alone, so it draws no shadows; this
** computes, with the light environment's ray caster (light.h), a factor per
** vertex in [0, 1] by which the renderer scales the vertex's diffuse colour.
**
** Shadow: one ray (or, with a soft edge, several rays spread over a cone of
** the given angle around it) from the vertex towards the key light; the
** blocked fraction b darkens the vertex by strength * b. Ambient occlusion:
** rays over the hemisphere of the vertex's normal (a Fibonacci spiral over
** the sphere, each weighted by its cosine to the normal), hits nearer than
** the distance counting; the cosine-weighted blocked fraction b darkens it
** by strength * b. A two-sided vertex takes the mean of its two faces. The
** factor is the product of the two. Rays start a little off the surface,
** along the normal, so that a surface does not shadow its own vertices.
*/
#ifndef LSYS_SHADE_H
#define LSYS_SHADE_H

#include "common.h"
#include "scene.h"

#define LSYS_SHADE_MAXSAMPLES 1024   /* ambient occlusion rays per face */

typedef struct lsys_shade_opts {
  int shadows;              /* 1: shadows of the key light */
  double softness;          /* the cone of the shadow rays in degrees, [0, 30]; 0: one ray */
  double shadow_strength;   /* [0, 1]: how much a fully blocked vertex is darkened */
  int ao;                   /* 1: ambient occlusion */
  int ao_samples;           /* rays per face, 1 .. LSYS_SHADE_MAXSAMPLES */
  double ao_distance;       /* > 0 world units: the reach of the rays; 0: 1/4 of the
                               scene's bounding-box diagonal */
  double ao_strength;       /* [0, 1] */
  int threads;              /* workers, 1 .. LSYS_LIGHT_MAXTHREADS (the result is the same) */
  lsys_meter *meter;        /* the memory budget (NULL: none) */
} lsys_shade_opts;

/* The defaults: neither shadows nor ambient occlusion; softness 0, shadow
** strength 0.6, 16 rays, distance 0 (a quarter diagonal), ambient strength
** 0.6, 1 thread. */
void lsys_shade_defaults (lsys_shade_opts *o);

/*
** The factors of the vertices of scene s's mesh into out[0 .. nv), as
** bytes (255: unchanged). A scene with instances (a population) is not
** shaded: every factor 255. Returns LSYS_OK; LSYS_EARG for a bad option (e
** names it); LSYS_EMEMORY (beyond the meter); LSYS_ENOMEM.
*/
int lsys_shade_compute (uint8_t *out, const lsys_scene *s, const lsys_shade_opts *o,
                        lsys_error *e);

/* The ground plane under a scene (lsys_shade_add_ground). */
typedef struct lsys_shade_ground {
  double size;              /* > 0: its side over the plant's widest extent (and at least
                               its height's half); default 1.6 */
  int cells;                /* cells along a side, 1 .. 1024 (lsys.render's default 160) */
  unsigned col;             /* its colour index: col .. col + nfade - 1 when nfade > 1 */
  unsigned nfade;           /* > 1: colours col .. col + nfade - 1 from the distance of the
                               square's half side from its centre out to 2.5 times that
                               (LSYS_SHADE_GROUND_FADE), so that a ground grown far fades
                               into what is behind it */
  int has_rect;             /* 1: the ground reaches over rect too (what a camera sees) */
  double rect[4];           /* x0, z0, x1, z1 */
} lsys_shade_ground;

/* The farthest a ground reaches from the plant's centre in x or z, in halves
** of its default square's side (a camera looking at the horizon). */
#define LSYS_SHADE_GROUND_REACH 4
#define LSYS_SHADE_GROUND_FADE 2.5

/*
** Appends to m a grid of quads facing up (+y), just under m's lowest point
** (by 1e-3 of its diagonal), coloured g->col, solid (one-sided): a square
** centred under its bounding box and g->size times its widest horizontal
** extent (at least half its height) across, of cells x cells cells, grown to
** cover g->rect (when has_rect) within LSYS_SHADE_GROUND_REACH half sides of
** the centre, with cells of the same size (fewer, larger ones when that
** would make more than 4 cells^2). Returns LSYS_OK, LSYS_EARG (bad size or
** cells: e names it), LSYS_ENOMEM; nothing for an empty mesh.
*/
int lsys_shade_add_ground (lsys_mesh *m, const lsys_shade_ground *g, lsys_error *e);

/* Half the side of the square lsys_shade_add_ground puts under m (0: m is empty). */
double lsys_shade_ground_half (const lsys_mesh *m, const lsys_shade_ground *g);

#endif
