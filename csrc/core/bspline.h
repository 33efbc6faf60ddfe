/*
** Uniform B-spline curves of degree 2 or 3 in 2 or 3 dimensions, and the
** polyline operations of stroke capture (Anastacio et al. 2009, §3.1):
** resampling to equal spacing, Chaikin subdivision and its reverse.
**
** A curve has n >= degree + 1 control points P_0 .. P_(n-1), 'dim' doubles
** each (interleaved). Its knots are integers, in one of two layouts:
**
**   uniform (floating)   u_j = j, j = 0 .. n + degree; the curve runs over
**                        [degree, n] and does not reach P_0 nor P_(n-1);
**   clamped (open)       degree + 1 knots 0, then 1 .. n - degree - 1, then
**                        degree + 1 knots n - degree; the curve runs over
**                        [0, n - degree] from P_0 to P_(n-1) (as the curves
**                        of cpfg's function editor).
**
** Either way the curve has n - degree polynomial spans of unit knot length.
** The public parameter t in [0, 1] is normalised over the whole curve:
** t = (u - u_start) / (n - degree); derivatives are taken with respect to t.
** Evaluation finds the span in O(1) and costs O(degree^2).
*/
#ifndef LSYS_BSPLINE_H
#define LSYS_BSPLINE_H

#include "common.h"

#define LSYS_BSPLINE_MAXPOINTS 10000000   /* control points, polyline points */
#define LSYS_BSPLINE_MAXHITS   10000000   /* intersections of one call */

typedef struct lsys_bspline {
  double *pt;        /* dim doubles per control point */
  double *knot;      /* n + degree + 1 knots */
  double *cum;       /* n - degree + 1 arc lengths from the start to each span's start */
  size_t n;          /* control points */
  int dim;           /* 2 or 3 */
  int degree;        /* 2 or 3 */
  int clamped;       /* 1 clamped, 0 uniform */
} lsys_bspline;

void lsys_bspline_init (lsys_bspline *c);
void lsys_bspline_free (lsys_bspline *c);

/*
** Sets 'c' from n control points (dim doubles each, copied). Refuses
** (LSYS_EARG, e set, 'c' unchanged) a degree other than 2 or 3, a dim other
** than 2 or 3, fewer than degree + 1 points, more than
** LSYS_BSPLINE_MAXPOINTS, or a coordinate that is not finite (the message
** names it: "point 3: coordinate 2 is not finite", points counted from 1).
** Computes the arc length of every span. Returns LSYS_OK, LSYS_EARG,
** LSYS_ELIMIT (too many points) or LSYS_ENOMEM.
*/
int lsys_bspline_set (lsys_bspline *c, const double *pt, size_t n, int dim, int degree,
                      int clamped, lsys_error *e);

/* Number of polynomial spans, n - degree. */
size_t lsys_bspline_spans (const lsys_bspline *c);

/*
** The point (k = 0) or its k-th derivative with respect to t (k = 1, 2)
** at t, clamped into [0, 1], into out[0 .. dim). NaN t gives t = 0.
*/
void lsys_bspline_eval (const lsys_bspline *c, double t, int k, double *out);

/*
** The degree + 1 basis functions that are not zero at t (clamped into
** [0, 1]), or their k-th derivative with respect to t (k = 0, 1, 2): N[j]
** belongs to control point first + j. Returns 'first'. The functions
** (k = 0) are non-negative and sum to 1 (partition of unity).
*/
size_t lsys_bspline_basis (const lsys_bspline *c, double t, int k, double *N);

/* 'm' >= 2 points at t = i / (m - 1), i = 0 .. m - 1, into out (m * dim). */
void lsys_bspline_sample (const lsys_bspline *c, size_t m, double *out);

/*
** Arc length of the whole curve, and of the piece between t0 and t1 (both
** clamped into [0, 1]; negative when t1 < t0). Each span is integrated by
** adaptive Gauss-Legendre quadrature to about 1e-12 relative error.
*/
double lsys_bspline_length (const lsys_bspline *c);
double lsys_bspline_length_between (const lsys_bspline *c, double t0, double t1);

/*
** The t at which the arc length from the start is s (clamped into
** [0, length]): the span by bisection of the span lengths, then Newton's
** method on s(t) kept inside a shrinking bracket (bisection when a step
** leaves it). A zero-length curve gives t = 0.
*/
double lsys_bspline_at_length (const lsys_bspline *c, double s);

/* 'm' >= 2 points at equal arc length (the first and last ends of the
** curve) into out (m * dim), and their parameters into t (NULL: not). */
void lsys_bspline_sample_length (const lsys_bspline *c, size_t m, double *out, double *t);

/*
** The point of the curve closest to q (dim doubles): its t and distance.
** Spans whose control-point box lies farther than the best distance so far
** are skipped; in the others, the best of 8 samples is refined by Newton's
** method on (C(u) - q) . C'(u) = 0 within the span, and the span's ends are
** candidates too. Exact for the global minimum in all but contrived cases
** (two nearly equidistant local minima closer than the sampling).
*/
void lsys_bspline_closest (const lsys_bspline *c, const double *q, double *t, double *dist);

/* An intersection: t on the curve, s along the ray (ray) or the parameter
** of the other curve (curve-curve), and the point. */
typedef struct lsys_bspline_hit {
  double t, s, x, y;
} lsys_bspline_hit;

/*
** All intersections of a 2D curve with the ray o + s d, s >= 0 (d need not
** be unit, s is in units of |d|), sorted by s: writes at most 'cap' of them
** to 'hits' and sets *count to how many there are (call again with a
** larger array when *count > cap). Per span the signed distance to the ray's
** line is a polynomial in Bernstein form; intervals whose coefficients have
** one sign are dropped, one sign change is solved by safeguarded Newton,
** more are split in two (at most 60 levels). A ray that starts on the curve
** reports s = 0. Crossings at a joint of two spans are reported once.
** Tangent touches (a double root) are reported at most once and usually not
** at all; a stretch of the curve lying along the ray is not reported.
** Returns LSYS_OK, LSYS_EARG (a 3D curve, d = 0 or not finite, o not
** finite) or LSYS_ELIMIT (more than LSYS_BSPLINE_MAXHITS), e set.
*/
int lsys_bspline_ray (const lsys_bspline *c, const double o[2], const double d[2],
                      lsys_bspline_hit *hits, size_t cap, size_t *count, lsys_error *e);

/*
** All crossings of two 2D curves a and b: hit.t on a, hit.s on b, sorted by
** t. Pairs of spans whose control-point boxes overlap are subdivided in
** Bezier form (halving the larger piece, at most 52 levels) until both
** pieces are flat to 1e-9 of the curves' size; their chords are then
** crossed and the point refined by Newton's method on a(t) = b(s).
** Crossings found twice (at span joints) are reported once; tangent touches
** at most once; overlapping stretches are not reported. Same buffer
** contract as lsys_bspline_ray. Returns LSYS_OK, LSYS_EARG (a 3D curve) or
** LSYS_ELIMIT (more than LSYS_BSPLINE_MAXHITS crossings or 50 million
** subdivision steps), e set.
*/
int lsys_bspline_intersect (const lsys_bspline *a, const lsys_bspline *b,
                            lsys_bspline_hit *hits, size_t cap, size_t *count, lsys_error *e);

/* ---------------------------------------------------------------------- */
/* Polylines: n points of dim (2 or 3) doubles each. */

/*
** Checks a polyline (n >= 2 ... LSYS_BSPLINE_MAXPOINTS points, dim 2 or 3,
** finite coordinates, spacing > 0 and finite) and counts the points of its
** resampling: m = max(1, round(L / spacing)) + 1 for its length L. Returns
** LSYS_OK, LSYS_EARG or LSYS_ELIMIT (m above LSYS_BSPLINE_MAXPOINTS), e set.
*/
int lsys_bspline_resample_count (const double *pt, size_t n, int dim, double spacing,
                                 size_t *m, lsys_error *e);

/*
** Resamples a polyline to 'm' >= 2 points equally spaced along it (spacing
** L / (m - 1), the nearest to the one asked for that divides L): the first
** and last points are kept exactly (Anastacio et al. 2009, §3.1: one point
** per pixel). A zero-length polyline gives m copies of its first point.
** 'out' holds m * dim doubles and must not overlap 'pt'.
*/
void lsys_bspline_resample (double *out, size_t m, const double *pt, size_t n, int dim);

/*
** One step of Chaikin's corner cutting on an open polyline of n >= 2
** points: every edge (c_i, c_(i+1)) gives 3/4 c_i + 1/4 c_(i+1) and
** 1/4 c_i + 3/4 c_(i+1), and the two end points are kept, so the result has
** 2n points f_0 = c_0, f_(2i+1), f_(2i+2) (edge i), f_(2n-1) = c_(n-1).
** 'out' holds 2n * dim doubles and must not overlap 'pt'.
*/
void lsys_bspline_chaikin (double *out, const double *pt, size_t n, int dim);

/*
** One step of Chaikin reverse subdivision (Anastacio et al. 2009, §3.1,
** after Samavati and Bartels): n >= 3 fine points f give m = (n + 1) / 2
** (integer division) coarse points c with the regular local filter
**
**     c_i = -1/4 f_(2i-1) + 3/4 f_(2i) + 3/4 f_(2i+1) - 1/4 f_(2i+2),
**
** i = 1 .. m - 2, and the boundary rule c_0 = f_0, c_(m-1) = f_(n-1) (the
** ends are kept). With the layout of lsys_bspline_chaikin the filter is
** exact: the two fine points around c_i are f_(2i) = 1/4 c_(i-1) +
** 3/4 c_i and f_(2i+1) = 3/4 c_i + 1/4 c_(i+1), and the combination gives
** c_i, so reverse(chaikin(c)) = c for every c (for odd n the last interior
** point reads f_(n-1) as its f_(2i+2)). Returns m. 'out' may be 'pt'
** (the filter reads only points at or after the one it writes).
*/
size_t lsys_bspline_chaikin_reverse (double *out, const double *pt, size_t n, int dim);

/*
** The whole stroke capture of Anastacio et al. 2009, §3.1: resamples the
** polyline to one point per 'spacing', then applies up to 'steps' reverse
** subdivisions, stopping before one that would leave fewer than
** degree + 1 points; when the resampling itself has fewer than
** degree + 1 points, the polyline is resampled to exactly degree + 1
** equally spaced points instead (a 2-point stroke gives a straight curve).
** The result is the control points of a curve of that degree (clamped ones
** start and end at the stroke's ends). 'out' holds 'cap' points, at least
** lsys_bspline_stroke_size's. Sets *nout. Returns LSYS_OK, LSYS_EARG
** (bad polyline as lsys_bspline_resample_count says; steps < 0; degree
** not 2 or 3; a stroke of zero length: "the stroke has no length") or
** LSYS_ELIMIT, e set.
*/
int lsys_bspline_stroke (double *out, size_t cap, const double *pt, size_t n, int dim,
                         double spacing, int steps, int degree, size_t *nout, lsys_error *e);

/* The number of points 'out' of lsys_bspline_stroke needs; same checks and
** returns as lsys_bspline_resample_count. */
int lsys_bspline_stroke_size (const double *pt, size_t n, int dim, double spacing, int degree,
                              size_t *cap, lsys_error *e);

#endif
