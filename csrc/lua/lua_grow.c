/*
** Lua binding of csrc/core/grow.h: the limb table of incremental growth
** (lsys.grow). Limb ids and plant numbers are 1-based here. Every method
** checks that the table and its scene are alive.
**
**   core.limbs{sides = 8, max_limbs = 0, limb_bytes = 0, plant_bytes = 0} -> Limbs
**                                       (with a Scene of its own; the bytes the caller
**                                       keeps per limb and plant count in max_memory)
**   T:scene() -> Scene                  T:update()     writes what changed into it
**   T:plant(x, y, z) -> p
**   T:set_leaf(shape [, ns, nt])      every leaf's shape (before the first leaf):
**       nil (the quad), a Surface (tessellated ns x nt a patch, default its
**       precision; its heading along the leaf, its up the leaf's normal, SIZE
**       one leaf size) or a Scene (its triangles; y along the leaf, z normal)
**   T:add(parent | 0, plant, at, ax, ay, az, angle, roll, length, radius, r, g, b)
**       -> id, or nil and "cap" when max_limbs limbs live
**   T:begin()  T:finish()               a tick; T:ticking() -> boolean; T:started() -> n0
**   getters (the state at the start of a tick within one):
**     T:length(i) T:radius(i) T:color(i) -> r, g, b  T:age(i) T:level(i) T:parent(i) -> id|nil
**     T:plant_of(i) T:alive(i) T:leaves(i) T:children(i) -> {ids}  T:count() (ids made)
**     T:living([p]) -> live limbs (of plant p), counted as they are made
**     T:base(i) -> x, y, z  T:tip(i) -> x, y, z  T:frame(i) -> R, H, F (lists)
**   setters (the next state within a tick):
**     T:set_length(i, x) T:set_radius(i, x) T:scale_length(i, f) T:scale_radius(i, f)
**     T:set_color(i, r, g, b) T:blend_color(i, r, g, b, t)
**     T:set_turn(i, ax, ay, az, angle, roll)
**     T:add_leaves(i, n, size, r, g, b) T:drop_leaves(i) T:remove(i)   (at the tick's end)
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "grow.h"

#define LIMBS_T "lsys.Limbs"

/* A rule compiled for the tick loop: a condition for the expression machine
** over the limb's variables (GUARD_VARS) and what to do where it holds. */
#define MAXCLAUSES 8

/* A condition "v1 op e1 and v2 op e2 and ...", each e a constant k or m * v + k:
** checked without the machine. */
typedef struct clause { int a, op, b; double k, m; } clause;

typedef struct crule {
  lsys_ins *code;       /* NULL: always */
  int ncode;
  int ncl;              /* > 0: the condition is these clauses (code kept for reference) */
  clause cl[MAXCLAUSES];
  double slen, srad;    /* scale factors (1: none) */
  int blend, setcol;
  float brgb[3], crgb[3];
  double bt;
  int fn;               /* index in the tick's function list (0: none) */
} crule;

typedef struct ckind { crule *r; int n; } ckind;

/* The variables a condition reads, in this order (lsys.grow's VARS): the
** limb's state at the start of the tick, but for V_COUNT and V_TOTAL, the
** living limbs of its plant and of the world as they are when the rule runs
** (with the children made so far in the tick: Davison's spawning rule reads
** treeLimbs.size(), which makeChild appends to). */
enum { V_LENGTH, V_RADIUS, V_AGE, V_LEVEL, V_LEAVES, V_COUNT, V_ROOT, V_TOTAL, NVARS };

typedef struct llimbs {
  lsys_limbs g;
  lsys_lscene *S;      /* its scene, kept alive by user value 1 */
  ckind *kinds;        /* by the limbs' tags */
  int nkinds;
  lsys_rng rng;        /* for conditions (they cannot draw today; the machine wants one) */
  int cur_rule;        /* while run runs: the rule (1-based in its kind) and limb */
  int32_t cur_limb;
  int closed;
} llimbs;

static void freekind (ckind *k) {
  int j;
  for (j = 0; j < k->n; j++) LSYS_FREE(k->r[j].code);
  LSYS_FREE(k->r);
  k->r = NULL;
  k->n = 0;
}

/* The table at 1, alive, with its scene alive. */
static lsys_limbs *checklimbs (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  if (t->closed) luaL_error(L, "the limbs were closed");
  if (!t->S->inited) luaL_error(L, "the limbs' scene was closed");
  return &t->g;
}

/* The table at 1 for a method that writes its scene (begin starts what
** finish writes): refused while the scene is held. */
static lsys_limbs *checkwriter (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  lsysL_changescene(L, ((const llimbs *)lua_touserdata(L, 1))->S);
  return g;
}

static int limbs_gc (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  if (!t->closed) {
    int k;
    lsys_grow_free(&t->g);
    for (k = 0; k < t->nkinds; k++) freekind(&t->kinds[k]);
    LSYS_FREE(t->kinds);
    t->kinds = NULL;
    t->nkinds = 0;
  }
  t->closed = 1;
  return 0;
}

/* A live limb id at stack index k (1-based in Lua). */
static int32_t limbarg (lua_State *L, lsys_limbs *g, int k) {
  lua_Integer i = luaL_checkinteger(L, k);
  if (i < 1 || (lua_Unsigned)i > g->n) luaL_argerror(L, k, "no such limb");
  if (!lsys_grow_alive(g, (int32_t)(i - 1))) luaL_argerror(L, k, "the limb was removed");
  return (int32_t)(i - 1);
}

static double numarg (lua_State *L, int k) {
  double x = luaL_checknumber(L, k);
  if (!isfinite(x)) luaL_argerror(L, k, "not a finite number");
  return x;
}

/* The world's memory budget is spent (its limbs at 1): an error without a position (the
** file of lsys.grow that called would be no help; a tick names the rule and limb). */
static int memerror (lua_State *L) {
  const llimbs *t = (const llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  char b[32];
  size_t limit = t->g.max_memory > 0 ? t->g.max_memory : lsys_common_memory_limit();
  lua_pushfstring(L, "lsys.grow: the world would need more than max_memory (%s) with %I "
                  "limbs (set LSYS_MAX_MEMORY, or lsys.max_memory)", lsys_common_fmtsize(b, limit),
                  (lua_Integer)t->g.n);
  return lua_error(L);
}

static int status (lua_State *L, int r, const char *what) {
  if (r == LSYS_OK) return 0;
  if (r == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (r == LSYS_EMEMORY) return memerror(L);
  if (r == LSYS_ELIMIT) return luaL_error(L, "%s: too many (colours or limbs)", what);
  if (r == LSYS_EBUSY) return luaL_error(L, "%s: %s", what, "a tick is (not) running");
  return luaL_error(L, "%s: bad arguments", what);
}

static int l_limbs (lua_State *L) {
  lua_Integer sides = 8, max = 0, held[2] = {0, 0};
  llimbs *t;
  lsys_lscene *S;
  lsys_material grey;
  if (!lua_isnoneornil(L, 1)) {
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_getfield(L, 1, "sides");
    sides = luaL_optinteger(L, -1, 8);
    lua_getfield(L, 1, "max_limbs");
    max = luaL_optinteger(L, -1, 0);
    lua_getfield(L, 1, "limb_bytes");           /* what the caller keeps per limb, plant */
    held[0] = luaL_optinteger(L, -1, 0);
    lua_getfield(L, 1, "plant_bytes");
    held[1] = luaL_optinteger(L, -1, 0);
    lua_pop(L, 4);
  }
  luaL_argcheck(L, held[0] >= 0 && held[1] >= 0, 1, "limb_bytes and plant_bytes must be >= 0");
  luaL_argcheck(L, sides >= 3 && sides <= LSYS_LIMBS_MAXSIDES, 1, "sides must be 3 to 64");
  luaL_argcheck(L, max >= 0, 1, "max_limbs must be >= 0");
  lua_settop(L, 1);
  t = (llimbs *)lua_newuserdatauv(L, sizeof *t, 1);          /* 2 */
  t->closed = 1;
  luaL_setmetatable(L, LIMBS_T);
  S = lsysL_newscene(L);     /* 3 */
  lsys_mesh_material_color(&grey, 0.6, 0.6, 0.6);               /* colour 0: a Scene has one */
  if (lsys_scene_set_palette(&S->sc, &grey, 1) != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_setiuservalue(L, 2, 1);
  t->S = S;
  t->kinds = NULL;
  t->nkinds = 0;
  t->cur_rule = 0;
  t->cur_limb = 0;
  lsys_rng_seed(&t->rng, 1);
  lsys_grow_init(&t->g, &S->sc, (int)sides);
  t->g.maxlimbs = (size_t)max;
  t->g.held_limb = (size_t)held[0];
  t->g.held_plant = (size_t)held[1];
  t->closed = 0;
  return 1;
}

static int limbs_scene (lua_State *L) {
  checklimbs(L);
  lua_getiuservalue(L, 1, 1);
  return 1;
}

static int limbs_update (lua_State *L) {
  return status(L, lsys_grow_update(checkwriter(L)), "update");
}

static int limbs_set_leaf (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  const lsys_surface *sf = luaL_testudata(L, 2, SURFACE_T) ? lsysL_checksurface(L, 2) : NULL;
  lsys_mesh m;
  int r;
  if (g->nl > 0) return luaL_error(L, "leaf shape: leaves are made already (set it first)");
  if (lua_isnoneornil(L, 2)) return status(L, lsys_grow_set_leaf(g, NULL), "leaf shape");
  if (sf == NULL) {
    const lsys_lscene *S = (const lsys_lscene *)luaL_testudata(L, 2, SCENE_T);
    if (S == NULL || !S->inited) return luaL_typeerror(L, 2, "lsys.Surface or open lsys.Scene");
    if (S->sc.mesh.nt == 0) return luaL_error(L, "leaf shape: the scene has no triangles");
    r = lsys_grow_set_leaf(g, &S->sc.mesh);
    if (r == LSYS_EARG)
      return luaL_error(L, "leaf shape: the scene has more than %d vertices or a point that is "
                        "not finite", LSYS_LIMBS_MAXLEAFV);
    return status(L, r, "leaf shape");
  } else {
    lua_Integer ns = luaL_optinteger(L, 3, sf->precision_s);
    lua_Integer nt = luaL_optinteger(L, 4, sf->precision_t);
    lsys_place pl;
    luaL_argcheck(L, ns >= 1 && ns <= LSYS_SURFACE_MAXDIV, 3, "1 to 256 lines a patch");
    luaL_argcheck(L, nt >= 1 && nt <= LSYS_SURFACE_MAXDIV, 4, "1 to 256 lines a patch");
    memset(&pl, 0, sizeof pl);
    pl.H[1] = 1; pl.U[2] = 1; pl.L[0] = 1;       /* L = H x U: the leaf's x */
    pl.scale = 1;
    pl.uv_surface = 1;
    lsys_mesh_init(&m);
    r = lsys_surface_mesh(&m, sf, &pl, (int)ns, (int)nt);
    if (r == LSYS_OK) r = lsys_grow_set_leaf(g, &m);
    lsys_mesh_free(&m);
    if (r == LSYS_EARG || r == LSYS_ELIMIT)
      return luaL_error(L, "leaf shape: the surface makes more than %d vertices (%d x %d lines "
                        "a patch); give fewer lines", LSYS_LIMBS_MAXLEAFV, (int)ns, (int)nt);
    return status(L, r, "leaf shape");
  }
}

static int limbs_plant (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  double p[3];
  int32_t id;
  int k;
  for (k = 0; k < 3; k++) p[k] = numarg(L, 2 + k);
  status(L, lsys_grow_plant(g, p, &id), "plant");
  lua_pushinteger(L, (lua_Integer)id + 1);
  return 1;
}

static int limbs_add (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  lsys_limbspec s;
  lua_Integer par = luaL_checkinteger(L, 2), pl = luaL_checkinteger(L, 3);
  int32_t id;
  int k, r;
  s.parent = par == 0 ? -1 : limbarg(L, g, 2);
  luaL_argcheck(L, par != 0 || (pl >= 1 && (lua_Unsigned)pl <= g->np), 3, "no such plant");
  s.plant = (int32_t)(pl - 1);
  s.at = numarg(L, 4);
  for (k = 0; k < 3; k++) s.axis[k] = numarg(L, 5 + k);
  s.angle = numarg(L, 8);
  s.roll = numarg(L, 9);
  s.length = numarg(L, 10);
  s.radius = numarg(L, 11);
  for (k = 0; k < 3; k++) s.rgb[k] = (float)numarg(L, 12 + k);
  {
    lua_Integer tag = luaL_optinteger(L, 15, 0);
    luaL_argcheck(L, tag >= 0 && tag <= 65535, 15, "a tag is 0 to 65535");
    s.tag = (uint16_t)tag;
  }
  r = lsys_grow_add(g, &s, &id);
  if (r == LSYS_ELIMIT) {
    lua_pushnil(L);
    lua_pushliteral(L, "cap");
    return 2;
  }
  status(L, r, "add");
  lua_pushinteger(L, (lua_Integer)id + 1);
  return 1;
}

static int limbs_begin (lua_State *L) {
  return status(L, lsys_grow_begin(checkwriter(L)), "begin");
}

static int limbs_finish (lua_State *L) {
  return status(L, lsys_grow_end(checkwriter(L)), "finish");
}

static int limbs_ticking (lua_State *L) {
  lua_pushboolean(L, checklimbs(L)->intick);
  return 1;
}

static int limbs_started (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)checklimbs(L)->n0);
  return 1;
}

/* {======================================================================
** Getters
** ======================================================================= */

#define GETTER(name, expr, push) \
  static int limbs_##name (lua_State *L) { \
    lsys_limbs *g = checklimbs(L); \
    int32_t i = limbarg(L, g, 2); \
    push(L, expr); \
    return 1; \
  }

GETTER(length, g->len[i], lua_pushnumber)
GETTER(radius, g->rad[i], lua_pushnumber)
GETTER(age, (lua_Integer)g->age[i], lua_pushinteger)
GETTER(level, (lua_Integer)g->level[i], lua_pushinteger)
GETTER(plant_of, (lua_Integer)g->plant[i] + 1, lua_pushinteger)
GETTER(leaves, (lua_Integer)g->nleaves[i], lua_pushinteger)

static int limbs_parent (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  if (g->parent[i] < 0) return 0;
  lua_pushinteger(L, (lua_Integer)g->parent[i] + 1);
  return 1;
}

static int limbs_alive (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  lua_Integer i = luaL_checkinteger(L, 2);
  lua_pushboolean(L, i >= 1 && (lua_Unsigned)i <= g->n && lsys_grow_alive(g, (int32_t)(i - 1)));
  return 1;
}

static int limbs_color (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  int k;
  for (k = 0; k < 3; k++) lua_pushnumber(L, g->rgb[3 * i + k]);
  return 3;
}

static int limbs_children (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2), c;
  lua_Integer k = 0;
  lua_newtable(L);
  g = checklimbs(L);                        /* again: a finalizer may have closed it */
  for (c = g->first[i]; c >= 0; c = g->next[c]) {
    lua_pushinteger(L, (lua_Integer)c + 1);
    lua_rawseti(L, -2, ++k);
  }
  return 1;
}

static int limbs_count (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)checklimbs(L)->n);
  return 1;
}

static int limbs_living (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  lua_Integer p;
  if (lua_isnoneornil(L, 2)) {
    lua_pushinteger(L, (lua_Integer)g->nalive);
    return 1;
  }
  p = luaL_checkinteger(L, 2);
  luaL_argcheck(L, p >= 1 && (lua_Unsigned)p <= g->np, 2, "no such plant");
  lua_pushinteger(L, (lua_Integer)g->pcount[p - 1]);
  return 1;
}

static int limbs_base (lua_State *L) {
  lsys_limbs *g = checkwriter(L);
  int32_t i = limbarg(L, g, 2);
  int k;
  status(L, lsys_grow_update(g), "base");
  for (k = 0; k < 3; k++) lua_pushnumber(L, g->wp[3 * i + k]);
  return 3;
}

static int limbs_tip (lua_State *L) {
  lsys_limbs *g = checkwriter(L);
  int32_t i = limbarg(L, g, 2);
  double t[3];
  int k;
  status(L, lsys_grow_update(g), "tip");
  lsys_grow_tip(g, i, t);
  for (k = 0; k < 3; k++) lua_pushnumber(L, t[k]);
  return 3;
}

static int limbs_frame (lua_State *L) {
  lsys_limbs *g = checkwriter(L);
  int32_t i = limbarg(L, g, 2);
  double m[9];
  int k;
  status(L, lsys_grow_update(g), "frame");
  memcpy(m, g->wm + 9 * i, sizeof m);       /* before the lists: a finalizer may close g */
  for (k = 0; k < 3; k++) lsysL_pushnums(L, m + 3 * k, 3);
  return 3;
}

/* }====================================================================== */

/* {======================================================================
** Setters
** ======================================================================= */

/* The setters of length and radius: set_x(i, v), or scale_x(i, f) (the next
** value times f, so scales in one tick compound). */
static int setsize (lua_State *L, int radius, int scale, const char *what) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double x = numarg(L, 3);
  luaL_argcheck(L, x >= 0, 3, scale ? "a scale factor is >= 0"
                               : radius ? "a radius is >= 0" : "a length is >= 0");
  if (scale) x *= radius ? g->nrad[i] : g->nlen[i];
  return status(L, radius ? lsys_grow_set_radius(g, i, x) : lsys_grow_set_length(g, i, x),
                what);
}

static int limbs_set_length (lua_State *L) { return setsize(L, 0, 0, "set_length"); }
static int limbs_set_radius (lua_State *L) { return setsize(L, 1, 0, "set_radius"); }
static int limbs_scale_length (lua_State *L) { return setsize(L, 0, 1, "scale_length"); }
static int limbs_scale_radius (lua_State *L) { return setsize(L, 1, 1, "scale_radius"); }

static void rgbarg (lua_State *L, int k, float c[3]) {
  int j;
  for (j = 0; j < 3; j++) c[j] = (float)numarg(L, k + j);
}

static int limbs_set_color (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  float c[3];
  rgbarg(L, 3, c);
  return status(L, lsys_grow_set_color(g, i, c), "set_color");
}

/* blend_color(i, r, g, b, t): from the colour of the start of the tick towards
** (r, g, b) by the fraction t */
static int limbs_blend_color (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  float c[3];
  double t = numarg(L, 6);
  int k;
  rgbarg(L, 3, c);
  for (k = 0; k < 3; k++) c[k] = (float)(g->rgb[3 * i + k] + (c[k] - g->rgb[3 * i + k]) * t);
  return status(L, lsys_grow_set_color(g, i, c), "blend_color");
}

static int limbs_set_turn (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double ax[3];
  int k;
  for (k = 0; k < 3; k++) ax[k] = numarg(L, 3 + k);
  luaL_argcheck(L, ax[0] != 0 || ax[1] != 0 || ax[2] != 0, 3, "the axis is zero");
  return status(L, lsys_grow_set_turn(g, i, ax, numarg(L, 6), numarg(L, 7)), "set_turn");
}

static int limbs_add_leaves (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  lua_Integer n = luaL_checkinteger(L, 3);
  double size = numarg(L, 4);
  float c[3];
  luaL_argcheck(L, n >= 0 && n <= 1000, 3, "0 to 1000 leaves at a time");
  luaL_argcheck(L, size >= 0, 4, "a leaf size is >= 0");
  rgbarg(L, 5, c);
  return status(L, lsys_grow_add_leaves(g, i, (int)n, size, c), "add_leaves");
}

static int limbs_drop_leaves (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  return status(L, lsys_grow_drop_leaves(g, limbarg(L, g, 2)), "drop_leaves");
}

static int limbs_remove (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  return status(L, lsys_grow_remove(g, limbarg(L, g, 2)), "remove");
}

/* }====================================================================== */

/* {======================================================================
** Rules in the tick loop
** ======================================================================= */

/* A number field of the table at t, or 'dflt'. */
static double optfield (lua_State *L, int t, const char *k, double dflt) {
  double x;
  if (lua_getfield(L, t, k) == LUA_TNIL) { lua_pop(L, 1); return dflt; }
  x = lua_tonumber(L, -1);
  if (!lua_isnumber(L, -1) || !isfinite(x)) luaL_error(L, "set_rules: '%s' must be a number", k);
  lua_pop(L, 1);
  return x;
}

/* Field k of the table at t: a list of n finite numbers into v; 0 when absent. */
static int optlist (lua_State *L, int t, const char *k, double *v, int n) {
  int j;
  if (lua_getfield(L, t, k) == LUA_TNIL) { lua_pop(L, 1); return 0; }
  if (!lua_istable(L, -1)) luaL_error(L, "set_rules: '%s' must be a list of %d numbers", k, n);
  for (j = 0; j < n; j++) {
    lua_rawgeti(L, -1, j + 1);
    v[j] = lua_tonumber(L, -1);
    if (!lua_isnumber(L, -1) || !isfinite(v[j]))
      luaL_error(L, "set_rules: '%s'[%d] must be a number", k, j + 1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return 1;
}

/* Whether the program is a conjunction of comparisons of a variable with a
** constant or an affine function of a variable, as lsys.compile writes it:
** clauses ARG K CMP or ARG K ARG MUL K ADD CMP, each followed by JF to the end
** but the last, then COND; then its clauses go to r. */
static void simplify (const lsys_ins *c, int n, crule *r) {
  int k = 0, m = 0;
  if (n < 4 || c[n - 1].op != LSYS_OP_COND) return;
  while (k < n - 1) {
    clause *q = &r->cl[m];
    if (m == MAXCLAUSES || c[k].op != LSYS_OP_ARG || c[k].a < 0 || c[k].a >= NVARS) return;
    q->a = c[k].a;
    q->b = -1;
    q->m = 0;
    if (k + 2 < n && c[k + 1].op == LSYS_OP_K && c[k + 2].op >= LSYS_OP_LT &&
        c[k + 2].op <= LSYS_OP_NE) {
      q->k = c[k + 1].k;
      q->op = c[k + 2].op;
      k += 3;
    } else if (k + 6 < n && c[k + 1].op == LSYS_OP_K && c[k + 2].op == LSYS_OP_ARG &&
               c[k + 2].a >= 0 && c[k + 2].a < NVARS && c[k + 3].op == LSYS_OP_MUL &&
               c[k + 4].op == LSYS_OP_K && c[k + 5].op == LSYS_OP_ADD &&
               c[k + 6].op >= LSYS_OP_LT && c[k + 6].op <= LSYS_OP_NE) {
      q->m = c[k + 1].k;
      q->b = c[k + 2].a;
      q->k = c[k + 4].k;
      q->op = c[k + 6].op;
      k += 7;
    } else return;
    m++;
    if (k == n - 1) break;                           /* the COND */
    if (c[k].op != LSYS_OP_JF || c[k].a != n - 1) return;
    k++;
  }
  if (k != n - 1) return;
  r->ncl = m;
}

/* The clauses of r on args (all must hold). */
static int clauses (const crule *r, const double *args) {
  int k;
  for (k = 0; k < r->ncl; k++) {
    const clause *q = &r->cl[k];
    double x = args[q->a], y = q->b >= 0 ? q->m * args[q->b] + q->k : q->k;
    int ok;
    switch (q->op) {
      case LSYS_OP_LT: ok = x < y; break;
      case LSYS_OP_LE: ok = x <= y; break;
      case LSYS_OP_GT: ok = x > y; break;
      case LSYS_OP_GE: ok = x >= y; break;
      case LSYS_OP_EQ: ok = x == y; break;
      default: ok = x != y; break;
    }
    if (!ok) return 0;
  }
  return 1;
}

/* Reads rule table at 'idx' (rule number j) into r, every field once; its
** condition's code is checked, then copied into C memory last (nothing runs
** Lua code after the copy). Returns 0 when that allocation fails. */
static int readrule (lua_State *L, int idx, int j, crule *r) {
  double v[4];
  lsys_ins *c = NULL;
  int nc = 0;
  idx = lua_absindex(L, idx);
  memset(r, 0, sizeof *r);
  if (!lua_istable(L, idx)) luaL_error(L, "set_rules: rule %d is not a table", j);
  if (lua_getfield(L, idx, "code") != LUA_TNIL) {
    c = lsysL_readcode(L, -1, &nc);          /* on the stack until the end */
    if (lsys_expr_check(c, nc, NVARS, 0) != 0)
      luaL_error(L, "set_rules: rule %d: the condition's code is malformed", j);
  }
  r->slen = optfield(L, idx, "scale_length", 1);
  r->srad = optfield(L, idx, "scale_radius", 1);
  if (r->slen < 0 || r->srad < 0) luaL_error(L, "set_rules: rule %d: a scale factor is >= 0", j);
  if ((r->blend = optlist(L, idx, "blend", v, 4)) != 0) {
    r->brgb[0] = (float)v[0]; r->brgb[1] = (float)v[1]; r->brgb[2] = (float)v[2]; r->bt = v[3];
  }
  if ((r->setcol = optlist(L, idx, "color", v, 3)) != 0) {
    r->crgb[0] = (float)v[0]; r->crgb[1] = (float)v[1]; r->crgb[2] = (float)v[2];
  }
  v[0] = optfield(L, idx, "fn", 0);
  if (v[0] < 0 || v[0] > 1e9 || v[0] != floor(v[0]))
    luaL_error(L, "set_rules: rule %d: 'fn' must be an index", j);
  r->fn = (int)v[0];
  if (c != NULL) {
    if ((r->code = (lsys_ins *)LSYS_MALLOC((size_t)nc * sizeof *c + 1)) == NULL) return 0;
    memcpy(r->code, c, (size_t)nc * sizeof *c);
    r->ncode = nc;
    simplify(c, nc, r);
    lua_pop(L, 2);
  } else lua_pop(L, 1);
  return 1;
}

/* The rules being read by set_rules, in a userdata whose __gc frees them if
** an error interrupts the reading. */
static int kindbox_gc (lua_State *L) {
  freekind((ckind *)lua_touserdata(L, 1));
  return 0;
}

/* T:set_rules(kind, {rule, ...}): what the limbs tagged 'kind' run at each
** tick, in order; a rule is {code = {op, a, k, ...} (a condition over length,
** radius, age, level, leaves, count, root, total), scale_length =, scale_radius =,
** blend = {r, g, b, t}, color = {r, g, b}, fn = index in run's list}. The
** list is read once; the table is taken after it (its metamethods ran). */
static int limbs_set_rules (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  lua_Integer kind = luaL_checkinteger(L, 2), n, j;
  ckind *nk;
  checklimbs(L);
  luaL_argcheck(L, kind >= 0 && kind <= 65535, 2, "a kind is 0 to 65535");
  luaL_checktype(L, 3, LUA_TTABLE);
  lua_settop(L, 3);
  if (t->g.intick) return luaL_error(L, "set_rules: not during a tick");
  n = luaL_len(L, 3);
  luaL_argcheck(L, n >= 0 && n <= 10000, 3, "at most 10,000 rules");
  nk = (ckind *)lua_newuserdatauv(L, sizeof *nk, 0);        /* 4 */
  nk->r = NULL;
  nk->n = 0;
  if (luaL_newmetatable(L, "lsys.LimbRules")) {
    lua_pushcfunction(L, kindbox_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, 4);
  if (n > 0 && (nk->r = (crule *)LSYS_MALLOC((size_t)n * sizeof *nk->r)) == NULL)
    return luaL_error(L, "not enough memory");
  for (j = 1; j <= n; j++) {
    int ok;
    lua_rawgeti(L, 3, j);
    ok = readrule(L, -1, (int)j, &nk->r[nk->n]);
    lua_pop(L, 1);
    if (!ok) return luaL_error(L, "not enough memory");
    nk->n++;
  }
  checklimbs(L);                            /* again: the rules' metamethods ran */
  if (t->g.intick) return luaL_error(L, "set_rules: not during a tick");
  if (kind >= t->nkinds) {
    ckind *k2 = (ckind *)LSYS_REALLOC(t->kinds, (size_t)(kind + 1) * sizeof *k2);
    if (k2 == NULL) return luaL_error(L, "not enough memory");
    memset(k2 + t->nkinds, 0, (size_t)(kind + 1 - t->nkinds) * sizeof *k2);
    t->kinds = k2;
    t->nkinds = (int)kind + 1;
  }
  freekind(&t->kinds[kind]);
  t->kinds[kind] = *nk;
  nk->r = NULL;                             /* the table owns them now */
  nk->n = 0;
  return 0;
}

/* Applies the declarative part of rule r to limb i. */
static int apply (lsys_limbs *g, const crule *r, int32_t i) {
  int st = LSYS_OK, k;
  if (r->slen != 1) st = lsys_grow_set_length(g, i, g->nlen[i] * r->slen);
  if (st == LSYS_OK && r->srad != 1) st = lsys_grow_set_radius(g, i, g->nrad[i] * r->srad);
  if (st == LSYS_OK && r->blend) {
    float c[3];
    for (k = 0; k < 3; k++)
      c[k] = (float)(g->rgb[3 * i + k] + (r->brgb[k] - g->rgb[3 * i + k]) * r->bt);
    st = lsys_grow_set_color(g, i, c);
  }
  if (st == LSYS_OK && r->setcol) st = lsys_grow_set_color(g, i, r->crgb);
  return st;
}

/* T:run(limbs, world, fns): the body of a tick (between begin and finish):
** every limb that existed at its start runs the rules of its tag in order;
** a rule's condition runs here, its declared changes too, and its function
** fns[fn](limbs[id], world) only where the condition holds. */
static int limbs_run (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  lsys_limbs *g = checklimbs(L);
  size_t i, n0 = g->n0;
  luaL_checktype(L, 2, LUA_TTABLE);
  luaL_checktype(L, 4, LUA_TTABLE);
  lua_settop(L, 4);
  if (!g->intick) return luaL_error(L, "run: no tick is running");
  for (i = 0; i < n0; i++) {
    const ckind *k;
    double args[NVARS], out[1];
    int j;
    if (!(g->flag[i] & LSYS_LIMB_ALIVE) || g->tag[i] >= t->nkinds) continue;
    k = &t->kinds[g->tag[i]];
    args[V_LENGTH] = g->len[i]; args[V_RADIUS] = g->rad[i]; args[V_AGE] = g->age[i];
    args[V_LEVEL] = g->level[i]; args[V_LEAVES] = g->nleaves[i];
    args[V_ROOT] = g->parent[i] < 0;
    for (j = 0; j < k->n; j++) {
      const crule *r = &k->r[j];
      args[V_COUNT] = g->pcount[g->plant[i]];     /* as the limbs made so far leave them */
      args[V_TOTAL] = (double)g->nalive;
      t->cur_rule = j + 1;
      t->cur_limb = (int32_t)i + 1;
      if (r->ncl > 0 ? !clauses(r, args)
          : r->code != NULL && !lsys_expr_run(r->code, r->ncode, args, out, &t->rng, NULL))
        continue;
      if (apply(g, r, (int32_t)i) != LSYS_OK)      /* set_length and set_radius refuse inf */
        luaL_error(L, "its scale makes the limb's length or radius too large to be finite");
      if (r->fn > 0) {
        lua_rawgeti(L, 4, r->fn);
        lua_rawgeti(L, 2, (lua_Integer)i + 1);
        lua_pushvalue(L, 3);
        lua_call(L, 2, 0);
        /* the function may have changed anything: the table, its kinds, the tick */
        if (t->closed || !t->S->inited) return luaL_error(L, "a rule closed the limbs");
        if (!g->intick) return luaL_error(L, "a rule ended the tick");
        if (g->tag[i] >= t->nkinds) break;
        k = &t->kinds[g->tag[i]];
        if (j + 1 >= k->n) break;
      }
    }
  }
  t->cur_rule = 0;
  t->cur_limb = 0;
  return 0;
}

/* T:where() -> rule, limb: what run was running (after an error), or nothing. */
static int limbs_where (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  checklimbs(L);
  if (t->cur_limb == 0) return 0;
  lua_pushinteger(L, t->cur_rule);
  lua_pushinteger(L, t->cur_limb);
  return 2;
}

/* }====================================================================== */

static const luaL_Reg limbs_methods[] = {
  {"scene", limbs_scene}, {"update", limbs_update}, {"plant", limbs_plant},
  {"set_leaf", limbs_set_leaf}, {"add", limbs_add},
  {"begin", limbs_begin}, {"finish", limbs_finish}, {"ticking", limbs_ticking},
  {"started", limbs_started}, {"length", limbs_length}, {"radius", limbs_radius},
  {"age", limbs_age}, {"level", limbs_level}, {"plant_of", limbs_plant_of},
  {"leaves", limbs_leaves}, {"parent", limbs_parent}, {"alive", limbs_alive},
  {"color", limbs_color}, {"children", limbs_children}, {"count", limbs_count},
  {"living", limbs_living}, {"base", limbs_base},
  {"tip", limbs_tip}, {"frame", limbs_frame}, {"set_length", limbs_set_length},
  {"set_radius", limbs_set_radius}, {"scale_length", limbs_scale_length},
  {"scale_radius", limbs_scale_radius}, {"set_color", limbs_set_color},
  {"blend_color", limbs_blend_color}, {"set_turn", limbs_set_turn},
  {"add_leaves", limbs_add_leaves}, {"drop_leaves", limbs_drop_leaves},
  {"remove", limbs_remove}, {"set_rules", limbs_set_rules}, {"run", limbs_run},
  {"where", limbs_where}, {"close", limbs_gc}, {NULL, NULL}
};

static const luaL_Reg limbs_meta[] = {
  {"__index", NULL}, {"__gc", limbs_gc}, {"__close", limbs_gc}, {NULL, NULL}
};

void lsysL_open_grow (lua_State *L) {
  lsysL_createmeta(L, LIMBS_T, limbs_meta, limbs_methods);
  lua_pushcfunction(L, l_limbs);
  lua_setfield(L, -2, "limbs");
}
