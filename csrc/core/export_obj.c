/*
** Wavefront OBJ export with its MTL file (export.h).
*/
#include <stdio.h>
#include <string.h>

#include "export_impl.h"

/* ------------------------------------------------------------------ */
/* MTL                                                                  */
/* ------------------------------------------------------------------ */

/* The MTL path: the extension of the file name (if any) becomes ".mtl". */
static char *mtlpath (const char *path, const char **name) {
  size_t n = strlen(path), base = 0, end = n, i;
  char *s;
  for (i = 0; i < n; i++)
    if (path[i] == '/' || path[i] == '\\') base = i + 1;
  for (i = n; i > base; i--)
    if (path[i - 1] == '.') { end = i - 1; break; }
  if (end == base) end = n;                    /* ".obj" alone: keep it whole */
  s = (char *)LSYS_MALLOC(end + 5);
  if (s == NULL) return NULL;
  memcpy(s, path, end);
  memcpy(s + end, ".mtl", 5);
  *name = s + base;
  return s;
}

/*
** An MTL colour, linear. The MTL format predates colour management and
** readers disagree: Blender's importer (io/wavefront_obj, obj_import_mtl.cc)
** copies Kd into the Principled BSDF's Base Color and Ke into Emission,
** which hold scene-linear values, and its exporter writes them back as they
** are; three.js's MTLLoader decodes Kd as sRGB. Blender is where exported
** plants are mostly taken, so Ka, Kd, Ks and Ke are all written linear (one
** convention for the whole file), as GLB's factors: a plant looks in Blender
** as in `lsys render`, and darker in a reader that takes MTL as sRGB (use
** .glb there). 'd' (opacity) and Ns are not colours and stay as they are.
*/
static void putrgb (lsys_writer *w, const char *tag, const float *c) {
  float v[3];
  int k;
  for (k = 0; k < 3; k++) v[k] = tolinear(c[k]);
  lsys_export_putvec(w, tag, v, 3);
}

/* "<tag> m<k>" or "<tag> m<k>_t<t>" and a newline: the name of slot k's
** material with texture t (0: none). */
static void putmtlname (lsys_writer *w, const char *tag, size_t k, unsigned t) {
  char *s = (char *)wroom(w, 64);
  while (*tag) *s++ = *tag++;
  *s++ = ' '; *s++ = 'm';
  s = putuint(s, k);
  if (t > 0) {
    *s++ = '_'; *s++ = 't';
    s = putuint(s, t);
  }
  *s++ = '\n';
  wdone(w, s);
}

/*
** One MTL entry. With a texture: map_Kd names its file as it was given
** when loaded (relative paths are then relative to where lsys ran, which
** OBJ readers take as relative to the .mtl file: write the OBJ next to the
** textures, or load them by absolute paths). Decal: Kd is white and illum 0
** (colour without lighting), so the image is the colour.
*/
static void putmtl (lsys_writer *w, const lsys_material *mt, size_t k, const lsys_texture *tx,
                    unsigned t) {
  static const float white[3] = {1, 1, 1};
  int spec = mt->specular[0] > 0 || mt->specular[1] > 0 || mt->specular[2] > 0;
  int decal = tx != NULL && tx->mode == LSYS_TEX_DECAL;
  float d = lsys_unit(mt->diffuse[3]);
  lsys_export_wstr(w, "\n");
  putmtlname(w, "newmtl", k, t);
  putrgb(w, "Ka", mt->ambient);
  putrgb(w, "Kd", decal ? white : mt->diffuse);
  putrgb(w, "Ks", mt->specular);
  putrgb(w, "Ke", mt->emission);
  lsys_export_putvec(w, "Ns", &mt->shininess, 1);  /* the same Phong exponent as OpenGL's */
  lsys_export_putvec(w, "d", &d, 1);
  lsys_export_wstr(w, decal ? "illum 0\n" : spec ? "illum 2\n" : "illum 1\n");
  if (tx != NULL) {
    lsys_export_wstr(w, "map_Kd ");
    lsys_export_wstr(w, tx->path);
    lsys_export_wstr(w, "\n");
  }
}

/* Writes the material file into *wp, finished but not committed: it
** replaces its target together with the .obj. */
static int writemtl (lsys_writer **wp, const lsys_groups *g, const lsys_material *pal,
                     size_t npal, const char *path, lsys_error *e) {
  lsys_writer *w;
  size_t k, r = 0;
  int st = lsys_export_wopen(&w, path, e);
  if (st != LSYS_OK) return st;
  lsys_export_wstr(w, "# lsys materials\n");
  for (k = 0; k < g->nmat; k++) {
    const lsys_material *mt = lsys_export_slotmaterial(pal, npal, k);
    if (plainused(g, k, r < g->nruns ? &g->runs[r] : NULL)) putmtl(w, mt, k, NULL, 0);
    for (; r < g->nruns && g->runs[r].slot == k; r++)
      if (g->runs[r].tex > 0)
        putmtl(w, mt, k, g->tex[g->runs[r].tex - 1], g->runs[r].tex);
  }
  if ((st = lsys_export_wfinish(w, e)) != LSYS_OK) {
    lsys_export_wabort(w);
    return st;
  }
  *wp = w;
  return LSYS_OK;
}

/* ------------------------------------------------------------------ */
/* OBJ                                                                  */
/* ------------------------------------------------------------------ */

/* "f a/a/a b/b/b c/c/c" with 1-based numbers. */
static void putface (lsys_writer *w, const uint32_t *v) {
  char *s = (char *)wroom(w, 128);
  int k, j;
  *s++ = 'f';
  for (k = 0; k < 3; k++) {
    *s++ = ' ';
    for (j = 0; j < 3; j++) {
      if (j > 0) *s++ = '/';
      s = putuint(s, (uint64_t)v[k] + 1);
    }
  }
  *s++ = '\n';
  wdone(w, s);
}

static void putline (lsys_writer *w, uint64_t a) {
  char *s = (char *)wroom(w, 64);
  *s++ = 'l'; *s++ = ' ';
  s = putuint(s, a);
  *s++ = ' ';
  s = putuint(s, a + 1);
  *s++ = '\n';
  wdone(w, s);
}

/* The header, the positions of the mesh vertices and of the segment ends
** (in material order), the normals and the texture coordinates. */
static void putvertices (lsys_writer *w, const lsys_mesh *m, const lsys_groups *g,
                         const char *mtlname) {
  char head[160];
  size_t i;
  snprintf(head, sizeof head, "# lsys: %zu vertices, %zu triangles, %zu line segments\n",
           m->nv, m->nt, m->nl);
  lsys_export_wstr(w, head);
  lsys_export_wstr(w, "mtllib ");
  lsys_export_wstr(w, mtlname);
  lsys_export_wstr(w, "\n");
  for (i = 0; i < m->nv; i++) lsys_export_putvec(w, "v", m->pos + 3 * i, 3);
  for (i = 0; i < m->nl; i++) {
    const float *p = m->lpos + 6 * (size_t)g->lord[i];
    lsys_export_putvec(w, "v", p, 3);
    lsys_export_putvec(w, "v", p + 3, 3);
  }
  for (i = 0; i < m->nv; i++) lsys_export_putvec(w, "vn", m->nrm + 3 * i, 3);
  for (i = 0; i < m->nv; i++) lsys_export_putvec(w, "vt", m->uv + 2 * i, 2);
}

/* The faces and segments, under their materials. */
static void putelements (lsys_writer *w, const lsys_mesh *m, const lsys_groups *g) {
  size_t i, k, r;
  for (k = 0, r = 0; k < g->nmat; k++) {
    const lsys_run *first = r < g->nruns && g->runs[r].slot == k ? &g->runs[r] : NULL;
    if (plainused(g, k, first)) {
      putmtlname(w, "usemtl", k, 0);
      if (first != NULL && first->tex == 0) {
        for (i = first->first; i < first->end; i++) putface(w, m->tri + 3 * (size_t)g->tord[i]);
        r++;
      }
      for (i = g->lfirst[k]; i < g->lfirst[k + 1]; i++) putline(w, m->nv + 2 * i + 1);
    }
    for (; r < g->nruns && g->runs[r].slot == k; r++) {
      putmtlname(w, "usemtl", k, g->runs[r].tex);
      for (i = g->runs[r].first; i < g->runs[r].end; i++)
        putface(w, m->tri + 3 * (size_t)g->tord[i]);
    }
  }
}

/*
** OBJ layout: the positions of the mesh vertices, then two per segment in
** material order; the normals and texture coordinates of the mesh vertices
** (texture.h: v up, as OBJ has it); then, per material slot, 'usemtl m<k>'
** followed by its untextured faces and its segments ('l' elements, which
** refer to positions only), and 'usemtl m<k>_t<t>' with the faces of slot
** k textured with texture t.
*/
int lsys_export_obj (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e) {
  lsys_groups g;
  lsys_writer *w, *mw = NULL;
  const char *mtlname;
  char *mpath;
  int st = lsys_export_checkmesh(m, path, e);
  if (st != LSYS_OK) return st;
  mpath = mtlpath(path, &mtlname);
  if (mpath == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if (strcmp(mpath, path) == 0) {
    LSYS_FREE(mpath);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "cannot write '%s': it would be its own material file", path);
  }
  st = lsys_export_wopen(&w, path, e);          /* first, so that a bad path names the .obj */
  if (st == LSYS_OK) {
    st = lsys_export_groupmesh(&g, m, npal, tex, ntex, path, e);
    if (st == LSYS_OK) {
      st = writemtl(&mw, &g, pal, npal, mpath, e);
      if (st != LSYS_OK) lsys_export_freegroups(&g);
    }
    if (st != LSYS_OK) lsys_export_wabort(w);
  }
  if (st != LSYS_OK) {
    LSYS_FREE(mpath);
    return st;
  }
  putvertices(w, m, &g, mtlname);
  putelements(w, m, &g);
  lsys_export_freegroups(&g);
  LSYS_FREE(mpath);
  /* both files complete before either replaces its target */
  if ((st = lsys_export_wfinish(w, e)) != LSYS_OK) {
    lsys_export_wabort(w);
    lsys_export_wabort(mw);
    return st;
  }
  if ((st = lsys_export_wcommit(mw, e)) != LSYS_OK) {
    lsys_export_wabort(w);
    return st;
  }
  return lsys_export_wcommit(w, e);
}
