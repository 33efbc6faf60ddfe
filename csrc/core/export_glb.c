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
** Instancing (a population, lsys_export_glb_instanced): the meshes are
** the scene's parts (its prototypes) that have instances, each with its own
** vertex accessors over its range of the shared vertex view and its own
** index and line accessors over its part of each run (the sorts are
** stable, so a part's triangles are one stretch of each run), indices
** counted from the part's first vertex; one node per such mesh carries
** EXT_mesh_gpu_instancing, whose TRANSLATION, ROTATION and SCALE accessors
** read a view of the instances' T R S after the segments (40 bytes an
** instance, by part). The extension is in extensionsUsed and, as it
** recommends (the file has no fallback), in extensionsRequired.
**
** Textures: each one used gets an image (a PNG file's bytes embedded, an SGI
** image encoded as PNG from its pixels), a sampler (its filters, REPEAT
** wrapping) and a texture; each (slot, texture) pair gets a material whose baseColorTexture is it: modulate
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
#include "pngio.h"
#include "population.h"

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
  /* the meshes: the scene's parts with instancing, else one, 'whole' */
  const lsys_part *parts;
  size_t nparts;
  lsys_part whole;
  const lsys_instance *inst;      /* instancing: the instances (NULL: one plain node) */
  size_t ninst;
  size_t *ifirst;                 /* nparts + 1 offsets into iord: the instances by part */
  uint32_t *iord;
  size_t nbytes;                  /* the BIN chunk's instance data */
} glb;

/* Whether part p is written (a mesh and a node): it draws something and,
** with instancing, has instances. */
static int partused (const glb *G, size_t p) {
  const lsys_part *q = &G->parts[p];
  if (q->nt == 0 && q->nl == 0) return 0;
  return G->inst == NULL || G->ifirst[p + 1] > G->ifirst[p];
}

/* The first i in [lo, hi) with a[i] >= x (a ascending there), or hi. */
static size_t lower (const uint32_t *a, size_t lo, size_t hi, size_t x) {
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (a[mid] < x) lo = mid + 1; else hi = mid;
  }
  return lo;
}

/* The stretch [*a, *b) of tord of run r that is part p's triangles. */
static void runpart (const glb *G, size_t r, const lsys_part *p, size_t *a, size_t *b) {
  const lsys_run *u = &G->g.runs[r];
  *a = lower(G->g.tord, u->first, u->end, p->t0);
  *b = lower(G->g.tord, *a, u->end, p->t0 + p->nt);
}

/* The stretch [*a, *b) of lord of slot k that is part p's segments. */
static void slotpart (const glb *G, size_t k, const lsys_part *p, size_t *a, size_t *b) {
  *a = lower(G->g.lord, G->g.lfirst[k], G->g.lfirst[k + 1], p->l0);
  *b = lower(G->g.lord, *a, G->g.lfirst[k + 1], p->l0 + p->nl);
}

/* The number of accessors of part p: its vertices (when it has triangles),
** one per stretch of a run and of a slot's segments, and T, R, S. */
static size_t naccessors (const glb *G, size_t p) {
  const lsys_part *q = &G->parts[p];
  size_t n = q->nt > 0 ? 3 : 0, r, k, a, b;
  for (r = 0; r < G->g.nruns; r++) {
    runpart(G, r, q, &a, &b);
    n += b > a;
  }
  for (k = 0; k < G->g.nmat; k++) {
    slotpart(G, k, q, &a, &b);
    n += b > a;
  }
  return n + (G->inst != NULL ? 3 : 0);
}

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
  if (lsys_common_grow((void **)&j->p, &j->cap, j->n + k + 1, 1) != LSYS_OK) {
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
  if (s != NULL) j->n = (size_t)(lsys_export_putfloat(s, x) - j->p);
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

/* The PNG bytes of texture 't' into a new block; LSYS_OK, or an error naming
** the .glb being written and the file. A PNG file is embedded as it is; an
** SGI image (glTF has no such type) is encoded as PNG from the pixels read
** when the texture was loaded. Refuses a file that is now neither (it may
** have changed since it was loaded) or is too large for glTF binary. */
static int slurpimage (const lsys_texture *t, unsigned char **data, size_t *len,
                       const char *path, lsys_error *e) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const char *name = t->path;
  lsys_error re;
  size_t n = 0;
  unsigned char *p = (unsigned char *)lsys_common_readfile(name, (size_t)UINT32_MAX / 2, &n, &re);
  *data = NULL;
  if (p == NULL && re.code == LSYS_ENOMEM)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if (p == NULL) {                   /* re.msg: "cannot open 'name': reason" */
    const char *why = strstr(re.msg, "': ");
    return lsys_seterror(e, re.code, (size_t)-1, "cannot write '%s': cannot read texture "
                         "'%s': %s", path, name, why != NULL ? why + 3 : re.msg);
  }
  if (n >= 2 && p[0] == 0x01 && p[1] == 0xda && t->rgba != NULL) {   /* SGI's magic, 474 */
    int st;
    LSYS_FREE(p);
    st = lsys_pngio_encode(t->rgba, t->w, t->h, lsys_texture_hasalpha(t), data, len, &re);
    if (st != LSYS_OK)
      return lsys_seterror(e, st, (size_t)-1, "cannot write '%s': texture '%s' as PNG: %s",
                           path, name, re.msg);
    return LSYS_OK;
  }
  if (n < 8 || memcmp(p, sig, 8) != 0) {
    LSYS_FREE(p);
    return lsys_seterror(e, LSYS_ESYNTAX, (size_t)-1, "cannot write '%s': texture '%s' is no "
                         "longer a PNG or SGI image", path, name);
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
    int st = slurpimage(G->g.tex[G->imgtex[i] - 1], &G->img[i], &G->imglen[i], G->path, e);
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
    const lsys_material *mt = lsys_export_slotmaterial(G->pal, G->npal, k);
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
  size_t i, view0 = (G->ntri ? 2 : 0) + (G->nl ? 1 : 0) + (G->nbytes ? 1 : 0);
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

/* The primitives of part p: per stretch of a run a TRIANGLES primitive,
** per stretch of a slot's segments a LINES primitive. Its accessors are
** numbered from *nacc on, in jpartaccessors' order; *nacc ends past them. */
static void jprimitives (jbuf *j, const glb *G, size_t p, size_t *nacc) {
  const lsys_groups *g = &G->g;
  const lsys_part *q = &G->parts[p];
  size_t k, r, a, b, v = *nacc;
  int first = 1;
  if (q->nt > 0) *nacc += 3;
  for (r = 0; r < g->nruns; r++) {
    runpart(G, r, q, &a, &b);
    if (b == a) continue;
    jadd(j, "%s{\"attributes\":{\"POSITION\":%zu,\"NORMAL\":%zu,\"TEXCOORD_0\":%zu},"
         "\"indices\":%zu,\"material\":%lu,\"mode\":4}", first ? "" : ",", v, v + 1, v + 2,
         (*nacc)++, (unsigned long)G->rmat[r]);
    first = 0;
  }
  for (k = 0; k < g->nmat; k++) {
    slotpart(G, k, q, &a, &b);
    if (b == a) continue;
    jadd(j, "%s{\"attributes\":{\"POSITION\":%zu},\"material\":%lu,\"mode\":1}",
         first ? "" : ",", (*nacc)++, (unsigned long)G->pmat[k]);
    first = 0;
  }
  if (G->inst != NULL) *nacc += 3;
}

/* The scene, its nodes and meshes: one plain node and mesh, or with
** instancing a node and a mesh per part used, the node placing the mesh's
** instances (its last three accessors). */
static void jmesh (jbuf *j, const glb *G) {
  size_t p, n = 0, nacc = 0;
  jadd(j, "\"scenes\":[{\"nodes\":[");
  for (p = 0; p < G->nparts; p++)
    if (partused(G, p)) {
      jadd(j, "%s%zu", n ? "," : "", n);
      n++;
    }
  jadd(j, "]}],\"nodes\":[");
  if (G->inst == NULL) jadd(j, "{\"mesh\":0,\"name\":\"lsys\"}");
  for (p = 0, n = 0; G->inst != NULL && p < G->nparts; p++) {
    if (!partused(G, p)) continue;
    nacc += naccessors(G, p);
    jadd(j, "%s{\"mesh\":%zu,\"name\":\"prototype %zu\",\"extensions\":"
         "{\"EXT_mesh_gpu_instancing\":{\"attributes\":{\"TRANSLATION\":%zu,"
         "\"ROTATION\":%zu,\"SCALE\":%zu}}}}", n ? "," : "", n, p + 1, nacc - 3, nacc - 2,
         nacc - 1);
    n++;
  }
  jadd(j, "],\"meshes\":[");
  for (p = 0, n = 0, nacc = 0; p < G->nparts; p++) {
    if (!partused(G, p)) continue;
    jadd(j, "%s{\"primitives\":[", n++ ? "," : "");
    jprimitives(j, G, p, &nacc);
    jadd(j, "]}");
  }
  jadd(j, "],");
}

/* The buffer and its views: vertices and indices (when there are
** triangles), segment end points (when there are segments), instances,
** images. */
static void jviews (jbuf *j, const glb *G) {
  size_t i, off = G->vbytes + G->ibytes + G->lbytes + G->nbytes;
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
  if (G->nbytes)
    jadd(j, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}",
         G->ntri || G->nl ? "," : "", G->vbytes + G->ibytes + G->lbytes, G->nbytes);
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

/* Bounds of the end points of segments lord[a .. b). */
static void lineminmax (const glb *G, size_t a, size_t b, float lo[3], float hi[3]) {
  size_t i;
  int c;
  lo[0] = lo[1] = lo[2] = HUGE_VALF;
  hi[0] = hi[1] = hi[2] = -HUGE_VALF;
  for (i = a; i < b; i++) {
    float l2[3], h2[3];
    minmax(G->m->lpos + 6 * (size_t)G->g.lord[i], 2, 3, l2, h2);
    for (c = 0; c < 3; c++) {
      if (l2[c] < lo[c]) lo[c] = l2[c];
      if (h2[c] > hi[c]) hi[c] = h2[c];
    }
  }
}

/* The three vertex attributes of part p: its range of the vertex view. */
static void jvertexaccessors (jbuf *j, const glb *G, const lsys_part *q, const char *sep) {
  float lo[3], hi[3];
  size_t off = 32 * q->v0;
  minmax(G->m->pos + 3 * q->v0, q->nv, 3, lo, hi);
  jadd(j, "%s{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%zu,"
       "\"type\":\"VEC3\"", sep, off, q->nv);
  jvec(j, ",\"min\":", lo, 3);
  jvec(j, ",\"max\":", hi, 3);
  jadd(j, "},{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,\"count\":%zu,"
       "\"type\":\"VEC3\"},{\"bufferView\":0,\"byteOffset\":%zu,\"componentType\":5126,"
       "\"count\":%zu,\"type\":\"VEC2\"}", off + 12, q->nv, off + 24, q->nv);
}

/* The accessors of part p, in the order jprimitives numbers them: its
** vertex attributes (when it has triangles), the indices of each stretch of
** a run, the end points of each stretch of a slot's segments, and with
** instancing the TRANSLATION, ROTATION and SCALE of its instances (their
** stretch of the instance view: n translations, n rotations, n scales). */
static void jpartaccessors (jbuf *j, const glb *G, size_t p, int *first) {
  const lsys_groups *g = &G->g;
  const lsys_part *q = &G->parts[p];
  size_t r, k, a, b, lview = G->ntri ? 2 : 0;
  if (q->nt > 0) {
    jvertexaccessors(j, G, q, *first ? "" : ",");
    *first = 0;
  }
  for (r = 0; r < g->nruns; r++) {
    runpart(G, r, q, &a, &b);
    if (b == a) continue;
    jadd(j, "%s{\"bufferView\":1,\"byteOffset\":%zu,\"componentType\":5125,"
         "\"count\":%zu,\"type\":\"SCALAR\"}", *first ? "" : ",", 12 * a, 3 * (b - a));
    *first = 0;
  }
  for (k = 0; k < g->nmat; k++) {
    float lo[3], hi[3];
    slotpart(G, k, q, &a, &b);
    if (b == a) continue;
    lineminmax(G, a, b, lo, hi);
    jadd(j, "%s{\"bufferView\":%zu,\"byteOffset\":%zu,\"componentType\":5126,"
         "\"count\":%zu,\"type\":\"VEC3\"", *first ? "" : ",", lview, 24 * a, 2 * (b - a));
    jvec(j, ",\"min\":", lo, 3);
    jvec(j, ",\"max\":", hi, 3);
    jadd(j, "}");
    *first = 0;
  }
  if (G->inst != NULL) {
    size_t n = G->ifirst[p + 1] - G->ifirst[p], off = 40 * G->ifirst[p];
    size_t iview = lview + (G->nl ? 1 : 0);
    jadd(j, "%s{\"bufferView\":%zu,\"byteOffset\":%zu,\"componentType\":5126,"
         "\"count\":%zu,\"type\":\"VEC3\"},{\"bufferView\":%zu,\"byteOffset\":%zu,"
         "\"componentType\":5126,\"count\":%zu,\"type\":\"VEC4\"},{\"bufferView\":%zu,"
         "\"byteOffset\":%zu,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"}",
         *first ? "" : ",", iview, off, n, iview, off + 12 * n, n, iview, off + 28 * n, n);
    *first = 0;
  }
}

/* The accessors, part by part. */
static void jaccessors (jbuf *j, const glb *G) {
  size_t p;
  int first = 1;
  jadd(j, "\"accessors\":[");
  for (p = 0; p < G->nparts; p++)
    if (partused(G, p)) jpartaccessors(j, G, p, &first);
  jadd(j, "]");
}

/* The whole JSON chunk into 'j', padded with spaces to 4 bytes. */
static void jchunk (jbuf *j, const glb *G) {
  jadd(j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"lsys\"},");
  if (G->unlit || G->inst != NULL) {
    jadd(j, "\"extensionsUsed\":[");
    if (G->unlit) jadd(j, "\"KHR_materials_unlit\"");
    if (G->inst != NULL) jadd(j, "%s\"EXT_mesh_gpu_instancing\"", G->unlit ? "," : "");
    jadd(j, "],");
  }
  if (G->inst != NULL) jadd(j, "\"extensionsRequired\":[\"EXT_mesh_gpu_instancing\"],");
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

/* The first vertex of the part that holds triangle t (0 without instancing:
** indices are the mesh's). */
static uint32_t vbase (const glb *G, size_t t) {
  size_t lo = 0, hi = G->nparts;
  if (G->inst == NULL) return 0;
  while (lo < hi) {               /* the last part with t0 <= t */
    size_t mid = lo + (hi - lo) / 2;
    if (G->parts[mid].t0 <= t) lo = mid + 1; else hi = mid;
  }
  return lo > 0 && t < G->parts[lo - 1].t0 + G->parts[lo - 1].nt
         ? (uint32_t)G->parts[lo - 1].v0 : 0;
}

/* The instances' T R S, part by part: per part its translations, then its
** rotations, then its scales (jpartaccessors). They were checked. */
static void bininstances (lsys_writer *w, const glb *G) {
  size_t p, i;
  int pass, c;
  for (p = 0; p < G->nparts; p++)
    for (pass = 0; pass < 3; pass++)
      for (i = G->ifirst[p]; i < G->ifirst[p + 1]; i++) {
        float t[3], q[4], sc[3];
        const float *v = pass == 0 ? t : pass == 1 ? q : sc;
        unsigned char *b = wroom(w, 16);
        lsys_population_trs(G->inst[G->iord[i]].m, t, q, sc);
        for (c = 0; c < (pass == 1 ? 4 : 3); c++) b = putf32(b, fin(v[c]));
        wdone(w, b);
      }
}

/* The BIN chunk after its vertices: the indices in the order of the runs
** (each counted from its part's first vertex), the segment end points in
** material order, the instances, the images. */
static void binrest (lsys_writer *w, const glb *G) {
  static const unsigned char zero[4] = {0, 0, 0, 0};
  const lsys_mesh *m = G->m;
  size_t i;
  for (i = 0; i < G->ntri; i++) {
    const uint32_t *t = m->tri + 3 * (size_t)G->g.tord[i];
    uint32_t v0 = vbase(G, G->g.tord[i]);
    unsigned char *p = wroom(w, 12);
    p = put32(p, t[0] - v0); p = put32(p, t[1] - v0); p = put32(p, t[2] - v0);
    wdone(w, p);
  }
  for (i = 0; i < G->nl; i++) {
    const float *q = m->lpos + 6 * (size_t)G->g.lord[i];
    unsigned char *p = wroom(w, 24);
    int c;
    for (c = 0; c < 6; c++) p = putf32(p, fin(q[c]));
    wdone(w, p);
  }
  if (G->inst != NULL) bininstances(w, G);
  for (i = 0; i < G->nimg; i++) {
    lsys_export_wbytes(w, G->img[i], G->imglen[i]);
    lsys_export_wbytes(w, zero, (4 - G->imglen[i] % 4) % 4);
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
  if ((st = lsys_export_wopen(&w, G->path, e)) != LSYS_OK) return st;
  p = put32(hdr, GLB_MAGIC);
  p = put32(p, 2);
  p = put32(p, (uint32_t)total);
  p = put32(p, (uint32_t)jlen);
  p = put32(p, GLB_JSON);
  lsys_export_wbytes(w, hdr, (size_t)(p - hdr));
  lsys_export_wbytes(w, json, jlen);
  if (G->binlen) {
    p = put32(hdr, (uint32_t)G->binlen);
    p = put32(p, GLB_BIN);
    lsys_export_wbytes(w, hdr, (size_t)(p - hdr));
  }
  binvertices(w, G->m, G->nv);
  binrest(w, G);
  return lsys_export_wcommit(w, e);
}

static void glbfree (glb *G) {
  size_t i;
  for (i = 0; G->img != NULL && i < G->nimg; i++) LSYS_FREE(G->img[i]);
  LSYS_FREE(G->img); LSYS_FREE(G->imglen); LSYS_FREE(G->imgtex);
  LSYS_FREE(G->pmat); LSYS_FREE(G->rmat); LSYS_FREE(G->gtex);
  LSYS_FREE(G->ifirst); LSYS_FREE(G->iord);
  lsys_export_freegroups(&G->g);
}

/* Writes the file of G (its mesh, palette, path and parts set); frees G. */
static int glbsave (glb *G, const lsys_texture *const *tex, int ntex, lsys_error *e) {
  const lsys_mesh *m = G->m;
  jbuf j = {0};
  int st;
  G->ntri = m->nt; G->nl = m->nl; G->nv = G->ntri ? m->nv : 0;
  G->vbytes = 32 * G->nv; G->ibytes = 12 * G->ntri; G->lbytes = 24 * G->nl;
  if (G->nv > UINT32_MAX / 32 || G->ntri > UINT32_MAX / 12 || G->nl > UINT32_MAX / 24 ||
      G->ninst > UINT32_MAX / 40 ||
      (uint64_t)G->vbytes + G->ibytes + G->lbytes + G->nbytes > UINT32_MAX - 1024) {
    glbfree(G);
    return toolarge(G, e);
  }
  G->binlen = G->vbytes + G->ibytes + G->lbytes + G->nbytes;
  st = lsys_export_groupmesh(&G->g, m, G->npal, tex, ntex, G->path, e);
  if (st != LSYS_OK) memset(&G->g, 0, sizeof G->g);     /* it freed its arrays */
  if (st == LSYS_OK) st = glbmaterials(G, e);
  if (st == LSYS_OK) st = glbimages(G, e);
  if (st == LSYS_OK) {
    jchunk(&j, G);
    st = j.err ? nomem(G, e) : glbwrite(G, j.p, j.n, e);
  }
  LSYS_FREE(j.p);
  glbfree(G);
  return st;
}

int lsys_export_glb (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                     const lsys_texture *const *tex, int ntex, const char *path,
                     lsys_error *e) {
  glb G = {0};
  int st = lsys_export_checkmesh(m, path, e);
  if (st != LSYS_OK) return st;
  G.m = m; G.pal = pal; G.npal = npal; G.path = path;
  G.whole.nv = m->nv; G.whole.nt = m->nt; G.whole.nl = m->nl;
  G.parts = &G.whole;
  G.nparts = 1;
  return glbsave(&G, tex, ntex, e);
}

/* The instances of s by part into G (a counting sort), each checked to be
** a translation, rotation and positive scale; whether some part is used. */
static int byparts (glb *G, const lsys_scene *s, int *used, lsys_error *e) {
  size_t i, p;
  G->ifirst = (size_t *)LSYS_MALLOC((s->nparts + 1) * sizeof *G->ifirst);
  G->iord = (uint32_t *)LSYS_MALLOC(s->ninst * sizeof *G->iord);
  if (G->ifirst == NULL || G->iord == NULL) return nomem(G, e);
  memset(G->ifirst, 0, (s->nparts + 1) * sizeof *G->ifirst);
  for (i = 0; i < s->ninst; i++) {
    float t[3], q[4], sc[3];
    if (s->inst[i].part >= s->nparts)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': instance %zu has no "
                           "prototype", G->path, i + 1);
    if (!lsys_population_trs(s->inst[i].m, t, q, sc))
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s' with instancing: "
                           "instance %zu is not a translation, rotation and positive scale "
                           "(save with instancing = false)", G->path, i + 1);
    G->ifirst[s->inst[i].part + 1]++;
  }
  for (p = 0; p < s->nparts; p++) G->ifirst[p + 1] += G->ifirst[p];
  for (i = 0; i < s->ninst; i++) G->iord[G->ifirst[s->inst[i].part]++] = (uint32_t)i;
  for (p = s->nparts; p > 0; p--) G->ifirst[p] = G->ifirst[p - 1];
  G->ifirst[0] = 0;
  for (p = 0, *used = 0; p < s->nparts; p++) *used |= partused(G, p);
  return LSYS_OK;
}

int lsys_export_glb_instanced (const lsys_scene *s, const char *path, lsys_error *e) {
  glb G = {0};
  size_t p;
  int st = lsys_export_checkmesh(&s->mesh, path, e), used = 0;
  if (st != LSYS_OK) return st;
  for (p = 0; p < s->nparts; p++) {
    const lsys_part *q = &s->parts[p];
    if (q->v0 + q->nv > s->mesh.nv || q->t0 + q->nt > s->mesh.nt || q->l0 + q->nl > s->mesh.nl)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "cannot write '%s': prototype %zu is "
                           "out of the mesh", path, p + 1);
  }
  G.m = &s->mesh; G.pal = s->pal; G.npal = s->npal; G.path = path;
  G.parts = s->parts; G.nparts = s->nparts;
  G.inst = s->inst; G.ninst = s->ninst; G.nbytes = 40 * s->ninst;
  if ((st = byparts(&G, s, &used, e)) != LSYS_OK || !used) {
    lsys_mesh empty;
    glbfree(&G);
    if (st != LSYS_OK) return st;
    lsys_mesh_init(&empty);
    return lsys_export_glb(&empty, s->pal, s->npal, NULL, 0, path, e);
  }
  return glbsave(&G, s->tex, s->ntex, e);
}
