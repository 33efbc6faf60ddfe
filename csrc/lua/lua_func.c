/*
** Lua binding of csrc/core/func.h: the lsys.Func userdata, a positional
** function y = f(x) (Anastacio et al. 2009, §4; cpfg's .func files).
**
**   core.func(points [, opts]) -> Func
**       points = { {x, y}, ... } (at least 4, x nondecreasing from 0 to 1);
**       opts.name (default "f"), opts.samples (default 0: exact),
**       opts.approx ("exact", the default, or "cpfg": lsys_func_cpfg)
**   core.func_parse(text, filename [, samples]) -> { Func, ... }
**       a .func (one function) or .fset text; samples applies to the old
**       "range:" form, as a cpfg view file's "function:" line gives it
**   f(x), f:eval(x) -> number      f:points() -> { {x, y}, ... }
**   f:name() -> string    f:samples() -> integer    f:format() -> fver 1 1 text
**   f:approx() -> "exact" | "cpfg"
**
** A Func is immutable once made; rules call it from C (lsysL_checkfunc).
*/
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"

static lsys_func *newfunc (lua_State *L) {
  lsys_lfunc *u = (lsys_lfunc *)lua_newuserdatauv(L, sizeof *u, 0);
  lsys_func_init(&u->f);
  u->life.closed = u->life.kept = 0;
  luaL_setmetatable(L, FUNC_T);
  return &u->f;
}

/* __gc and __close: idempotent; a kept function (a model's) is freed by the
** collector. */
static int func_gc (lua_State *L) {
  lsys_lfunc *u = (lsys_lfunc *)luaL_checkudata(L, 1, FUNC_T);
  if (lsysL_life_end(L, &u->life)) lsys_func_free(&u->f);
  return 0;
}

/* opts.samples: a whole number from 0 to LSYS_FUNC_MAXSAMPLES */
static int optsamples (lua_State *L, int t) {
  lua_Integer s;
  int isnum;
  if (lua_getfield(L, t, "samples") == LUA_TNIL) { lua_pop(L, 1); return 0; }
  s = lua_tointegerx(L, -1, &isnum);
  if (!isnum || s < 0 || s > LSYS_FUNC_MAXSAMPLES)
    luaL_error(L, "core.func: opts.samples must be a whole number from 0 to %d",
               LSYS_FUNC_MAXSAMPLES);
  lua_pop(L, 1);
  return (int)s;
}

/* core.func(points [, opts]) */
static int l_func (lua_State *L) {
  lua_Integer n, i;
  const char *name = "f";
  int samples = 0, st, cpfg = 0;
  double *pt;
  lsys_func *f;
  lsys_error e;
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 2);
  if (!lua_isnil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    if (lua_getfield(L, 2, "name") != LUA_TNIL) {
      if (lua_type(L, -1) != LUA_TSTRING) luaL_error(L, "core.func: opts.name must be a string");
      name = lua_tostring(L, -1);           /* 3, alive on the stack: an __index may */
    }                                       /* have made it, and opts not keep it */
    samples = optsamples(L, 2);
    if (lua_getfield(L, 2, "approx") != LUA_TNIL) {
      const char *a = lua_tostring(L, -1);
      if (lua_type(L, -1) != LUA_TSTRING || (strcmp(a, "exact") != 0 && strcmp(a, "cpfg") != 0))
        luaL_error(L, "core.func: opts.approx must be \"exact\" or \"cpfg\"");
      cpfg = strcmp(a, "cpfg") == 0;
    }
    lua_pop(L, 1);
  }
  n = luaL_len(L, 1);
  if (n < 4 || n > LSYS_FUNC_MAXPOINTS)
    return luaL_argerror(L, 1, lua_pushfstring(L, n < 4 ?
                         "a function needs at least 4 points, got %I" :
                         "too many points: %I (limit is 65536)", n));
  pt = (double *)lua_newuserdatauv(L, 2 * (size_t)n * sizeof *pt, 0);   /* scratch */
  for (i = 1; i <= n; i++) {
    int c;
    if (lua_geti(L, 1, i) != LUA_TTABLE)
      return luaL_argerror(L, 1, lua_pushfstring(L, "point %I is a %s, not a table {x, y}", i,
                                                  luaL_typename(L, -1)));
    for (c = 0; c < 2; c++) {
      int isnum;
      lua_geti(L, -1 - c, c + 1);
      pt[2 * (i - 1) + c] = lua_tonumberx(L, -1, &isnum);
      if (!isnum || lua_type(L, -1) != LUA_TNUMBER)
        return luaL_argerror(L, 1, lua_pushfstring(L, "point %I: %s is a %s, not a number", i,
                                                    c ? "y" : "x", luaL_typename(L, -1)));
    }
    lua_pop(L, 3);
  }
  f = newfunc(L);
  st = lsys_func_set(f, pt, (size_t)n, name, samples, &e);
  if (st != LSYS_OK) {
    if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
    return luaL_argerror(L, 1, e.msg);
  }
  if (cpfg) lsys_func_cpfg(f);
  return 1;
}

/* core.func_parse(text, filename [, samples]) */
static int l_func_parse (lua_State *L) {
  size_t len, n, k;
  const char *text = luaL_checklstring(L, 1, &len);
  const char *name = luaL_checkstring(L, 2);
  lua_Integer vs = luaL_optinteger(L, 3, 0);
  lsys_func *fs;
  lsys_error e;
  int st;
  luaL_argcheck(L, vs >= -1 && vs <= LSYS_FUNC_MAXSAMPLES, 3, "samples out of range");
  st = lsys_func_parse(&fs, &n, text, len, name, (int)vs, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 0);   /* names the file and line */
  lua_createtable(L, (int)n, 0);
  for (k = 0; k < n; k++) {                  /* moved into userdata: nothing can raise */
    lsys_lfunc *u = (lsys_lfunc *)lua_newuserdatauv(L, sizeof *u, 0);
    u->f = fs[k];
    u->life.closed = u->life.kept = 0;
    lsys_func_init(&fs[k]);
    luaL_setmetatable(L, FUNC_T);
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
  LSYS_FREE(fs);
  return 1;
}

/* f(x) and f:eval(x) */
static int func_eval (lua_State *L) {
  const lsys_func *f = lsysL_checkfunc(L, 1);
  lua_pushnumber(L, lsys_func_eval(f, luaL_checknumber(L, 2)));
  return 1;
}

/* The points are copied before the lists are made (a finalizer run by an
** allocation may close the function). */
static int func_points (lua_State *L) {
  size_t i, n = lsysL_checkfunc(L, 1)->n;
  double *pt = (double *)lua_newuserdatauv(L, 2 * n * sizeof *pt + 1, 0);
  const lsys_func *f = lsysL_checkfunc(L, 1);
  if (f->n < n) n = f->n;
  if (n > 0) memcpy(pt, f->pt, 2 * n * sizeof *pt);
  lua_createtable(L, (int)n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, pt[2 * i]);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, pt[2 * i + 1]);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  return 1;
}

static int func_name (lua_State *L) {
  lua_pushstring(L, lsysL_checkfunc(L, 1)->name);
  return 1;
}

static int func_samples (lua_State *L) {
  lua_pushinteger(L, lsysL_checkfunc(L, 1)->samples);
  return 1;
}

static int func_approx (lua_State *L) {
  lua_pushstring(L, lsysL_checkfunc(L, 1)->cpfg ? "cpfg" : "exact");
  return 1;
}

static int func_format (lua_State *L) {
  size_t len = lsys_func_format(lsysL_checkfunc(L, 1), NULL, 0);
  luaL_Buffer b;
  char *p = luaL_buffinitsize(L, &b, len + 1);
  lsys_func_format(lsysL_checkfunc(L, 1), p, len + 1);   /* again: the buffer allocated */
  luaL_pushresultsize(&b, len);
  return 1;
}

static int func_tostring (lua_State *L) {
  const lsys_lfunc *u = (const lsys_lfunc *)luaL_checkudata(L, 1, FUNC_T);
  const char *more = "";
  if (!u->life.closed && u->f.samples > 2)
    more = lua_pushfstring(L, ", %d samples", u->f.samples);
  if (u->life.closed) lua_pushliteral(L, FUNC_T " (closed)");   /* read after that string */
  else lua_pushfstring(L, FUNC_T "(%s: %d points%s)", u->f.name, (int)u->f.n, more);
  return 1;
}

static const luaL_Reg func_methods[] = {
  {"eval", func_eval}, {"points", func_points}, {"name", func_name},
  {"samples", func_samples}, {"approx", func_approx}, {"format", func_format},
  {NULL, NULL}
};

static const luaL_Reg func_meta[] = {
  {"__index", NULL}, {"__gc", func_gc}, {"__close", func_gc}, {"__call", func_eval},
  {"__tostring", func_tostring}, {NULL, NULL}
};

static const luaL_Reg func_funcs[] = {
  {"func", l_func}, {"func_parse", l_func_parse}, {NULL, NULL}
};

void lsysL_open_func (lua_State *L) {
  lsysL_createmeta(L, FUNC_T, func_meta, func_methods);
  luaL_setfuncs(L, func_funcs, 0);
}
