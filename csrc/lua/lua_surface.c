/*
** Lua binding of csrc/core/surface.h: the lsys.Surface userdata (a cpfg surface
** file, cpfg guide §4.1) and patch evaluation.
**
**   core.surface_load(path) -> Surface        reads a surface file
**   core.surface_parse(text [, name]) -> Surface
**       the same from a string; 'name' (default "surface") starts messages
**   s:info() -> {patches, contact, heading, up, end, lo, hi, size,
**                precision = {s, t}, names = {...}}
**   s:patch(i) -> { {x, y, z}, ... }          the 16 control points of patch i
**       (from 1), row by row as patch_eval takes them
**   s:with_points(points) -> Surface          a copy with other control points:
**       16 {x, y, z} per patch, patch after patch (point 16 (i - 1) + k is
**       point k of patch i)
**   s:format() -> string                      the surface file's text
**   core.patch_eval(basis, ctrl, s, t) -> x, y, z
**       basis 1 | 2 | 3 or "bezier" | "bspline" | "cardinal"; ctrl a list of
**       16 {x, y, z}, row by row (row r, column c at 4 r + c + 1)
**
** Malformed files raise "name:LINE: what is wrong". A Surface is immutable
** once made; it keeps its name as its user value.
*/
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"

#define MAXFILE ((size_t)16 << 20)    /* bytes of a surface file */

/* __gc and __close: idempotent; a kept surface is freed by the collector. */
static int surface_gc (lua_State *L) {
  lsys_lsurface *u = (lsys_lsurface *)luaL_checkudata(L, 1, SURFACE_T);
  if (lsysL_life_end(L, &u->life)) lsys_surface_free(&u->s);
  return 0;
}

/* Pushes a new empty Surface whose user value is the string at 'name'. */
static lsys_surface *newsurface (lua_State *L, int name) {
  lsys_lsurface *u = (lsys_lsurface *)lua_newuserdatauv(L, sizeof *u, 1);
  lsys_surface_init(&u->s);
  u->life.closed = u->life.kept = 0;
  luaL_setmetatable(L, SURFACE_T);
  lua_pushvalue(L, name);
  lua_setiuservalue(L, -2, 1);
  return &u->s;
}

/* core.surface_load(path) */
static int l_surface_load (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  lsys_surface *s = newsurface(L, 1);
  lsys_error e;
  size_t len = 0;
  int st;
  char *text = lsys_common_readfile(path, MAXFILE, &len, &e);
  if (text == NULL) return lsysL_raise(L, LSYS_ESYNTAX, &e, 0);   /* names the file */
  st = lsys_surface_parse(s, text, len, path, &e);
  LSYS_FREE(text);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 0);   /* names file and line */
  return 1;
}

/* core.surface_parse(text [, name]) */
static int l_surface_parse (lua_State *L) {
  size_t len;
  const char *text = luaL_checklstring(L, 1, &len);
  const char *name = luaL_optstring(L, 2, "surface");
  lsys_surface *s;
  lsys_error e;
  int st;
  lua_settop(L, 2);
  if (lua_isnil(L, 2)) {
    lua_pushstring(L, name);
    lua_replace(L, 2);
  }
  s = newsurface(L, 2);
  st = lsys_surface_parse(s, text, len, name, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 0);   /* names file and line */
  return 1;
}

#define pushvec lsysL_pushnums

/* s:info(): the fields are read again after each allocation (a finalizer
** may close the surface) */
static int surface_info (lua_State *L) {
  const lsys_surface *s;
  size_t i, n;
  lua_createtable(L, 0, 11);
  s = lsysL_checksurface(L, 1);
  lua_pushinteger(L, (lua_Integer)s->npatch);
  lua_setfield(L, -2, "patches");
  pushvec(L, lsysL_checksurface(L, 1)->contact, 3);
  lua_setfield(L, -2, "contact");
  pushvec(L, lsysL_checksurface(L, 1)->heading, 3);
  lua_setfield(L, -2, "heading");
  pushvec(L, lsysL_checksurface(L, 1)->up, 3);
  lua_setfield(L, -2, "up");
  pushvec(L, lsysL_checksurface(L, 1)->end, 3);
  lua_setfield(L, -2, "end");
  pushvec(L, lsysL_checksurface(L, 1)->lo, 3);
  lua_setfield(L, -2, "lo");
  pushvec(L, lsysL_checksurface(L, 1)->hi, 3);
  lua_setfield(L, -2, "hi");
  s = lsysL_checksurface(L, 1);
  lua_pushnumber(L, (lua_Number)s->size);
  lua_setfield(L, -2, "size");
  lua_createtable(L, 2, 0);
  s = lsysL_checksurface(L, 1);
  lua_pushinteger(L, (lua_Integer)s->precision_s);
  lua_rawseti(L, -2, 1);
  lua_pushinteger(L, (lua_Integer)s->precision_t);
  lua_rawseti(L, -2, 2);
  lua_setfield(L, -2, "precision");
  lua_createtable(L, (int)lsysL_checksurface(L, 1)->npatch, 0);
  n = lsysL_checksurface(L, 1)->npatch;
  for (i = 0; i < n; i++) {
    s = lsysL_checksurface(L, 1);
    if (s->info == NULL) break;
    lua_pushstring(L, s->info[i].name);
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  lua_setfield(L, -2, "names");
  return 1;
}

/* s:patch(i): copied first (a finalizer run by an allocation may close the
** surface) */
static int surface_patch (lua_State *L) {
  lua_Integer i = luaL_checkinteger(L, 2);
  size_t n = lsysL_checksurface(L, 1)->npatch;
  lsys_patch p;
  int k, j;
  luaL_argcheck(L, i >= 1 && (size_t)i <= n, 2,
                lua_pushfstring(L, "patch index must be from 1 to %I", (lua_Integer)n));
  p = lsysL_checksurface(L, 1)->patch[i - 1];
  lua_createtable(L, 16, 0);
  for (k = 0; k < 16; k++) {
    lua_createtable(L, 3, 0);
    for (j = 0; j < 3; j++) {
      lua_pushnumber(L, (lua_Number)p.ctrl[3 * k + j]);
      lua_rawseti(L, -2, j + 1);
    }
    lua_rawseti(L, -2, k + 1);
  }
  return 1;
}

/* s:with_points(points) */
static int surface_with_points (lua_State *L) {
  size_t n = lsysL_checksurface(L, 1)->npatch, i;
  lsys_surface *dst;
  lsys_error e;
  double *pt;
  int k, st;
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  if ((size_t)luaL_len(L, 2) != 16 * n)
    return luaL_argerror(L, 2, lua_pushfstring(L, "expected %I points (16 per patch), got %I",
                                                (lua_Integer)(16 * n), luaL_len(L, 2)));
  pt = (double *)lua_newuserdatauv(L, 48 * n * sizeof *pt + 1, 0);   /* 3: scratch */
  for (i = 0; i < 16 * n; i++) {
    if (lua_geti(L, 2, (lua_Integer)i + 1) != LUA_TTABLE)
      return luaL_argerror(L, 2, lua_pushfstring(L, "point %I is a %s, not a table",
                                                  (lua_Integer)i + 1, luaL_typename(L, -1)));
    for (k = 0; k < 3; k++) {
      int isnum;
      lua_geti(L, -1, k + 1);
      pt[3 * i + (size_t)k] = (double)lua_tonumberx(L, -1, &isnum);
      if (!isnum)
        return luaL_argerror(L, 2, lua_pushfstring(L, "coordinate %d of point %I is not a "
                                                    "number", k + 1, (lua_Integer)i + 1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_getiuservalue(L, 1, 1);                 /* 4: the name */
  dst = newsurface(L, 4);                     /* 5 */
  st = lsys_surface_with_points(dst, lsysL_checksurface(L, 1), pt, &e);
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (st != LSYS_OK) return luaL_argerror(L, 2, e.msg);
  return 1;
}

/* s:format() */
static int surface_format (lua_State *L) {
  size_t len = lsys_surface_format(lsysL_checksurface(L, 1), NULL, 0);
  luaL_Buffer b;
  char *p = luaL_buffinitsize(L, &b, len + 1);
  len = lsys_surface_format(lsysL_checksurface(L, 1), p, len + 1);   /* again: it allocated */
  luaL_pushresultsize(&b, len);
  return 1;
}

static int surface_tostring (lua_State *L) {
  const lsys_lsurface *u = (const lsys_lsurface *)luaL_checkudata(L, 1, SURFACE_T);
  const lsys_surface *s = &u->s;
  if (u->life.closed) {
    lua_pushliteral(L, "lsys.Surface (closed)");
    return 1;
  }
  lua_getiuservalue(L, 1, 1);
  lua_pushfstring(L, "lsys.Surface(%s, %d patch%s)", luaL_optstring(L, -1, "?"),
                  (int)s->npatch, s->npatch == 1 ? "" : "es");
  return 1;
}

/* core.patch_eval(basis, ctrl, s, t) */
static int l_patch_eval (lua_State *L) {
  static const char *const names[] = {"bezier", "bspline", "cardinal", NULL};
  lsys_patch p;
  double s, t, pos[3];
  int basis, i, k;
  if (lua_type(L, 1) == LUA_TSTRING) basis = luaL_checkoption(L, 1, NULL, names) + 1;
  else {
    lua_Integer b = luaL_checkinteger(L, 1);
    luaL_argcheck(L, b >= 1 && b <= 3, 1, "basis must be 1 (Bezier), 2 (B-spline) or 3 (Cardinal)");
    basis = (int)b;
  }
  luaL_checktype(L, 2, LUA_TTABLE);
  s = luaL_checknumber(L, 3);
  t = luaL_checknumber(L, 4);
  luaL_argcheck(L, isfinite(s), 3, "not a finite number");
  luaL_argcheck(L, isfinite(t), 4, "not a finite number");
  luaL_argcheck(L, luaL_len(L, 2) == 16, 2, "expected 16 control points");
  for (i = 0; i < 16; i++) {
    if (lua_geti(L, 2, i + 1) != LUA_TTABLE)
      return luaL_argerror(L, 2, lua_pushfstring(L, "control point %d is a %s, not a table",
                                                  i + 1, luaL_typename(L, -1)));
    for (k = 0; k < 3; k++) {
      int isnum;
      lua_geti(L, -1, k + 1);
      p.ctrl[3 * i + k] = (double)lua_tonumberx(L, -1, &isnum);
      if (!isnum)
        return luaL_argerror(L, 2, lua_pushfstring(L, "coordinate %d of control point %d is "
                                                    "not a number", k + 1, i + 1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lsys_surface_patch_eval(basis, &p, s, t, pos, NULL, NULL);
  for (k = 0; k < 3; k++) lua_pushnumber(L, (lua_Number)pos[k]);
  return 3;
}

static const luaL_Reg surface_methods[] = {
  {"info", surface_info},
  {"patch", surface_patch},
  {"with_points", surface_with_points},
  {"format", surface_format},
  {NULL, NULL}
};

static const luaL_Reg surface_meta[] = {
  {"__index", NULL},  /* placeholder: the method table */
  {"__gc", surface_gc},
  {"__close", surface_gc},
  {"__tostring", surface_tostring},
  {NULL, NULL}
};

static const luaL_Reg funcs[] = {
  {"surface_load", l_surface_load},
  {"surface_parse", l_surface_parse},
  {"patch_eval", l_patch_eval},
  {NULL, NULL}
};

void lsysL_open_surface (lua_State *L) {
  lsysL_createmeta(L, SURFACE_T, surface_meta, surface_methods);
  luaL_setfuncs(L, funcs, 0);
}
