/*
** Mesh buffers and the export writers: Wavefront OBJ with its MTL file,
** binary little-endian PLY, and glTF 2.0 binary (.glb).
**
** The writers stream through one 64 KiB buffer and format numbers
** themselves: with printf, a text exporter spends most of its time parsing
** format strings. Binary output is assembled byte by byte, low byte first,
** so the files are the same on any host.
**
** Common conventions of the writers:
** - the material of a triangle is the colour index of its first vertex,
**   that of a segment its own colour index, both taken modulo the palette
**   size; only materials that something uses are written;
** - so is its texture (the texture index of its first vertex, when that
**   texture exists and was loaded from a file): OBJ and GLB write one
**   material per (colour, texture) pair, PLY ignores textures;
** - coordinates that are not finite are written as 0 (a JSON file cannot
**   hold NaN, and most OBJ readers choke on it);
** - a failed write leaves the partial file in place: the output may be a
**   device or a pipe, which must not be removed.
*/
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"
#include "outfile.h"

/* ------------------------------------------------------------------ */
/* Buffers                                                              */
/* ------------------------------------------------------------------ */

void lsys_mesh_init (lsys_mesh *m) {
  *m = (lsys_mesh){0};
}

void lsys_mesh_free (lsys_mesh *m) {
  LSYS_FREE(m->pos); LSYS_FREE(m->nrm); LSYS_FREE(m->uv);
  LSYS_FREE(m->col); LSYS_FREE(m->twosided); LSYS_FREE(m->tex); LSYS_FREE(m->tri);
  LSYS_FREE(m->lpos); LSYS_FREE(m->lwidth); LSYS_FREE(m->lcol);
  lsys_mesh_init(m);
}

void lsys_mesh_clear (lsys_mesh *m) {
  m->nv = m->nt = m->nl = 0;
  m->curtex = 0;
}

static int growall (void **arr[], const size_t elem[], int k, size_t *cap, size_t need,
                    lsys_meter *mt);

int lsys_mesh_copy (lsys_mesh *dst, const lsys_mesh *src) {
  lsys_mesh_init(dst);
  dst->curtex = src->curtex;
  if ((src->nv > 0 || src->nt > 0) && lsys_mesh_reserve(dst, src->nv, src->nt) != LSYS_OK)
    goto fail;
  if (src->nv > 0) {
    memcpy(dst->pos, src->pos, src->nv * 3 * sizeof(float));
    memcpy(dst->nrm, src->nrm, src->nv * 3 * sizeof(float));
    memcpy(dst->uv, src->uv, src->nv * 2 * sizeof(float));
    memcpy(dst->col, src->col, src->nv * sizeof(uint16_t));
    memcpy(dst->twosided, src->twosided, src->nv);
    memcpy(dst->tex, src->tex, src->nv * sizeof(uint16_t));
  }
  if (src->nt > 0) memcpy(dst->tri, src->tri, src->nt * 3 * sizeof(uint32_t));
  dst->nv = src->nv;
  dst->nt = src->nt;
  if (src->nl > 0) {
    size_t cap = 0;
    void **arr[3] = { (void **)&dst->lpos, (void **)&dst->lwidth, (void **)&dst->lcol };
    const size_t elem[3] = { 6 * sizeof(float), 2 * sizeof(float), sizeof(uint16_t) };
    if (growall(arr, elem, 3, &cap, src->nl, NULL) != LSYS_OK) goto fail;
    dst->lcap = cap;
    memcpy(dst->lpos, src->lpos, src->nl * 6 * sizeof(float));
    memcpy(dst->lwidth, src->lwidth, src->nl * 2 * sizeof(float));
    memcpy(dst->lcol, src->lcol, src->nl * sizeof(uint16_t));
    dst->nl = src->nl;
  }
  return LSYS_OK;
fail:
  lsys_mesh_free(dst);
  return LSYS_ENOMEM;
}

/*
** Grows the 'k' arrays 'arr' (item sizes 'elem') that share the capacity
** '*cap' to hold 'need' items. Every array starts from the same capacity, so
** lsys_grow picks the same new one for all; '*cap' changes only when all of
** them have grown (an array that grew before a failure is merely larger).
*/
static int growall (void **arr[], const size_t elem[], int k, size_t *cap, size_t need,
                    lsys_meter *mt) {
  size_t c = *cap, sum = 0;
  int i, st;
  if (mt != NULL) {              /* the budget for all of them: one block of 'sum' per item */
    for (i = 0; i < k; i++) sum += elem[i];
    if (need <= c) return LSYS_OK;
    if ((st = lsys_meter_take(mt, *cap, need, sum, &c)) != LSYS_OK) return st;
    for (i = 0; i < k; i++) {    /* exactly the capacity the budget allowed */
      void *np = LSYS_REALLOC(*arr[i], c * elem[i]);
      if (np == NULL) return LSYS_ENOMEM;
      *arr[i] = np;
    }
    *cap = c;
    return LSYS_OK;
  }
  for (i = 0; i < k; i++) {
    c = *cap;
    if (lsys_grow(arr[i], &c, need, elem[i]) != LSYS_OK) return LSYS_ENOMEM;
  }
  *cap = c;
  return LSYS_OK;
}

/* Vertex indices are uint32_t: at most UINT32_MAX vertices (LSYS_ELIMIT). */
int lsys_mesh_reserve (lsys_mesh *m, size_t nv, size_t nt) {
  int st;
  if (nv > (size_t)UINT32_MAX - m->nv || nt > ((size_t)-1 / 12) - m->nt)
    return LSYS_ELIMIT;
  if (m->nv + nv > m->vcap) {
    void **arr[6] = { (void **)&m->pos, (void **)&m->nrm, (void **)&m->uv,
                      (void **)&m->col, (void **)&m->twosided, (void **)&m->tex };
    const size_t elem[6] = { 3 * sizeof(float), 3 * sizeof(float), 2 * sizeof(float),
                             sizeof(uint16_t), sizeof(uint8_t), sizeof(uint16_t) };
    if ((st = growall(arr, elem, 6, &m->vcap, m->nv + nv, m->meter)) != LSYS_OK) return st;
  }
  if (m->nt + nt > m->tcap &&
      (st = lsys_grow_metered((void **)&m->tri, &m->tcap, m->nt + nt, 3 * sizeof(uint32_t),
                              m->meter)) != LSYS_OK)
    return st;
  return LSYS_OK;
}

/* double to float, saturating: converting a value beyond FLT_MAX is undefined. */
static float tofloat (double x) {
  return x > FLT_MAX ? FLT_MAX : x < -FLT_MAX ? -FLT_MAX : (float)x;
}

int lsys_mesh_line (lsys_mesh *m, const double a[3], const double b[3],
                    double w0, double w1, unsigned col) {
  float *p;
  if (m->nl == m->lcap) {
    void **arr[3] = { (void **)&m->lpos, (void **)&m->lwidth, (void **)&m->lcol };
    const size_t elem[3] = { 6 * sizeof(float), 2 * sizeof(float), sizeof(uint16_t) };
    if (m->nl >= (size_t)UINT32_MAX) return LSYS_ELIMIT;
    int st;
    if ((st = growall(arr, elem, 3, &m->lcap, m->nl + 1, m->meter)) != LSYS_OK) return st;
  }
  p = m->lpos + 6 * m->nl;
  p[0] = tofloat(a[0]); p[1] = tofloat(a[1]); p[2] = tofloat(a[2]);
  p[3] = tofloat(b[0]); p[4] = tofloat(b[1]); p[5] = tofloat(b[2]);
  m->lwidth[2 * m->nl] = tofloat(w0);
  m->lwidth[2 * m->nl + 1] = tofloat(w1);
  m->lcol[m->nl] = (uint16_t)col;
  m->nl++;
  return LSYS_OK;
}

/* NaN coordinates take no part (every comparison with them is false). */
static void addbounds (const float *p, size_t n, double lo[3], double hi[3]) {
  size_t i;
  int k;
  for (i = 0; i < n; i++, p += 3)
    for (k = 0; k < 3; k++) {
      if (p[k] < lo[k]) lo[k] = p[k];
      if (p[k] > hi[k]) hi[k] = p[k];
    }
}

static int cmpedge (const void *x, const void *y) {
  const uint32_t *a = (const uint32_t *)x, *b = (const uint32_t *)y;
  return a[0] != b[0] ? (a[0] > b[0]) - (a[0] < b[0]) : (a[1] > b[1]) - (a[1] < b[1]);
}

size_t lsys_mesh_edges (const lsys_mesh *m, size_t t0, size_t nt, uint32_t *edges) {
  size_t i, n = 0, k;
  if (t0 >= m->nt) return 0;
  if (nt > m->nt - t0) nt = m->nt - t0;
  for (i = t0; i < t0 + nt; i++)
    for (k = 0; k < 3; k++) {
      uint32_t a = m->tri[3 * i + k], b = m->tri[3 * i + (k + 1) % 3];
      if (a == b) continue;                     /* degenerate */
      edges[2 * n] = a < b ? a : b;
      edges[2 * n + 1] = a < b ? b : a;
      n++;
    }
  qsort(edges, n, 2 * sizeof *edges, cmpedge);
  for (i = k = 0; i < n; i++)
    if (k == 0 || edges[2 * i] != edges[2 * k - 2] || edges[2 * i + 1] != edges[2 * k - 1]) {
      edges[2 * k] = edges[2 * i];
      edges[2 * k + 1] = edges[2 * i + 1];
      k++;
    }
  return k;
}

int lsys_mesh_bounds (const lsys_mesh *m, double lo[3], double hi[3]) {
  int k, ok = 1;
  for (k = 0; k < 3; k++) { lo[k] = HUGE_VAL; hi[k] = -HUGE_VAL; }
  addbounds(m->pos, m->nv, lo, hi);
  addbounds(m->lpos, 2 * m->nl, lo, hi);
  for (k = 0; k < 3; k++)
    if (!(lo[k] <= hi[k])) ok = 0;
  if (!ok)
    for (k = 0; k < 3; k++) lo[k] = hi[k] = 0;
  return ok;
}

static float unit (double x) {
  return x > 0 ? (x < 1 ? (float)x : 1.0f) : 0.0f;   /* NaN gives 0 */
}

void lsys_material_color (lsys_material *mt, double r, double g, double b) {
  float c[3];
  int k;
  c[0] = unit(r); c[1] = unit(g); c[2] = unit(b);
  *mt = (lsys_material){0};
  for (k = 0; k < 3; k++) {
    mt->diffuse[k] = c[k];
    mt->ambient[k] = 0.3f * c[k];
  }
  mt->diffuse[3] = mt->ambient[3] = mt->specular[3] = mt->emission[3] = 1.0f;
}

/* The material used when the palette is empty. */
static const lsys_material defmaterial = {
  {0.24f, 0.24f, 0.24f, 1}, {0.8f, 0.8f, 0.8f, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}, 0
};

/* ------------------------------------------------------------------ */
/* Buffered output                                                      */
/* ------------------------------------------------------------------ */

#define WBUFSIZE ((size_t)1 << 16)

/* A buffered writer on an atomic output file (outfile.h): the target is
** replaced only when everything was written. */
typedef struct writer {
  lsys_outfile out;
  size_t n;                /* bytes waiting in b */
  unsigned char b[WBUFSIZE];
} writer;

static void wflush (writer *w) {
  lsys_outfile_write(&w->out, w->b, w->n);
  w->n = 0;
}

/* Room for 'k' (<= WBUFSIZE) more bytes; fill them, then call wdone. */
static unsigned char *wroom (writer *w, size_t k) {
  if (w->n + k > WBUFSIZE) wflush(w);
  return w->b + w->n;
}

static void wdone (writer *w, void *end) {
  w->n = (size_t)((unsigned char *)end - w->b);
}

static void wbytes (writer *w, const void *s, size_t n) {
  const unsigned char *p = (const unsigned char *)s;
  while (n > 0) {
    size_t k = n < WBUFSIZE ? n : WBUFSIZE;
    unsigned char *d = wroom(w, k);
    memcpy(d, p, k);
    wdone(w, d + k);
    p += k; n -= k;
  }
}

static void wstr (writer *w, const char *s) {
  wbytes(w, s, strlen(s));
}

static int wopen (writer **wp, const char *path, lsys_error *e) {
  writer *w = (writer *)LSYS_MALLOC(sizeof *w);
  int st;
  if (w == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if ((st = lsys_outfile_open(&w->out, path, e)) != LSYS_OK) {
    LSYS_FREE(w);
    return st;
  }
  w->n = 0;
  *wp = w;
  return LSYS_OK;
}

/* Flushes and closes the temporary file; the target is replaced by wcommit.
** On failure the temporary file is gone and e names the target. */
static int wfinish (writer *w, lsys_error *e) {
  wflush(w);
  return lsys_outfile_finish(&w->out, e);
}

/* Finishes (when not done yet) and replaces the target; frees the writer. */
static int wcommit (writer *w, lsys_error *e) {
  int st;
  wflush(w);
  st = lsys_outfile_commit(&w->out, e);
  LSYS_FREE(w);
  return st;
}

/* Drops what was written; the target stays as it was. Frees the writer. */
static void wabort (writer *w) {
  if (w == NULL) return;
  lsys_outfile_abort(&w->out);
  LSYS_FREE(w);
}

/* ------------------------------------------------------------------ */
/* Number formatting                                                    */
/* ------------------------------------------------------------------ */

static const double P10[64] = {
  1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
  1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26, 1e27, 1e28, 1e29, 1e30, 1e31,
  1e32, 1e33, 1e34, 1e35, 1e36, 1e37, 1e38, 1e39, 1e40, 1e41, 1e42, 1e43, 1e44, 1e45, 1e46,
  1e47, 1e48, 1e49, 1e50, 1e51, 1e52, 1e53, 1e54, 1e55, 1e56, 1e57, 1e58, 1e59, 1e60, 1e61,
  1e62, 1e63
};

/* x * 10^e for |e| < 64, with a single rounding. */
static double scale10 (double x, int e) {
  return e >= 0 ? x * P10[e] : x / P10[-e];
}

static char *putuint (char *s, uint64_t u) {
  char t[20];
  int n = 0;
  do { t[n++] = (char)('0' + u % 10); u /= 10; } while (u != 0);
  while (n > 0) *s++ = t[--n];
  return s;
}

static inline float fin (float x) {
  return isfinite(x) ? x : 0.0f;
}

/*
** Writes 'f' in decimal, in the style of %g, with the fewest significant
** digits between 6 and 9 that read back as the same float (9 always do, and
** 6 cover every shorter form). Non-finite values are written as 0. At most
** 15 characters; returns the end.
**
** The digits come from a double scaled into [1e8, 1e9): a double carries 53
** bits where 9 decimal digits need 30, so they are exact except next to a
** tie, where being one unit off still stays within half a float ulp.
*/
static char *putfloat (char *s, float f) {
  double a = f, m, v;
  uint64_t M = 0;
  int e2, k, kk = 0, p, i, nd;
  char dig[9];
  if (!isfinite(a) || a == 0) { *s++ = '0'; return s; }
  if (a < 0) { *s++ = '-'; a = -a; }
  (void)frexp(a, &e2);                         /* 2^(e2-1) <= a < 2^e2 */
  k = (int)floor((e2 - 1) * 0.30102999566398120);  /* floor(log10 a), or one less */
  m = scale10(a, 8 - k);
  if (m >= 1e9) { k++; m = scale10(a, 8 - k); }
  else if (m < 1e8) { k--; m = scale10(a, 8 - k); }
  for (p = 6; p <= 9; p++) {
    kk = k;
    M = (uint64_t)(m / P10[9 - p] + 0.5);
    if (M >= (uint64_t)P10[p]) { M /= 10; kk++; }   /* rounded up to 10^p */
    if (p == 9) break;
    v = scale10((double)M, kk - p + 1);
    if (v <= FLT_MAX && (float)v == (float)a) break;     /* (float) of more is undefined */
  }
  for (i = p - 1; i >= 0; i--) { dig[i] = (char)('0' + M % 10); M /= 10; }
  for (nd = p; nd > 1 && dig[nd - 1] == '0'; nd--) {}
  k = kk;                                      /* the value is 0.d1d2... * 10^(k+1) */
  if (k >= -4 && k < 9) {
    if (k >= 0) {
      for (i = 0; i <= k; i++) *s++ = i < nd ? dig[i] : '0';
      if (nd > k + 1) {
        *s++ = '.';
        for (i = k + 1; i < nd; i++) *s++ = dig[i];
      }
    }
    else {
      *s++ = '0'; *s++ = '.';
      for (i = -1; i > k; i--) *s++ = '0';
      for (i = 0; i < nd; i++) *s++ = dig[i];
    }
  }
  else {
    *s++ = dig[0];
    if (nd > 1) {
      *s++ = '.';
      for (i = 1; i < nd; i++) *s++ = dig[i];
    }
    *s++ = 'e';
    if (k < 0) { *s++ = '-'; k = -k; } else *s++ = '+';
    if (k < 10) *s++ = '0';
    s = putuint(s, (uint64_t)k);
  }
  return s;
}

/* Three floats separated by spaces, after 'tag'; ends the line. */
static void putvec (writer *w, const char *tag, const float *v, int n) {
  char *s = (char *)wroom(w, 64);
  int k;
  while (*tag) *s++ = *tag++;
  for (k = 0; k < n; k++) {
    *s++ = ' ';
    s = putfloat(s, fin(v[k]));
  }
  *s++ = '\n';
  wdone(w, s);
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
** 32-bit numbers of the formats. */
static int checkmesh (const lsys_mesh *m, const char *path, lsys_error *e) {
  size_t t;
  if (m->nt > UINT32_MAX || m->nl > UINT32_MAX / 2 || m->nv > UINT32_MAX)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot write '%s': mesh too large", path);
  for (t = 0; t < 3 * m->nt; t++)
    if (m->tri[t] >= m->nv)
      return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                           "cannot write '%s': triangle %zu refers to vertex %lu of %zu",
                           path, t / 3 + 1, (unsigned long)m->tri[t], m->nv);
  return LSYS_OK;
}

/*
** Triangles and segments sorted by material with a counting sort. With
** textures, the triangles are first sorted by texture, so that the stable
** sort by material leaves each material's triangles in runs of one texture.
** A material slot and a texture make one exported material: slot k alone
** ('plain', for its untextured triangles and its segments) and slot k with
** texture t, in the order of the runs.
*/
typedef struct run {
  size_t first, end;           /* range of tord */
  uint32_t slot;               /* material slot */
  uint16_t tex;                /* texture index, 0 for none */
  uint8_t twosided;            /* some triangle has a two-sided vertex */
} run;

typedef struct groups {
  size_t nmat;                 /* material slots: the palette size, at least 1 */
  size_t *tfirst, *lfirst;     /* nmat + 1 offsets into tord and lord */
  uint32_t *tord, *lord;       /* triangle and segment numbers, by material */
  run *runs;                   /* the triangle runs, by slot then texture */
  size_t nruns, runcap;
  const lsys_texture *const *tex;
  size_t ntex;                 /* textures that apply; 0 when none can */
} groups;

static void freegroups (groups *g) {
  LSYS_FREE(g->tfirst); LSYS_FREE(g->lfirst);
  LSYS_FREE(g->tord); LSYS_FREE(g->lord); LSYS_FREE(g->runs);
}

/* The texture index of vertex a when its texture can be exported (it
** exists and has a file), else 0. */
static unsigned texof (const groups *g, const lsys_mesh *m, uint32_t a) {
  unsigned k = g->ntex ? m->tex[a] : 0;
  return k >= 1 && k <= g->ntex && g->tex[k - 1] != NULL && g->tex[k - 1]->path != NULL ? k : 0;
}

static int twosided (const lsys_mesh *m, const uint32_t *v) {
  return (m->twosided[v[0]] | m->twosided[v[1]] | m->twosided[v[2]]) != 0;
}

/* Colour indices are 16-bit, so more than 65536 slots are never needed:
** c % npal == c % 65536 == c when npal > 65536. Texture indices are
** 16-bit too. */
static int groupmesh (groups *g, const lsys_mesh *m, size_t npal,
                      const lsys_texture *const *tex, int ntex, const char *path,
                      lsys_error *e) {
  size_t k, t, i, nmat = npal == 0 ? 1 : (npal < 65536 ? npal : 65536);
  uint32_t *order = NULL;      /* triangles by texture, when textured */
  size_t *tcount = NULL;
  *g = (groups){0};
  g->nmat = nmat;
  if (tex != NULL && ntex > 0 && m->tex != NULL && m->nt > 0) {
    g->tex = tex;
    g->ntex = ntex < 65535 ? (size_t)ntex : 65535;
  }
  g->tfirst = (size_t *)LSYS_MALLOC((nmat + 1) * sizeof(size_t));
  g->lfirst = (size_t *)LSYS_MALLOC((nmat + 1) * sizeof(size_t));
  g->tord = (uint32_t *)LSYS_MALLOC((m->nt ? m->nt : 1) * sizeof(uint32_t));
  g->lord = (uint32_t *)LSYS_MALLOC((m->nl ? m->nl : 1) * sizeof(uint32_t));
  if (g->ntex > 0) {
    order = (uint32_t *)LSYS_MALLOC(m->nt * sizeof(uint32_t));
    tcount = (size_t *)LSYS_MALLOC((g->ntex + 2) * sizeof(size_t));
  }
  if (!g->tfirst || !g->lfirst || !g->tord || !g->lord ||
      (g->ntex > 0 && (order == NULL || tcount == NULL))) {
    LSYS_FREE(order); LSYS_FREE(tcount);
    freegroups(g);
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  }
  if (order != NULL) {                 /* by texture first (a counting sort) */
    memset(tcount, 0, (g->ntex + 2) * sizeof(size_t));
    for (t = 0; t < m->nt; t++) tcount[texof(g, m, m->tri[3 * t]) + 1]++;
    for (k = 0; k <= g->ntex; k++) tcount[k + 1] += tcount[k];
    for (t = 0; t < m->nt; t++) order[tcount[texof(g, m, m->tri[3 * t])]++] = (uint32_t)t;
    LSYS_FREE(tcount);
  }
  memset(g->tfirst, 0, (nmat + 1) * sizeof(size_t));
  memset(g->lfirst, 0, (nmat + 1) * sizeof(size_t));
  for (t = 0; t < m->nt; t++) g->tfirst[m->col[m->tri[3 * t]] % nmat + 1]++;
  for (t = 0; t < m->nl; t++) g->lfirst[m->lcol[t] % nmat + 1]++;
  for (k = 0; k < nmat; k++) {
    g->tfirst[k + 1] += g->tfirst[k];
    g->lfirst[k + 1] += g->lfirst[k];
  }
  /* fill, using tfirst[k] as the cursor of slot k, then shift back */
  for (i = 0; i < m->nt; i++) {
    t = order != NULL ? order[i] : i;
    g->tord[g->tfirst[m->col[m->tri[3 * t]] % nmat]++] = (uint32_t)t;
  }
  for (t = 0; t < m->nl; t++) g->lord[g->lfirst[m->lcol[t] % nmat]++] = (uint32_t)t;
  for (k = nmat; k > 0; k--) {
    g->tfirst[k] = g->tfirst[k - 1];
    g->lfirst[k] = g->lfirst[k - 1];
  }
  g->tfirst[0] = g->lfirst[0] = 0;
  LSYS_FREE(order);
  /* the runs: one per slot and texture */
  for (k = 0; k < nmat; k++)
    for (i = g->tfirst[k]; i < g->tfirst[k + 1];) {
      const uint32_t *v = m->tri + 3 * (size_t)g->tord[i];
      unsigned tx = texof(g, m, v[0]);
      run *r;
      if (g->nruns == g->runcap &&
          lsys_grow((void **)&g->runs, &g->runcap, g->nruns + 1, sizeof *g->runs) != LSYS_OK) {
        freegroups(g);
        return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory",
                             path);
      }
      r = &g->runs[g->nruns++];
      r->first = i;
      r->slot = (uint32_t)k;
      r->tex = (uint16_t)tx;
      r->twosided = 0;
      for (; i < g->tfirst[k + 1]; i++) {
        v = m->tri + 3 * (size_t)g->tord[i];
        if (texof(g, m, v[0]) != tx) break;
        if (twosided(m, v)) r->twosided = 1;
      }
      r->end = i;
    }
  return LSYS_OK;
}

static const lsys_material *material (const lsys_material *pal, size_t npal, size_t k) {
  return npal == 0 ? &defmaterial : &pal[k];
}

/* Whether slot k's plain material is used: by untextured triangles (the
** first run of the slot, texture 0) or by segments. 'r' is the slot's
** first run or NULL. */
static int plainused (const groups *g, size_t k, const run *r) {
  return (r != NULL && r->slot == k && r->tex == 0) || g->lfirst[k + 1] > g->lfirst[k];
}

/* ------------------------------------------------------------------ */
/* OBJ and MTL                                                          */
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

static void putrgb (writer *w, const char *tag, const float *c) {
  float v[3];
  int k;
  for (k = 0; k < 3; k++) v[k] = unit(c[k]);
  putvec(w, tag, v, 3);
}

/* "<tag> m<k>" or "<tag> m<k>_t<t>" and a newline: the name of slot k's
** material with texture t (0: none). */
static void putmtlname (writer *w, const char *tag, size_t k, unsigned t) {
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
static void putmtl (writer *w, const lsys_material *mt, size_t k, const lsys_texture *tx,
                    unsigned t) {
  static const float white[3] = {1, 1, 1};
  int spec = mt->specular[0] > 0 || mt->specular[1] > 0 || mt->specular[2] > 0;
  int decal = tx != NULL && tx->mode == LSYS_TEX_DECAL;
  float d = unit(mt->diffuse[3]);
  wstr(w, "\n");
  putmtlname(w, "newmtl", k, t);
  putrgb(w, "Ka", mt->ambient);
  putrgb(w, "Kd", decal ? white : mt->diffuse);
  putrgb(w, "Ks", mt->specular);
  putrgb(w, "Ke", mt->emission);
  putvec(w, "Ns", &mt->shininess, 1);       /* the same Phong exponent as OpenGL's */
  putvec(w, "d", &d, 1);
  wstr(w, decal ? "illum 0\n" : spec ? "illum 2\n" : "illum 1\n");
  if (tx != NULL) {
    wstr(w, "map_Kd ");
    wstr(w, tx->path);
    wstr(w, "\n");
  }
}

/* Writes the material file into *wp, finished but not committed: it
** replaces its target together with the .obj. */
static int writemtl (writer **wp, const groups *g, const lsys_material *pal, size_t npal,
                     const char *path, lsys_error *e) {
  writer *w;
  size_t k, r = 0;
  int st = wopen(&w, path, e);
  if (st != LSYS_OK) return st;
  wstr(w, "# lsys materials\n");
  for (k = 0; k < g->nmat; k++) {
    const lsys_material *mt = material(pal, npal, k);
    if (plainused(g, k, r < g->nruns ? &g->runs[r] : NULL)) putmtl(w, mt, k, NULL, 0);
    for (; r < g->nruns && g->runs[r].slot == k; r++)
      if (g->runs[r].tex > 0)
        putmtl(w, mt, k, g->tex[g->runs[r].tex - 1], g->runs[r].tex);
  }
  if ((st = wfinish(w, e)) != LSYS_OK) {
    wabort(w);
    return st;
  }
  *wp = w;
  return LSYS_OK;
}

/* "f a/a/a b/b/b c/c/c" with 1-based numbers. */
static void putface (writer *w, const uint32_t *v) {
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

static void putline (writer *w, uint64_t a) {
  char *s = (char *)wroom(w, 64);
  *s++ = 'l'; *s++ = ' ';
  s = putuint(s, a);
  *s++ = ' ';
  s = putuint(s, a + 1);
  *s++ = '\n';
  wdone(w, s);
}

/*
** OBJ layout: the positions of the mesh vertices, then two per segment in
** material order; the normals and texture coordinates of the mesh vertices
** (texture.h: v up, as OBJ has it); then, per material slot, 'usemtl m<k>'
** followed by its untextured faces and its segments ('l' elements, which
** refer to positions only), and 'usemtl m<k>_t<t>' with the faces of slot
** k textured with texture t.
*/
int lsys_mesh_save_obj (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e) {
  groups g;
  writer *w, *mw = NULL;
  const char *mtlname;
  char *mpath, head[160];
  size_t i, k, r;
  int st = checkmesh(m, path, e);
  if (st != LSYS_OK) return st;
  mpath = mtlpath(path, &mtlname);
  if (mpath == NULL)
    return lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
  if (strcmp(mpath, path) == 0) {
    LSYS_FREE(mpath);
    return lsys_seterror(e, LSYS_EARG, (size_t)-1,
                         "cannot write '%s': it would be its own material file", path);
  }
  st = wopen(&w, path, e);               /* first, so that a bad path names the .obj */
  if (st == LSYS_OK) {
    st = groupmesh(&g, m, npal, tex, ntex, path, e);
    if (st == LSYS_OK) {
      st = writemtl(&mw, &g, pal, npal, mpath, e);
      if (st != LSYS_OK) freegroups(&g);
    }
    if (st != LSYS_OK) wabort(w);
  }
  if (st != LSYS_OK) {
    LSYS_FREE(mpath);
    return st;
  }
  snprintf(head, sizeof head, "# lsys: %zu vertices, %zu triangles, %zu line segments\n",
           m->nv, m->nt, m->nl);
  wstr(w, head);
  wstr(w, "mtllib ");
  wstr(w, mtlname);
  wstr(w, "\n");
  for (i = 0; i < m->nv; i++) putvec(w, "v", m->pos + 3 * i, 3);
  for (i = 0; i < m->nl; i++) {
    const float *p = m->lpos + 6 * (size_t)g.lord[i];
    putvec(w, "v", p, 3);
    putvec(w, "v", p + 3, 3);
  }
  for (i = 0; i < m->nv; i++) putvec(w, "vn", m->nrm + 3 * i, 3);
  for (i = 0; i < m->nv; i++) putvec(w, "vt", m->uv + 2 * i, 2);
  for (k = 0, r = 0; k < g.nmat; k++) {
    const run *first = r < g.nruns && g.runs[r].slot == k ? &g.runs[r] : NULL;
    if (plainused(&g, k, first)) {
      putmtlname(w, "usemtl", k, 0);
      if (first != NULL && first->tex == 0) {
        for (i = first->first; i < first->end; i++) putface(w, m->tri + 3 * (size_t)g.tord[i]);
        r++;
      }
      for (i = g.lfirst[k]; i < g.lfirst[k + 1]; i++) putline(w, m->nv + 2 * i + 1);
    }
    for (; r < g.nruns && g.runs[r].slot == k; r++) {
      putmtlname(w, "usemtl", k, g.runs[r].tex);
      for (i = g.runs[r].first; i < g.runs[r].end; i++)
        putface(w, m->tri + 3 * (size_t)g.tord[i]);
    }
  }
  freegroups(&g);
  LSYS_FREE(mpath);
  /* both files complete before either replaces its target */
  if ((st = wfinish(w, e)) != LSYS_OK) {
    wabort(w);
    wabort(mw);
    return st;
  }
  if ((st = wcommit(mw, e)) != LSYS_OK) {
    wabort(w);
    return st;
  }
  return wcommit(w, e);
}

/* ------------------------------------------------------------------ */
/* PLY                                                                  */
/* ------------------------------------------------------------------ */

static unsigned char tobyte (float c) {
  return (unsigned char)(unit(c) * 255.0f + 0.5f);
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

/*
** PLY layout: the mesh vertices, then two vertices per line segment (normal
** and texture coordinates 0); the faces; and, when there are segments, an
** 'edge' element (vertex1, vertex2) that refers to those extra vertices.
** Vertex colours are the diffuse colours of the materials. Line widths are
** not kept. Textures are ignored (PLY has no standard way to name an
** image); the texture coordinates are there as s and t.
*/
int lsys_mesh_save_ply (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e) {
  writer *w;
  char head[1024];
  size_t i, nmat = npal == 0 ? 1 : npal;
  int n, st = checkmesh(m, path, e);
  (void)tex; (void)ntex;
  if (st != LSYS_OK) return st;
  if (m->nv + 2 * m->nl > (size_t)INT32_MAX)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "cannot write '%s': mesh too large", path);
  st = wopen(&w, path, e);
  if (st != LSYS_OK) return st;
  n = snprintf(head, sizeof head,
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
  wbytes(w, head, (size_t)n);
  if (m->nl > 0) {
    n = snprintf(head, sizeof head, "element edge %zu\nproperty int vertex1\n"
                 "property int vertex2\n", m->nl);
    wbytes(w, head, (size_t)n);
  }
  wstr(w, "end_header\n");
  for (i = 0; i < m->nv; i++) {
    unsigned char *p = wroom(w, 64);
    p = plyvertex(p, m->pos + 3 * i, m->nrm + 3 * i, m->uv + 2 * i,
                  material(pal, npal, m->col[i] % nmat));
    wdone(w, p);
  }
  for (i = 0; i < m->nl; i++) {
    const lsys_material *mt = material(pal, npal, m->lcol[i] % nmat);
    unsigned char *p = wroom(w, 128);
    p = plyvertex(p, m->lpos + 6 * i, NULL, NULL, mt);
    p = plyvertex(p, m->lpos + 6 * i + 3, NULL, NULL, mt);
    wdone(w, p);
  }
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
  return wcommit(w, e);
}

/* ------------------------------------------------------------------ */
/* glTF binary                                                          */
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
  if (s != NULL) j->n = (size_t)(putfloat(s, x) - j->p);
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

/*
** Material mapping. The base colour is the diffuse colour with its alpha
** (alphaMode BLEND below 1); the emission becomes emissiveFactor. A Phong
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
  for (i = 0; i < 4; i++) c[i] = unit(mt->diffuse[i]);
  for (i = 0; i < 3; i++) em[i] = unit(mt->emission[i]);
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

#define GLB_MAGIC  0x46546C67u     /* "glTF" */
#define GLB_JSON   0x4E4F534Au     /* "JSON" */
#define GLB_BIN    0x004E4942u     /* "BIN\0" */

/*
** GLB layout. BIN chunk: the mesh vertices interleaved (position, unit
** normal, uv with v turned to glTF's downward axis: 32 bytes each) when
** there are triangles; the triangle indices (uint32) in the order of the
** runs (material slot, then texture); the segment end points in material
** order; the texture images, each padded to 4 bytes. JSON: one scene with
** one node and one mesh; per run, a TRIANGLES primitive sharing the three
** vertex accessors with its own index accessor; per material used by
** segments, a LINES primitive with its own POSITION accessor over its run
** of end points (no indices, no normals; line widths have no glTF
** equivalent). An empty mesh gives a scene without nodes.
**
** Textures: each one used gets an image (the PNG file's bytes, embedded), a
** sampler (its filters, REPEAT wrapping) and a texture; each (slot,
** texture) pair gets a material whose baseColorTexture is it: modulate
** keeps the diffuse colour as the factor (glTF multiplies by the texel's
** RGB, also for an intensity texture of a colour image), decal uses a white
** factor and KHR_materials_unlit. A modulated texture with transparent
** texels on an opaque material is cut at alpha 1/2 (alphaMode MASK).
*/
int lsys_mesh_save_glb (const lsys_mesh *m, const lsys_material *pal, size_t npal,
                        const lsys_texture *const *tex, int ntex, const char *path,
                        lsys_error *e) {
  groups g;
  jbuf j = {0};
  writer *w;
  uint32_t *pmat = NULL;          /* slot -> glTF material of its plain material */
  uint32_t *rmat = NULL;          /* run -> glTF material */
  uint32_t *gtex = NULL;          /* texture index -> glTF texture (UINT32_MAX: unused) */
  unsigned char **img = NULL;     /* per glTF texture: the PNG bytes */
  size_t *imglen = NULL;
  uint16_t *imgtex = NULL;        /* per glTF texture: the texture index */
  size_t k, i, r, nmat = 0, nimg = 0, nacc, ntri = m->nt, nl = m->nl, nv = ntri ? m->nv : 0;
  size_t vbytes = 32 * nv, ibytes = 12 * ntri, lbytes = 24 * nl, ibase, binlen, jlen, total;
  int st = checkmesh(m, path, e), first, unlit = 0;
  float lo[3], hi[3];
  unsigned char hdr[28], *p;
  if (st != LSYS_OK) return st;
  if (nv > UINT32_MAX / 32 || ntri > UINT32_MAX / 12 || nl > UINT32_MAX / 24 ||
      (uint64_t)vbytes + ibytes + lbytes > UINT32_MAX - 1024)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "cannot write '%s': mesh too large for glTF binary (4 GiB)", path);
  st = groupmesh(&g, m, npal, tex, ntex, path, e);
  if (st != LSYS_OK) return st;
  pmat = (uint32_t *)LSYS_MALLOC(g.nmat * sizeof *pmat);
  rmat = (uint32_t *)LSYS_MALLOC((g.nruns ? g.nruns : 1) * sizeof *rmat);
  gtex = (uint32_t *)LSYS_MALLOC((g.ntex + 1) * sizeof *gtex);
  img = (unsigned char **)LSYS_MALLOC((g.ntex + 1) * sizeof *img);
  imglen = (size_t *)LSYS_MALLOC((g.ntex + 1) * sizeof *imglen);
  imgtex = (uint16_t *)LSYS_MALLOC((g.ntex + 1) * sizeof *imgtex);
  if (pmat == NULL || rmat == NULL || gtex == NULL || img == NULL || imglen == NULL ||
      imgtex == NULL) {
    st = lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
    goto done;
  }
  /* materials: per slot its plain one (if used), then one per texture run */
  for (k = 0; k <= g.ntex; k++) gtex[k] = UINT32_MAX;
  for (k = 0, r = 0; k < g.nmat; k++) {
    pmat[k] = plainused(&g, k, r < g.nruns ? &g.runs[r] : NULL) ? (uint32_t)nmat++ : 0;
    for (; r < g.nruns && g.runs[r].slot == k; r++) {
      unsigned t = g.runs[r].tex;
      rmat[r] = t == 0 ? pmat[k] : (uint32_t)nmat++;
      if (t > 0 && g.tex[t - 1]->mode == LSYS_TEX_DECAL) unlit = 1;
      if (t > 0 && gtex[t] == UINT32_MAX) {
        gtex[t] = (uint32_t)nimg;
        imgtex[nimg] = (uint16_t)t;
        img[nimg] = NULL;
        nimg++;
      }
    }
  }
  /* the images, read now: their sizes go into the JSON */
  binlen = vbytes + ibytes + lbytes;
  ibase = binlen;
  for (i = 0; i < nimg; i++) {
    st = slurpimage(g.tex[imgtex[i] - 1]->path, &img[i], &imglen[i], path, e);
    if (st != LSYS_OK) {
      nimg = i;                   /* the ones read so far are freed below */
      goto done;
    }
    if (imglen[i] > UINT32_MAX - 1024 - binlen) {
      nimg = i + 1;
      st = lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "cannot write '%s': mesh too large for glTF binary (4 GiB)", path);
      goto done;
    }
    binlen += (imglen[i] + 3) & ~(size_t)3;
  }

  jadd(&j, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"lsys\"},");
  if (unlit) jadd(&j, "\"extensionsUsed\":[\"KHR_materials_unlit\"],");
  jadd(&j, "\"scene\":0,");
  if (ntri == 0 && nl == 0) jadd(&j, "\"scenes\":[{}]}");
  else {
    size_t bv = 0, lview;
    jadd(&j, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"lsys\"}],");
    /* primitives; accessors 0-2 are the vertex attributes, then one per group */
    jadd(&j, "\"meshes\":[{\"primitives\":[");
    nacc = ntri ? 3 : 0;
    first = 1;
    for (r = 0; r < g.nruns; r++) {
      jadd(&j, "%s{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2},"
           "\"indices\":%zu,\"material\":%lu,\"mode\":4}", first ? "" : ",", nacc++,
           (unsigned long)rmat[r]);
      first = 0;
    }
    for (k = 0; k < g.nmat; k++)
      if (g.lfirst[k + 1] > g.lfirst[k]) {
        jadd(&j, "%s{\"attributes\":{\"POSITION\":%zu},\"material\":%lu,\"mode\":1}",
             first ? "" : ",", nacc++, (unsigned long)pmat[k]);
        first = 0;
      }
    jadd(&j, "]}],\"materials\":[");
    first = 1;
    for (k = 0, r = 0; k < g.nmat; k++) {
      const lsys_material *mt = material(pal, npal, k);
      const run *fr = r < g.nruns && g.runs[r].slot == k ? &g.runs[r] : NULL;
      if (plainused(&g, k, fr)) {
        jmaterial(&j, mt, k, fr != NULL && fr->tex == 0 && fr->twosided, NULL, 0, 0, first);
        first = 0;
      }
      for (; r < g.nruns && g.runs[r].slot == k; r++) {
        unsigned t = g.runs[r].tex;
        if (t == 0) continue;
        jmaterial(&j, mt, k, g.runs[r].twosided, g.tex[t - 1], t, gtex[t], first);
        first = 0;
      }
    }
    jadd(&j, "],");
    if (nimg > 0) {
      jadd(&j, "\"textures\":[");
      for (i = 0; i < nimg; i++)
        jadd(&j, "%s{\"sampler\":%zu,\"source\":%zu}", i ? "," : "", i, i);
      jadd(&j, "],\"samplers\":[");
      for (i = 0; i < nimg; i++) {
        const lsys_texture *tx = g.tex[imgtex[i] - 1];
        jadd(&j, "%s{\"magFilter\":%d,\"minFilter\":%d,\"wrapS\":10497,\"wrapT\":10497}",
             i ? "," : "", tx->mag_linear ? 9729 : 9728, tx->min_linear ? 9729 : 9728);
      }
      jadd(&j, "],\"images\":[");
      for (i = 0; i < nimg; i++)
        jadd(&j, "%s{\"bufferView\":%zu,\"mimeType\":\"image/png\"}", i ? "," : "",
             (ntri ? 2 : 0) + (nl ? 1 : 0) + i);
      jadd(&j, "],");
    }
    jadd(&j, "\"buffers\":[{\"byteLength\":%zu}],\"bufferViews\":[", binlen);
    if (ntri) {
      jadd(&j, "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"byteStride\":32,"
           "\"target\":34962},", vbytes);
      jadd(&j, "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}",
           vbytes, ibytes);
      bv = 2;
    }
    lview = bv;
    if (nl)
      jadd(&j, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"byteStride\":12,"
           "\"target\":34962}", ntri ? "," : "", vbytes + ibytes, lbytes);
    {
      size_t off = ibase;
      for (i = 0; i < nimg; i++) {
        jadd(&j, ",{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", off, imglen[i]);
        off += (imglen[i] + 3) & ~(size_t)3;
      }
    }
    jadd(&j, "],\"accessors\":[");
    first = 1;
    if (ntri) {
      minmax(m->pos, nv, 3, lo, hi);
      jadd(&j, "{\"bufferView\":0,\"byteOffset\":0,\"componentType\":5126,\"count\":%zu,"
           "\"type\":\"VEC3\"", nv);
      jvec(&j, ",\"min\":", lo, 3);
      jvec(&j, ",\"max\":", hi, 3);
      jadd(&j, "},{\"bufferView\":0,\"byteOffset\":12,\"componentType\":5126,\"count\":%zu,"
           "\"type\":\"VEC3\"},{\"bufferView\":0,\"byteOffset\":24,\"componentType\":5126,"
           "\"count\":%zu,\"type\":\"VEC2\"}", nv, nv);
      for (r = 0; r < g.nruns; r++)
        jadd(&j, ",{\"bufferView\":1,\"byteOffset\":%zu,\"componentType\":5125,"
             "\"count\":%zu,\"type\":\"SCALAR\"}", 12 * g.runs[r].first,
             3 * (g.runs[r].end - g.runs[r].first));
      first = 0;
    }
    for (k = 0; k < g.nmat; k++) {
      size_t a = g.lfirst[k], b = g.lfirst[k + 1];
      if (b == a) continue;
      lo[0] = lo[1] = lo[2] = HUGE_VALF;
      hi[0] = hi[1] = hi[2] = -HUGE_VALF;
      for (i = a; i < b; i++) {
        float l2[3], h2[3];
        int c;
        minmax(m->lpos + 6 * (size_t)g.lord[i], 2, 3, l2, h2);
        for (c = 0; c < 3; c++) {
          if (l2[c] < lo[c]) lo[c] = l2[c];
          if (h2[c] > hi[c]) hi[c] = h2[c];
        }
      }
      jadd(&j, "%s{\"bufferView\":%zu,\"byteOffset\":%zu,\"componentType\":5126,"
           "\"count\":%zu,\"type\":\"VEC3\"", first ? "" : ",", lview, 24 * a, 2 * (b - a));
      jvec(&j, ",\"min\":", lo, 3);
      jvec(&j, ",\"max\":", hi, 3);
      jadd(&j, "}");
      first = 0;
    }
    jadd(&j, "]}");
  }
  while (!j.err && j.n % 4 != 0) jadd(&j, " ");
  jlen = j.n;
  total = 12 + 8 + jlen + (binlen ? 8 + binlen : 0);
  if (j.err || jlen > UINT32_MAX - 1024 || total > UINT32_MAX) {
    if (j.err)
      st = lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "cannot write '%s': out of memory", path);
    else
      st = lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                         "cannot write '%s': mesh too large for glTF binary (4 GiB)", path);
    goto done;
  }
  st = wopen(&w, path, e);
  if (st != LSYS_OK) goto done;
  p = put32(hdr, GLB_MAGIC);
  p = put32(p, 2);
  p = put32(p, (uint32_t)total);
  p = put32(p, (uint32_t)jlen);
  p = put32(p, GLB_JSON);
  wbytes(w, hdr, (size_t)(p - hdr));
  wbytes(w, j.p, jlen);
  if (binlen) {
    p = put32(hdr, (uint32_t)binlen);
    p = put32(p, GLB_BIN);
    wbytes(w, hdr, (size_t)(p - hdr));
  }
  for (i = 0; i < nv; i++) {
    const float *n = m->nrm + 3 * i;
    double x = fin(n[0]), y = fin(n[1]), z = fin(n[2]), len = sqrt(x * x + y * y + z * z);
    int c;
    p = wroom(w, 32);
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
  for (i = 0; i < ntri; i++) {
    const uint32_t *t = m->tri + 3 * (size_t)g.tord[i];
    p = wroom(w, 12);
    p = put32(p, t[0]); p = put32(p, t[1]); p = put32(p, t[2]);
    wdone(w, p);
  }
  for (i = 0; i < nl; i++) {
    const float *q = m->lpos + 6 * (size_t)g.lord[i];
    int c;
    p = wroom(w, 24);
    for (c = 0; c < 6; c++) p = putf32(p, fin(q[c]));
    wdone(w, p);
  }
  for (i = 0; i < nimg; i++) {
    static const unsigned char zero[4] = {0, 0, 0, 0};
    wbytes(w, img[i], imglen[i]);
    wbytes(w, zero, (4 - imglen[i] % 4) % 4);
  }
  st = wcommit(w, e);
done:
  for (i = 0; img != NULL && i < nimg; i++) LSYS_FREE(img[i]);
  LSYS_FREE(img); LSYS_FREE(imglen); LSYS_FREE(imgtex);
  LSYS_FREE(pmat); LSYS_FREE(rmat); LSYS_FREE(gtex);
  LSYS_FREE(j.p);
  freegroups(&g);
  return st;
}
