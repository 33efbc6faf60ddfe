/*
** Lua binding of the shadow-propagation grid (csrc/core/shadow.h): the
** lsys.Shadow userdata.
**
**   core.shadow(opts) -> Shadow
**     opts.lo, opts.hi  the box {x, y, z} the grid covers (hi is rounded up to whole voxels)
**     opts.voxel        the voxel's edge, world units, > 0
**     opts.depth        the pyramid's last level q, an integer in [0, 64] (4)
**     opts.a            the shadow a caster puts in its own voxel, > 0 (1)
**     opts.b            its fall-off per level down, > 1 (2): level q gets a b^-q
**     opts.threads      the workers of adds and directions, 0 .. 64 (0: the derivation's
**                       default)
**     opts.max_memory   bytes the grid and an add's blocks may take (the process's budget)
**   S:add(points [, weights])      casters: a flat list {x1, y1, z1, x2, ...}, a list of
**                                  weights (1 each)
**   S:add_scene(scene [, weight])  the scene's triangles as casters at their centroids,
**                                  weighing weight (1) times their area over a voxel's face
**   S:add_box(lo, hi, value)       adds value to the voxels the box lo .. hi overlaps
**   S:clear()                      every shadow back to 0
**   S:shadow(points) -> list       the shadow s at each point (0 outside the grid)
**   S:exposure(points [, C]) -> list   max(C - s + a, 0) at each point; C (1): the
**                                  exposure of a bud in full light (Palubicki et al. 2009)
**   S:direction(points, headings [, opts]) -> flat list of 3 a point: the unit vector to the
**                                  least-shadow voxel in the cone opts.angle (degrees, 90)
**                                  and opts.radius (voxels, 2) around the heading
**   S:stats() -> {nx, ny, nz, voxels, bytes, voxel, lo = {x, y, z}, hi = {x, y, z}}
**   S:close(), __close, __gc
**
** A method reads its lists into blocks the stack owns (their metamethods
** may run any Lua code, and close the Shadow), then checks the Shadow
** again, runs the core, which calls no Lua, and makes the list of results.
*/
#include <string.h>

#include "shadow.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#define SHADOW_T "lsys.Shadow"
#define MAXPOINTS ((lua_Integer)1 << 28)
#define DEFANGLE 90
#define DEFRADIUS 2
#define DEFC 1

typedef struct lshadow {
  lsys_shadow *S;             /* NULL once closed */
  lsys_meter mt;              /* its budget: the grid while it lives, an add's blocks */
  int threads;                /* 0: lsys_derive_default_threads() */
} lshadow;

static lshadow *checkshadow (lua_State *L, int i, const char *who) {
  lshadow *u = (lshadow *)luaL_checkudata(L, i, SHADOW_T);
  if (u->S == NULL) luaL_error(L, "%s: the shadow grid was closed", who);
  return u;
}

static int threadsof (const lshadow *u) {
  return u->threads > 0 ? u->threads : lsys_derive_default_threads();
}

/* Raises the core's message "shadow: ..." as "<who>: ...". */
static int raise (lua_State *L, int st, const lsys_error *e, const char *who) {
  const char *m = e->msg;
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (strncmp(m, "shadow: ", 8) == 0) m += 8;
  return luaL_error(L, "%s: %s", who, m);
}

/* A finite number at the top of the stack (popped); 'what' names it. */
static double popnum (lua_State *L, const char *who, const char *what, lua_Integer i) {
  double x = lua_tonumber(L, -1);
  if (lua_type(L, -1) != LUA_TNUMBER || !isfinite(x))
    luaL_error(L, "%s: %s[%I] must be a finite number, got %s", who, what, i,
               lua_type(L, -1) == LUA_TNUMBER ? "a non-finite number" : luaL_typename(L, -1));
  lua_pop(L, 1);
  return x;
}

/* The list {x, y, z} at index i into v. */
static void readvec (lua_State *L, int i, double v[3], const char *who, const char *what) {
  lua_Integer k;
  if (!lua_istable(L, i) || luaL_len(L, i) != 3)
    luaL_error(L, "%s: %s must be a list {x, y, z} of numbers", who, what);
  for (k = 1; k <= 3; k++) {
    lua_geti(L, i, k);
    v[k - 1] = popnum(L, who, what, k);
  }
}

/* The flat list of numbers at i (a multiple of 3 of them, *n triples) into a
** new block on the stack. */
static double *readflat (lua_State *L, int i, const char *who, const char *what,
                         lua_Integer *n) {
  lua_Integer len, k;
  double *v;
  if (!lua_istable(L, i))
    luaL_error(L, "%s: %s must be a flat list {x1, y1, z1, x2, ...}, got %s", who, what,
               luaL_typename(L, i));
  len = luaL_len(L, i);
  if (len < 0 || len % 3 != 0 || len / 3 > MAXPOINTS)
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

/* The list of n numbers at i into a new block on the stack. */
static double *readlist (lua_State *L, int i, const char *who, const char *what,
                         lua_Integer n, const char *per) {
  lua_Integer len, k;
  double *v;
  if (!lua_istable(L, i))
    luaL_error(L, "%s: %s must be a list of numbers, got %s", who, what, luaL_typename(L, i));
  len = luaL_len(L, i);
  if (len != n) luaL_error(L, "%s: %I %s for %I %s", who, len, what, n, per);
  v = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  for (k = 1; k <= n; k++) {
    lua_geti(L, i, k);
    v[k - 1] = popnum(L, who, what, k);
  }
  return v;
}

/* Pushes the list of the n numbers v (a block on the stack, read before the
** table is made). */
static void pushlist (lua_State *L, const double *v, lua_Integer n) {
  lua_Integer k;
  lua_createtable(L, n > INT32_MAX ? 0 : (int)n, 0);
  for (k = 0; k < n; k++) {
    lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

/* opts.<k>, a list {x, y, z} that must be there, into v. */
static void reqvec (lua_State *L, const lsys_opts *op, const char *k, double v[3]) {
  char what[32];
  snprintf(what, sizeof what, "opts.%s", k);
  if (!lsysL_optfield(L, op, k, LUA_TNONE, NULL))
    luaL_error(L, "core.shadow: opts.%s is missing (a list {x, y, z} of numbers)", k);
  readvec(L, lua_gettop(L), v, "core.shadow", what);
  lua_pop(L, 1);
}

/* core.shadow(opts) */
static int l_shadow (lua_State *L) {
  static const char *const names[] = {"lo", "hi", "voxel", "depth", "a", "b", "threads",
    "max_memory", NULL};
  lsys_opts op = {1, "core.shadow: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_shadow_opts o;
  lsys_error e;
  lshadow *u;
  size_t limit;
  int threads, st;
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  if (lsysL_optunknown(L, &op, names))
    return luaL_error(L, "core.shadow: unknown option '%s' (known: lo, hi, voxel, depth, a, b, "
                      "threads, max_memory)", luaL_tolstring(L, -1, NULL));
  lsys_shadow_defaults(&o);
  reqvec(L, &op, "lo", o.lo);
  reqvec(L, &op, "hi", o.hi);
  if (!lsysL_optfield(L, &op, "voxel", LUA_TNONE, NULL))
    return luaL_error(L, "core.shadow: opts.voxel is missing (the voxel's edge, a finite "
                      "number > 0)");
  lua_pop(L, 1);
  o.voxel = lsysL_optnum(L, &op, "voxel", 1, 0, HUGE_VAL, "a finite number > 0");
  o.depth = lsysL_optint(L, &op, "depth", o.depth, 0, LSYS_SHADOW_MAXDEPTH);
  o.a = lsysL_optnum(L, &op, "a", o.a, 0, HUGE_VAL, "a finite number > 0");
  o.b = lsysL_optnum(L, &op, "b", o.b, 1, HUGE_VAL, "a finite number > 1");
  threads = lsysL_optint(L, &op, "threads", 0, 0, LSYS_SHADOW_MAXTHREADS);
  limit = (size_t)lsysL_optnum(L, &op, "max_memory", (double)lsys_common_memory_limit(), 0,
                               1.8e19, "a positive number of bytes");
  u = (lshadow *)lua_newuserdatauv(L, sizeof *u, 0);
  memset(u, 0, sizeof *u);
  u->mt.limit = limit;
  u->threads = threads;
  luaL_setmetatable(L, SHADOW_T);
  o.meter = &u->mt;
  st = lsys_shadow_new(&u->S, &o, &e);
  if (st != LSYS_OK) return raise(L, st, &e, "core.shadow");
  return 1;
}

/* S:add(points [, weights]) */
static int shadow_add (lua_State *L) {
  static const char *who = "shadow:add";
  const double *p, *w = NULL;
  lua_Integer n;
  lshadow *u;
  lsys_error e;
  int st;
  checkshadow(L, 1, who);
  lua_settop(L, 3);
  p = readflat(L, 2, who, "points", &n);                     /* at 4 */
  if (!lua_isnil(L, 3)) w = readlist(L, 3, who, "weights", n, "points");
  u = checkshadow(L, 1, who);                                /* again: Lua code ran since */
  st = lsys_shadow_add(u->S, p, w, (size_t)n, threadsof(u), &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 0;
}

/* S:add_scene(scene [, weight]) */
static int shadow_add_scene (lua_State *L) {
  static const char *who = "shadow:add_scene";
  lsys_lscene *sc;
  lshadow *u;
  lsys_error e;
  double w;
  int st;
  checkshadow(L, 1, who);
  lsysL_checkscene(L, 2);
  w = luaL_optnumber(L, 3, 1);
  if (!isfinite(w)) return luaL_error(L, "%s: the weight must be a finite number", who);
  u = checkshadow(L, 1, who);
  sc = lsysL_checkscene(L, 2);           /* the pointers last: the core calls no Lua */
  st = lsys_shadow_add_scene(u->S, &sc->sc, w, threadsof(u), &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 0;
}

/* S:add_box(lo, hi, value) */
static int shadow_add_box (lua_State *L) {
  static const char *who = "shadow:add_box";
  double lo[3], hi[3], v;
  lshadow *u;
  lsys_error e;
  int st;
  checkshadow(L, 1, who);
  lua_settop(L, 4);
  readvec(L, 2, lo, who, "lo");
  readvec(L, 3, hi, who, "hi");
  v = luaL_checknumber(L, 4);
  if (!isfinite(v)) return luaL_error(L, "%s: the value must be a finite number", who);
  u = checkshadow(L, 1, who);
  st = lsys_shadow_add_box(u->S, lo, hi, v, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 0;
}

/* S:clear() */
static int shadow_clear (lua_State *L) {
  lsys_shadow_clear(checkshadow(L, 1, "shadow:clear")->S);
  return 0;
}

/* S:shadow(points) and S:exposure(points [, C]) */
static int query (lua_State *L, int exposure, const char *who) {
  const double *p;
  double *out, C = DEFC;
  lua_Integer n;
  lshadow *u;
  lsys_error e;
  int st;
  checkshadow(L, 1, who);
  lua_settop(L, 3);
  if (exposure && !lua_isnil(L, 3)) {
    C = luaL_checknumber(L, 3);
    if (!isfinite(C)) return luaL_error(L, "%s: C must be a finite number", who);
  }
  p = readflat(L, 2, who, "points", &n);                     /* at 4 */
  out = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  u = checkshadow(L, 1, who);
  st = lsys_shadow_query(u->S, p, (size_t)n, exposure, C, out, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  pushlist(L, out, n);
  return 1;
}

static int shadow_shadow (lua_State *L) { return query(L, 0, "shadow:shadow"); }
static int shadow_exposure (lua_State *L) { return query(L, 1, "shadow:exposure"); }

/* A finite number option in (0, hi]; absent, 'def'. */
static double optupto (lua_State *L, const lsys_opts *o, const char *k, double def, double hi,
                       const char *expect) {
  double x = lsysL_optnum(L, o, k, def, 0, HUGE_VAL, expect);
  if (x > hi) {
    lua_getfield(L, o->t, k);
    lsysL_opterror(L, o, k, expect);
  }
  return x;
}

/* S:direction(points, headings [, opts]) */
static int shadow_direction (lua_State *L) {
  static const char *const names[] = {"angle", "radius", NULL};
  static const char *who = "shadow:direction";
  lsys_opts op = {0, "shadow:direction: opts.", "", LSYS_GOT_VALUE, 0};
  const double *p, *h;
  double *out, angle, radius;
  lua_Integer n, nh;
  lshadow *u;
  lsys_error e;
  int st;
  checkshadow(L, 1, who);
  lua_settop(L, 4);
  if (!lua_isnil(L, 4)) {
    luaL_checktype(L, 4, LUA_TTABLE);
    op.t = 4;
    if (lsysL_optunknown(L, &op, names))
      return luaL_error(L, "%s: unknown option '%s' (known: angle, radius)", who,
                        luaL_tolstring(L, -1, NULL));
  }
  angle = optupto(L, &op, "angle", DEFANGLE, 180, "a number of degrees in (0, 180]");
  radius = optupto(L, &op, "radius", DEFRADIUS, LSYS_SHADOW_MAXRADIUS,
                   "a number of voxels in (0, 32]");
  p = readflat(L, 2, who, "points", &n);                     /* at 5 */
  h = readflat(L, 3, who, "headings", &nh);                  /* at 6 */
  if (nh != n) return luaL_error(L, "%s: %I headings for %I points", who, nh, n);
  out = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * 3 * sizeof(double) : 1, 0);
  u = checkshadow(L, 1, who);
  st = lsys_shadow_direction(u->S, p, h, (size_t)n, angle, radius, out, threadsof(u), &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  pushlist(L, out, 3 * n);
  return 1;
}

/* S:stats() -> table */
static int shadow_stats (lua_State *L) {
  lsys_shadow_stats s;
  lsys_shadow_info(checkshadow(L, 1, "shadow:stats")->S, &s);   /* copied: tables allocate */
  lua_createtable(L, 0, 8);
  lua_pushinteger(L, s.n[0]); lua_setfield(L, -2, "nx");
  lua_pushinteger(L, s.n[1]); lua_setfield(L, -2, "ny");
  lua_pushinteger(L, s.n[2]); lua_setfield(L, -2, "nz");
  lua_pushinteger(L, (lua_Integer)s.voxels); lua_setfield(L, -2, "voxels");
  lua_pushinteger(L, (lua_Integer)s.bytes); lua_setfield(L, -2, "bytes");
  lua_pushnumber(L, s.voxel); lua_setfield(L, -2, "voxel");
  lsysL_pushnums(L, s.lo, 3); lua_setfield(L, -2, "lo");
  lsysL_pushnums(L, s.hi, 3); lua_setfield(L, -2, "hi");
  return 1;
}

/* S:close(), __close, __gc: idempotent */
static int shadow_close (lua_State *L) {
  lshadow *u = (lshadow *)luaL_checkudata(L, 1, SHADOW_T);
  lsys_shadow *S = u->S;
  u->S = NULL;
  lsys_shadow_free(S);
  return 0;
}

static int shadow_tostring (lua_State *L) {
  lshadow *u = (lshadow *)luaL_checkudata(L, 1, SHADOW_T);
  lsys_shadow_stats s;
  if (u->S == NULL) {
    lua_pushliteral(L, SHADOW_T " (closed)");
    return 1;
  }
  lsys_shadow_info(u->S, &s);
  lua_pushfstring(L, SHADOW_T ": %d x %d x %d voxels of %f", s.n[0], s.n[1], s.n[2], s.voxel);
  return 1;
}

static const luaL_Reg shadow_meta[] = {
  {"__index", NULL}, {"__gc", shadow_close}, {"__close", shadow_close},
  {"__tostring", shadow_tostring}, {NULL, NULL}
};
static const luaL_Reg shadow_methods[] = {
  {"add", shadow_add}, {"add_scene", shadow_add_scene}, {"add_box", shadow_add_box},
  {"clear", shadow_clear}, {"shadow", shadow_shadow}, {"exposure", shadow_exposure},
  {"direction", shadow_direction}, {"stats", shadow_stats}, {"close", shadow_close},
  {NULL, NULL}
};
static const luaL_Reg shadow_funcs[] = {
  {"shadow", l_shadow}, {NULL, NULL}
};

void lsysL_open_shadow (lua_State *L) {
  lsysL_createmeta(L, SHADOW_T, shadow_meta, shadow_methods);
  luaL_setfuncs(L, shadow_funcs, 0);
}
