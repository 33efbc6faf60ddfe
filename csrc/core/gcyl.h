/*
** Generalized cylinders (Měch and Prusinkiewicz, cpfg guide §3): an axis
** of Hermite segments between control points (§3.1), a longitudinal
** section R(t) (§3.2.2), a contour swept along the axis and interpolated
** between the ends (§3.2.3), with rotation-minimising frames (§3.3,
** Bloomenthal) or the turtle's own frames. The turtle keeps the control
** points (turtle.c); this file turns a pair of them into mesh strips.
*/
#ifndef LSYS_GCYL_H
#define LSYS_GCYL_H

#include "mesh.h"

#define LSYS_GC_TANGENT 1.2     /* default tangent coefficient (§3.1) */

/* A control point (§3.1). */
typedef struct lsys_gcpoint {
  double pos[3];          /* the turtle's position */
  double H[3], U[3];      /* the turtle's heading and up */
  double V[3];            /* contour reference direction at this point: unit, normal to H */
  double r;               /* radius (half the line width) */
  double v;               /* texture v reached here (§5.2) */
  int contour, color, texture;
  int first;              /* 1: the point of @Gs (the start gets a cap) */
  uint32_t ring;          /* first vertex of its ring in the mesh, or UINT32_MAX */
  int sides;              /* the ring's vertices less one (@!(n) may change them) */
} lsys_gcpoint;

/* A sampled contour (contour.h) as the builder reads it. */
typedef struct lsys_gccontour {
  const double *v, *n;    /* p + 1 vertices and normals, 3 doubles each */
  int left;               /* 1: normals point left of the direction of travel, 0: right */
  int closed;
  const uint32_t *cap;    /* triangles of the flat end cap (indices 0..p-1), or NULL */
  int ncap;
} lsys_gccontour;

/* What shapes one segment. */
typedef struct lsys_gcshape {
  double tan0, tan1;      /* tangent coefficients at the two ends (@Gt, §3.2.1) */
  double rtan[4];         /* radius tangents: [angle0, length0, angle1, length1] (@Gr,
                             §3.2.2), degrees; a length of 0 means the default */
  int adjust;             /* @Gr(1): keep the tangents' angles on a segment of length != 1 */
  int strips;             /* mesh strips between the points (>= 1) */
  int minimize;           /* 1: rotation-minimising frames; 0: the turtle's frames */
  double aspect;          /* texture width / height, for v (§5.2); 1 without texture */
  int capstart, capend;   /* close the start / end with a flat cap (closed contours) */
} lsys_gcshape;

/* F(u) and F'(u) of the Hermite curve P0, T0, P1, T1 (either output may be NULL). */
void lsys_gcyl_hermite (const double P0[3], const double T0[3], const double P1[3],
                        const double T1[3], double u, double F[3], double dF[3]);

/* The longitudinal section R(t) = (R_u, R_v) of a segment from radius rb to
** rt whose axis has length 'len' (for @Gr(1)), and its derivative. */
void lsys_gcyl_section (const lsys_gcshape *sh, double rb, double rt, double len, double t,
                        double R[2], double dR[2]);

/* Carries the unit vector 'V' (normal to the unit tangent 'T0') along with
** the smallest rotation that takes T0 to T1 (Bloomenthal's method, §3.3);
** the result is normal to T1. */
void lsys_gcyl_transport (double V[3], const double T0[3], const double T1[3]);

/*
** Appends the strips from control point 'a' to 'b' to 'm' with 'p' polygons
** around; 'ca' and 'cb' are the contours at the two ends. Reuses a's ring
** when it can (a->ring, same colour and texture, tangent along a->H).
** Sets b->V (the frame carried to b, or b's own up vector when the twist is
** not minimised), b->v and b->ring. Returns LSYS_OK or LSYS_ENOMEM/ELIMIT.
*/
int lsys_gcyl_segment (lsys_mesh *m, const lsys_gcpoint *a, lsys_gcpoint *b,
                       const lsys_gcshape *sh, const lsys_gccontour *ca,
                       const lsys_gccontour *cb, int p);

#endif
