/*
** Triangulation of the turtle's polygons ('{' ... '}', cpfg guide §4.2):
** planar or nearly planar, convex or concave, given as a closed ring of 3D
** points.
*/
#ifndef LSYS_POLYGON_H
#define LSYS_POLYGON_H

#include "common.h"

/* The most vertices of one polygon (the turtle refuses more, naming the module), and
** the most points the ear tests of a polygon of n vertices may look at, in units of
** n log2 n (past it the polygon is refused: see lsys_polygon_triangulate). */
#define LSYS_POLYGON_MAXV (1u << 24)
#define LSYS_POLYGON_MAXWORK 256

/* Scratch arrays, grown by doubling and reused from one polygon to the next.
** A zeroed struct is a valid empty one; lsys_polygon_work_free releases it. */
typedef struct lsys_polywork {
  double *xy;                 /* projected points, 2 per vertex */
  size_t xycap;
  uint32_t *link;             /* 4 per vertex: ring prev/next, reflex list prev/next */
  size_t linkcap;
  uint8_t *state;             /* per vertex: convex, reflex or removed */
  size_t statecap;
  uint32_t *tris;             /* the result: 3 vertex numbers per triangle */
  size_t tcap;
  uint32_t *kd;               /* 3 per vertex: the 2-d tree's order, counts, positions */
  size_t kdcap;
  uint8_t *kdaxis;            /* per tree node: the axis it splits */
  size_t kdaxiscap;
  float *kdbox;               /* 4 per tree node: the box of its points */
  size_t kdboxcap;
  uint32_t *queue;            /* 6 per vertex: the heap of candidates and the waits */
  size_t qcap;
  double *key;                /* per vertex: its triangle's size, the heap's order */
  size_t keycap;
  lsys_meter *meter;          /* the budget the arrays grow within (NULL: none); the
                                 caller's, as the turtle's interpretation meter */
} lsys_polywork;

void lsys_polygon_work_free (lsys_polywork *w);

/*
** Triangulates the polygon of 'n' vertices 'pts' (x, y, z each; the last
** vertex connects back to the first) in the plane of its Newell normal,
** which is written to 'normal' (unit; (0, 0, 1) when the polygon has no
** area). Each triangle is written as 3 vertex numbers (0 .. n-1) into the
** array that '*tris' is set to (owned by 'w', valid until its next use),
** counter-clockwise seen from the side 'normal' points to.
** Returns the number of triangles: n - 2 for a simple polygon, fewer when
** repeated points, collinear vertices or a zero-area polygon are dropped;
** or LSYS_ENOMEM, LSYS_EMEMORY (w->meter), or LSYS_ELIMIT when n is over
** LSYS_POLYGON_MAXV or the ear tests would look at more than
** LSYS_POLYGON_MAXWORK * n * log2(n) points. Ear tests look for reflex
** vertices in a 2-d tree and a big polygon is cut from a heap, so a comb of
** 512,000 vertices takes well under a second (polygon.c says more); a
** self-intersecting polygon still gives triangles (a fan of what resists ear
** clipping).
*/
long lsys_polygon_triangulate (lsys_polywork *w, const double *pts, size_t n,
                               double normal[3], const uint32_t **tris);

#endif
