/*
** Scene geometry (docs/architecture.md): what the turtle writes and what the
** renderer and the export writers (export.h) read.
**
** One triangle mesh (indexed; per-vertex position, normal, uv and colour
** index) and one set of wide line segments. Colour indices refer to a
** palette of materials that the view supplies (lsys_material): colour c
** uses pal[c % npal], so indices past the palette's end wrap around.
** Arrays grow by doubling and are reused across interpretations.
*/
#ifndef LSYS_MESH_H
#define LSYS_MESH_H

#include <float.h>
#include <math.h>

#include "common.h"
#include "texture.h"

typedef struct lsys_mesh {
  /* triangles: vertex arrays, 3 indices per triangle */
  float *pos, *nrm, *uv;          /* 3, 3 and 2 floats per vertex */
  uint16_t *col;                  /* colour (material) index per vertex */
  uint8_t *twosided;              /* 1 when the vertex belongs to a surface lit on both
                                     sides (polygons, leaves, discs), 0 for solids */
  uint16_t *tex;                  /* texture index per vertex: 0 none, k the view's k-th
                                     texture (cpfg guide §5); a triangle takes its first
                                     vertex's texture */
  unsigned curtex;                /* the texture lsys_mesh_vertex gives new vertices */
  size_t nv, vcap;
  uint32_t *tri;
  size_t nt, tcap;                /* nt triangles: tri[3*nt] */
  /* lines: 2 end points each, a width in pixels and a colour index */
  float *lpos;                    /* 6 floats per segment */
  float *lwidth;                  /* 2 per segment: width at each end */
  uint16_t *lcol;
  size_t nl, lcap;
  lsys_meter *meter;              /* while the turtle fills it: its memory budget (or NULL);
                                     growing past it fails with LSYS_EMEMORY */
  int fixed;                      /* 1: the arrays are places in another mesh's (the
                                     turtle's pieces, turtle_par.c): growing fails with
                                     LSYS_ELIMIT */
} lsys_mesh;

/* A material (cpfg material file fields); a plain colour has diffuse set,
** ambient = 0.3 * diffuse, no specular. Components in [0, 1]. */
typedef struct lsys_material {
  float ambient[4], diffuse[4], specular[4], emission[4];
  float shininess;                /* 0..128 (OpenGL) */
} lsys_material;

void lsys_mesh_init (lsys_mesh *m);
void lsys_mesh_free (lsys_mesh *m);
void lsys_mesh_clear (lsys_mesh *m);
/* Makes 'dst' (empty or freed) a copy of 'src' with capacities just the
** sizes. Returns LSYS_OK, or LSYS_ENOMEM leaving 'dst' empty. */
int lsys_mesh_copy (lsys_mesh *dst, const lsys_mesh *src);

/*
** Brings 'dst', an earlier copy of 'src', up to date: src has changed since
** only in the vertex ranges r[0 .. 2n) ([r[2k], r[2k+1]), as
** lsys_scene_take_ranges gives them) and by appending vertices, triangles and
** lines (a grown plant: lsys_limbs). Copies just those ranges and what was
** appended; allocates only when dst must grow. Returns LSYS_OK, LSYS_EARG
** when src has fewer vertices, triangles or lines than dst (it is not a later
** state of it: copy it whole), or LSYS_ENOMEM (dst unchanged in size).
*/
int lsys_mesh_sync (lsys_mesh *dst, const lsys_mesh *src, const size_t *r, size_t n);

/* Makes room for 'nv' more vertices and 'nt' more triangles. */
int lsys_mesh_reserve (lsys_mesh *m, size_t nv, size_t nt);
/* Makes room for 'nl' more line segments (within the meter). LSYS_OK,
** LSYS_ELIMIT (more than UINT32_MAX segments), LSYS_ENOMEM or LSYS_EMEMORY. */
int lsys_mesh_reserve_lines (lsys_mesh *m, size_t nl);
/* Appends a vertex (room must have been reserved); returns its index. */
static inline uint32_t lsys_mesh_vertex (lsys_mesh *m, const double p[3], const double n[3],
                                         double u, double v, unsigned col, int twosided) {
  size_t i = m->nv++;
  float *P = m->pos + 3 * i, *N = m->nrm + 3 * i;
  P[0] = (float)p[0]; P[1] = (float)p[1]; P[2] = (float)p[2];
  N[0] = (float)n[0]; N[1] = (float)n[1]; N[2] = (float)n[2];
  m->uv[2 * i] = (float)u; m->uv[2 * i + 1] = (float)v;
  m->col[i] = (uint16_t)col;
  m->twosided[i] = (uint8_t)twosided;
  m->tex[i] = (uint16_t)m->curtex;
  return (uint32_t)i;
}
/* Appends a triangle (room must have been reserved). */
static inline void lsys_mesh_tri (lsys_mesh *m, uint32_t a, uint32_t b, uint32_t c) {
  uint32_t *t = m->tri + 3 * m->nt++;
  t[0] = a; t[1] = b; t[2] = c;
}
/* A double as a float, saturating: converting a value beyond FLT_MAX is undefined. */
static inline float lsys_mesh_float (double x) {
  return x > FLT_MAX ? FLT_MAX : x < -FLT_MAX ? -FLT_MAX : (float)x;
}
/* Appends a line segment from 'a' to 'b' (inline: the turtle draws one per F).
** LSYS_OK, or lsys_mesh_reserve_lines's error. */
static inline int lsys_mesh_line (lsys_mesh *m, const double a[3], const double b[3],
                                  double w0, double w1, unsigned col) {
  float *p;
  if (m->nl == m->lcap) {
    int st = lsys_mesh_reserve_lines(m, 1);
    if (st != LSYS_OK) return st;
  }
  p = m->lpos + 6 * m->nl;
  if ((fabs(a[0]) <= FLT_MAX) & (fabs(a[1]) <= FLT_MAX) & (fabs(a[2]) <= FLT_MAX) &
      (fabs(b[0]) <= FLT_MAX) & (fabs(b[1]) <= FLT_MAX) & (fabs(b[2]) <= FLT_MAX) &
      (fabs(w0) <= FLT_MAX) & (fabs(w1) <= FLT_MAX)) {      /* nothing to clamp: one branch */
    p[0] = (float)a[0]; p[1] = (float)a[1]; p[2] = (float)a[2];
    p[3] = (float)b[0]; p[4] = (float)b[1]; p[5] = (float)b[2];
    m->lwidth[2 * m->nl] = (float)w0;
    m->lwidth[2 * m->nl + 1] = (float)w1;
  } else {
    p[0] = lsys_mesh_float(a[0]); p[1] = lsys_mesh_float(a[1]); p[2] = lsys_mesh_float(a[2]);
    p[3] = lsys_mesh_float(b[0]); p[4] = lsys_mesh_float(b[1]); p[5] = lsys_mesh_float(b[2]);
    m->lwidth[2 * m->nl] = lsys_mesh_float(w0);
    m->lwidth[2 * m->nl + 1] = lsys_mesh_float(w1);
  }
  m->lcol[m->nl] = (uint16_t)col;
  m->nl++;
  return LSYS_OK;
}

/* Axis-aligned bounds of all vertices and line ends: lo[3], hi[3].
** Returns 0 (and lo = hi = 0) for an empty mesh, else 1. */
int lsys_mesh_bounds (const lsys_mesh *m, double lo[3], double hi[3]);

/* The distinct edges of triangles t0 .. t0 + nt - 1 (a wireframe), as vertex
** pairs a < b sorted by (a, b) into 'edges' (room for 6 nt values; triangles
** beyond the mesh are ignored). Returns the number of edges. */
size_t lsys_mesh_edges (const lsys_mesh *m, size_t t0, size_t nt, uint32_t *edges);

/* Colour indices are 16 bits: LSYS_MESH_NCOLORS of them. */
#define LSYS_MESH_NCOLORS 65536

/* How much of 'm' each colour index draws: count[c] (LSYS_MESH_NCOLORS
** entries, all written) becomes the number of triangles (a triangle has
** its first vertex's colour) and line segments of colour c, stopping at
** UINT32_MAX. The indices are the turtle's, before the palette wraps them.
** Returns how many indices are used (count[c] > 0). */
size_t lsys_mesh_color_counts (const lsys_mesh *m, uint32_t *count);

/* ---- Tubes (mesh_tube.c): the turtle's cylinders and exported lines ---- */

/* The cos/sin table of a ring of 'n' sides: cs[2k], cs[2k + 1] for k in
** 0 .. n (the last repeats the first exactly), 2 n + 2 values. */
void lsys_mesh_ringtable (double *cs, int n);

/* How rings are laid out: in the plane of L and U (L = H x U, so that the
** bands lsys_mesh_band makes face outwards), by the table 'cs' of 'n'
** sides, in colour 'col'; u of the first vertex 'u0' (0 unless set). */
typedef struct lsys_tubeframe {
  const double *H, *L, *U;
  const double *cs;
  int n;
  unsigned col;
  double u0;
} lsys_tubeframe;

/*
** Appends a ring of n + 1 vertices (the last repeats the first, for u = u0 +
** 1) of radius 'r' around 'c': vertex k along L cos(2 pi k / n) + U sin(2 pi
** k / n), with u = u0 + k / n and 'v'; normals point outwards, tilted along H
** by 'slope' (a taper's (r0 - r1) / length). Room must have been reserved.
** Returns its first vertex.
*/
uint32_t lsys_mesh_ring (lsys_mesh *m, const lsys_tubeframe *f, const double c[3], double r,
                         double slope, double v);

/* Appends a flat cap on the ring at 'ring' (n sides): a fan of n triangles
** around a new centre vertex at 'c', all with normal 'nn'; 'flip' winds it
** for a top cap (rings turn anticlockwise about -H). n + 1 vertices. */
void lsys_mesh_cap (lsys_mesh *m, const double c[3], const double nn[3], uint32_t ring, int n,
                    unsigned col, int flip);

/* Appends the 2 n triangles between the rings at 'base' and 'top'. 'twist'
** is how far the top ring is turned about the heading from the base ring
** (radians, in the sense its vertices go round; see lsys_mesh_ringmatch):
** each quad is split along its shorter diagonal, from base vertex k to top
** vertex k + 1 unless the twist is positive, so that a twisted band's
** triangles span no more of the circle than an untwisted band's do. */
void lsys_mesh_band (lsys_mesh *m, uint32_t base, uint32_t top, int n, double twist);

/* Carries the vector 'v' over a bend into 'out': rotates it by the least
** rotation that takes the unit heading 'a' to the unit heading 'b' (the
** rotation about a x b; a . b must be above -1). A vector normal to 'a'
** comes out normal to 'b': parallel transport of a tube's frame. */
void lsys_mesh_transport (double out[3], const double v[3], const double a[3],
                          const double b[3]);

/*
** The frame L2, U2 of a ring that continues a ring of 'n' sides ('cs' its
** lsys_mesh_ringtable) whose first vertex points along the unit 'pL' about
** the unit heading 'pH', for a segment with the turtle frame H, L, U (unit,
** L and U normal to H): L, U turned about H by the whole number of sides,
** *steps (0 .. n - 1), that brings the first vertex closest to pL carried
** over the bend (lsys_mesh_transport). Vertex k of the new ring is then
** vertex k + *steps of the turtle's own ring, where the turtle puts it, and
** matches vertex k of the old ring to within half a side. Returns the twist
** left, the angle from the carried pL to L2 about H in the sense the ring's
** vertices go round (|twist| <= pi / n), for lsys_mesh_band.
*/
double lsys_mesh_ringmatch (double L2[3], double U2[3], int *steps, const double pH[3],
                            const double pL[3], const double H[3], const double L[3],
                            const double U[3], const double *cs, int n);

/*
** Makes 'dst' (empty or freed) the vertices and triangles of 'src' followed
** by its line segments as tubes of 'n' sides (3 .. 1024), with no line
** segments left. A segment's widths w0, w1 (line style: pixels) become the
** diameters w0 * unit and w1 * unit of its ends; widths below 1 or not
** numbers count as 1, the thinnest line the renderer draws, and widths
** above 16384 as 16384, as the renderer caps them. A tube that starts where
** the segment before it ended, as wide, of the same colour and bent by less
** than 30 degrees shares that segment's top ring (no crack, no inner caps, as
** the turtle's cylinders); other ends are closed with flat caps. A segment
** of zero length or with an end that is not finite is left out. Tube
** vertices are one-sided, untextured; u goes round, v along the tube.
** Allocates once. Returns LSYS_OK; LSYS_EARG for a bad 'n' or a 'unit' that
** is not a positive finite number; LSYS_ELIMIT when the result would have
** more than UINT32_MAX vertices; LSYS_ENOMEM. On failure 'dst' is empty.
*/
int lsys_mesh_tubes (lsys_mesh *dst, const lsys_mesh *src, int n, double unit);

/* Fills a material from an RGB colour (diffuse), with the default ambient
** and no specular highlight. */
void lsys_mesh_material_color (lsys_material *mt, double r, double g, double b);

/* x clamped to [0, 1], as colours are (NaN gives 0). */
static inline float lsys_unit (double x) {
  return x > 0 ? (x < 1 ? (float)x : 1.0f) : 0.0f;
}

#endif
