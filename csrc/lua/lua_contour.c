/*
** Lua binding of csrc/core/contour.h: the lsys.Contour userdata.
**
**   core.contour_load(path) -> Contour       reads a contour file (Appendix B.1 or cver)
**   core.contour(points [, closed]) -> Contour
**       points = { {x, y [, z]}, ... } (all 2 or all 3 numbers); closed
**       defaults to true
**   c:sample(p) -> vertices, normals         p + 1 entries each, {x, y, z}
**   c:size() -> n    c:closed() -> boolean    c:dim() -> 2 | 3
**   c:points() -> { {x, y [, z]}, ... }      the control points (dim numbers each)
**
** A Contour is immutable once made.
*/
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"

#define MAXFILE (16u << 20)   /* bytes of a contour file */
#define MAXSIDES 65536        /* p of c:sample(p) */

static lsys_contour *newcontour (lua_State *L) {
  lsys_lcontour *u = (lsys_lcontour *)lua_newuserdatauv(L, sizeof *u, 0);
  lsys_contour_init(&u->c);
  u->life.closed = u->life.kept = 0;
  luaL_setmetatable(L, CONTOUR_T);
  return &u->c;
}

/* __gc and __close: idempotent; a kept contour is freed by the collector. */
static int contour_gc (lua_State *L) {
  lsys_lcontour *u = (lsys_lcontour *)luaL_checkudata(L, 1, CONTOUR_T);
  if (lsysL_life_end(L, &u->life)) lsys_contour_free(&u->c);
  return 0;
}

/* core.contour_load(path) */
static int l_contour_load (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  lsys_contour *c = newcontour(L);
  lsys_error e;
  size_t len = 0;
  int st;
  char *text = lsys_common_readfile(path, MAXFILE, &len, &e);
  if (text == NULL) return lsysL_raise(L, LSYS_ESYNTAX, &e, 0);   /* names the file */
  st = lsys_contour_parse(c, text, len, path, &e);
  LSYS_FREE(text);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 0);   /* names file and line */
  return 1;
}

/* core.contour(points [, closed]) */
static int l_contour (lua_State *L) {
  lua_Integer n, i;
  int dim = 0, closed, k, st;
  double *pt;
  lsys_contour *c;
  lsys_error e;
  luaL_checktype(L, 1, LUA_TTABLE);
  if (lua_isnoneornil(L, 2)) closed = 1;
  else {
    luaL_checktype(L, 2, LUA_TBOOLEAN);
    closed = lua_toboolean(L, 2);
  }
  n = luaL_len(L, 1);
  if (n < (closed ? 3 : 4))
    return luaL_argerror(L, 1, lua_pushfstring(L, "%s contour needs at least %d points, got %I",
                                                closed ? "a closed" : "an open",
                                                closed ? 3 : 4, n));
  if (n > LSYS_CONTOUR_MAXPOINTS)
    return luaL_argerror(L, 1, lua_pushfstring(L, "too many points (limit is %d)",
                                                LSYS_CONTOUR_MAXPOINTS));
  pt = (double *)lua_newuserdatauv(L, 3 * (size_t)n * sizeof *pt, 0);   /* scratch */
  for (i = 1; i <= n; i++) {
    int d;
    if (lua_geti(L, 1, i) != LUA_TTABLE)
      return luaL_argerror(L, 1, lua_pushfstring(L, "point %I is a %s, not a table", i,
                                                  luaL_typename(L, -1)));
    d = (int)lua_rawlen(L, -1);
    if (dim == 0) dim = d;
    if (d != dim || (d != 2 && d != 3))
      return luaL_argerror(L, 1, lua_pushfstring(L, d == 2 || d == 3
                                                  ? "point %I has %d coordinates, point 1 has %d"
                                                  : "point %I has %d coordinates, not 2 or 3",
                                                  i, d, dim));
    pt[3 * (i - 1) + 2] = 0.0;
    for (k = 0; k < dim; k++) {
      if (lua_rawgeti(L, -1, k + 1) != LUA_TNUMBER)
        return luaL_argerror(L, 1, lua_pushfstring(L, "coordinate %d of point %I is a %s, "
                                                    "not a number", k + 1, i,
                                                    luaL_typename(L, -1)));
      pt[3 * (i - 1) + k] = lua_tonumber(L, -1);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  c = newcontour(L);
  if ((st = lsys_contour_set(c, pt, (size_t)n, closed, dim, &e)) != LSYS_OK) {
    if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
    return luaL_argerror(L, 1, e.msg);
  }
  return 1;
}

/* Pushes a list of p + 1 {x, y, z} tables. */
static void pushpoints (lua_State *L, const double *v, int p) {
  int i, k;
  lua_createtable(L, p + 1, 0);
  for (i = 0; i <= p; i++) {
    lua_createtable(L, 3, 0);
    for (k = 0; k < 3; k++) {
      lua_pushnumber(L, v[3 * i + k]);
      lua_rawseti(L, -2, k + 1);
    }
    lua_rawseti(L, -2, i + 1);
  }
}

/* c:sample(p) -> vertices, normals */
static int contour_sample (lua_State *L) {
  const lsys_contour *c = lsysL_checkcontour(L, 1);
  lua_Integer p = luaL_checkinteger(L, 2);
  double *v;
  luaL_argcheck(L, p >= 3 && p <= MAXSIDES, 2, "must be between 3 and 65536");
  luaL_argcheck(L, c->pt != NULL, 1, "empty contour");
  v = (double *)lua_newuserdatauv(L, 6 * ((size_t)p + 1) * sizeof *v, 0);
  c = lsysL_checkcontour(L, 1);              /* again: a finalizer may have closed it */
  lsys_contour_sample(c, (int)p, v, v + 3 * (p + 1));
  pushpoints(L, v, (int)p);
  pushpoints(L, v + 3 * (p + 1), (int)p);
  return 2;
}

static int contour_size (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsysL_checkcontour(L, 1)->n);
  return 1;
}

static int contour_closed (lua_State *L) {
  lua_pushboolean(L, lsysL_checkcontour(L, 1)->closed);
  return 1;
}

static int contour_dim (lua_State *L) {
  lua_pushinteger(L, lsysL_checkcontour(L, 1)->dim);
  return 1;
}

/* c:points(): the control points are copied first (a finalizer run by an
** allocation may close the contour). */
static int contour_points (lua_State *L) {
  size_t i, n = lsysL_checkcontour(L, 1)->n;
  double *pt = (double *)lua_newuserdatauv(L, 3 * n * sizeof *pt + 1, 0);   /* scratch */
  const lsys_contour *c = lsysL_checkcontour(L, 1);
  int k, dim = c->dim;
  if (c->n < n) n = c->n;
  if (n > 0) memcpy(pt, c->pt, 3 * n * sizeof *pt);
  lua_createtable(L, (int)n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, dim, 0);
    for (k = 0; k < dim; k++) {
      lua_pushnumber(L, pt[3 * i + (size_t)k]);
      lua_rawseti(L, -2, k + 1);
    }
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  return 1;
}

static int contour_tostring (lua_State *L) {
  const lsys_lcontour *u = (const lsys_lcontour *)luaL_checkudata(L, 1, CONTOUR_T);
  const lsys_contour *c = &u->c;
  if (u->life.closed) {
    lua_pushliteral(L, CONTOUR_T " (closed)");
    return 1;
  }
  lua_pushfstring(L, CONTOUR_T "(%I points, %s)", (lua_Integer)c->n,
                  c->closed ? "closed" : "open");
  return 1;
}

static const luaL_Reg contour_methods[] = {
  {"sample", contour_sample}, {"size", contour_size}, {"closed", contour_closed},
  {"dim", contour_dim}, {"points", contour_points}, {NULL, NULL}
};

static const luaL_Reg contour_meta[] = {
  {"__index", NULL},  /* placeholder: set to the method table */
  {"__gc", contour_gc}, {"__close", contour_gc}, {"__tostring", contour_tostring},
  {NULL, NULL}
};

static const luaL_Reg contour_funcs[] = {
  {"contour_load", l_contour_load}, {"contour", l_contour}, {NULL, NULL}
};

void lsysL_open_contour (lua_State *L) {
  lsysL_createmeta(L, CONTOUR_T, contour_meta, contour_methods);
  luaL_setfuncs(L, contour_funcs, 0);
}
