/*
** The derivation engine (docs/manual.md §6): rule storage, context matching
** with ignore/consider lists, parallel rewriting with stochastic choice,
** cut, sub-L-systems, decomposition and homomorphism.
**
** Semantics follow cpfg (cpfg guide, Appendix A; docs/manual.md §6). Rules whose
** successor needs computing (a condition, parameter expressions, a weight
** expression, a function producing the successor) call back into the
** binding through 'lsys_rulefn'; all other rules are pure template copies.
*/
#ifndef LSYS_DERIVE_H
#define LSYS_DERIVE_H

#include "lstring.h"
#include "expr.h"
#include "rng.h"

enum { LSYS_PROD = 0, LSYS_DECOMP = 1, LSYS_HOMO = 2 };

#define LSYS_MAXTHREADS 64    /* threads of one derivation step */

/* rule flags */
#define LSYS_RF_CALL   1   /* call back: condition and/or computed values */
#define LSYS_RF_DYN    2   /* the callback produces the successor into m->dyn */
#define LSYS_RF_STOCH  4   /* has a weight */
#define LSYS_RF_WEXPR  8   /* the weight is computed: vals[0] */

/* where a successor parameter comes from */
enum { LSYS_PS_CONST = 0, LSYS_PS_ARG = 1, LSYS_PS_VAL = 2 };

typedef struct lsys_patmod { uint32_t sym, np; } lsys_patmod;
typedef struct lsys_psrc { uint32_t kind, idx; double value; } lsys_psrc;

typedef struct lsys_rule {
  uint32_t pred, pred_np;
  uint32_t flags;
  uint32_t lc, nlc, lcargs;     /* pattern modules in m->pat; lcargs = params in lc */
  uint32_t more, nmore, moreargs;  /* predecessor modules after the first (cpfg's strict
                                ** predecessor of several modules) and their params */
  uint32_t rc, nrc;
  uint32_t succ, nsucc;         /* codes in m->tcode */
  uint32_t src, nsrc;           /* parameter sources in m->tsrc */
  uint32_t nargs, nvals;        /* formal parameters; values the callback returns */
  double weight;
  int id;                       /* the caller's rule number (messages) */
  lsys_ins *vm; int nvm;        /* when set, evaluated in C instead of the callback */
  lsys_xfast fx;                /* vm without the stack machine, when fx.ok (expr.h) */
  int vmtry, vmtryout;          /* the program's first vmtry instructions: the condition
                                ** and the weight (vmtryout outputs); cpfg runs the rest,
                                ** the successor's values, only for the chosen rule */
} lsys_rule;

typedef struct lsys_rulespec {
  const lsys_patmod *lc; uint32_t nlc;
  lsys_patmod pred;
  const lsys_patmod *more; uint32_t nmore;  /* more predecessor modules (productions) */
  const lsys_patmod *rc; uint32_t nrc;
  const uint16_t *succ; uint32_t nsucc;   /* successor codes (sym, np) */
  const lsys_psrc *src; uint32_t nsrc;    /* one per successor parameter */
  uint32_t flags, nvals;
  double weight;
  int id;
} lsys_rulespec;

typedef struct lsys_ruleset {
  int kind, sub, group;
  uint32_t *list; size_t nlist, listcap;    /* rules in declaration order */
  uint32_t *byp;                            /* rules grouped by predecessor */
  uint32_t *start; uint32_t nsym;           /* byp[start[s] .. start[s+1]) */
  uint32_t *plain;   /* plain[s]: the first rule for s when it is a pure template copy */
  int compiled, hasctx;
  int stoch;         /* a rule of the set is weighted (cpfg: a stochastic L-system) */
  int pure;          /* trying its rules has no effect but the answer: each runs on the
                        expression machine or is a template, draws nothing, unweighted */
} lsys_ruleset;

typedef struct lsys_skip {
  int sub, consider;
  uint8_t bits[(LSYS_MAXSYM + 8) / 8];
  uint8_t lcls[256], rcls[256];   /* what a context's scan does at symbols below 256
                                  ** (context.c): stops, passes, or jumps a branch */
} lsys_skip;

/* The scratch of one thread rewriting modules: formal parameters and
** values, the stochastic alternatives, the generator the rules draw from. */
/* The brackets of a string for its contexts (context.c), in two parts that
** need no table of the whole string's brackets (cpfg keeps none either).
** The string's own: the far brackets, whose partner is more than
** LSYS_BRK_NEAR modules away or missing, as position << 32 | partner (NONE
** when missing) sorted by position, and of a string with parameters its
** first parameter at every LSYS_BRK_PSTEP-th module. A window of modules (a
** thread's chunk and a margin): a bit per module (set at the brackets), the
** brackets before each 64 modules, each bracket's partner in the window by
** the bracket's rank (NONE: outside it), and the modules' parameter offsets.
** A partner outside a window is a far one or a scan of at most LSYS_BRK_NEAR
** modules away; a window costs about 1.2 bits a module and 4 bytes a
** bracket of the window, the string's part a few bytes a far bracket. */
#define LSYS_BRK_NEAR 1024
#define LSYS_BRK_PSTEP 256
typedef struct lsys_brk {
  uint64_t *far; size_t nfar, farcap;
  uint32_t *pck; size_t pckcap;
  uint32_t *stk; size_t stkcap;   /* building: the open brackets */
  int withp;                      /* pck holds the parameters' offsets */
} lsys_brk;

typedef struct lsys_brkwin {
  const lsys_brk *g;
  size_t ca, cb;                  /* the modules it was made for (the sequential
                                  ** step makes the next when one leaves them) */
  size_t wa, wn;                  /* modules [wa, wa + wn), with the margins */
  uint64_t *bits; size_t bitscap;
  uint32_t *cnt; size_t cntcap;
  uint32_t *pos; size_t poscap;
  uint32_t *stk; size_t stkcap;   /* building: the open brackets, rank and position */
  uint32_t *poff; size_t poffcap; /* wn + 1 offsets, when withp */
  int withp;
} lsys_brkwin;

typedef struct lsys_scratch {
  double *args; size_t argscap;
  double *alt; size_t altcap;  /* stochastic alternatives: weight, rule, args, vals */
  lsys_rng *rng;
  int worker;                  /* a worker thread: no callbacks, nothing written to the model */
} lsys_scratch;

struct lsys_rules;
struct lsys_par;
/*
** Evaluates rule 'r' for the matched module: 'args' holds the formal
** parameters (left context, predecessor modules, right context, in order). Writes
** r->nvals values into 'vals' (RF_CALL) or the successor into m->dyn
** (RF_DYN). Returns 1 when the rule applies, 0 when its condition fails,
** or a negative LSYS_E* code with m->err set.
*/
typedef int (*lsys_rulefn) (void *ud, struct lsys_rules *m, const lsys_rule *r,
                            const double *args, double *vals);

typedef struct lsys_rules {
  lsys_alphabet *ab;
  lsys_rule *rules; size_t nrules, rulecap;
  lsys_patmod *pat; size_t npat, patcap;
  uint16_t *tcode; size_t ntcode, tcodecap;
  lsys_psrc *tsrc; size_t ntsrc, tsrccap;
  lsys_ruleset *sets; size_t nsets, setcap;
  lsys_skip *skips; size_t nskips, skipcap;
  /* settings */
  int ring, group;
  int f32;                     /* parameters are stored rounded to float32, as cpfg
                               ** stores them (lsys_round32) */
  size_t max_modules;
  size_t max_memory;           /* bytes for a step's strings and tables; 0: the
                               ** process default, lsys_common_memory_limit() */
  int maxdepth[3];             /* by kind; [LSYS_PROD] unused */
  lsys_rng rng, hrng;          /* derivation; homomorphism */
  /* cpfg's generator (random = "cpfg", rng.h): rng and hrng draw erand48's numbers;
  ** productions are chosen by drand48, one number for every module a step visits in
  ** a stochastic set, in single precision as cpfg's SelectProd; a step runs on the
  ** calling thread */
  int cpfg;
  int hshare;                  /* cpfg: no homomorphism seed, the homomorphism draws
                               ** from the derivation's generator */
  int choice_ready;            /* cpfg: choice_u is this module's number */
  uint64_t choice48;           /* cpfg: drand48's state */
  double choice_u;
  int cpfgtry;                 /* cpfg: 1 while a weighted rule that runs in Lua is
                               ** tried (its mark, lsys_derive_cpfg_mark, stops it after the
                               ** condition and weight), 2 while the chosen one runs
                               ** again from its state before the try (the mark then
                               ** puts back the state after every try, cpfgz) */
  int cpfgtried;               /* cpfg: the rule tried reached its mark */
  lsys_rng cpfgz;
  lsys_rng *cur;               /* the generator 'ran' uses now */
  lsys_rulefn fn; void *fnud;
  const lsys_func **funcs;     /* positional functions of LSYS_OP_FN (the table is
                               ** owned, the functions not: lsys_rules_setfuncs) */
  size_t nfuncs;
  int threads;                 /* for a step; 0: lsys_derive_default_threads() */
  size_t parmin;               /* strings shorter than this are rewritten on one thread */
  /* scratch, reused */
  lsys_scratch sc;             /* the calling thread's */
  struct lsys_par *par;        /* the worker threads' (derive_par.c) */
  lsys_lstring dyn, tmp;
  lsys_lstring altdyn;         /* the successors weighted function rules produced */
  lsys_lstring *levels; size_t nlevels;
  lsys_brk brk;                /* the context tables: the string's, */
  lsys_brkwin win;             /* the calling thread's window */
  uint32_t *substack; size_t nsub, subcap;
  uint32_t *act; size_t actcap;   /* per symbol: what the fast loop does */
  /* state for messages */
  long cur_rule;               /* index in rules[] being evaluated, or -1 */
  size_t cur_index;            /* module index being rewritten */
  int depth_hit;               /* a depth limit stopped an applicable rule */
  int busy;                    /* a step, an expansion or a streamed homomorphism runs:
                               ** the rules and the scratch must not change (a rule
                               ** callback re-entering the model is refused). A caller
                               ** whose callback longjmps out of the core resets it. */
  const lsys_lstring *hsrc;    /* streaming homomorphism: the string, its tables */
  int hctx;
  lsys_rng *hkeep;
  lsys_meter meter;            /* the budget of the running operation */
  lsys_error err;
} lsys_rules;

/* The mark a weighted rule running in Lua calls after its condition and weight
** (lsys.cpfg_try): 1 when it is being tried and is to stop there (cpfg
** evaluates a successor only once the production is chosen); else 0, after
** putting back the generator's state of the moment the choice was made. */
int lsys_derive_cpfg_mark (lsys_rules *m);

/* The start of a weighted rule in Lua that keeps what its try computed (the
** cpfg loader's statement blocks: their locals stay in the rule's table): 1
** when the chosen rule runs again and is to go on from its mark, skipping its
** pre-condition block and condition (they ran once, as in cpfg); else 0. */
int lsys_derive_cpfg_resume (lsys_rules *m);

/* x rounded to the nearest float32, as a double; beyond float32's range,
** +-FLT_MAX (so a finite value stays finite). */
static inline double lsys_round32 (double x) {
  return x > 3.4028234663852886e38 ? 3.4028234663852886e38
       : x < -3.4028234663852886e38 ? -3.4028234663852886e38 : (double)(float)x;
}

/* The threads a step uses when the model does not say (m->threads == 0):
** LSYS_THREADS from the environment when it is a whole number from 1 (more
** than LSYS_MAXTHREADS counts as that), else the processors this process may
** run on. Read once. */
int lsys_derive_default_threads (void);

int lsys_rules_init (lsys_rules *m, lsys_alphabet *ab);
void lsys_rules_free (lsys_rules *m);

/* Adds a rule to the set (kind, sub, group); returns its index in
** m->rules or a negative code (message in e). */
long lsys_rules_add (lsys_rules *m, int kind, int sub, int group,
                     const lsys_rulespec *spec, lsys_error *e);

/* Sets (code != NULL) or clears the expression program of rule 'idx'; it
** must write exactly the rule's nvals values. Returns LSYS_OK or LSYS_EARG. */
int lsys_rules_setvm (lsys_rules *m, size_t idx, const lsys_ins *code, int n);

/* Sets the table of positional functions the rules' expression programs
** call (LSYS_OP_FN indices); the pointers are copied, the functions are the
** caller's and must stay alive while the model uses them. Clears every
** rule's program first (their indices referred to the old table). Returns
** LSYS_OK, LSYS_ENOMEM or LSYS_EBUSY. */
int lsys_rules_setfuncs (lsys_rules *m, const lsys_func *const *funcs, size_t n);

/* Sets the ignore (consider = 0) or consider list of sub-L-system 'sub'. */
int lsys_rules_skiplist (lsys_rules *m, int sub, int consider,
                         const uint32_t *syms, size_t n);

/* Creates the set (kind, sub, group) if it does not exist (a sub-L-system
** with no rules of its own). */
int lsys_rules_newset (lsys_rules *m, int kind, int sub, int group);

/* Number of rules in the set (kind, sub, group); -1 when there is none. */
long lsys_rules_setsize (const lsys_rules *m, int kind, int sub, int group);

/*
** One parallel derivation step 'src' -> 'dst' (productions, cut, then
** decomposition). 'dst' is reset first; it may be 'src', which is then
** rewritten in place (its old contents are lost; on failure it is left
** empty). The productions of a long string run on m->threads threads when
** every rule they may apply runs on the expression machine or is a template
** (derive_par.c); the string is the same for every number of threads. The
** result may be narrow (lstring.h).
** Returns LSYS_OK; LSYS_ELIMIT when 'dst' would exceed m->max_modules;
** LSYS_EMEMORY when the source, the new string and the step's tables
** would need more than m->max_memory bytes (checked before allocating);
** LSYS_ERULE (or what the callback returned) with m->err set; LSYS_EBUSY
** when the model is busy already (a rule callback called it again). The
** functions that change the rules (lsys_rules_add, _setvm, _skiplist,
** _newset) also return LSYS_EBUSY while the model is busy.
*/
int lsys_derive_step (lsys_rules *m, lsys_lstring *src, lsys_lstring *dst);

/* Applies the rules of 'kind' (LSYS_HOMO or LSYS_DECOMP) to every module
** of 'src' recursively within m->maxdepth[kind], into 'dst'. */
int lsys_derive_expand (lsys_rules *m, int kind, lsys_lstring *src, lsys_lstring *dst);

/*
** The homomorphism one module at a time, for the turtle (no expanded copy).
** lsys_derive_homo_begin prepares 'src' (which must not change until
** lsys_derive_homo_end); it returns 1, 0 when there is no homomorphism, or an
** error code. lsys_derive_homo_module expands module 'i' (parameters at 'poff')
** into 'out' and returns 1 (1 + k when a predecessor of several modules took
** the k modules after i too: the caller skips them), or 0 when no homomorphism
** rule is for its symbol (the module stands for itself), or an error code with
** m->err set.
*/
int lsys_derive_homo_begin (lsys_rules *m, lsys_lstring *src);
int lsys_derive_homo_module (lsys_rules *m, size_t i, size_t poff, lsys_lstring *out);
void lsys_derive_homo_end (lsys_rules *m);

#endif
