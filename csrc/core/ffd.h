/*
** Free-form deformations of a finished scene (Lintermann and Deussen 1999,
** section "Free-form deformations" and the sidebar "FFD and Hyperpatch"):
** the FFD and Hyperpatch components deform the geometry their subtree drew,
** after the turtle drew it. Here is that last step: maps applied in place to
** a range of a scene's vertices and line end points.
**
**   hyperpatch   a trivariate Bezier volume (tensor-product Bernstein
**                polynomials) of degrees (dl, dm, dn), each 1 (linear) to 4
**                (quartic), over a lattice box: an origin and three edge
**                vectors a, b, c. A world point p has lattice coordinates
**                (s, t, u) with p = origin + s a + t b + u c, and moves to
**
**                  X(s, t, u) = sum_ijk B_i^dl(s) B_j^dm(t) B_k^dn(u) P_ijk
**
**                B_i^d(s) = C(d, i) s^i (1 - s)^(d - i). The control points
**                P_ijk are stored at i + (dl + 1) * (j + (dm + 1) * k).
**                lsys_ffd_hyperpatch_init puts them on the regular lattice,
**                origin + (i/dl) a + (j/dm) b + (k/dn) c, where the map is
**                the identity (the linear precision of Bernstein
**                polynomials). Points outside the box (s, t or u outside
**                [0, 1]) are mapped by the same polynomial: extrapolation,
**                not clamping, so the map stays smooth across the box's faces.
**   function     any map p -> p' given by a C callback (the FFD component's
**                "deformation by functions").
**   affine       a 3 x 4 matrix (a primitive's non-uniform scaling).
**
** Normals are transformed by the inverse transpose of the map's Jacobian
** and normalized; where the Jacobian is singular (or the result is not
** finite) a vertex keeps its normal. Line end points move like vertices;
** line widths (pixels) stay. Every deformation marks the vertex range dirty
** (lsys_scene_touch) and allocates nothing.
*/
#ifndef LSYS_FFD_H
#define LSYS_FFD_H

#include "common.h"
#include "scene.h"

#define LSYS_HP_MAXDEG 4
#define LSYS_HP_MAXPTS ((LSYS_HP_MAXDEG + 1) * (LSYS_HP_MAXDEG + 1) * (LSYS_HP_MAXDEG + 1))

typedef struct lsys_hyperpatch {
  int deg[3];                     /* dl, dm, dn: 1 .. 4 */
  double origin[3];
  double axis[3][3];              /* the edge vectors a, b, c of the lattice box */
  double inv[3][3];               /* the inverse of the matrix whose columns are a, b, c */
  double cp[LSYS_HP_MAXPTS][3];   /* control points, (dl+1)(dm+1)(dn+1) of them */
} lsys_hyperpatch;

/* A hyperpatch of degrees deg[0..2] over the box 'origin' + [0,1]^3 of
** 'axes' (axes[0] = a, ...), its control points on the regular lattice.
** LSYS_EARG with a message in 'e' for a degree outside 1..4, a non-finite
** number, or a singular frame (edge vectors that are zero, parallel or in
** one plane: |det| <= 1e-12 |a| |b| |c|). */
int lsys_ffd_hyperpatch_init (lsys_hyperpatch *hp, const int deg[3], const double origin[3],
                              const double axes[3][3], lsys_error *e);

/* The number of control points, (dl + 1)(dm + 1)(dn + 1). */
size_t lsys_ffd_hyperpatch_count (const lsys_hyperpatch *hp);

/* Control point (i, j, k) (0-based), or NULL when an index is out of range. */
double *lsys_ffd_hyperpatch_point (lsys_hyperpatch *hp, int i, int j, int k);

/* Lattice coordinates (s, t, u) of the world point p. */
void lsys_ffd_hyperpatch_local (const lsys_hyperpatch *hp, const double p[3], double stu[3]);

/* The image of the world point p in out[3] and, when J is not NULL, the
** Jacobian d out / d p (row r: the derivatives of out[r]). */
void lsys_ffd_hyperpatch_eval (const lsys_hyperpatch *hp, const double p[3], double out[3],
                               double J[3][3]);

/* Deforms vertices [v0, v1) and the end points of line segments [l0, l1)
** by the hyperpatch. LSYS_EARG when a range is reversed or past the end;
** LSYS_ENOMEM when the records could not keep their end points apart from
** the lines (lsys_scene_detach_records; nothing moved). The same for the
** two below. */
int lsys_ffd_range (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                    const lsys_hyperpatch *hp);

/* A map given by a function: writes the image of p in out and returns
** LSYS_OK, or a non-zero status that stops the deformation. */
typedef int (*lsys_deform_fn) (void *ud, const double p[3], double out[3]);

/* The same for the map 'fn'. Normals come from the Jacobian by central
** differences of fn with the step h = 1e-4 times the diagonal of the
** bounding box of the range (its vertices and line ends; 1e-4 when that
** box is a point): six more calls per vertex. When fn fails, the
** deformation stops: the vertices before it (and, when it failed on a line
** end, all vertices and the lines before it) are moved, the rest are not;
** its status is returned with e->pos the vertex index (a line end: nv +
** 2 * segment + end). fn must not change the number of the scene's vertices
** or lines (its arrays may move: each point is found again after fn). */
int lsys_ffd_func (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                   lsys_deform_fn fn, void *ud, lsys_error *e);

/* The affine map p' = M p + t, m = {M row 0, t0, M row 1, t1, M row 2,
** t2} (a 3 x 4 matrix by rows). */
int lsys_ffd_affine (lsys_scene *s, size_t v0, size_t v1, size_t l0, size_t l1,
                     const double m[12]);

/*
** The vertices [*v0, *v1) and line segments [*l0, *l1) that modules [m0, m1)
** of the interpreted string drew (0-based module indices, as in records).
** The turtle writes geometry in module order, so these are ranges; they
** come from the records: the triangles from the first record of a module
** >= m0 to the first record of a module >= m1 (a segment's cylinder is
** written when the next module begins, before that module's records, so it
** counts with its F), and the vertices those triangles made: from one past
** the last vertex that earlier triangles use to the last one they use. A
** vertex shared with earlier geometry (the ring where a cylinder continues
** the segment before it, a branch's base) is not in the range, so a
** deformed subtree stays attached to what it grows from. Costs one pass
** over the triangles before the range. Lines: each
** segment record draws one line in the line style, so when the scene holds
** as many lines as segment records, segment record n drew line n; otherwise
** (cylinders, ribbons) the line range is empty. Returns 1, or 0 with empty
** ranges when the modules drew nothing (or the scene has no records).
*/
int lsys_ffd_module_range (const lsys_scene *s, uint32_t m0, uint32_t m1, size_t *v0,
                           size_t *v1, size_t *l0, size_t *l1);

#endif
