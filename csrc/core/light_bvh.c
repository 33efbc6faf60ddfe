/*
** The light's hierarchies (light_impl.h): the primitives copied out of a
** scene, the build by binned surface area heuristic, the 4-wide trees.
**
** Build: a node's primitives are binned by their centroids into NBINS bins
** along each of the three axes; the split between two bins that minimises
** the surface area heuristic is taken unless a leaf costs less and holds at
** most MAXLEAF primitives. A traversal step costs as much as a test of a
** block of primitives: four triangles (a packet, one vector test) or one
** capsule. Each level is a pass over its primitives, so the build is
** O(n log n) for any reasonable scene; below FORCEDEPTH nodes are halved
** whatever their boxes, so the depth (and the traversal stack) stays
** bounded for any scene. The binary tree is built depth first with an
** explicit stack; its leaves become packets of triangles or runs of
** capsules in leaf order, its boxes are padded, and it is collapsed into a
** 4-wide tree: each node takes a binary node's children, opening the inner
** one of the largest box until it has four. For each of the eight octants
** of directions a node keeps the order a ray meets its children in, as the
** splits it was made of give it (each split's lower side first along an
** axis the ray goes up), so that a walk need not sort them.
*/
#include <float.h>
#include <math.h>
#include <string.h>

#include "light_impl.h"

#define NBINS 16
#define MAXLEAF 16             /* at most 255: a 4-wide node's counts are bytes */
#define FORCEDEPTH 90          /* + log2(2^31) levels of halving < LSYS_LIGHT_STACK */

#define MINF(a, b) ((a) < (b) ? (a) : (b))
#define MAXF(a, b) ((a) > (b) ? (a) : (b))

/* ---------------------------------------------------------------------- */
/* the primitives */

static int okf3 (const float v[3]) {
  return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static void boxof (float *bb, const float *p, int np, float pad) {
  int i, c;
  for (c = 0; c < 3; c++) {
    bb[c] = bb[3 + c] = p[c];
    for (i = 1; i < np; i++) {
      bb[c] = MINF(bb[c], p[3 * i + c]);
      bb[3 + c] = MAXF(bb[3 + c], p[3 * i + c]);
    }
    bb[c] -= pad;
    bb[3 + c] += pad;
  }
}

/* Writes the triangle v (3 vertices) to P and its box to bb; 0 when it is
** degenerate or not finite (left out). */
static size_t puttri (lsys_lprim *P, float *bb, const float v[9]) {
  float *e1 = P->b, *e2 = P->c;
  int c;
  if (!okf3(v) || !okf3(v + 3) || !okf3(v + 6)) return 0;
  for (c = 0; c < 3; c++) {
    P->a[c] = v[c];
    e1[c] = v[3 + c] - v[c];
    e2[c] = v[6 + c] - v[c];
  }
  if (e1[1] * e2[2] - e1[2] * e2[1] == 0 && e1[2] * e2[0] - e1[0] * e2[2] == 0 &&
      e1[0] * e2[1] - e1[1] * e2[0] == 0)
    return 0;
  P->kind = LSYS_LIGHT_TRI;
  boxof(bb, v, 3, 0);
  return 1;
}

/* The capsule around the segment v[0..2] -> v[3..5] of radius r. */
static size_t putcap (lsys_lprim *P, float *bb, const float v[6], float r) {
  int c;
  if (!okf3(v) || !okf3(v + 3)) return 0;
  for (c = 0; c < 3; c++) {
    P->a[c] = v[c];
    P->b[c] = v[3 + c] - v[c];
  }
  P->c[0] = r;
  P->c[1] = P->b[0] * P->b[0] + P->b[1] * P->b[1] + P->b[2] * P->b[2];
  P->c[2] = 0;
  P->kind = LSYS_LIGHT_CAPSULE;
  boxof(bb, v, 2, r);
  return 1;
}

/* The point p under m (NULL: as it is), into q. */
static void place (float q[3], const float p[3], const float *m) {
  double x[3];
  if (m == NULL) { memcpy(q, p, 3 * sizeof(float)); return; }
  lsys_xform(m, p, x);
  q[0] = (float)x[0]; q[1] = (float)x[1]; q[2] = (float)x[2];
}

/* Appends the triangles of part p of the mesh and, when r > 0, its lines, under
** m (NULL: as they are), to the primitives P (boxes bb), counting them in L. */
static void putpart (lsys_light *L, lsys_lprim *P, float *bb, const lsys_mesh *ms,
                     const lsys_part *p, const float *m, float r) {
  size_t k, n = L->ntri + L->ncap;
  float v[9];
  int i;
  for (k = p->t0; k < p->t0 + p->nt && k < ms->nt; k++) {
    const uint32_t *t = ms->tri + 3 * k;
    if (t[0] >= ms->nv || t[1] >= ms->nv || t[2] >= ms->nv) continue;
    for (i = 0; i < 3; i++) place(v + 3 * i, ms->pos + 3 * t[i], m);
    if (puttri(P + n, bb + 6 * n, v)) { n++; L->ntri++; }
  }
  if (r <= 0) return;
  for (k = p->l0; k < p->l0 + p->nl && k < ms->nl; k++) {
    for (i = 0; i < 2; i++) place(v + 3 * i, ms->lpos + 6 * k + 3 * i, m);
    if (putcap(P + n, bb + 6 * n, v, r)) { n++; L->ncap++; }
  }
}

/* The triangles and lines s draws (as lsys_population_size counts them). */
static void sizes (const lsys_scene *s, size_t *nt, size_t *nl) {
  size_t i;
  if (s->ninst == 0) { *nt = s->mesh.nt; *nl = s->mesh.nl; return; }
  *nt = *nl = 0;
  for (i = 0; i < s->ninst; i++)
    if (s->inst[i].part < s->nparts) {
      *nt += s->parts[s->inst[i].part].nt;
      *nl += s->parts[s->inst[i].part].nl;
    }
}

/* The primitives s draws into P and bb; returns their number. */
static size_t gather (lsys_light *L, lsys_lprim *P, float *bb, const lsys_scene *s, float r) {
  size_t i;
  L->ntri = L->ncap = 0;
  if (s->ninst == 0) {
    lsys_part all = {0, s->mesh.nv, 0, s->mesh.nt, 0, s->mesh.nl, 0, 0};
    putpart(L, P, bb, &s->mesh, &all, NULL, r);
  } else
    for (i = 0; i < s->ninst; i++)
      if (s->inst[i].part < s->nparts)
        putpart(L, P, bb, &s->mesh, &s->parts[s->inst[i].part], s->inst[i].m, r);
  return L->ntri + L->ncap;
}

/* ---------------------------------------------------------------------- */
/* the build */

typedef struct bin { float b[6]; size_t n; } bin;   /* a box: lo[3], hi[3] */

/* A node of the binary tree. */
typedef struct node2 {
  float lo[3], hi[3];          /* the box (padded once built) */
  uint32_t off;                /* leaf: its first item; else its first child */
  uint16_t cnt;                /* leaf: its items (1 .. MAXLEAF); else 0 */
  uint16_t axis;               /* inner: the axis its children were split along */
} node2;

typedef struct builder {
  lsys_light *L;
  const lsys_lprim *prim;      /* the primitives gathered */
  const float *bb;             /* 6 floats a primitive: its box */
  uint32_t *ix;                /* the primitives of the tree being built, in node order */
  size_t n;                    /* how many */
  int blk;                     /* primitives a test takes: 4 triangles, 1 capsule */
  node2 *n2;                   /* the binary tree, root 0 */
  size_t n2n, n2cap;
  lsys_meter *mt;
} builder;

static float harea (const float *b) {
  float dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
  return dx * dy + dy * dz + dz * dx;
}

static void binit (float *b) {
  b[0] = b[1] = b[2] = FLT_MAX;
  b[3] = b[4] = b[5] = -FLT_MAX;
}

static void bgrow (float *b, const float *x) {
  int c;
  for (c = 0; c < 3; c++) {
    b[c] = MINF(b[c], x[c]);
    b[3 + c] = MAXF(b[3 + c], x[3 + c]);
  }
}

/* The boxes of ix[first .. first + n): of the primitives (nb) and of their
** doubled centroids (cb). */
static void bounds (const builder *B, size_t first, size_t n, float nb[6], float cb[6]) {
  size_t i;
  int c;
  binit(nb);
  binit(cb);
  for (i = first; i < first + n; i++) {
    const float *b = B->bb + 6 * (size_t)B->ix[i];
    for (c = 0; c < 3; c++) {
      float x = b[c] + b[3 + c];
      nb[c] = MINF(nb[c], b[c]);
      nb[3 + c] = MAXF(nb[3 + c], b[3 + c]);
      cb[c] = MINF(cb[c], x);
      cb[3 + c] = MAXF(cb[3 + c], x);
    }
  }
}

static int binof (const float *b, int ax, float lo, float scale) {
  int k = (int)((b[ax] + b[3 + ax] - lo) * scale);
  return k < 0 ? 0 : k >= NBINS ? NBINS - 1 : k;
}

/* The tests n primitives take. */
static float blocks (const builder *B, size_t n) {
  return (float)((n + (size_t)B->blk - 1) / (size_t)B->blk);
}

/* The best split of ix[first .. first + n) (box nb, centroids' box cb) by
** binned SAH: puts the primitives of the left side first (the lower
** centroids along the axis *axis) and returns their number; 0 for a leaf;
** n / 2 (unordered) when no binned split separates them and they are too
** many for a leaf. */
static size_t split (builder *B, size_t first, size_t n, const float nb[6], const float cb[6],
                     int *axis) {
  bin bins[3][NBINS];
  float scale[3], best = FLT_MAX, rarea[NBINS];
  size_t rn[NBINS], i, j;
  int ax, k, bax = -1, bk = 0;
  for (ax = 0; ax < 3; ax++) {
    float ext = cb[3 + ax] - cb[ax];
    scale[ax] = ext > 0 ? (float)NBINS * (1 - 1e-6f) / ext : 0;
    for (k = 0; k < NBINS; k++) {
      binit(bins[ax][k].b);
      bins[ax][k].n = 0;
    }
  }
  for (i = first; i < first + n; i++) {
    const float *b = B->bb + 6 * (size_t)B->ix[i];
    for (ax = 0; ax < 3; ax++)
      if (scale[ax] > 0) {
        bin *q = &bins[ax][binof(b, ax, cb[ax], scale[ax])];
        bgrow(q->b, b);
        q->n++;
      }
  }
  for (ax = 0; ax < 3; ax++) {
    float box[6];
    size_t ln = 0;
    if (scale[ax] <= 0) continue;
    binit(box);
    for (k = NBINS - 1, j = 0; k > 0; k--) {        /* right sides: bins k .. NBINS - 1 */
      if (bins[ax][k].n > 0) bgrow(box, bins[ax][k].b);
      j += bins[ax][k].n;
      rn[k] = j;
      rarea[k] = j > 0 ? harea(box) : 0;
    }
    binit(box);
    for (k = 0; k < NBINS - 1; k++) {                /* left sides: bins 0 .. k */
      float cost;
      if (bins[ax][k].n > 0) bgrow(box, bins[ax][k].b);
      ln += bins[ax][k].n;
      if (ln == 0 || rn[k + 1] == 0) continue;
      cost = harea(box) * blocks(B, ln) + rarea[k + 1] * blocks(B, rn[k + 1]);
      if (cost < best) { best = cost; bax = ax; bk = k; }
    }
  }
  *axis = 0;
  if (bax < 0) return n <= MAXLEAF ? 0 : n / 2;
  /* a leaf costs its tests; a split one step and its sides' tests (per unit area) */
  if (n <= MAXLEAF && harea(nb) * (blocks(B, n) - 1) <= best) return 0;
  for (i = first, j = first + n; i < j;) {           /* partition: bins <= bk first */
    if (binof(B->bb + 6 * (size_t)B->ix[i], bax, cb[bax], scale[bax]) <= bk) i++;
    else {
      uint32_t t = B->ix[i];
      B->ix[i] = B->ix[--j];
      B->ix[j] = t;
    }
  }
  i -= first;
  *axis = bax;
  return i == 0 || i == n ? n / 2 : i;
}

/* Counts 'bytes' more in the meter, when they fit. */
static int charge (lsys_meter *mt, size_t bytes) {
  if (!lsys_common_meter_fits(mt, bytes)) {
    mt->hit = 1;
    return LSYS_EMEMORY;
  }
  if (mt != NULL) mt->used += bytes;
  return LSYS_OK;
}

/* A new pair of nodes of the binary tree: their index in *c, growing the
** array within the meter. LSYS_OK, LSYS_EMEMORY or LSYS_ENOMEM. */
static int newpair (builder *B, size_t *c) {
  int st;
  if (B->n2n + 2 > B->n2cap &&
      (st = lsys_common_grow_metered((void **)&B->n2, &B->n2cap, B->n2n + 2, sizeof *B->n2,
                                     B->mt)) != LSYS_OK)
    return st;
  *c = B->n2n;
  B->n2n += 2;
  return LSYS_OK;
}

typedef struct task { size_t node, first, n, depth; } task;

/* Builds the binary tree over ix[0 .. n). LSYS_OK, LSYS_EMEMORY or LSYS_ENOMEM. */
static int buildtree (builder *B) {
  task stack[LSYS_LIGHT_STACK], t = {0, 0, 0, 1};
  int sp = 0, st;
  t.n = B->n;
  B->n2n = 1;
  for (;;) {
    float nb[6], cb[6];
    size_t nl, c;
    int axis = 0;
    node2 *nd = &B->n2[t.node];
    bounds(B, t.first, t.n, nb, cb);
    memcpy(nd->lo, nb, 3 * sizeof(float));
    memcpy(nd->hi, nb + 3, 3 * sizeof(float));
    nl = t.n <= 1 ? 0 : t.depth >= FORCEDEPTH ? t.n / 2 : split(B, t.first, t.n, nb, cb, &axis);
    if (nl == 0) {
      nd->off = (uint32_t)t.first;
      nd->cnt = (uint16_t)t.n;
      if (sp == 0) return LSYS_OK;
      t = stack[--sp];
      continue;
    }
    if ((st = newpair(B, &c)) != LSYS_OK) return st;
    B->n2[t.node].off = (uint32_t)c;
    B->n2[t.node].cnt = 0;
    B->n2[t.node].axis = (uint16_t)axis;
    stack[sp].node = c + 1;
    stack[sp].first = t.first + nl;
    stack[sp].n = t.n - nl;
    stack[sp++].depth = t.depth + 1;
    t.node = c;
    t.n = nl;
    t.depth++;
  }
}

/* The binary tree's leaves in order of their ranges (depth first, left
** first): calls f on each. */
static void leaves (builder *B, void (*f) (builder *B, node2 *leaf, void *ud), void *ud) {
  size_t stack[LSYS_LIGHT_STACK], x = 0;
  int sp = 0;
  for (;;) {
    node2 *nd = &B->n2[x];
    if (nd->cnt > 0) {
      f(B, nd, ud);
      if (sp == 0) return;
      x = stack[--sp];
    } else {
      stack[sp++] = nd->off + 1;
      x = nd->off;
    }
  }
}

/* A triangle leaf's primitives into packets at *(size_t *)ud on, the leaf
** then their range. */
static void packleaf (builder *B, node2 *leaf, void *ud) {
  size_t *np = (size_t *)ud, k, npk = (leaf->cnt + 3) / 4;
  lsys_ltri4 *T = B->L->pack + *np;
  int c;
  memset(T, 0, npk * sizeof *T);
  for (k = 0; k < leaf->cnt; k++) {
    const lsys_lprim *P = &B->prim[B->ix[leaf->off + k]];
    for (c = 0; c < 3; c++) {
      T[k / 4].a[c][k % 4] = P->a[c];
      T[k / 4].e1[c][k % 4] = P->b[c];
      T[k / 4].e2[c][k % 4] = P->c[c];
    }
  }
  leaf->off = (uint32_t)*np;
  leaf->cnt = (uint16_t)npk;
  *np += npk;
}

static void countleaf (builder *B, node2 *leaf, void *ud) {
  (void)B;
  *(size_t *)ud += (leaf->cnt + 3) / 4;
}

/* A capsule leaf's primitives into the capsules at *(size_t *)ud on. */
static void capleaf (builder *B, node2 *leaf, void *ud) {
  size_t *nc = (size_t *)ud, k;
  for (k = 0; k < leaf->cnt; k++) B->L->caps[*nc + k] = B->prim[B->ix[leaf->off + k]];
  leaf->off = (uint32_t)*nc;
  *nc += leaf->cnt;
}

/* Widens every box by a little more than float rounding can move a hit, so
** that a ray that hits a primitive enters every box that holds it. */
static void pad (builder *B) {
  const lsys_light *L = B->L;
  double diag = 0, big = 0;
  float p;
  size_t i;
  int c;
  for (c = 0; c < 3; c++) {
    double d = L->hi[c] - L->lo[c];
    diag += d * d;
    big = fmax(big, fmax(fabs(L->lo[c]), fabs(L->hi[c])));
  }
  p = (float)(1e-5 * sqrt(diag) + 1e-6 * big);
  for (i = 0; i < B->n2n; i++)
    for (c = 0; c < 3; c++) {
      B->n2[i].lo[c] -= p;
      B->n2[i].hi[c] += p;
    }
}

/* Slot k of the 4-wide node q: the binary node x, or empty (x NULL). */
static void setslot (lsys_lnode4 *q, int k, const node2 *x, uint32_t child) {
  int c;
  for (c = 0; c < 3; c++) {
    q->b[c][k] = x != NULL ? x->lo[c] : FLT_MAX;
    q->b[3 + c][k] = x != NULL ? x->hi[c] : -FLT_MAX;
  }
  q->item[k] = LSYS_LITEM(child, x != NULL ? x->cnt : 0);
}

/* The slots of the binary subtree at x whose leaves (for this purpose) are
** the 4-wide node's children kid[0 .. nk), in the order a ray of the octant
** oct meets them (each split's lower side first along an axis the ray goes
** up, else last), from *n on in ord. */
static void order (const node2 *n2, size_t x, const size_t kid[4], int nk, int oct,
                   uint8_t *ord, int *n) {
  int k;
  for (k = 0; k < nk; k++)
    if (kid[k] == x) { *ord |= (uint8_t)(k << 2 * (*n)++); return; }
  k = oct >> n2[x].axis & 1;                      /* 1: the ray goes down that axis */
  order(n2, n2[x].off + (size_t)k, kid, nk, oct, ord, n);
  order(n2, n2[x].off + (size_t)(1 - k), kid, nk, oct, ord, n);
}

/* q's child orders for each octant, its children being kid[0 .. nk) under
** the binary node x (empty slots last). */
static void orders (lsys_lnode4 *q, const node2 *n2, size_t x, const size_t kid[4], int nk) {
  int oct, n, k;
  for (oct = 0; oct < 8; oct++) {
    uint8_t o = 0;
    n = 0;
    order(n2, x, kid, nk, oct, &o, &n);
    for (k = nk; k < 4; k++) o |= (uint8_t)(k << 2 * n++);
    q->item[oct >> 1] |= (uint64_t)o << (40 + 8 * (oct & 1));
  }
}

/* The children of the binary node x that a 4-wide node takes: its two, then
** the inner one of the largest box opened, until there are four or only
** leaves. Returns their number. */
static int gather4 (const node2 *n2, size_t x, size_t kid[4]) {
  int nk = 2;
  kid[0] = n2[x].off;
  kid[1] = n2[x].off + 1;
  while (nk < 4) {
    int k, best = -1;
    float ba = -1;
    for (k = 0; k < nk; k++) {
      const node2 *y = &n2[kid[k]];
      float b[6] = {y->lo[0], y->lo[1], y->lo[2], y->hi[0], y->hi[1], y->hi[2]};
      if (y->cnt == 0 && harea(b) > ba) { ba = harea(b); best = k; }
    }
    if (best < 0) break;
    kid[nk++] = n2[kid[best]].off + 1;
    kid[best] = n2[kid[best]].off;
  }
  return nk;
}

/* Makes the 4-wide tree T out of the binary one, depth first. The binary
** tree has (n2n - 1) / 2 inner nodes and each 4-wide node takes one of them
** as its own, so that many (at least 1) are enough. LSYS_OK, LSYS_EMEMORY
** or LSYS_ENOMEM. */
static int collapse (builder *B, lsys_ltree *T) {
  typedef struct item { size_t x, q, depth; } item;
  item stack[3 * LSYS_LIGHT_STACK + 4];
  size_t cap = B->n2n > 1 ? (B->n2n - 1) / 2 : 1, bytes = cap * sizeof *T->node + 64;
  int sp = 0, st;
  if ((st = charge(B->mt, bytes)) != LSYS_OK) return st;
  if ((T->mem = LSYS_MALLOC(bytes)) == NULL) return LSYS_ENOMEM;
  T->node = (lsys_lnode4 *)(((uintptr_t)T->mem + 63) & ~(uintptr_t)63);
  T->nnodes = T->depth = 1;
  if (B->n2[0].cnt > 0) {                          /* the root is a leaf */
    int k;
    size_t kid[4] = {0, 0, 0, 0};
    setslot(&T->node[0], 0, &B->n2[0], B->n2[0].off);
    for (k = 1; k < 4; k++) setslot(&T->node[0], k, NULL, 0);
    orders(&T->node[0], B->n2, 0, kid, 1);
    return LSYS_OK;
  }
  stack[sp].x = 0; stack[sp].q = 0; stack[sp++].depth = 1;
  while (sp > 0) {
    item it = stack[--sp];
    size_t kid[4];
    int nk = gather4(B->n2, it.x, kid), k;
    if (it.depth > T->depth) T->depth = it.depth;
    for (k = 0; k < 4; k++) {
      const node2 *y = k < nk ? &B->n2[kid[k]] : NULL;
      uint32_t child = y != NULL && y->cnt > 0 ? y->off : 0;
      if (y != NULL && y->cnt == 0) {
        child = (uint32_t)T->nnodes++;
        stack[sp].x = kid[k]; stack[sp].q = child; stack[sp++].depth = it.depth + 1;
      }
      setslot(&T->node[it.q], k, y, child);
    }
    orders(&T->node[it.q], B->n2, it.x, kid, nk);
  }
  return LSYS_OK;
}

/* The tree over ix[0 .. n) (triangles when blk is 4, else capsules) into
** T, with its packets or capsules. */
static int tree (builder *B, lsys_ltree *T) {
  lsys_light *L = B->L;
  size_t k = 0;
  int st;
  if (B->n == 0) return LSYS_OK;
  if ((st = buildtree(B)) != LSYS_OK) return st;
  if (B->blk == 4) {
    leaves(B, countleaf, &k);
    if ((st = charge(B->mt, k * sizeof *L->pack)) != LSYS_OK) return st;
    if ((L->pack = (lsys_ltri4 *)LSYS_MALLOC(k * sizeof *L->pack)) == NULL) return LSYS_ENOMEM;
    L->npack = k;
    k = 0;
    leaves(B, packleaf, &k);
  } else {
    if ((st = charge(B->mt, B->n * sizeof *L->caps)) != LSYS_OK) return st;
    if ((L->caps = (lsys_lprim *)LSYS_MALLOC(B->n * sizeof *L->caps)) == NULL)
      return LSYS_ENOMEM;
    leaves(B, capleaf, &k);
  }
  pad(B);
  return collapse(B, T);
}

static int membudget (lsys_error *e, size_t need, const lsys_meter *mt) {
  char b1[32], b2[32];
  if (need == 0)
    return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "light: the hierarchy needs more than "
                         "max_memory (%s)", lsys_common_fmtsize(b2, mt->limit));
  return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "light: the hierarchy needs %s, more "
                       "than max_memory (%s)", lsys_common_fmtsize(b1, need),
                       lsys_common_fmtsize(b2, mt->limit));
}

/* The bytes L keeps. */
static size_t kept (const lsys_light *L) {
  size_t b = L->npack * sizeof *L->pack + L->ncap * sizeof *L->caps;
  if (L->tri.mem != NULL) b += L->tri.nnodes * sizeof(lsys_lnode4);
  if (L->cap.mem != NULL) b += L->cap.nnodes * sizeof(lsys_lnode4);
  return b;
}

/* Both trees over the gathered primitives P (boxes bb): the triangles' and
** the capsules'. */
static int trees (builder *B, lsys_lprim *P, float *bb, size_t n) {
  lsys_light *L = B->L;
  size_t i, k = 0;
  float all[6];
  int c, st;
  binit(all);
  for (i = 0; i < n; i++) bgrow(all, bb + 6 * i);
  for (c = 0; c < 3; c++) {
    L->lo[c] = n > 0 ? all[c] : 0;
    L->hi[c] = n > 0 ? all[3 + c] : 0;
  }
  for (i = 0; i < n; i++) if (P[i].kind == LSYS_LIGHT_TRI) B->ix[k++] = (uint32_t)i;
  for (i = 0; i < n; i++) if (P[i].kind != LSYS_LIGHT_TRI) B->ix[k++] = (uint32_t)i;
  B->prim = P;
  B->bb = bb;
  B->n = L->ntri;
  B->blk = 4;
  if ((st = tree(B, &L->tri)) != LSYS_OK) return st;
  B->ix += L->ntri;
  B->n = L->ncap;
  B->blk = 1;
  st = tree(B, &L->cap);
  B->ix -= L->ntri;
  return st;
}

int lsys_light_bvh (lsys_light *L, const lsys_scene *s, double radius, lsys_meter *mt,
                    lsys_error *e) {
  size_t nt, nl, n, scratch, used0 = mt != NULL ? mt->used : 0;
  builder B;
  lsys_lprim *P;
  float *bb;
  int st = LSYS_OK;
  sizes(s, &nt, &nl);
  n = nt + (radius > 0 ? nl : 0);
  if (n > (size_t)INT32_MAX)
    return lsys_seterror(e, LSYS_ELIMIT, (size_t)-1, "light: %zu primitives, more than 2^31", n);
  memset(&B, 0, sizeof B);
  B.L = L;
  B.mt = mt;
  B.n2cap = n > 0 ? n : 1;        /* grows up to 2 n - 1 nodes when it must */
  /* the build holds at once: the primitives gathered, their boxes and order,
  ** the binary tree, and what stays (about as much as the primitives) */
  scratch = n * (sizeof *P + 6 * sizeof(float) + sizeof(uint32_t)) + B.n2cap * sizeof *B.n2;
  if (!lsys_common_meter_fits(mt, scratch + n * sizeof *P)) {
    mt->hit = 1;
    return membudget(e, scratch + n * sizeof *P, mt);
  }
  P = (lsys_lprim *)LSYS_MALLOC(n > 0 ? n * sizeof *P : 1);
  B.n2 = (node2 *)LSYS_MALLOC(B.n2cap * sizeof *B.n2);
  bb = (float *)LSYS_MALLOC(n > 0 ? n * 6 * sizeof(float) : 1);
  B.ix = (uint32_t *)LSYS_MALLOC(n > 0 ? n * sizeof(uint32_t) : 1);
  if (mt != NULL) mt->used += scratch;
  if (P != NULL && B.n2 != NULL && bb != NULL && B.ix != NULL) {
    size_t m = gather(L, P, bb, s, (float)radius);
    st = trees(&B, P, bb, m);
  } else st = LSYS_ENOMEM;
  LSYS_FREE(P);
  LSYS_FREE(bb);
  LSYS_FREE(B.ix);
  LSYS_FREE(B.n2);
  if (mt != NULL) mt->used = used0 + (st == LSYS_OK ? kept(L) : 0);
  if (st != LSYS_OK) return st == LSYS_EMEMORY ? membudget(e, 0, mt) : st;
  return LSYS_OK;
}
