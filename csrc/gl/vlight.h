/*
** Leaves coloured by the light they receive, in the viewer window (the L key,
** docs/viewer.md "Light on the leaves"). Plain memory and the core's light
** (light.h), no window and no Lua: the caller computes the colours of a
** posted frame on its own thread (the window goes on drawing meanwhile) and
** hands them to the window (lsys_viewer_light), which draws the frame with
** them instead of the model's colours while the key is on.
**
** The leaves are the triangles of the frame's discs, polygons and surfaces
** (the turtle records of those kinds, whose triangles are two-sided); the
** stems (segments, cylinders, generalized cylinders, spheres) and the lines
** keep their colours. Each leaf triangle gets the light at its centroid from
** the uniform overcast sky of 64 directions (light.h), shaded by every
** triangle of the frame, through the face of the leaf that looks up (a leaf
** is two-sided: the face whose normal has y >= 0 receives the sky), relative
** to an open horizontal leaf: 1 in the open, 0 in full shade (the
** normalisation of lsys.environment.light with facing). A vertex takes the
** area-weighted mean of the leaf triangles around it, so that the colour
** varies smoothly across a leaf, and that value picks one of
** LSYS_VLIGHT_BINS steps of the ramp (lsys_vlight_ramp), dark purple at 0
** through teal and green to yellow at 1.
*/
#ifndef LSYS_VLIGHT_H
#define LSYS_VLIGHT_H

#include "viewer.h"

#define LSYS_VLIGHT_BINS 64     /* steps of the ramp, appended to the frame's palette */
#define LSYS_VLIGHT_SAMPLES 64  /* directions of the overcast sky */

/* The light colours of one frame: its mesh's colour (and texture) indices
** and palette as drawn with them, and what they show. */
typedef struct lsys_vlight {
  uint16_t *col;                /* nv: a leaf vertex's npal0 + its step of the ramp; the
                                   others their own index modulo npal0 (the frame's palette
                                   size, 1 when it has none) */
  uint16_t *tex;                /* nv: the leaves untextured, or NULL (the mesh's) */
  uint16_t *lcol;               /* nl: the lines' colour indices modulo npal0, or NULL (the
                                   mesh's, all below npal0) */
  lsys_material *pal;           /* npal0 + LSYS_VLIGHT_BINS materials */
  size_t npal;
  size_t nleaves;               /* leaf triangles given a light (0: see msg) */
  double min, max, mean;        /* their light; the mean weighted by area */
  char msg[256];                /* why no leaf is coloured, or "" */
} lsys_vlight;

/* The colour of light x (clamped to [0, 1]) on the ramp, rgb in [0, 1]. */
void lsys_vlight_ramp (double x, float rgb[3]);

/*
** The triangles of frame f's leaf records among the records of s (discs,
** polygons, surfaces: their tri0, ntri) into f->leafr, as ranges [a, b)
** merged where they touch. A population (f->sc.ninst > 0) gets none.
** Returns LSYS_OK or LSYS_ENOMEM (f->leafr NULL).
*/
int lsys_vlight_leaves (lsys_vframe *f, const lsys_scene *s);

/*
** Computes the light colours of frame f into *l (emptied first; free with
** lsys_vlight_free), with 'threads' workers (the results are the same for
** any number) and the memory budget 'mt' (NULL: none) counting the light's
** hierarchy and the scratch. A frame with nothing to colour (no leaves, a
** population, a live frame) gets l->nleaves = 0 and l->msg saying so.
** Returns LSYS_OK, LSYS_EMEMORY (e->msg names max_memory), LSYS_ELIMIT or
** LSYS_ENOMEM (then *l is empty).
*/
int lsys_vlight_compute (lsys_vlight *l, const lsys_vframe *f, int live, int threads,
                         lsys_meter *mt, lsys_error *e);

/* Frees the arrays of l and leaves it empty. */
void lsys_vlight_free (lsys_vlight *l);

/* Scene 'sc', a copy of frame f's (borrowing its arrays), drawn with the
** light colours l instead (when it has any). */
void lsys_vlight_apply (const lsys_vlight *l, lsys_scene *sc);

/* The legend's last line for l (NULL: not computed yet) into buf[n]:
** "0.05 - 1.00, mean 0.61", or why nothing is coloured. */
void lsys_vlight_note (const lsys_vlight *l, char *buf, size_t n);

#endif
