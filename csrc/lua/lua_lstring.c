/*
** lsys.Lstring: the module string as a Lua userdata.
*/
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "outfile.h"

/* __gc and __close: idempotent; a string in use by a running operation is not
** freed (it cannot be collected then, but __close can be called on it). */
static int lstring_gc (lua_State *L) {
  lsys_lstr *u = (lsys_lstr *)luaL_checkudata(L, 1, LSTRING_T);
  if (u->busy) return luaL_error(L, "cannot close an Lstring while a derivation or "
                                    "interpretation uses it");
  lsys_lstring_free(&u->s);
  u->closed = 1;
  return 0;
}

static int lstring_len (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsysL_checklstring_any(L, 1)->n);
  return 1;
}

/* Pushes the text of modules [i, j) of 's', parameters with 'digits' significant digits
** (0: exact). */
static void pushtext (lua_State *L, int idx, size_t i, size_t j, int digits) {
  lsys_lstring *s = lsysL_checklstring_any(L, idx);  /* formatted as it is: never widened */
  lsys_buf b = {0};
  if (lsys_lstring_format_digits(&b, s, lsysL_getalphabet(L), lsysL_ownernames(L, idx), i, j,
                                 digits) != LSYS_OK) {
    lsys_lstring_buf_free(&b);
    luaL_error(L, "not enough memory");
  }
  lua_pushlstring(L, b.p ? b.p : "", b.n);
  lsys_lstring_buf_free(&b);   /* lua_pushlstring may raise: a leak of b only on memory errors */
}

static int lstring_tostring (lua_State *L) {
  lsys_lstring *s;
  if (((lsys_lstr *)luaL_checkudata(L, 1, LSTRING_T))->closed) {
    lua_pushliteral(L, "lsys.Lstring (closed)");
    return 1;
  }
  s = lsysL_checklstring_any(L, 1);
  pushtext(L, 1, 0, s->n, 0);
  return 1;
}

/* The sinks of s:write: a C stream (its errno kept), an output file. */
typedef struct filesink { FILE *f; int err; } filesink;

static int tofile (void *ud, const char *p, size_t n) {
  filesink *fs = (filesink *)ud;
  if (fwrite(p, 1, n, fs->f) == n) return LSYS_OK;
  fs->err = errno ? errno : EIO;
  return LSYS_EARG;
}

static int tooutfile (void *ud, const char *p, size_t n) {
  lsys_outfile *o = (lsys_outfile *)ud;
  lsys_outfile_write(o, p, n);
  return o->err != 0 ? LSYS_EARG : LSYS_OK;
}

/* s:write(target [, tail]) -> s: writes the text of s (tostring's bytes) and then the
** string 'tail' to 'target', an open Lua file (io.stdout) or a path, which is written
** atomically (outfile.c); the text is streamed in pieces of 64 KiB, never built whole.
** Raises when the file cannot be written (the target is then left as it was). */
static int lstring_write (lua_State *L) {
  lsys_lstring *s = lsysL_checklstring_any(L, 1);    /* a narrow string stays narrow */
  luaL_Stream *fh = (luaL_Stream *)luaL_testudata(L, 2, LUA_FILEHANDLE);
  size_t tlen;
  const char *tail = luaL_optlstring(L, 3, "", &tlen), *path = NULL;
  const lsys_alphabet *a = lsysL_getalphabet(L);
  const lsys_names *decl = lsysL_ownernames(L, 1);
  lsys_error e;
  int st;
  if (fh != NULL) luaL_argcheck(L, fh->closef != NULL, 2, "attempt to use a closed file");
  else {
    luaL_argexpected(L, lua_type(L, 2) == LUA_TSTRING || lua_type(L, 2) == LUA_TNUMBER, 2,
                     "file or path");
    path = lua_tostring(L, 2);                 /* a number becomes its text, like io.open's */
  }
  s = lsysL_checklstring_any(L, 1);            /* again: a finalizer may have closed it */
  if (fh != NULL) {
    filesink fs = { fh->f, 0 };
    errno = 0;
    st = lsys_lstring_write(s, a, decl, 0, s->n, 0, tofile, &fs);
    if (st == LSYS_OK && tlen > 0) st = tofile(&fs, tail, tlen);
    if (st == LSYS_OK && fflush(fh->f) != 0) { fs.err = errno ? errno : EIO; st = LSYS_EARG; }
    if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
    if (st != LSYS_OK) return luaL_error(L, "cannot write the string: %s", strerror(fs.err));
  } else {
    lsys_outfile o;
    st = lsys_outfile_open(&o, path, &e);
    if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
    st = lsys_lstring_write(s, a, decl, 0, s->n, 0, tooutfile, &o);
    if (st == LSYS_OK && tlen > 0) st = tooutfile(&o, tail, tlen);
    if (st == LSYS_ENOMEM) {
      lsys_outfile_abort(&o);
      return luaL_error(L, "not enough memory");
    }
    st = lsys_outfile_commit(&o, &e);          /* reports a failed write, frees o */
    if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  }
  lua_settop(L, 1);
  return 1;
}

/* Converts a Lua index (1-based, negative from the end) like string.sub. */
static size_t posrelat (lua_Integer pos, size_t len) {
  if (pos > 0) return (size_t)pos;
  else if (pos == 0) return 1;
  else if (pos < -(lua_Integer)len) return 1;
  else return len + (size_t)pos + 1;
}

static int lstring_sub (lua_State *L) {
  lsys_lstring *s = checklstring(L, 1), *d;
  size_t i = posrelat(luaL_checkinteger(L, 2), s->n);
  lua_Integer je = luaL_optinteger(L, 3, -1);
  size_t j = je >= 0 ? (size_t)je : (je < -(lua_Integer)s->n ? 0 : s->n + (size_t)je + 1);
  if (j > s->n) j = s->n;
  d = lsysL_newlstring(L);
  lsysL_setowner(L, -1, 1);
  s = checklstring(L, 1);                   /* again: a finalizer may have closed it */
  if (i <= j && j > s->n) j = s->n;         /* or rewritten it */
  if (i <= j && lsys_lstring_append(d, s, i - 1, j, lsys_lstring_poff(s, i - 1)) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  return 1;
}

/* s:text([i [, j [, digits]]]): the text of a range, parameters rounded to 'digits'
** significant digits (1 to 17; default: exact) */
static int lstring_text (lua_State *L) {
  lsys_lstring *s = lsysL_checklstring_any(L, 1);
  size_t i = posrelat(luaL_optinteger(L, 2, 1), s->n);
  lua_Integer je = luaL_optinteger(L, 3, -1);
  lua_Integer digits = luaL_optinteger(L, 4, 0);
  size_t j = je >= 0 ? (size_t)je : (je < -(lua_Integer)s->n ? 0 : s->n + (size_t)je + 1);
  luaL_argcheck(L, lua_isnoneornil(L, 4) || (1 <= digits && digits <= 17), 4,
                "digits must be from 1 to 17");
  if (j > s->n) j = s->n;
  if (i > j) lua_pushliteral(L, "");
  else pushtext(L, 1, i - 1, j, (int)digits);
  return 1;
}

/* Pushes name and parameters of module i (0-based) whose params are at 'off':
** the parameters are read before the name is pushed (an allocation, whose
** finalizers may close the string). */
static int pushmodule (lua_State *L, lsys_lstring *s, size_t i, size_t off) {
  uint32_t c = s->code[i], np = LSYS_CNP(c), k;
  luaL_checkstack(L, (int)np + 2, "too many parameters");
  lua_pushnil(L);                           /* the name's place */
  for (k = 0; k < np; k++) lua_pushnumber(L, s->par[off + k]);
  lua_pushstring(L, lsys_alphabet_name(lsysL_getalphabet(L), LSYS_CSYM(c)));
  lua_replace(L, -(int)np - 2);
  return (int)np + 1;
}

static int lstring_module (lua_State *L) {
  lsys_lstring *s = checklstring(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  if (i < 0) i += (lua_Integer)s->n + 1;
  luaL_argcheck(L, i >= 1 && (size_t)i <= s->n, 2, "module index out of range");
  return pushmodule(L, s, (size_t)i - 1, lsys_lstring_poff(s, (size_t)i - 1));
}

/* s:set(i, p1, p2, ...): replaces the parameters of module i in place (as many
** as it has; finite numbers). The arrangement (lsys.arrange) updates its @J
** modules this way between interpretations. */
static int lstring_set (lua_State *L) {
  lsys_lstring *s = checklstring(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  size_t np, off, k;
  if (i < 0) i += (lua_Integer)s->n + 1;
  luaL_argcheck(L, i >= 1 && (size_t)i <= s->n, 2, "module index out of range");
  np = LSYS_CNP(s->code[i - 1]);
  if ((size_t)lua_gettop(L) - 2 != np)
    return luaL_error(L, "set: module %d has %d parameters, got %d", (int)i, (int)np,
                      lua_gettop(L) - 2);
  off = lsys_lstring_poff(s, (size_t)i - 1);
  for (k = 0; k < np; k++) {
    double x = luaL_checknumber(L, (int)k + 3);
    luaL_argcheck(L, isfinite(x), (int)k + 3, "not a finite number");
    s->par[off + k] = x;
  }
  return 0;
}

static int modules_iter (lua_State *L) {
  lsys_lstring *s = checklstring(L, lua_upvalueindex(1));
  size_t i = (size_t)lua_tointeger(L, lua_upvalueindex(2));
  size_t off = (size_t)lua_tointeger(L, lua_upvalueindex(3));
  int n;
  if (i >= s->n) return 0;
  if (off > s->npar) off = lsys_lstring_poff(s, i);   /* the string changed */
  lua_pushinteger(L, (lua_Integer)i + 1);
  lua_replace(L, lua_upvalueindex(2));
  lua_pushinteger(L, (lua_Integer)(off + LSYS_CNP(s->code[i])));
  lua_replace(L, lua_upvalueindex(3));
  lua_pushinteger(L, (lua_Integer)i + 1);
  n = pushmodule(L, s, i, off);
  return n + 1;
}

static int lstring_modules (lua_State *L) {
  checklstring(L, 1);
  lua_settop(L, 1);
  lua_pushinteger(L, 0);
  lua_pushinteger(L, 0);
  lua_pushcclosure(L, modules_iter, 3);
  return 1;
}

static int lstring_count (lua_State *L) {
  lsys_lstring *s = checklstring(L, 1);
  size_t len, i, n = 0;
  const char *name = luaL_checklstring(L, 2, &len);   /* a number is converted: allocates */
  uint32_t sym = lsys_alphabet_find(lsysL_getalphabet(L), name, len);
  s = checklstring(L, 1);
  if (sym != 0)
    for (i = 0; i < s->n; i++) n += LSYS_CSYM(s->code[i]) == sym;
  lua_pushinteger(L, (lua_Integer)n);
  return 1;
}

/* s:counts() -> { name = count, ... } for every module name in s */
static int lstring_counts (lua_State *L) {
  lsys_lstring *s = lsysL_checklstring_any(L, 1);    /* counted as it is: never widened */
  lsys_alphabet *a = lsysL_getalphabet(L);
  size_t *n = (size_t *)lua_newuserdatauv(L, (a->n + 1) * sizeof *n, 0);
  size_t i;
  uint32_t k;
  s = lsysL_checklstring_any(L, 1);         /* again: a finalizer may have closed it */
  memset(n, 0, (a->n + 1) * sizeof *n);
  if (s->sym8 != NULL)
    for (i = 0; i < s->n; i++) { if (s->sym8[i] < a->n) n[s->sym8[i]]++; }
  else
    for (i = 0; i < s->n; i++) {
      uint32_t sym = LSYS_CSYM(s->code[i]);
      if (sym < a->n) n[sym]++;
    }
  lua_newtable(L);
  for (k = 1; k < a->n; k++)
    if (n[k] > 0) {
      lua_pushinteger(L, (lua_Integer)n[k]);
      lua_setfield(L, -2, lsys_alphabet_name(a, k));
    }
  return 1;
}

/* a == b: false when either is not an Lstring (Lua calls __eq for any two
** userdata); raises when one was closed. */
static int lstring_eq (lua_State *L) {
  lsys_lstring *a, *b;
  if (luaL_testudata(L, 1, LSTRING_T) == NULL || luaL_testudata(L, 2, LSTRING_T) == NULL) {
    lua_pushboolean(L, 0);
    return 1;
  }
  a = checklstring(L, 1);
  b = checklstring(L, 2);
  lua_pushboolean(L, a->n == b->n && a->npar == b->npar &&
                     (a->n == 0 || memcmp(a->code, b->code, a->n * sizeof *a->code) == 0) &&
                     (a->npar == 0 || memcmp(a->par, b->par, a->npar * sizeof *a->par) == 0));
  return 1;
}

static int lstring_concat (lua_State *L) {
  lsys_lstring *a, *b, *d;
  checklstring(L, 1);
  checklstring(L, 2);
  d = lsysL_newlstring(L);
  lsysL_setowner(L, -1, 1);
  a = checklstring(L, 1);                   /* after the allocation (finalizers) */
  b = checklstring(L, 2);
  if (lsys_lstring_copy(d, a) != LSYS_OK || lsys_lstring_append(d, b, 0, b->n, 0) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  return 1;
}

/* s:insert(positions, piece): a new Lstring with 'piece' (an Lstring)
** inserted before each of the module indices in the ascending list
** 'positions' (n + 1: at the end), in one pass. */
static int lstring_insert (lua_State *L) {
  lsys_lstring *a, *b, *d;
  lua_Integer k, np, prev = 1;
  size_t off = 0;
  checklstring(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  checklstring(L, 3);
  np = luaL_len(L, 2);                      /* may run Lua code */
  d = lsysL_newlstring(L);                   /* may run finalizers */
  lsysL_setowner(L, -1, 1);
  a = checklstring(L, 1);                   /* nothing below runs Lua code */
  b = checklstring(L, 3);
  for (k = 1; k <= np + 1; k++) {
    lua_Integer at = (lua_Integer)a->n + 1;
    size_t o2;
    if (k <= np) {
      int isnum;
      lua_rawgeti(L, 2, k);
      at = lua_tointegerx(L, -1, &isnum);
      lua_pop(L, 1);
      if (!isnum || at < prev || at > (lua_Integer)a->n + 1)
        return luaL_error(L, "insert: positions must be ascending module indices from 1 "
                             "to %d (entry %d)", (int)a->n + 1, (int)k);
    }
    o2 = lsys_lstring_poff(a, (size_t)at - 1 < a->n ? (size_t)at - 1 : a->n);
    if (at == (lua_Integer)a->n + 1) o2 = a->npar;
    if (lsys_lstring_append(d, a, (size_t)prev - 1, (size_t)at - 1, off) != LSYS_OK ||
        (k <= np && lsys_lstring_append(d, b, 0, b->n, 0) != LSYS_OK))
      return luaL_error(L, "not enough memory");
    off = o2;
    prev = at;
  }
  return 1;
}

static int lstring_copy (lua_State *L) {
  lsys_lstring *a, *d;
  checklstring(L, 1);
  d = lsysL_newlstring(L);
  lsysL_setowner(L, -1, 1);
  a = checklstring(L, 1);                   /* after the allocation (finalizers) */
  if (lsys_lstring_copy(d, a) != LSYS_OK) return luaL_error(L, "not enough memory");
  return 1;
}

/* s:bytes(): memory held by the string (codes, parameters), in bytes */
static int lstring_bytes (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsys_lstring_bytes(lsysL_checklstring_any(L, 1)));
  return 1;
}

/* lsys.lstring(text [, names]): parses cpfg text notation */
static int l_lstring (lua_State *L) {
  size_t len;
  const char *text = luaL_checklstring(L, 1, &len);
  const char *names = luaL_optstring(L, 2, "");
  lsys_names decl = {0};
  lsys_error e;
  lsys_lstring *s = lsysL_newlstring(L);
  int st = lsysL_readnames(L, names, &decl);
  if (st == LSYS_OK)
    st = lsys_lstring_parse(s, text, len, lsysL_getalphabet(L), &decl, &e);
  lsys_alphabet_names_free(&decl);
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (st != LSYS_OK)
    return luaL_error(L, "lstring: %s at character %d", e.msg, (int)e.pos + 1);
  return 1;
}

/* core.lstring_rules(s) -> the Rules that made the Lstring 's' (its owner, the user
** value lsysL_setowner keeps), or nil for an Lstring made without rules: lsys.model finds
** the model of a string by it. Raises for anything but an Lstring; answers for a closed
** one too, as it reads only the user value, which a close leaves (the model of a closed
** string is named in the message its use raises). */
static int l_lstring_rules (lua_State *L) {
  luaL_checkudata(L, 1, LSTRING_T);
  if (lua_getiuservalue(L, 1, 1) != LUA_TUSERDATA || luaL_testudata(L, -1, RULES_T) == NULL)
    lua_pushnil(L);
  return 1;
}

static const luaL_Reg lstring_methods[] = {
  {"sub", lstring_sub}, {"text", lstring_text}, {"module", lstring_module}, {"set", lstring_set},
  {"insert", lstring_insert},
  {"modules", lstring_modules}, {"count", lstring_count}, {"counts", lstring_counts}, {"copy", lstring_copy},
  {"bytes", lstring_bytes}, {"write", lstring_write}, {NULL, NULL}
};

static const luaL_Reg lstring_meta[] = {
  {"__index", NULL},   /* placeholder: the method table */
  {"__gc", lstring_gc}, {"__close", lstring_gc}, {"__len", lstring_len},
  {"__tostring", lstring_tostring}, {"__eq", lstring_eq}, {"__concat", lstring_concat},
  {NULL, NULL}
};

void lsysL_open_lstring (lua_State *L) {
  lsysL_createmeta(L, LSTRING_T, lstring_meta, lstring_methods);
  lua_pushcfunction(L, l_lstring);
  lua_setfield(L, -2, "lstring");
  lua_pushcfunction(L, l_lstring_rules);
  lua_setfield(L, -2, "lstring_rules");
}
