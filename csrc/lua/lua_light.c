/*
** Lua binding of the light environment (csrc/core/light.h): the lsys.Light
** userdata.
**
**   core.light(scene, opts) -> Light
**     opts.sky         "overcast" (default) | {sun = {x, y, z}, ambient = a (0)}
**                      | {{x, y, z [, w (1)]}, ...} (weighted directions)
**     opts.radiance    the overcast sky's: "uniform" (default) | "cosine" | "cie"
**     opts.samples     overcast directions, 1 .. 65536 (64)
**     opts.transmittance  what a surface lets through, [0, 1) (0: opaque)
**     opts.max_hits    hits counted along a ray with a transmittance, 1 .. 64 (8)
**     opts.line_radius lines occlude as capsules of this radius, world units (0: they do not)
**     opts.offset      hits nearer a point are not counted, world units (1e-4 of the
**                      scene's diagonal)
**     opts.threads     the queries' default, 0 .. 64 (0: the derivation's default)
**     opts.max_memory  bytes the hierarchy may take (the process's budget)
**   light:query(points [, normals] [, opts]) -> values [, directions]
**     points, normals: flat lists {x1, y1, z1, x2, ...} (normals nil: buds, every direction
**     counts); opts {directions = true, threads = n}; values: a list of one number a
**     point; directions (with opts.directions) a flat list of 3 a point. A table without
**     list items in the place of the normals is the options.
**   light:sky() -> directions (a flat list), weights (a list)
**   light:stats() -> {triangles, capsules, nodes, depth, bytes, directions, offset}
**   light:close(), __close, __gc
**
** The Light owns its copy of the scene's geometry (core.light builds it and
** keeps no pointer into the Scene). A query reads its lists into blocks the
** stack owns (their metamethods may run any Lua code, and close the Light),
** then checks the Light again, runs the core, which calls no Lua, and
** makes the lists of results.
*/
#include <string.h>

#include "light.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#define MAXPOINTS ((lua_Integer)1 << 28)

typedef struct llight {
  lsys_light *L;              /* NULL once closed */
  int threads;                /* the queries' default; 0: lsys_derive_default_threads() */
} llight;

static lsys_light *checklight (lua_State *L, int i, const char *who) {
  llight *u = (llight *)luaL_checkudata(L, i, LIGHT_T);
  if (u->L == NULL) luaL_error(L, "%s: the light was closed", who);
  return u->L;
}

/* Raises the core's message "light: ..." as "<who>: ...". */
static int raise (lua_State *L, int st, const lsys_error *e, const char *who) {
  const char *m = e->msg;
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (strncmp(m, "light: ", 7) == 0) m += 7;
  return luaL_error(L, "%s: %s", who, m);
}

/* A finite number at the top of the stack (popped); 'what' names it. */
static double popnum (lua_State *L, const char *who, const char *what, lua_Integer i) {
  int ok;
  double x = lua_tonumberx(L, -1, &ok);
  if (lua_type(L, -1) != LUA_TNUMBER || !isfinite(x))
    luaL_error(L, "%s: %s[%I] must be a finite number, got %s", who, what, i,
               lua_type(L, -1) == LUA_TNUMBER ? "a non-finite number" : luaL_typename(L, -1));
  lua_pop(L, 1);
  return x;
}

/* {x, y, z [, w]} at the top of the stack into v (w defaults to 1); popped. */
static void readvec (lua_State *L, double *v, int nw, const char *who, const char *what) {
  lua_Integer n = lua_istable(L, -1) ? luaL_len(L, -1) : 0, k;
  if (n < 3 || n > 3 + nw)
    luaL_error(L, "%s: %s must be %s", who, what,
               nw ? "a list {x, y, z [, w]} of numbers" : "a list {x, y, z} of numbers");
  v[3] = 1;
  for (k = 1; k <= n; k++) {
    lua_geti(L, -1, k);
    v[k - 1] = popnum(L, who, what, k);
  }
  lua_pop(L, 1);
}

/* A finite number option in [lo, hi], the ends left out as 'open' says (1:
** lo, 2: hi); absent, 'def'. */
static double optrange (lua_State *L, const lsys_opts *o, const char *k, double def, double lo,
                        double hi, int open, const char *expect) {
  double x;
  if (o->t == 0 || lua_getfield(L, o->t, k) == LUA_TNIL) {
    if (o->t != 0) lua_pop(L, 1);
    return def;
  }
  lua_pop(L, 1);
  x = lsysL_optnum(L, o, k, def, -HUGE_VAL, HUGE_VAL, expect);
  if (x < lo || x > hi || ((open & 1) && x == lo) || ((open & 2) && x == hi)) {
    lua_getfield(L, o->t, k);
    lsysL_opterror(L, o, k, expect);
  }
  return x;
}

/* opts.sky into o; the caller's directions in a block left on the stack. */
static void readsky (lua_State *L, const lsys_opts *op, lsys_light_opts *o) {
  static const char *who = "core.light";
  static const char *expect = "'overcast', {sun = {x, y, z}, ambient = a} or a list of "
                              "directions {x, y, z, w}";
  int t;
  if (!lsysL_optfield(L, op, "sky", LUA_TNONE, NULL)) { lua_pushnil(L); return; }
  t = lua_gettop(L);
  if (lua_type(L, t) == LUA_TSTRING) {
    if (strcmp(lua_tostring(L, t), "overcast") != 0) lsysL_opterror(L, op, "sky", expect);
    lua_pushnil(L);
  } else if (lua_type(L, t) != LUA_TTABLE) lsysL_opterror(L, op, "sky", expect);
  else if (lua_getfield(L, t, "sun") != LUA_TNIL) {
    static const char *const names[] = {"sun", "ambient", NULL};
    lsys_opts so = {t, "core.light: opts.sky.", "", LSYS_GOT_VALUE, 0};
    double v[4];
    readvec(L, v, 0, who, "opts.sky.sun");
    memcpy(o->sun, v, sizeof o->sun);
    if (lsysL_optunknown(L, &so, names))
      luaL_error(L, "core.light: unknown sky option '%s' (known: sun, ambient)",
                 luaL_tolstring(L, -1, NULL));
    o->ambient = optrange(L, &so, "ambient", 0, 0, 1, 0, "a number in [0, 1]");
    o->kind = LSYS_LIGHT_SUN;
    lua_pushnil(L);
  } else {
    lua_Integer n = luaL_len(L, t), k;
    double *d;
    char what[48];
    lua_pop(L, 1);
    if (n < 1 || n > LSYS_LIGHT_MAXSAMPLES) lsysL_opterror(L, op, "sky", expect);
    d = (double *)lua_newuserdatauv(L, (size_t)n * 4 * sizeof(double), 0);
    for (k = 1; k <= n; k++) {
      lua_geti(L, t, k);
      snprintf(what, sizeof what, "opts.sky[%d]", (int)k);
      readvec(L, d + 4 * (k - 1), 1, who, what);
    }
    o->kind = LSYS_LIGHT_DIRS;
    o->dirs = d;
    o->ndirs = (size_t)n;
  }
  lua_remove(L, t);
}

/* core.light(scene, opts) */
static int l_light (lua_State *L) {
  static const char *const names[] = {"sky", "radiance", "samples", "transmittance",
    "max_hits", "line_radius", "offset", "threads", "max_memory", NULL};
  static const char *const radiances[] = {"uniform", "cosine", "cie", NULL};
  lsys_opts op = {2, "core.light: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_light_opts o;
  lsys_meter mt = {0, 0, 0, NULL};
  lsys_lscene *S;
  lsys_error e;
  llight *u;
  int threads, st;
  lsysL_checkscene(L, 1);
  if (lua_isnoneornil(L, 2)) op.t = 0;
  else luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  if (lsysL_optunknown(L, &op, names))
    return luaL_error(L, "core.light: unknown option '%s' (known: sky, radiance, samples, "
                      "transmittance, max_hits, line_radius, offset, threads, max_memory)",
                      luaL_tolstring(L, -1, NULL));
  lsys_light_defaults(&o);
  readsky(L, &op, &o);                                  /* leaves a block (or nil) at 3 */
  o.radiance = lsysL_optchoice(L, &op, "radiance", LSYS_LIGHT_UNIFORM, radiances,
                               "'uniform', 'cosine' or 'cie'");
  o.samples = lsysL_optint(L, &op, "samples", 64, 1, LSYS_LIGHT_MAXSAMPLES);
  o.transmittance = optrange(L, &op, "transmittance", 0, 0, 1, 2, "a number in [0, 1)");
  o.max_hits = lsysL_optint(L, &op, "max_hits", 8, 1, LSYS_LIGHT_MAXHITS);
  o.line_radius = optrange(L, &op, "line_radius", 0, 0, HUGE_VAL, 0, "a finite number >= 0");
  o.offset = optrange(L, &op, "offset", 0, 0, HUGE_VAL, 1, "a finite number > 0");
  threads = lsysL_optint(L, &op, "threads", 0, 0, LSYS_LIGHT_MAXTHREADS);
  mt.limit = (size_t)lsysL_optnum(L, &op, "max_memory", (double)lsys_common_memory_limit(), 0,
                                  1.8e19, "a positive number of bytes");
  o.meter = &mt;
  u = (llight *)lua_newuserdatauv(L, sizeof *u, 0);
  u->L = NULL;
  u->threads = threads;
  luaL_setmetatable(L, LIGHT_T);
  S = lsysL_checkscene(L, 1);                           /* again: the allocation may close it */
  st = lsys_light_build(&u->L, &S->sc, &o, &e);
  if (st != LSYS_OK) return raise(L, st, &e, "core.light");
  return 1;
}

/* The flat list of numbers at i (a multiple of 3 of them, *n triples) into a
** new block on the stack. */
static double *readflat (lua_State *L, int i, const char *who, const char *what,
                         lua_Integer *n) {
  lua_Integer len = luaL_len(L, i), k;
  double *v;
  if (len % 3 != 0 || len / 3 > MAXPOINTS)
    luaL_error(L, "%s: %s must be a flat list {x1, y1, z1, x2, ...} of at most 2^28 points, "
               "got %I numbers", who, what, len);
  v = (double *)lua_newuserdatauv(L, len > 0 ? (size_t)len * sizeof(double) : 1, 0);
  for (k = 1; k <= len; k++) {
    lua_geti(L, i, k);
    v[k - 1] = popnum(L, who, what, k);
  }
  *n = len / 3;
  return v;
}

/* light:query(points [, normals] [, opts]) */
static int light_query (lua_State *L) {
  static const char *const names[] = {"directions", "threads", NULL};
  static const char *who = "light:query";
  lsys_opts op = {0, "light:query: opts.", "", LSYS_GOT_VALUE, 0};
  llight *u;
  const double *pts, *nrm = NULL;
  double *out, *dir = NULL;
  lua_Integer n, nn, k;
  int wantdir, threads, st;
  lsys_error e;
  checklight(L, 1, who);
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 4);
  if (lua_istable(L, 3) && lua_isnil(L, 4) && lua_rawlen(L, 3) == 0)   /* (points, opts) */
    lua_insert(L, 3);                                 /* the nil at 4 goes to 3 */
  if (!lua_isnil(L, 3) && !lua_istable(L, 3))
    return luaL_error(L, "%s: the normals must be a flat list {x1, y1, z1, ...} or nil, got %s",
                      who, luaL_typename(L, 3));
  if (!lua_isnil(L, 4)) {
    luaL_checktype(L, 4, LUA_TTABLE);
    op.t = 4;
    if (lsysL_optunknown(L, &op, names))
      return luaL_error(L, "%s: unknown option '%s' (known: directions, threads)", who,
                        luaL_tolstring(L, -1, NULL));
  }
  wantdir = lsysL_optbool(L, &op, "directions", 0);
  threads = lsysL_optint(L, &op, "threads", -1, 0, LSYS_LIGHT_MAXTHREADS);
  pts = readflat(L, 2, who, "points", &n);                               /* at 5 */
  if (lua_istable(L, 3)) {
    nrm = readflat(L, 3, who, "normals", &nn);                           /* at 6 */
    if (nn != n)
      return luaL_error(L, "%s: %I normals for %I points", who, nn, n);
  } else lua_pushnil(L);
  out = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  if (wantdir) dir = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * 3 * sizeof(double) : 1,
                                                 0);
  checklight(L, 1, who);                              /* again: Lua code ran since */
  u = (llight *)lua_touserdata(L, 1);
  if (threads < 0) threads = u->threads;
  if (threads == 0) threads = lsys_derive_default_threads();
  st = lsys_light_query(u->L, pts, (size_t)n, nrm, out, dir, threads, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  lua_createtable(L, n > INT32_MAX ? 0 : (int)n, 0);
  for (k = 0; k < n; k++) {
    lua_pushnumber(L, out[k]);
    lua_rawseti(L, -2, k + 1);
  }
  if (!wantdir) return 1;
  lua_createtable(L, 3 * n > INT32_MAX ? 0 : (int)(3 * n), 0);
  for (k = 0; k < 3 * n; k++) {
    lua_pushnumber(L, dir[k]);
    lua_rawseti(L, -2, k + 1);
  }
  return 2;
}

/* light:sky() -> directions, weights */
static int light_sky (lua_State *L) {
  const double *d, *w;
  size_t n = lsys_light_sky(checklight(L, 1, "light:sky"), &d, &w), k;
  double *c = (double *)lua_newuserdatauv(L, n * 4 * sizeof(double), 0);
  /* the allocation may run finalizers, and one may close the light: ask again (a closed
  ** light raises; an open one has the same sky) */
  n = lsys_light_sky(checklight(L, 1, "light:sky"), &d, &w);
  memcpy(c, d, 3 * n * sizeof(double));                 /* copied: the tables allocate */
  memcpy(c + 3 * n, w, n * sizeof(double));
  lua_createtable(L, (int)(3 * n), 0);
  for (k = 0; k < 3 * n; k++) {
    lua_pushnumber(L, c[k]);
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
  lua_createtable(L, (int)n, 0);
  for (k = 0; k < n; k++) {
    lua_pushnumber(L, c[3 * n + k]);
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
  return 2;
}

/* light:stats() -> table */
static int light_stats (lua_State *L) {
  lsys_light_stats s;
  lsys_light_info(checklight(L, 1, "light:stats"), &s);
  lua_createtable(L, 0, 7);
  lua_pushinteger(L, (lua_Integer)s.triangles); lua_setfield(L, -2, "triangles");
  lua_pushinteger(L, (lua_Integer)s.capsules); lua_setfield(L, -2, "capsules");
  lua_pushinteger(L, (lua_Integer)s.nodes); lua_setfield(L, -2, "nodes");
  lua_pushinteger(L, (lua_Integer)s.depth); lua_setfield(L, -2, "depth");
  lua_pushinteger(L, (lua_Integer)s.bytes); lua_setfield(L, -2, "bytes");
  lua_pushinteger(L, (lua_Integer)s.ndirs); lua_setfield(L, -2, "directions");
  lua_pushnumber(L, s.offset); lua_setfield(L, -2, "offset");
  return 1;
}

/* light:close(), __close, __gc: idempotent */
static int light_close (lua_State *L) {
  llight *u = (llight *)luaL_checkudata(L, 1, LIGHT_T);
  lsys_light *p = u->L;
  u->L = NULL;
  lsys_light_free(p);
  return 0;
}

static int light_tostring (lua_State *L) {
  llight *u = (llight *)luaL_checkudata(L, 1, LIGHT_T);
  lsys_light_stats s;
  if (u->L == NULL) {
    lua_pushliteral(L, LIGHT_T " (closed)");
    return 1;
  }
  lsys_light_info(u->L, &s);
  lua_pushfstring(L, LIGHT_T ": %I triangles, %I capsules, %I directions",
                  (lua_Integer)s.triangles, (lua_Integer)s.capsules, (lua_Integer)s.ndirs);
  return 1;
}

static const luaL_Reg light_meta[] = {
  {"__index", NULL}, {"__gc", light_close}, {"__close", light_close},
  {"__tostring", light_tostring}, {NULL, NULL}
};
static const luaL_Reg light_methods[] = {
  {"query", light_query}, {"sky", light_sky}, {"stats", light_stats}, {"close", light_close},
  {NULL, NULL}
};
static const luaL_Reg light_funcs[] = {
  {"light", l_light}, {NULL, NULL}
};

void lsysL_open_light (lua_State *L) {
  lsysL_createmeta(L, LIGHT_T, light_meta, light_methods);
  luaL_setfuncs(L, light_funcs, 0);
}
