/*
** Module names <-> symbol ids; the module-name scanner.
*/
#include <string.h>

#include "alphabet.h"
#include "symbols.h"

static uint32_t hashname (const char *s, size_t len) {
  uint32_t h = 2166136261u;               /* FNV-1a */
  size_t i;
  for (i = 0; i < len; i++) h = (h ^ (unsigned char)s[i]) * 16777619u;
  return h;
}

static int rehash (lsys_alphabet *a, uint32_t nslots) {
  uint32_t *slots = (uint32_t *)LSYS_MALLOC(nslots * sizeof *slots);
  uint32_t id;
  if (slots == NULL) return LSYS_ENOMEM;
  memset(slots, 0, nslots * sizeof *slots);
  for (id = 1; id < a->n; id++) {
    uint32_t h = hashname(a->names[id], strlen(a->names[id])) & (nslots - 1);
    while (slots[h] != 0) h = (h + 1) & (nslots - 1);
    slots[h] = id;
  }
  LSYS_FREE(a->slots);
  a->slots = slots;
  a->nslots = nslots;
  return LSYS_OK;
}

int lsys_alphabet_init (lsys_alphabet *a) {
  static const char *const fixed[] = {"[", "]", "%", "?", "$"};
  size_t i;
  memset(a, 0, sizeof *a);
  a->names = (char **)LSYS_MALLOC(64 * sizeof *a->names);
  if (a->names == NULL) return LSYS_ENOMEM;
  a->cap = 64;
  a->names[0] = NULL;
  a->n = 1;
  if (rehash(a, 128) != LSYS_OK) return LSYS_ENOMEM;
  for (i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
    if (lsys_alphabet_intern(a, fixed[i], 1, NULL) == 0) return LSYS_ENOMEM;
  return LSYS_OK;
}

void lsys_alphabet_free (lsys_alphabet *a) {
  uint32_t i;
  if (a->names != NULL)
    for (i = 1; i < a->n; i++) LSYS_FREE(a->names[i]);
  LSYS_FREE(a->names);
  LSYS_FREE(a->slots);
  memset(a, 0, sizeof *a);
}

void lsys_alphabet_truncate (lsys_alphabet *a, uint32_t n) {
  uint32_t id;
  if (n < LSYS_SYM_FIRSTFREE || n >= a->n) return;
  for (id = n; id < a->n; id++) LSYS_FREE(a->names[id]);
  a->n = n;
  memset(a->slots, 0, a->nslots * sizeof *a->slots);     /* the same table, refilled */
  for (id = 1; id < a->n; id++) {
    uint32_t h = hashname(a->names[id], strlen(a->names[id])) & (a->nslots - 1);
    while (a->slots[h] != 0) h = (h + 1) & (a->nslots - 1);
    a->slots[h] = id;
  }
}

uint32_t lsys_alphabet_find (const lsys_alphabet *a, const char *name, size_t len) {
  uint32_t h;
  if (a->nslots == 0) return 0;
  h = hashname(name, len) & (a->nslots - 1);
  while (a->slots[h] != 0) {
    const char *s = a->names[a->slots[h]];
    if (strncmp(s, name, len) == 0 && s[len] == '\0') return a->slots[h];
    h = (h + 1) & (a->nslots - 1);
  }
  return 0;
}

uint32_t lsys_alphabet_intern (lsys_alphabet *a, const char *name, size_t len,
                               lsys_error *e) {
  uint32_t id = lsys_alphabet_find(a, name, len);
  char *copy;
  if (id != 0) return id;
  if (a->n > LSYS_MAXSYM) {
    lsys_seterror(e, LSYS_ELIMIT, (size_t)-1,
                  "too many module names (limit is %u)", LSYS_MAXSYM);
    return 0;
  }
  if (a->n == a->cap) {
    size_t cap = a->cap;
    if (lsys_common_grow((void **)&a->names, &cap, a->n + 1, sizeof *a->names) != LSYS_OK)
      goto nomem;
    a->cap = (uint32_t)cap;
  }
  if ((a->n + 1) * 2 > a->nslots && rehash(a, a->nslots * 2) != LSYS_OK) goto nomem;
  copy = (char *)LSYS_MALLOC(len + 1);
  if (copy == NULL) goto nomem;
  memcpy(copy, name, len);
  copy[len] = '\0';
  id = a->n++;
  a->names[id] = copy;
  {
    uint32_t h = hashname(name, len) & (a->nslots - 1);
    while (a->slots[h] != 0) h = (h + 1) & (a->nslots - 1);
    a->slots[h] = id;
  }
  return id;
nomem:
  lsys_seterror(e, LSYS_ENOMEM, (size_t)-1, "not enough memory");
  return 0;
}

static int isletter (int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}

static size_t utf8len (const unsigned char *s, size_t len) {
  size_t n, i;
  if (s[0] < 0x80) return 1;
  if (s[0] >= 0xF0 && s[0] <= 0xF4) n = 4;
  else if (s[0] >= 0xE0) n = 3;
  else if (s[0] >= 0xC2 && s[0] < 0xE0) n = 2;
  else return 0;
  if (n > len) return 0;
  for (i = 1; i < n; i++)
    if ((s[i] & 0xC0) != 0x80) return 0;
  return n;
}

size_t lsys_alphabet_scan (const char *s, size_t len, const lsys_names *decl) {
  unsigned char c;
  size_t best = 0, i;
  if (len == 0) return 0;
  c = (unsigned char)s[0];
  if (c <= ' ' || c == 0x7F || c == '(' || c == ')' || c == '<' || c == '>' || c == ':')
    return 0;
  if (decl != NULL)
    for (i = 0; i < decl->n; i++) {
      size_t n = strlen(decl->v[i]);
      if (n > best && n <= len && memcmp(decl->v[i], s, n) == 0) best = n;
    }
  if (best > 0) return best;
  switch (c) {
    case '@':        /* the turtle's '@' names (symbols.h), the longest that fits; else '@'
                        and one letter (cpfg's @H, lsys's @X, ...) */
      if ((best = lsys_symbols_match(s, len, '@')) > 0) return best;
      return (len > 1 && isletter((unsigned char)s[1])) ? 2 : 1;
    case '?':
      return (len > 1 && isletter((unsigned char)s[1])) ? 2 : 1;
    case '~': {
      size_t n;
      if (len < 2 || (unsigned char)s[1] <= ' ' || s[1] == '(' || s[1] == ')')
        return 1;
      n = utf8len((const unsigned char *)s + 1, len - 1);
      return n ? 1 + n : 0;
    }
    default:
      return utf8len((const unsigned char *)s, len);
  }
}

int lsys_alphabet_names_add (lsys_names *d, const char *name, size_t len) {
  char *copy;
  if (lsys_common_grow((void **)&d->v, &d->cap, d->n + 1, sizeof *d->v) != LSYS_OK)
    return LSYS_ENOMEM;
  copy = (char *)LSYS_MALLOC(len + 1);
  if (copy == NULL) return LSYS_ENOMEM;
  memcpy(copy, name, len);
  copy[len] = '\0';
  d->v[d->n++] = copy;
  return LSYS_OK;
}

void lsys_alphabet_names_free (lsys_names *d) {
  size_t i;
  for (i = 0; i < d->n; i++) LSYS_FREE(d->v[i]);
  LSYS_FREE(d->v);
  memset(d, 0, sizeof *d);
}
