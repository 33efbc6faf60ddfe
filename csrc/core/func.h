/*
** Positional functions (Anastacio et al. 2009, §4; Prusinkiewicz et al.
** 2001): functions y = f(x) of a relative position x in [0, 1], drawn as a
** clamped cubic B-spline in the plane, as cpfg's function files define them.
**
** n >= 4 control points (x_i, y_i), x nondecreasing from 0 to 1. The knots
** are 0,0,0,0,1,2,...,n-3,n-3,n-3,n-3, so the curve starts at the first
** point and ends at the last; f(x) is the y of the curve point whose x is
** the argument. As the control x never decrease, x(t) never decreases
** either, and each value is found exactly: the span whose x range holds the
** argument, then Newton's method with a bisection safeguard on that span's
** polynomial, to full double precision (cpfg bisects to 0.001 in x). Where
** the curve has a vertical piece (x constant over a range of t), f takes
** the y at the lowest such t. Arguments are clamped to [0, 1] as in cpfg; a
** NaN argument gives NaN.
**
** With samples > 2 (cpfg's "samples:"), f is the linear interpolation of
** 'samples' exact values at x = i / (samples - 1), computed as cpfg does, so
** a cpfg model's numbers match cpfg's. samples 0, 1 or 2: exact values.
**
** Files: the old form "range: 0.0 1.0" / "points: N" / N lines "x y"; the
** form "fver 1 1" / "name: NAME" / "samples: S" / optional "background"
** lines / optional "markers: K" + K lines "mI x y" / optional "flip: on|off"
** / "points: N" / N lines "x y [multiplicity]"; and function sets
** "funcgalleryver 1 1" / "items: K" / K functions in the fver 1 1 form.
*/
#ifndef LSYS_FUNC_H
#define LSYS_FUNC_H

#include <stddef.h>

#include "common.h"

#define LSYS_FUNC_MAXPOINTS 65536     /* control points, multiplicities expanded */
#define LSYS_FUNC_MAXSAMPLES 1000000  /* the samples table */
#define LSYS_FUNC_MAXITEMS 1024       /* functions in a set */
#define LSYS_FUNC_MAXNAME 127         /* bytes of a name */
#define LSYS_FUNC_XTOL 1e-6           /* the first x is 0, the last 1, within this */

typedef struct lsys_func {
  double *pt;         /* 2 doubles per control point: x, y */
  size_t n;           /* control points (>= 4 once set) */
  char name[LSYS_FUNC_MAXNAME + 1];
  int samples;        /* 0: exact; > 2: the table 'vals' is used */
  double *vals;       /* 'samples' values at i / (samples - 1), or NULL */
  double *bez;        /* per span (n - 3 of them): the Bezier points x0..x3, y0..y3 */
  int cpfg;           /* 1: cpfg's approximation (lsys_func_cpfg) */
} lsys_func;

void lsys_func_init (lsys_func *f);
void lsys_func_free (lsys_func *f);     /* idempotent; leaves 'f' empty */

/*
** Sets 'f' from n points (x, y pairs in 'pt'), a name (1 to
** LSYS_FUNC_MAXNAME bytes, no control characters) and samples (0 to
** LSYS_FUNC_MAXSAMPLES). Checks: 4 <= n <= LSYS_FUNC_MAXPOINTS, finite
** coordinates of magnitude at most 1e9, x nondecreasing, the first x 0 and
** the last 1 within LSYS_FUNC_XTOL (other ends are errors, not clamped).
** Messages name the point ("point 3: x is 0.2, less than the x of point 2
** (0.5)"). Returns LSYS_OK, LSYS_EARG (e set; 'f' unchanged) or
** LSYS_ENOMEM.
*/
int lsys_func_set (lsys_func *f, const double *pt, size_t n, const char *name, int samples,
                   lsys_error *e);

/* f(x) for a set function: see above. */
double lsys_func_eval (const lsys_func *f, double x);

/*
** Switches 'f' to cpfg's approximation (vlab: cpfg/splinefun.cpp), for
** models that must give cpfg's numbers: the control points are rounded to
** float32 (cpfg reads them as floats) and a value is the y of the curve
** point found by bisecting the curve parameter until its x is within 0.001
** of the argument (at most 64 halvings); with samples > 2 the table holds
** such values. cpfg's Lilac gives a branching angle of 53.1232 where the
** exact value is 53.1316. Allocates nothing.
*/
void lsys_func_cpfg (lsys_func *f);

/*
** Parses the text of a .func or .fset file into a new array of *nout
** functions (one for a .func), which the caller frees with lsys_func_free
** on each and LSYS_FREE on the array. 'text' need not be NUL-terminated.
** 'name' (the file name) starts every message: "name:LINE: what is wrong".
** 'samples' applies to the old "range:" form only (cpfg takes it from the
** view file's "function:" line; < 0 means 0); the fver form carries its
** own. The old form has no name inside: the function is named after the
** file ('name' without its folder and its ".func"). Blank lines, CR of
** CRLF files and trailing blanks are accepted everywhere. Returns LSYS_OK,
** LSYS_ESYNTAX (e set; *out NULL, *nout 0) or LSYS_ENOMEM.
*/
int lsys_func_parse (lsys_func **out, size_t *nout, const char *text, size_t len,
                     const char *name, int samples, lsys_error *e);

/*
** Writes 'f' in the fver 1 1 form into buf (at most 'size' bytes, NUL
** included, like snprintf) and returns the length of the whole text.
** Consecutive equal points are written once with their multiplicity;
** numbers in the shortest form that reads back to the same double, so
** format(parse(format(f))) is format(f) byte for byte.
*/
size_t lsys_func_format (const lsys_func *f, char *buf, size_t size);

#endif
