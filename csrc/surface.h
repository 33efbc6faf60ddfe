/*
** Bicubic surfaces: seed 004 §4.1 (predefined surfaces ~name read from
** cpfg surface files), §4.3 (L-system defined patches @PS @PC @PD with the
** Bézier, B-spline and Cardinal bases of Appendix A) and §5.1 (texture
** coordinates per patch or per surface).
*/
#ifndef LSYS_SURFACE_H
#define LSYS_SURFACE_H

#include "common.h"
#include "mesh.h"

enum { LSYS_BASIS_BEZIER = 1, LSYS_BASIS_BSPLINE = 2, LSYS_BASIS_CARDINAL = 3 };

/* A 4 x 4 patch: control point (row r, column c) at ctrl[3 * (4 * r + c)]. */
typedef struct lsys_patch {
  double ctrl[48];
} lsys_patch;

/* A predefined surface (a cpfg .s file). */
typedef struct lsys_surface {
  lsys_patch *patch; size_t npatch;
  int basis;              /* LSYS_BASIS_*: Bézier for .s files */
  double contact[3];      /* contact point P_S: put at the turtle's position */
  double heading[3];      /* H_S, unit: turned onto the turtle's heading */
  double up[3];           /* U_S, unit, normal to H_S: turned onto the turtle's up */
  double end[3];          /* where the turtle stands after drawing (surface space) */
  double lo[3], hi[3];    /* bounds of the control points (per-surface texture) */
  int precision_s, precision_t;   /* lines per patch from the file (default 4 x 4) */
} lsys_surface;

void lsys_surface_init (lsys_surface *s);
void lsys_surface_free (lsys_surface *s);

/*
** Parses the text of a cpfg surface file. 'name' starts every message:
** "name:LINE: what is wrong". Returns LSYS_OK, LSYS_ESYNTAX or LSYS_ENOMEM;
** on failure 's' is left empty.
*/
int lsys_surface_parse (lsys_surface *s, const char *text, size_t len, const char *name,
                        lsys_error *e);

/* A point of a patch at (s, t) in [0,1]^2 (s along the rows' direction,
** i.e. across columns c = 0..3; t across rows r = 0..3), with the partial
** derivatives (either may be NULL). Basis as LSYS_BASIS_*. */
void lsys_patch_eval (int basis, const lsys_patch *p, double s, double t, double pos[3],
                      double ds[3], double dt[3]);

/* Where and how a surface or patch is drawn. */
typedef struct lsys_place {
  double origin[3];       /* the turtle's position */
  double H[3], L[3], U[3];/* the turtle's frame */
  double scale;           /* multiplies surface coordinates */
  unsigned color;         /* colour index of the vertices */
  int uv_surface;         /* 1: uv from x, y over the surface bounds; 0: per patch (s,t) */
} lsys_place;

/*
** Appends a tessellated surface to 'm': every patch as an (ns + 1) x (nt + 1)
** grid of vertices (ns, nt >= 1), two-sided, with normals from the
** derivatives (normalised; a degenerate point takes a neighbour's normal).
** Surface coordinates x are mapped to origin + scale * R (x - contact) where
** R turns H_S to H, U_S to U and H_S x U_S to L. The texture of new vertices
** is m->curtex. Returns LSYS_OK or LSYS_ENOMEM / LSYS_ELIMIT.
*/
int lsys_surface_mesh (lsys_mesh *m, const lsys_surface *s, const lsys_place *pl, int ns,
                       int nt);

/* Where the turtle stands after drawing 's' at 'pl': origin + scale R (end - contact). */
void lsys_surface_endpoint (const lsys_surface *s, const lsys_place *pl, double out[3]);

/*
** Appends one patch whose control points are already in world space (@PD):
** (ns + 1) x (nt + 1) vertices, two-sided, uv = (s, t). pl->origin, frame and
** scale are not used; color and uv_surface are (uv_surface gives uv from
** the patch's own bounds in its best-fit plane).
*/
int lsys_patch_mesh (lsys_mesh *m, int basis, const lsys_patch *p, const lsys_place *pl,
                     int ns, int nt);

#endif
