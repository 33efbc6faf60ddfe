/*
** Lua binding of csrc/core/ffd.h: free-form deformations of a finished
** Scene (Lintermann and Deussen 1999, sidebar "FFD and Hyperpatch"), the
** lsys.Hyperpatch userdata and three Scene methods.
**
**   core.hyperpatch{degree = {dl, dm, dn} | n, origin = {x, y, z},
**                   size = {sx, sy, sz} | axes = {a, b, c}} -> Hyperpatch
**       defaults: degree 3, origin {0, 0, 0}, size {1, 1, 1}
**   hp:point(i, j, k) -> x, y, z        0-based lattice indices
**   hp:set(i, j, k, x, y, z)
**   hp:map(x, y, z) -> x', y', z'
**   hp:degree() -> dl, dm, dn           hp:count() -> control points
**
**   scene:deform(hp | f, opts) -> vertices moved
**       f(x, y, z) -> x', y', z'; opts {modules = {m0, m1}} (1-based,
**       inclusive, as records number them) or {vertices = {v0, v1}}
**       (1-based, inclusive); none: the whole scene with its lines
**   scene:transform(m, opts) -> vertices moved; m = 3 x 4 or 4 x 4 rows
**   scene:module_range(m0 [, m1]) -> v0, v1 (1-based, inclusive) or nil
**   scene:vertex(i) -> x, y, z, nx, ny, nz
**
** A Hyperpatch owns no heap memory; __close still ends it, as for every
** userdata of the module. A function's error or bad return leaves the scene
** as it was (the range is saved first and put back).
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "ffd.h"

#define HYPERPATCH_T "lsys.Hyperpatch"

typedef struct lhp {
  lsys_hyperpatch hp;
  int closed;
} lhp;

static lsys_hyperpatch *checkhp (lua_State *L, int i) {
  lhp *h = (lhp *)luaL_checkudata(L, i, HYPERPATCH_T);
  if (h->closed) luaL_error(L, "the hyperpatch was closed");
  return &h->hp;
}

static int hp_close (lua_State *L) {
  ((lhp *)luaL_checkudata(L, 1, HYPERPATCH_T))->closed = 1;
  return 0;
}

/* A finite number at stack index i; 'what' names it in the message. */
static double checkfinite (lua_State *L, int i, const char *who, const char *what) {
  int ok;
  double x = lua_tonumberx(L, i, &ok);
  if (!ok || !isfinite(x))
    luaL_error(L, "%s: %s must be a finite number, got %s", who, what,
               ok ? "a non-finite number" : luaL_typename(L, i));
  return x;
}

/* The list of 3 finite numbers in field k of the table at t (when present). */
static int readvec3 (lua_State *L, int t, const char *k, double v[3], const char *who) {
  int r;
  char what[48];
  if (lua_getfield(L, t, k) == LUA_TNIL) { lua_pop(L, 1); return 0; }
  if (!lua_istable(L, -1) || luaL_len(L, -1) != 3)
    luaL_error(L, "%s: '%s' must be a list of 3 numbers", who, k);
  for (r = 0; r < 3; r++) {
    lua_geti(L, -1, r + 1);
    snprintf(what, sizeof what, "'%s'[%d]", k, r + 1);
    v[r] = checkfinite(L, -1, who, what);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return 1;
}

/* A degree: an integer from 1 (linear) to 4 (quartic). */
static int readdegree (lua_State *L, int i, const char *what) {
  int ok;
  lua_Integer d = lua_tointegerx(L, i, &ok);
  if (!ok) luaL_error(L, "core.hyperpatch: %s must be an integer, got %s", what,
                      lua_type(L, i) == LUA_TNUMBER ? "a fraction" : luaL_typename(L, i));
  if (d < 1 || d > LSYS_HP_MAXDEG)
    luaL_error(L, "core.hyperpatch: %s is %I: degrees are 1 (linear) to 4 (quartic)", what, d);
  return (int)d;
}

/* core.hyperpatch{degree=, origin=, size=, axes=} */
static int l_hyperpatch (lua_State *L) {
  static const char *const names[] = {"degree", "origin", "size", "axes", NULL};
  static const char *who = "core.hyperpatch";
  lsys_opts o = {1, "", "", LSYS_GOT_NONE, 0};
  int deg[3] = {3, 3, 3}, r;
  double origin[3] = {0, 0, 0}, size[3] = {1, 1, 1}, axes[3][3] = {{0}};
  lsys_error e;
  lhp *h;
  if (lua_isnoneornil(L, 1)) {
    lua_settop(L, 0);
    lua_newtable(L);
  }
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  if (lsysL_optunknown(L, &o, names))
    return luaL_error(L, "%s: unknown option %s (known: degree, origin, size, axes)", who,
                      luaL_tolstring(L, -1, NULL));
  lua_getfield(L, 1, "degree");
  if (lua_istable(L, -1)) {
    if (luaL_len(L, -1) != 3) return luaL_error(L, "%s: 'degree' must be n or {dl, dm, dn}", who);
    for (r = 0; r < 3; r++) {
      char what[32];
      snprintf(what, sizeof what, "'degree'[%d]", r + 1);
      lua_geti(L, 2, r + 1);
      deg[r] = readdegree(L, -1, what);
      lua_pop(L, 1);
    }
  } else if (!lua_isnil(L, -1)) deg[0] = deg[1] = deg[2] = readdegree(L, -1, "'degree'");
  lua_pop(L, 1);
  readvec3(L, 1, "origin", origin, who);
  if (readvec3(L, 1, "size", size, who)) {
    lua_getfield(L, 1, "axes");
    if (!lua_isnil(L, -1)) return luaL_error(L, "%s: give 'size' or 'axes', not both", who);
    lua_pop(L, 1);
  }
  for (r = 0; r < 3; r++) axes[r][r] = size[r];
  if (lua_getfield(L, 1, "axes") != LUA_TNIL) {
    static const char *const ax[3] = {"axes[1]", "axes[2]", "axes[3]"};
    if (!lua_istable(L, -1) || luaL_len(L, -1) != 3)
      return luaL_error(L, "%s: 'axes' must be a list of 3 vectors {x, y, z}", who);
    lua_newtable(L);                          /* axes[r] under a name readvec3 can show */
    for (r = 0; r < 3; r++) {
      lua_geti(L, -2, r + 1);
      lua_setfield(L, -2, ax[r]);
      readvec3(L, lua_gettop(L), ax[r], axes[r], who);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  h = (lhp *)lua_newuserdatauv(L, sizeof *h, 0);
  h->closed = 0;
  luaL_setmetatable(L, HYPERPATCH_T);
  memset(&e, 0, sizeof e);
  if (lsys_ffd_hyperpatch_init(&h->hp, deg, origin, axes, &e) != LSYS_OK)
    return luaL_error(L, "%s: %s", who, e.msg);
  return 1;
}

/* The control point of indices (i, j, k) at stack index 2. */
static double *checkpoint (lua_State *L, lsys_hyperpatch *hp, const char *who) {
  lua_Integer i = luaL_checkinteger(L, 2), j = luaL_checkinteger(L, 3),
              k = luaL_checkinteger(L, 4);
  double *P = NULL;
  if (i >= 0 && i <= 4 && j >= 0 && j <= 4 && k >= 0 && k <= 4)
    P = lsys_ffd_hyperpatch_point(hp, (int)i, (int)j, (int)k);
  if (P == NULL)
    luaL_error(L, "%s: no control point (%I, %I, %I): indices are 0..%d, 0..%d, 0..%d", who, i,
               j, k, hp->deg[0], hp->deg[1], hp->deg[2]);
  return P;
}

static int hp_point (lua_State *L) {
  double *P = checkpoint(L, checkhp(L, 1), "hyperpatch:point");
  lua_pushnumber(L, P[0]); lua_pushnumber(L, P[1]); lua_pushnumber(L, P[2]);
  return 3;
}

static int hp_set (lua_State *L) {
  double *P = checkpoint(L, checkhp(L, 1), "hyperpatch:set"), q[3];
  static const char *const what[3] = {"x", "y", "z"};
  int r;
  for (r = 0; r < 3; r++) q[r] = checkfinite(L, 5 + r, "hyperpatch:set", what[r]);
  memcpy(P, q, sizeof q);
  return 0;
}

static int hp_map (lua_State *L) {
  lsys_hyperpatch *hp = checkhp(L, 1);
  static const char *const what[3] = {"x", "y", "z"};
  double p[3], q[3];
  int r;
  for (r = 0; r < 3; r++) p[r] = checkfinite(L, 2 + r, "hyperpatch:map", what[r]);
  lsys_ffd_hyperpatch_eval(hp, p, q, NULL);
  for (r = 0; r < 3; r++) lua_pushnumber(L, q[r]);
  return 3;
}

static int hp_degree (lua_State *L) {
  lsys_hyperpatch *hp = checkhp(L, 1);
  int r;
  for (r = 0; r < 3; r++) lua_pushinteger(L, hp->deg[r]);
  return 3;
}

static int hp_count (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)lsys_ffd_hyperpatch_count(checkhp(L, 1)));
  return 1;
}

static int hp_tostring (lua_State *L) {
  lhp *h = (lhp *)luaL_checkudata(L, 1, HYPERPATCH_T);
  if (h->closed) lua_pushliteral(L, "lsys.Hyperpatch (closed)");
  else lua_pushfstring(L, "lsys.Hyperpatch: degree %d x %d x %d, %d control points",
                       h->hp.deg[0], h->hp.deg[1], h->hp.deg[2],
                       (int)lsys_ffd_hyperpatch_count(&h->hp));
  return 1;
}

/* ---------------------------------------------------------------------- */
/* the ranges of scene:deform and scene:transform */

typedef struct range { size_t v0, v1, l0, l1; } range;

/* Two 1-based inclusive indices {a, b} in field k of the options at t. */
static void readpair (lua_State *L, int t, const char *k, const char *who, lua_Integer ab[2]) {
  int r;
  lua_getfield(L, t, k);
  if (!lua_istable(L, -1) || luaL_len(L, -1) != 2)
    luaL_error(L, "%s: opts.%s must be {first, last}", who, k);
  for (r = 0; r < 2; r++) {
    int ok;
    lua_geti(L, -1, r + 1);
    ab[r] = lua_tointegerx(L, -1, &ok);
    if (!ok || ab[r] < 1)
      luaL_error(L, "%s: opts.%s[%d] must be an integer >= 1", who, k, r + 1);
    lua_pop(L, 1);
  }
  if (ab[1] < ab[0]) luaL_error(L, "%s: opts.%s is empty (%I > %I)", who, k, ab[0], ab[1]);
  lua_pop(L, 1);
}

/* The range of the options at 't' (none: the whole scene). */
static range readrange (lua_State *L, const lsys_scene *sc, int t, const char *who) {
  static const char *const names[] = {"modules", "vertices", NULL};
  lsys_opts o = {0, "", "", LSYS_GOT_NONE, 0};
  range g = {0, sc->mesh.nv, 0, sc->mesh.nl};
  lua_Integer ab[2];
  int hasm, hasv;
  if (lua_isnoneornil(L, t)) return g;
  luaL_checktype(L, t, LUA_TTABLE);
  o.t = lua_absindex(L, t);
  if (lsysL_optunknown(L, &o, names))
    luaL_error(L, "%s: unknown option %s (known: modules, vertices)", who,
               luaL_tolstring(L, -1, NULL));
  lua_getfield(L, t, "modules"); hasm = !lua_isnil(L, -1);
  lua_getfield(L, t, "vertices"); hasv = !lua_isnil(L, -1);
  lua_pop(L, 2);
  if (hasm && hasv) luaL_error(L, "%s: give opts.modules or opts.vertices, not both", who);
  if (hasm) {
    uint32_t m0, m1;
    readpair(L, o.t, "modules", who, ab);
    m0 = ab[0] - 1 >= UINT32_MAX ? UINT32_MAX : (uint32_t)(ab[0] - 1);
    m1 = ab[1] >= UINT32_MAX ? UINT32_MAX : (uint32_t)ab[1];
    lsys_ffd_module_range(sc, m0, m1, &g.v0, &g.v1, &g.l0, &g.l1);
  } else if (hasv) {
    readpair(L, o.t, "vertices", who, ab);
    if ((size_t)ab[1] > sc->mesh.nv)
      luaL_error(L, "%s: opts.vertices: no vertex %I (the scene has %d)", who, ab[1],
                 (int)sc->mesh.nv);
    g.v0 = (size_t)ab[0] - 1;
    g.v1 = (size_t)ab[1];
    g.l0 = g.l1 = 0;
  }
  return g;
}

/* ---------------------------------------------------------------------- */
/* scene:deform with a Lua function */

typedef struct luafn {
  lua_State *L;
  int fn;                  /* stack index of the function */
  int bad;                 /* which return was bad (1..3), 0: the call raised */
} luafn;

/* Calls f(x, y, z) in protected mode; on failure leaves the error (or the
** bad value) on the stack and returns LSYS_ERULE. */
static int callfn (void *ud, const double p[3], double out[3]) {
  luafn *f = (luafn *)ud;
  lua_State *L = f->L;
  int r;
  lua_pushvalue(L, f->fn);
  for (r = 0; r < 3; r++) lua_pushnumber(L, p[r]);
  if (lua_pcall(L, 3, 3, 0) != LUA_OK) { f->bad = 0; return LSYS_ERULE; }
  for (r = 0; r < 3; r++) {
    int ok;
    out[r] = lua_tonumberx(L, r - 3, &ok);
    if (!ok || !isfinite(out[r]) || lua_type(L, r - 3) != LUA_TNUMBER) {
      f->bad = r + 1;
      lua_pushvalue(L, r - 3);
      return LSYS_ERULE;
    }
  }
  lua_pop(L, 3);
  return LSYS_OK;
}

/* Saves positions and normals of the range's vertices and its line ends in
** a new userdata (pushed) and returns it. */
static float *saverange (lua_State *L, const lsys_mesh *m, const range *g) {
  size_t nv = g->v1 - g->v0, nl = g->l1 - g->l0;
  float *b = (float *)lua_newuserdatauv(L, (6 * nv + 6 * nl) * sizeof *b + 1, 0);
  if (nv > 0) {              /* a mesh without vertices (or lines) has NULL arrays */
    memcpy(b, m->pos + 3 * g->v0, 3 * nv * sizeof *b);
    memcpy(b + 3 * nv, m->nrm + 3 * g->v0, 3 * nv * sizeof *b);
  }
  if (nl > 0) memcpy(b + 6 * nv, m->lpos + 6 * g->l0, 6 * nl * sizeof *b);
  return b;
}

static void restorerange (lsys_mesh *m, const range *g, const float *b) {
  size_t nv = g->v1 - g->v0, nl = g->l1 - g->l0;
  if (nv > 0) {
    memcpy(m->pos + 3 * g->v0, b, 3 * nv * sizeof *b);
    memcpy(m->nrm + 3 * g->v0, b + 3 * nv, 3 * nv * sizeof *b);
  }
  if (nl > 0) memcpy(m->lpos + 6 * g->l0, b + 6 * nv, 6 * nl * sizeof *b);
}

/* What failed at e->pos (a vertex, or nv + a line end), as "vertex 12" or
** "line 3 end 2", 1-based. */
static const char *where (lua_State *L, const lsys_mesh *m, size_t pos) {
  if (pos < m->nv) return lua_pushfstring(L, "vertex %I", (lua_Integer)pos + 1);
  pos -= m->nv;
  return lua_pushfstring(L, "line %I end %d", (lua_Integer)(pos / 2) + 1, (int)(pos % 2) + 1);
}

static int deform_fn (lua_State *L, lsys_lscene *S, const range *g) {
  static const char *const xyz[3] = {"x", "y", "z"};
  luafn f;
  lsys_error e;
  float *save;
  int st, top;
  save = saverange(L, &S->sc.mesh, g);
  top = lua_gettop(L);
  f.L = L; f.fn = 2; f.bad = 0;
  memset(&e, 0, sizeof e);
  st = lsys_ffd_func(&S->sc, g->v0, g->v1, g->l0, g->l1, callfn, &f, &e);
  if (st == LSYS_OK) return 0;
  restorerange(&S->sc.mesh, g, save);
  if (st != LSYS_ERULE || lua_gettop(L) == top)
    return luaL_error(L, "scene:deform: %s", e.msg);
  {
    /* each piece is made before the next is pushed: the order in which C evaluates a
    ** call's arguments is unspecified, and these read the stack's top */
    int bad = lua_gettop(L);
    const char *what = f.bad == 0 ? luaL_tolstring(L, top + 1, NULL)
                       : lua_type(L, bad) == LUA_TNUMBER ? "not finite"
                       : lua_isnil(L, bad) ? "nil"
                       : lua_pushfstring(L, "a %s", luaL_typename(L, bad));
    const char *at = where(L, &S->sc.mesh, e.pos);
    if (f.bad == 0)
      return luaL_error(L, "scene:deform: the function failed at %s: %s", at, what);
    return luaL_error(L, "scene:deform: the function must return 3 finite numbers; at %s its "
                      "%s is %s", at, xyz[f.bad - 1], what);
  }
}

/* scene:deform(hp | f, opts) -> vertices moved. The scene is held from the
** start: the options and the function run Lua code, which can neither close
** it nor move its arrays meanwhile. */
static int scene_deform (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  range g;
  int isfn = lua_type(L, 2) == LUA_TFUNCTION;
  lsys_hyperpatch *hp = NULL;
  if (!isfn) {
    if (luaL_testudata(L, 2, HYPERPATCH_T) == NULL)
      return luaL_error(L, "scene:deform: argument 1 must be a Hyperpatch or a function, got %s",
                        luaL_typename(L, 2));
    checkhp(L, 2);
  }
  lua_settop(L, 3);
  S = lsysL_holdscene(L, 1);                 /* 4 */
  g = readrange(L, &S->sc, 3, "scene:deform");
  if (!isfn) hp = checkhp(L, 2);            /* again: the options ran Lua code */
  if (isfn) deform_fn(L, S, &g);
  else {
    int st = lsys_ffd_range(&S->sc, g.v0, g.v1, g.l0, g.l1, hp);
    if (st != LSYS_OK)
      return luaL_error(L, "scene:deform: %s", st == LSYS_ENOMEM ? "not enough memory"
                                                                 : "range out of the scene");
  }
  lua_pushinteger(L, (lua_Integer)(g.v1 - g.v0));
  return 1;
}

/* scene:transform(m, opts): m = {{a, b, c, d}, {e, f, g, h}, {i, j, k, l}
** [, {0, 0, 0, 1}]} by rows */
static int scene_transform (lua_State *L) {
  static const char *who = "scene:transform";
  lsys_lscene *S = lsysL_checkscene(L, 1);
  double m[12];
  lua_Integer n;
  int r, c;
  range g;
  luaL_checktype(L, 2, LUA_TTABLE);
  lua_settop(L, 3);
  S = lsysL_holdscene(L, 1);                 /* 4: the matrix and options run Lua code */
  n = luaL_len(L, 2);
  if (n != 3 && n != 4) return luaL_error(L, "%s: the matrix must have 3 or 4 rows, got %I", who, n);
  for (r = 0; r < (int)n; r++) {
    if (lua_geti(L, 2, r + 1) != LUA_TTABLE || luaL_len(L, -1) != 4)
      return luaL_error(L, "%s: row %d must be a list of 4 numbers", who, r + 1);
    for (c = 0; c < 4; c++) {
      char what[32];
      double x;
      snprintf(what, sizeof what, "m[%d][%d]", r + 1, c + 1);
      lua_geti(L, -1, c + 1);
      x = checkfinite(L, -1, who, what);
      if (r < 3) m[4 * r + c] = x;
      else if (x != (c == 3))
        return luaL_error(L, "%s: row 4 must be {0, 0, 0, 1} (an affine map)", who);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  g = readrange(L, &S->sc, 3, who);
  if ((r = lsys_ffd_affine(&S->sc, g.v0, g.v1, g.l0, g.l1, m)) != LSYS_OK)
    return luaL_error(L, "%s: %s", who, r == LSYS_ENOMEM ? "not enough memory"
                                                         : "range out of the scene");
  lua_pushinteger(L, (lua_Integer)(g.v1 - g.v0));
  return 1;
}

/* scene:module_range(m0 [, m1]) -> v0, v1 (1-based, inclusive) or nil */
static int scene_module_range (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer a = luaL_checkinteger(L, 2), b = luaL_optinteger(L, 3, a);
  size_t v0, v1, l0, l1;
  luaL_argcheck(L, a >= 1, 2, "module indices start at 1");
  luaL_argcheck(L, b >= a, 3, "the last module is before the first");
  if (!lsys_ffd_module_range(&S->sc, a - 1 >= UINT32_MAX ? UINT32_MAX : (uint32_t)(a - 1),
                             b >= UINT32_MAX ? UINT32_MAX : (uint32_t)b, &v0, &v1, &l0, &l1)
      || v1 == v0) {
    lua_pushnil(L);
    return 1;
  }
  lua_pushinteger(L, (lua_Integer)v0 + 1);
  lua_pushinteger(L, (lua_Integer)v1);
  return 2;
}

/* scene:vertex(i) -> x, y, z, nx, ny, nz */
static int scene_vertex (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  int r;
  if (i < 1 || (size_t)i > S->sc.mesh.nv)
    return luaL_error(L, "scene:vertex: no vertex %I (the scene has %d)", i, (int)S->sc.mesh.nv);
  for (r = 0; r < 3; r++) lua_pushnumber(L, S->sc.mesh.pos[3 * (size_t)(i - 1) + r]);
  for (r = 0; r < 3; r++) lua_pushnumber(L, S->sc.mesh.nrm[3 * (size_t)(i - 1) + r]);
  return 6;
}

static const luaL_Reg hp_methods[] = {
  {"point", hp_point}, {"set", hp_set}, {"map", hp_map}, {"degree", hp_degree},
  {"count", hp_count}, {NULL, NULL}
};

static const luaL_Reg hp_meta[] = {
  {"__index", NULL}, {"__close", hp_close}, {"__tostring", hp_tostring}, {NULL, NULL}
};

static const luaL_Reg scene_methods[] = {
  {"deform", scene_deform}, {"transform", scene_transform},
  {"module_range", scene_module_range}, {"vertex", scene_vertex}, {NULL, NULL}
};

/* After lsysL_open_scene: adds the methods to the Scene's __methods. */
void lsysL_open_ffd (lua_State *L) {
  lsysL_createmeta(L, HYPERPATCH_T, hp_meta, hp_methods);
  luaL_getmetatable(L, SCENE_T);
  lua_getfield(L, -1, "__methods");
  luaL_setfuncs(L, scene_methods, 0);
  lua_pop(L, 2);
  lua_pushcfunction(L, l_hyperpatch);
  lua_setfield(L, -2, "hyperpatch");
}
