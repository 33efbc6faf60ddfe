/*
** Lua binding of the branch-path IK (ik.h, seed 000) for lsys.arrange.
**
**   core.ik_chain{ base = { H = v, U = v, p = v },
**                  joints = { { p0 = v, p1 = v, H = v, U = v, alpha = {h, u, l},
**                               rest = {h, u, l}, stiff = {sh, su, sl}, free = mask }, ... } }
**     -> IK      (v: {x, y, z}; angles in degrees; alpha: the joint's @J angles as the
**                 segment is drawn now; rest default 0, stiff default 1, free default 7)
**   ik:solve{ p = v, s = v, t = v, wp =, wt =, we =, ws =, max_iter =, gtol = }
**     -> { status = "gtol" | "ftol" | "maxiter" | "maxeval" | "linesearch",
**          iterations, evaluations, f0, f, dist }
**   ik:angles() -> { {h, u, l}, ... } (degrees)     ik:set_angles(list)
**   ik:forward() -> p, s, t, { {start, end}, ... }   (s = U x H and t = U of the tip)
**   #ik -> the number of joints
*/
#include <math.h>
#include <string.h>

#include "ik.h"
#include "lua_lsys.h"

#define IK_T "lsys.IK"
#define DEG (180.0 / 3.14159265358979323846)

typedef struct lik {
  lsys_ikchain c;
  void *work;             /* lsys_ik_work_size(n): a solve allocates nothing */
} lik;

/* The IK chain at 'i'; raises when it was finalized. */
static lik *checkik (lua_State *L, int i) {
  lik *k = (lik *)luaL_checkudata(L, i, IK_T);
  if (k->c.j == NULL) luaL_error(L, "ik: the chain was closed");
  return k;
}

static int ik_gc (lua_State *L) {
  lik *k = (lik *)luaL_checkudata(L, 1, IK_T);
  LSYS_FREE(k->c.j);
  LSYS_FREE(k->work);
  k->c.j = NULL;
  k->work = NULL;
  k->c.n = 0;
  return 0;
}

/* Reads t[key] = {x, y, z} (finite) into v; 'def' when absent (NULL: required). */
static void getvec (lua_State *L, int t, const char *key, double v[3], const double *def,
                    const char *what) {
  int i;
  if (lua_getfield(L, t, key) == LUA_TNIL && def != NULL) {
    memcpy(v, def, 3 * sizeof *v);
    lua_pop(L, 1);
    return;
  }
  if (!lua_istable(L, -1)) luaL_error(L, "ik: %s.%s must be a table of 3 numbers", what, key);
  for (i = 0; i < 3; i++) {
    lua_rawgeti(L, -1, i + 1);
    v[i] = lua_tonumber(L, -1);
    if (!lua_isnumber(L, -1) || !isfinite(v[i]))
      luaL_error(L, "ik: %s.%s must be a table of 3 finite numbers", what, key);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

static double getnum (lua_State *L, int t, const char *key, double def, const char *what) {
  double x;
  if (lua_getfield(L, t, key) == LUA_TNIL) { lua_pop(L, 1); return def; }
  x = lua_tonumber(L, -1);
  if (!lua_isnumber(L, -1) || !isfinite(x) || x < 0)
    luaL_error(L, "ik: %s.%s must be a number >= 0", what, key);
  lua_pop(L, 1);
  return x;
}

static int l_ik_chain (lua_State *L) {
  static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
  double bH[3], bU[3], base[9], prevend[3], prev[9];
  lua_Integer n, i;
  lik *k;
  luaL_checktype(L, 1, LUA_TTABLE);
  if (lua_getfield(L, 1, "base") != LUA_TTABLE) return luaL_error(L, "ik: a base table expected");
  getvec(L, 2, "H", bH, NULL, "base");
  getvec(L, 2, "U", bU, NULL, "base");
  getvec(L, 2, "p", prevend, NULL, "base");
  lua_pop(L, 1);
  if (lua_getfield(L, 1, "joints") != LUA_TTABLE) return luaL_error(L, "ik: a joints list expected");
  n = luaL_len(L, 2);
  luaL_argcheck(L, n >= 1 && n <= (1 << 22), 1, "ik: 1 or more joints expected");
  k = (lik *)lua_newuserdatauv(L, sizeof *k, 0);
  memset(k, 0, sizeof *k);
  luaL_setmetatable(L, IK_T);
  k->c.j = (lsys_ikjoint *)LSYS_MALLOC((size_t)n * sizeof *k->c.j);
  k->work = LSYS_MALLOC(lsys_ik_work_size((int)n));
  if (k->c.j == NULL || k->work == NULL) return luaL_error(L, "not enough memory for the IK");
  k->c.n = (int)n;
  lsys_ik_frame(base, bH, bU);
  memcpy(k->c.base, base, sizeof base);
  memcpy(k->c.root, prevend, sizeof prevend);
  memcpy(prev, base, sizeof prev);
  for (i = 1; i <= n; i++) {
    lsys_ikjoint *j = &k->c.j[i - 1];
    double p0[3], p1[3], H[3], U[3], M[9], a[3], r[3], s[3];
    int t, q;
    if (lua_rawgeti(L, 2, i) != LUA_TTABLE) return luaL_error(L, "ik: joint %d is not a table", (int)i);
    t = lua_gettop(L);
    memset(j, 0, sizeof *j);
    getvec(L, t, "p0", p0, NULL, "joint");
    getvec(L, t, "p1", p1, NULL, "joint");
    getvec(L, t, "H", H, NULL, "joint");
    getvec(L, t, "U", U, NULL, "joint");
    getvec(L, t, "alpha", a, zero, "joint");
    getvec(L, t, "rest", r, zero, "joint");
    getvec(L, t, "stiff", s, one, "joint");
    for (q = 0; q < 3; q++) {
      if (s[q] < 0) return luaL_error(L, "ik: joint %d: stiffness must be >= 0", (int)i);
      j->alpha[q] = a[q] / DEG;
      j->rest[q] = r[q] / DEG;
      j->stiff[q] = s[q];
    }
    j->free = (unsigned)getnum(L, t, "free", 7, "joint") & 7u;
    lsys_ik_frame(M, H, U);
    lsys_ik_setjoint(j, prev, prevend, M, p0, p1);
    memcpy(prev, M, sizeof M);
    memcpy(prevend, p1, sizeof p1);
    lua_pop(L, 1);
  }
  return 1;
}

static const char *const statusname[] = {
  "?", "gtol", "ftol", "maxiter", "maxeval", "linesearch"
};

static int ik_solve (lua_State *L) {
  lik *k = checkik(L, 1);
  lsys_ikgoal G;
  lsys_cg_opts o;
  lsys_ik_result r;
  lsys_error e;
  luaL_checktype(L, 2, LUA_TTABLE);
  memset(&G, 0, sizeof G);
  getvec(L, 2, "p", G.p, NULL, "goal");
  getvec(L, 2, "s", G.s, NULL, "goal");
  getvec(L, 2, "t", G.t, NULL, "goal");
  G.wp = getnum(L, 2, "wp", 1, "goal");
  G.wt = getnum(L, 2, "wt", 1, "goal");
  G.we = getnum(L, 2, "we", 1, "goal");
  G.ws = getnum(L, 2, "ws", 0, "goal");
  lsys_cg_defaults(&o);
  o.max_iter = (int)getnum(L, 2, "max_iter", o.max_iter, "goal");
  o.gtol = getnum(L, 2, "gtol", o.gtol, "goal");
  if (o.max_iter < 1) o.max_iter = 1;
  if (lsys_ik_solve(&k->c, &G, &o, k->work, &r, &e) != LSYS_OK)
    return luaL_error(L, "ik: %s", e.msg);
  lua_createtable(L, 0, 6);
  lua_pushstring(L, statusname[r.cg.status >= 1 && r.cg.status <= 5 ? r.cg.status : 0]);
  lua_setfield(L, -2, "status");
  lua_pushinteger(L, r.cg.iterations);
  lua_setfield(L, -2, "iterations");
  lua_pushinteger(L, r.cg.evaluations);
  lua_setfield(L, -2, "evaluations");
  lua_pushnumber(L, r.f0);
  lua_setfield(L, -2, "f0");
  lua_pushnumber(L, r.f);
  lua_setfield(L, -2, "f");
  lua_pushnumber(L, r.dist);
  lua_setfield(L, -2, "dist");
  return 1;
}

static void pushvec (lua_State *L, const double v[3]) {
  int i;
  lua_createtable(L, 3, 0);
  for (i = 0; i < 3; i++) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

static int ik_angles (lua_State *L) {
  lik *k = checkik(L, 1);
  int i, q;
  lua_createtable(L, k->c.n, 0);
  for (i = 0; i < k->c.n; i++) {
    lua_createtable(L, 3, 0);
    for (q = 0; q < 3; q++) {
      lua_pushnumber(L, k->c.j[i].alpha[q] * DEG);
      lua_rawseti(L, -2, q + 1);
    }
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

static int ik_set_angles (lua_State *L) {
  lik *k = checkik(L, 1);
  int i, q;
  luaL_checktype(L, 2, LUA_TTABLE);
  for (i = 0; i < k->c.n; i++) {
    if (lua_rawgeti(L, 2, i + 1) != LUA_TTABLE) return luaL_error(L, "ik: angles %d missing", i + 1);
    for (q = 0; q < 3; q++) {
      lua_rawgeti(L, -1, q + 1);
      k->c.j[i].alpha[q] = luaL_checknumber(L, -1) / DEG;
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  return 0;
}

static int ik_forward (lua_State *L) {
  lik *k = checkik(L, 1);
  double p[3], s[3], t[3], *pts;
  int i;
  pts = (double *)lua_newuserdatauv(L, (size_t)k->c.n * 6 * sizeof *pts, 0);
  lsys_ik_forward(&k->c, NULL, p, s, t, NULL, pts);
  pushvec(L, p);
  pushvec(L, s);
  pushvec(L, t);
  lua_createtable(L, k->c.n, 0);
  for (i = 0; i < k->c.n; i++) {
    lua_createtable(L, 2, 0);
    pushvec(L, pts + 6 * i);
    lua_rawseti(L, -2, 1);
    pushvec(L, pts + 6 * i + 3);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, i + 1);
  }
  return 4;
}

static int ik_len (lua_State *L) {
  lua_pushinteger(L, checkik(L, 1)->c.n);
  return 1;
}

static const luaL_Reg ik_methods[] = {
  {"solve", ik_solve}, {"angles", ik_angles}, {"set_angles", ik_set_angles},
  {"forward", ik_forward}, {NULL, NULL}
};

void lsys_open_ik (lua_State *L) {
  luaL_newmetatable(L, IK_T);
  luaL_newlib(L, ik_methods);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, ik_gc);
  lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, ik_gc);
  lua_setfield(L, -2, "__close");
  lua_pushcfunction(L, ik_len);
  lua_setfield(L, -2, "__len");
  lua_pop(L, 1);
  lua_pushcfunction(L, l_ik_chain);
  lua_setfield(L, -2, "ik_chain");
}
