/*
** Lua binding of space (csrc/core/space.h): the lsys.Space and lsys.Markers
** userdata.
**
**   core.space(points, opts) -> Space
**     points          a flat list {x1, y1, z1, x2, ...}
**     opts.radius     the cells' side and the queries' default radius, > 0 (required)
**     opts.groups     a list of integers, one a point (all 0)
**     opts.vigour     a list of numbers, one a point (all 0)
**     opts.scene      a Scene: its segments' ends and triangles' centroids join the space
**                     after the points (group 0, vigour math.huge: obstacles)
**     opts.threads    the queries' default, 0 .. 64 (0: the derivation's default)
**     opts.max_memory bytes the space may take (the process's budget)
**   space:count([points] [, opts]) -> list of integers: the points within the radius
**   space:density([points] [, opts]) -> list: the sum of (1 - d^2 / r^2)^2 over them
**   space:nearest([points] [, opts]) -> list: the nearest one's distance (math.huge: none)
**   space:free([points] [, opts]) -> list of 1 / 0: Honda's collision test, 1 when no point
**     of the query's group and of a vigour at least its own is within the radius
**     points: a flat list of query points, or nil: the space's listed points, each leaving
**     itself out; opts {radius = r (the space's; at most 16 times it), offset = d (the
**     scene's points nearer a query are left out; 0), threads = n, and for free with points
**     groups = {...}, vigour = {...} (the queries', 0)}
**   space:stats() -> {points, listed, cells, buckets, bytes, radius}
**   #space, space:close(), __close, __gc, __tostring
**
**   core.markers(points, opts) -> Markers      (space colonisation's attraction points)
**     points a flat list; opts {threads = n, max_memory = bytes (the markers and the
**     scratch of their passes)}
**   markers:perceive(buds, headings, opts) -> counts, directions
**     buds, headings: flat lists, one triple a bud; opts {perception = r (> 0, required),
**     angle = a (the cone's half-angle, degrees, (0, 180]; 90), kill = k (>= 0: markers
**     within k of a bud are removed first; 0), threads = n}; counts: a list of integers (the
**     markers each bud was given), directions: a flat list (their normalised sum of unit
**     vectors; 0, 0, 0 for none)
**   markers:remove(points, radius [, opts]) -> the number removed (within radius of a point)
**   markers:count() (and #markers) -> the markers left; markers:points() -> a flat list
**   markers:close(), __close, __gc, __tostring
**
**   core.field(opts) -> Field                  (a resource that diffuses in a grid)
**     opts {lo = {x, y, z}, hi = {x, y, z} (lo <= hi), cell = h (> 0), threads = n,
**     max_memory = bytes}; every amount 0
**   field:dims() -> nx, ny, nz, h;  field:values() -> the flat list of amounts (x fastest)
**   field:set(values) (a list of nx ny nz finite amounts >= 0), field:fill(v)
**   field:at(points) -> the amounts of the points' cells (0 outside)
**   field:add(points, amounts) -> how many were inside (an amount < 0 takes, down to 0)
**   field:take(points, wants) -> what each got (its cell's share: space.h)
**   field:diffuse(D, t [, opts {threads = n}]) -> the substeps taken (space.h)
**   field:gradient(points) -> a flat list, 3 a point;  field:total() -> the sum
**   field:close(), __close, __gc, __tostring
**
** The lists are read into blocks the stack owns before anything else (their
** metamethods may run any Lua code, and close the object), the object is
** checked again, the core runs (it calls no Lua), and the lists of results
** are made from blocks.
*/
#include <string.h>

#include "space.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#define SPACE_T   "lsys.Space"
#define MARKERS_T "lsys.Markers"
#define FIELD_T   "lsys.Field"
#define MAXPOINTS ((lua_Integer)1 << 28)

typedef struct lspace {
  lsys_space *S;              /* NULL once closed */
  int threads;                /* the queries' default; 0: lsys_derive_default_threads() */
} lspace;

typedef struct lmarkers {
  lsys_markers *M;            /* NULL once closed */
  lsys_meter mt;              /* the markers' budget: they point to it */
  int threads;
} lmarkers;

typedef struct lfield {
  lsys_field *F;              /* NULL once closed */
  lsys_meter mt;              /* the field's budget: it points to it */
  int threads;
} lfield;

static lsys_space *checkspace (lua_State *L, int i, const char *who) {
  lspace *u = (lspace *)luaL_checkudata(L, i, SPACE_T);
  if (u->S == NULL) luaL_error(L, "%s: the space was closed", who);
  return u->S;
}

static lsys_markers *checkmarkers (lua_State *L, int i, const char *who) {
  lmarkers *u = (lmarkers *)luaL_checkudata(L, i, MARKERS_T);
  if (u->M == NULL) luaL_error(L, "%s: the markers were closed", who);
  return u->M;
}

/* Raises the core's message "space: ..." or "markers: ..." as "<who>: ...". */
static int raise (lua_State *L, int st, const lsys_error *e, const char *who) {
  const char *m = e->msg;
  if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (strncmp(m, "space: ", 7) == 0) m += 7;
  else if (strncmp(m, "markers: ", 9) == 0) m += 9;
  else if (strncmp(m, "field: ", 7) == 0) m += 7;
  return luaL_error(L, "%s: %s", who, m);
}

static int threadsof (int asked, int def) {
  if (asked < 0) asked = def;
  return asked > 0 ? asked : lsys_derive_default_threads();
}

/* ---------------------------------------------------------------------- */
/* lists */

/* Whether the table at i has a metatable (its reads may run Lua code). */
static int hasmeta (lua_State *L, int i) {
  if (!lua_getmetatable(L, i)) return 0;
  lua_pop(L, 1);
  return 1;
}

/* t[k] pushed: raw for a table without a metatable (the lists of a pass: no
** metamethod to run, and faster), else as Lua reads it. */
#define geti(L, t, k, raw) ((raw) ? lua_rawgeti(L, t, k) : lua_geti(L, t, k))

/* The flat list of points at i into a new block on the stack; *n triples. */
static double *readflat (lua_State *L, int i, const char *who, const char *what,
                         lua_Integer *n) {
  lua_Integer len, k;
  double *v;
  int raw;
  if (!lua_istable(L, i))
    luaL_error(L, "%s: %s must be a flat list {x1, y1, z1, x2, ...}, got %s", who, what,
               luaL_typename(L, i));
  raw = !hasmeta(L, i);
  len = raw ? (lua_Integer)lua_rawlen(L, i) : luaL_len(L, i);
  if (len < 0 || len % 3 != 0 || len / 3 > MAXPOINTS)
    luaL_error(L, "%s: %s must be a flat list {x1, y1, z1, x2, ...} of at most 2^28 points, "
               "got %I numbers", who, what, len);
  v = (double *)lua_newuserdatauv(L, len > 0 ? (size_t)len * sizeof(double) : 1, 0);
  for (k = 1; k <= len; k++) {
    int ok;
    double x;
    geti(L, i, k, raw);
    x = lua_tonumberx(L, -1, &ok);
    if (lua_type(L, -1) != LUA_TNUMBER || !isfinite(x))
      luaL_error(L, "%s: %s[%I] must be a finite number, got %s", who, what, k,
                 lua_type(L, -1) == LUA_TNUMBER ? "a non-finite number" : luaL_typename(L, -1));
    lua_pop(L, 1);
    v[k - 1] = x;
  }
  *n = len / 3;
  return v;
}

/* The list o[k] of n integers (ints) or numbers into a new block on the stack,
** or NULL (and a nil pushed) when absent. */
static void *readvalues (lua_State *L, const lsys_opts *o, const char *k, lua_Integer n,
                         int ints) {
  lua_Integer len, j;
  void *b;
  int t, raw;
  if (!lsysL_optfield(L, o, k, LUA_TTABLE, ints ? "a list of integers, one a point"
                                               : "a list of numbers, one a point")) {
    lua_pushnil(L);
    return NULL;
  }
  t = lua_gettop(L);
  raw = !hasmeta(L, t);
  len = raw ? (lua_Integer)lua_rawlen(L, t) : luaL_len(L, t);
  if (len != n)
    luaL_error(L, "%s%s%s has %I entries for %I points", o->pre, k, o->post, len, n);
  b = lua_newuserdatauv(L, n > 0 ? (size_t)n * 8 : 1, 0);
  for (j = 1; j <= n; j++) {
    int ok;
    geti(L, t, j, raw);
    if (ints) {
      lua_Integer x = lua_tointegerx(L, -1, &ok);
      if (!ok || lua_type(L, -1) != LUA_TNUMBER)
        luaL_error(L, "%s%s%s[%I] must be an integer, got %s", o->pre, k, o->post, j,
                   lua_type(L, -1) == LUA_TNUMBER ? "a number with a fraction"
                                                  : luaL_typename(L, -1));
      ((int64_t *)b)[j - 1] = (int64_t)x;
    } else {
      double x = lua_tonumberx(L, -1, &ok);
      if (lua_type(L, -1) != LUA_TNUMBER)
        luaL_error(L, "%s%s%s[%I] must be a number, got %s", o->pre, k, o->post, j,
                   luaL_typename(L, -1));
      ((double *)b)[j - 1] = x;
    }
    lua_pop(L, 1);
  }
  lua_remove(L, t);
  return b;
}

/* Pushes the list of the n numbers v (integers when ints). */
static void pushlist (lua_State *L, const double *v, lua_Integer n, int ints) {
  lua_Integer k;
  lua_createtable(L, n > INT32_MAX ? 0 : (int)n, 0);
  for (k = 0; k < n; k++) {
    if (ints) lua_pushinteger(L, (lua_Integer)v[k]);
    else lua_pushnumber(L, v[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

static void checkopts (lua_State *L, lsys_opts *op, const char *const names[], const char *who,
                       const char *known) {
  if (lsysL_optunknown(L, op, names))
    luaL_error(L, "%s: unknown option '%s' (known: %s)", who, luaL_tolstring(L, -1, NULL),
               known);
}

/* ---------------------------------------------------------------------- */
/* lsys.Space */

/* core.space(points, opts) */
static int l_space (lua_State *L) {
  static const char *const names[] = {"radius", "groups", "vigour", "scene", "threads",
                                      "max_memory", NULL};
  static const char *who = "core.space";
  lsys_opts op = {2, "core.space: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_meter mt = {0, 0, 0, NULL};
  lsys_space_opts o;
  lsys_error e;
  lua_Integer n;
  const double *pts;
  lspace *u;
  int threads, st, scene = 0;
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  checkopts(L, &op, names, who, "radius, groups, vigour, scene, threads, max_memory");
  memset(&o, 0, sizeof o);
  if (!lsysL_optfield(L, &op, "radius", LUA_TNONE, NULL))
    return luaL_error(L, "core.space: opts.radius is required (a finite number > 0)");
  lua_pop(L, 1);
  o.radius = lsysL_optnum(L, &op, "radius", 0, 0, HUGE_VAL, "a finite number > 0");
  threads = lsysL_optint(L, &op, "threads", 0, 0, LSYS_SPACE_MAXTHREADS);
  mt.limit = (size_t)lsysL_optnum(L, &op, "max_memory", (double)lsys_common_memory_limit(), 0,
                                  1.8e19, "a positive number of bytes");
  pts = readflat(L, 1, who, "points", &n);                          /* at 3 */
  o.groups = (const int64_t *)readvalues(L, &op, "groups", n, 1);   /* at 4 */
  o.vigour = (const double *)readvalues(L, &op, "vigour", n, 0);    /* at 5 */
  if (lsysL_optfield(L, &op, "scene", LUA_TNONE, NULL)) {           /* at 6 */
    lsysL_checkscene(L, 6);
    scene = 6;
  }
  o.meter = &mt;
  u = (lspace *)lua_newuserdatauv(L, sizeof *u, 0);
  u->S = NULL;
  u->threads = threads;
  luaL_setmetatable(L, SPACE_T);
  if (scene) o.scene = &lsysL_checkscene(L, scene)->sc;      /* again: the allocations ran */
  st = lsys_space_build(&u->S, pts, (size_t)n, &o, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 1;
}

/* A finite number option >= 0 and at most 'hi' (absent: def). */
static double optupto (lua_State *L, const lsys_opts *o, const char *k, double def, double hi,
                       const char *expect) {
  double x = lsysL_optnum(L, o, k, def, -HUGE_VAL, HUGE_VAL, expect);
  if (x < 0 || x > hi) {
    lua_getfield(L, o->t, k);
    lsysL_opterror(L, o, k, expect);
  }
  return x;
}

/* space:count/density/nearest/free([points] [, opts]) */
static int query (lua_State *L, int kind, const char *who) {
  static const char *const names[] = {"radius", "offset", "threads", NULL};
  static const char *const fnames[] = {"radius", "offset", "threads", "groups", "vigour", NULL};
  lsys_opts op = {0, NULL, "", LSYS_GOT_VALUE, 0};
  char pre[48];
  lsys_space_ask q;
  lsys_space_stats ss;
  lsys_error e;
  lua_Integer n = 0;
  lspace *u;
  double *out;
  int st, asked, isfree = kind == LSYS_SPACE_FREE;
  checkspace(L, 1, who);
  lua_settop(L, 3);
  snprintf(pre, sizeof pre, "%s: opts.", who);
  op.pre = pre;
  if (!lua_isnil(L, 2) && !lua_istable(L, 2))
    return luaL_error(L, "%s: the points must be a flat list {x1, y1, z1, ...} or nil (the "
                      "space's own), got %s", who, luaL_typename(L, 2));
  if (!lua_isnil(L, 3)) {
    luaL_checktype(L, 3, LUA_TTABLE);
    op.t = 3;
    checkopts(L, &op, isfree ? fnames : names, who, isfree ? "radius, offset, threads, "
              "groups, vigour" : "radius, offset, threads");
  }
  memset(&q, 0, sizeof q);
  q.kind = kind;
  q.radius = lsysL_optnum(L, &op, "radius", 0, 0, HUGE_VAL, "a finite number > 0");
  q.offset = optupto(L, &op, "offset", 0, HUGE_VAL, "a finite number >= 0");
  asked = lsysL_optint(L, &op, "threads", -1, 0, LSYS_SPACE_MAXTHREADS);
  if (lua_isnil(L, 2)) {
    if (isfree && op.t != 0 && (lua_getfield(L, 3, "groups") != LUA_TNIL ||
                                lua_getfield(L, 3, "vigour") != LUA_TNIL))
      return luaL_error(L, "%s: opts.groups and opts.vigour are for query points (the "
                        "space's own points have theirs)", who);
    lua_settop(L, 3);
    lua_pushnil(L);                                                  /* at 4 */
    lsys_space_info(checkspace(L, 1, who), &ss);
    n = (lua_Integer)ss.listed;
  } else {
    q.points = readflat(L, 2, who, "points", &n);                    /* at 4 */
    q.n = (size_t)n;
    if (isfree) {
      q.groups = (const int64_t *)readvalues(L, &op, "groups", n, 1);
      q.vigour = (const double *)readvalues(L, &op, "vigour", n, 0);
    }
  }
  out = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  checkspace(L, 1, who);                               /* again: Lua code ran since */
  u = (lspace *)lua_touserdata(L, 1);
  q.threads = threadsof(asked, u->threads);
  st = lsys_space_query(u->S, &q, out, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  pushlist(L, out, n, kind == LSYS_SPACE_COUNT || isfree);
  return 1;
}

static int space_count (lua_State *L) { return query(L, LSYS_SPACE_COUNT, "space:count"); }
static int space_density (lua_State *L) { return query(L, LSYS_SPACE_DENSITY, "space:density"); }
static int space_nearest (lua_State *L) { return query(L, LSYS_SPACE_NEAREST, "space:nearest"); }
static int space_free (lua_State *L) { return query(L, LSYS_SPACE_FREE, "space:free"); }

/* space:stats() -> table */
static int space_stats (lua_State *L) {
  lsys_space_stats s;
  lsys_space_info(checkspace(L, 1, "space:stats"), &s);
  lua_createtable(L, 0, 6);
  lua_pushinteger(L, (lua_Integer)s.points); lua_setfield(L, -2, "points");
  lua_pushinteger(L, (lua_Integer)s.listed); lua_setfield(L, -2, "listed");
  lua_pushinteger(L, (lua_Integer)s.cells); lua_setfield(L, -2, "cells");
  lua_pushinteger(L, (lua_Integer)s.buckets); lua_setfield(L, -2, "buckets");
  lua_pushinteger(L, (lua_Integer)s.bytes); lua_setfield(L, -2, "bytes");
  lua_pushnumber(L, s.radius); lua_setfield(L, -2, "radius");
  return 1;
}

static int space_len (lua_State *L) {
  lsys_space_stats s;
  lsys_space_info(checkspace(L, 1, "space:__len"), &s);
  lua_pushinteger(L, (lua_Integer)s.points);
  return 1;
}

/* space:close(), __close, __gc: idempotent */
static int space_close (lua_State *L) {
  lspace *u = (lspace *)luaL_checkudata(L, 1, SPACE_T);
  lsys_space *S = u->S;
  u->S = NULL;
  lsys_space_free(S);
  return 0;
}

static int space_tostring (lua_State *L) {
  lspace *u = (lspace *)luaL_checkudata(L, 1, SPACE_T);
  lsys_space_stats s;
  if (u->S == NULL) {
    lua_pushliteral(L, SPACE_T " (closed)");
    return 1;
  }
  lsys_space_info(u->S, &s);
  lua_pushfstring(L, SPACE_T ": %I points in %I cells of %f", (lua_Integer)s.points,
                  (lua_Integer)s.cells, s.radius);
  return 1;
}

/* ---------------------------------------------------------------------- */
/* lsys.Markers */

/* core.markers(points [, opts]) */
static int l_markers (lua_State *L) {
  static const char *const names[] = {"threads", "max_memory", NULL};
  static const char *who = "core.markers";
  lsys_opts op = {2, "core.markers: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_error e;
  lua_Integer n;
  const double *pts;
  lmarkers *u;
  int threads, st;
  size_t limit;
  if (lua_isnoneornil(L, 2)) op.t = 0;
  else luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  checkopts(L, &op, names, who, "threads, max_memory");
  threads = lsysL_optint(L, &op, "threads", 0, 0, LSYS_SPACE_MAXTHREADS);
  limit = (size_t)lsysL_optnum(L, &op, "max_memory", (double)lsys_common_memory_limit(), 0,
                               1.8e19, "a positive number of bytes");
  pts = readflat(L, 1, who, "points", &n);
  u = (lmarkers *)lua_newuserdatauv(L, sizeof *u, 0);
  u->M = NULL;
  u->mt.limit = limit;
  u->mt.used = 0;
  u->mt.hit = 0;
  u->mt.lock = NULL;
  u->threads = threads;
  luaL_setmetatable(L, MARKERS_T);
  st = lsys_space_markers_new(&u->M, pts, (size_t)n, &u->mt, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 1;
}

/* markers:perceive(buds, headings, opts) -> counts, directions */
static int markers_perceive (lua_State *L) {
  static const char *const names[] = {"perception", "angle", "kill", "threads", NULL};
  static const char *who = "markers:perceive";
  lsys_opts op = {4, "markers:perceive: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_markers_opts o;
  lsys_error e;
  lua_Integer nb, nh, k;
  const double *buds, *heads;
  size_t *cnt;
  double *dir;
  lmarkers *u;
  int st, asked;
  checkmarkers(L, 1, who);
  luaL_checktype(L, 4, LUA_TTABLE);
  lua_settop(L, 4);
  checkopts(L, &op, names, who, "perception, angle, kill, threads");
  if (!lsysL_optfield(L, &op, "perception", LUA_TNONE, NULL))
    return luaL_error(L, "%s: opts.perception is required (a finite number > 0)", who);
  lua_pop(L, 1);
  o.perception = lsysL_optnum(L, &op, "perception", 0, 0, HUGE_VAL, "a finite number > 0");
  o.angle = optupto(L, &op, "angle", 90, 180, "a number of degrees in (0, 180]");
  if (o.angle == 0) {
    lua_getfield(L, 4, "angle");
    lsysL_opterror(L, &op, "angle", "a number of degrees in (0, 180]");
  }
  o.kill = optupto(L, &op, "kill", 0, HUGE_VAL, "a finite number >= 0");
  asked = lsysL_optint(L, &op, "threads", -1, 0, LSYS_SPACE_MAXTHREADS);
  buds = readflat(L, 2, who, "buds", &nb);                             /* at 5 */
  heads = readflat(L, 3, who, "headings", &nh);                        /* at 6 */
  if (nh != nb) return luaL_error(L, "%s: %I headings for %I buds", who, nh, nb);
  cnt = (size_t *)lua_newuserdatauv(L, nb > 0 ? (size_t)nb * sizeof(size_t) : 1, 0);
  dir = (double *)lua_newuserdatauv(L, nb > 0 ? (size_t)nb * 3 * sizeof(double) : 1, 0);
  checkmarkers(L, 1, who);                             /* again: Lua code ran since */
  u = (lmarkers *)lua_touserdata(L, 1);
  o.threads = threadsof(asked, u->threads);
  st = lsys_space_markers_perceive(u->M, buds, heads, (size_t)nb, &o, cnt, dir, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  lua_createtable(L, nb > INT32_MAX ? 0 : (int)nb, 0);
  for (k = 0; k < nb; k++) {
    lua_pushinteger(L, (lua_Integer)cnt[k]);
    lua_rawseti(L, -2, k + 1);
  }
  pushlist(L, dir, 3 * nb, 0);
  return 2;
}

/* markers:remove(points, radius [, opts]) -> removed */
static int markers_remove (lua_State *L) {
  static const char *const names[] = {"threads", NULL};
  static const char *who = "markers:remove";
  lsys_opts op = {0, "markers:remove: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_error e;
  lua_Integer n;
  const double *pts;
  double r;
  size_t removed;
  lmarkers *u;
  int st, asked;
  checkmarkers(L, 1, who);
  r = luaL_checknumber(L, 3);
  luaL_argcheck(L, r > 0 && isfinite(r), 3, "a finite radius > 0 expected");
  lua_settop(L, 4);
  if (!lua_isnil(L, 4)) {
    luaL_checktype(L, 4, LUA_TTABLE);
    op.t = 4;
    checkopts(L, &op, names, who, "threads");
  }
  asked = lsysL_optint(L, &op, "threads", -1, 0, LSYS_SPACE_MAXTHREADS);
  pts = readflat(L, 2, who, "points", &n);
  checkmarkers(L, 1, who);                             /* again: Lua code ran since */
  u = (lmarkers *)lua_touserdata(L, 1);
  st = lsys_space_markers_remove(u->M, pts, (size_t)n, r, threadsof(asked, u->threads),
                                 &removed, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  lua_pushinteger(L, (lua_Integer)removed);
  return 1;
}

static int markers_count (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsys_space_markers_count(checkmarkers(L, 1, "markers:count")));
  return 1;
}

static int markers_len (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsys_space_markers_count(checkmarkers(L, 1, "markers:__len")));
  return 1;
}

/* markers:points() -> flat list */
static int markers_points (lua_State *L) {
  static const char *who = "markers:points";
  size_t n = lsys_space_markers_count(checkmarkers(L, 1, who));
  double *c = (double *)lua_newuserdatauv(L, n > 0 ? 3 * n * sizeof(double) : 1, 0);
  lsys_markers *M = checkmarkers(L, 1, who);           /* again: the allocation may close it */
  n = lsys_space_markers_count(M);                           /* and it cannot have grown */
  if (n > 0) memcpy(c, lsys_space_markers_points(M), 3 * n * sizeof(double));
  pushlist(L, c, (lua_Integer)(3 * n), 0);
  return 1;
}

/* markers:close(), __close, __gc: idempotent */
static int markers_close (lua_State *L) {
  lmarkers *u = (lmarkers *)luaL_checkudata(L, 1, MARKERS_T);
  lsys_markers *M = u->M;
  u->M = NULL;
  lsys_space_markers_free(M);
  return 0;
}

static int markers_tostring (lua_State *L) {
  lmarkers *u = (lmarkers *)luaL_checkudata(L, 1, MARKERS_T);
  if (u->M == NULL) lua_pushliteral(L, MARKERS_T " (closed)");
  else lua_pushfstring(L, MARKERS_T ": %I markers", (lua_Integer)lsys_space_markers_count(u->M));
  return 1;
}

/* ---------------------------------------------------------------------- */
/* lsys.Field */

static lsys_field *checkfield (lua_State *L, int i, const char *who) {
  lfield *u = (lfield *)luaL_checkudata(L, i, FIELD_T);
  if (u->F == NULL) luaL_error(L, "%s: the field was closed", who);
  return u->F;
}

/* opts[k] = {x, y, z} into v. */
static void optvec3 (lua_State *L, const lsys_opts *o, const char *k, double v[3]) {
  static const char *expect = "a list {x, y, z} of finite numbers";
  int a, ok;
  if (!lsysL_optfield(L, o, k, LUA_TTABLE, expect))
    luaL_error(L, "%s%s%s is required (%s)", o->pre, k, o->post, expect);
  if (luaL_len(L, -1) != 3) lsysL_opterror(L, o, k, expect);
  for (a = 0; a < 3; a++) {
    lua_geti(L, -1, a + 1);
    v[a] = lua_tonumberx(L, -1, &ok);
    if (lua_type(L, -1) != LUA_TNUMBER || !isfinite(v[a])) {
      lua_pop(L, 1);
      lsysL_opterror(L, o, k, expect);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* core.field(opts) */
static int l_field (lua_State *L) {
  static const char *const names[] = {"lo", "hi", "cell", "threads", "max_memory", NULL};
  static const char *who = "core.field";
  lsys_opts op = {1, "core.field: opts.", "", LSYS_GOT_VALUE, 0};
  double lo[3], hi[3], cell;
  lsys_error e;
  lfield *u;
  int threads, st;
  size_t limit;
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  checkopts(L, &op, names, who, "lo, hi, cell, threads, max_memory");
  optvec3(L, &op, "lo", lo);
  optvec3(L, &op, "hi", hi);
  if (!lsysL_optfield(L, &op, "cell", LUA_TNONE, NULL))
    return luaL_error(L, "core.field: opts.cell is required (a finite number > 0)");
  lua_pop(L, 1);
  cell = lsysL_optnum(L, &op, "cell", 1, 0, HUGE_VAL, "a finite number > 0");
  threads = lsysL_optint(L, &op, "threads", 0, 0, LSYS_SPACE_MAXTHREADS);
  limit = (size_t)lsysL_optnum(L, &op, "max_memory", (double)lsys_common_memory_limit(), 0,
                               1.8e19, "a positive number of bytes");
  u = (lfield *)lua_newuserdatauv(L, sizeof *u, 0);
  u->F = NULL;
  memset(&u->mt, 0, sizeof u->mt);
  u->mt.limit = limit;
  u->threads = threads;
  luaL_setmetatable(L, FIELD_T);
  st = lsys_space_field_new(&u->F, lo, hi, cell, &u->mt, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  return 1;
}

static int field_dims (lua_State *L) {
  size_t n[3];
  double h = lsys_space_field_dims(checkfield(L, 1, "field:dims"), n);
  lua_pushinteger(L, (lua_Integer)n[0]);
  lua_pushinteger(L, (lua_Integer)n[1]);
  lua_pushinteger(L, (lua_Integer)n[2]);
  lua_pushnumber(L, h);
  return 4;
}

static size_t cellsof (const lsys_field *F) {
  size_t n[3];
  lsys_space_field_dims(F, n);
  return n[0] * n[1] * n[2];
}

/* field:values() -> flat list */
static int field_values (lua_State *L) {
  static const char *who = "field:values";
  size_t n = cellsof(checkfield(L, 1, who));
  double *c = (double *)lua_newuserdatauv(L, n * sizeof(double), 0);
  lsys_field *F = checkfield(L, 1, who);               /* again: the allocation may close it */
  memcpy(c, lsys_space_field_values(F), n * sizeof(double));
  pushlist(L, c, (lua_Integer)n, 0);
  return 1;
}

/* field:set(values) */
static int field_set (lua_State *L) {
  static const char *who = "field:set";
  size_t n = cellsof(checkfield(L, 1, who)), k;
  lua_Integer len;
  double *v;
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 2);
  len = luaL_len(L, 2);
  if (len < 0 || (size_t)len != n)
    return luaL_error(L, "%s: %I values for %I cells", who, len, (lua_Integer)n);
  v = (double *)lua_newuserdatauv(L, n * sizeof(double), 0);
  for (k = 0; k < n; k++) {
    int ok;
    lua_geti(L, 2, (lua_Integer)k + 1);
    v[k] = lua_tonumberx(L, -1, &ok);
    if (lua_type(L, -1) != LUA_TNUMBER || !isfinite(v[k]) || v[k] < 0)
      return luaL_error(L, "%s: values[%I] must be a finite number >= 0", who,
                        (lua_Integer)k + 1);
    lua_pop(L, 1);
  }
  memcpy(lsys_space_field_values(checkfield(L, 1, who)), v, n * sizeof(double));
  return 0;
}

/* field:fill(v) */
static int field_fill (lua_State *L) {
  lsys_field *F = checkfield(L, 1, "field:fill");
  double x = luaL_checknumber(L, 2), *q = lsys_space_field_values(F);
  size_t k, n = cellsof(F);
  luaL_argcheck(L, isfinite(x) && x >= 0, 2, "a finite amount >= 0 expected");
  for (k = 0; k < n; k++) q[k] = x;
  return 0;
}

/* The points at 2 and, with 'values', the list at 3 of as many numbers: blocks at 4, 5. */
static lua_Integer readpv (lua_State *L, const char *who, const char *what, int values,
                           const double **pts, const double **v) {
  lua_Integer n, k;
  double *b;
  *pts = readflat(L, 2, who, "points", &n);                           /* at 4 */
  *v = NULL;
  if (!values) return n;
  luaL_checktype(L, 3, LUA_TTABLE);
  if (luaL_len(L, 3) != n)
    luaL_error(L, "%s: %I %s for %I points", who, luaL_len(L, 3), what, n);
  b = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);   /* at 5 */
  for (k = 1; k <= n; k++) {
    int ok;
    lua_geti(L, 3, k);
    b[k - 1] = lua_tonumberx(L, -1, &ok);
    if (lua_type(L, -1) != LUA_TNUMBER)
      luaL_error(L, "%s: %s[%I] must be a number, got %s", who, what, k, luaL_typename(L, -1));
    lua_pop(L, 1);
  }
  *v = b;
  return n;
}

/* field:at(points) -> amounts */
static int field_at (lua_State *L) {
  static const char *who = "field:at";
  const double *pts, *none, *q;
  lua_Integer n, k;
  double *out;
  lsys_field *F;
  checkfield(L, 1, who);
  lua_settop(L, 3);
  n = readpv(L, who, NULL, 0, &pts, &none);
  out = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  F = checkfield(L, 1, who);                           /* again: Lua code ran since */
  q = lsys_space_field_values(F);
  for (k = 0; k < n; k++) {
    long long c = lsys_space_field_cell(F, pts + 3 * k);
    out[k] = c >= 0 ? q[c] : 0;
  }
  pushlist(L, out, n, 0);
  return 1;
}

/* field:add(points, amounts) -> inside */
static int field_add (lua_State *L) {
  static const char *who = "field:add";
  const double *pts, *v;
  lua_Integer n;
  long long in;
  lsys_error e;
  checkfield(L, 1, who);
  lua_settop(L, 3);
  n = readpv(L, who, "amounts", 1, &pts, &v);
  in = lsys_space_field_add(checkfield(L, 1, who), pts, v, (size_t)n, &e);
  if (in < 0) return raise(L, LSYS_EARG, &e, who);
  lua_pushinteger(L, (lua_Integer)in);
  return 1;
}

/* field:take(points, wants) -> got */
static int field_take (lua_State *L) {
  static const char *who = "field:take";
  const double *pts, *v;
  lua_Integer n;
  lsys_error e;
  double *got;
  int st;
  checkfield(L, 1, who);
  lua_settop(L, 3);
  n = readpv(L, who, "wants", 1, &pts, &v);
  got = (double *)lua_newuserdatauv(L, n > 0 ? (size_t)n * sizeof(double) : 1, 0);
  st = lsys_space_field_take(checkfield(L, 1, who), pts, v, (size_t)n, got, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  pushlist(L, got, n, 0);
  return 1;
}

/* field:diffuse(D, t [, opts]) -> substeps */
static int field_diffuse (lua_State *L) {
  static const char *const names[] = {"threads", NULL};
  static const char *who = "field:diffuse";
  lsys_opts op = {0, "field:diffuse: opts.", "", LSYS_GOT_VALUE, 0};
  double D, t;
  long m;
  lsys_error e;
  lfield *u;
  int asked, st;
  checkfield(L, 1, who);
  D = luaL_checknumber(L, 2);
  t = luaL_checknumber(L, 3);
  lua_settop(L, 4);
  if (!lua_isnil(L, 4)) {
    luaL_checktype(L, 4, LUA_TTABLE);
    op.t = 4;
    checkopts(L, &op, names, who, "threads");
  }
  asked = lsysL_optint(L, &op, "threads", -1, 0, LSYS_SPACE_MAXTHREADS);
  checkfield(L, 1, who);                               /* again: Lua code ran since */
  u = (lfield *)lua_touserdata(L, 1);
  st = lsys_space_field_diffuse(u->F, D, t, threadsof(asked, u->threads), &m, &e);
  if (st != LSYS_OK) return raise(L, st, &e, who);
  lua_pushinteger(L, (lua_Integer)m);
  return 1;
}

/* field:gradient(points) -> flat list */
static int field_gradient (lua_State *L) {
  static const char *who = "field:gradient";
  const double *pts, *none;
  lua_Integer n, k;
  double *out;
  lsys_field *F;
  checkfield(L, 1, who);
  lua_settop(L, 3);
  n = readpv(L, who, NULL, 0, &pts, &none);
  out = (double *)lua_newuserdatauv(L, n > 0 ? 3 * (size_t)n * sizeof(double) : 1, 0);
  F = checkfield(L, 1, who);
  for (k = 0; k < n; k++) lsys_space_field_gradient(F, pts + 3 * k, out + 3 * k);
  pushlist(L, out, 3 * n, 0);
  return 1;
}

static int field_total (lua_State *L) {
  lua_pushnumber(L, lsys_space_field_total(checkfield(L, 1, "field:total")));
  return 1;
}

/* field:close(), __close, __gc: idempotent */
static int field_close (lua_State *L) {
  lfield *u = (lfield *)luaL_checkudata(L, 1, FIELD_T);
  lsys_field *F = u->F;
  u->F = NULL;
  lsys_space_field_free(F);
  return 0;
}

static int field_tostring (lua_State *L) {
  lfield *u = (lfield *)luaL_checkudata(L, 1, FIELD_T);
  size_t n[3];
  if (u->F == NULL) lua_pushliteral(L, FIELD_T " (closed)");
  else {
    double h = lsys_space_field_dims(u->F, n);
    lua_pushfstring(L, FIELD_T ": %I x %I x %I cells of %f", (lua_Integer)n[0],
                    (lua_Integer)n[1], (lua_Integer)n[2], h);
  }
  return 1;
}

/* ---------------------------------------------------------------------- */

static const luaL_Reg space_meta[] = {
  {"__index", NULL}, {"__gc", space_close}, {"__close", space_close},
  {"__len", space_len}, {"__tostring", space_tostring}, {NULL, NULL}
};
static const luaL_Reg space_methods[] = {
  {"count", space_count}, {"density", space_density}, {"nearest", space_nearest},
  {"free", space_free}, {"stats", space_stats}, {"close", space_close}, {NULL, NULL}
};
static const luaL_Reg markers_meta[] = {
  {"__index", NULL}, {"__gc", markers_close}, {"__close", markers_close},
  {"__len", markers_len}, {"__tostring", markers_tostring}, {NULL, NULL}
};
static const luaL_Reg markers_methods[] = {
  {"perceive", markers_perceive}, {"remove", markers_remove}, {"count", markers_count},
  {"points", markers_points}, {"close", markers_close}, {NULL, NULL}
};
static const luaL_Reg field_meta[] = {
  {"__index", NULL}, {"__gc", field_close}, {"__close", field_close},
  {"__tostring", field_tostring}, {NULL, NULL}
};
static const luaL_Reg field_methods[] = {
  {"dims", field_dims}, {"values", field_values}, {"set", field_set}, {"fill", field_fill},
  {"at", field_at}, {"add", field_add}, {"take", field_take}, {"diffuse", field_diffuse},
  {"gradient", field_gradient}, {"total", field_total}, {"close", field_close}, {NULL, NULL}
};
static const luaL_Reg space_funcs[] = {
  {"space", l_space}, {"markers", l_markers}, {"field", l_field}, {NULL, NULL}
};

void lsysL_open_space (lua_State *L) {
  lsysL_createmeta(L, SPACE_T, space_meta, space_methods);
  lsysL_createmeta(L, MARKERS_T, markers_meta, markers_methods);
  lsysL_createmeta(L, FIELD_T, field_meta, field_methods);
  luaL_setfuncs(L, space_funcs, 0);
}
