/*
** The turtle on several threads: a long string is cut at its big
** branches. A branch's state is known as soon as its '[' is reached, and the
** module after its ']' starts from that same state (']' restores what '['
** saved), so the string falls into pieces, each a run of modules with a known
** start: the first piece starts from the turtle's first state, the first
** piece of a branch and the piece after the branch both start where the piece
** before the '[' ended. Pieces run as soon as that piece is done.
**
** The scene is exactly the one-thread turtle's, for every number of threads:
**   - records and lines: one pass over the string counts what each piece
**     writes (F and G a line in the line style and a record; @O @o @c @L a
**     record), so every piece writes straight to its place in the scene, and
**     record indices (a record's parent) are final when written;
**   - vertices, triangles and stiffnesses: each piece has its own, copied to
**     the scene in string order afterwards with their indices moved (a
**     record's triangles and stiffness, a triangle's vertices);
**   - open cylinder ends: a piece that starts at an open end continues it by
**     its ring in the piece that drew it (vertex indices from FOREIGN on, moved
**     when copied); the caps on the ends nothing continued come last, as in
**     one run.
** Modules whose effect crosses branches through something other than the
** state (polygons, generalized cylinders, patches, surfaces, sub-L-systems,
** @S: the symbol table's LSYS_SPLIT_CROSS, the default, symbols.h) and
** homomorphisms keep the string on one thread.
*/
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "turtle_impl.h"

#define MAXPIECES 2048              /* pieces of one run (at most) */
#define PIECEMIN  ((size_t)1 << 12) /* the smallest branch cut off by default, */
#define PIECES    512               /* or 1/PIECES of the string */
#define PARMIN    ((size_t)1 << 16) /* shorter strings run on one thread */
#define MAXOPEN   ((size_t)1 << 20) /* deeper nesting keeps the string on one thread */
#define FOREIGN   (UINT32_MAX - 2048u)   /* vertex FOREIGN + k: k-th of the inherited ring */
#define LSYS_PARTHREADS 64         /* as derive.h's LSYS_MAXTHREADS */

enum { K_OPEN = 1, K_CLOSE = 2, K_CROSS = 4 };

/* The k-th item of array a, which may be NULL (then empty: no pointer arithmetic on it). */
#define AT(a, k) ((a) != NULL ? (a) + (k) : NULL)

/* Places in the scene's records, lines and record end points, and in the
** parameter pool; the modules that draw triangles. */
typedef struct at { size_t rec, line, pt, par, shape; } at;

typedef struct branch { size_t i, j; at ai, aj; } branch;   /* modules [i, j) */

typedef struct piece {
  size_t a, b;                 /* modules [a, b) */
  at at;                       /* where its records, lines and parameters start */
  size_t nrec, nline, npt;     /* how many it writes */
  size_t h0;                   /* where its record shapes go in the scene */
  int dep;                     /* the piece whose end state starts it; -1: the first state */
  lsys_scene sc;               /* its output: records, lines and end points borrowed from
                                  the scene's; its own shapes and stiffnesses */
  lsys_cylend *ends; size_t nends, endcap;
  int foreign;                 /* ends[0] is the open end of piece src, srcend, continued */
  int src; size_t srcend;
  size_t nv, nt;               /* its vertices and triangles */
  size_t v0, t0, s0;           /* where they and its stiffnesses go */
  unsigned curtex;             /* the mesh's texture when it ended (UINT32_MAX: drew nothing) */
  lsys_tstate end;             /* the state after b */
  int kid[2], nkid;            /* the pieces that start from its end state */
  lsys_error err;
  int status;                  /* LSYS_OK, an error, or 1: not run (an earlier piece failed) */
} piece;

typedef struct par {
  lsys_turtle *t;
  const lsys_lstring *s;
  const lsys_alphabet *ab;
  const lsys_tstate *first;
  piece *p; int np;
  int phase;                   /* 0: run the pieces, 1: put their geometry in place */
  int dry;                     /* 1: pieces draw triangles: phase 0 counts them (drawn to
                                  scratch), phase 1 draws them again, to their places */
  atomic_int next;             /* phase 1: the next piece to copy */
  pthread_mutex_t mx;          /* phase 0: the pieces ready to run, and the meter */
  pthread_cond_t cv;
  int *ready, nready, finished;
  int maxsides;                /* the most sides of the run's cylinders, discs, spheres */
} par;

/* ---------------------------------------------------------------------- */
/* the cut */

/* What each symbol is to the cut: bracket or crossing (cls), and what it writes
** (inc: records, lines, record end points and modules that draw triangles, one
** count in each 16 bits), from the symbol table's split class of its operation
** (symbols.h); a class this does not know, like an operation out of the table,
** crosses branches. */
#define INC(rec, line, pt, shape) \
  ((uint64_t)(rec) | (uint64_t)(line) << 16 | (uint64_t)(pt) << 32 | (uint64_t)(shape) << 48)

static void classify (const lsys_turtle *t, uint8_t *cls, uint64_t *inc) {
  size_t k;
  int rec = !t->o->norecords, line = t->o->style == LSYS_STYLE_LINE;
  for (k = 0; k < t->nop; k++) {
    cls[k] = 0;
    inc[k] = 0;
    switch (lsys_symbols_split(t->op[k])) {
      case LSYS_SPLIT_STATE: break;
      case LSYS_SPLIT_OPEN: cls[k] = K_OPEN; break;
      case LSYS_SPLIT_CLOSE: cls[k] = K_CLOSE; break;
      case LSYS_SPLIT_SEGMENT:       /* a line's record has the line's end point */
        inc[k] = INC(rec, line, rec && !line, !line);
        break;
      case LSYS_SPLIT_SHAPE: inc[k] = INC(rec, 0, rec, 1); break;
      case LSYS_SPLIT_RECORD: inc[k] = INC(rec, 0, rec, 0); break;
      default: cls[k] = K_CROSS; break;       /* LSYS_SPLIT_CROSS and anything else */
    }
  }
}

/* Adds the counts packed in *acc to *cur and empties it. */
static void addcounts (at *cur, uint64_t *acc) {
  cur->rec += (size_t)(*acc & 0xffff);
  cur->line += (size_t)(*acc >> 16 & 0xffff);
  cur->pt += (size_t)(*acc >> 32 & 0xffff);
  cur->shape += (size_t)(*acc >> 48);
  *acc = 0;
}

/* Finds the branches of at least *minsize modules (doubled while there are too
** many) and counts the records, lines and parameters; returns 1 when the string
** is not for pieces, LSYS_ENOMEM, or LSYS_OK with *nb branches in closing order.
** The counts of the modules since the last bracket add up in 16-bit fields of one
** word, emptied at each bracket and every 65,535 modules (a module adds at most 1
** to each). */
static int scan (const lsys_turtle *t, const lsys_lstring *s, branch *br, int *nb,
                 size_t *minsize, at *total) {
  typedef struct opened { size_t i; at a; } opened;
  size_t i, i1, depth = 0, opencap = 0, nop = t->nop, ntab = nop > 256 ? nop : 256;
  const uint8_t *s8 = s->sym8;
  uint8_t *cls;
  uint64_t *inc, acc = 0;
  opened *open = NULL;
  at cur = {0, 0, 0, 0, 0};
  int n = 0, st = LSYS_OK;
  if ((inc = (uint64_t *)LSYS_MALLOC(ntab * (sizeof *inc + 1))) == NULL) return LSYS_ENOMEM;
  cls = (uint8_t *)(inc + ntab);
  memset(inc, 0, ntab * (sizeof *inc + 1));
  classify(t, cls, inc);
  for (i = 0; i < s->n && st == LSYS_OK; i = i1) {
    i1 = s->n - i > 65535 ? i + 65535 : s->n;
    for (; i < i1; i++) {
      uint16_t c = s8 != NULL ? (uint16_t)LSYS_CODE(s8[i], 0) : s->code[i];
      uint32_t sym = LSYS_CSYM(c);
      int k;
      if (sym >= nop) sym = 0;              /* the table's entry 0 is nothing */
      cur.par += LSYS_CNP(c);
      if ((k = cls[sym]) == 0) { acc += inc[sym]; continue; }
      addcounts(&cur, &acc);
      if (k == K_CROSS) { st = 1; break; }
      if (k == K_OPEN) {
        if (depth == opencap && (depth >= MAXOPEN || lsys_common_grow((void **)&open, &opencap,
                                                                      depth + 1, sizeof *open))) {
          st = depth >= MAXOPEN ? 1 : LSYS_ENOMEM;
          break;
        }
        open[depth].i = i;
        open[depth++].a = cur;
      }
      else if (depth > 0 && i + 1 - open[--depth].i >= *minsize) {
        while (n == MAXPIECES / 2) {       /* too many: only the bigger ones */
          int k2, m = 0;
          *minsize *= 2;
          for (k2 = 0; k2 < n; k2++)
            if (br[k2].j - br[k2].i >= *minsize) br[m++] = br[k2];
          n = m;
        }
        if (i + 1 - open[depth].i >= *minsize) {
          br[n].i = open[depth].i; br[n].j = i + 1;
          br[n].ai = open[depth].a; br[n].aj = cur;
          n++;
        }
      }
    }
    addcounts(&cur, &acc);
  }
  LSYS_FREE(open);
  LSYS_FREE(inc);
  *nb = n;
  *total = cur;
  return st;
}

static int bystart (const void *x, const void *y) {
  const branch *a = (const branch *)x, *b = (const branch *)y;
  return (a->i > b->i) - (a->i < b->i);
}

/* A new piece from module a (with the counts 'x') whose start state is dep's end. */
static piece *newpiece (par *P, size_t a, at x, int dep) {
  piece *p = &P->p[P->np++];
  memset(p, 0, sizeof *p);
  p->a = a;
  p->at = x;
  p->dep = dep;
  if (dep >= 0) P->p[dep].kid[P->p[dep].nkid++] = P->np - 1;
  return p;
}

static void endpiece (piece *p, size_t b, at x) {
  p->b = b;
  p->nrec = x.rec - p->at.rec;
  p->nline = x.line - p->at.line;
  p->npt = x.pt - p->at.pt;
}

/* The pieces of the string from its branches, in string order. A branch of
** the cut is at least as long as any branch it holds, so the branches that
** enclose a cut one are cut too: a piece never closes a bracket that another
** piece opened, except the ']' that ends its branch. */
static void cut (par *P, branch *br, int nb, at total) {
  static const at zero = {0, 0, 0, 0, 0};
  int dep[MAXPIECES / 2], nopen = 0, cur = 0, k;
  size_t close[MAXPIECES / 2];
  at closeat[MAXPIECES / 2];
  qsort(br, (size_t)nb, sizeof *br, bystart);
  P->np = 0;
  newpiece(P, 0, zero, -1);
  for (k = 0; ; k++) {
    size_t next = k < nb ? br[k].i : (size_t)-1;
    while (nopen > 0 && close[nopen - 1] <= next) {   /* a branch ends: back to its parent */
      nopen--;
      endpiece(&P->p[cur], close[nopen], closeat[nopen]);
      cur = P->np;
      newpiece(P, close[nopen], closeat[nopen], dep[nopen]);
    }
    if (k == nb) break;
    endpiece(&P->p[cur], br[k].i, br[k].ai);        /* a branch starts */
    dep[nopen] = cur;
    cur = P->np;
    newpiece(P, br[k].i, br[k].ai, dep[nopen]);
    close[nopen] = br[k].j;
    closeat[nopen++] = br[k].aj;
  }
  endpiece(&P->p[cur], P->s->n, total);
}

/* ---------------------------------------------------------------------- */
/* the pieces on the threads */

typedef struct worker {
  par *P;
  lsys_turtle wt;
  lsys_mesh scratch;           /* phase 0: the geometry of a piece that draws triangles */
  float *stiff; size_t stiffcap;    /* phase 1: the stiffnesses drawn again */
  pthread_t th;
} worker;

/* The start state of a piece; an open end of an earlier piece that it may
** continue is copied to wt->ends[0]. Phase 0 finds that end's piece and index
** (p->src, p->srcend; the earlier piece's own copy names it); phase 1 reads them. */
static int startof (par *P, lsys_turtle *wt, piece *p, lsys_tstate *st) {
  *st = p->dep < 0 ? *P->first : P->p[p->dep].end;
  wt->nends = 0;
  if (st->tip == LSYS_NOREC) return LSYS_OK;
  if (P->phase == 0) {
    const piece *d = &P->p[p->dep];
    if (d->foreign && st->tip == 0) { p->src = d->src; p->srcend = d->srcend; }
    else { p->src = p->dep; p->srcend = st->tip; }
    p->foreign = 1;
  }
  if (lsys_common_grow((void **)&wt->ends, &wt->endcap, 1, sizeof *wt->ends) != LSYS_OK)
    return lsys_seterror(&wt->err, LSYS_ENOMEM, p->a, "not enough memory");
  wt->ends[0] = P->p[p->src].ends[p->srcend];
  wt->ends[0].ring = FOREIGN;
  wt->ends[0].continued = 0;
  wt->nends = 1;
  st->tip = 0;
  return LSYS_OK;
}

/* Runs piece p into the scene shell 'sc': records, lines and record end
** points go to their places in the scene (written again, the same, in phase
** 1), the rest to the arrays sc holds: in phase 0 the piece's own shapes (its
** records name them from 0), in phase 1 their places in the scene. */
static int runin (par *P, worker *w, piece *p, lsys_scene *sc) {
  lsys_turtle *wt = &w->wt;
  lsys_scene *S = P->t->scene;
  lsys_tstate st;
  size_t base[4];
  int status;
  sc->rec = AT(S->rec, p->at.rec);
  sc->reccap = p->nrec;
  sc->nrec = 0;
  sc->recpt = AT(S->recpt, 3 * p->at.pt);
  sc->ptcap = 3 * p->npt;
  sc->npt = 0;
  sc->nshape = 0;
  base[0] = p->at.rec; base[1] = p->at.line; base[2] = p->at.pt;
  base[3] = P->phase == 0 ? 0 : p->h0;
  wt->fixshape = P->phase != 0;
  sc->mesh.lpos = AT(S->mesh.lpos, 6 * p->at.line);
  sc->mesh.lwidth = AT(S->mesh.lwidth, 2 * p->at.line);
  sc->mesh.lcol = AT(S->mesh.lcol, p->at.line);
  sc->mesh.lcap = p->nline;
  sc->mesh.nl = 0;
  sc->meter = S->meter;
  sc->mesh.meter = S->mesh.meter;
  wt->scene = sc;
  if ((status = startof(P, wt, p, &st)) != LSYS_OK) return status;
  status = lsys_turtle_runpiece(wt, P->s, P->ab, p->a, p->b, p->at.par, &st, base);
  if (status == LSYS_OK && (sc->nrec != p->nrec || sc->mesh.nl != p->nline ||
                            sc->npt != p->npt || (P->phase != 0 && sc->nshape != sc->shapecap)))
    status = lsys_seterror(&wt->err, LSYS_ELIMIT, p->a, "internal error: module %zu: the "
                           "records or lines of a piece were miscounted", p->a + 1);
  return status;
}

/* Phase 0: the piece's records and lines, its end state, open ends and
** stiffnesses; its vertices and triangles counted (drawn to scratch). */
static void runone (par *P, worker *w, piece *p) {
  lsys_turtle *wt = &w->wt;
  lsys_scene sc;
  memset(&sc, 0, sizeof sc);
  sc.mesh = w->scratch;
  sc.mesh.nv = sc.mesh.nt = 0;
  sc.mesh.curtex = UINT32_MAX;               /* "drew nothing" until it draws */
  wt->ends = NULL; wt->endcap = 0;
  p->status = runin(P, w, p, &sc);
  p->err = wt->err;
  p->end = wt->state;
  p->ends = wt->ends; p->nends = wt->nends; p->endcap = wt->endcap;
  wt->ends = NULL; wt->nends = wt->endcap = 0;
  p->nv = sc.mesh.nv; p->nt = sc.mesh.nt;
  p->curtex = sc.mesh.curtex;
  p->sc.stiff = sc.stiff; p->sc.nstiff = sc.nstiff; p->sc.stiffcap = sc.stiffcap;
  p->sc.shape = sc.shape; p->sc.nshape = sc.nshape; p->sc.shapecap = sc.shapecap;
  sc.mesh.lpos = NULL; sc.mesh.lwidth = NULL; sc.mesh.lcol = NULL; sc.mesh.lcap = 0;
  w->scratch = sc.mesh;                      /* what grew stays for the next piece */
  if (p->status == LSYS_OK && !P->dry && p->nv + p->nt > 0)
    p->status = lsys_seterror(&p->err, LSYS_ELIMIT, p->a, "internal error: module %zu: "
                              "a piece drew triangles unannounced", p->a + 1);
  if (p->status == LSYS_OK && p->nv >= FOREIGN)
    p->status = lsys_seterror(&p->err, LSYS_ELIMIT, p->a, "module %zu: more than %u vertices",
                              p->a + 1, (unsigned)FOREIGN);
}

/* Phase 1: draws the piece's vertices and triangles again, to their places
** in the scene, and moves its indices: a triangle's vertices, a record's
** triangles and stiffness; copies its stiffnesses. */
static int placeone (par *P, worker *w, piece *p) {
  lsys_scene *S = P->t->scene, sc;
  lsys_mesh *m = &S->mesh;
  size_t k;
  if (P->dry) {
    lsys_turtle *wt = &w->wt;
    lsys_mesh *pm = &sc.mesh;
    uint32_t v0 = (uint32_t)p->v0, fr = 0;
    int status;
    memset(&sc, 0, sizeof sc);
    pm->pos = AT(m->pos, 3 * p->v0); pm->nrm = AT(m->nrm, 3 * p->v0);
    pm->uv = AT(m->uv, 2 * p->v0); pm->col = AT(m->col, p->v0);
    pm->twosided = AT(m->twosided, p->v0); pm->tex = AT(m->tex, p->v0);
    pm->vcap = m->vcap - p->v0;               /* up to the scene's end (slack) */
    pm->tri = AT(m->tri, 3 * p->t0);
    pm->tcap = m->tcap - p->t0;
    pm->fixed = 1;
    sc.stiff = w->stiff; sc.stiffcap = w->stiffcap;
    sc.shape = AT(S->shape, p->h0); sc.shapecap = p->sc.nshape;
    status = runin(P, w, p, &sc);
    w->stiff = sc.stiff; w->stiffcap = sc.stiffcap;
    if (status == LSYS_OK && (pm->nv != p->nv || pm->nt != p->nt))
      status = lsys_seterror(&wt->err, LSYS_ELIMIT, p->a, "internal error: module %zu: a "
                             "piece drew other triangles the second time", p->a + 1);
    if (status != LSYS_OK) { p->err = wt->err; return p->status = status; }
    if (p->foreign) fr = (uint32_t)(P->p[p->src].v0 + P->p[p->src].ends[p->srcend].ring);
    for (k = 0; k < 3 * p->nt; k++) {
      uint32_t x = pm->tri[k];
      pm->tri[k] = x >= FOREIGN ? fr + (x - FOREIGN) : x + v0;
    }
  }
  if (!P->dry && p->sc.nshape > 0) {    /* the shapes to their place, the records to them */
    lsys_rec *r = S->rec + p->at.rec;
    memcpy(S->shape + p->h0, p->sc.shape, p->sc.nshape * sizeof *S->shape);
    if (p->h0 > 0)
      for (k = 0; k < p->nrec; k++) r[k].shape += (uint32_t)p->h0;
  }
  if (p->t0 > 0 || p->s0 > 0) {
    lsys_rshape *h = AT(S->shape, p->h0);
    for (k = 0; k < p->sc.nshape; k++) {
      h[k].tri0 += (uint32_t)p->t0;
      if (h[k].stiff != LSYS_NOREC) h[k].stiff += (uint32_t)p->s0;
    }
  }
  if (p->sc.nstiff > 0)
    memcpy(S->stiff + 3 * p->s0, p->sc.stiff, 3 * p->sc.nstiff * sizeof(float));
  return LSYS_OK;
}

/* Phase 0: runs the pieces as their start states become known. A worker goes
** on with the piece after a branch itself (the trunk it walks) and leaves the
** branch to the others. Phase 1: copies the pieces' geometry. */
static void *work (void *arg) {
  worker *w = (worker *)arg;
  par *P = w->P;
  int k = -1;
  if (P->phase == 1) {
    while ((k = atomic_fetch_add(&P->next, 1)) < P->np) placeone(P, w, &P->p[k]);
    return NULL;
  }
  for (;;) {
    piece *p;
    if (k < 0) {                               /* take a ready piece, or stop */
      pthread_mutex_lock(&P->mx);
      while (P->nready == 0 && P->finished < P->np) pthread_cond_wait(&P->cv, &P->mx);
      if (P->nready > 0) k = P->ready[--P->nready];
      pthread_mutex_unlock(&P->mx);
      if (k < 0) return NULL;
    }
    p = &P->p[k];
    if (p->dep >= 0 && P->p[p->dep].status != LSYS_OK) p->status = 1;
    else runone(P, w, p);
    pthread_mutex_lock(&P->mx);
    P->finished++;
    if (p->nkid > 1) P->ready[P->nready++] = p->kid[0];
    if (p->nkid > 1 || P->finished == P->np) pthread_cond_broadcast(&P->cv);
    pthread_mutex_unlock(&P->mx);
    k = p->nkid > 0 ? p->kid[p->nkid - 1] : -1;
  }
}

/* Runs a phase on 'nt' threads (the caller's one of them). */
static void phase (par *P, worker *w, int nt, int ph) {
  int k, started = 1;
  P->phase = ph;
  atomic_store(&P->next, 0);
  P->nready = 1; P->ready[0] = 0; P->finished = 0;
  for (k = 1; k < nt; k++, started++)
    if (pthread_create(&w[k].th, NULL, work, &w[k]) != 0) break;
  work(&w[0]);
  for (k = 1; k < started; k++) pthread_join(w[k].th, NULL);
}

/* ---------------------------------------------------------------------- */
/* the run */

/* The most vertices (what = 0) or triangles (1) one module of a piece asks
** room for at once (a cylinder's, a sphere's): the scene has that much room
** past its pieces' places, so that a piece drawing to its places asks for
** room that is there (it uses exactly what it counted). */
static size_t slack (const par *P, int what) {
  size_t n = (size_t)P->maxsides, rows = n / 2 < 2 ? 2 : n / 2;
  return what == 0 ? 3 * (n + 2) + (rows + 1) * (n + 1) : 4 * n + 2 * rows * n;
}

/* After the pieces: the places of their vertices, triangles and
** stiffnesses, room for them in the scene, the open ends in string order. */
static int places (par *P) {
  lsys_turtle *t = P->t;
  lsys_scene *S = t->scene;
  size_t nv = 0, ntri = 0, ns = 0, ne = 0, nh = 0;
  int k;
  for (k = 0; k < P->np; k++) {
    piece *p = &P->p[k];
    p->v0 = nv; p->t0 = ntri; p->s0 = ns; p->h0 = nh;
    nv += p->nv; ntri += p->nt; ns += p->sc.nstiff; nh += p->sc.nshape;
    ne += p->nends - (size_t)p->foreign;
    if (p->foreign && p->ends[0].continued) P->p[p->src].ends[p->srcend].continued = 1;
    if (p->curtex != UINT32_MAX) S->mesh.curtex = p->curtex;
  }
  if (nv > UINT32_MAX || ns >= LSYS_NOREC || nh >= LSYS_NOREC)
    return lsys_seterror(&t->err, LSYS_ELIMIT, (size_t)-1, "more than %u vertices",
                         (unsigned)UINT32_MAX);
  if (nh > 0 && lsys_scene_reserve_shapes(S, nh) != LSYS_OK) goto nomem;
  if ((nv > 0 || ntri > 0) && lsys_mesh_reserve(&S->mesh, nv + slack(P, 0), ntri + slack(P, 1))
                               != LSYS_OK)
    goto nomem;
  if (ns > 0 && lsys_common_grow_metered((void **)&S->stiff, &S->stiffcap, 3 * ns, sizeof(float),
                                         S->meter) != LSYS_OK)
    goto nomem;
  if (lsys_common_grow((void **)&t->ends, &t->endcap, ne, sizeof *t->ends) != LSYS_OK) goto nomem;
  t->nends = 0;
  for (k = 0; k < P->np; k++) {
    piece *p = &P->p[k];
    size_t e;
    for (e = (size_t)p->foreign; e < p->nends; e++) {
      t->ends[t->nends] = p->ends[e];
      t->ends[t->nends++].ring += (uint32_t)p->v0;
    }
  }
  S->mesh.nv = nv; S->mesh.nt = ntri; S->nstiff = ns; S->nshape = nh;
  return LSYS_OK;
nomem:
  return lsys_seterror(&t->err, (S->meter && S->meter->hit) || (S->mesh.meter &&
                       S->mesh.meter->hit) ? LSYS_EMEMORY : LSYS_ENOMEM, (size_t)-1,
                       "the interpretation needs more memory than it may use (max_memory)");
}

/* Readies the scene's records and lines for the pieces (exactly the room). */
static int room (lsys_turtle *t, at total) {
  lsys_scene *S = t->scene;
  int st = LSYS_OK;
  if (total.rec >= LSYS_NOREC)
    return lsys_seterror(&t->err, LSYS_ELIMIT, (size_t)-1, "too many turtle records");
  if (total.rec > 0) st = lsys_scene_reserve_records(S, total.rec);
  if (st == LSYS_OK && total.pt > 0) st = lsys_scene_reserve_points(S, total.pt);
  if (st == LSYS_OK && total.line > 0) st = lsys_mesh_reserve_lines(&S->mesh, total.line);
  if (st == LSYS_OK) return LSYS_OK;
  if (st == LSYS_ELIMIT)
    return lsys_seterror(&t->err, st, (size_t)-1, "more than %u line segments",
                         (unsigned)UINT32_MAX);
  return lsys_seterror(&t->err, st, (size_t)-1, st == LSYS_EMEMORY ?
                       "the interpretation would need more than max_memory (set max_memory "
                       "in the model, or LSYS_MAX_MEMORY)" : "not enough memory");
}

static void lock (lsys_turtle *t, void *mx) {
  lsys_meter *m[3];
  int k;
  m[0] = t->meter; m[1] = t->scene->meter; m[2] = t->scene->mesh.meter;
  for (k = 0; k < 3; k++) if (m[k] != NULL) m[k]->lock = mx;
}

/* Runs the pieces and puts their output together. */
static int runall (par *P, int nt) {
  lsys_turtle *t = P->t;
  worker w[LSYS_PARTHREADS];
  int k, st = LSYS_OK;
  for (k = 0; k < nt; k++) {
    lsys_turtle *wt = &w[k].wt;
    w[k].P = P;
    lsys_mesh_init(&w[k].scratch);
    w[k].stiff = NULL; w[k].stiffcap = 0;
    lsys_turtle_init(wt);
    wt->o = t->o; wt->op = t->op; wt->nop = t->nop; wt->ring = t->ring; wt->nring = t->nring;
    wt->meter = t->meter;
  }
  if ((P->ready = (int *)LSYS_MALLOC((size_t)P->np * sizeof *P->ready)) == NULL)
    return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  pthread_mutex_init(&P->mx, NULL);
  pthread_cond_init(&P->cv, NULL);
  lock(t, &P->mx);
  phase(P, w, nt, 0);
  for (k = 0; k < P->np && st == LSYS_OK; k++)
    if (P->p[k].status != LSYS_OK) { t->err = P->p[k].err; st = P->p[k].status; }
  P->maxsides = t->o->sides;                   /* and what @!(n) asked for */
  for (k = 0; k < nt; k++) {
    const lsys_error *e = &w[k].wt.warn;      /* the warning about the first module */
    if (w[k].wt.maxsides > P->maxsides) P->maxsides = w[k].wt.maxsides;
    if (e->code != 0 && (t->warn.code == 0 || e->pos < t->warn.pos)) t->warn = *e;
  }
  if (st == LSYS_OK && (st = places(P)) == LSYS_OK) {
    phase(P, w, nt, 1);
    for (k = 0; k < P->np && st == LSYS_OK; k++)
      if (P->p[k].status != LSYS_OK) { t->err = P->p[k].err; st = P->p[k].status; }
  }
  lock(t, NULL);
  pthread_cond_destroy(&P->cv);
  pthread_mutex_destroy(&P->mx);
  LSYS_FREE(P->ready);
  for (k = 0; k < nt; k++) {
    w[k].wt.op = NULL; w[k].wt.nop = 0; w[k].wt.ring = NULL;
    lsys_turtle_free(&w[k].wt);
    lsys_mesh_free(&w[k].scratch);
    LSYS_FREE(w[k].stiff);
  }
  return st;
}

int lsys_turtle_par (lsys_turtle *t, const lsys_lstring *s, const lsys_alphabet *ab) {
  lsys_scene *S = t->scene;
  int nt = t->threads < 1 ? 1 : t->threads > LSYS_PARTHREADS ? LSYS_PARTHREADS : t->threads;
  size_t minsize = t->piecemin;
  branch *br;
  at total = {0, 0, 0, 0, 0};
  par P;
  int nb = 0, st, k;
  if (minsize == 0) {                       /* by default, long strings on several threads */
    if (nt < 2 || s->n < PARMIN) return 1;
    minsize = s->n / PIECES;
    if (minsize < PIECEMIN) minsize = PIECEMIN;
  }
  if ((br = (branch *)LSYS_MALLOC(MAXPIECES / 2 * sizeof *br)) == NULL)
    return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  st = scan(t, s, br, &nb, &minsize, &total);
  if (st == LSYS_OK && nb == 0 && t->piecemin == 0) st = 1;   /* nothing to share */
  if (st != LSYS_OK) {
    LSYS_FREE(br);
    return st == 1 ? 1 : lsys_seterror(&t->err, st, (size_t)-1, "not enough memory");
  }
  memset(&P, 0, sizeof P);
  P.t = t; P.s = s; P.ab = ab;
  P.first = &((run *)t->runbuf)->st;
  P.dry = total.shape > 0;
  if ((P.p = (piece *)LSYS_MALLOC((size_t)(2 * nb + 1) * sizeof *P.p)) == NULL) {
    LSYS_FREE(br);
    return lsys_seterror(&t->err, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  }
  cut(&P, br, nb, total);
  LSYS_FREE(br);
  t->npieces = P.np;
  if ((st = room(t, total)) == LSYS_OK) st = runall(&P, nt > P.np ? P.np : nt);
  if (st == LSYS_OK) {
    S->nrec = total.rec;
    S->npt = total.pt;
    S->mesh.nl = total.line;
    t->state = P.p[P.np - 1].end;
    st = lsys_turtle_finish(t);
  }
  for (k = 0; k < P.np; k++) {
    LSYS_FREE(P.p[k].sc.stiff);
    LSYS_FREE(P.p[k].sc.shape);
    LSYS_FREE(P.p[k].ends);
  }
  LSYS_FREE(P.p);
  if (st != LSYS_OK && S != NULL) {          /* no half scene */
    lsys_mesh_clear(&S->mesh);
    S->nrec = S->nshape = S->npt = S->nstiff = 0;
  }
  return st;
}
