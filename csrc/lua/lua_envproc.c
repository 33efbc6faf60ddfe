/*
** Lua binding of environmental programs (csrc/core/envproc.h): the process
** and its bytes, under the text protocol of lua/lsys/environment.lua.
**
**   core.envproc { transport = "pipes" | "files" | "memory" (default pipes),
**                  dir = folder (default: the current one),
**                  argv = { "honda81", "-e", "x.e", "spec", ... },
**                  timeout = seconds (default 30) } -> EnvProcess
**     p:exchange(msg) -> reply   one chunk (ending with its "Control: F S" line)
**                                and the reply up to its first Control line
**     p:more() -> reply          the next part of a reply whose Control flag
**                                lacked the last-chunk bit (4)
**     p:close()                  ends the program (also __close, __gc)
**
** Errors raise with the core's message ("environmental program 'honda81': did
** not answer within 30 s"). The core blocks (at most the timeout) but calls no
** Lua, and a reply is copied into a Lua string before anything can run, so no
** finalizer can free what a method reads.
*/
#include <string.h>

#include "envproc.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#define MAXARGS 1000

typedef struct lenvproc {
  lsys_envproc *p;            /* NULL once closed */
} lenvproc;

/* The process at 1; raises when it was closed. Called after the other
** arguments are read (reading them may run a finalizer that closes it). */
static lsys_envproc *checkproc (lua_State *L, const char *who) {
  lenvproc *u = (lenvproc *)luaL_checkudata(L, 1, ENVPROC_T);
  if (u->p == NULL) luaL_error(L, "%s: the process was closed", who);
  return u->p;
}

/* A string without zero bytes at the top of the stack, else raises naming it. */
static const char *plainstring (lua_State *L, const char *what, lua_Integer i) {
  size_t n;
  const char *s;
  if (lua_type(L, -1) != LUA_TSTRING) {
    if (i > 0) luaL_error(L, "envproc: opts.argv[%I] must be a string, got %s", i,
                          luaL_typename(L, -1));
    luaL_error(L, "envproc: opts.%s must be a string, got %s", what, luaL_typename(L, -1));
  }
  s = lua_tolstring(L, -1, &n);
  if (strlen(s) != n) {
    if (i > 0) luaL_error(L, "envproc: opts.argv[%I] has a zero byte", i);
    luaL_error(L, "envproc: opts.%s has a zero byte", what);
  }
  return s;
}

/* core.envproc(opts): the strings stay on the stack while the core reads them. */
static int l_envproc (lua_State *L) {
  static const char *const names[] = { "transport", "dir", "argv", "timeout", NULL };
  static const char *const transports[] = { "pipes", "files", "memory", NULL };
  lsys_opts o = { 1, "envproc: opts.", "", LSYS_GOT_VALUE, 0 };
  const char *dir = NULL, **argv;
  lua_Integer n, i;
  int transport, aidx, base, st;
  double timeout;
  lenvproc *u;
  lsys_error e;
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  if (lsysL_optunknown(L, &o, names))
    return luaL_error(L, "envproc: unknown option '%s'", luaL_tolstring(L, -1, NULL));
  transport = lsysL_optchoice(L, &o, "transport", LSYS_ENVPROC_PIPES, transports,
                              "'pipes', 'files' or 'memory'");
  timeout = lsysL_optnum(L, &o, "timeout", 30, 0, 1e6, "a number of seconds in (0, 1e6)");
  if (lsysL_optfield(L, &o, "dir", LUA_TNONE, NULL)) dir = plainstring(L, "dir", 0);
  else lua_pushnil(L);
  if (!lsysL_optfield(L, &o, "argv", LUA_TTABLE, "a list of strings"))
    return luaL_error(L, "envproc: opts.argv is missing (the program and its arguments)");
  aidx = lua_gettop(L);
  n = luaL_len(L, aidx);
  if (n < 1 || n > MAXARGS)
    return luaL_error(L, "envproc: opts.argv must hold 1 to %d strings, got %I", MAXARGS, n);
  luaL_checkstack(L, (int)n + 4, "envproc: too many arguments");
  base = lua_gettop(L);
  for (i = 1; i <= n; i++) {
    lua_geti(L, aidx, i);
    plainstring(L, "argv", i);
  }
  argv = (const char **)lua_newuserdatauv(L, ((size_t)n + 1) * sizeof *argv, 0);
  u = (lenvproc *)lua_newuserdatauv(L, sizeof *u, 0);
  u->p = NULL;
  luaL_setmetatable(L, ENVPROC_T);
  for (i = 1; i <= n; i++) argv[i - 1] = lua_tostring(L, base + (int)i);   /* no Lua from here */
  argv[n] = NULL;
  st = lsys_envproc_start(&u->p, transport, dir, argv, timeout, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  return 1;
}

/* p:exchange(msg) -> reply */
static int envproc_exchange (lua_State *L) {
  size_t len, n;
  const char *msg = luaL_checklstring(L, 2, &len), *r;
  lsys_envproc *p = checkproc(L, "EnvProcess:exchange");
  lsys_error e;
  int st = lsys_envproc_exchange(p, msg, len, &r, &n, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  lua_pushlstring(L, r, n);
  return 1;
}

/* p:more() -> reply */
static int envproc_more (lua_State *L) {
  lsys_envproc *p = checkproc(L, "EnvProcess:more");
  const char *r;
  size_t n;
  lsys_error e;
  int st = lsys_envproc_more(p, &r, &n, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  lua_pushlstring(L, r, n);
  return 1;
}

/* p:close(), __close, __gc: ends the program (blocks at most its timeout). Idempotent. */
static int envproc_close (lua_State *L) {
  lenvproc *u = (lenvproc *)luaL_checkudata(L, 1, ENVPROC_T);
  lsys_envproc *p = u->p;
  u->p = NULL;
  lsys_envproc_close(p);
  return 0;
}

static int envproc_tostring (lua_State *L) {
  static const char *const transports[] = { "pipes", "files", "memory" };
  lenvproc *u = (lenvproc *)luaL_checkudata(L, 1, ENVPROC_T);
  if (u->p == NULL) lua_pushliteral(L, ENVPROC_T " (closed)");
  else lua_pushfstring(L, ENVPROC_T " '%s' (%s, pid %I)", lsys_envproc_name(u->p),
                       transports[lsys_envproc_transport(u->p)],
                       (lua_Integer)lsys_envproc_pid(u->p));
  return 1;
}

static const luaL_Reg envproc_meta[] = {
  {"__index", NULL}, {"__gc", envproc_close}, {"__close", envproc_close},
  {"__tostring", envproc_tostring}, {NULL, NULL}
};
static const luaL_Reg envproc_methods[] = {
  {"exchange", envproc_exchange}, {"more", envproc_more}, {"close", envproc_close},
  {NULL, NULL}
};
static const luaL_Reg envproc_funcs[] = {
  {"envproc", l_envproc}, {NULL, NULL}
};

void lsysL_open_envproc (lua_State *L) {
  lsysL_createmeta(L, ENVPROC_T, envproc_meta, envproc_methods);
  luaL_setfuncs(L, envproc_funcs, 0);
}
