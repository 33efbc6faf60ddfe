/*
** glTF 2.0 binary (.glb) export (export.h): the materials and textures,
** the JSON chunk that describes the scene, and the BIN chunk that holds
** its data.
**
** GLB layout. BIN chunk: the mesh vertices interleaved (position, unit
** normal, uv with v turned to glTF's downward axis: 32 bytes each) when
** there are triangles; the triangle indices (uint32) in the order of the
** runs (material slot, then texture); the segment end points in material
** order; the texture images, each padded to 4 bytes. JSON: one scene with
** one node and one mesh; per run, a TRIANGLES primitive sharing the three
** vertex accessors with its own index accessor; per material used by
** segments, a LINES primitive with its own POSITION accessor over its run
** of end points (no indices, no normals; line widths have no glTF
** equivalent: export.h's tubes replace the lines by triangles before this
** writer sees them). An empty mesh gives a scene without nodes.
**
** Textures: each one used gets an image (the PNG file's bytes, embedded), a
** sampler (its filters, REPEAT wrapping) and a texture; each (slot,
** texture) pair gets a material whose baseColorTexture is it: modulate
** keeps the diffuse colour as the factor (glTF multiplies by the texel's
** RGB, also for an intensity texture of a colour image), decal uses a white
** factor and KHR_materials_unlit. A modulated texture with transparent
** texels on an opaque material is cut at alpha 1/2 (alphaMode MASK).
*/
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "export_impl.h"

#define GLB_MAGIC  0x46546C67u     /* "glTF" */
#define GLB_JSON   0x4E4F534Au     /* "JSON" */
#define GLB_BIN    0x004E4942u     /* "BIN\0" */

/* What the parts of the writer share. */
typedef struct glb {
  const lsys_mesh *m;
  const lsys_material *pal;
  size_t npal;
  const char *path;
  lsys_groups g;
  size_t nv, ntri, nl;            /* vertices written (none without triangles), triangles,
                                     segments */
  size_t vbytes, ibytes, lbytes;  /* the BIN chunk's vertices, indices and segments */
  size_t binlen;                  /* the BIN chunk's length, images included */
  /* materials and textures */
  uint32_t *pmat;                 /* slot -> glTF material of its plain material */
  uint32_t *rmat;                 /* run -> glTF material */
  uint32_t *gtex;                 /* texture index -> glTF texture (UINT32_MAX: unused) */
  unsigned char **img;            /* per glTF texture: the PNG bytes */
  size_t *imglen;
  uint16_t *imgtex;               /* per glTF texture: the texture index */
  size_t nimg;
  int unlit;                      /* some material is unlit (a decal texture) */
} glb;

static int nomem (const glb *G, lsys_error *e) {
  return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory",
                       G->path);
}

static int toolarge (const glb *G, lsys_error *e) {
  return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                       "cannot write '%s': mesh too large for glTF binary (4 GiB)", G->path);
}

/* ------------------------------------------------------------------ */
/* JSON text                                                            */
/* ------------------------------------------------------------------ */

/* A growable text buffer for the JSON chunk; 'err' sticks after a failure. */
typedef struct jbuf {
  char *p;
  size_t n, cap;
  int err;
} jbuf;

static char *jroom (jbuf *j, size_t k) {
  if (j->err) return NULL;
  if (lsys_grow((void **)&j->p, &j->cap, j->n + k + 1, 1) != LSYS_OK) {
    j->err = 1;
    return NULL;
  }
  return j->p + j->n;
}

static void jadd (jbuf *j, const char *fmt, ...) {
  va_list ap;
  char *s;
  int n;
  va_start(ap, fmt);
  n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (n < 0 || (s = jroom(j, (size_t)n)) == NULL) { j->err = 1; return; }
  va_start(ap, fmt);
  vsnprintf(s, (size_t)n + 1, fmt, ap);
  va_end(ap);
  j->n += (size_t)n;
}

static void jnum (jbuf *j, float x) {
  char *s = jroom(j, 16);
  if (s != NULL) j->n = (size_t)(lsys_putfloat(s, x) - j->p);
}

/* 'head' (the key with its quotes and colon), then the array of 'v'. */
static void jvec (jbuf *j, const char *head, const float *v, int n) {
  int k;
  jadd(j, "%s[", head);
  for (k = 0; k < n; k++) {
    if (k > 0) jadd(j, ",");
    jnum(j, v[k]);
  }
  jadd(j, "]");
}

/* ------------------------------------------------------------------ */
/* Materials and textures                                               */
/* ------------------------------------------------------------------ */

/* Numbers the glTF materials: per slot its plain one (if used), then one
** per texture run; and the glTF textures, one per texture used. */
static int glbmaterials (glb *G, lsys_error *e) {
  const lsys_groups *g = &G->g;
  size_t k, r, nmat = 0;
  G->pmat = (uint32_t *)LSYS_MALLOC(g->nmat * sizeof *G->pmat);
  G->rmat = (uint32_t *)LSYS_MALLOC((g->nruns ? g->nruns : 1) * sizeof *G->rmat);
  G->gtex = (uint32_t *)LSYS_MALLOC((g->ntex + 1) * sizeof *G->gtex);
  G->img = (unsigned char **)LSYS_MALLOC((g->ntex + 1) * sizeof *G->img);
  G->imglen = (size_t *)LSYS_MALLOC((g->ntex + 1) * sizeof *G->imglen);
  G->imgtex = (uint16_t *)LSYS_MALLOC((g->ntex + 1) * sizeof *G->imgtex);
  if (G->pmat == NULL || G->rmat == NULL || G->gtex == NULL || G->img == NULL ||
      G->imglen == NULL || G->imgtex == NULL)
    return nomem(G, e);
  for (k = 0; k <= g->ntex; k++) G->gtex[k] = UINT32_MAX;
  for (k = 0, r = 0; k < g->nmat; k++) {
    G->pmat[k] = plainused(g, k, r < g->nruns ? &g->runs[r] : NULL) ? (uint32_t)nmat++ : 0;
    for (; r < g->nruns && g->runs[r].slot == k; r++) {
      unsigned t = g->runs[r].tex;
      G->rmat[r] = t == 0 ? G->pmat[k] : (uint32_t)nmat++;
      if (t > 0 && g->tex[t - 1]->mode == LSYS_TEX_DECAL) G->unlit = 1;
      if (t > 0 && G->gtex[t] == UINT32_MAX) {
        G->gtex[t] = (uint32_t)G->nimg;
        G->imgtex[G->nimg] = (uint16_t)t;
        G->img[G->nimg] = NULL;
        G->nimg++;
      }
    }
  }
  return LSYS_OK;
}

/* Reads the whole file 'name' (a texture) into a new block; LSYS_OK, or an
** error naming the .glb being written and the file. Refuses what is not a
** regular PNG file (it may have changed since it was loaded) or is too large
** for glTF binary. */
static int slurpimage (const char *name, unsigned char **data, size_t *len,
                       const char *path, lsys_error *e) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  lsys_error re;
  size_t n = 0;
  unsigned char *p = (unsigned char *)lsys_readfile(name, (size_t)UINT32_MAX / 2, &n, &re);
  *data = NULL;
  if (p == NULL && re.code == LSYS_ENOMEM)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if (p == NULL) {                   /* re.msg: "cannot open 'name': reason" */
    const char *why = strstr(re.msg, "': ");
    return lsys_seterror(e, re.code, (size_t)-1, "cannot write '%s': cannot read texture "
                         "'%s': %s", path, name, why != NULL ? why + 3 : re.msg);
  }
  if (n < 8 || memcmp(p, sig, 8) != 0) {
    LSYS_FREE(p);
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot write '%s': texture '%s' is no "
                         "longer a PNG file", path, name);
  }
  *data = p;
  *len = n;
  return LSYS_OK;
}

/* Reads the images now (their sizes go into the JSON) and adds them to
** binlen. On failure, nimg counts the images to free. */
static int glbimages (glb *G, lsys_error *e) {
  size_t i, n = G->nimg;
  for (i = 0; i < n; i++) {
    int st = slurpimage(G->g.tex[G->imgtex[i] - 1]->path, &G->img[i], &G->imglen[i], G->path,
                        e);
    if (st != LSYS_OK) {
      G->nimg = i;
      return st;
    }
    if (G->imglen[i] > UINT32_MAX - 1024 - G->binlen) {
      G->nimg = i + 1;
      return toolarge(G, e);
    }
    G->binlen += (G->imglen[i] + 3) & ~(size_t)3;
  }
  return LSYS_OK;
}

/*
** Material mapping. The base colour is the diffuse colour with its alpha
** (alphaMode BLEND below 1); the emission becomes emissiveFactor. Both are
** linear in glTF and display (sRGB) values in the palette: the RGB goes
** through the sRGB transfer function (tolinear), alpha as it is. A texture
** image is embedded as it is: glTF decodes baseColorTexture as sRGB, as the
** renderer shows it. A Phong
** exponent s corresponds to a microfacet distribution of width
** alpha = sqrt(2 / (s + 2)) (the usual Blinn-Phong/Beckmann match), and
** glTF's roughness is sqrt(alpha): roughness = (2 / (s + 2))^(1/4). That
** gives 1 for s = 0, which looks chalky next to the cpfg rendering, so the
** result is capped at 0.8: plain colours (s = 0) get 0.8, s = 128 gives 0.35.
** metallicFactor is 0: L-system materials are dielectric.
*/
static void jmaterial (jbuf *j, const lsys_material *mt, size_t k, int twosided,
                       const lsys_texture *tx, unsigned t, uint32_t gtex, int first) {
  float c[4], em[3], s = fin(mt->shininess), r;
  int i, decal = tx != NULL && tx->mode == LSYS_TEX_DECAL;
  for (i = 0; i < 3; i++) c[i] = tolinear(mt->diffuse[i]);     /* glTF factors are linear */
  c[3] = lsys_unit(mt->diffuse[3]);                             /* alpha is not encoded */
  for (i = 0; i < 3; i++) em[i] = tolinear(mt->emission[i]);
  if (decal) c[0] = c[1] = c[2] = 1;
  if (s < 0) s = 0;
  r = (float)pow(2.0 / (s + 2.0), 0.25);
  if (r > 0.8f) r = 0.8f;
  jadd(j, "%s{\"name\":\"m%zu", first ? "" : ",", k);
  if (tx != NULL) jadd(j, "_t%u", t);
  jadd(j, "\",\"pbrMetallicRoughness\":{");
  jvec(j, "\"baseColorFactor\":", c, 4);
  if (tx != NULL) jadd(j, ",\"baseColorTexture\":{\"index\":%lu}", (unsigned long)gtex);
  jadd(j, ",\"metallicFactor\":0,\"roughnessFactor\":");
  jnum(j, r);
  jadd(j, "}");
  if (em[0] > 0 || em[1] > 0 || em[2] > 0) jvec(j, ",\"emissiveFactor\":", em, 3);
  if (c[3] < 1) jadd(j, ",\"alphaMode\":\"BLEND\"");
  else if (tx != NULL && !decal && lsys_texture_hasalpha(tx))
    jadd(j, ",\"alphaMode\":\"MASK\"");     /* cut at alpha 1/2, as the renderer does */
  if (twosided) jadd(j, ",\"doubleSided\":true");
  if (decal) jadd(j, ",\"extensions\":{\"KHR_materials_unlit\":{}}");
  jadd(j, "}");
}

/* The materials, in the order glbmaterials numbered them. */
static void jmaterials (jbuf *j, const glb *G) {
  const lsys_groups *g = &G->g;
  size_t k, r;
  int first = 1;
  jadd(j, "\"materials\":[");
  for (k = 0, r = 0; k < g->nmat; k++) {
    const lsys_material *mt = lsys_slotmaterial(G->pal, G->npal, k);
    const lsys_run *fr = r < g->nruns && g->runs[r].slot == k ? &g->runs[r] : NULL;
    if (plainused(g, k, fr)) {
      jmaterial(j, mt, k, fr != NULL && fr->tex == 0 && fr->twosided, NULL, 0, 0, first);
      first = 0;
    }
    for (; r < g->nruns && g->runs[r].slot == k; r++) {
      unsigned t = g->runs[r].tex;
      if (t == 0) continue;
      jmaterial(j, mt, k, g->runs[r].twosided, g->tex[t - 1], t, G->gtex[t], first);
      first = 0;
    }
  }
  jadd(j, "],");
}

/* The textures, their samplers and their images (the buffer views after
** those of the geometry). */
static void jtextures (jbuf *j, const glb *G) {
  size_t i, view0 = (G->ntri ? 2 : 0) + (G->nl ? 1 : 0);
  if (G->nimg == 0) return;
  jadd(j, "\"textures\":[");
  for (i = 0; i < G->nimg; i++)
    jadd(j, "%s{\"sampler\":%zu,\"source\":%zu}", i ? "," : "", i, i);
  jadd(j, "],\"samplers\":[");
  for (i = 0; i < G->nimg; i++) {
    const lsys_texture *tx = G->g.tex[G->imgtex[i] - 1];
    jadd(j, "%s{\"magFilter\":%d,\"minFilter\":%d,\"wrapS\":10497,\"wrapT\":10497}",
         i ? "," : "", tx->mag_linear ? 9729 : 9728, tx->min_linear ? 9729 : 9728);
  }
  jadd(j, "],\"images\":[");
  for (i = 0; i < G->nimg; i++)
    jadd(j, "%s{\"bufferView\":%zu,\"mimeType\":\"image/png\"}", i ? "," : "", view0 + i);
  jadd(j, "],");
}

/* ------------------------------------------------------------------ */
/* The JSON chunk                                                       */
/* ------------------------------------------------------------------ */

/* The mesh: per run a TRIANGLES primitive, per slot with segments a LINES
** primitive. Accessors 0-2 are the vertex attributes, then one per
** primitive (jaccessors). */
static void jmesh (jbuf *j, const glb *G) {
  const lsys_groups *g = &G->g;
  size_t k, r, nacc = G->ntri ? 3 : 0;
  int first = 1;
  jadd(j, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"lsys\"}],");
  jadd(j, "\"meshes\":[{\"primitives\":[");
  for (r = 0; r < g->nruns; r++) {
    jadd(j, "%s{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
         "\"indices\":%zu,\"material\":%lu,\"mode\":4}", first ? "" : ",", nacc++,
         (unsigned long)G->rmat[r]);
    first = 0;
  }
  for (k = 0; k < g->nmat; k++)
    if (g->lfirst[k + 1] > g->lfirst[k]) {
      jadd(j, "%s{\"attributes\":{\"POSITION\":%zu},\"material\":%lu,\"mode\":1}",
           first ? "" : ",", nacc++, (unsigned long)G->pmat[k]);
      first = 0;
    }
  jadd(j, "]}],");
}

/* The buffer and its views: vertices and indices (when there are
** triangles), segment end points (when there are segments), images. */
static void jviews (jbuf *j, const glb *G) {
  size_t i, off = G->vbytes + G->ibytes + G->lbytes;
  jadd(j, "\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":[", G->binlen);
  if (G->ntri) {
    jadd(j, "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"byteStride\":32,"
         "\"target\":34962},", G->vbytes);
    jadd(j, "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}",
         G->vbytes, G->ibytes);
  }
  if (G->nl)
    jadd(j, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":12,"
         "\"target\":34962}", G->ntri ? "," : "", G->vbytes + G->ibytes, G->lbytes);
  for (i = 0; i < G->nimg; i++) {
    jadd(j, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", off, G->imglen[i]);
    off += (G->imglen[i] + 3) & ~(size_t)3;
  }
  jadd(j, "],");
}

/* Bounds of 'n' points (3 floats each, 'stride' floats apart), as written. */
static void minmax (const float *p, size_t n, size_t stride, float lo[3], float hi[3]) {
  size_t i;
  int k;
  for (k = 0; k < 3; k++) { lo[k] = HUGE_VALF; hi[k] = -HUGE_VALF; }
  for (i = 0; i < n; i++, p += stride)
    for (k = 0; k < 3; k++) {
      float x = fin(p[k]);
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
}

/* The accessors of the triangles: the three vertex attributes, then the
** indices of each run. */
static void jtriaccessors (jbuf *j, const glb *G) {
  const lsys_groups *g = &G->g;
  float lo[3], hi[3];
  size_t r, nv = G->nv;
  minmax(G->m->pos, nv, 3, lo, hi);
  jadd(j, "{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":%zu,"
       "\"type\":\"VEC3\"", nv);
  jvec(j, ",\"min\":", lo, 3);
  jvec(j, ",\"max\":", hi, 3);
  jadd(j, "},{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":%zu,"
       "\"type\":\"VEC3\"},{\"bufferView\":0,\"byteOffset\":24,\"componentType\":5126,"
       "\"count\":%zu,\"type\":\"VEC2\"}", nv, nv);
  for (r = 0; r < g->nruns; r++)
    jadd(j, ",{\"bufferView\":1,\"byteOffset\":%zu,\"componentType\":5125,"
         "\"count\":%zu,\"type\":\"SCALAR\"}", 12 * g->runs[r].first,
         3 * (g->runs[r].end - g->runs[r].first));
}

/* The accessors: those of the triangles, then one per slot with segments,
** over its run of end points. */
static void jaccessors (jbuf *j, const glb *G) {
  const lsys_groups *g = &G->g;
  size_t k, i, lview = G->ntri ? 2 : 0;
  int first = 1;
  jadd(j, "\"accessors\":[");
  if (G->ntri) {
    jtriaccessors(j, G);
    first = 0;
  }
  for (k = 0; k < g->nmat; k++) {
    size_t a = g->lfirst[k], b = g->lfirst[k + 1];
    float lo[3], hi[3];
    if (b == a) continue;
    lo[0] = lo[1] = lo[2] = HUGE_VALF;
    hi[0] = hi[1] = hi[2] = -HUGE_VALF;
    for (i = a; i < b; i++) {
      float l2[3], h2[3];
      int c;
      minmax(G->m->lpos + 6 * (size_t)g->lord[i], 2, 3, l2, h2);
      for (c = 0; c < 3; c++) {
        if (l2[c] < lo[c]) lo[c] = l2[c];
        if (h2[c] > hi[c]) hi[c] = h2[c];
      }
    }
    jadd(j, "%s{\"bufferView\":%zu,\"byteOffset\":%zu,\"componentType\":5126,"
         "\"count\":%zu,\"type\":\"VEC3\"", first ? "" : ",", lview, 24 * a, 2 * (b - a));
    jvec(j, ",\"min\":", lo, 3);
    jvec(j, ",\"max\":", hi, 3);
    jadd(j, "}");
    first = 0;
  }
  jadd(j, "]");
}

/* The whole JSON chunk into 'j', padded with spaces to 4 bytes. */
static void jchunk (jbuf *j, const glb *G) {
  jadd(j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"lsys\"},");
  if (G->unlit) jadd(j, "\"extensionsUsed\":[\"KHR_materials_unlit\"],");
  jadd(j, "\"scene\":0,");
  if (G->ntri == 0 && G->nl == 0) jadd(j, "\"scenes\":[{}]}");
  else {
    jmesh(j, G);
    jmaterials(j, G);
    jtextures(j, G);
    jviews(j, G);
    jaccessors(j, G);
    jadd(j, "}");
  }
  while (!j->err && j->n % 4 != 0) jadd(j, " ");
}

/* ------------------------------------------------------------------ */
/* The BIN chunk                                                        */
/* ------------------------------------------------------------------ */

/* The mesh vertices interleaved: position, unit normal (+z when it has no
** direction), uv with v turned downwards. */
static void binvertices (lsys_writer *w, const lsys_mesh *m, size_t nv) {
  size_t i;
  for (i = 0; i < nv; i++) {
    const float *n = m->nrm + 3 * i;
    double x = fin(n[0]), y = fin(n[1]), z = fin(n[2]), len = sqrt(x * x + y * y + z * z);
    unsigned char *p = wroom(w, 32);
    int c;
    for (c = 0; c < 3; c++) p = putf32(p, fin(m->pos[3 * i + c]));
    if (len > 1e-30 && isfinite(len)) {
      p = putf32(p, (float)(x / len));
      p = putf32(p, (float)(y / len));
      p = putf32(p, (float)(z / len));
    }
    else {
      p = putf32(p, 0.0f); p = putf32(p, 0.0f); p = putf32(p, 1.0f);
    }
    p = putf32(p, fin(m->uv[2 * i]));
    p = putf32(p, fin(1.0f - fin(m->uv[2 * i + 1])));
    wdone(w, p);
  }
}

/* The BIN chunk after its vertices: the indices in the order of the runs,
** the segment end points in material order, the images. */
static void binrest (lsys_writer *w, const glb *G) {
  static const unsigned char zero[4] = {0, 0, 0, 0};
  const lsys_mesh *m = G->m;
  size_t i;
  for (i = 0; i < G->ntri; i++) {
    const uint32_t *t = m->tri + 3 * (size_t)G->g.tord[i];
    unsigned char *p = wroom(w, 12);
    p = put32(p, t[0]); p = put32(p, t[1]); p = put32(p, t[2]);
    wdone(w, p);
  }
  for (i = 0; i < G->nl; i++) {
    const float *q = m->lpos + 6 * (size_t)G->g.lord[i];
    unsigned char *p = wroom(w, 24);
    int c;
    for (c = 0; c < 6; c++) p = putf32(p, fin(q[c]));
    wdone(w, p);
  }
  for (i = 0; i < G->nimg; i++) {
    lsys_wbytes(w, G->img[i], G->imglen[i]);
    lsys_wbytes(w, zero, (4 - G->imglen[i] % 4) % 4);
  }
}

/* ------------------------------------------------------------------ */
/* The file                                                             */
/* ------------------------------------------------------------------ */

/* The 12-byte header, the JSON chunk (its 'jlen' bytes in 'json') and the
** BIN chunk (none when empty). */
static int glbwrite (const glb *G, const char *json, size_t jlen, lsys_error *e) {
  size_t total = 12 + 8 + jlen + (G->binlen ? 8 + G->binlen : 0);
  unsigned char hdr[28], *p;
  lsys_writer *w;
  int st;
  if (jlen > UINT32_MAX - 1024 || total > UINT32_MAX) return toolarge(G, e);
  if ((st = lsys_wopen(&w, G->path, e)) != LSYS_OK) return st;
  p = put32(hdr, GLB_MAGIC);
  p = put32(p, 2);
  p = put32(p, (uint32_t)total);
  p = put32(p, (uint32_t)jlen);
  p = put32(p, GLB_JSON);
  lsys_wbytes(w, hdr, (size_t)(p - hdr));
  lsys_wbytes(w, json, jlen);
  if (G->binlen) {
    p = put32(hdr, (uint32_t)G->binlen);
    p = put32(p, GLB_BIN);
    lsys_wbytes(w, hdr, (size_t)(p - hdr));
  }
  binvertices(w, G->m, G->nv);
  binrest(w, G);
  return lsys_wcommit(w, e);
}

static void glbfree (glb *G) {
  size_t i;
  for (i = 0; G->img != NULL && i < G->nimg; i++) LSYS_FREE(G->img[i]);
  LSYS_FREE(G->img); LSYS_FREE(G->imglen); LSYS_FREE(G->imgtex);
  LSYS_FREE(G->pmat); LSYS_FREE(G->rmat); LSYS_FREE(G->gtex);
  lsys_freegroups(&G->g);
}

int lsys_mesh_save_glb (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e) {
  glb G = {0};
  jbuf j = {0};
  int st = lsys_checkmesh(m, path, e);
  if (st != LSYS_OK) return st;
  G.m = m; G.pal = pal; G.npal = npal; G.path = path;
  G.ntri = m->nt; G.nl = m->nl; G.nv = G.ntri ? m->nv : 0;
  G.vbytes = 32 * G.nv; G.ibytes = 12 * G.ntri; G.lbytes = 24 * G.nl;
  if (G.nv > UINT32_MAX / 32 || G.ntri > UINT32_MAX / 12 || G.nl > UINT32_MAX / 24 ||
      (uint64_t)G.vbytes + G.ibytes + G.lbytes > UINT32_MAX - 1024)
    return toolarge(&G, e);
  G.binlen = G.vbytes + G.ibytes + G.lbytes;
  st = lsys_groupmesh(&G.g, m, npal, tex, ntex, path, e);
  if (st != LSYS_OK) return st;
  st = glbmaterials(&G, e);
  if (st == LSYS_OK) st = glbimages(&G, e);
  if (st == LSYS_OK) {
    jchunk(&j, &G);
    st = j.err ? nomem(&G, e) : glbwrite(&G, j.p, j.n, e);
  }
  LSYS_FREE(j.p);
  glbfree(&G);
  return st;
}
