/*
** The turtle's symbols: the rows of LSYS_SYMBOLS (symbols.h) as data.
*/
#include <string.h>

#include "symbols.h"

#define ROW(op, name, split, keep, query) {name, #op, LSYS_SPLIT_##split, keep, query},
const lsys_symbol lsys_symbols[LSYS_NSYMBOLS] = { LSYS_SYMBOLS(ROW) };
#undef ROW

size_t lsys_symbols_match (const char *s, size_t len, char c) {
  size_t best = 0, k;
  if (len == 0 || s[0] != c) return 0;
  for (k = 0; k < LSYS_NSYMBOLS; k++) {
    const char *name = lsys_symbols[k].name;
    size_t n;
    if (name == NULL || name[0] != c) continue;
    n = strlen(name);
    if (n > best && n <= len && memcmp(name, s, n) == 0) best = n;
  }
  return best;
}
