/*
** Space (space.h): the spatial hash, its build and its queries on worker
** threads. Space colonisation's markers are in space_markers.c.
**
** The build sorts the points by bucket with a counting sort, then each
** bucket by cell and index (buckets are short: a sort only where a bucket
** holds several cells out of order), and lays them out as space_impl.h
** says. A query looks at the (2k + 1)^3 cells around its point, in one
** fixed order, and at the points of each cell in stored order: what it
** sums, it sums in the same order on whichever thread takes it.
*/
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>

#include "space_impl.h"

#define CHUNK 256                 /* query points a worker takes at a time */

/* ---------------------------------------------------------------------- */
/* threads */

typedef struct runner {
  void (*work) (void *, size_t);
  void *ctx;
  size_t n;
  atomic_size_t next;
} runner;

static void *runloop (void *arg) {
  runner *r = (runner *)arg;
  size_t k;
  while ((k = atomic_fetch_add(&r->next, 1)) < r->n) r->work(r->ctx, k);
  return NULL;
}

void lsys_space_run (int threads, size_t nchunks, void (*work) (void *, size_t), void *ctx) {
  pthread_t th[LSYS_SPACE_MAXTHREADS];
  runner r;
  int k, started = 1;
  r.work = work;
  r.ctx = ctx;
  r.n = nchunks;
  atomic_init(&r.next, 0);
  if (threads < 1) threads = 1;
  if (threads > LSYS_SPACE_MAXTHREADS) threads = LSYS_SPACE_MAXTHREADS;
  if ((size_t)threads > nchunks) threads = nchunks > 0 ? (int)nchunks : 1;
  for (k = 1; k < threads; k++, started++)     /* none for one: the caller works alone */
    if (pthread_create(&th[k], NULL, runloop, &r) != 0) break;
  runloop(&r);
  for (k = 1; k < started; k++) pthread_join(th[k], NULL);
}

/* ---------------------------------------------------------------------- */
/* the scene's points */

/* The point p under m (NULL: as it is), into q. */
static void place (double q[3], const float p[3], const float *m) {
  if (m != NULL) lsys_xform(m, p, q);
  else { q[0] = p[0]; q[1] = p[1]; q[2] = p[2]; }
}

/* Part 'pt' of the mesh (under m) into q: each segment's end, then each
** triangle's centroid. Returns the number written. */
static size_t partpoints (double *q, const lsys_mesh *ms, const lsys_part *pt, const float *m) {
  size_t k, w = 0;
  for (k = pt->l0; k < pt->l0 + pt->nl && k < ms->nl; k++)
    place(q + 3 * w++, ms->lpos + 6 * k + 3, m);
  for (k = pt->t0; k < pt->t0 + pt->nt && k < ms->nt; k++) {
    const uint32_t *t = ms->tri + 3 * k;
    float c[3];
    int i;
    if (t[0] >= ms->nv || t[1] >= ms->nv || t[2] >= ms->nv) continue;
    for (i = 0; i < 3; i++)
      c[i] = (ms->pos[3 * t[0] + i] + ms->pos[3 * t[1] + i] + ms->pos[3 * t[2] + i]) / 3;
    place(q + 3 * w++, c, m);
  }
  return w;
}

size_t lsys_space_scenepoints (const lsys_scene *s) {
  size_t i, n = 0;
  if (s->ninst == 0) return s->mesh.nl + s->mesh.nt;
  for (i = 0; i < s->ninst; i++)
    if (s->inst[i].part < s->nparts)
      n += s->parts[s->inst[i].part].nl + s->parts[s->inst[i].part].nt;
  return n;
}

/* The scene's points into q (room for lsys_space_scenepoints); returns how many. */
static size_t scenepoints (double *q, const lsys_scene *s) {
  size_t i, w = 0;
  if (s->ninst == 0) {
    lsys_part all = {0, s->mesh.nv, 0, s->mesh.nt, 0, s->mesh.nl, 0, 0};
    return partpoints(q, &s->mesh, &all, NULL);
  }
  for (i = 0; i < s->ninst; i++)
    if (s->inst[i].part < s->nparts)
      w += partpoints(q + 3 * w, &s->mesh, &s->parts[s->inst[i].part], s->inst[i].m);
  return w;
}

/* ---------------------------------------------------------------------- */
/* build */

void lsys_space_free (lsys_space *S) {
  if (S == NULL) return;
  LSYS_FREE(S->bstart);
  LSYS_FREE(S->cc);
  LSYS_FREE(S->pstart);
  LSYS_FREE(S->p);
  LSYS_FREE(S->g);
  LSYS_FREE(S->v);
  LSYS_FREE(S->id);
  LSYS_FREE(S);
}

/* A point's sort key: its cell, then its index. */
typedef struct skey { int64_t c[3]; uint32_t i; } skey;

static int keyless (const skey *a, const skey *b) {
  int k;
  for (k = 0; k < 3; k++)
    if (a->c[k] != b->c[k]) return a->c[k] < b->c[k];
  return a->i < b->i;
}

static int cmpkey (const void *x, const void *y) {
  const skey *a = (const skey *)x, *b = (const skey *)y;
  return keyless(a, b) ? -1 : keyless(b, a);
}

/* Sorts k[0 .. n) by cell and index: by insertion when short or nearly in
** order (the counting sort kept each bucket's points in index order). */
static void sortbucket (skey *k, size_t n) {
  size_t i, out = 0;
  for (i = 1; i < n; i++) out += keyless(&k[i], &k[i - 1]);
  if (out == 0) return;
  if (n > 16 && out > 4) { qsort(k, n, sizeof *k, cmpkey); return; }
  for (i = 1; i < n; i++) {
    skey x = k[i];
    size_t j = i;
    while (j > 0 && keyless(&x, &k[j - 1])) { k[j] = k[j - 1]; j--; }
    k[j] = x;
  }
}

static int nomemory (lsys_error *e, lsys_meter *mt, size_t need) {
  char b1[32], b2[32];
  mt->hit = 1;
  return lsys_seterror(e, LSYS_EMEMORY, (size_t)-1, "space: %s needed, more than max_memory "
                       "(%s)", lsys_common_fmtsize(b1, need), lsys_common_fmtsize(b2, mt->limit));
}

/* What a space of n points, c cells and nb buckets holds. */
static size_t spacebytes (size_t n, size_t c, size_t nb) {
  return sizeof(lsys_space) + (nb + 1) * sizeof(uint32_t) + c * (3 * sizeof(int64_t) +
         sizeof(uint32_t)) + sizeof(uint32_t) + n * (3 * sizeof(double) + sizeof(int64_t) +
         sizeof(double) + sizeof(uint32_t));
}

/* The build's scratch: the points' buckets and keys, the scene's points. */
typedef struct scratch {
  uint32_t *bk;
  skey *key;
  double *sp;
} scratch;

/* Checks the listed points; gathers the scene's (those in range only) into
** sc->sp. The number of points into *total. */
static int gatherpoints (const double *points, size_t n, const lsys_space_opts *o, scratch *sc,
                         size_t *total, lsys_error *e) {
  size_t i, ns = 0, w = 0;
  for (i = 0; i < n; i++) {
    if (!lsys_space_near(points + 3 * i, o->radius)) {
      const double *p = points + 3 * i;
      if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return lsys_seterror(e, LSYS_EARG, i, "space: point %zu is not finite", i + 1);
      return lsys_seterror(e, LSYS_EARG, i, "space: point %zu is too far from the origin for "
                           "the radius", i + 1);
    }
  }
  if (o->scene != NULL) {
    ns = scenepoints(sc->sp, o->scene);
    for (i = 0; i < ns; i++)               /* what the cells cannot hold is left out */
      if (lsys_space_near(sc->sp + 3 * i, o->radius)) {
        if (w != i) memcpy(sc->sp + 3 * w, sc->sp + 3 * i, 3 * sizeof(double));
        w++;
      }
  }
  *total = n + w;
  return LSYS_OK;
}

/* The position of point i: listed, or the scene's. */
static const double *pointat (const double *points, size_t n, const scratch *sc, size_t i) {
  return i < n ? points + 3 * i : sc->sp + 3 * (i - n);
}

/* Lays out the sorted keys (S->n of them) as space_impl.h says. */
static int layout (lsys_space *S, const skey *key, const double *points, size_t n,
                   const lsys_space_opts *o, const scratch *sc) {
  size_t s, c, nc = 0;
  for (s = 0; s < S->n; s++)
    if (s == 0 || memcmp(key[s].c, key[s - 1].c, sizeof key[s].c) != 0) nc++;
  S->ncell = nc;
  S->cc = (int64_t *)LSYS_MALLOC(nc > 0 ? 3 * nc * sizeof(int64_t) : 1);
  S->pstart = (uint32_t *)LSYS_MALLOC((nc + 1) * sizeof(uint32_t));
  S->p = (double *)LSYS_MALLOC(S->n > 0 ? 3 * S->n * sizeof(double) : 1);
  S->g = (int64_t *)LSYS_MALLOC(S->n > 0 ? S->n * sizeof(int64_t) : 1);
  S->v = (double *)LSYS_MALLOC(S->n > 0 ? S->n * sizeof(double) : 1);
  S->id = (uint32_t *)LSYS_MALLOC(S->n > 0 ? S->n * sizeof(uint32_t) : 1);
  if (S->cc == NULL || S->pstart == NULL || S->p == NULL || S->g == NULL || S->v == NULL ||
      S->id == NULL)
    return LSYS_ENOMEM;
  memset(S->bstart, 0, (S->mask + 2) * sizeof(uint32_t));
  for (s = 0, c = 0; s < S->n; s++) {
    uint32_t i = key[s].i;
    if (s == 0 || memcmp(key[s].c, key[s - 1].c, sizeof key[s].c) != 0) {
      memcpy(S->cc + 3 * c, key[s].c, sizeof key[s].c);
      S->pstart[c++] = (uint32_t)s;
      S->bstart[lsys_space_hash(key[s].c[0], key[s].c[1], key[s].c[2], S->mask) + 1]++;
    }
    memcpy(S->p + 3 * s, pointat(points, n, sc, i), 3 * sizeof(double));
    S->id[s] = i;
    S->g[s] = i < n && o->groups != NULL ? o->groups[i] : 0;
    S->v[s] = i >= n ? HUGE_VAL : o->vigour != NULL ? o->vigour[i] : 0;
  }
  S->pstart[nc] = (uint32_t)S->n;
  for (c = 0; c <= S->mask; c++) S->bstart[c + 1] += S->bstart[c];
  return LSYS_OK;
}

/* Sorts the S->n points into sc->key by (bucket, cell, index). */
static void sortpoints (lsys_space *S, const double *points, size_t n, scratch *sc) {
  uint32_t *cnt = S->bstart;             /* the buckets' counts first, then their starts */
  size_t i, k, nb = S->mask + 1;
  memset(cnt, 0, (nb + 1) * sizeof(uint32_t));
  for (i = 0; i < S->n; i++) {
    const double *p = pointat(points, n, sc, i);
    sc->bk[i] = (uint32_t)lsys_space_hash(lsys_space_coord(p[0], S->cell),
                                          lsys_space_coord(p[1], S->cell),
                                          lsys_space_coord(p[2], S->cell), S->mask);
    cnt[sc->bk[i] + 1]++;
  }
  for (k = 0; k < nb; k++) cnt[k + 1] += cnt[k];
  for (i = 0; i < S->n; i++) {
    const double *p = pointat(points, n, sc, i);
    skey *q = &sc->key[cnt[sc->bk[i]]++];
    for (k = 0; k < 3; k++) q->c[k] = lsys_space_coord(p[k], S->cell);
    q->i = (uint32_t)i;
  }
  for (k = nb; k > 0; k--) cnt[k] = cnt[k - 1];    /* back to the starts */
  cnt[0] = 0;
  for (k = 0; k < nb; k++)
    if (cnt[k + 1] - cnt[k] > 1) sortbucket(sc->key + cnt[k], cnt[k + 1] - cnt[k]);
}

int lsys_space_build (lsys_space **out, const double *points, size_t n,
                      const lsys_space_opts *o, lsys_error *e) {
  lsys_meter *mt = o != NULL ? o->meter : NULL;
  size_t ns, total, nb = 64, need, used0 = mt != NULL ? mt->used : 0;
  scratch sc = {NULL, NULL, NULL};
  lsys_space *S;
  int st;
  *out = NULL;
  if (o == NULL || !(o->radius > 0 && isfinite(o->radius)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "space: the radius must be a finite number "
                         "> 0");
  ns = o->scene != NULL ? lsys_space_scenepoints(o->scene) : 0;
  if (n > LSYS_SPACE_MAXPOINTS || ns > LSYS_SPACE_MAXPOINTS - n)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "space: more than %u points",
                         LSYS_SPACE_MAXPOINTS);
  total = n + ns;
  while (nb < 2 * total) nb <<= 1;
  need = spacebytes(total, total, nb) + total * (sizeof(uint32_t) + sizeof(skey)) +
         ns * 3 * sizeof(double);
  if (!lsys_common_meter_fits(mt, need)) return nomemory(e, mt, need);
  if ((S = (lsys_space *)LSYS_MALLOC(sizeof *S)) == NULL) return LSYS_ENOMEM;
  memset(S, 0, sizeof *S);
  S->cell = o->radius;
  S->listed = n;
  S->mask = nb - 1;
  S->bstart = (uint32_t *)LSYS_MALLOC((nb + 1) * sizeof(uint32_t));
  sc.sp = (double *)LSYS_MALLOC(ns > 0 ? 3 * ns * sizeof(double) : 1);
  sc.bk = (uint32_t *)LSYS_MALLOC(total > 0 ? total * sizeof(uint32_t) : 1);
  sc.key = (skey *)LSYS_MALLOC(total > 0 ? total * sizeof(skey) : 1);
  if (mt != NULL) mt->used += need;
  if (S->bstart == NULL || sc.sp == NULL || sc.bk == NULL || sc.key == NULL) st = LSYS_ENOMEM;
  else if ((st = gatherpoints(points, n, o, &sc, &S->n, e)) == LSYS_OK) {
    sortpoints(S, points, n, &sc);
    st = layout(S, sc.key, points, n, o, &sc);
  }
  LSYS_FREE(sc.sp);
  LSYS_FREE(sc.bk);
  LSYS_FREE(sc.key);
  S->bytes = spacebytes(S->n, S->ncell, nb);
  if (mt != NULL) mt->used = used0 + (st == LSYS_OK ? S->bytes : 0);
  if (st != LSYS_OK) {
    lsys_space_free(S);
    return st;
  }
  *out = S;
  return LSYS_OK;
}

void lsys_space_info (const lsys_space *S, lsys_space_stats *st) {
  st->points = S->n;
  st->listed = S->listed;
  st->cells = S->ncell;
  st->buckets = S->mask + 1;
  st->bytes = S->bytes;
  st->radius = S->cell;
}

/* ---------------------------------------------------------------------- */
/* queries */

typedef struct qjob {
  const lsys_space *S;
  const lsys_space_ask *q;
  double *out;
  double r2, off2;
  int64_t span;
  size_t n;                       /* query points, or stored points (own queries) */
} qjob;

/* The answer for the query point x (group g, vigour vg), leaving out the
** stored point whose id is 'self'. */
static double ask1 (const qjob *j, const double x[3], uint32_t self, int64_t g, double vg) {
  const lsys_space *S = j->S;
  const double r2 = j->r2, off2 = j->off2;
  const int kind = j->q->kind;
  int64_t c[3], dy, dz, k = j->span;
  double acc = kind == LSYS_SPACE_NEAREST ? HUGE_VAL : 0;
  int i;
  for (i = 0; i < 3; i++) c[i] = lsys_space_coord(x[i], S->cell);
  for (dy = -k; dy <= k; dy++)
    for (dz = -k; dz <= k; dz++) {
      uint32_t rg[2 * LSYS_SPACE_MAXSPAN + 1][2], s;
      int nr = lsys_space_rowcells(S, c[0] - k, c[0] + k, c[1] + dy, c[2] + dz, rg), ir;
      for (ir = 0; ir < nr; ir++)
        for (s = rg[ir][0]; s < rg[ir][1]; s++) {
          const double *p = S->p + 3 * (size_t)s;
          double ex, ey, ez, d2;
          if (S->id[s] == self) continue;
          ex = x[0] - p[0];
          ey = x[1] - p[1];
          ez = x[2] - p[2];
          d2 = ex * ex + ey * ey + ez * ez;
          if (!(d2 <= r2)) continue;
          if (d2 < off2 && S->id[s] >= S->listed) continue;
          switch (kind) {
            case LSYS_SPACE_COUNT: acc += 1; break;
            case LSYS_SPACE_DENSITY: {
              double t = 1 - d2 / r2;
              acc += t * t;
              break;
            }
            case LSYS_SPACE_NEAREST: if (d2 < acc) acc = d2; break;
            default: if (S->g[s] == g && vg <= S->v[s]) return 0;
          }
        }
    }
  if (kind == LSYS_SPACE_FREE) return 1;
  if (kind == LSYS_SPACE_NEAREST && acc < HUGE_VAL) return sqrt(acc);
  return acc;
}

static void qwork (void *ctx, size_t chunk) {
  const qjob *j = (const qjob *)ctx;
  const lsys_space_ask *q = j->q;
  const lsys_space *S = j->S;
  size_t i, a = chunk * CHUNK, b = a + CHUNK < j->n ? a + CHUNK : j->n;
  for (i = a; i < b; i++) {
    if (q->points == NULL) {              /* stored order: neighbours share cells */
      uint32_t id = S->id[i];
      if (id < S->listed) j->out[id] = ask1(j, S->p + 3 * i, id, S->g[i], S->v[i]);
    } else
      j->out[i] = ask1(j, q->points + 3 * i, UINT32_MAX, q->groups ? q->groups[i] : 0,
                       q->vigour ? q->vigour[i] : 0);
  }
}

int lsys_space_query (const lsys_space *S, const lsys_space_ask *q, double *out,
                      lsys_error *e) {
  double r = q->radius > 0 ? q->radius : S->cell;
  qjob j;
  size_t i;
  if (q->kind < LSYS_SPACE_COUNT || q->kind > LSYS_SPACE_FREE)
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "space: no such query");
  if (!(q->radius >= 0 && r <= LSYS_SPACE_MAXSPAN * S->cell))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "space: the radius must be a number in "
                         "(0, %g] (%d times the space's)", LSYS_SPACE_MAXSPAN * S->cell,
                         LSYS_SPACE_MAXSPAN);
  if (!(q->offset >= 0 && isfinite(q->offset)))
    return lsys_seterror(e, LSYS_EARG, (size_t)-1, "space: the offset must be a finite "
                         "number >= 0");
  if (q->points != NULL)
    for (i = 0; i < q->n; i++)
      if (!lsys_space_near(q->points + 3 * i, S->cell))
        return lsys_seterror(e, LSYS_EARG, i, "space: query point %zu is %s", i + 1,
                             isfinite(q->points[3 * i]) && isfinite(q->points[3 * i + 1]) &&
                             isfinite(q->points[3 * i + 2]) ? "too far from the origin for "
                             "the radius" : "not finite");
  j.S = S;
  j.q = q;
  j.out = out;
  j.r2 = r * r;
  j.off2 = q->offset * q->offset;
  j.span = lsys_space_span(r, S->cell);
  j.n = q->points != NULL ? q->n : S->n;
  lsys_space_run(q->threads, (j.n + CHUNK - 1) / CHUNK, qwork, &j);
  return LSYS_OK;
}
