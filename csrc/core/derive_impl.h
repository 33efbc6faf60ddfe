/*
** What the derivation engine's files share (not part of the API; see
** derive.h): derive.c rewrites, context.c matches contexts.
*/
#ifndef LSYS_DERIVE_IMPL_H
#define LSYS_DERIVE_IMPL_H

#include "derive.h"

#define NONE UINT32_MAX

/* A view of the string being matched: codes, parameters, and for contexts
** the bracket matches and per-module parameter offsets. */
typedef struct view {
  const uint16_t *code;
  const double *par;
  size_t n;
  const uint32_t *match;   /* NULL when no context tables were built */
  const uint32_t *poff;
  const lsys_skip *skip;
  int ring;
  uint32_t eq;             /* the symbol of '=' (right contexts), or NONE */
} view;

/* Builds the bracket-match and parameter-offset tables of 's' in m->match
** and m->poff (within the model's memory budget). LSYS_OK, LSYS_ELIMIT,
** LSYS_ENOMEM or LSYS_EMEMORY. */
int lsys_buildtables (lsys_model *m, const lsys_lstring *s);

/* The symbol of '=' in the model's alphabet, or NONE. */
uint32_t lsys_eqsym (const lsys_model *m);

/* Whether rule r's left context matches before module i, and its right
** context from module j; they write the contexts' parameters into 'args'
** (left) and 'a' (right). */
int lsys_matchleft (const lsys_model *m, const view *v, size_t i, const lsys_rule *r,
                    double *args);
int lsys_matchright (const lsys_model *m, const view *v, size_t j, const lsys_rule *r,
                     double *a);

#endif
