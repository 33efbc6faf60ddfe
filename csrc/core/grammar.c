/*
** The rule language: splitting a rule into its parts (docs/manual.md §4).
*/
#include <string.h>

#include "grammar.h"
#include "lstring.h"

void lsys_grammar_prule_free (lsys_prule *r) {
  LSYS_FREE(r->mods);
  LSYS_FREE(r->params);
  memset(r, 0, sizeof *r);
}

static int isspacec (int c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

static int isidstart (int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static int isidchar (int c) { return isidstart(c) || (c >= '0' && c <= '9'); }

/* Trims white space around [*b, *e). */
static void trim (const char *t, size_t *b, size_t *e) {
  while (*b < *e && isspacec((unsigned char)t[*b])) (*b)++;
  while (*e > *b && isspacec((unsigned char)t[*e - 1])) (*e)--;
}

/*
** Finds the first occurrence of 'tok' in [b, e) outside parentheses and
** quoted strings; returns its offset or (size_t)-1.
*/
static size_t findtop (const char *t, size_t b, size_t e, const char *tok) {
  size_t tl = strlen(tok), i;
  int depth = 0;
  char quote = 0;
  for (i = b; i < e; i++) {
    char c = t[i];
    if (quote) {
      if (c == '\\') i++;
      else if (c == quote) quote = 0;
      continue;
    }
    if (depth > 0 && (c == '"' || c == '\'')) { quote = c; continue; }
    if (c == '(') depth++;
    else if (c == ')') { if (depth > 0) depth--; }
    else if (depth == 0 && i + tl <= e && memcmp(t + i, tok, tl) == 0) return i;
  }
  return (size_t)-1;
}

static int addmod (lsys_prule *r, uint32_t sym, uint32_t pos) {
  lsys_pmod *m;
  if (lsys_common_grow((void **)&r->mods, &r->modcap, r->nmods + 1, sizeof *r->mods) != LSYS_OK)
    return LSYS_ENOMEM;
  m = &r->mods[r->nmods++];
  m->sym = sym;
  m->np = 0;
  m->first = (uint32_t)r->nparams;
  m->pos = pos;
  return LSYS_OK;
}

static int addparam (lsys_prule *r, size_t b, size_t e) {
  if (lsys_common_grow((void **)&r->params, &r->parcap, r->nparams + 1,
                       sizeof *r->params) != LSYS_OK)
    return LSYS_ENOMEM;
  r->params[r->nparams].off = (uint32_t)b;
  r->params[r->nparams].len = (uint32_t)(e - b);
  r->nparams++;
  r->mods[r->nmods - 1].np++;
  return LSYS_OK;
}

/*
** Parses the modules in [b, e). 'formal' = 1: parameters are names;
** 0: parameters are expressions (split at top-level commas).
** Returns the number of modules through '*count'.
*/
static int parsemods (lsys_prule *r, const char *t, size_t b, size_t e, int formal,
                      lsys_alphabet *a, const lsys_names *decl, uint32_t *count,
                      lsys_error *err) {
  size_t i = b;
  *count = 0;
  while (i < e) {
    size_t nl, start;
    uint32_t sym;
    if (isspacec((unsigned char)t[i])) { i++; continue; }
    start = i;
    if (t[i] == ')')
      return lsys_seterror(err, LSYS_ESYNTAX, i, "unbalanced parentheses: ')' without '('");
    nl = lsys_alphabet_scan(t + i, e - i, decl);
    if (nl == 0)
      return lsys_seterror(err, LSYS_ESYNTAX, i, "unexpected '%c'", t[i]);
    sym = lsys_alphabet_intern(a, t + i, nl, err);
    if (sym == 0) { err->pos = i; return err->code; }
    if (addmod(r, sym, (uint32_t)i) != LSYS_OK)
      return lsys_seterror(err, LSYS_ENOMEM, i, "not enough memory");
    (*count)++;
    i += nl;
    while (i < e && isspacec((unsigned char)t[i])) i++;
    if (i < e && t[i] == '(') {
      size_t pb = ++i;
      int depth = 0;
      char quote = 0;
      int closed = 0;
      for (; i < e; i++) {
        char c = t[i];
        if (quote) {
          if (c == '\\') i++;
          else if (c == quote) quote = 0;
          continue;
        }
        if (c == '"' || c == '\'') quote = c;
        else if (c == '(' || c == '{' || c == '[') depth++;
        else if ((c == ')' || c == '}' || c == ']') && depth > 0) depth--;
        else if (depth == 0 && (c == ',' || c == ')')) {
          size_t xb = pb, xe = i;
          trim(t, &xb, &xe);
          if (xb == xe) {
            if (c == ')' && pb == start + nl + 1 && r->mods[r->nmods - 1].np == 0 &&
                i == xb) { closed = 1; break; }    /* A() */
            return lsys_seterror(err, LSYS_ESYNTAX, xb, "empty parameter in '%s'",
                                 lsys_alphabet_name(a, sym));
          }
          if (formal) {
            size_t k;
            if (!isidstart((unsigned char)t[xb]))
              return lsys_seterror(err, LSYS_ESYNTAX, xb,
                                   "parameter of '%s' in a pattern must be a name",
                                   lsys_alphabet_name(a, sym));
            for (k = xb; k < xe; k++)
              if (!isidchar((unsigned char)t[k]))
                return lsys_seterror(err, LSYS_ESYNTAX, xb,
                                     "parameter of '%s' in a pattern must be a name",
                                     lsys_alphabet_name(a, sym));
          }
          if (r->mods[r->nmods - 1].np == LSYS_MAXPARAMS)
            return lsys_seterror(err, LSYS_ESYNTAX, xb,
                                 "too many parameters for '%s' (limit is %d)",
                                 lsys_alphabet_name(a, sym), LSYS_MAXPARAMS);
          if (addparam(r, xb, xe) != LSYS_OK)
            return lsys_seterror(err, LSYS_ENOMEM, xb, "not enough memory");
          pb = i + 1;
          if (c == ')') { closed = 1; break; }
        }
      }
      if (!closed)
        return lsys_seterror(err, LSYS_ESYNTAX, start,
                             "unbalanced parentheses after '%s'", lsys_alphabet_name(a, sym));
      i++;
      if ((sym == LSYS_SYM_LBR || sym == LSYS_SYM_RBR) && r->mods[r->nmods - 1].np > 0)
        return lsys_seterror(err, LSYS_ESYNTAX, start, "'%s' takes no parameters",
                             lsys_alphabet_name(a, sym));
    }
  }
  return LSYS_OK;
}

/* Checks bracket balance of modules [from, from+n). */
static int checkbrackets (const lsys_prule *r, size_t from, size_t n, const char *what,
                          lsys_error *err) {
  size_t k;
  long depth = 0;
  for (k = from; k < from + n; k++) {
    if (r->mods[k].sym == LSYS_SYM_LBR) depth++;
    else if (r->mods[k].sym == LSYS_SYM_RBR && --depth < 0)
      return lsys_seterror(err, LSYS_ESYNTAX, r->mods[k].pos,
                           "unbalanced brackets in %s: ']' without '['", what);
  }
  if (depth > 0) {                     /* the last '[' that is never closed */
    long d = 0;
    for (k = from + n; k-- > from;) {
      if (r->mods[k].sym == LSYS_SYM_RBR) d++;
      else if (r->mods[k].sym == LSYS_SYM_LBR && d-- == 0) break;
    }
    return lsys_seterror(err, LSYS_ESYNTAX, r->mods[k].pos,
                         "unbalanced brackets in %s: '[' without ']'", what);
  }
  return LSYS_OK;
}

static int parsepattern (lsys_prule *r, const char *t, size_t b, size_t e,
                         lsys_alphabet *a, const lsys_names *decl, lsys_error *err) {
  size_t lt = findtop(t, b, e, "<"), gt = findtop(t, b, e, ">");
  size_t pb = b, pe = e;
  uint32_t n;
  int st;
  if (lt != (size_t)-1 && findtop(t, lt + 1, e, "<") != (size_t)-1)
    return lsys_seterror(err, LSYS_ESYNTAX, findtop(t, lt + 1, e, "<"),
                         "more than one '<' in the pattern");
  if (gt != (size_t)-1 && findtop(t, gt + 1, e, ">") != (size_t)-1)
    return lsys_seterror(err, LSYS_ESYNTAX, findtop(t, gt + 1, e, ">"),
                         "more than one '>' in the pattern");
  if (lt != (size_t)-1 && gt != (size_t)-1 && gt < lt)
    return lsys_seterror(err, LSYS_ESYNTAX, gt, "'>' before '<' in the pattern");
  if (lt != (size_t)-1) {
    size_t k;
    if ((st = parsemods(r, t, b, lt, 1, a, decl, &n, err)) != LSYS_OK) return st;
    if (n == 0) return lsys_seterror(err, LSYS_ESYNTAX, lt, "empty left context before '<'");
    for (k = 0; k < r->nmods; k++)
      if (r->mods[k].sym == LSYS_SYM_LBR || r->mods[k].sym == LSYS_SYM_RBR)
        return lsys_seterror(err, LSYS_ESYNTAX, r->mods[k].pos,
                             "brackets are not allowed in a left context");
    r->nlc = n;
    pb = lt + 1;
  }
  if (gt != (size_t)-1) pe = gt;
  if ((st = parsemods(r, t, pb, pe, 1, a, decl, &n, err)) != LSYS_OK) return st;
  if (n == 0) {
    size_t at = pb;
    while (at < pe && isspacec((unsigned char)t[at])) at++;
    return lsys_seterror(err, LSYS_ESYNTAX, at, "missing predecessor");
  }
  {       /* several modules: a strict predecessor as cpfg's (manual §4.2) */
    size_t k;
    for (k = r->nmods - n; k < r->nmods; k++)
      if (r->mods[k].sym == LSYS_SYM_LBR || r->mods[k].sym == LSYS_SYM_RBR)
        return lsys_seterror(err, LSYS_ESYNTAX, r->mods[k].pos,
                             "a bracket cannot be in a predecessor");
  }
  r->npred = n;
  if (gt != (size_t)-1) {
    if ((st = parsemods(r, t, gt + 1, e, 1, a, decl, &n, err)) != LSYS_OK) return st;
    if (n == 0) return lsys_seterror(err, LSYS_ESYNTAX, gt, "empty right context after '>'");
    r->nrc = n;
  }
  return LSYS_OK;
}

int lsys_grammar_rule_parse (lsys_prule *r, const char *t, size_t len, int pattern_only,
                             lsys_alphabet *a, const lsys_names *decl, lsys_error *err) {
  size_t arrow, colon, lb = 0, le, sb, se, k;
  int st;
  memset(r, 0, sizeof *r);
  if (pattern_only >= 2) {             /* a successor template (3: pieces, unchecked) */
    size_t b = 0, e = len;
    trim(t, &b, &e);
    if (e - b == 1 && t[b] == '*') { r->empty = 1; return LSYS_OK; }
    if ((st = parsemods(r, t, b, e, 0, a, decl, &r->nsucc, err)) != LSYS_OK) return st;
    return pattern_only == 3 ? LSYS_OK : checkbrackets(r, 0, r->nsucc, "successor", err);
  }
  {                                    /* parentheses first: they hide the rest */
    size_t i, open = 0;
    int depth = 0;
    char quote = 0;
    for (i = 0; i < len; i++) {
      char c = t[i];
      if (quote) { if (c == '\\') i++; else if (c == quote) quote = 0; continue; }
      if (depth > 0 && (c == '"' || c == '\'')) quote = c;
      else if (c == '(') { if (depth++ == 0) open = i; }
      else if (c == ')' && --depth < 0)
        return lsys_seterror(err, LSYS_ESYNTAX, i, "unbalanced parentheses: ')' without '('");
    }
    if (depth > 0)
      return lsys_seterror(err, LSYS_ESYNTAX, open, "unbalanced parentheses: '(' without ')'");
  }
  arrow = findtop(t, 0, len, "-->");
  if (pattern_only) {
    if (arrow != (size_t)-1)
      return lsys_seterror(err, LSYS_ESYNTAX, arrow,
                           "a rule with a function has no '-->' successor");
    le = len;
  }
  else {
    if (arrow == (size_t)-1) {
      size_t op = findtop(t, 0, len, "->");
      if (op == (size_t)-1) op = findtop(t, 0, len, "=>");
      if (op != (size_t)-1)
        return lsys_seterror(err, LSYS_ESYNTAX, op, "unknown operator '%.2s' (rules use '-->')",
                             t + op);
      return lsys_seterror(err, LSYS_ESYNTAX, 0, "missing '-->'");
    }
    if (findtop(t, arrow + 3, len, "-->") != (size_t)-1)
      return lsys_seterror(err, LSYS_ESYNTAX, findtop(t, arrow + 3, len, "-->"),
                           "more than one '-->'");
    le = arrow;
  }
  /* left side: pattern [: condition] */
  colon = findtop(t, lb, le, ":");
  if (colon != (size_t)-1) {
    size_t cb = colon + 1, ce = le;
    trim(t, &cb, &ce);
    if (cb == ce) return lsys_seterror(err, LSYS_ESYNTAX, colon, "empty condition after ':'");
    r->cond.off = (uint32_t)cb;
    r->cond.len = (uint32_t)(ce - cb);
    le = colon;
  }
  if ((st = parsepattern(r, t, lb, le, a, decl, err)) != LSYS_OK) return st;
  if (pattern_only) return LSYS_OK;
  /* right side: successor [: weight] */
  sb = arrow + 3;
  se = len;
  colon = findtop(t, sb, se, ":");
  if (colon != (size_t)-1) {
    size_t wb = colon + 1, we = se;
    if (findtop(t, colon + 1, se, ":") != (size_t)-1)
      return lsys_seterror(err, LSYS_ESYNTAX, findtop(t, colon + 1, se, ":"),
                           "more than one ':' after '-->'");
    trim(t, &wb, &we);
    if (wb == we) return lsys_seterror(err, LSYS_ESYNTAX, colon, "missing weight after ':'");
    r->weight.off = (uint32_t)wb;
    r->weight.len = (uint32_t)(we - wb);
    se = colon;
  }
  trim(t, &sb, &se);
  if (sb == se)
    return lsys_seterror(err, LSYS_ESYNTAX, arrow, "empty successor (write '*' for none)");
  if (se - sb == 1 && t[sb] == '*') { r->empty = 1; return LSYS_OK; }
  k = r->nmods;
  if ((st = parsemods(r, t, sb, se, 0, a, decl, &r->nsucc, err)) != LSYS_OK) return st;
  return checkbrackets(r, k, r->nsucc, "successor", err);
}
