/*
** Lua binding of the branch-path IK (ik.h; Power et al. 1999) for lsys.arrange.
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
#include "lua_aux.h"
#include "lua_lsys.h"

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

/* The fields of the table at 't', named "ik: <pre><key>" in messages that
** show nothing more; numbers may be numerals. */
static lsys_opts ikopts (int t, const char *pre) {
  lsys_opts o = {0, NULL, "", LSYS_GOT_NONE, 1};
  o.t = t;
  o.pre = pre;
  return o;
}

/* Reads o[key] = {x, y, z} (finite) into v; 'def' when absent (NULL: required). */
static void getvec (lua_State *L, const lsys_opts *o, const char *key, double v[3],
                    const double *def) {
  int i;
  if (!lsysL_optfield(L, o, key, LUA_TNONE, NULL)) {
    if (def == NULL) lsysL_opterror(L, o, key, "a table of 3 numbers");
    memcpy(v, def, 3 * sizeof *v);
    return;
  }
  if (!lua_istable(L, -1)) lsysL_opterror(L, o, key, "a table of 3 numbers");
  for (i = 0; i < 3; i++) {
    lua_rawgeti(L, -1, i + 1);
    v[i] = lua_tonumber(L, -1);
    if (!lua_isnumber(L, -1) || !isfinite(v[i]))
      lsysL_opterror(L, o, key, "a table of 3 finite numbers");
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* A number >= 0 (weights, counts, tolerances). */
static double getnum (lua_State *L, const lsys_opts *o, const char *key, double def) {
  double x = lsysL_optnum(L, o, key, def, -HUGE_VAL, HUGE_VAL, "a number >= 0");
  if (x < 0) lsysL_opterror(L, o, key, "a number >= 0");
  return x;
}

static int l_ik_chain (lua_State *L) {
  static const double zero[3] = {0, 0, 0}, one[3] = {1, 1, 1};
  double bH[3], bU[3], base[9], prevend[3], prev[9];
  lua_Integer n, i;
  lsys_opts o;
  lik *k;
  luaL_checktype(L, 1, LUA_TTABLE);
  if (lua_getfield(L, 1, "base") != LUA_TTABLE) return luaL_error(L, "ik: a base table expected");
  o = ikopts(2, "ik: base.");
  getvec(L, &o, "H", bH, NULL);
  getvec(L, &o, "U", bU, NULL);
  getvec(L, &o, "p", prevend, NULL);
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
    o = ikopts(t, "ik: joint.");
    memset(j, 0, sizeof *j);
    getvec(L, &o, "p0", p0, NULL);
    getvec(L, &o, "p1", p1, NULL);
    getvec(L, &o, "H", H, NULL);
    getvec(L, &o, "U", U, NULL);
    getvec(L, &o, "alpha", a, zero);
    getvec(L, &o, "rest", r, zero);
    getvec(L, &o, "stiff", s, one);
    for (q = 0; q < 3; q++) {
      if (s[q] < 0) return luaL_error(L, "ik: joint %d: stiffness must be >= 0", (int)i);
      j->alpha[q] = a[q] / DEG;
      j->rest[q] = r[q] / DEG;
      j->stiff[q] = s[q];
    }
    j->free = (unsigned)getnum(L, &o, "free", 7) & 7u;
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

/* The goal is read before the chain is taken: its metamethods run Lua code. */
static int ik_solve (lua_State *L) {
  lik *k = checkik(L, 1);
  lsys_opts go = ikopts(2, "ik: goal.");
  lsys_ikgoal G;
  lsys_cg_opts o;
  lsys_ik_result r;
  lsys_error e;
  luaL_checktype(L, 2, LUA_TTABLE);
  memset(&G, 0, sizeof G);
  getvec(L, &go, "p", G.p, NULL);
  getvec(L, &go, "s", G.s, NULL);
  getvec(L, &go, "t", G.t, NULL);
  G.wp = getnum(L, &go, "wp", 1);
  G.wt = getnum(L, &go, "wt", 1);
  G.we = getnum(L, &go, "we", 1);
  G.ws = getnum(L, &go, "ws", 0);
  lsys_cg_defaults(&o);
  o.max_iter = (int)getnum(L, &go, "max_iter", o.max_iter);
  o.gtol = getnum(L, &go, "gtol", o.gtol);
  if (o.max_iter < 1) o.max_iter = 1;
  k = checkik(L, 1);
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

#define pushvec(L, v) lsysL_pushnums((L), (v), 3)

/* The angles are copied before the tables are made (a finalizer run by an
** allocation may close the chain). */
static int ik_angles (lua_State *L) {
  int i, q, n = checkik(L, 1)->c.n;
  double *a = (double *)lua_newuserdatauv(L, 3 * (size_t)n * sizeof *a, 0);
  lik *k = checkik(L, 1);
  for (i = 0; i < n; i++)
    for (q = 0; q < 3; q++) a[3 * i + q] = k->c.j[i].alpha[q] * DEG;
  lua_createtable(L, n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, 3, 0);
    for (q = 0; q < 3; q++) {
      lua_pushnumber(L, a[3 * i + q]);
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
  int i, n = k->c.n;
  pts = (double *)lua_newuserdatauv(L, (size_t)n * 6 * sizeof *pts, 0);
  k = checkik(L, 1);                        /* again: a finalizer may have closed it */
  lsys_ik_forward(&k->c, NULL, p, s, t, NULL, pts);
  pushvec(L, p);
  pushvec(L, s);
  pushvec(L, t);
  lua_createtable(L, n, 0);
  for (i = 0; i < n; i++) {
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

static const luaL_Reg ik_meta[] = {
  {"__index", NULL},  /* placeholder: the method table */
  {"__gc", ik_gc}, {"__close", ik_gc}, {"__len", ik_len}, {NULL, NULL}
};

void lsysL_open_ik (lua_State *L) {
  lsysL_createmeta(L, IK_T, ik_meta, ik_methods);
  lua_pushcfunction(L, l_ik_chain);
  lua_setfield(L, -2, "ik_chain");
}
