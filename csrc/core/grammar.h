/*
** The rule language (docs/manual.md §4): splits a rule
**     lc < pred > rc : cond --> successor : weight
** into modules, formal parameter names, and the text of the condition, the
** successor's parameter expressions and the weight. Expressions stay text:
** the Lua side compiles them (lua/lsys/grammar.lua).
*/
#ifndef LSYS_GRAMMAR_H
#define LSYS_GRAMMAR_H

#include "alphabet.h"

typedef struct lsys_span { uint32_t off, len; } lsys_span;

typedef struct lsys_pmod {
  uint32_t sym;       /* interned symbol id */
  uint32_t np;        /* number of parameters */
  uint32_t first;     /* index of its first parameter in lsys_prule.params */
  uint32_t pos;       /* byte offset of the name in the rule text */
} lsys_pmod;

typedef struct lsys_prule {
  lsys_pmod *mods;     /* left context, predecessor (npred modules), right context,
                       ** successor */
  size_t nmods, modcap;
  lsys_span *params;   /* formal names (patterns) or expressions (successor) */
  size_t nparams, parcap;
  uint32_t nlc, npred, nrc, nsucc;   /* npred >= 1 modules: cpfg's strict predecessor */
  lsys_span cond, weight;   /* len 0 when absent */
  int empty;                /* the successor is '*' */
} lsys_prule;

void lsys_grammar_prule_free (lsys_prule *r);

/*
** Parses one rule. With 'pattern_only' the text is only 'lc < pred > rc'
** (a rule whose successor a Lua function produces) or a successor template
** when 'pattern_only' is 2 (nmods = nsucc, parameters are expressions;
** 3: the same without the bracket-balance check, for pieces of a successor).
** Returns LSYS_OK or LSYS_ESYNTAX with e->pos the byte offset at fault.
*/
int lsys_grammar_rule_parse (lsys_prule *r, const char *text, size_t len, int pattern_only,
                             lsys_alphabet *a, const lsys_names *decl, lsys_error *e);

#endif
