/*
** Incremental growth (Davison, "Incremental rules for growing plants",
** section "Incremental rules"; docs/manual.md §12): a plant is a set of
** persistent limbs whose state changes a little at each tick, and new limbs
** are attached to existing ones, instead of a string derived and drawn anew.
**
** The limbs are a table of arrays (struct of arrays) indexed by limb id: the
** parent, the plant, the level (1 for a limb growing from the ground), the age
** in ticks, the length, radius and colour, the rotation relative to the
** parent's frame where it is attached, and the cached world frame. Ids are
** given in creation order and never reused, so a parent's id is below its
** children's and one pass in id order updates every world frame.
**
** Ticks are parallel steps as in an L-system: between lsys_grow_begin and
** lsys_grow_end, setters write the next state while getters (the arrays
** len, rad, rgb, ...) keep the state of the start of the tick; limbs added
** during a tick exist at once (and are counted at once in nalive and pcount:
** the paper's spawning rule, section "Incremental rules", tests
** treeLimbs.size(), the list makeChild has just appended to) but first run at
** the next tick; removals and leaves take effect at the end of the tick.
**
** Geometry lives in a scene (scene.h) the caller owns: each limb owns a fixed
** range of vertices and triangles (a cylinder of 'sides' sides: 2 sides
** vertices, 2 sides triangles), each leaf another (the world's leaf shape,
** lsys_grow_set_leaf: by default a quad of 4 vertices and 2 triangles; lit
** on both sides); lsys_grow_update rewrites in place the
** ranges of limbs that changed or moved, marks them dirty in the scene
** (lsys_scene_touch), and appends ranges for new limbs. A removed limb's or
** leaf's range is made degenerate and reused by the next one made. Once the
** arrays have grown to their size, a tick allocates nothing. Colours are
** quantized to 5 bits a channel and interned in the scene's palette.
**
** Frames: a world frame is a base point and three unit columns R (right), H
** (heading: the limb's axis) and F (front), as lsys.components' frames (R = -L,
** F = -U of the turtle). A root limb starts at its plant's position with
** R = +x, H = +y, F = +z. Angles are in degrees.
*/
#ifndef LSYS_LIMBS_H
#define LSYS_LIMBS_H

#include "common.h"
#include "scene.h"

#define LSYS_LIMBS_MAXSIDES 64
#define LSYS_LIMBS_MAXLEAFV 65536     /* vertices of a leaf shape */

/* What a new limb is. */
typedef struct lsys_limbspec {
  int32_t parent;         /* its parent's id, or -1 for a root */
  int32_t plant;          /* a root's plant (lsys_grow_plant); a child takes its parent's */
  double at;              /* where along the parent it grows, 0 to 1 (1: the tip) */
  double axis[3];         /* the rotation from the parent's frame: roll about the parent's
                             heading first, then 'angle' about 'axis' (in the parent's
                             local x, y, z) rolled with it */
  double angle, roll;
  double length, radius;  /* > 0 and >= 0 */
  float rgb[3];           /* 0 to 1 */
  uint16_t tag;           /* the caller's (lsys.grow: the limb's kind) */
} lsys_limbspec;

/* What is deferred to the end of a tick. */
typedef struct lsys_limbop {
  int op;                 /* LEAVES, DROP or REMOVE (grow.c) */
  int32_t limb;
  int n;
  double size;
  float rgb[3];
} lsys_limbop;

/* Flags of lsys_limbs.flag */
#define LSYS_LIMB_ALIVE 0x01

typedef struct lsys_limbs {
  lsys_scene *sc;         /* the geometry's scene (borrowed) */
  int sides;
  double ring[2 * LSYS_LIMBS_MAXSIDES];   /* cos, sin of the sides' angles */
  size_t maxlimbs;        /* 0: no cap; else lsys_grow_add fails with LSYS_ELIMIT past it */
  size_t max_memory;      /* the budget (bytes) of lsys_grow_bytes: growing past it fails
                             with LSYS_EMEMORY; 0: the process's (lsys_common_memory_limit) */
  size_t held_limb, held_plant;   /* bytes the caller keeps for each limb and each plant
                                     made (lsys.grow's Lua handles), counted in the budget */
  size_t n, cap;          /* limb ids 0 .. n - 1, dead ones included */
  size_t nalive;
  /* per limb */
  int32_t *parent, *plant, *first, *next;   /* tree: first child, next sibling */
  int32_t *last, *prev;   /* last child, previous sibling: appending and unlinking in O(1) */
  uint16_t *level, *tag;
  uint32_t *age;
  uint8_t *flag, *chg;    /* LSYS_LIMB_*; what changed since the last update */
  double *len, *rad;      /* the state (at the start of the tick within one) */
  double *nlen, *nrad;    /* the next state (during a tick) */
  float *rgb, *nrgb;      /* 3 each */
  double *loc, *nloc;     /* rotation from the parent's frame: 9 each (columns R, H, F) */
  double *at;
  double *wp, *wm;        /* world base point (3) and frame columns R, H, F (9) */
  uint32_t *v0, *t0;      /* its vertex and triangle range */
  uint16_t *col;          /* palette index of its colour */
  int32_t *leaf;          /* its first leaf, or -1 */
  uint32_t *nleaves;
  /* leaves */
  size_t nl, lcap;
  int32_t *lf_limb, *lf_next;   /* lf_limb -1: free (lf_next links free leaves) */
  uint32_t *lf_k, *lf_v0, *lf_t0;
  float *lf_size;
  uint16_t *lf_col;
  int32_t lf_free;
  /* the leaf shape, in the leaf's frame (lsys_grow_set_leaf) */
  const float *sh_pos, *sh_nrm, *sh_uv;
  const uint32_t *sh_tri;
  uint32_t sh_nv, sh_nt;
  void *sh_mem;           /* what they point into when not the built-in quad */
  /* reusable geometry ranges of removed limbs and leaves: v0, t0 pairs */
  uint32_t *freelimb, *freeleaf;
  size_t nfreelimb, capfreelimb, nfreeleaf, capfreeleaf;
  /* plants */
  size_t np, pcap;
  double *ppos;           /* 3 each */
  uint32_t *pcount;       /* living limbs of each plant, counted as they are made (as
                             nalive): not the state of the start of a tick */
  /* a tick */
  int intick;
  size_t n0;              /* limbs at its start: the ones that age at its end */
  lsys_limbop *pending;   /* deferred to the end of the tick */
  size_t npend, cappend;
  int dirty;              /* something waits for lsys_grow_update */
  uint16_t *qmap;         /* quantized colour -> palette index + 1 (32768 entries) */
} lsys_limbs;

/* A grower writing into 'sc' with cylinders of 'sides' sides (3 to
** LSYS_LIMBS_MAXSIDES). */
void lsys_grow_init (lsys_limbs *g, lsys_scene *sc, int sides);
void lsys_grow_free (lsys_limbs *g);

/*
** The shape of every leaf: the triangles of 'shape' (positions, normals and
** uv; its colours and textures are not used), in the leaf's own frame: y
** along the leaf from where it is attached, z its normal, x = y cross z
** across it; a leaf of size s is the shape scaled by s. Copied. Only before
** the first leaf is made (LSYS_EBUSY after), so that every leaf's vertex
** range has one size; NULL restores the quad (x in [-0.25, 0.25], y in
** [0, 1], z = 0). LSYS_EARG when 'shape' has no triangles, more than
** LSYS_LIMBS_MAXLEAFV vertices, an index out of range or a coordinate that
** is not finite; LSYS_ENOMEM.
*/
int lsys_grow_set_leaf (lsys_limbs *g, const lsys_mesh *shape);

/* The bytes g's budget counts: its arrays (capacities), its scene's
** (lsys_scene_bytes), and what the caller keeps for its limbs and plants. */
size_t lsys_grow_bytes (const lsys_limbs *g);

/* A new plant at 'pos'; its index in *id. LSYS_OK, LSYS_EMEMORY (the budget,
** max_memory) or LSYS_ENOMEM. */
int lsys_grow_plant (lsys_limbs *g, const double pos[3], int32_t *id);

/* A new limb; its id in *id. LSYS_OK, LSYS_EARG (no such parent or plant, a
** dead parent, bad numbers), LSYS_ELIMIT (maxlimbs reached), LSYS_EMEMORY
** (the budget) or LSYS_ENOMEM. Everything that grows (the limbs' arrays, the
** leaves', the deferred operations, the scene's mesh) grows within the
** budget; a failed update (LSYS_EMEMORY too) leaves what it did not do for a
** retry. */
int lsys_grow_add (lsys_limbs *g, const lsys_limbspec *s, int32_t *id);

/* Setters (of the next state within a tick). LSYS_OK or LSYS_EARG (a dead or
** unknown limb, a negative or non-finite value). */
int lsys_grow_set_length (lsys_limbs *g, int32_t i, double len);
int lsys_grow_set_radius (lsys_limbs *g, int32_t i, double r);
int lsys_grow_set_color (lsys_limbs *g, int32_t i, const float rgb[3]);
int lsys_grow_set_turn (lsys_limbs *g, int32_t i, const double axis[3], double angle,
                        double roll);

/* n leaves of 'size' and colour rgb at the tip of limb i; all its leaves
** dropped; the limb and its subtree removed. Deferred to the end of a tick.
** LSYS_OK, LSYS_EARG or LSYS_ENOMEM. */
int lsys_grow_add_leaves (lsys_limbs *g, int32_t i, int n, double size, const float rgb[3]);
int lsys_grow_drop_leaves (lsys_limbs *g, int32_t i);
int lsys_grow_remove (lsys_limbs *g, int32_t i);

/* A tick: lsys_grow_begin, the rules' reads and writes, lsys_grow_end (which
** commits the next state, applies what was deferred, ages the limbs that
** existed at the start, and updates the geometry). LSYS_EBUSY when a tick is
** already running (begin) or none is (end). */
int lsys_grow_begin (lsys_limbs *g);
int lsys_grow_end (lsys_limbs *g);

/* Writes what changed into the scene (world frames down the changed
** subtrees, vertex ranges in place, new ranges appended). LSYS_OK or
** LSYS_ENOMEM (then the scene may lack the newest limbs; a later update
** retries). */
int lsys_grow_update (lsys_limbs *g);

/* Whether limb i exists and is alive. */
int lsys_grow_alive (const lsys_limbs *g, int32_t i);

/* The limb's world tip: its base + H * length (after lsys_grow_update). */
void lsys_grow_tip (const lsys_limbs *g, int32_t i, double tip[3]);

#endif
