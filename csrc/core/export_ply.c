/*
** Binary little-endian PLY export (export.h).
*/
#include <stdio.h>

#include "export_impl.h"

/* A vertex colour byte: the display (sRGB) value as it is, which is how PLY
** readers take 8-bit colours (MeshLab; Blender's importer decodes them as
** sRGB by default), unlike glTF's and MTL's linear factors. */
static unsigned char tobyte (float c) {
  return (unsigned char)(lsys_unit(c) * 255.0f + 0.5f);
}

static unsigned char *plyvertex (unsigned char *p, const float *pos, const float *nrm,
                                 const float *uv, const lsys_material *mt) {
  int k;
  for (k = 0; k < 3; k++) p = putf32(p, fin(pos[k]));
  for (k = 0; k < 3; k++) p = putf32(p, nrm ? fin(nrm[k]) : 0.0f);
  for (k = 0; k < 2; k++) p = putf32(p, uv ? fin(uv[k]) : 0.0f);
  for (k = 0; k < 3; k++) *p++ = tobyte(mt->diffuse[k]);
  return p;
}

static void plyheader (lsys_writer *w, const lsys_mesh *m) {
  char head[1024];
  int n = snprintf(head, sizeof head,
                   "ply\nformat binary_little_endian 1.0\ncomment written by lsys\n"
                   "comment line segments: the edge element; their end points follow the "
                   "triangle vertices\n"
                   "element vertex %zu\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "property float nx\nproperty float ny\nproperty float nz\n"
                   "property float s\nproperty float t\n"
                   "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                   "element face %zu\nproperty list uchar uint vertex_indices\n",
                   m->nv + 2 * m->nl, m->nt);
  lsys_export_wbytes(w, head, (size_t)n);
  if (m->nl > 0) {
    n = snprintf(head, sizeof head, "element edge %zu\nproperty int vertex1\n"
                 "property int vertex2\n", m->nl);
    lsys_export_wbytes(w, head, (size_t)n);
  }
  lsys_export_wstr(w, "end_header\n");
}

/* The vertices, two per segment after those of the mesh. */
static void plyvertices (lsys_writer *w, const lsys_mesh *m, const lsys_material *pal,
                         size_t npal) {
  size_t i, nmat = npal == 0 ? 1 : npal;
  for (i = 0; i < m->nv; i++) {
    unsigned char *p = wroom(w, 64);
    p = plyvertex(p, m->pos + 3 * i, m->nrm + 3 * i, m->uv + 2 * i,
                  lsys_export_slotmaterial(pal, npal, m->col[i] % nmat));
    wdone(w, p);
  }
  for (i = 0; i < m->nl; i++) {
    const lsys_material *mt = lsys_export_slotmaterial(pal, npal, m->lcol[i] % nmat);
    unsigned char *p = wroom(w, 128);
    p = plyvertex(p, m->lpos + 6 * i, NULL, NULL, mt);
    p = plyvertex(p, m->lpos + 6 * i + 3, NULL, NULL, mt);
    wdone(w, p);
  }
}

/*
** PLY layout: the mesh vertices, then two vertices per line segment (normal
** and texture coordinates 0); the faces; and, when there are segments, an
** 'edge' element (vertex1, vertex2) that refers to those extra vertices.
** Vertex colours are the diffuse colours of the materials. Line widths are
** not kept. Textures are ignored (PLY has no standard way to name an
** image); the texture coordinates are there as s and t.
*/
int lsys_export_ply (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e) {
  lsys_writer *w;
  size_t i;
  int st = lsys_export_checkmesh(m, path, e);
  (void)tex; (void)ntex;
  if (st != LSYS_OK) return st;
  if (m->nv + 2 * m->nl > (size_t)INT32_MAX)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot write '%s': mesh too large", path);
  st = lsys_export_wopen(&w, path, e);
  if (st != LSYS_OK) return st;
  plyheader(w, m);
  plyvertices(w, m, pal, npal);
  for (i = 0; i < m->nt; i++) {
    unsigned char *p = wroom(w, 16);
    *p++ = 3;
    p = put32(p, m->tri[3 * i]);
    p = put32(p, m->tri[3 * i + 1]);
    p = put32(p, m->tri[3 * i + 2]);
    wdone(w, p);
  }
  for (i = 0; i < m->nl; i++) {
    unsigned char *p = wroom(w, 8);
    p = put32(p, (uint32_t)(m->nv + 2 * i));
    p = put32(p, (uint32_t)(m->nv + 2 * i + 1));
    wdone(w, p);
  }
  return lsys_export_wcommit(w, e);
}
