/*
** Lua binding of csrc/core/bspline.h: the lsys.BSpline userdata and the
** polyline functions of stroke capture (Anastacio et al. 2009, §3.1).
**
**   core.bspline(points [, {degree = 2|3, clamped = bool}]) -> BSpline
**       points = { {x, y}, ... } or { {x, y, z}, ... }; degree 3, uniform
**   c:eval(t)  c:deriv(t [, k])  c:length([t0, t1])  c:at_length(s)
**   c:sample(n)  c:sample_length(n)  c:ray(ox, oy, dx, dy)  c:intersect(d)
**   c:closest(x, y [, z])  c:points()  c:dim()  c:degree()  c:clamped()
**   #c  tostring(c)
**   core.bspline_resample(points, spacing) -> points
**   core.chaikin(points [, steps])  core.chaikin_reverse(points [, steps])
**   core.stroke_curve(points [, {spacing = 1, steps = 3, degree = 2}])
**
** A BSpline owns a copy of its control points and is immutable; __close
** frees it early, after which its methods raise. docs/sketch.md documents
** the API.
*/
#include <math.h>
#include <string.h>

#include "bspline.h"
#include "lua_aux.h"
#include "lua_lsys.h"

#define BSPLINE_T "lsys.BSpline"
#define MAXSTEPS 30            /* steps of chaikin / chaikin_reverse / stroke_curve */

static lsys_bspline *checkbspline (lua_State *L, int i, const char *who) {
  lsys_bspline *c = (lsys_bspline *)luaL_checkudata(L, i, BSPLINE_T);
  if (c->pt == NULL) luaL_error(L, "%s: the curve was closed", who);
  return c;
}

static int bspline_gc (lua_State *L) {       /* also __close: idempotent */
  lsys_bspline_free((lsys_bspline *)luaL_checkudata(L, 1, BSPLINE_T));
  return 0;
}

/*
** Reads the list of points at 'arg' (all of 2 or all of 3 numbers) into a
** scratch block owned by Lua (pushed on the stack); at least 'min' points.
** Messages begin with 'who'.
*/
static double *readpoints (lua_State *L, int arg, const char *who, lua_Integer min,
                           size_t *np, int *dimp) {
  lua_Integer n, i;
  int dim = 0, k;
  double *pt = NULL;
  luaL_checktype(L, arg, LUA_TTABLE);
  n = luaL_len(L, arg);
  if (n < min)
    luaL_error(L, "%s: at least %I points needed, got %I", who, min, n);
  if (n > LSYS_BSPLINE_MAXPOINTS)
    luaL_error(L, "%s: too many points (limit is %d)", who, LSYS_BSPLINE_MAXPOINTS);
  for (i = 1; i <= n; i++) {
    int d = lua_geti(L, arg, i) == LUA_TTABLE ? (int)lua_rawlen(L, -1) : 0;
    if (d != 2 && d != 3) luaL_error(L, "%s: point %I is not a table of 2 or 3 numbers", who, i);
    if (dim == 0) {
      dim = d;
      pt = (double *)lua_newuserdatauv(L, (size_t)n * (size_t)dim * sizeof *pt, 0);
      lua_insert(L, -2);
    }
    if (d != dim)
      luaL_error(L, "%s: point %I has %d coordinates, point 1 has %d", who, i, d, dim);
    for (k = 0; k < dim; k++) {
      double v;
      if (lua_rawgeti(L, -1, k + 1) != LUA_TNUMBER)
        luaL_error(L, "%s: point %I is not a table of 2 or 3 numbers", who, i);
      v = lua_tonumber(L, -1);
      if (!isfinite(v)) luaL_error(L, "%s: point %I: coordinate %d is not finite", who, i, k + 1);
      pt[(size_t)(i - 1) * (size_t)dim + (size_t)k] = v;
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  if (dim == 0) {                        /* no points (min was 0) */
    dim = 2;
    pt = (double *)lua_newuserdatauv(L, 1, 0);
  }
  *np = (size_t)n;
  *dimp = dim;
  return pt;
}

/* Pushes a list of n points of 'dim' numbers; with 't', each also gets t. */
static void pushpoints (lua_State *L, const double *pt, size_t n, int dim, const double *t) {
  size_t i;
  int k;
  lua_createtable(L, n > (size_t)INT32_MAX ? INT32_MAX : (int)n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, dim, t != NULL);
    for (k = 0; k < dim; k++) {
      lua_pushnumber(L, pt[i * (size_t)dim + (size_t)k]);
      lua_rawseti(L, -2, k + 1);
    }
    if (t != NULL) {
      lua_pushnumber(L, t[i]);
      lua_setfield(L, -2, "t");
    }
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
}

/* core.bspline(points [, opts]) */
static int l_bspline (lua_State *L) {
  static const char *const names[] = { "degree", "clamped", NULL };
  lsys_opts o = { 0, "bspline: opts.", "", LSYS_GOT_VALUE, 0 };
  lsys_bspline *c;
  lsys_error e;
  size_t n;
  int dim, degree, clamped, st;
  double *pt;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    o.t = 2;
  }
  if (lsysL_optunknown(L, &o, names))
    return luaL_error(L, "bspline: unknown option '%s'", luaL_tolstring(L, -1, NULL));
  degree = lsysL_optint(L, &o, "degree", 3, 2, 3);
  clamped = lsysL_optbool(L, &o, "clamped", 0);
  lua_settop(L, 1);
  pt = readpoints(L, 1, "bspline", 0, &n, &dim);
  c = (lsys_bspline *)lua_newuserdatauv(L, sizeof *c, 0);
  lsys_bspline_init(c);
  luaL_setmetatable(L, BSPLINE_T);
  if ((st = lsys_bspline_set(c, pt, n, dim, degree, clamped, &e)) != LSYS_OK) {
    if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
    return luaL_error(L, "bspline: %s", e.msg);
  }
  return 1;
}

/* A parameter t at 'arg': a number, not NaN (clamped into [0, 1] later). */
static double checkt (lua_State *L, int arg) {
  double t = luaL_checknumber(L, arg);
  luaL_argcheck(L, t == t, arg, "t is NaN");
  return t;
}

static int pushvec (lua_State *L, const double *v, int dim) {
  int k;
  for (k = 0; k < dim; k++) lua_pushnumber(L, v[k]);
  return dim;
}

static int bspline_eval (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "eval");
  double p[3];
  lsys_bspline_eval(c, checkt(L, 2), 0, p);
  return pushvec(L, p, c->dim);
}

static int bspline_deriv (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "deriv");
  double t = checkt(L, 2), p[3];
  lua_Integer k = luaL_optinteger(L, 3, 1);
  luaL_argcheck(L, k == 1 || k == 2, 3, "must be 1 or 2");
  lsys_bspline_eval(c, t, (int)k, p);
  return pushvec(L, p, c->dim);
}

static int bspline_length (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "length");
  if (lua_isnoneornil(L, 2) && lua_isnoneornil(L, 3))
    lua_pushnumber(L, lsys_bspline_length(c));
  else
    lua_pushnumber(L, lsys_bspline_length_between(c, checkt(L, 2), checkt(L, 3)));
  return 1;
}

static int bspline_at_length (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "at_length");
  double s = luaL_checknumber(L, 2);
  luaL_argcheck(L, s == s, 2, "s is NaN");
  lua_pushnumber(L, lsys_bspline_at_length(c, s));
  return 1;
}

/* The count n at 'arg' of sample / sample_length. */
static size_t checkcount (lua_State *L, int arg) {
  lua_Integer m = luaL_checkinteger(L, arg);
  luaL_argcheck(L, m >= 2 && m <= LSYS_BSPLINE_MAXPOINTS, arg, "must be between 2 and 10000000");
  return (size_t)m;
}

/* The methods that allocate take the curve again after each allocation (a
** finalizer it runs may close the curve), and read it into memory of their
** own before they make the tables. */
static int bspline_sample (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "sample");
  size_t m = checkcount(L, 2);
  int dim = c->dim;
  double *out = (double *)lua_newuserdatauv(L, m * (size_t)dim * sizeof *out, 0);
  lsys_bspline_sample(checkbspline(L, 1, "sample"), m, out);
  pushpoints(L, out, m, dim, NULL);
  return 1;
}

static int bspline_sample_length (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "sample_length");
  size_t m = checkcount(L, 2);
  int dim = c->dim;
  double *out = (double *)lua_newuserdatauv(L, m * ((size_t)dim + 1) * sizeof *out, 0);
  lsys_bspline_sample_length(checkbspline(L, 1, "sample_length"), m, out, out + m * (size_t)dim);
  pushpoints(L, out, m, dim, out + m * (size_t)dim);
  return 1;
}

/* Pushes hits as { {t =, <second> =, x =, y =}, ... }. */
static void pushhits (lua_State *L, const lsys_bspline_hit *h, size_t n, const char *second) {
  size_t i;
  lua_createtable(L, (int)n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, 0, 4);
    lua_pushnumber(L, h[i].t);
    lua_setfield(L, -2, "t");
    lua_pushnumber(L, h[i].s);
    lua_setfield(L, -2, second);
    lua_pushnumber(L, h[i].x);
    lua_setfield(L, -2, "x");
    lua_pushnumber(L, h[i].y);
    lua_setfield(L, -2, "y");
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
}

static int bspline_ray (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "ray");
  double o[2], d[2];
  size_t cap = 16, n;
  lsys_bspline_hit *h;
  lsys_error e;
  int st, pass;
  o[0] = luaL_checknumber(L, 2), o[1] = luaL_checknumber(L, 3);
  d[0] = luaL_checknumber(L, 4), d[1] = luaL_checknumber(L, 5);
  for (pass = 0; pass < 2; pass++) {           /* again with room for all */
    h = (lsys_bspline_hit *)lua_newuserdatauv(L, cap * sizeof *h, 0);
    c = checkbspline(L, 1, "ray");
    if ((st = lsys_bspline_ray(c, o, d, h, cap, &n, &e)) != LSYS_OK) {
      if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
      return luaL_error(L, "ray: %s", e.msg);
    }
    if (n <= cap) break;
    cap = n;
  }
  pushhits(L, h, n, "s");
  return 1;
}

static int bspline_intersect (lua_State *L) {
  const lsys_bspline *a = checkbspline(L, 1, "intersect");
  const lsys_bspline *b = checkbspline(L, 2, "intersect");
  size_t cap = 16, n;
  lsys_bspline_hit *h;
  lsys_error e;
  int st, pass;
  for (pass = 0; pass < 2; pass++) {
    h = (lsys_bspline_hit *)lua_newuserdatauv(L, cap * sizeof *h, 0);
    a = checkbspline(L, 1, "intersect");
    b = checkbspline(L, 2, "intersect");
    if ((st = lsys_bspline_intersect(a, b, h, cap, &n, &e)) != LSYS_OK) {
      if (st == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
      return luaL_error(L, "intersect: %s", e.msg);
    }
    if (n <= cap) break;
    cap = n;
  }
  pushhits(L, h, n, "u");
  return 1;
}

static int bspline_closest (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "closest");
  double q[3], t, d;
  int k;
  for (k = 0; k < c->dim; k++) {
    q[k] = luaL_checknumber(L, k + 2);
    luaL_argcheck(L, isfinite(q[k]), k + 2, "must be finite");
  }
  lsys_bspline_closest(c, q, &t, &d);
  lua_pushnumber(L, t);
  lua_pushnumber(L, d);
  return 2;
}

static int bspline_points (lua_State *L) {
  const lsys_bspline *c = checkbspline(L, 1, "points");
  size_t n = c->n;
  int dim = c->dim;
  double *pt = (double *)lua_newuserdatauv(L, n * (size_t)dim * sizeof *pt + 1, 0);
  c = checkbspline(L, 1, "points");
  if (n > 0) memcpy(pt, c->pt, n * (size_t)dim * sizeof *pt);
  pushpoints(L, pt, n, dim, NULL);
  return 1;
}

static int bspline_dim (lua_State *L) {
  lua_pushinteger(L, checkbspline(L, 1, "dim")->dim);
  return 1;
}

static int bspline_degree (lua_State *L) {
  lua_pushinteger(L, checkbspline(L, 1, "degree")->degree);
  return 1;
}

static int bspline_clamped (lua_State *L) {
  lua_pushboolean(L, checkbspline(L, 1, "clamped")->clamped);
  return 1;
}

static int bspline_len (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)checkbspline(L, 1, "#")->n);
  return 1;
}

static int bspline_tostring (lua_State *L) {
  const lsys_bspline *c = (const lsys_bspline *)luaL_checkudata(L, 1, BSPLINE_T);
  if (c->pt == NULL) lua_pushliteral(L, BSPLINE_T " (closed)");
  else
    lua_pushfstring(L, BSPLINE_T "(%I points, %dD, degree %d, %s)", (lua_Integer)c->n, c->dim,
                    c->degree, c->clamped ? "clamped" : "uniform");
  return 1;
}

/* ---------------------------------------------------------------------- */
/* Polylines */

static int l_resample (lua_State *L) {
  size_t n, m;
  int dim, st;
  double spacing = luaL_checknumber(L, 2), *pt, *out;
  lsys_error e;
  lua_settop(L, 2);
  pt = readpoints(L, 1, "bspline_resample", 2, &n, &dim);
  if ((st = lsys_bspline_resample_count(pt, n, dim, spacing, &m, &e)) != LSYS_OK)
    return luaL_error(L, "bspline_resample: %s", e.msg);
  out = (double *)lua_newuserdatauv(L, m * (size_t)dim * sizeof *out, 0);
  lsys_bspline_resample(out, m, pt, n, dim);
  pushpoints(L, out, m, dim, NULL);
  return 1;
}

static int checksteps (lua_State *L, int arg) {
  lua_Integer s = luaL_optinteger(L, arg, 1);
  luaL_argcheck(L, s >= 0 && s <= MAXSTEPS, arg, "must be between 0 and 30");
  return (int)s;
}

static int l_chaikin (lua_State *L) {
  int steps = checksteps(L, 2), dim, k;
  size_t n;
  double *pt;
  lua_settop(L, 2);
  pt = readpoints(L, 1, "chaikin", 2, &n, &dim);
  for (k = 0; k < steps; k++) {
    double *out;
    if (n > LSYS_BSPLINE_MAXPOINTS / 2)
      return luaL_error(L, "chaikin: too many points (limit is %d)", LSYS_BSPLINE_MAXPOINTS);
    out = (double *)lua_newuserdatauv(L, 2 * n * (size_t)dim * sizeof *out, 0);
    lsys_bspline_chaikin(out, pt, n, dim);
    lua_replace(L, -2);                  /* drop the old block */
    pt = out;
    n *= 2;
  }
  pushpoints(L, pt, n, dim, NULL);
  return 1;
}

static int l_chaikin_reverse (lua_State *L) {
  int steps = checksteps(L, 2), dim, k;
  size_t n;
  double *pt;
  lua_settop(L, 2);
  pt = readpoints(L, 1, "chaikin_reverse", 2, &n, &dim);
  for (k = 0; k < steps && n >= 3; k++) n = lsys_bspline_chaikin_reverse(pt, pt, n, dim);
  pushpoints(L, pt, n, dim, NULL);
  return 1;
}

/* core.stroke_curve(points [, {spacing =, steps =, degree =}]) */
static int l_stroke_curve (lua_State *L) {
  static const char *const names[] = { "spacing", "steps", "degree", NULL };
  lsys_opts o = { 0, "stroke_curve: opts.", "", LSYS_GOT_VALUE, 0 };
  double spacing, *pt, *out;
  int steps, degree, dim, st;
  size_t n, cap, m;
  lsys_error e;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    o.t = 2;
  }
  if (lsysL_optunknown(L, &o, names))
    return luaL_error(L, "stroke_curve: unknown option '%s'", luaL_tolstring(L, -1, NULL));
  spacing = lsysL_optnum(L, &o, "spacing", 1.0, 0.0, HUGE_VAL, "a positive number");
  steps = lsysL_optint(L, &o, "steps", 3, 0, MAXSTEPS);
  degree = lsysL_optint(L, &o, "degree", 2, 2, 3);
  lua_settop(L, 2);
  pt = readpoints(L, 1, "stroke_curve", 2, &n, &dim);
  if ((st = lsys_bspline_stroke_size(pt, n, dim, spacing, degree, &cap, &e)) != LSYS_OK)
    return luaL_error(L, "stroke_curve: %s", e.msg);
  out = (double *)lua_newuserdatauv(L, cap * (size_t)dim * sizeof *out, 0);
  if ((st = lsys_bspline_stroke(out, cap, pt, n, dim, spacing, steps, degree, &m, &e))
      != LSYS_OK)
    return luaL_error(L, "stroke_curve: %s", e.msg);
  pushpoints(L, out, m, dim, NULL);
  return 1;
}

static const luaL_Reg bspline_methods[] = {
  {"eval", bspline_eval}, {"deriv", bspline_deriv}, {"length", bspline_length},
  {"at_length", bspline_at_length}, {"sample", bspline_sample},
  {"sample_length", bspline_sample_length}, {"ray", bspline_ray},
  {"intersect", bspline_intersect}, {"closest", bspline_closest}, {"points", bspline_points},
  {"dim", bspline_dim}, {"degree", bspline_degree}, {"clamped", bspline_clamped},
  {NULL, NULL}
};

static const luaL_Reg bspline_meta[] = {
  {"__index", NULL},  /* placeholder: set to the method table */
  {"__gc", bspline_gc}, {"__close", bspline_gc}, {"__len", bspline_len},
  {"__tostring", bspline_tostring}, {NULL, NULL}
};

static const luaL_Reg bspline_funcs[] = {
  {"bspline", l_bspline}, {"bspline_resample", l_resample}, {"chaikin", l_chaikin},
  {"chaikin_reverse", l_chaikin_reverse}, {"stroke_curve", l_stroke_curve}, {NULL, NULL}
};

void lsysL_open_bspline (lua_State *L) {
  lsysL_createmeta(L, BSPLINE_T, bspline_meta, bspline_methods);
  luaL_setfuncs(L, bspline_funcs, 0);
}
