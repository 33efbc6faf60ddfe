/*
** The parallel step's own types and the helpers its two files share
** (derive_par.c: the phases and threads; derive_class.c: what each symbol's
** modules become, the choices counting keeps). Private to the derivation.
*/
#ifndef LSYS_DERIVE_PAR_IMPL_H
#define LSYS_DERIVE_PAR_IMPL_H

#include <pthread.h>
#include <stdatomic.h>

#include "derive_impl.h"

#define MAXCHUNKS 256
#define CHUNKMIN 2048             /* modules: smaller chunks cost more than they share */

#define NFAST 4                   /* rules of a symbol of class PC_FAST, at most */
#define NORULE 0xFFFF             /* no rule (a copy) */
#define NCTAB 16                  /* symbols of class PC_CTAB, at most */
#define CTN 257                   /* a context table's side: symbols below 256, and none */

/* What a worker does with a module of a symbol. */
enum {
  PC_COPY,      /* no rule: copied */
  PC_PLAIN,     /* one rule that always applies: its template */
  PC_VM,        /* one rule on the expression machine, no condition */
  PC_VMC,       /* the same with a condition */
  PC_FAST,      /* up to NFAST rules without contexts or weights, each a program of
                ** lsys_expr_fast's form (or a template): the first that applies */
  PC_CTAB,      /* rules of templates with a context of at most one module each side,
                ** of symbols without parameters: the rule by those two symbols */
  PC_GEN,       /* contexts, weights, several rules, groups: lsys_derive_choose */
  PC_SEQ        /* the sequential step must run */
};

/* What a symbol's modules become: the rule (when one) whose successor has
** 'nsucc' modules and 'nsrc' parameters for modules of 'pnp' parameters
** (NOPNP: none of PC_PLAIN or PC_VM); modules of other counts are copied. */
typedef struct pent {
  uint8_t cls, pnp, nar;      /* nar: the rule's successor fits a narrow string */
  uint8_t fl;                 /* what the rule's successor asks of the string (FL_*) */
  uint8_t pargs;              /* the successor takes parameters of the module's own */
  uint32_t nsucc, nsrc, rule;
  const uint16_t *t;
  const uint8_t *t8;          /* the template as symbols (when nar) */
  lsys_xfast fx;              /* PC_VM: the values without the stack machine (fx.ok) */
  uint32_t nfr, fr[NFAST];    /* PC_FAST: the rules, in the order they are tried */
  uint16_t *ctab;             /* PC_CTAB: the rule (or NORULE) by left and right symbol */
} pent;

#define NOPNP 0xFF

/* What a module's successor asks of the new string (chunk flags). */
enum { FL_WIDE = 1, FL_GEN = 2, FL_SHRINK = 4, FL_CTX = 8 };  /* FL_CTX: filling
                                  ** reads the neighbours (a context table) */

#define CW_SLOW ((uint64_t)1 << 63)
#define CW(n, np, fl) ((uint64_t)(n) | (uint64_t)(np) << 24 | (uint64_t)(fl) << 48)

/* The modules of a narrow string, by symbol: copied (NK_COPY), replaced by
** a template of at most NTPL symbols that fits a narrow string (NK_TPL), or
** the general path (NK_SLOW). */
enum { NK_COPY, NK_TPL, NK_SLOW };
#define NTPL 32

/* A chunk's choices: what counting found for each module of class PC_GEN
** (its rule, NORULE when it is copied, and the parameters of its successor),
** so that filling writes them without choosing again. */
typedef struct gcache {
  uint16_t *rid; size_t rcap;
  double *par; size_t pcap;
} gcache;


/* The workers' scratch, kept by the model between steps. */
typedef struct lsys_par {
  lsys_scratch ws[LSYS_MAXTHREADS];
  lsys_brkwin win[LSYS_MAXTHREADS];   /* the workers' context windows */
  struct side {                /* filling in place on several threads: the source of the
                               ** chunk a worker fills, copied before others overwrite it */
    uint16_t *code; size_t codecap;
    uint8_t *code8; size_t code8cap;
    double *par; size_t parcap;
  } side[LSYS_MAXTHREADS];
  gcache gc[MAXCHUNKS];       /* by chunk; sized from the step before (gneed*) */
  size_t gneedr, gneedp;      /* the most choices and parameters a chunk needed */
  pent *pe; size_t npe;       /* per symbol */
  uint8_t *t8; size_t nt8;    /* m->tcode as symbols */
  uint8_t *rnar; size_t nrnar;  /* per rule: its successor fits a narrow string */
  lsys_xfast *rfx; size_t nrfx; /* per rule: its program without the stack machine */
  uint16_t *ctab;             /* NCTAB tables of CTN * CTN rules (PC_CTAB) */
  uint8_t nkind[256], nlen[256];
  uint64_t wcount[256 << LSYS_NPBITS];  /* codes of symbols below 256: CW_SLOW, or the
                              ** successor's modules, parameters << 24 and FL_* << 48 */
  uint8_t ntpl[256][NTPL];    /* NK_TPL: the template at the end (filling goes backwards) */
} lsys_par;

typedef struct chunk {
  size_t a, b;                /* source modules [a, b) */
  size_t sp, nsp;             /* its first parameter, its parameters */
  size_t cnt, pcnt;           /* modules and parameters of its successors */
  size_t o, po;               /* where they go in the new string */
  size_t lo;                  /* filling: modules [lo, b) are written */
  size_t fail;                /* filling: the module whose values failed, or SIZE_MAX */
  int bad, wide, gen, shrink; /* counting: failed; needs a wide string; lsys_derive_choose ran; a
                              ** successor shorter than its module; */
  int ctx;                    /* filling reads the neighbours */
  int side;                   /* filling in place: its source is in the side copy of worker
                              ** side - 1 (0: none) */
  size_t nr, npc;             /* choices kept in the chunk's gcache: entries, parameters */
  size_t upto;                /* modules [a, upto) have their choices kept */
  size_t needr, needp;        /* the choices and parameters the whole chunk had */
} chunk;

enum { PH_NP, PH_COUNT, PH_FILL };

typedef struct job {
  lsys_rules *m;
  const uint16_t *code;       /* the source: wide, */
  const uint8_t *code8;       /* or narrow */
  const double *spar;
  lsys_lstring *out;
  const view *v;
  view wv[LSYS_MAXTHREADS];   /* each worker's: v with its own window (contexts) */
  lsys_ruleset *const *sets;
  int nsets, phase, withnp, narrow, inplace, keep;   /* keep: choices go in gcaches */
  int copy;                   /* filling in place, each chunk copies its source aside
                              ** first, so that the chunks before it need not wait */
  const lsys_par *P;
  lsys_rng rng;               /* each worker draws from a copy */
  chunk ch[MAXCHUNKS];
  atomic_int done[MAXCHUNKS]; /* filling in place: chunk written, */
  atomic_int copied[MAXCHUNKS];   /* or its source copied aside (copy) */
  atomic_int stop;
  size_t nch;
  atomic_size_t next;
} job;

typedef struct worker { job *j; lsys_scratch *w; lsys_rng rng; pthread_t t; int id; } worker;

/* The view worker scratch 'w' matches contexts in. */
static inline const view *wview (const job *j, const lsys_scratch *w) {
  return &j->wv[w - j->P->ws];
}

/* The output of a chunk being filled, from its end: codes down to o0,
** parameters down to p0. */
typedef struct wout {
  uint16_t *o0, *oc; double *p0, *op;
  const uint16_t *rid; const double *cp;   /* the chunk's kept choices, */
  size_t nr, npc, upto;                    /* taken from the end */
} wout;

static inline uint16_t srccode (const job *j, size_t i) {
  return j->code8 != NULL ? (uint16_t)LSYS_CODE(j->code8[i], 0) : j->code[i];
}

/* The templates as symbols and the workers' scratch (0: no memory). */
int lsys_derive_par_prepare (lsys_rules *m, lsys_par *P, int nt);
/* Every symbol's class (0: the step must run on the calling thread). */
int lsys_derive_par_classify (lsys_rules *m, lsys_ruleset *const *sets, int nsets, int *needsp,
                              int *genp);
/* The rule module i takes (NULL: copied), its arguments and values; -1: sequential. */
int lsys_derive_par_pick (job *j, lsys_scratch *w, size_t i, uint16_t cd, const double **args,
                          const double **vals, const lsys_rule **rule);
/* The parameters of rule r's successor into op. */
void lsys_derive_par_succpar (const lsys_rules *m, const lsys_rule *r, const double *args,
                              const double *vals, double *op);
/* The choices counting keeps: kept, their cursor for filling, the next one, the room. */
void lsys_derive_par_keepchoice (job *j, chunk *c, size_t i, const lsys_rule *r, const double *args,
                                 const double *vals);
void lsys_derive_par_keptchoices (const job *j, const chunk *c, wout *o);
int lsys_derive_par_kept (wout *o, const lsys_rules *m, size_t i, const lsys_rule **r,
                          const double **kp);
void lsys_derive_par_keeproom (job *j, const lsys_lstring *src);
void lsys_derive_par_keptneed (job *j, size_t n);

#endif
