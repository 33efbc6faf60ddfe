/*
** Incremental growth: the limb table and its geometry updated in place
** (grow.h; Davison, "Incremental rules for growing plants").
*/
#include <math.h>
#include <string.h>

#include "grow.h"
#include "vec3.h"

#define RAD (PI / 180.0)

enum { OP_LEAVES = 1, OP_DROP, OP_REMOVE };

/* chg bits: what changed since the last update */
enum { C_NEW = 1, C_LEN = 2, C_RAD = 4, C_ROT = 8, C_COL = 16, C_LEAF = 32, C_XF = 64 };

#define LEAF_TILT 50.0                   /* degrees between a leaf and its limb's heading */
#define GOLDEN 137.50776405003785        /* degrees between successive leaves around it */

/* The built-in leaf shape (lsys_grow_set_leaf): a rhombus 1 long, 0.5 wide. */
static const float QUAD_POS[12] = {0, 0, 0, -0.25f, 0.5f, 0, 0, 1, 0, 0.25f, 0.5f, 0};
static const float QUAD_NRM[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
static const float QUAD_UV[8] = {0.5f, 0, 1, 0.5f, 0.5f, 1, 0, 0.5f};
static const uint32_t QUAD_TRI[6] = {0, 1, 2, 0, 2, 3};

static void quadleaf (lsys_limbs *g) {
  g->sh_pos = QUAD_POS;
  g->sh_nrm = QUAD_NRM;
  g->sh_uv = QUAD_UV;
  g->sh_tri = QUAD_TRI;
  g->sh_nv = 4;
  g->sh_nt = 2;
  g->sh_mem = NULL;
}

void lsys_grow_init (lsys_limbs *g, lsys_scene *sc, int sides) {
  int k;
  memset(g, 0, sizeof *g);
  g->sc = sc;
  sc->cull = 1;                 /* closed tubes, wound counterclockwise: back faces hide */
  g->sides = sides < 3 ? 3 : sides > LSYS_LIMBS_MAXSIDES ? LSYS_LIMBS_MAXSIDES : sides;
  for (k = 0; k < g->sides; k++) {
    g->ring[2 * k] = cos(2 * PI * k / g->sides);
    g->ring[2 * k + 1] = sin(2 * PI * k / g->sides);
  }
  g->lf_free = -1;
  quadleaf(g);
}

void lsys_grow_free (lsys_limbs *g) {
  void *arrs[] = {
    g->parent, g->plant, g->first, g->next, g->last, g->prev, g->level, g->tag, g->age, g->flag, g->chg, g->len,
    g->rad, g->nlen, g->nrad, g->rgb, g->nrgb, g->loc, g->nloc, g->at, g->wp, g->wm, g->v0,
    g->t0, g->col, g->leaf, g->nleaves, g->lf_limb, g->lf_next, g->lf_k, g->lf_v0, g->lf_t0,
    g->lf_size, g->lf_col, g->freelimb, g->freeleaf, g->ppos, g->pcount,
    g->pending, g->qmap, g->sh_mem
  };
  size_t k, maxlimbs = g->maxlimbs, maxmem = g->max_memory, hl = g->held_limb,
         hp = g->held_plant;
  for (k = 0; k < sizeof arrs / sizeof arrs[0]; k++) LSYS_FREE(arrs[k]);
  lsys_grow_init(g, g->sc, g->sides);
  g->maxlimbs = maxlimbs;             /* the settings stay */
  g->max_memory = maxmem;
  g->held_limb = hl;
  g->held_plant = hp;
}

/* {======================================================================
** Storage
** ======================================================================= */

/* Arrays that grow together: each to 'need' elements of its size, from *cap
** (doubling), as far as the meter 'mt' allows (lsys_common_meter_take: LSYS_EMEMORY
** when not even 'need' fit). The arrays grown before a failure keep their data. */
typedef struct soa { void **p; size_t size; } soa;

static size_t rowbytes (const soa *a, size_t n) {
  size_t k, sum = 0;
  for (k = 0; k < n; k++) sum += a[k].size;
  return sum;
}

static int growsoa (const soa *a, size_t n, size_t *cap, size_t need, lsys_meter *mt) {
  size_t ncap, k;
  int st;
  if (need <= *cap) return LSYS_OK;
  if ((st = lsys_common_meter_take(mt, *cap, need, rowbytes(a, n), &ncap)) != LSYS_OK) return st;
  for (k = 0; k < n; k++) {
    void *q = LSYS_REALLOC(*a[k].p, ncap * a[k].size);
    if (q == NULL) return LSYS_ENOMEM;
    *a[k].p = q;
  }
  *cap = ncap;
  return LSYS_OK;
}

/* The per-limb, per-leaf and per-plant arrays of g (NLIMB, NLEAF, NPLANT of them). */
#define NLIMB 27
#define NLEAF 7
#define NPLANT 2

static void limbarrays (lsys_limbs *g, soa a[NLIMB]) {
  const soa t[NLIMB] = {
    {(void **)&g->parent, 4}, {(void **)&g->plant, 4}, {(void **)&g->first, 4},
    {(void **)&g->next, 4}, {(void **)&g->last, 4}, {(void **)&g->prev, 4},
    {(void **)&g->level, 2}, {(void **)&g->tag, 2},
    {(void **)&g->age, 4},
    {(void **)&g->flag, 1}, {(void **)&g->chg, 1}, {(void **)&g->len, 8},
    {(void **)&g->rad, 8}, {(void **)&g->nlen, 8}, {(void **)&g->nrad, 8},
    {(void **)&g->rgb, 12}, {(void **)&g->nrgb, 12}, {(void **)&g->loc, 72},
    {(void **)&g->nloc, 72}, {(void **)&g->at, 8}, {(void **)&g->wp, 24},
    {(void **)&g->wm, 72}, {(void **)&g->v0, 4}, {(void **)&g->t0, 4}, {(void **)&g->col, 2},
    {(void **)&g->leaf, 4}, {(void **)&g->nleaves, 4}
  };
  memcpy(a, t, sizeof t);
}

static void leafarrays (lsys_limbs *g, soa a[NLEAF]) {
  const soa t[NLEAF] = {
    {(void **)&g->lf_limb, 4}, {(void **)&g->lf_next, 4}, {(void **)&g->lf_k, 4},
    {(void **)&g->lf_v0, 4}, {(void **)&g->lf_t0, 4}, {(void **)&g->lf_size, 4},
    {(void **)&g->lf_col, 2}
  };
  memcpy(a, t, sizeof t);
}

static void plantarrays (lsys_limbs *g, soa a[NPLANT]) {
  const soa t[NPLANT] = {
    {(void **)&g->ppos, 3 * sizeof *g->ppos}, {(void **)&g->pcount, sizeof *g->pcount}
  };
  memcpy(a, t, sizeof t);
}

size_t lsys_grow_bytes (const lsys_limbs *g) {
  lsys_limbs *w = (lsys_limbs *)g;          /* the descriptors only name its arrays */
  soa l[NLIMB], f[NLEAF], p[NPLANT];
  double b;
  limbarrays(w, l);
  leafarrays(w, f);
  plantarrays(w, p);
  b = (double)g->cap * rowbytes(l, NLIMB) + (double)g->lcap * rowbytes(f, NLEAF) +
      (double)g->pcap * rowbytes(p, NPLANT) +
      (double)(g->capfreelimb + g->capfreeleaf) * 2 * sizeof(uint32_t) +
      (double)g->cappend * sizeof *g->pending + (g->qmap ? 32768.0 * sizeof *g->qmap : 0) +
      (g->sh_mem ? 8.0 * g->sh_nv * sizeof(float) + 3.0 * g->sh_nt * sizeof(uint32_t) : 0) +
      (double)g->n * g->held_limb + (double)g->np * g->held_plant +
      (double)lsys_scene_bytes(g->sc);
  return b < (double)SIZE_MAX ? (size_t)b : SIZE_MAX;
}

/* A meter of g's budget, counting what g holds now. */
static void gmeter (const lsys_limbs *g, lsys_meter *mt) {
  mt->limit = g->max_memory > 0 ? g->max_memory : lsys_common_memory_limit();
  mt->used = lsys_grow_bytes(g);
  mt->hit = 0;
  mt->lock = NULL;
}

/* Room for 'more' bytes the caller keeps (a limb's or a plant's), then for
** 'need' items of the arrays a[n] (capacity *cap), within g's budget. */
static int reserve (lsys_limbs *g, size_t more, const soa *a, size_t n, size_t *cap,
                    size_t need) {
  lsys_meter mt;
  gmeter(g, &mt);
  if (!lsys_common_meter_fits(&mt, more)) return LSYS_EMEMORY;
  mt.used += more;
  return growsoa(a, n, cap, need, &mt);
}

int lsys_grow_plant (lsys_limbs *g, const double pos[3], int32_t *id) {
  soa a[NPLANT];
  int r;
  if (g->np >= INT32_MAX) return LSYS_ELIMIT;
  plantarrays(g, a);
  if ((r = reserve(g, g->held_plant, a, NPLANT, &g->pcap, g->np + 1)) != LSYS_OK) return r;
  vcopy(g->ppos + 3 * g->np, pos);
  g->pcount[g->np] = 0;
  *id = (int32_t)g->np++;
  return LSYS_OK;
}

int lsys_grow_set_leaf (lsys_limbs *g, const lsys_mesh *shape) {
  size_t k, nv, nt;
  float *f;
  uint32_t *t;
  if (g->nl > 0) return LSYS_EBUSY;
  if (shape == NULL) {
    LSYS_FREE(g->sh_mem);
    quadleaf(g);
    return LSYS_OK;
  }
  nv = shape->nv;
  nt = shape->nt;
  if (nt == 0 || nv > LSYS_LIMBS_MAXLEAFV || nt > 4 * (size_t)LSYS_LIMBS_MAXLEAFV)
    return LSYS_EARG;
  for (k = 0; k < 3 * nt; k++) if (shape->tri[k] >= nv) return LSYS_EARG;
  for (k = 0; k < 3 * nv; k++)
    if (!isfinite(shape->pos[k]) || !isfinite(shape->nrm[k])) return LSYS_EARG;
  f = (float *)LSYS_MALLOC(8 * nv * sizeof *f + 3 * nt * sizeof *t);
  if (f == NULL) return LSYS_ENOMEM;
  t = (uint32_t *)(f + 8 * nv);
  memcpy(f, shape->pos, 3 * nv * sizeof *f);
  memcpy(f + 3 * nv, shape->nrm, 3 * nv * sizeof *f);
  memcpy(f + 6 * nv, shape->uv, 2 * nv * sizeof *f);
  memcpy(t, shape->tri, 3 * nt * sizeof *t);
  LSYS_FREE(g->sh_mem);
  g->sh_mem = f;
  g->sh_pos = f;
  g->sh_nrm = f + 3 * nv;
  g->sh_uv = f + 6 * nv;
  g->sh_tri = t;
  g->sh_nv = (uint32_t)nv;
  g->sh_nt = (uint32_t)nt;
  return LSYS_OK;
}

int lsys_grow_alive (const lsys_limbs *g, int32_t i) {
  return i >= 0 && (size_t)i < g->n && (g->flag[i] & LSYS_LIMB_ALIVE);
}

/* }====================================================================== */

/* {======================================================================
** Frames
** ======================================================================= */

/* v rotated about the unit axis k by 'deg' degrees (right hand). */
static void rot (double v[3], const double k[3], double deg) { vrotate(v, k, deg * RAD); }

/* The rotation (columns R, H, F, in the parent's frame) of a roll about y,
** then 'angle' about 'axis' rolled with it. */
static int localrot (const double axis[3], double angle, double roll, double m[9]) {
  static const double Y[3] = {0, 1, 0};
  double ax[3];
  int k;
  vcopy(ax, axis);
  if (!vnorm(ax)) return LSYS_EARG;
  memset(m, 0, 9 * sizeof *m);
  m[0] = m[4] = m[8] = 1;
  rot(ax, Y, roll);
  for (k = 0; k < 3; k++) {
    rot(m + 3 * k, Y, roll);
    rot(m + 3 * k, ax, angle);
  }
  return LSYS_OK;
}

/* out = A * B (3 x 3, columns) */
static void matmul (const double A[9], const double B[9], double out[9]) {
  int c, r;
  for (c = 0; c < 3; c++)
    for (r = 0; r < 3; r++)
      out[3 * c + r] = A[r] * B[3 * c] + A[3 + r] * B[3 * c + 1] + A[6 + r] * B[3 * c + 2];
}

/* The world frame of limb i from its parent's (or its plant's position). */
static void worldframe (lsys_limbs *g, int32_t i) {
  int32_t p = g->parent[i];
  if (p < 0) {
    vcopy(g->wp + 3 * i, g->ppos + 3 * g->plant[i]);
    memcpy(g->wm + 9 * i, g->loc + 9 * i, 9 * sizeof(double));
  } else {
    const double *H = g->wm + 9 * p + 3;
    double d = g->len[p] * g->at[i];
    vlin(g->wp + 3 * i, g->wp + 3 * p, 1, H, d);
    matmul(g->wm + 9 * p, g->loc + 9 * i, g->wm + 9 * i);
  }
}

void lsys_grow_tip (const lsys_limbs *g, int32_t i, double tip[3]) {
  vlin(tip, g->wp + 3 * i, 1, g->wm + 9 * i + 3, g->len[i]);
}

/* }====================================================================== */

/* {======================================================================
** Colours
** ======================================================================= */

static double clamp01 (double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

/* The palette index of rgb quantized to 5 bits a channel (interned). */
static int colorindex (lsys_limbs *g, const float rgb[3], uint16_t *idx) {
  int q[3], k, key;
  if (g->qmap == NULL) {
    g->qmap = (uint16_t *)LSYS_MALLOC(32768 * sizeof *g->qmap);
    if (g->qmap == NULL) return LSYS_ENOMEM;
    memset(g->qmap, 0, 32768 * sizeof *g->qmap);
  }
  for (k = 0; k < 3; k++) q[k] = (int)floor(clamp01(rgb[k]) * 31 + 0.5);
  key = (q[0] << 10) | (q[1] << 5) | q[2];
  if (g->qmap[key] == 0) {
    lsys_material m;
    size_t at;
    int r;
    lsys_mesh_material_color(&m, q[0] / 31.0, q[1] / 31.0, q[2] / 31.0);
    if ((r = lsys_scene_add_material(g->sc, &m, &at)) != LSYS_OK) return r;
    if (at >= 65535) return LSYS_ELIMIT;
    g->qmap[key] = (uint16_t)(at + 1);
  }
  *idx = (uint16_t)(g->qmap[key] - 1);
  return LSYS_OK;
}

/* }====================================================================== */

/* {======================================================================
** Limbs and their state
** ======================================================================= */

static int isfin (double x) { return isfinite(x); }

int lsys_grow_add (lsys_limbs *g, const lsys_limbspec *s, int32_t *id) {
  int32_t i, p = s->parent;
  double m[9];
  soa a[NLIMB];
  int k, r;
  if (p >= 0 ? !lsys_grow_alive(g, p) : (s->plant < 0 || (size_t)s->plant >= g->np))
    return LSYS_EARG;
  if (!(isfin(s->length) && s->length >= 0 && isfin(s->radius) && s->radius >= 0 &&
        isfin(s->at) && s->at >= 0 && s->at <= 1 && isfin(s->angle) && isfin(s->roll)))
    return LSYS_EARG;
  for (k = 0; k < 3; k++)
    if (!isfin(s->axis[k]) || !isfinite(s->rgb[k])) return LSYS_EARG;
  if (localrot(s->axis, s->angle, s->roll, m) != LSYS_OK) return LSYS_EARG;
  if (g->maxlimbs > 0 && g->nalive >= g->maxlimbs) return LSYS_ELIMIT;
  if (g->n >= INT32_MAX - 1) return LSYS_ELIMIT;
  limbarrays(g, a);
  if ((r = reserve(g, g->held_limb, a, NLIMB, &g->cap, g->n + 1)) != LSYS_OK) return r;
  i = (int32_t)g->n++;
  g->parent[i] = p;
  g->plant[i] = p >= 0 ? g->plant[p] : s->plant;
  g->first[i] = g->last[i] = g->next[i] = -1;
  g->prev[i] = p >= 0 ? g->last[p] : -1;
  if (p >= 0) {                      /* appended last among its siblings */
    if (g->last[p] >= 0) g->next[g->last[p]] = i;
    else g->first[p] = i;
    g->last[p] = i;
  }
  g->level[i] = (uint16_t)(p >= 0 ? (g->level[p] < 65535 ? g->level[p] + 1 : 65535) : 1);
  g->age[i] = 0;
  g->tag[i] = s->tag;
  g->flag[i] = LSYS_LIMB_ALIVE;
  g->chg[i] = C_NEW;
  g->len[i] = g->nlen[i] = s->length;
  g->rad[i] = g->nrad[i] = s->radius;
  for (k = 0; k < 3; k++) g->rgb[3 * i + k] = g->nrgb[3 * i + k] = (float)clamp01(s->rgb[k]);
  memcpy(g->loc + 9 * i, m, sizeof m);
  memcpy(g->nloc + 9 * i, m, sizeof m);
  g->at[i] = s->at;
  g->v0[i] = g->t0[i] = UINT32_MAX;     /* no range yet: lsys_grow_update gives one */
  g->leaf[i] = -1;
  g->nleaves[i] = 0;
  g->nalive++;
  g->pcount[g->plant[i]]++;
  g->dirty = 1;
  *id = i;
  return LSYS_OK;
}

/* Whether limb i can be changed (it lives). */
static int settable (lsys_limbs *g, int32_t i) { return lsys_grow_alive(g, i); }

int lsys_grow_set_length (lsys_limbs *g, int32_t i, double len) {
  if (!settable(g, i) || !isfin(len) || len < 0) return LSYS_EARG;
  g->nlen[i] = len;
  if (!g->intick) g->len[i] = len;
  g->chg[i] |= C_LEN;
  g->dirty = 1;
  return LSYS_OK;
}

int lsys_grow_set_radius (lsys_limbs *g, int32_t i, double r) {
  if (!settable(g, i) || !isfin(r) || r < 0) return LSYS_EARG;
  g->nrad[i] = r;
  if (!g->intick) g->rad[i] = r;
  g->chg[i] |= C_RAD;
  g->dirty = 1;
  return LSYS_OK;
}

int lsys_grow_set_color (lsys_limbs *g, int32_t i, const float rgb[3]) {
  int k;
  if (!settable(g, i)) return LSYS_EARG;
  for (k = 0; k < 3; k++) if (!isfinite(rgb[k])) return LSYS_EARG;
  for (k = 0; k < 3; k++) {
    g->nrgb[3 * i + k] = (float)clamp01(rgb[k]);
    if (!g->intick) g->rgb[3 * i + k] = g->nrgb[3 * i + k];
  }
  g->chg[i] |= C_COL;
  g->dirty = 1;
  return LSYS_OK;
}

int lsys_grow_set_turn (lsys_limbs *g, int32_t i, const double axis[3], double angle,
                        double roll) {
  double m[9];
  if (!settable(g, i) || !isfin(angle) || !isfin(roll) || !isfin(axis[0]) ||
      !isfin(axis[1]) || !isfin(axis[2]) || localrot(axis, angle, roll, m) != LSYS_OK)
    return LSYS_EARG;
  memcpy(g->nloc + 9 * i, m, sizeof m);
  if (!g->intick) memcpy(g->loc + 9 * i, m, sizeof m);
  g->chg[i] |= C_ROT;
  g->dirty = 1;
  return LSYS_OK;
}

static int defer (lsys_limbs *g, int op, int32_t i, int n, double size, const float *rgb) {
  lsys_limbop *o;
  lsys_meter mt;
  int r;
  gmeter(g, &mt);
  r = lsys_common_grow_metered((void **)&g->pending, &g->cappend, g->npend + 1, sizeof *g->pending,
                               &mt);
  if (r != LSYS_OK) return r;
  o = &g->pending[g->npend++];
  o->op = op; o->limb = i; o->n = n; o->size = size;
  o->rgb[0] = rgb ? rgb[0] : 0; o->rgb[1] = rgb ? rgb[1] : 0; o->rgb[2] = rgb ? rgb[2] : 0;
  g->dirty = 1;
  return LSYS_OK;
}

int lsys_grow_add_leaves (lsys_limbs *g, int32_t i, int n, double size, const float rgb[3]) {
  if (!settable(g, i) || n < 0 || n > 1000 || !isfin(size) || size < 0 ||
      !isfinite(rgb[0]) || !isfinite(rgb[1]) || !isfinite(rgb[2]))
    return LSYS_EARG;
  return n == 0 ? LSYS_OK : defer(g, OP_LEAVES, i, n, size, rgb);
}

int lsys_grow_drop_leaves (lsys_limbs *g, int32_t i) {
  if (!settable(g, i)) return LSYS_EARG;
  return defer(g, OP_DROP, i, 0, 0, NULL);
}

int lsys_grow_remove (lsys_limbs *g, int32_t i) {
  if (!settable(g, i)) return LSYS_EARG;
  return defer(g, OP_REMOVE, i, 0, 0, NULL);
}

/* }====================================================================== */

/* {======================================================================
** Geometry
** ======================================================================= */

/* Collapses vertices [v0, v0 + nv) onto their first: their triangles vanish. */
static void degenerate (lsys_limbs *g, uint32_t v0, uint32_t nv) {
  float *P = g->sc->mesh.pos + 3 * (size_t)v0;
  uint32_t k;
  for (k = 1; k < nv; k++) memcpy(P + 3 * k, P, 3 * sizeof *P);
  lsys_scene_touch(g->sc, v0, nv);
}

static int pushrange (uint32_t **a, size_t *n, size_t *cap, uint32_t v0, uint32_t t0) {
  if (lsys_common_grow((void **)a, cap, *n + 1, 2 * sizeof **a) != LSYS_OK) return LSYS_ENOMEM;
  (*a)[2 * *n] = v0;
  (*a)[2 * *n + 1] = t0;
  (*n)++;
  return LSYS_OK;
}

/* A range of vertices and triangles for a new limb or leaf: a freed one, or
** appended with its triangles (a cylinder's, or the leaf shape's). */
static int newrange (lsys_limbs *g, int leaf, uint32_t *v0, uint32_t *t0) {
  lsys_mesh *m = &g->sc->mesh;
  uint32_t nv = leaf ? g->sh_nv : 2 * (uint32_t)g->sides, nt = leaf ? g->sh_nt : nv, k;
  uint32_t *fl = leaf ? g->freeleaf : g->freelimb;
  size_t *nf = leaf ? &g->nfreeleaf : &g->nfreelimb;
  int r;
  if (*nf > 0) {
    (*nf)--;
    *v0 = fl[2 * *nf];
    *t0 = fl[2 * *nf + 1];
    return LSYS_OK;
  }
  {                                   /* the mesh grows within g's budget */
    lsys_meter mt, *old = m->meter;
    gmeter(g, &mt);
    m->meter = &mt;
    r = lsys_mesh_reserve(m, nv, nt);
    m->meter = old;
    if (r != LSYS_OK) return r;
  }
  *v0 = (uint32_t)m->nv;
  *t0 = (uint32_t)m->nt;
  memset(m->pos + 3 * m->nv, 0, 3 * nv * sizeof *m->pos);
  memset(m->nrm + 3 * m->nv, 0, 3 * nv * sizeof *m->nrm);
  memset(m->uv + 2 * m->nv, 0, 2 * nv * sizeof *m->uv);
  memset(m->col + m->nv, 0, nv * sizeof *m->col);
  memset(m->twosided + m->nv, leaf ? 1 : 0, nv);
  memset(m->tex + m->nv, 0, nv * sizeof *m->tex);
  m->nv += nv;
  if (leaf) {
    memcpy(m->uv + 2 * (size_t)*v0, g->sh_uv, 2 * nv * sizeof *m->uv);
    for (k = 0; k < nt; k++) {
      const uint32_t *t = g->sh_tri + 3 * k;
      lsys_mesh_tri(m, *v0 + t[0], *v0 + t[1], *v0 + t[2]);
    }
  } else {
    uint32_t S = (uint32_t)g->sides;
    for (k = 0; k < S; k++) {           /* around, and 0 at the base, 1 at the tip */
      m->uv[2 * (*v0 + k)] = m->uv[2 * (*v0 + S + k)] = (float)k / (float)S;
      m->uv[2 * (*v0 + S + k) + 1] = 1;
    }
    for (k = 0; k < S; k++) {           /* ring 0 at the base, ring 1 at the tip */
      uint32_t a = *v0 + k, b = *v0 + (k + 1) % S;
      lsys_mesh_tri(m, a, b + S, b);        /* counterclockwise seen from outside */
      lsys_mesh_tri(m, a, a + S, b + S);
    }
  }
  return LSYS_OK;
}

/* The cylinder of limb i from its base to its tip: positions, normals and
** colours (its texture coordinates were written with its range). */
static void writelimb (lsys_limbs *g, int32_t i) {
  lsys_mesh *m = &g->sc->mesh;
  const double *R = g->wm + 9 * i, *F = R + 6, *b = g->wp + 3 * i;
  double r = g->rad[i], tip[3];
  uint32_t S = (uint32_t)g->sides, k, v0 = g->v0[i];
  uint16_t col = g->col[i];
  lsys_grow_tip(g, i, tip);
  for (k = 0; k < S; k++) {
    double c = g->ring[2 * k], s = g->ring[2 * k + 1];
    float *P0 = m->pos + 3 * (size_t)(v0 + k), *P1 = m->pos + 3 * (size_t)(v0 + S + k);
    float *N0 = m->nrm + 3 * (size_t)(v0 + k), *N1 = m->nrm + 3 * (size_t)(v0 + S + k);
    int j;
    for (j = 0; j < 3; j++) {
      double n = R[j] * c + F[j] * s;
      P0[j] = (float)(b[j] + n * r);
      P1[j] = (float)(tip[j] + n * r);
      N0[j] = N1[j] = (float)n;
    }
    m->col[v0 + k] = m->col[v0 + S + k] = col;
  }
  lsys_scene_touch(g->sc, v0, 2 * S);
}

/* Leaf l: the leaf shape at the tip of its limb, scaled by its size, its y
** tilted LEAF_TILT degrees from the limb's heading towards the k-th leaf's
** direction (the golden angle apart about the heading), its z the leaf's
** normal. */
static void writeleaf (lsys_limbs *g, int32_t l) {
  lsys_mesh *m = &g->sc->mesh;
  int32_t i = g->lf_limb[l];
  const double *R = g->wm + 9 * i, *H = R + 3, *F = R + 6;
  double phi = GOLDEN * g->lf_k[l] * RAD, tilt = LEAF_TILT * RAD, s = g->lf_size[l];
  double tip[3], radial[3], y[3], w[3], x[3], z[3];
  uint32_t v0 = g->lf_v0[l], k, nv = g->sh_nv;
  uint16_t c = g->lf_col[l];
  lsys_grow_tip(g, i, tip);
  vlin(radial, R, cos(phi), F, sin(phi));
  vlin(y, H, cos(tilt), radial, sin(tilt));
  vlin(w, R, -sin(phi), F, cos(phi));
  vcross(z, y, w);
  vnorm(z);
  vcross(x, y, z);
  for (k = 0; k < nv; k++) {
    const float *a = g->sh_pos + 3 * k, *b = g->sh_nrm + 3 * k;
    float *P = m->pos + 3 * (size_t)(v0 + k), *N = m->nrm + 3 * (size_t)(v0 + k);
    int j;
    for (j = 0; j < 3; j++) {
      P[j] = (float)(tip[j] + s * (a[0] * x[j] + a[1] * y[j] + a[2] * z[j]));
      N[j] = (float)(b[0] * x[j] + b[1] * y[j] + b[2] * z[j]);
    }
    m->col[v0 + k] = c;
  }
  lsys_scene_touch(g->sc, v0, nv);
}

static void recolor (lsys_limbs *g, int32_t i) {
  lsys_mesh *m = &g->sc->mesh;
  uint32_t k, nv = 2 * (uint32_t)g->sides;
  for (k = 0; k < nv; k++) m->col[g->v0[i] + k] = g->col[i];
  lsys_scene_touch(g->sc, g->v0[i], nv);
}

/* }====================================================================== */

/* {======================================================================
** Leaves, removal, the tick
** ======================================================================= */

/* The leaves of op o; each one made is taken off o->n, so that a retry after a
** failure makes only the rest. */
static int addleaves (lsys_limbs *g, lsys_limbop *o) {
  int r;
  uint16_t c;
  if (!lsys_grow_alive(g, o->limb)) return LSYS_OK;
  if ((r = colorindex(g, o->rgb, &c)) != LSYS_OK) return r;
  while (o->n > 0) {
    int32_t l;
    if (g->lf_free >= 0) { l = g->lf_free; g->lf_free = g->lf_next[l]; }
    else {
      soa a[NLEAF];
      if (g->nl >= INT32_MAX - 1) return LSYS_ENOMEM;
      leafarrays(g, a);
      if ((r = reserve(g, 0, a, NLEAF, &g->lcap, g->nl + 1)) != LSYS_OK) return r;
      l = (int32_t)g->nl++;
    }
    if ((r = newrange(g, 1, &g->lf_v0[l], &g->lf_t0[l])) != LSYS_OK) {
      g->lf_limb[l] = -1; g->lf_next[l] = g->lf_free; g->lf_free = l;
      return r;
    }
    g->lf_limb[l] = o->limb;
    g->lf_k[l] = g->nleaves[o->limb]++;
    g->lf_size[l] = (float)o->size;
    g->lf_col[l] = c;
    g->lf_next[l] = g->leaf[o->limb];
    g->leaf[o->limb] = l;
    g->chg[o->limb] |= C_LEAF;
    o->n--;
  }
  return LSYS_OK;
}

static int dropleaves (lsys_limbs *g, int32_t i) {
  int32_t l = g->leaf[i];
  while (l >= 0) {
    int32_t nx = g->lf_next[l];
    degenerate(g, g->lf_v0[l], g->sh_nv);
    if (pushrange(&g->freeleaf, &g->nfreeleaf, &g->capfreeleaf, g->lf_v0[l], g->lf_t0[l])
        != LSYS_OK) return LSYS_ENOMEM;
    g->lf_limb[l] = -1;
    g->lf_next[l] = g->lf_free;
    g->lf_free = l;
    l = nx;
  }
  g->leaf[i] = -1;
  g->nleaves[i] = 0;
  return LSYS_OK;
}

/* Frees the geometry of one limb of a subtree being removed and marks it dead. */
static int killone (lsys_limbs *g, int32_t c) {
  int r;
  if ((r = dropleaves(g, c)) != LSYS_OK) return r;
  if (g->v0[c] != UINT32_MAX) {
    degenerate(g, g->v0[c], 2 * (uint32_t)g->sides);
    if (pushrange(&g->freelimb, &g->nfreelimb, &g->capfreelimb, g->v0[c], g->t0[c]) != LSYS_OK)
      return LSYS_ENOMEM;
    g->v0[c] = g->t0[c] = UINT32_MAX;
  }
  g->flag[c] &= (uint8_t)~LSYS_LIMB_ALIVE;
  g->nalive--;
  g->pcount[g->plant[c]]--;
  return LSYS_OK;
}

/* Removes limb i and its subtree (walked in preorder without recursion: a
** plant may be a chain of any depth); ids stay, ranges are freed for reuse. */
static int removelimb (lsys_limbs *g, int32_t i) {
  int32_t c = i, p = g->parent[i];
  int r;
  if (!lsys_grow_alive(g, i)) return LSYS_OK;
  for (;;) {
    if ((r = killone(g, c)) != LSYS_OK) return r;
    if (g->first[c] >= 0) { c = g->first[c]; continue; }
    while (c != i && g->next[c] < 0) c = g->parent[c];
    if (c == i) break;
    c = g->next[c];
  }
  if (p >= 0) {                      /* unlinked from its parent's children */
    int32_t pv = g->prev[i], nx = g->next[i];
    if (pv >= 0) g->next[pv] = nx;
    else g->first[p] = nx;
    if (nx >= 0) g->prev[nx] = pv;
    else g->last[p] = pv;
  }
  return LSYS_OK;
}

int lsys_grow_begin (lsys_limbs *g) {
  if (g->intick) return LSYS_EBUSY;
  g->intick = 1;
  g->n0 = g->n;
  return LSYS_OK;
}

int lsys_grow_end (lsys_limbs *g) {
  size_t i;
  if (!g->intick) return LSYS_EBUSY;
  g->intick = 0;
  for (i = 0; i < g->n; i++) {       /* the next state becomes the state */
    uint8_t c = g->chg[i];
    if (!(g->flag[i] & LSYS_LIMB_ALIVE)) continue;
    if (c & C_LEN) g->len[i] = g->nlen[i];
    if (c & C_RAD) g->rad[i] = g->nrad[i];
    if (c & C_COL) memcpy(g->rgb + 3 * i, g->nrgb + 3 * i, 3 * sizeof *g->rgb);
    if (c & C_ROT) memcpy(g->loc + 9 * i, g->nloc + 9 * i, 9 * sizeof *g->loc);
    if (i < g->n0) g->age[i]++;
  }
  return lsys_grow_update(g);       /* applies what was deferred, then the geometry */
}

int lsys_grow_update (lsys_limbs *g) {
  size_t i;
  int r;
  if (!g->intick && g->npend > 0) {  /* what a tick (or a call outside one) deferred; on
                                        a failure the ops not yet done stay for a retry */
    size_t k;
    for (k = 0; k < g->npend; k++) {
      lsys_limbop *o = &g->pending[k];
      r = o->op == OP_LEAVES ? addleaves(g, o)
          : o->op == OP_DROP ? (lsys_grow_alive(g, o->limb) ? dropleaves(g, o->limb) : LSYS_OK)
          : removelimb(g, o->limb);
      if (r != LSYS_OK) { memmove(g->pending, g->pending + k, (g->npend - k) * sizeof *o);
                          g->npend -= k; return r; }
    }
    g->npend = 0;
  }
  if (!g->dirty) return LSYS_OK;
  for (i = 0; i < g->n; i++) {
    int32_t p = g->parent[i];
    uint8_t c = g->chg[i];
    int xf, shape;
    if (!(g->flag[i] & LSYS_LIMB_ALIVE)) continue;
    xf = (c & (C_NEW | C_ROT)) || (p >= 0 && (g->chg[p] & (C_XF | C_LEN)));
    if (xf) { worldframe(g, (int32_t)i); c |= C_XF; }
    if (c & (C_NEW | C_COL)) {
      uint16_t col;
      if ((r = colorindex(g, g->rgb + 3 * i, &col)) != LSYS_OK) return r;
      g->col[i] = col;
    }
    if (g->v0[i] == UINT32_MAX) {
      if ((r = newrange(g, 0, &g->v0[i], &g->t0[i])) != LSYS_OK) return r;
      c |= C_XF;
    }
    shape = (c & (C_XF | C_LEN | C_RAD)) != 0;
    if (shape) writelimb(g, (int32_t)i);
    else if (c & C_COL) recolor(g, (int32_t)i);
    if (shape || (c & C_LEAF)) {
      int32_t l;
      for (l = g->leaf[i]; l >= 0; l = g->lf_next[l]) writeleaf(g, l);
    }
    g->chg[i] = c;                   /* its children read C_XF and C_LEN */
  }
  for (i = 0; i < g->n; i++) g->chg[i] = 0;
  g->dirty = 0;
  return LSYS_OK;
}

/* }====================================================================== */
