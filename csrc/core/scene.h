/*
** The scene (docs/architecture.md): everything an
** interpretation produces and everything its consumers need, in one place.
** The turtle fills it; the export writers, the offscreen renderer and the
** viewer's snapshots read it.
**
**   mesh       triangles and wide lines (mesh.h)
**   palette    materials, indexed by the mesh's colour indices (owned)
**   textures   indexed by the mesh's texture indices, tex[k - 1] (borrowed:
**              whoever owns the scene keeps them alive; in Lua the Scene's
**              user values do)
**   records    one per drawing module (lsys_rec, read as lsys_trec), for
**              picking, arranging, and the Lua API; with the joint
**              stiffnesses of Z
**   camera, light, background   how to look at it (from the view)
**   parts      contiguous ranges of vertices, triangles, lines and records:
**              one plant of a population, one component of a component
**              graph, one limb's geometry in incremental growth. A scene
**              without parts is one part: everything.
**   instances  a part drawn under a transform (populations: population.h).
**              A scene without instances is drawn as its mesh is; a scene
**              with instances is drawn as its instances only, each its
**              part's geometry under its transform, so that its parts are
**              prototypes shared by every instance of them.
**   dirty      the vertex ranges changed in place since the consumer last
**              took them (a viewer copies only those: lsys_viewer_patch).
**
** A consumer may look at a scene another way for one call through a copy
** of the struct with other camera, light, background or textures: the copy
** borrows the arrays, is read only, and is never freed (the viewer's camera,
** lsys.render's options).
**
** Parts, instances and the dirty range are the layout the component graphs,
** incremental growth and populations build on: the turtle writes one part
** and no instances; lsys.population (population.h) writes a part per
** prototype and an instance per plant, and the renderer, the viewer and
** the export writers draw or write each instance.
*/
#ifndef LSYS_SCENE_H
#define LSYS_SCENE_H

#include "common.h"
#include "mesh.h"
#include "texture.h"

#define LSYS_NOREC UINT32_MAX
#define LSYS_SCENE_NDIRTY 32    /* dirty ranges kept; past that the nearest two merge */

/* What a turtle record stands for. */
enum {
  LSYS_REC_SEGMENT = 1,   /* F or G: p0 -> p1 */
  LSYS_REC_SPHERE,        /* @O: centre p0 = p1, diameter w0 */
  LSYS_REC_DISC,          /* @c, @o */
  LSYS_REC_POLYGON,       /* }: p0 = first vertex, p1 = last */
  LSYS_REC_LABEL,         /* @L */
  LSYS_REC_SYSTEM,        /* @S (only when system calls are allowed) */
  LSYS_REC_GCYL,          /* a generalized-cylinder segment: previous control point ->
                             p1 (the @Gc or @Ge module) */
  LSYS_REC_SURFACE        /* ~X (p1: where the turtle ends) or @PD (p1: the turtle) */
};

/* Everything a record says about a drawing module, unpacked (lsys_scene_record).
** L is H x U. A segment starts at p1 - len * H (it runs along H); other records
** have len = 0. The stiffness of the joint before a segment, when Z set one, is
** stiff[3 * stiff .. 3 * stiff + 2] of the scene. */
typedef struct lsys_trec {
  uint32_t module;        /* index of the module in the string (0-based) */
  uint32_t parent;        /* record of the segment this one starts from, or LSYS_NOREC */
  uint8_t kind, pad;
  uint16_t color;
  float w0, w1;           /* width at the start and at the end */
  float len;              /* length of a segment */
  float p1[3];            /* end point (a sphere's or disc's centre, a polygon's last vertex) */
  float H[3], U[3];       /* frame at the end */
  uint32_t stiff;         /* Z(sh, su, sl) in effect for the joint before it, or LSYS_NOREC */
  uint32_t tri0, ntri;    /* the mesh triangles the module drew up to this record: for a
                             polygon, surface, disc or sphere the whole shape (highlights) */
} lsys_trec;

/*
** How a scene keeps its records: a big plant has millions, and most of what
** one says is what many others say too. A stored record (16 bytes) holds its
** module, its parent, its shape and where its end point is. A shape holds the
** rest (kind, colour, widths, length, frame, stiffness, triangles), once for
** all the records that have the same: the segments of a plant without
** tropisms turn by a few angles, so their frames repeat. The end point of a
** segment drawn as a line is the second end of its line in the mesh (the same
** float: both are the turtle's position rounded once); any other record's is
** in the scene's 'recpt'. Before a scene's lines change or leave it
** (deformations, a viewer taking the mesh), lsys_scene_detach_records moves
** those end points to 'recpt', so that records keep what the turtle wrote.
*/
typedef struct lsys_rec {
  uint32_t module, parent;
  uint32_t shape;         /* its shape: shape[shape] */
  uint32_t at;            /* its end point: line 'at' of the mesh when the shape's 'line' is
                             set, else recpt[3 * at .. 3 * at + 2] */
} lsys_rec;

typedef struct lsys_rshape {
  float H[3], U[3];
  float len, w0, w1;
  uint32_t stiff, tri0, ntri;
  uint16_t color;
  uint8_t kind;
  uint8_t line;           /* 1: the end points of its records are mesh lines' */
} lsys_rshape;

/*
** How to look at a scene (the view's camera). With a target and an eye the
** camera looks from the eye at the target; without a target it aims at the
** centre of the bounding box. Without an eye, it looks along 'dir' and steps
** back until every vertex and line end is in the image with a margin of 5%
** of its size on each side (around the target, so the margins may differ).
** A parallel projection is scaled the same way. Near and far planes always
** come from the bounding box.
*/
enum { LSYS_PERSPECTIVE = 0, LSYS_PARALLEL = 1 };

typedef struct lsys_camera {
  double eye[3];        /* viewpoint, when has_eye */
  double target[3];     /* view reference point, when has_target */
  double up[3];         /* up vector, when has_up; default +y */
  double dir[3];        /* view direction used when there is no eye; default (0, 0, -1) */
  int has_eye, has_target, has_up;
  int projection;       /* LSYS_PARALLEL (default, as cpfg) or LSYS_PERSPECTIVE */
  double fov;           /* vertical field of view in degrees (perspective); default 30 */
  double twist;         /* degrees; a positive twist turns the picture counterclockwise */
  double zoom;          /* magnification about the image centre, after fitting; default 1 */
  double halfh;         /* parallel: half the image height in world units (before zoom)
                           when > 0, instead of fitting (the viewer keeps a scale) */
  int has_box;          /* fit the box (box[0..2] the low corner, box[3..5] the high one)
                           instead of the scene: one camera for every picture of a
                           growing plant (its final size); near and far planes cover both */
  double box[6];
  int has_bounds;       /* bounds[] holds the scene's bounds (lsys_mesh_bounds: lo, hi) as
                           the caller knows them: the camera needs no pass over the scene */
  double bounds[6];
} lsys_camera;

/* A range of a scene's arrays (see above). */
typedef struct lsys_part {
  size_t v0, nv;          /* vertices */
  size_t t0, nt;          /* triangles */
  size_t l0, nl;          /* line segments */
  size_t r0, nr;          /* records */
} lsys_part;

/* Part 'part' drawn under the column-major 4 x 4 transform 'm' (affine:
** m[3] = m[7] = m[11] = 0, m[15] = 1). */
typedef struct lsys_instance {
  uint32_t part;
  float m[16];
} lsys_instance;

/* At most this many lights of a view's own (OpenGL 1.x has at least 8). */
#define LSYS_SCENE_NLIGHTS 8

/* One light of a view's own (cpfg's "light:" lines): pos[3] = 0 makes it a
** direction towards the light (world space), 1 a position; its ambient,
** diffuse and specular colours are RGB in [0, 1]. */
typedef struct lsys_slight {
  double pos[4];
  float ambient[3], diffuse[3], specular[3];
} lsys_slight;

typedef struct lsys_scene {
  lsys_mesh mesh;
  lsys_material *pal; size_t npal;             /* owned; colour c uses pal[c % npal] */
  size_t palcap;                               /* room in pal (lsys_scene_add_material) */
  const lsys_texture *const *tex; int ntex;    /* borrowed; texture k is tex[k - 1] */
  lsys_rec *rec; size_t nrec, reccap;         /* the records (see lsys_rec) */
  lsys_rshape *shape; size_t nshape, shapecap; /* what records share */
  float *recpt; size_t npt, ptcap;             /* 3 per record whose end point is its own */
  float *stiff; size_t nstiff, stiffcap;       /* 3 per Z-stiffened record */
  lsys_camera cam;
  double light[3];      /* world-space direction towards the key light */
  lsys_slight lights[LSYS_SCENE_NLIGHTS];   /* a view's own lights: when nlights > 0 */
  int nlights;          /* they replace the default ones (key, fill, sky, ground) */
  float background[3];  /* RGB in [0, 1] */
  lsys_part *parts; size_t nparts, partcap;
  lsys_instance *inst; size_t ninst, instcap;
  size_t dirty[2 * (LSYS_SCENE_NDIRTY + 1)];  /* vertex ranges changed in place: [dirty[2k],
                                                 dirty[2k+1]), sorted, apart
                                                 (lsys_scene_ranges_add) */
  size_t ndirty;
  lsys_meter *meter;      /* while it is filled: the memory budget of its arrays (or NULL) */
  int cull;               /* 1: its solid (not two-sided) triangles are wound counterclockwise
                             seen from outside and enclose what they bound (a grown plant's
                             limbs): a renderer may cull their back faces */
} lsys_scene;

/* Fills 'c' with the defaults above. */
void lsys_scene_camera_defaults (lsys_camera *c);

/* An empty scene: no geometry, no palette (a grey default), the default
** camera, the light towards (0.4, 0.8, 0.6), a pale sky-blue background
** (0.93, 0.96, 1). These are the view schema's defaults (lua/lsys/view.lua
** owns them; render_spec checks that the two agree). */
void lsys_scene_init (lsys_scene *s);
void lsys_scene_free (lsys_scene *s);
/* Empties the geometry, records, parts and instances; keeps the capacities,
** the palette, textures, camera and light. */
void lsys_scene_clear (lsys_scene *s);

/* Replaces the palette with a copy of pal[0 .. n-1]. LSYS_OK or LSYS_ENOMEM
** (the old palette stays). */
int lsys_scene_set_palette (lsys_scene *s, const lsys_material *pal, size_t n);

/* Appends a material to the palette and sets *idx to its index; the palette
** grows geometrically. LSYS_OK, LSYS_ELIMIT (65,536 entries: colour indices
** are 16-bit) or LSYS_ENOMEM. */
int lsys_scene_add_material (lsys_scene *s, const lsys_material *m, size_t *idx);

/* Makes room for 'n' more records (within the meter). LSYS_OK, LSYS_ENOMEM
** or LSYS_EMEMORY. */
int lsys_scene_reserve_records (lsys_scene *s, size_t n);
/* Makes room for 'n' more shapes, and for 'n' more end points (within the meter).
** LSYS_OK, LSYS_ENOMEM or LSYS_EMEMORY. */
int lsys_scene_reserve_shapes (lsys_scene *s, size_t n);
int lsys_scene_reserve_points (lsys_scene *s, size_t n);

/* Record k (< nrec) unpacked into *r. A record whose shape or end point is
** out of the scene's arrays (a run that failed half way) reads as zeros
** there. Allocates nothing. */
void lsys_scene_record (const lsys_scene *s, size_t k, lsys_trec *r);

/* The shape of record k (< nrec), and its kind (a shape of zeros when the
** record has none in the scene). */
static inline const lsys_rshape *lsys_scene_recshape (const lsys_scene *s, size_t k) {
  static const lsys_rshape none = {{0, 0, 0}, {0, 0, 0}, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  uint32_t i = s->rec[k].shape;
  return i < s->nshape ? &s->shape[i] : &none;
}
static inline int lsys_scene_reckind (const lsys_scene *s, size_t k) {
  return lsys_scene_recshape(s, k)->kind;
}

/* Appends the record 'r' (its parent and stiffness as they are) with a shape
** and an end point of its own. LSYS_OK, LSYS_ELIMIT (too many records),
** LSYS_ENOMEM or LSYS_EMEMORY. */
int lsys_scene_add_record (lsys_scene *s, const lsys_trec *r);

/* Appends src's records to dst's as they read in src, but with their
** parents moved by dst's present number of records and their stiffnesses,
** triangles and lines by 'ds', 'dt' and 'dl' (where src's stiffnesses,
** triangles and lines start in dst). Room is made first; on a failure (LSYS_ENOMEM,
** LSYS_EMEMORY, LSYS_ELIMIT) dst's records are as before. */
int lsys_scene_append_records (lsys_scene *dst, const lsys_scene *src, size_t ds, size_t dt,
                               size_t dl);

/* Gives every record whose end point is a mesh line's an end point of its own,
** equal to it: the lines may then change or go. LSYS_OK or LSYS_ENOMEM (the
** records as they were). */
int lsys_scene_detach_records (lsys_scene *s);

/* Appends the stiffness (sh, su, sl) and sets *idx to its index (for a
** record's 'stiff'). LSYS_OK, LSYS_ENOMEM or LSYS_EMEMORY. */
int lsys_scene_add_stiffness (lsys_scene *s, const double k[3], uint32_t *idx);

/* Starts a part at the present ends of the arrays; lsys_scene_end_part
** closes it at their new ends. Returns its index, or -1 when out of memory. */
long lsys_scene_begin_part (lsys_scene *s);
void lsys_scene_end_part (lsys_scene *s, size_t part);

/* Adds an instance of 'part' under 'm' (16 floats, column-major). LSYS_OK,
** LSYS_EARG (no such part) or LSYS_ENOMEM. */
int lsys_scene_add_instance (lsys_scene *s, size_t part, const float m[16]);

/* Marks vertices [v0, v0 + nv) changed in place (lsys_scene_ranges_add into the
** dirty ranges). lsys_scene_take_dirty returns the range covering them all (0
** when there is none) and empties the list; lsys_scene_take_ranges copies the
** list into r (room for 2 * LSYS_SCENE_NDIRTY), returns its length and empties
** it. Allocates nothing. */
void lsys_scene_touch (lsys_scene *s, size_t v0, size_t nv);
int lsys_scene_take_dirty (lsys_scene *s, size_t *v0, size_t *v1);
size_t lsys_scene_take_ranges (lsys_scene *s, size_t *r);

/* Adds [a, b) to the list r[0 .. 2 * *n) of sorted ranges that neither overlap
** nor touch, merging it with those it overlaps or touches; when that makes
** more than 'max' ranges, the two with the smallest gap between them merge
** (r has room for max + 1 ranges). The list then covers every range added,
** and a little more once it is full. */
void lsys_scene_ranges_add (size_t *r, size_t *n, size_t max, size_t a, size_t b);

/* The part that holds record 'r' (its index), or -1 when none does. */
long lsys_scene_part_of_record (const lsys_scene *s, size_t r);

/* The point 'p' under the affine column-major transform 'm', in doubles. */
static inline void lsys_xform (const float m[16], const float p[3], double out[3]) {
  int i;
  for (i = 0; i < 3; i++)
    out[i] = (double)m[i] * p[0] + (double)m[4 + i] * p[1] + (double)m[8 + i] * p[2] +
             (double)m[12 + i];
}

/* Axis-aligned bounds (lo[3], hi[3]) of the scene as drawn: its mesh's
** (lsys_mesh_bounds) without instances; with instances, of every vertex
** and line end of each instance's part under its transform (what a
** flattened copy's mesh bounds would be, in doubles). Returns 0 (and lo =
** hi = 0) when nothing is drawn, else 1. Allocates nothing. */
int lsys_scene_bounds (const lsys_scene *s, double lo[3], double hi[3]);

/* The bytes of memory the scene's arrays hold (their capacities): mesh,
** palette, records, stiffnesses, parts and instances; not the textures it
** borrows. */
size_t lsys_scene_bytes (const lsys_scene *s);

#endif
