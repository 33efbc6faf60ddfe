/*
** What the export writers (export_obj.c, export_ply.c, export_glb.c)
** share; not for use outside them.
**
** - A buffered writer on an atomic output file (export_write.c): the
**   writers stream through one 64 KiB buffer, and the target is replaced
**   only when everything was written (outfile.h).
** - Number formatting (export_write.c): the writers format numbers
**   themselves, as with printf a text exporter spends most of its time
**   parsing format strings. Binary output is assembled byte by byte, low
**   byte first, so the files are the same on any host.
** - Validation and grouping by material and texture (export_group.c).
*/
#ifndef LSYS_EXPORT_IMPL_H
#define LSYS_EXPORT_IMPL_H

#include <math.h>
#include <string.h>

#include "common.h"
#include "export.h"
#include "mesh.h"
#include "outfile.h"
#include "texture.h"

/* ------------------------------------------------------------------ */
/* Buffered output                                                      */
/* ------------------------------------------------------------------ */

#define WBUFSIZE ((size_t)1 << 16)

typedef struct lsys_writer {
  lsys_outfile out;
  size_t n;                /* bytes waiting in b */
  unsigned char b[WBUFSIZE];
} lsys_writer;

/* Opens a writer for 'path' into *wp; LSYS_OK, or an error naming it. */
int lsys_export_wopen (lsys_writer **wp, const char *path, lsys_error *e);
void lsys_export_wflush (lsys_writer *w);
void lsys_export_wbytes (lsys_writer *w, const void *s, size_t n);
void lsys_export_wstr (lsys_writer *w, const char *s);
/* Flushes and closes the temporary file; the target is replaced by
** lsys_export_wcommit. On failure the temporary file is gone and e names the
** target. */
int lsys_export_wfinish (lsys_writer *w, lsys_error *e);
/* Finishes (when not done yet) and replaces the target; frees the writer. */
int lsys_export_wcommit (lsys_writer *w, lsys_error *e);
/* Drops what was written; the target stays as it was. Frees the writer
** (NULL is allowed). */
void lsys_export_wabort (lsys_writer *w);

/* Room for 'k' (<= WBUFSIZE) more bytes; fill them, then call wdone. */
static inline unsigned char *wroom (lsys_writer *w, size_t k) {
  if (w->n + k > WBUFSIZE) lsys_export_wflush(w);
  return w->b + w->n;
}

static inline void wdone (lsys_writer *w, void *end) {
  w->n = (size_t)((unsigned char *)end - w->b);
}

/* ------------------------------------------------------------------ */
/* Number formatting                                                    */
/* ------------------------------------------------------------------ */

/* Writes 'f' in decimal, in the style of %g, with the fewest significant
** digits between 6 and 9 that read back as the same float; non-finite
** values as 0. At most 15 characters; returns the end. */
char *lsys_export_putfloat (char *s, float f);

/* 'tag', then the 'n' floats of 'v' (non-finite ones as 0) each after a
** space; ends the line. */
void lsys_export_putvec (lsys_writer *w, const char *tag, const float *v, int n);

static inline char *putuint (char *s, uint64_t u) {
  char t[20];
  int n = 0;
  do { t[n++] = (char)('0' + u % 10); u /= 10; } while (u != 0);
  while (n > 0) *s++ = t[--n];
  return s;
}

static inline float fin (float x) {
  return isfinite(x) ? x : 0.0f;
}

/* The linear value of the display (sRGB) colour component 'c', clamped to
** [0, 1] first: the exact sRGB transfer function of IEC 61966-2-1, as
** glTF 2.0 (3.9.2) and KHR_materials take colour factors. 0.5 gives
** 0.21404114. */
static inline float tolinear (double c) {
  double x = lsys_unit(c);
  return (float)(x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4));
}

static inline unsigned char *put32 (unsigned char *p, uint32_t x) {
  p[0] = (unsigned char)x; p[1] = (unsigned char)(x >> 8);
  p[2] = (unsigned char)(x >> 16); p[3] = (unsigned char)(x >> 24);
  return p + 4;
}

static inline unsigned char *putf32 (unsigned char *p, float f) {
  uint32_t u;
  memcpy(&u, &f, sizeof u);
  return put32(p, u);
}

/* ------------------------------------------------------------------ */
/* Validation and grouping by material                                  */
/* ------------------------------------------------------------------ */

/* Triangles must refer to existing vertices, and the counts must fit the
** 32-bit numbers of the formats. LSYS_OK, or an error naming 'path'. */
int lsys_export_checkmesh (const lsys_mesh *m, const char *path, lsys_error *e);

/*
** Triangles and segments sorted by material with a counting sort. With
** textures, the triangles are first sorted by texture, so that the stable
** sort by material leaves each material's triangles in runs of one texture.
** A material slot and a texture make one exported material: slot k alone
** ('plain', for its untextured triangles and its segments) and slot k with
** texture t, in the order of the runs.
*/
typedef struct lsys_run {
  size_t first, end;           /* range of tord */
  uint32_t slot;               /* material slot */
  uint16_t tex;                /* texture index, 0 for none */
  uint8_t twosided;            /* some triangle has a two-sided vertex */
} lsys_run;

typedef struct lsys_groups {
  size_t nmat;                 /* material slots: the palette size, at least 1 */
  size_t *tfirst, *lfirst;     /* nmat + 1 offsets into tord and lord */
  uint32_t *tord, *lord;       /* triangle and segment numbers, by material */
  lsys_run *runs;              /* the triangle runs, by slot then texture */
  size_t nruns, runcap;
  const lsys_texture *const *tex;
  size_t ntex;                 /* textures that apply; 0 when none can */
} lsys_groups;

/* Groups the mesh for a palette of 'npal' materials and the textures
** 'tex' (see lsys_export_obj). LSYS_OK, or LSYS_ENOMEM with a message
** naming 'path' and nothing to free. */
int lsys_export_groupmesh (lsys_groups *g, const lsys_mesh *m, size_t npal,
                           const lsys_texture *const *tex, int ntex, const char *path,
                           lsys_error *e);
void lsys_export_freegroups (lsys_groups *g);

/* Whether slot k's plain material is used: by untextured triangles (the
** first run of the slot, texture 0) or by segments. 'r' is the slot's
** first run or NULL. */
static inline int plainused (const lsys_groups *g, size_t k, const lsys_run *r) {
  return (r != NULL && r->slot == k && r->tex == 0) || g->lfirst[k + 1] > g->lfirst[k];
}

/* The material of slot k: pal[k], or a grey default when the palette is
** empty. */
const lsys_material *lsys_export_slotmaterial (const lsys_material *pal, size_t npal, size_t k);

#endif
