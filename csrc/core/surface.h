/*
** Bicubic surfaces after the cpfg guide (Měch and Prusinkiewicz): §4.1
** (predefined surfaces ~name read from cpfg surface files), §4.3 (L-system
** defined patches @PS @PC @PD with the Bézier, B-spline and Cardinal bases
** of Appendix A) and §5.1 (texture coordinates per patch or per surface).
** The file format is described at the top of surface.c and in
** docs/surfaces.md.
**
** Parameters: a patch is evaluated at (s, t) in [0,1]^2, where s runs
** across the columns c = 0..3 of its 4 x 4 control points (along a row)
** and t across the rows r = 0..3 (along a column):
**
**   P(s, t) = T M G M^T S^T,  S = [s^3 s^2 s 1], T = [t^3 t^2 t 1],
**
** with G the control points (G[r][c]) and M the basis matrix.
*/
#ifndef LSYS_SURFACE_H
#define LSYS_SURFACE_H

#include "common.h"
#include "mesh.h"

enum { LSYS_BASIS_BEZIER = 1, LSYS_BASIS_BSPLINE = 2, LSYS_BASIS_CARDINAL = 3 };

#define LSYS_SURFACE_MAXPATCHES 4096   /* patches of one surface file */
#define LSYS_SURFACE_MAXDIV     256    /* lines per patch (PRECISION, ns, nt) */
#define LSYS_SURFACE_MAXCOORD   1e30   /* |number| in a surface file */
#define LSYS_SURFACE_NAMELEN    64     /* patch names: at most 63 bytes */

/* A 4 x 4 patch: control point (row r, column c) at ctrl[3 * (4 * r + c)]. */
typedef struct lsys_patch {
  double ctrl[48];
} lsys_patch;

/* Neighbour directions of a patch in a surface file, in file order: above
** left, above, above right, left, right, below left, below, below right.
** "Above" is the side of row 0, "left" the side of column 0; direction d
** and 7 - d are opposite. */
enum { LSYS_NB_AL, LSYS_NB_A, LSYS_NB_AR, LSYS_NB_L, LSYS_NB_R, LSYS_NB_BL, LSYS_NB_B,
       LSYS_NB_BR };

/* What a surface file says about a patch besides its control points. */
typedef struct lsys_patchinfo {
  char name[LSYS_SURFACE_NAMELEN];
  int nb[8];              /* neighbour patch index per LSYS_NB_*, -1 for none ('~') */
  int color[2];           /* TOP COLOR and BOTTOM COLOR (kept, not used for drawing) */
  double diffuse[2];      /* their DIFFUSE factors (kept, not used) */
} lsys_patchinfo;

/* A predefined surface (a cpfg .s file). */
typedef struct lsys_surface {
  lsys_patch *patch; size_t npatch;
  lsys_patchinfo *info;   /* npatch entries */
  int basis;              /* LSYS_BASIS_*: Bézier for .s files */
  double contact[3];      /* contact point P_S: put at the turtle's position */
  double heading[3];      /* H_S, unit: turned onto the turtle's heading */
  double up[3];           /* U_S, unit, normal to H_S: turned onto the turtle's up */
  double end[3];          /* where the turtle stands after drawing (surface space) */
  double size;            /* SIZE: the reference size (1e-30..1e30); drawing divides by it */
  double lo[3], hi[3];    /* bounds of the control points */
  int precision_s, precision_t;   /* lines per patch from the file (default 5 x 5) */
} lsys_surface;

void lsys_surface_init (lsys_surface *s);
void lsys_surface_free (lsys_surface *s);

/*
** Parses the text of a cpfg surface file ('len' bytes, need not end in
** NUL). 'name' starts every message: "name:LINE: what is wrong". Returns
** LSYS_OK, LSYS_ESYNTAX or LSYS_ENOMEM; on failure 's' is left empty.
*/
int lsys_surface_parse (lsys_surface *s, const char *text, size_t len, const char *name,
                        lsys_error *e);

/*
** Sets 'dst' to a copy of 's' whose control points are 'pt' (48 doubles per
** patch, in patch order, laid out as lsys_patch.ctrl), with the bounds
** computed again: how an editor changes a surface. 'dst' must have been
** initialised and must not be 's'; its old contents are freed. Returns
** LSYS_OK, LSYS_EARG ('e' set, "point 5: coordinate 2 is not finite";
** 'dst' unchanged) or LSYS_ENOMEM.
*/
int lsys_surface_with_points (lsys_surface *dst, const lsys_surface *s, const double *pt,
                              lsys_error *e);

/*
** Writes 's' as a surface file (the format at the top of surface.c, every
** line present, numbers in the shortest form that reads back the same;
** HEADING and UP as normalised when read) into 'buf' of 'size' bytes, NUL
** terminated when size > 0, as snprintf does. Returns the length of the
** whole text (call with size 0 first to learn it).
*/
size_t lsys_surface_format (const lsys_surface *s, char *buf, size_t size);

/* A point of a patch at (s, t) in [0,1]^2 (s along the rows' direction,
** i.e. across columns c = 0..3; t across rows r = 0..3), with the partial
** derivatives (either may be NULL). Basis as LSYS_BASIS_*; any other
** value is taken as Bézier. */
void lsys_surface_patch_eval (int basis, const lsys_patch *p, double s, double t, double pos[3],
                              double ds[3], double dt[3]);

/* Where and how a surface or patch is drawn. */
typedef struct lsys_place {
  double origin[3];       /* the turtle's position */
  double H[3], L[3], U[3];/* the turtle's frame */
  double scale;           /* multiplies surface coordinates (after the division by SIZE) */
  unsigned color;         /* colour index of the vertices */
  int uv_surface;         /* 1: uv from x, y over the surface bounds; 0: per patch (s,t) */
} lsys_place;

/*
** Appends a tessellated surface to 'm': every patch as an (ns + 1) x (nt + 1)
** grid of vertices and 2 ns nt triangles (1 <= ns, nt <= LSYS_SURFACE_MAXDIV),
** two-sided, wound counter-clockwise seen from the side the normal points
** to. Normals come from the derivatives (ds x dt, normalised; a degenerate
** point takes the normal of a point next to it inside the patch, else the
** patch's average normal) and are averaged along the edges that the file
** names as shared with a neighbour.
** Surface coordinates x are mapped to origin + (scale / size) R (x - contact)
** where R turns H_S to H, U_S to U and H_S x U_S to L (= H x U). uv is (s, t)
** per patch, or with pl->uv_surface the surface-space x and y scaled over
** the bounds of the tessellated surface to [0,1]. The texture of new
** vertices is m->curtex. Returns LSYS_OK, LSYS_EARG (bad ns or nt),
** LSYS_ENOMEM or LSYS_ELIMIT.
*/
int lsys_surface_mesh (lsys_mesh *m, const lsys_surface *s, const lsys_place *pl, int ns,
                       int nt);

/* Where the turtle stands after drawing 's' at 'pl':
** origin + (scale / size) R (end - contact). */
void lsys_surface_endpoint (const lsys_surface *s, const lsys_place *pl, double out[3]);

/*
** Appends one patch whose control points are already in world space (@PD):
** (ns + 1) x (nt + 1) vertices and 2 ns nt triangles, two-sided, normals and
** winding as lsys_surface_mesh. pl->origin, frame and scale are not used;
** color and uv_surface are: uv is (s, t), or with uv_surface the position
** projected on the plane spanned by the patch's s and t directions, scaled
** over the bounds of the tessellated patch to [0,1]. Returns as
** lsys_surface_mesh.
*/
int lsys_surface_patch_mesh (lsys_mesh *m, int basis, const lsys_patch *p, const lsys_place *pl,
                             int ns, int nt);

#endif
