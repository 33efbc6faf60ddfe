/*
** What bspline.c shares with bspline_hit.c (the intersections): evaluation
** at a knot value u inside a given span and the Bezier form of a span.
** Not part of the core's interface.
*/
#ifndef LSYS_BSPLINE_IMPL_H
#define LSYS_BSPLINE_IMPL_H

#include "bspline.h"

/* The domain of the curve in knot values: [c->knot[degree], c->knot[n]]. */
#define BS_U0(c) ((c)->knot[(c)->degree])
#define BS_U1(c) ((c)->knot[(c)->n])

/* The span s (degree .. n - 1) that holds knot value u (clamped). */
size_t lsys_bspline_span (const lsys_bspline *c, double u);

/* The point (k = 0) or k-th derivative with respect to u (k = 0 .. degree)
** at u using span s, into out[0 .. dim). */
void lsys_bspline_eval_span (const lsys_bspline *c, size_t s, double u, int k, double *out);

/* The degree + 1 Bezier control points of span s (u from knot[s] to
** knot[s] + 1), dim doubles each, into bz. */
void lsys_bspline_bezier (const lsys_bspline *c, size_t s, double *bz);

#endif
