/*
** Triangulation of the turtle's polygons ('{' ... '}', cpfg guide §4.2):
** planar or nearly planar, convex or concave, given as a closed ring of 3D
** points.
*/
#ifndef LSYS_POLYGON_H
#define LSYS_POLYGON_H

#include "common.h"

/* Scratch arrays, grown by doubling and reused from one polygon to the next.
** A zeroed struct is a valid empty one; lsys_polywork_free releases it. */
typedef struct lsys_polywork {
  double *xy;                 /* projected points, 2 per vertex */
  size_t xycap;
  uint32_t *link;             /* 4 per vertex: ring prev/next, reflex list prev/next */
  size_t linkcap;
  uint8_t *state;             /* per vertex: convex, reflex or removed */
  size_t statecap;
  uint32_t *tris;             /* the result: 3 vertex numbers per triangle */
  size_t tcap;
} lsys_polywork;

void lsys_polywork_free (lsys_polywork *w);

/*
** Triangulates the polygon of 'n' vertices 'pts' (x, y, z each; the last
** vertex connects back to the first) in the plane of its Newell normal,
** which is written to 'normal' (unit; (0, 0, 1) when the polygon has no
** area). Each triangle is written as 3 vertex numbers (0 .. n-1) into the
** array that '*tris' is set to (owned by 'w', valid until its next use),
** counter-clockwise seen from the side 'normal' points to.
** Returns the number of triangles: n - 2 for a simple polygon, fewer when
** repeated points, collinear vertices or a zero-area polygon are dropped;
** or LSYS_ENOMEM, or LSYS_ELIMIT when n does not fit 32-bit vertex numbers.
** A self-intersecting polygon still gives triangles (a fan of what resists
** ear clipping) in O(n^2) time.
*/
long lsys_polygon_triangulate (lsys_polywork *w, const double *pts, size_t n,
                               double normal[3], const uint32_t **tris);

#endif
