/*
** Rays through the light's hierarchy (light_impl.h): the primitive tests
** and the traversal of the 4-wide tree.
**
** The rays of a query share their directions, so they are traced in
** packets (after Wald et al. 2001, "Interactive rendering with coherent ray
** tracing"): up to PACK rays of one direction from nearby points walk the
** tree together. A node is fetched once for the packet; each of its rays
** tests the node's four child boxes side by side in one vector, and a child
** goes on the stack once, with the mask of the rays that enter it. So a ray
** meets exactly the boxes and primitives it would meet alone (a packet does
** its rays' tests in another order), while the loads, the stack and the
** branches of one walk serve all of them. The children go on the stack
** without a branch on each, farthest first in the order the build worked
** out for the direction's octant. The part of a triangle test that depends
** only on the triangle and the direction (the direction's cross product
** with an edge, the determinant and its inverse) is done once a packet of
** triangles for all the rays, the rest for each ray, four triangles at a
** time (Möller and Trumbore 1997, section 2). The rays of a query are put
** in packets by the order of their origins across their direction (so that
** a packet's rays run side by side), and a ray that stops at its first hit
** is first tested against the packet of triangles that stopped the last
** packet (lsys_light_cast).
**
** The vectors are SSE2 on x86-64 and plain arrays of four floats elsewhere
** (or with LSYS_LIGHT_SCALAR), which compute each lane alike, in the same
** order: the same results on every machine.
**
** Any hit beyond tmin counts, up to a cap (a transmittance counts the hits:
** each primitive is in one leaf, so a ray meets it at most once, and the
** count up to the cap does not depend on the order the primitives come
** in). Testing every primitive (lsys_light_brute) uses the same triangle
** and capsule tests, so both agree exactly.
*/
#include <float.h>
#include <math.h>
#include <string.h>

#include "light_impl.h"

#define STACK (3 * LSYS_LIGHT_STACK + 4)  /* a node pushes at most 4 and pops 1 */
#define CASTMAX 256                        /* rays lsys_light_cast orders at once */
#define PACK 16                            /* rays in a packet (16 at most: 16-bit masks) */

#if defined(__SSE2__) && !defined(LSYS_LIGHT_SCALAR)
#define VEC 1
#include <emmintrin.h>
#endif

/* ---------------------------------------------------------------------- */
/* four floats at once */

#ifdef VEC
typedef __m128 f4;
#define f4load _mm_loadu_ps
#define f4set1 _mm_set1_ps
#define f4add _mm_add_ps
#define f4sub _mm_sub_ps
#define f4mul _mm_mul_ps
#define f4div _mm_div_ps
#define f4min _mm_min_ps                   /* a < b ? a : b, lane by lane */
#define f4max _mm_max_ps                   /* a > b ? a : b */
#define f4le(a, b) _mm_movemask_ps(_mm_cmple_ps((a), (b)))   /* bit k: a[k] <= b[k] */
#define f4ge(a, b) _mm_movemask_ps(_mm_cmpge_ps((a), (b)))
#define f4gt(a, b) _mm_movemask_ps(_mm_cmpgt_ps((a), (b)))
#define f4lt(a, b) _mm_movemask_ps(_mm_cmplt_ps((a), (b)))
#define f4ne(a, b) _mm_movemask_ps(_mm_cmpneq_ps((a), (b)))
#else
typedef struct f4 { float x[4]; } f4;
#define F4OP(name, expr) \
  static inline f4 name (f4 a, f4 b) { \
    f4 r; int k; for (k = 0; k < 4; k++) r.x[k] = (expr); return r; }
#define F4CMP(name, expr) \
  static inline int name (f4 a, f4 b) { \
    int m = 0, k; for (k = 0; k < 4; k++) m |= (expr) << k; return m; }
F4OP(f4add, a.x[k] + b.x[k])
F4OP(f4sub, a.x[k] - b.x[k])
F4OP(f4mul, a.x[k] * b.x[k])
F4OP(f4div, a.x[k] / b.x[k])
F4OP(f4min, a.x[k] < b.x[k] ? a.x[k] : b.x[k])
F4OP(f4max, a.x[k] > b.x[k] ? a.x[k] : b.x[k])
F4CMP(f4le, a.x[k] <= b.x[k])
F4CMP(f4ge, a.x[k] >= b.x[k])
F4CMP(f4gt, a.x[k] > b.x[k])
F4CMP(f4lt, a.x[k] < b.x[k])
F4CMP(f4ne, a.x[k] != b.x[k])
static inline f4 f4load (const float *p) {
  f4 r;
  memcpy(r.x, p, sizeof r.x);
  return r;
}
static inline f4 f4set1 (float x) {
  f4 r = {{x, x, x, x}};
  return r;
}
#endif

/* ---------------------------------------------------------------------- */
/* the primitives */

/* Whether the ray o + t d, tmin < t < tmax, meets the capsule P (from outside: a
** point in it is not shadowed by it, as a bud by its own stem), in doubles:
** the first of its entries into the body and the two end spheres. */
static int capsule (const lsys_lprim *P, const float o[3], const float d[3], float tmin,
                    float tmax) {
  double w[3], r = P->c[0], bb = P->c[1], dd = 0, dw = 0, ww = 0, db = 0, wb = 0, t = HUGE_VAL;
  double s, A, Bq, C, h;
  int c, end;
  for (c = 0; c < 3; c++) {
    w[c] = (double)o[c] - P->a[c];
    dd += (double)d[c] * d[c];
    dw += (double)d[c] * w[c];
    ww += w[c] * w[c];
    db += (double)d[c] * P->b[c];
    wb += w[c] * P->b[c];
  }
  s = bb > 0 ? wb / bb : 0;                          /* inside: nearest point of the axis */
  s = s < 0 ? 0 : s > 1 ? 1 : s;
  if (ww - 2 * s * wb + s * s * bb < r * r) return 0;
  if (bb > 0) {                                      /* the body, entered from outside it */
    A = bb * dd - db * db;
    Bq = bb * dw - db * wb;
    C = bb * ww - wb * wb - r * r * bb;
    if (A > 0 && C > 0 && (h = Bq * Bq - A * C) >= 0) {
      double tb = (-Bq - sqrt(h)) / A, y = wb + tb * db;
      if (tb > 0 && y >= 0 && y <= bb) t = tb;
    }
  }
  for (end = 0; end < 2; end++) {                    /* the spheres at a and at a + b */
    double vw = 0, vv = 0;
    for (c = 0; c < 3; c++) {
      double x = w[c] - end * (double)P->b[c];
      vw += (double)d[c] * x;
      vv += x * x;
    }
    if (dd > 0 && (h = vw * vw - dd * (vv - r * r)) >= 0) {
      double ts = (-vw - sqrt(h)) / dd;
      if (ts > 0 && ts < t) t = ts;
    }
  }
  return t > tmin && t < HUGE_VAL && t < tmax;
}


/* A direction set up for the tests: for each axis, the rows of a node's
** boxes that hold its near and far planes (lo or hi by the direction's
** sign), the inverse direction (a zero component made tiny, so that no 0 *
** inf makes a NaN) and the octant (bit c: the ray goes down axis c). */
typedef struct rdir {
  int near[3], far[3], oct;
  float d[3], tmin, tmax;
  f4 vd[3], vinv[3], vtmin, vtmax;
} rdir;

/* Up to PACK rays of one direction: their origins, each also in all four
** lanes for the tests. */
typedef struct rpack {
  float o[PACK][3];
  f4 vo[PACK][3];
} rpack;

static void setdir (rdir *D, const lsys_light *L, const float d[3], float tmin) {
  int c;
  D->oct = 0;
  for (c = 0; c < 3; c++) {
    float x = d[c] != 0 ? d[c] : 1e-30f, inv = 1 / x;
    D->d[c] = d[c];
    D->near[c] = inv >= 0 ? c : 3 + c;
    D->far[c] = inv >= 0 ? 3 + c : c;
    D->oct |= (inv < 0) << c;
    D->vd[c] = f4set1(d[c]);
    D->vinv[c] = f4set1(inv);
  }
  D->tmin = tmin;
  D->vtmin = f4set1(tmin);
  D->tmax = L->tmax;
  D->vtmax = f4set1(L->tmax);
}

/* The n (1 .. PACK) origins o[0 .. n) into P (only the first n are used). */
static void setpack (rpack *P, const float *const o[PACK], int n) {
  int k, c;
  for (k = 0; k < n; k++)
    for (c = 0; c < 3; c++) {
      P->o[k][c] = o[k][c];
      P->vo[k][c] = f4set1(o[k][c]);
    }
}

/* What a triangle test shares between the rays of a direction, for the four
** triangles of a packet: the edges, the direction's cross product p with
** the second edge, the determinant's inverse, and the mask of the
** triangles whose determinant is not 0. */
typedef struct trid {
  f4 e1[3], e2[3], p[3], inv;
  int ok;
} trid;

static inline void trisetup (trid *S, const lsys_ltri4 *T, const rdir *D) {
  f4 det;
  int c;
  for (c = 0; c < 3; c++) {
    S->e1[c] = f4load(T->e1[c]);
    S->e2[c] = f4load(T->e2[c]);
  }
  S->p[0] = f4sub(f4mul(D->vd[1], S->e2[2]), f4mul(D->vd[2], S->e2[1]));
  S->p[1] = f4sub(f4mul(D->vd[2], S->e2[0]), f4mul(D->vd[0], S->e2[2]));
  S->p[2] = f4sub(f4mul(D->vd[0], S->e2[1]), f4mul(D->vd[1], S->e2[0]));
  det = f4add(f4add(f4mul(S->e1[0], S->p[0]), f4mul(S->e1[1], S->p[1])),
              f4mul(S->e1[2], S->p[2]));
  S->inv = f4div(f4set1(1), det);
  S->ok = f4ne(det, f4set1(0));
}

/* The mask of the four triangles of T that the ray from o (in all four
** lanes) hits: Möller and Trumbore's barycentric u, v and distance t, both
** faces. */
static inline int trihit (const trid *S, const lsys_ltri4 *T, const rdir *D, const f4 o[3]) {
  const f4 zero = f4set1(0), one = f4set1(1);
  f4 s0 = f4sub(o[0], f4load(T->a[0])), s1 = f4sub(o[1], f4load(T->a[1]));
  f4 s2 = f4sub(o[2], f4load(T->a[2])), q0, q1, q2, u, v, t;
  int m;
  u = f4mul(f4add(f4add(f4mul(s0, S->p[0]), f4mul(s1, S->p[1])), f4mul(s2, S->p[2])), S->inv);
  m = S->ok & f4ge(u, zero) & f4le(u, one);
  if (m == 0) return 0;
  q0 = f4sub(f4mul(s1, S->e1[2]), f4mul(s2, S->e1[1]));
  q1 = f4sub(f4mul(s2, S->e1[0]), f4mul(s0, S->e1[2]));
  q2 = f4sub(f4mul(s0, S->e1[1]), f4mul(s1, S->e1[0]));
  v = f4mul(f4add(f4add(f4mul(D->vd[0], q0), f4mul(D->vd[1], q1)), f4mul(D->vd[2], q2)),
            S->inv);
  t = f4mul(f4add(f4add(f4mul(S->e2[0], q0), f4mul(S->e2[1], q1)), f4mul(S->e2[2], q2)),
            S->inv);
  return m & f4ge(v, zero) & f4le(f4add(u, v), one) & f4gt(t, D->vtmin) & f4lt(t, D->vtmax);
}

/* The hits a mask of trihit counts: its bits. */
static const unsigned char nbits[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

/* The mask of the four children of q (bit k: child k) that the ray from o
** (in all four lanes) enters: its slab tests against their boxes side by
** side, the near and far planes in the rows nf[0 .. 2], nf[3 .. 5]. */
static inline int slabs (const lsys_lnode4 *q, const int nf[6], const rdir *D, const f4 o[3]) {
  f4 lo, hi;
  lo = f4mul(f4sub(f4load(q->b[nf[0]]), o[0]), D->vinv[0]);
  hi = f4mul(f4sub(f4load(q->b[nf[3]]), o[0]), D->vinv[0]);
  lo = f4max(lo, f4mul(f4sub(f4load(q->b[nf[1]]), o[1]), D->vinv[1]));
  hi = f4min(hi, f4mul(f4sub(f4load(q->b[nf[4]]), o[1]), D->vinv[1]));
  lo = f4max(lo, f4mul(f4sub(f4load(q->b[nf[2]]), o[2]), D->vinv[2]));
  hi = f4min(hi, f4mul(f4sub(f4load(q->b[nf[5]]), o[2]), D->vinv[2]));
  return f4le(f4max(lo, D->vtmin), f4min(D->vtmax, hi));
}

/* ---------------------------------------------------------------------- */
/* the walk */


/* A stack item: a child's item (LSYS_LITEM, the orders masked off) and the
** mask of the rays that go there above it. */
#define ITEM(item, rays) (((item) & 0xffffffffffull) | (uint64_t)(rays) << 40)

/* The 4 bits of a slab test's mask spread to every sixteenth bit. */
#define SPREAD16(m) ((uint64_t)((m) & 1) | (uint64_t)((m) >> 1 & 1) << 16 | \
                     (uint64_t)((m) >> 2 & 1) << 32 | (uint64_t)((m) >> 3 & 1) << 48)
static const uint64_t sixteenths[16] = {
  SPREAD16(0), SPREAD16(1), SPREAD16(2), SPREAD16(3), SPREAD16(4), SPREAD16(5), SPREAD16(6),
  SPREAD16(7), SPREAD16(8), SPREAD16(9), SPREAD16(10), SPREAD16(11), SPREAD16(12),
  SPREAD16(13), SPREAD16(14), SPREAD16(15)
};

/* Pushes child k of q with the rays that enter it (bits 16 k .. 16 k + 15
** of 'by'), when there are any. */
#define PUSH(k) do { \
    unsigned k_ = (k), e_ = (unsigned)(by >> 16 * k_) & 0xffffu; \
    stack[sp] = ITEM(q->item[k_], e_); \
    sp += e_ != 0; \
  } while (0)

/* The index of the lowest set bit of the non-zero mask m. */
static inline int lowbit (int m) {
#if defined(__GNUC__)
  return __builtin_ctz((unsigned)m);
#else
  int k = 0;
  while (!(m >> k & 1)) k++;
  return k;
#endif
}

/*
** The hits of the rays of P in the tree T (its leaves: packets of triangles
** when 'tri', else capsules), counted on in hits[r] up to cap for the rays
** r of the mask 'rays'. *last gets the packet (or capsule) of a hit that
** took a ray to the cap, when there is one (else it is left as it is).
*/
static void walk (const lsys_light *L, const lsys_ltree *T, int tri, const rdir *D,
                  const rpack *P, int rays, int cap, int hits[PACK], uint32_t *last) {
  uint64_t stack[STACK];
  int sp = 1, h[PACK], nf[6], c, oct = D->oct;
  for (c = 0; c < PACK; c++) h[c] = hits[c];          /* locals: no store to them aliases D */
  for (c = 0; c < 3; c++) { nf[c] = D->near[c]; nf[3 + c] = D->far[c]; }
  stack[0] = ITEM(LSYS_LITEM(0, 0), rays);          /* the root */
  while (sp > 0) {
    uint64_t it = stack[--sp];
    uint32_t i = (uint32_t)it, n = (uint32_t)(it >> 32) & 0xff;
    int m = (int)(it >> 40) & rays;                 /* less the rays done since */
    if (m == 0) continue;
    if (n > 0) {                                    /* a leaf: its primitives */
      for (n += i; i < n; i++) {
        int live = m, r;
        trid S;
        if (tri) trisetup(&S, &L->pack[i], D);
        for (; live != 0; live &= live - 1) {
          r = lowbit(live);
          h[r] += tri ? nbits[trihit(&S, &L->pack[i], D, P->vo[r])]
                     : capsule(&L->caps[i], P->o[r], D->d, D->tmin, D->tmax);
          if (h[r] >= cap) {
            h[r] = cap;
            m &= ~(1 << r);
            *last = i;
          }
        }
        if (m == 0) break;
      }
      rays &= ~((int)(it >> 40) & ~m);              /* those that reached the cap */
      if (rays == 0) break;
    } else {                                        /* a node: the children the rays enter */
      const lsys_lnode4 *q = &T->node[i];
      uint64_t by = 0;                              /* bit 16 k + r: ray r enters child k */
      unsigned o = LSYS_LORDER(q, oct);
      int live = m;
      for (; live != 0; live &= live - 1) {
        int r = lowbit(live);
        by |= sixteenths[slabs(q, nf, D, P->vo[r])] << r;
      }
      PUSH(o >> 6);                                 /* farthest first */
      PUSH(o >> 4 & 3);
      PUSH(o >> 2 & 3);
      PUSH(o & 3);
    }
  }
  for (c = 0; c < PACK; c++) hits[c] = h[c];
}

/* The hits of the rays of P (mask 'rays'; the others get 0) up to cap: the
** triangles' tree, then the capsules' for those still under the cap. */
static void trace (const lsys_light *L, const rdir *D, const rpack *P, int rays, int cap,
                   int hits[PACK], uint32_t *last) {
  int r;
  for (r = 0; r < PACK; r++) hits[r] = 0;
  if (L->tri.nnodes > 0) walk(L, &L->tri, 1, D, P, rays, cap, hits, &last[0]);
  for (r = 0; r < PACK; r++) if (hits[r] >= cap) rays &= ~(1 << r);
  if (rays != 0 && L->cap.nnodes > 0) walk(L, &L->cap, 0, D, P, rays, cap, hits, &last[1]);
}

int lsys_light_trace (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap) {
  const float *po[PACK] = {o};
  uint32_t last[2];
  int hits[PACK];
  rdir D;
  rpack P;
  setdir(&D, L, d, tmin);
  setpack(&P, po, 1);
  trace(L, &D, &P, 1, cap, hits, last);
  return hits[0];
}

int lsys_light_brute (const lsys_light *L, const float o[3], const float d[3], float tmin,
                      int cap) {
  const float *po[PACK] = {o};
  size_t i;
  int hits = 0;
  rdir D;
  rpack P;
  setdir(&D, L, d, tmin);
  setpack(&P, po, 1);
  for (i = 0; i < L->npack; i++) {
    trid S;
    trisetup(&S, &L->pack[i], &D);
    if ((hits += nbits[trihit(&S, &L->pack[i], &D, P.vo[0])]) >= cap) return cap;
  }
  for (i = 0; i < L->ncap; i++)
    if ((hits += capsule(&L->caps[i], P.o[0], D.d, tmin, D.tmax)) >= cap) return cap;
  return hits;
}

/* The 8 bits of x spread to the even bits of 16. */
static unsigned evens (unsigned x) {
  x = (x | x << 4) & 0x0f0fu;
  x = (x | x << 2) & 0x3333u;
  return (x | x << 1) & 0x5555u;
}

/* The n rays ix[0 .. n) (n <= CASTMAX) put in the order of their origins'
** projections along d on the plane across it (a Morton order there): rays
** that are near there go close to each other all the way. */
static void across (const float (*o)[3], const float d[3], uint16_t *ix, size_t n) {
  float e1[3], e2[3], len, lo[2] = {FLT_MAX, FLT_MAX}, hi[2] = {-FLT_MAX, -FLT_MAX}, sc[2];
  float uv[CASTMAX][2];
  uint16_t key[CASTMAX], tmp[CASTMAX];
  size_t cnt[257], i, k;
  int ax = fabsf(d[0]) <= fabsf(d[1]) && fabsf(d[0]) <= fabsf(d[2]) ? 0
         : fabsf(d[1]) <= fabsf(d[2]) ? 1 : 2, c, pass;
  e1[0] = ax == 0 ? 0 : ax == 1 ? -d[2] : d[1];      /* d x the axis d is least along */
  e1[1] = ax == 1 ? 0 : ax == 0 ? d[2] : -d[0];
  e1[2] = ax == 2 ? 0 : ax == 0 ? -d[1] : d[0];
  len = sqrtf(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  if (!(len > 0)) return;
  for (c = 0; c < 3; c++) e1[c] /= len;
  e2[0] = d[1] * e1[2] - d[2] * e1[1];
  e2[1] = d[2] * e1[0] - d[0] * e1[2];
  e2[2] = d[0] * e1[1] - d[1] * e1[0];
  for (i = 0; i < n; i++) {
    const float *p = o[ix[i]];
    uv[i][0] = p[0] * e1[0] + p[1] * e1[1] + p[2] * e1[2];
    uv[i][1] = p[0] * e2[0] + p[1] * e2[1] + p[2] * e2[2];
    for (c = 0; c < 2; c++) {
      lo[c] = uv[i][c] < lo[c] ? uv[i][c] : lo[c];
      hi[c] = uv[i][c] > hi[c] ? uv[i][c] : hi[c];
    }
  }
  for (c = 0; c < 2; c++) sc[c] = hi[c] > lo[c] ? 255.99f / (hi[c] - lo[c]) : 0;
  for (i = 0; i < n; i++) {
    unsigned q[2];
    for (c = 0; c < 2; c++) {                        /* 0 .. 255 (0 for a NaN) */
      float x = (uv[i][c] - lo[c]) * sc[c];
      q[c] = x >= 255 ? 255 : x > 0 ? (unsigned)x : 0;
    }
    key[i] = (uint16_t)(evens(q[0]) | evens(q[1]) << 1);
  }
  for (pass = 0; pass < 2; pass++) {                 /* a radix sort, a byte at a time */
    uint16_t *from = pass == 0 ? ix : tmp, *to = pass == 0 ? tmp : ix, kt[CASTMAX];
    memset(cnt, 0, sizeof cnt);
    for (i = 0; i < n; i++) cnt[(key[i] >> 8 * pass & 0xff) + 1]++;
    for (k = 1; k < 257; k++) cnt[k] += cnt[k - 1];
    for (i = 0; i < n; i++) {
      size_t at = cnt[key[i] >> 8 * pass & 0xff]++;
      to[at] = from[i];
      kt[at] = key[i];
    }
    memcpy(key, kt, n * sizeof *key);
  }
}

/*
** The rays, taken CASTMAX at a time in the order across d, go through the
** tree PACK at a time (trace). A ray that stops at its first hit (cap 1)
** from a point near the last one in the same direction is likely stopped by
** the same primitive: the packet (or capsule) that stopped the last
** packet's ray is tested first, and the ray only goes into a packet when
** that does not stop it; once 16 tries have been made, only while at least
** one in eight stops its ray (among points far apart it seldom does, and
** costs a test each). Any hit gives the same answer, so this changes no
** result, only the work.
*/
void lsys_light_cast (const lsys_light *L, const float (*o)[3], const uint8_t *want, size_t m,
                      const float d[3], float tmin, int cap, uint8_t *hits) {
  const float *po[PACK];
  uint16_t ix[CASTMAX];
  size_t idx[PACK], i, j, nw, tries = 0, stops = 0;
  uint32_t last[2] = {UINT32_MAX, UINT32_MAX};
  int n, r, h[PACK], k, c;
  trid S;                                         /* the last stopping packet's setup */
  rdir D;
  rpack P;
  memset(&S, 0, sizeof S);
  setdir(&D, L, d, tmin);
  while (m > CASTMAX) {                           /* a block at a time */
    lsys_light_cast(L, o, want, CASTMAX, d, tmin, cap, hits);
    m -= CASTMAX;
    o += CASTMAX;
    hits += CASTMAX;
    if (want != NULL) want += CASTMAX;
  }
  for (i = nw = 0; i < m; i++) {
    hits[i] = 0;
    if (want == NULL || want[i]) ix[nw++] = (uint16_t)i;
  }
  across(o, d, ix, nw);
  for (j = 0; j < nw;) {
    for (n = 0; n < PACK && j < nw; j++) {        /* the next packet */
      i = ix[j];
      k = last[0] != UINT32_MAX ? 1 : last[1] != UINT32_MAX ? 2 : 0;
      if (cap == 1 && k != 0 && (tries < 16 || 8 * stops >= tries)) {
        tries++;
        if (k == 1) {
          f4 vo[3];
          for (c = 0; c < 3; c++) vo[c] = f4set1(o[i][c]);
          hits[i] = trihit(&S, &L->pack[last[0]], &D, vo) != 0;
        } else hits[i] = (uint8_t)capsule(&L->caps[last[1]], o[i], d, tmin, D.tmax);
        if (hits[i]) { stops++; continue; }
      }
      idx[n] = i;
      po[n++] = o[i];
    }
    if (n == 0) continue;
    setpack(&P, po, n);
    last[0] = last[1] = UINT32_MAX;
    trace(L, &D, &P, (1 << n) - 1, cap, h, last);
    for (r = 0; r < n; r++) hits[idx[r]] = (uint8_t)h[r];
    if (last[0] != UINT32_MAX) {                    /* a packet first */
      last[1] = UINT32_MAX;
      trisetup(&S, &L->pack[last[0]], &D);
    }
  }
}
