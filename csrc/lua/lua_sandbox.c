/*
** The bounds rule code runs within (docs/manual.md §4,
** "What rule code can reach"). Rule text may come from someone else, so
** while a model's rules run (a derivation step, an expansion, the turtle
** streaming the homomorphism; lsysL_rules_run) and while rules:sandboxed runs
** a function (the axiom's expressions, a cpfg file's Start/End blocks):
**
** - a count hook bounds the Lua instructions of each call of rule code
**   (the model's max_instructions): an endless loop ends in an error that
**   names the rule instead of hanging the derivation;
** - the state's allocator is wrapped, so that Lua cannot grow by more than
**   the model's max_memory during the run (a string built by rule code is as
**   bounded as the strings the core builds);
** - the methods of strings (`("x"):rep(n)`, `s:find(p)`) are those of the
**   sandbox's string library (lsys.sandbox registers it with
**   core.sandbox_strings), whose repetition and pattern functions refuse work
**   beyond these bounds: a C function runs no Lua instructions, so the hook
**   alone cannot stop a pattern that backtracks for hours.
**
** Everything is put back as it was when the run ends, however it ends, and
** runs nest (a rule function deriving another model): each level restores
** what it found.
*/
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common.h"
#include "lua_aux.h"

/* the registry field of the sandbox's string library */
#define SANDBOX_STRINGS "lsys.sandbox.strings"

/* the hook counts in steps of this many instructions */
#define HOOKSTEP 1000

/* Lua's allocator with the growth since the sandbox was entered bounded. A
** growth refused in Lua's core makes it collect garbage and ask again; the
** buffers of lauxlib (string.rep, table.concat, gsub) ask the allocator
** directly and raise at once, so lsysL_sandbox_collect collects at safe points
** before the budget is reached. The memory error is reworded by
** lsysL_sandbox_leave. */
static void *boundedalloc (void *ud, void *ptr, size_t osize, size_t nsize) {
  lsys_sandbox *sb = (lsys_sandbox *)ud;
  size_t old = ptr != NULL ? osize : 0;         /* a new block: osize is its type */
  void *p;
  if (nsize > old && sb->net + (long long)(nsize - old) > sb->limit) {
    sb->memhit = 1;
    return NULL;
  }
  p = sb->alloc(sb->aud, ptr, osize, nsize);
  if (p != NULL || nsize == 0) sb->net += (long long)nsize - (long long)old;
  return p;
}

void lsysL_sandbox_collect (lua_State *L, lsys_sandbox *sb) {
  if (sb->net <= sb->gcat) return;
  lua_gc(L, LUA_GCCOLLECT, 0);
  /* next when halfway from what is left to the bound: what rule code keeps is not
  ** collected again and again, and the collections come closer only near the bound */
  sb->gcat = sb->net + (sb->limit - sb->net) / 2;
}

/* The count hook: every HOOKSTEP instructions of Lua code in the run. The
** sandbox is the allocator's (the innermost one entered). */
static void counthook (lua_State *L, lua_Debug *ar) {
  void *ud;
  lsys_sandbox *sb;
  if (lua_getallocf(L, &ud) != boundedalloc) return;
  sb = (lsys_sandbox *)ud;
  /* a count hook it replaced still runs, at this one's pace (the program's interrupt:
  ** Ctrl-C before a long step still stops it within HOOKSTEP instructions) */
  if (sb->hook != NULL && sb->hook != counthook && (sb->hmask & LUA_MASKCOUNT))
    sb->hook(L, ar);
  lsysL_sandbox_collect(L, sb);
  sb->ran += HOOKSTEP;
  if (sb->ran > sb->budget) {
    char b[48];
    sb->timehit = 1;
    snprintf(b, sizeof b, "%.0f", sb->budget);
    lua_pushfstring(L, "ran more than %s Lua instructions in one call "
                    "(set max_instructions in the model)", b);
    lua_error(L);                   /* no position: the caller names the rule or block */
  }
}

void lsysL_sandbox_enter (lua_State *L, lsys_sandbox *sb, const lsys_lrules *R) {
  size_t limit = R->m.max_memory > 0 ? R->m.max_memory : lsys_common_memory_limit();
  memset(sb, 0, sizeof *sb);
  sb->budget = R->max_instructions > 0 ? R->max_instructions : LSYS_MAX_INSTRUCTIONS;
  sb->limit = limit >= (size_t)LLONG_MAX ? LLONG_MAX : (long long)limit;
  sb->gcat = sb->limit / 2;
  /* the string methods: the previous __index stays on the stack for leave */
  lua_pushliteral(L, "");
  if (lua_getmetatable(L, -1)) {
    lua_pushliteral(L, "__index");
    lua_rawget(L, -2);                                   /* "" mt old */
    if (lua_getfield(L, LUA_REGISTRYINDEX, SANDBOX_STRINGS) == LUA_TTABLE) {
      lua_pushliteral(L, "__index");
      lua_insert(L, -2);
      lua_rawset(L, -4);
      sb->swapped = 1;
    } else lua_pop(L, 1);
    lua_replace(L, -3);
    lua_pop(L, 1);                                       /* old */
  }
  sb->stridx = lua_gettop(L);
  /* the hook, then the allocator (the hook finds the sandbox through it) */
  sb->hook = lua_gethook(L);
  sb->hmask = lua_gethookmask(L);
  sb->hcount = lua_gethookcount(L);
  if (sb->budget < HUGE_VAL) lua_sethook(L, counthook, LUA_MASKCOUNT, HOOKSTEP);
  sb->alloc = lua_getallocf(L, &sb->aud);
  lua_setallocf(L, boundedalloc, sb);
  sb->entered = 1;
}

void lsysL_sandbox_leave (lua_State *L, lsys_sandbox *sb, int err) {
  if (!sb->entered) return;
  sb->entered = 0;
  lua_setallocf(L, sb->alloc, sb->aud);
  /* only our own hook goes: one set meanwhile (the program's interrupt, lsys.c) stays */
  if (sb->budget < HUGE_VAL && lua_gethook(L) == counthook)
    lua_sethook(L, sb->hook, sb->hmask, sb->hcount);
  if (sb->swapped) {
    lua_pushliteral(L, "");
    if (lua_getmetatable(L, -1)) {
      lua_pushliteral(L, "__index");
      lua_pushvalue(L, sb->stridx);
      lua_rawset(L, -3);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_remove(L, sb->stridx);
  if (err != LUA_OK && sb->memhit && (err == LUA_ERRMEM ||    /* lauxlib: a plain error */
      (lua_type(L, -1) == LUA_TSTRING && strcmp(lua_tostring(L, -1), "not enough memory") == 0))) {
    char b[32];
    lua_pop(L, 1);
    lua_pushfstring(L, "needs more than max_memory (%s) for Lua values (set max_memory "
                    "in the model, or LSYS_MAX_MEMORY)",
                    lsys_common_fmtsize(b, (size_t)sb->limit));
  }
}

/* rules:sandboxed(f, ...) -> f(...) within the bounds of the model's rules (its
** max_instructions for the whole call, its max_memory); raises f's error. */
static int rules_sandboxed (lua_State *L) {
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lsys_sandbox sb;
  int n, err;
  luaL_checktype(L, 2, LUA_TFUNCTION);
  n = lua_gettop(L);
  lsysL_sandbox_enter(L, &sb, R);
  lua_rotate(L, 2, 1);                       /* the string library below f and its args */
  sb.stridx = 2;
  sb.strict = 1;
  err = lua_pcall(L, n - 2, LUA_MULTRET, 0);
  lsysL_sandbox_leave(L, &sb, err);
  if (err != LUA_OK) return lua_error(L);
  return lua_gettop(L) - 1;
}

/* core.sandbox_strict() -> whether rule text runs now (in the innermost run): the
** string functions of lsys.sandbox then bound their work. */
static int l_sandbox_strict (lua_State *L) {
  void *ud;
  lua_pushboolean(L, lua_getallocf(L, &ud) == boundedalloc && ((lsys_sandbox *)ud)->strict);
  return 1;
}

/* core.sandbox_strings(t): the table whose functions are the methods of strings
** while rule code runs (lsys.sandbox). */
static int l_sandbox_strings (lua_State *L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  lua_setfield(L, LUA_REGISTRYINDEX, SANDBOX_STRINGS);
  return 0;
}

void lsysL_open_sandbox (lua_State *L) {
  lua_pushcfunction(L, l_sandbox_strings);
  lua_setfield(L, -2, "sandbox_strings");
  lua_pushcfunction(L, l_sandbox_strict);
  lua_setfield(L, -2, "sandbox_strict");
  luaL_getmetatable(L, RULES_T);
  lua_getfield(L, -1, "__index");
  lua_pushcfunction(L, rules_sandboxed);
  lua_setfield(L, -2, "sandboxed");
  lua_pop(L, 2);
}
