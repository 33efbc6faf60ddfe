/*
** Cross-sections (contours) of generalized cylinders: the cpfg guide
** (Měch and Prusinkiewicz) §3.2.3 ("Defining the cross-section", "Open
** contours") and Appendix B.1.
**
** A contour is a uniform cubic B-spline through n control points in the
** contour's own space (x, y, z; 2D files give z = 0). Closed: n segments,
** segment i uses P_i, P_(i+1)%n, P_(i+2)%n, P_(i+3)%n. Open: n - 3 segments,
** segment i uses P_i .. P_(i+3) (files repeat the end points three times so
** the curve reaches them).
*/
#ifndef LSYS_CONTOUR_H
#define LSYS_CONTOUR_H

#include "common.h"

#define LSYS_CONTOUR_MAXPOINTS 65536

typedef struct lsys_contour {
  double *pt;             /* 3 doubles per control point */
  size_t n;               /* control points: >= 3 closed, >= 4 open */
  int closed;             /* 1 closed, 0 open */
  int dim;                /* 2 or 3, as given in the file */
} lsys_contour;

void lsys_contour_init (lsys_contour *c);
void lsys_contour_free (lsys_contour *c);

/*
** Parses the text of a contour file, in one of two formats:
**  - cpfg's (Appendix B.1): a first line "N dim open|closed" (dim 2 or 3),
**    then N lines of dim numbers each;
**  - vlab's versioned one, first line "cver 1 1", "cver 1 2" or "cver 1 3"
**    (others are errors), then "name: NAME" (ignored), "points: LINES
**    TOTAL", "type: T" (1.1: open or closed; 1.2 and 1.3: o or c, then r
**    or e, end-point interpolation, drawn as r as cpfg does), in 1.3
**    "samples: K" (ignored: contour sides come from the view) and
**    optionally "background: FILE", "backgroundXY: X Y", "markers: K" and
**    K lines (skipped); then LINES lines "x y z m", the point repeated m
**    times (m >= 1; the m add up to TOTAL). The dimension is 3.
** Tokens are separated by blanks (spaces, tabs; CR of CRLF files too),
** blank lines are skipped and '#' starts a comment that runs to the end of
** the line. Coordinates must be finite and at most 1e9 in magnitude;
** nothing but comments may follow the points. 'text' need not be
** NUL-terminated: only its 'len' bytes are read. 'name' (the file name)
** starts every message: "name:LINE: what is wrong", e.g.
** "leaf.con:3: expected 2 numbers, got 1". 'c' must have been initialised;
** its old points are freed. Returns LSYS_OK, LSYS_ESYNTAX (e set) or
** LSYS_ENOMEM; on failure 'c' is left empty.
*/
int lsys_contour_parse (lsys_contour *c, const char *text, size_t len, const char *name,
                        lsys_error *e);

/* Sets 'c' from n points (3 doubles each; z is ignored and set to 0 when
** dim is 2). Same checks as the parser; messages name the point
** ("point 3: coordinate 2 is not finite"). Returns LSYS_OK, LSYS_EARG (e
** set; 'c' unchanged) or LSYS_ENOMEM. */
int lsys_contour_set (lsys_contour *c, const double *pt, size_t n, int closed, int dim,
                      lsys_error *e);

/*
** The p + 1 vertices V_0 .. V_p of a contour drawn with p polygons around
** it (p >= 3): 10n points are computed at equal steps of the curve
** parameter, then V_i are placed at equal arc length along that polyline.
** All vertices are then rotated about z so that V_0 lies on the +x axis.
** For a closed contour V_p = V_0; for an open one V_p is the curve's end.
** 'out' gets 3 (p + 1) doubles; 'nrm', when not NULL, 3 (p + 1) unit
** normals in the xy plane: the outward normal for a closed contour (on the
** side away from the enclosed area, whatever the winding of the file),
** the normal to the left of the direction of travel for an open one.
** Normals follow the tangent of the sampled polyline (central differences,
** interpolated like the vertices). Nothing is allocated. Returns LSYS_OK,
** or LSYS_EARG (nothing written) when p < 3 or 'c' holds no contour.
*/
int lsys_contour_sample (const lsys_contour *c, int p, double *out, double *nrm);

/* The default contour (id 0): the unit circle, V_i = (cos 2πi/p, sin 2πi/p, 0),
** normals equal to the vertices, V_p = V_0 exactly. Same layout as
** lsys_contour_sample; nothing is written when p < 3. */
void lsys_contour_circle (int p, double *out, double *nrm);

#endif
