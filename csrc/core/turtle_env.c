/*
** ?E, the communication module of open L-systems (Mech and Prusinkiewicz 1996, §3; cpfg's
** environmental pass, docs/open.md): each ?E the interpretation meets is appended to
** t->envq with the turtle's state there and the module that follows it, in the order the
** turtle meets them, for the environment to answer before the next step. A ?E that the
** homomorphism made is a query too, but its parameters live in the expansion: they and its
** following module are copied into the queries' pool, and its answers have nowhere to go
** (cpfg sends such a module and throws its answers away). See turtle_impl.h.
*/
#include <string.h>

#include "turtle_impl.h"

void lsys_turtle_envfree (lsys_envqueries *q) {
  LSYS_FREE(q->q);
  LSYS_FREE(q->pool);
  memset(q, 0, sizeof *q);
}

/* Copies 'n' parameters into the pool; their offset there in *at. */
static int pooled (run *R, lsys_envqueries *Q, const double *p, uint32_t n, size_t *at) {
  if (Q->npool + n > Q->poolcap &&
      lsys_common_grow_metered((void **)&Q->pool, &Q->poolcap, Q->npool + n, sizeof *Q->pool,
                               R->t->meter) != LSYS_OK)
    return lsys_turtle_nomem(R);
  *at = Q->npool;
  if (n > 0) memcpy(Q->pool + Q->npool, p, n * sizeof *p);
  Q->npool += n;
  return LSYS_OK;
}

int lsys_turtle_envquery (run *R, const double *p, uint32_t np, int original) {
  lsys_envqueries *Q = R->t->envq;
  const lsys_tstate *st = &R->st;
  lsys_envquery *q;
  int e;
  if (Q->n >= Q->cap &&
      lsys_common_grow_metered((void **)&Q->q, &Q->cap, Q->n + 1, sizeof *Q->q,
                               R->t->meter) != LSYS_OK)
    return lsys_turtle_nomem(R);
  q = &Q->q[Q->n];
  memset(q, 0, sizeof *q);
  q->np = np;
  q->next = LSYS_ENVQ_NONE;
  if (original) {
    const lsys_lstring *s = R->s;
    q->mod = R->mod;
    q->par = R->nextpar - np;
    if (R->mod + 1 < s->n) {
      uint16_t c = s->sym8 != NULL ? (uint16_t)LSYS_CODE(s->sym8[R->mod + 1], 0)
                                   : s->code[R->mod + 1];
      q->next = LSYS_CSYM(c);
      q->nextnp = LSYS_CNP(c);
      q->nextpar = R->nextpar;
    }
  } else {
    const lsys_lstring *h = &R->t->hbuf;
    q->mod = LSYS_ENVQ_MADE;
    if ((e = pooled(R, Q, p, np, &q->par)) != LSYS_OK) return e;
    if (R->hj + 1 < h->n) {
      uint16_t c = h->code[R->hj + 1];
      q->next = LSYS_CSYM(c);
      q->nextnp = LSYS_CNP(c);
      if ((e = pooled(R, Q, h->par + R->hnext, q->nextnp, &q->nextpar)) != LSYS_OK) return e;
    }
  }
  memcpy(q->pos, st->pos, sizeof q->pos);
  memcpy(q->H, st->H, sizeof q->H);
  memcpy(q->L, st->L, sizeof q->L);
  memcpy(q->U, st->U, sizeof q->U);
  q->width = st->width;
  q->scale = st->scale;
  q->color = (uint16_t)st->color;
  Q->n++;
  return LSYS_OK;
}
