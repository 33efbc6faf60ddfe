/*
** The one OpenGL drawing path (render.h): fixed-function drawing of a scene
** with vertex arrays. The camera it draws with is plain arithmetic, in
** viewcam.c (lsys_render_camera).
**
** Triangles are grouped by material (a counting sort of the triangle
** indices, once per frame, into a cached array) so that each group sets its
** full material once; the diffuse colour still comes per vertex from a
** colour array, so colour gradients along a surface survive. Groups of
** two-sided vertices are drawn with GL_LIGHT_MODEL_TWO_SIDE; translucent
** materials are drawn last, blended, without writing depth.
**
** Textured triangles (render.h) are grouped again, by texture, after the
** untextured ones: a stable counting sort by material into a scratch array,
** then by texture into the tail of the index array, so that each texture
** is bound once and its triangles come in runs of one material. Without
** textures none of this runs: the untextured path is the one above.
**
** Lines are unlit. Thin ones are GL lines grouped by width (glLineWidth is
** per draw call). Wide ones are expanded on the CPU into bands in clip
** coordinates: GL lines cannot taper, have no round ends, and stop at
** 255 pixels in Mesa, which supersampling reaches quickly.
**
** A scene with instances (a population, scene.h) is sorted and coloured as
** above once per frame, over its prototypes' mesh; then each draw call of a
** group becomes one per instance whose part has triangles (or lines) in it
** -- the group's stretch of that part, under the modelview view * M -- so
** that no vertex is copied per instance. The stretches are found by binary
** search: the sorts are stable and parts are consecutive ranges, so each
** group holds a part's elements together, parts in order. Fixed-function
** GL transforms normals by the inverse transpose of the modelview, so a
** non-uniform scale keeps them right (GL_NORMALIZE makes them unit again).
** Wide lines are expanded per instance, with view * M in the clip matrix.
** Instanced arrays (glDrawElementsInstanced with a per-instance attribute)
** would need shaders (OpenGL 3.3 or ARB_instanced_arrays with vertex
** programs), which this OpenGL 1.x path does without: a call per instance
** and group, its vertices read in place from the prototype's arrays.
*/
#include <GL/gl.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "render.h"
#include "vec3.h"

/* At most this many indices per glDrawElements call (GLsizei is an int). */
#define MAXDRAW (3u << 22)

/* ---------------------------------------------------------------------- */

void lsys_render_defaults (lsys_render_opts *o) {
  memset(o, 0, sizeof *o);
  o->width = o->height = 800;
  o->supersample = 3;
}

void lsys_render_cache_free (lsys_render_cache *c) {
  LSYS_FREE(c->idx);
  LSYS_FREE(c->rgba);
  LSYS_FREE(c->lidx);
  LSYS_FREE(c->start);
  LSYS_FREE(c->wpos);
  LSYS_FREE(c->wrgba);
  LSYS_FREE(c->widx);
  LSYS_FREE(c->tidx);
  LSYS_FREE(c->texok);
  LSYS_FREE(c->texname);
  LSYS_FREE(c->texkey);
  LSYS_FREE(c->texbuf);
  memset(c, 0, sizeof *c);
}

/* ---------------------------------------------------------------------- */
/* entry points */

#define GLFN(name) {"gl" #name, offsetof(lsys_gl, name)}

static const struct { const char *name; size_t off; } glfns[] = {
  GLFN(GetError), GLFN(GetFloatv), GLFN(GetIntegerv), GLFN(Viewport), GLFN(ClearColor),
  GLFN(ClearDepth), GLFN(Clear), GLFN(Finish), GLFN(Enable), GLFN(Disable),
  GLFN(EnableClientState), GLFN(DisableClientState), GLFN(MatrixMode), GLFN(LoadMatrixd),
  GLFN(LoadIdentity), GLFN(DepthFunc), GLFN(DepthMask), GLFN(BlendFunc), GLFN(ShadeModel),
  GLFN(PolygonMode), GLFN(LineWidth), GLFN(Lightfv), GLFN(LightModelfv), GLFN(LightModeli),
  GLFN(Materialfv), GLFN(Materialf), GLFN(ColorMaterial), GLFN(VertexPointer),
  GLFN(NormalPointer), GLFN(ColorPointer), GLFN(DrawElements), GLFN(GetString),
  GLFN(GenTextures), GLFN(DeleteTextures), GLFN(BindTexture), GLFN(TexImage2D),
  GLFN(TexParameteri), GLFN(TexEnvi), GLFN(TexCoordPointer), GLFN(PixelStorei),
  GLFN(AlphaFunc)
};

/* Each pointer is stored through memcpy: all function pointers share one
** representation on the platforms GL loaders run on (dlsym relies on it). */
int lsys_render_gl_load (lsys_gl *gl, lsys_glproc (*get) (const char *name), lsys_error *e) {
  size_t i;
  memset(gl, 0, sizeof *gl);
  for (i = 0; i < sizeof glfns / sizeof glfns[0]; i++) {
    lsys_glproc f = get(glfns[i].name);
    if (f == NULL)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1, "OpenGL function %s not found",
                           glfns[i].name);
    memcpy((char *)gl + glfns[i].off, &f, sizeof f);
  }
  return LSYS_OK;
}

int lsys_render_software (const lsys_gl *gl) {
  const char *r = (const char *)gl->GetString(GL_RENDERER);
  return r != NULL && (strstr(r, "llvmpipe") != NULL || strstr(r, "softpipe") != NULL ||
                       strstr(r, "swrast") != NULL);
}

/* ---------------------------------------------------------------------- */
/* drawing */

static const lsys_material grey = {
  {0.24f, 0.24f, 0.24f, 1}, {0.8f, 0.8f, 0.8f, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}, 0
};

static uint8_t tobyte (float x) {
  return x <= 0 ? 0 : x >= 1 ? 255 : (uint8_t)(x * 255 + 0.5f);
}

static void setrgba (uint8_t *d, const lsys_material *mt) {
  d[0] = tobyte(mt->diffuse[0]);
  d[1] = tobyte(mt->diffuse[1]);
  d[2] = tobyte(mt->diffuse[2]);
  d[3] = tobyte(mt->diffuse[3]);
}

static void setmaterial (const lsys_gl *gl, const lsys_material *mt) {
  float sh = mt->shininess < 0 ? 0 : mt->shininess > 128 ? 128 : mt->shininess;
  gl->Materialfv(GL_FRONT_AND_BACK, GL_AMBIENT, mt->ambient);
  gl->Materialfv(GL_FRONT_AND_BACK, GL_SPECULAR, mt->specular);
  gl->Materialfv(GL_FRONT_AND_BACK, GL_EMISSION, mt->emission);
  gl->Materialf(GL_FRONT_AND_BACK, GL_SHININESS, sh);
}

/* Draws 'n' indices from 'idx' in slices that fit a GLsizei. */
static void drawelements (const lsys_gl *gl, GLenum mode, const uint32_t *idx, size_t n) {
  while (n > 0) {
    size_t k = n < MAXDRAW ? n : MAXDRAW;
    gl->DrawElements(mode, (GLsizei)k, GL_UNSIGNED_INT, idx);
    idx += k;
    n -= k;
  }
}

/* One frame's view of the scene: what the drawing functions share. */
typedef struct frame {
  const lsys_gl *gl;
  const lsys_mesh *m;
  const lsys_material *pal;
  size_t npal;
  const lsys_texture *const *tex;
  size_t ntex;              /* 0: no texture can apply (the untextured path) */
  size_t *gstart, *tstart;  /* textured triangles: groups by material, buckets by texture */
  lsys_render_cache *c;
  double proj[16], view[16], mvp[16];
  int fbw, fbh, maxw;
  int keep;                 /* keep uploaded textures in the cache (keep_textures) */
  int cull;                 /* the scene's solids may lose their back faces (scene.h) */
  float lscale;             /* framebuffer pixels per image pixel */
  size_t nwv, nwi;          /* wide lines: vertices and indices written */
  const lsys_scene *s;      /* its instances and parts (none: the mesh as it is) */
  double cur[16];           /* wide lines: proj * view, times the instance's M */
} frame;

/* The first element k in [lo, hi) (of 'per' indices each) whose first index
** is at least x. */
static size_t firstat (const uint32_t *idx, int per, size_t lo, size_t hi, size_t x) {
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (idx[per * mid] < x) lo = mid + 1; else hi = mid;
  }
  return lo;
}

/* a * b, column-major 4 x 4 (b's last row 0 0 0 1, as instances' are). */
static void mulaffine (double out[16], const double a[16], const float b[16]) {
  int i, j;
  for (j = 0; j < 4; j++)
    for (i = 0; i < 4; i++)
      out[4 * j + i] = a[i] * b[4 * j] + a[4 + i] * b[4 * j + 1] + a[8 + i] * b[4 * j + 2] +
                       (j == 3 ? a[12 + i] : 0);
}

/*
** Draws 'n' indices of 'idx' (elements of 'per' indices: 3 for triangles, 2
** for lines): as they are, or once per instance, the stretch of its part
** (vertices [v0, v0 + nv) for triangles, line ends [2 l0, 2 (l0 + nl)) for
** lines) under view * M. The modelview is the view again afterwards.
*/
static void drawinst (const frame *F, GLenum mode, const uint32_t *idx, size_t n, int per) {
  const lsys_scene *s = F->s;
  size_t i, ne = n / (size_t)per;
  if (s->ninst == 0) {
    drawelements(F->gl, mode, idx, n);
    return;
  }
  for (i = 0; i < s->ninst; i++) {
    const lsys_part *p;
    size_t lo, hi, a, b;
    double mv[16];
    if (s->inst[i].part >= s->nparts) continue;
    p = &s->parts[s->inst[i].part];
    lo = per == 3 ? p->v0 : 2 * p->l0;
    hi = per == 3 ? p->v0 + p->nv : 2 * (p->l0 + p->nl);
    a = firstat(idx, per, 0, ne, lo);
    b = firstat(idx, per, a, ne, hi);
    if (b == a) continue;
    mulaffine(mv, F->view, s->inst[i].m);
    F->gl->LoadMatrixd(mv);
    drawelements(F->gl, mode, idx + (size_t)per * a, (size_t)per * (b - a));
  }
  F->gl->LoadMatrixd(F->view);
}

/* ---------------------------------------------------------------------- */
/* triangles */

/* Sorts the triangles by group g = twosided * npal + material (of each
** triangle's first vertex) into c->idx; c->start[g] is the first index of
** group g and c->start[2 npal] the end. */
static void sorttriangles (frame *F) {
  const lsys_mesh *m = F->m;
  size_t *start = F->c->start, t, g, sum = 0, npal = F->npal, ng = 2 * npal;
  memset(start, 0, (ng + 1) * sizeof *start);
  for (t = 0; t < m->nt; t++) {
    uint32_t a = m->tri[3 * t];
    start[(m->twosided[a] ? npal : 0) + m->col[a] % npal]++;
  }
  for (g = 0; g < ng; g++) {            /* counts -> first positions */
    size_t k = start[g];
    start[g] = sum;
    sum += 3 * k;
  }
  start[ng] = sum;
  for (t = 0; t < m->nt; t++) {
    const uint32_t *tri = m->tri + 3 * t;
    size_t *s = &start[(m->twosided[tri[0]] ? npal : 0) + m->col[tri[0]] % npal];
    memcpy(F->c->idx + *s, tri, 3 * sizeof *tri);
    *s += 3;
  }
  for (g = ng; g > 0; g--) start[g] = start[g - 1];   /* back to starts */
  start[0] = 0;
}

/* The group of triangle vertex a: twosided * npal + material. */
static size_t groupof (const frame *F, uint32_t a) {
  return (F->m->twosided[a] ? F->npal : 0) + F->m->col[a] % F->npal;
}

/* The texture of vertex a: its index when that texture can be drawn, else 0. */
static size_t texof (const frame *F, uint32_t a) {
  size_t k = F->m->tex[a];
  return k <= F->ntex && F->c->texok[k] ? k : 0;
}

/*
** sorttriangles when textures may apply: the untextured triangles as
** there; the textured ones after them in c->idx, by texture, each texture's
** bucket by group (a stable sort by group into c->tidx, then by texture).
** F->tstart[k] is the first index of texture k's bucket (k = 1..ntex) and
** F->tstart[ntex + 1] the end.
*/
static void sorttextured (frame *F) {
  const lsys_mesh *m = F->m;
  lsys_render_cache *c = F->c;
  size_t *start = c->start, *gs = F->gstart, *ts = F->tstart;
  size_t t, g, k, n, sum = 0, tsum = 0, ng = 2 * F->npal, ntex = F->ntex;
  memset(start, 0, (ng + 1) * sizeof *start);
  memset(gs, 0, (ng + 1) * sizeof *gs);
  memset(ts, 0, (ntex + 2) * sizeof *ts);
  for (t = 0; t < m->nt; t++) {
    uint32_t a = m->tri[3 * t];
    g = groupof(F, a);
    k = texof(F, a);
    if (k == 0) start[g]++;
    else { gs[g]++; ts[k]++; }
  }
  for (g = 0; g < ng; g++) {            /* counts -> first positions */
    n = start[g]; start[g] = sum; sum += 3 * n;
    n = gs[g]; gs[g] = tsum; tsum += 3 * n;
  }
  start[ng] = sum;
  gs[ng] = tsum;
  tsum = sum;                           /* the buckets follow the untextured triangles */
  for (k = 1; k <= ntex; k++) { n = ts[k]; ts[k] = tsum; tsum += 3 * n; }
  ts[ntex + 1] = tsum;
  for (t = 0; t < m->nt; t++) {
    const uint32_t *tri = m->tri + 3 * t;
    g = groupof(F, tri[0]);
    if (texof(F, tri[0])) {
      memcpy(c->tidx + gs[g], tri, 3 * sizeof *tri);
      gs[g] += 3;
    } else {
      memcpy(c->idx + start[g], tri, 3 * sizeof *tri);
      start[g] += 3;
    }
  }
  for (t = 0; t < gs[ng]; t += 3) {     /* gs[ng]: the textured indices, in group order */
    size_t *p = &ts[texof(F, c->tidx[t])];
    memcpy(c->idx + *p, c->tidx + t, 3 * sizeof *c->idx);
    *p += 3;
  }
  for (g = ng; g > 0; g--) start[g] = start[g - 1];   /* back to starts */
  start[0] = 0;
  for (k = ntex; k > 1; k--) ts[k] = ts[k - 1];
  ts[1] = sum;
}

/* ---------------------------------------------------------------------- */
/* textures */

/* Whether the context takes textures of any size (OpenGL 2.0 or the
** extension); otherwise they are resampled to powers of two. */
static int npotok (const lsys_gl *gl) {
  const char *v = (const char *)gl->GetString(GL_VERSION), *x;
  if (v != NULL && v[0] >= '2' && v[0] <= '9') return 1;
  x = (const char *)gl->GetString(GL_EXTENSIONS);
  return x != NULL && strstr(x, "GL_ARB_texture_non_power_of_two") != NULL;
}

/* The size a texture of n pixels is uploaded at: n itself, or the next
** power of two when 'pot'; at most 'max' (a power of two in practice). */
static int texsize (int n, int pot, int max) {
  int p = 1;
  if (!pot) return n < max ? n : max;
  while (p < n && p <= max / 2) p *= 2;
  return p;
}

/*
** Uploads texture k to the texture object name c->texname[k]: RGBA, or
** luminance (with alpha when some texel is not opaque) for an intensity
** texture in modulate mode; resampled to the nearest texel when the
** context cannot take its size. Returns LSYS_OK or LSYS_ENOMEM.
*/
static int upload (frame *F, size_t k, int pot, int maxsize) {
  const lsys_gl *gl = F->gl;
  const lsys_texture *t = F->tex[k - 1];
  lsys_render_cache *c = F->c;
  int lum = t->intensity && t->mode == LSYS_TEX_MODULATE;
  int alpha = lum && lsys_texture_hasalpha(t), nc = lum ? (alpha ? 2 : 1) : 4;
  int W = texsize(t->w, pot, maxsize), H = texsize(t->h, pot, maxsize);
  GLenum fmt = lum ? (alpha ? GL_LUMINANCE_ALPHA : GL_LUMINANCE) : GL_RGBA;
  const uint8_t *px = t->rgba;
  if (W != t->w || H != t->h || nc != 4) {
    int x, y;
    uint8_t *d;
    if (lsys_common_grow((void **)&c->texbuf, &c->texbufcap, (size_t)W * H * nc, 1) != LSYS_OK)
      return LSYS_ENOMEM;
    d = c->texbuf;
    for (y = 0; y < H; y++) {
      const uint8_t *row = t->rgba + 4 * (size_t)t->w * (size_t)((long long)y * t->h / H);
      for (x = 0; x < W; x++) {
        const uint8_t *s = row + 4 * (size_t)((long long)x * t->w / W);
        if (nc == 4) { memcpy(d, s, 4); d += 4; }
        else {
          *d++ = lsys_texture_intensity(s);
          if (alpha) *d++ = s[3];
        }
      }
    }
    px = c->texbuf;
  }
  gl->BindTexture(GL_TEXTURE_2D, c->texname[k]);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, t->mag_linear ? GL_LINEAR : GL_NEAREST);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, t->min_linear ? GL_LINEAR : GL_NEAREST);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl->TexImage2D(GL_TEXTURE_2D, 0, (GLint)fmt, W, H, 0, fmt, GL_UNSIGNED_BYTE, px);
  return LSYS_OK;
}

/* Creates and fills the texture objects of the textures with triangles;
** with keep_textures, those already holding the same texture stay. */
static int uploadall (frame *F) {
  const lsys_gl *gl = F->gl;
  lsys_render_cache *c = F->c;
  size_t k;
  GLint maxsize = 0;
  int pot = !npotok(gl);
  gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxsize);
  if (maxsize < 64) maxsize = 64;                  /* the least OpenGL guarantees */
  for (k = 1; k <= F->ntex; k++) {
    if (!F->keep) c->texname[k] = 0;
    if (F->tstart[k + 1] == F->tstart[k]) continue;
    if (F->keep && c->texname[k] != 0 && c->texkey[k] == F->tex[k - 1]) continue;
    if (c->texname[k] == 0) gl->GenTextures(1, &c->texname[k]);
    c->texkey[k] = F->tex[k - 1];
    if (upload(F, k, pot, maxsize) != LSYS_OK) return LSYS_ENOMEM;
  }
  return LSYS_OK;
}

void lsys_render_cache_release (lsys_render_cache *c, const lsys_gl *gl) {
  size_t k;
  for (k = 1; k <= c->nkept; k++)
    if (c->texname[k] != 0) {
      gl->DeleteTextures(1, &c->texname[k]);
      c->texname[k] = 0;
      c->texkey[k] = NULL;
    }
  c->nkept = 0;
}

static void deleteall (frame *F) {
  size_t k;
  for (k = 1; k <= F->ntex; k++)
    if (F->c->texname[k] != 0) {
      F->gl->DeleteTextures(1, &F->c->texname[k]);
      F->c->texname[k] = 0;
    }
}

/* Draws the runs of one group in texture k's bucket whose material is
** opaque (translucent 0) or translucent (1), textured unless 'plain'. */
static void drawbucket (const frame *F, size_t k, int translucent, int plain) {
  const lsys_gl *gl = F->gl;
  const lsys_texture *t = F->tex[k - 1];
  const uint32_t *idx = F->c->idx;
  size_t i = F->tstart[k], end = F->tstart[k + 1], npal = F->npal;
  int cut = 0;
  if (i == end) return;
  if (!plain) {
    gl->BindTexture(GL_TEXTURE_2D, F->c->texname[k]);
    gl->TexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE,
                t->mode == LSYS_TEX_DECAL ? GL_DECAL : GL_MODULATE);
    cut = !translucent && t->mode == LSYS_TEX_MODULATE && lsys_texture_hasalpha(t);
    if (cut) {
      gl->AlphaFunc(GL_GEQUAL, 0.5f);
      gl->Enable(GL_ALPHA_TEST);
    }
  }
  while (i < end) {
    size_t g = groupof(F, idx[i]), j = i + 3;
    const lsys_material *mt = &F->pal[g % npal];
    while (j < end && groupof(F, idx[j]) == g) j += 3;
    if ((mt->diffuse[3] < 1) == translucent) {
      gl->LightModeli(GL_LIGHT_MODEL_TWO_SIDE, g >= npal);
      setmaterial(gl, mt);
      drawinst(F, GL_TRIANGLES, idx + i, j - i, 3);
    }
    i = j;
  }
  if (cut) gl->Disable(GL_ALPHA_TEST);
}

/* The textured triangles, after the untextured ones of drawtriangles. */
static void drawtextured (const frame *F, int translucent, int wireframe) {
  static const double flipv[16] = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1};
  const lsys_gl *gl = F->gl;
  size_t k;
  if (F->tstart[F->ntex + 1] == F->tstart[1]) return;
  if (!wireframe) {
    gl->MatrixMode(GL_TEXTURE);
    gl->LoadMatrixd(flipv);                     /* v = 0 is the image's bottom row */
    gl->MatrixMode(GL_MODELVIEW);
    gl->EnableClientState(GL_TEXTURE_COORD_ARRAY);
    gl->TexCoordPointer(2, GL_FLOAT, 0, F->m->uv);
    gl->Enable(GL_TEXTURE_2D);
  }
  for (k = 1; k <= F->ntex; k++) drawbucket(F, k, translucent, wireframe);
  if (!wireframe) {
    gl->Disable(GL_TEXTURE_2D);
    gl->DisableClientState(GL_TEXTURE_COORD_ARRAY);
    gl->BindTexture(GL_TEXTURE_2D, 0);
  }
}

/* Draws the groups of opaque materials (translucent 0) or of translucent
** ones (1); c->idx and c->rgba must be filled. */
static void drawtriangles (const frame *F, int translucent, int wireframe) {
  const lsys_gl *gl = F->gl;
  const lsys_mesh *m = F->m;
  size_t g, npal = F->npal;
  gl->Enable(GL_LIGHTING);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_NORMAL_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(3, GL_FLOAT, 0, m->pos);
  gl->NormalPointer(GL_FLOAT, 0, m->nrm);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, F->c->rgba);
  if (wireframe) {
    gl->PolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    gl->LineWidth(F->lscale);
  }
  if (translucent) {
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl->DepthMask(GL_FALSE);
  }
  for (g = 0; g < 2 * npal; g++) {
    const lsys_material *mt = &F->pal[g % npal];
    size_t n = F->c->start[g + 1] - F->c->start[g];
    if (n == 0 || (mt->diffuse[3] < 1) != translucent) continue;
    gl->LightModeli(GL_LIGHT_MODEL_TWO_SIDE, g >= npal);
    if (F->cull && g < npal && !wireframe) gl->Enable(GL_CULL_FACE);
    else gl->Disable(GL_CULL_FACE);
    setmaterial(gl, mt);
    drawinst(F, GL_TRIANGLES, F->c->idx + F->c->start[g], n, 3);
  }
  gl->Disable(GL_CULL_FACE);
  if (F->ntex > 0) drawtextured(F, translucent, wireframe);
  gl->DepthMask(GL_TRUE);
  gl->Disable(GL_BLEND);
  gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  gl->DisableClientState(GL_NORMAL_ARRAY);
  gl->LightModeli(GL_LIGHT_MODEL_TWO_SIDE, 0);
  gl->Disable(GL_LIGHTING);
}

/* The floor of o (a window's ground): one quad facing up, lit as a solid
** surface of its colour, under the camera's own matrices. */
static void drawfloor (const frame *F, const lsys_render_opts *o) {
  static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
  const lsys_gl *gl = F->gl;
  const double *r = o->floor_rect;
  float pos[12], nrm[12];
  uint8_t rgba[16];
  lsys_material mt;
  int k, c;
  for (k = 0; k < 4; k++) {         /* counterclockwise seen from above */
    pos[3 * k] = (float)(k == 0 || k == 1 ? r[1] : r[3]);
    pos[3 * k + 1] = (float)r[0];
    pos[3 * k + 2] = (float)(k == 0 || k == 3 ? r[2] : r[4]);
    nrm[3 * k] = 0; nrm[3 * k + 1] = 1; nrm[3 * k + 2] = 0;
    for (c = 0; c < 3; c++) rgba[4 * k + c] = (uint8_t)(o->floor_rgb[c] * 255 + 0.5f);
    rgba[4 * k + 3] = 255;
  }
  lsys_mesh_material_color(&mt, o->floor_rgb[0], o->floor_rgb[1], o->floor_rgb[2]);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadMatrixd(F->view);
  gl->Enable(GL_LIGHTING);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_NORMAL_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(3, GL_FLOAT, 0, pos);
  gl->NormalPointer(GL_FLOAT, 0, nrm);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, rgba);
  setmaterial(gl, &mt);
  gl->DrawElements(GL_TRIANGLES, 6, GL_UNSIGNED_INT, idx);
  gl->DisableClientState(GL_NORMAL_ARRAY);
  gl->Disable(GL_LIGHTING);
}

/* ---------------------------------------------------------------------- */
/* lines */

/* Radius of end k (0..2 nl) in framebuffer pixels; widths that are not
** numbers or not positive draw as thin as possible, huge ones are capped. */
static float radius (const frame *F, size_t k) {
  float w = F->m->lwidth[k];
  return w > 0 ? 0.5f * (w < 16384 ? w : 16384) * F->lscale : 0;
}

/* Width of segment s in framebuffer pixels: the mean of its ends. */
static float segwidth (const frame *F, size_t s) {
  return radius(F, 2 * s) + radius(F, 2 * s + 1);
}

static int iswide (const frame *F, size_t s) {
  return segwidth(F, s) >= LSYS_RENDER_WIDE * F->lscale;
}

/* Fan triangles of a round end of radius r framebuffer pixels: the arc
** stays within half an image pixel, tol = lscale / 2 framebuffer pixels, of
** the circle (r (1 - cos(pi / 2m)) < tol when m >= (pi/2) sqrt(r / 2 tol)). */
static int capsteps (const frame *F, double r) {
  double k = ceil(1.5708 * sqrt(r > 0 ? r / F->lscale : 0));
  return k < 2 ? 2 : k > 32 ? 32 : (int)k;
}

/* Upper bounds of the vertices and indices of the wide lines. */
static void widecount (const frame *F, size_t *nv, size_t *ni) {
  size_t s, v = 0, i = 0;
  for (s = 0; s < F->m->nl; s++) {
    if (!iswide(F, s)) continue;
    int a = capsteps(F, radius(F, 2 * s)), b = capsteps(F, radius(F, 2 * s + 1));
    v += 4 + (size_t)a + (size_t)b;     /* band corners; per end: centre + arc inside */
    i += 6 + 3 * ((size_t)a + (size_t)b);
  }
  *nv = v;
  *ni = i;
}

static void transform (const double M[16], const float p[3], double c[4]) {
  int i;
  for (i = 0; i < 4; i++) c[i] = M[i] * p[0] + M[4 + i] * p[1] + M[8 + i] * p[2] + M[12 + i];
}

/* Appends a vertex at clip point c moved by (dx, dy) pixels on screen. */
static uint32_t wvertex (frame *F, const double c[4], double dx, double dy,
                         const uint8_t rgba[4]) {
  float *p = F->c->wpos + 4 * F->nwv;
  p[0] = (float)(c[0] + c[3] * dx * 2 / F->fbw);
  p[1] = (float)(c[1] + c[3] * dy * 2 / F->fbh);
  p[2] = (float)c[2];
  p[3] = (float)c[3];
  memcpy(F->c->wrgba + 4 * F->nwv, rgba, 4);
  return (uint32_t)F->nwv++;
}

static void wtri (frame *F, uint32_t a, uint32_t b, uint32_t c) {
  uint32_t *t = F->c->widx + F->nwi;
  t[0] = a; t[1] = b; t[2] = c;
  F->nwi += 3;
}

/* A half disc of radius r around clip point c, on the side of the unit
** screen direction (ux, uy), between the band corners a (at +n) and b (at
** -n), where n = (-uy, ux). */
static void cap (frame *F, const double c[4], double r, double ux, double uy, uint32_t a,
                 uint32_t b, const uint8_t rgba[4]) {
  int k, m = capsteps(F, r);
  double cs = cos(PI / m), sn = -sin(PI / m);       /* clockwise: +n, then u, then -n */
  double x = -uy * r, y = ux * r;
  uint32_t centre = wvertex(F, c, 0, 0, rgba), prev = a;
  for (k = 1; k <= m; k++) {
    uint32_t next = b;
    if (k < m) {
      double nx = cs * x - sn * y;
      y = sn * x + cs * y;
      x = nx;
      next = wvertex(F, c, x, y, rgba);
    }
    wtri(F, centre, prev, next);
    prev = next;
  }
}

/*
** Expands segment s into a band of its two end widths with round ends, in
** clip coordinates. The part in front of the near plane (z >= -w) is kept;
** an end cut there gets no round end.
*/
static void wideline (frame *F, size_t s, const uint8_t rgba[4]) {
  const lsys_mesh *m = F->m;
  double c0[4], c1[4], r0 = radius(F, 2 * s), r1 = radius(F, 2 * s + 1);
  double d0, d1, x0, y0, x1, y1, ux, uy, len;
  int cut0 = 0, cut1 = 0, i;
  uint32_t a0, b0, a1, b1;
  transform(F->cur, m->lpos + 6 * s, c0);
  transform(F->cur, m->lpos + 6 * s + 3, c1);
  d0 = c0[2] + c0[3];
  d1 = c1[2] + c1[3];
  if (!(d0 >= 0 || d1 >= 0)) return;          /* wholly behind the near plane (or NaN) */
  if (d0 < 0 || d1 < 0) {
    double t = d0 / (d0 - d1);
    double *c = d0 < 0 ? c0 : c1;
    for (i = 0; i < 4; i++) c[i] = c0[i] + t * (c1[i] - c0[i]);
    if (d0 < 0) { r0 = r0 + t * (r1 - r0); cut0 = 1; }
    else { r1 = r0 + t * (r1 - r0); cut1 = 1; }
  }
  if (!(c0[3] > 0 && c1[3] > 0)) return;
  x0 = c0[0] / c0[3] * F->fbw / 2; y0 = c0[1] / c0[3] * F->fbh / 2;
  x1 = c1[0] / c1[3] * F->fbw / 2; y1 = c1[1] / c1[3] * F->fbh / 2;
  ux = x1 - x0; uy = y1 - y0;
  len = sqrt(ux * ux + uy * uy);
  if (!(len > 1e-9)) { ux = 1; uy = 0; }     /* seen end-on: the round ends make a disc */
  else { ux /= len; uy /= len; }
  a0 = wvertex(F, c0, -uy * r0, ux * r0, rgba);
  b0 = wvertex(F, c0, uy * r0, -ux * r0, rgba);
  a1 = wvertex(F, c1, -uy * r1, ux * r1, rgba);
  b1 = wvertex(F, c1, uy * r1, -ux * r1, rgba);
  wtri(F, a0, b0, b1);
  wtri(F, a0, b1, a1);
  if (!cut1) cap(F, c1, r1, ux, uy, a1, b1, rgba);
  if (!cut0) cap(F, c0, r0, -ux, -uy, b0, a0, rgba);
}

/*
** The bands of the wide lines, in clip coordinates (identity matrices):
** those wideline made, or with instances each instance's, made and drawn in
** turn (the scratch, sized for the whole mesh, then holds one part's).
*/
static void drawwide (frame *F, const uint8_t *rgba) {
  const lsys_gl *gl = F->gl;
  const lsys_scene *sc = F->s;
  lsys_render_cache *c = F->c;
  size_t i, k;
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadIdentity();
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadIdentity();
  gl->VertexPointer(4, GL_FLOAT, 0, c->wpos);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, c->wrgba);
  if (sc->ninst == 0) drawelements(gl, GL_TRIANGLES, c->widx, F->nwi);
  for (i = 0; i < sc->ninst; i++) {
    const lsys_part *p;
    if (sc->inst[i].part >= sc->nparts) continue;
    p = &sc->parts[sc->inst[i].part];
    mulaffine(F->cur, F->mvp, sc->inst[i].m);
    F->nwv = F->nwi = 0;
    for (k = p->l0; k < p->l0 + p->nl && k < F->m->nl; k++)
      if (iswide(F, k)) wideline(F, k, rgba + 8 * k);
    if (F->nwi > 0) drawelements(gl, GL_TRIANGLES, c->widx, F->nwi);
  }
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(F->proj);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadMatrixd(F->view);
}

/*
** Thin lines: GL lines sorted by width in framebuffer pixels rounded to an
** integer (what GL does with aliased widths anyway). Wide lines: the bands
** of wideline, drawn with identity matrices as they are already in clip
** coordinates.
*/
static void drawlines (frame *F) {
  const lsys_gl *gl = F->gl;
  const lsys_mesh *m = F->m;
  lsys_render_cache *c = F->c;
  uint8_t *rgba = c->rgba + 4 * m->nv;
  size_t *start = c->start + 2 * F->npal + 1, s, k, sum = 0, maxw = (size_t)F->maxw;
  for (s = 0; s < m->nl; s++) {
    setrgba(rgba + 8 * s, &F->pal[m->lcol[s] % F->npal]);
    memcpy(rgba + 8 * s + 4, rgba + 8 * s, 4);
  }
  /* counting sort of the thin segments by width (bucket k: k pixels) */
  memset(start, 0, (maxw + 2) * sizeof *start);
  for (s = 0; s < m->nl; s++) {
    long kw = lroundf(segwidth(F, s));
    if (!iswide(F, s)) start[kw < 1 ? 1 : (size_t)kw > maxw ? maxw : (size_t)kw]++;
  }
  for (k = 0; k <= maxw + 1; k++) {
    size_t n = start[k];
    start[k] = sum;
    sum += 2 * n;
  }
  for (s = 0; s < m->nl; s++) {
    long kw = lroundf(segwidth(F, s));
    size_t *p;
    if (iswide(F, s)) {
      if (F->s->ninst == 0) wideline(F, s, rgba + 8 * s);
      continue;
    }
    p = &start[kw < 1 ? 1 : (size_t)kw > maxw ? maxw : (size_t)kw];
    c->lidx[*p] = (uint32_t)(2 * s);
    c->lidx[*p + 1] = (uint32_t)(2 * s + 1);
    *p += 2;
  }
  for (k = maxw + 1; k > 0; k--) start[k] = start[k - 1];
  start[0] = 0;
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(3, GL_FLOAT, 0, m->lpos);
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, 0, rgba);
  for (k = 1; k <= maxw; k++) {
    size_t n = start[k + 1] - start[k];
    if (n == 0) continue;
    gl->LineWidth((GLfloat)k);
    drawinst(F, GL_LINES, c->lidx + start[k], n, 2);
  }
  if (F->nwi > 0 || F->s->ninst > 0) drawwide(F, rgba);
}

/* ---------------------------------------------------------------------- */

/* Makes room for the scratch arrays of one frame. */
static int reserve (frame *F) {
  const lsys_mesh *m = F->m;
  lsys_render_cache *c = F->c;
  size_t nstart = 2 * F->npal + 1 + (size_t)F->maxw + 2;   /* triangle groups, line widths */
  size_t nwv = 0, nwi = 0, k;
  if (F->ntex > 0) {                      /* textured: groups, texture buckets */
    nstart += 2 * F->npal + 1 + F->ntex + 2;
    if (lsys_common_grow((void **)&c->tidx, &c->tidxcap, 3 * m->nt, sizeof *c->tidx) ||
        lsys_common_grow((void **)&c->texok, &c->texokcap, F->ntex + 1, 1) ||
        lsys_common_grow((void **)&c->texname, &c->texnamecap, F->ntex + 1, sizeof *c->texname) ||
        lsys_common_grow((void **)&c->texkey, &c->texkeycap, F->ntex + 1, sizeof *c->texkey))
      return LSYS_ENOMEM;
    c->texok[0] = 0;
    for (k = 1; k <= F->ntex; k++) {
      const lsys_texture *t = F->tex[k - 1];
      c->texok[k] = t != NULL && t->rgba != NULL && t->w > 0 && t->h > 0;
      if (!F->keep || k > c->nkept) {       /* kept names stay for uploadall to check */
        c->texname[k] = 0;
        c->texkey[k] = NULL;
      }
    }
    if (F->keep && c->nkept < F->ntex) c->nkept = F->ntex;
  }
  if (m->nl > 0) widecount(F, &nwv, &nwi);
  if (nwv > UINT32_MAX) return LSYS_ENOMEM;   /* indices are 32-bit */
  if (lsys_common_grow((void **)&c->idx, &c->idxcap, 3 * m->nt, sizeof *c->idx) ||
      lsys_common_grow((void **)&c->rgba, &c->rgbacap, 4 * (m->nv + 2 * m->nl), 1) ||
      lsys_common_grow((void **)&c->lidx, &c->lidxcap, 2 * m->nl, sizeof *c->lidx) ||
      lsys_common_grow((void **)&c->start, &c->startcap, nstart, sizeof *c->start) ||
      lsys_common_grow((void **)&c->wpos, &c->wposcap, 4 * nwv, sizeof *c->wpos) ||
      lsys_common_grow((void **)&c->wrgba, &c->wrgbacap, 4 * nwv, 1) ||
      lsys_common_grow((void **)&c->widx, &c->widxcap, nwi, sizeof *c->widx))
    return LSYS_ENOMEM;
  F->gstart = c->start + 2 * F->npal + 1 + (size_t)F->maxw + 2;
  F->tstart = F->gstart + 2 * F->npal + 1;
  return LSYS_OK;
}

/* The default lights, as fractions of the diffuse colour: a key light from
** the scene's direction, a dimmer fill from the opposite direction, and a
** sky above with a fainter bounce from the ground below (a two-light
** approximation of a hemisphere), over an ambient term stronger than the
** material's own (GL_LIGHT_MODEL_AMBIENT times the material's ambient, 0.3 of
** its colour by default). Any normal gets some of these: a face edge-on to
** the key light still has the fill's side or the sky's, and the ambient
** keeps a face turned away from all of them above about 0.4 of its colour,
** while the key light, brighter than the rest together at its side, keeps the
** shape. */
#define KEY 0.60f
#define FILL 0.25f
#define SKY 0.20f
#define GROUND 0.10f
#define AMBIENT 1.35f

/* Sets light 'id' to come from direction d (world space, w = 0) with the
** diffuse intensity 'k' and, when 'spec', a white highlight. */
static void setlight (const lsys_gl *gl, GLenum id, const double d[3], float k, int spec) {
  static const GLfloat black[4] = {0, 0, 0, 1};
  static const GLfloat white[4] = {1, 1, 1, 1};
  GLfloat pos[4], dif[4];
  pos[0] = (GLfloat)d[0];
  pos[1] = (GLfloat)d[1];
  pos[2] = (GLfloat)d[2];
  pos[3] = 0;
  dif[0] = dif[1] = dif[2] = k;
  dif[3] = 1;
  gl->Lightfv(id, GL_POSITION, pos);
  gl->Lightfv(id, GL_AMBIENT, black);
  gl->Lightfv(id, GL_DIFFUSE, dif);
  gl->Lightfv(id, GL_SPECULAR, spec ? white : black);
  gl->Enable(id);
}

/* A view's own lights (scene.h), as cpfg draws them: each with its colours,
** a direction (w = 0) or a position (w = 1) in world space; the rest off. */
static void viewlights (const lsys_gl *gl, const lsys_scene *s) {
  int k, j;
  for (k = 0; k < LSYS_SCENE_NLIGHTS; k++) {
    const lsys_slight *l = &s->lights[k];
    GLenum id = (GLenum)(GL_LIGHT0 + k);
    GLfloat pos[4], a[4], d[4], sp[4];
    if (k >= s->nlights) { gl->Disable(id); continue; }
    for (j = 0; j < 4; j++) pos[j] = (GLfloat)l->pos[j];
    for (j = 0; j < 3; j++) {
      a[j] = l->ambient[j];
      d[j] = l->diffuse[j];
      sp[j] = l->specular[j];
    }
    a[3] = d[3] = sp[3] = 1;
    gl->Lightfv(id, GL_POSITION, pos);
    gl->Lightfv(id, GL_AMBIENT, a);
    gl->Lightfv(id, GL_DIFFUSE, d);
    gl->Lightfv(id, GL_SPECULAR, sp);
    gl->Enable(id);
  }
}

/* Clears the framebuffer and sets the state every frame starts from: the
** camera's matrices, depth test, the lights and colour materials. */
static void startframe (const frame *F, const lsys_scene *s, const lsys_render_opts *o) {
  static const double up[3] = {0, 1, 0}, down[3] = {0, -1, 0};
  static const GLfloat ambient[4] = {AMBIENT, AMBIENT, AMBIENT, 1};
  static const GLfloat dim[4] = {0.2f, 0.2f, 0.2f, 1};     /* OpenGL's own default */
  const lsys_gl *gl = F->gl;
  double back[3];
  int k;
  gl->Viewport(o->x, o->y, F->fbw, F->fbh);
  gl->ClearColor(s->background[0], s->background[1], s->background[2],
                 o->transparent ? 0.0f : 1.0f);
  gl->ClearDepth(1);
  gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl->MatrixMode(GL_PROJECTION);
  gl->LoadMatrixd(F->proj);
  gl->MatrixMode(GL_MODELVIEW);
  gl->LoadMatrixd(F->view);
  gl->Enable(GL_DEPTH_TEST);
  gl->DepthFunc(GL_LEQUAL);
  gl->Disable(GL_CULL_FACE);
  gl->Disable(GL_BLEND);
  gl->ShadeModel(GL_SMOOTH);
  gl->Enable(GL_NORMALIZE);
  /* directions (w = 0) in world space, as the modelview matrix holds only
  ** the view transform here */
  if (s->nlights > 0) {
    viewlights(gl, s);
    gl->LightModelfv(GL_LIGHT_MODEL_AMBIENT, dim);
  } else {
    back[0] = -s->light[0];
    back[1] = -s->light[1];
    back[2] = -s->light[2];
    setlight(gl, GL_LIGHT0, s->light, KEY, 1);
    setlight(gl, GL_LIGHT1, back, FILL, 0);
    setlight(gl, GL_LIGHT2, up, SKY, 0);
    setlight(gl, GL_LIGHT3, down, GROUND, 0);
    for (k = 4; k < LSYS_SCENE_NLIGHTS; k++) gl->Disable((GLenum)(GL_LIGHT0 + k));
    gl->LightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  }
  gl->LightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, 0);
  gl->ColorMaterial(GL_FRONT_AND_BACK, GL_DIFFUSE);
  gl->Enable(GL_COLOR_MATERIAL);
}

int lsys_render_draw (const lsys_scene *s, const lsys_render_opts *o, int fbw, int fbh,
                      lsys_error *e) {
  const lsys_gl *gl = o->gl;
  lsys_render_cache local = {0};
  frame F;
  GLfloat range[2] = {1, 1};
  GLenum err;
  int i, j, k;
  if (gl == NULL)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "no OpenGL entry points to draw with");
  for (k = 0; k < 32 && gl->GetError() != GL_NO_ERROR; k++) {}   /* earlier errors are not ours */
  memset(&F, 0, sizeof F);
  F.gl = gl;
  F.m = &s->mesh;
  F.c = o->cache ? o->cache : &local;
  F.pal = s->pal;
  F.npal = s->npal;
  F.cull = s->cull;
  F.fbw = fbw;
  F.fbh = fbh;
  F.s = s;
  F.lscale = o->height > 0 ? (float)fbh / (float)o->height : 1;
  if (lsys_render_camera_scene(s, &s->cam, fbw, fbh, F.proj, F.view) != LSYS_OK)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "bad camera: the viewpoint and the target coincide, a zero "
                         "direction or up vector, or an empty viewport");
  for (i = 0; i < 4; i++)
    for (j = 0; j < 4; j++)
      F.mvp[4 * j + i] = F.proj[i] * F.view[4 * j] + F.proj[4 + i] * F.view[4 * j + 1] +
                         F.proj[8 + i] * F.view[4 * j + 2] + F.proj[12 + i] * F.view[4 * j + 3];
  memcpy(F.cur, F.mvp, sizeof F.cur);
  if (F.pal == NULL || F.npal == 0) { F.pal = &grey; F.npal = 1; }
  if (F.npal > 65536) F.npal = 65536;   /* colour indices are 16-bit */
  F.keep = o->keep_textures && o->cache != NULL;
  if (s->tex != NULL && s->ntex > 0 && F.m->tex != NULL && F.m->nt > 0) {
    F.tex = s->tex;
    F.ntex = s->ntex < 65535 ? (size_t)s->ntex : 65535;   /* texture indices are 16-bit */
  }
  gl->GetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
  F.maxw = range[1] >= 1 ? (int)range[1] : 1;
  if (F.maxw > 1024) F.maxw = 1024;
  if (reserve(&F) != LSYS_OK) {
    lsys_render_cache_free(&local);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory to draw the scene");
  }
  startframe(&F, s, o);
  if (o->sky) lsys_render_backdrop(gl, o, F.proj, F.view);
  if (F.m->nt > 0) {
    size_t v;
    for (v = 0; v < F.m->nv; v++) setrgba(F.c->rgba + 4 * v, &F.pal[F.m->col[v] % F.npal]);
    if (o->shade != NULL) lsys_render_shade(F.c->rgba, o->shade, F.m->nv);
    if (F.ntex == 0) sorttriangles(&F);
    else {
      sorttextured(&F);
      if (!o->wireframe && uploadall(&F) != LSYS_OK) {
        deleteall(&F);
        lsys_render_cache_free(&local);
        return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory for the textures");
      }
    }
    drawtriangles(&F, 0, o->wireframe);
  }
  if (o->floor && !o->wireframe) drawfloor(&F, o);
  if (F.m->nl > 0) drawlines(&F);
  if (F.m->nt > 0) drawtriangles(&F, 1, o->wireframe);   /* translucent, over everything */
  gl->DisableClientState(GL_VERTEX_ARRAY);
  gl->DisableClientState(GL_COLOR_ARRAY);
  if (F.ntex > 0 && !F.keep) deleteall(&F);
  lsys_render_cache_free(&local);
  if ((err = gl->GetError()) != GL_NO_ERROR)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "OpenGL error 0x%04x while drawing",
                         (unsigned)err);
  return LSYS_OK;
}
