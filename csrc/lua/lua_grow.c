/*
** Lua binding of csrc/core/grow.h: the limb table of incremental growth
** (lsys.grow). Limb ids and plant numbers are 1-based here. Every method
** checks that the table and its scene are alive.
**
**   core.limbs{sides = 8, max_limbs = 0} -> Limbs      (with a Scene of its own)
**   T:scene() -> Scene                  T:update()     writes what changed into it
**   T:plant(x, y, z) -> p
**   T:add(parent | 0, plant, at, ax, ay, az, angle, roll, length, radius, r, g, b)
**       -> id, or nil and "cap" when max_limbs limbs live
**   T:begin()  T:finish()               a tick; T:ticking() -> boolean; T:started() -> n0
**   getters (the state at the start of a tick within one):
**     T:length(i) T:radius(i) T:color(i) -> r, g, b  T:age(i) T:level(i) T:parent(i) -> id|nil
**     T:plant_of(i) T:alive(i) T:leaves(i) T:children(i) -> {ids}  T:count() (ids made)
**     T:living([p]) -> live limbs (of plant p)  T:living0(p) -> at the start of the tick
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

typedef struct llimbs {
  lsys_limbs g;
  lsys_lscene *S;      /* its scene, kept alive by user value 1 */
  int closed;
} llimbs;

/* The table at 1, alive, with its scene alive. */
static lsys_limbs *checklimbs (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  if (t->closed) luaL_error(L, "the limbs were closed");
  if (!t->S->inited) luaL_error(L, "the limbs' scene was closed");
  return &t->g;
}

static int limbs_gc (lua_State *L) {
  llimbs *t = (llimbs *)luaL_checkudata(L, 1, LIMBS_T);
  if (!t->closed) lsys_limbs_free(&t->g);
  t->closed = 1;
  return 0;
}

/* A live limb id at stack index k (1-based in Lua). */
static int32_t limbarg (lua_State *L, lsys_limbs *g, int k) {
  lua_Integer i = luaL_checkinteger(L, k);
  if (i < 1 || (lua_Unsigned)i > g->n) luaL_argerror(L, k, "no such limb");
  if (!lsys_limbs_alive(g, (int32_t)(i - 1))) luaL_argerror(L, k, "the limb was removed");
  return (int32_t)(i - 1);
}

static double numarg (lua_State *L, int k) {
  double x = luaL_checknumber(L, k);
  if (!isfinite(x)) luaL_argerror(L, k, "not a finite number");
  return x;
}

static int status (lua_State *L, int r, const char *what) {
  if (r == LSYS_OK) return 0;
  if (r == LSYS_ENOMEM) return luaL_error(L, "not enough memory");
  if (r == LSYS_ELIMIT) return luaL_error(L, "%s: too many (colours or limbs)", what);
  if (r == LSYS_EBUSY) return luaL_error(L, "%s: %s", what, "a tick is (not) running");
  return luaL_error(L, "%s: bad arguments", what);
}

static int l_limbs (lua_State *L) {
  lua_Integer sides = 8, max = 0;
  llimbs *t;
  lsys_lscene *S;
  lsys_material grey;
  if (!lua_isnoneornil(L, 1)) {
    luaL_checktype(L, 1, LUA_TTABLE);
    lua_getfield(L, 1, "sides");
    sides = luaL_optinteger(L, -1, 8);
    lua_getfield(L, 1, "max_limbs");
    max = luaL_optinteger(L, -1, 0);
    lua_pop(L, 2);
  }
  luaL_argcheck(L, sides >= 3 && sides <= LSYS_LIMBS_MAXSIDES, 1, "sides must be 3 to 64");
  luaL_argcheck(L, max >= 0, 1, "max_limbs must be >= 0");
  lua_settop(L, 1);
  t = (llimbs *)lua_newuserdatauv(L, sizeof *t, 1);          /* 2 */
  t->closed = 1;
  luaL_setmetatable(L, LIMBS_T);
  S = (lsys_lscene *)lua_newuserdatauv(L, sizeof *S, LSYS_SCENE_NUV);     /* 3 */
  memset(S, 0, sizeof *S);
  luaL_setmetatable(L, SCENE_T);
  lsys_scene_init(&S->sc);
  S->inited = 1;
  lsys_material_color(&grey, 0.6, 0.6, 0.6);               /* colour 0: a Scene has one */
  if (lsys_scene_set_palette(&S->sc, &grey, 1) != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_setiuservalue(L, 2, 1);
  t->S = S;
  lsys_limbs_init(&t->g, &S->sc, (int)sides);
  t->g.maxlimbs = (size_t)max;
  t->closed = 0;
  return 1;
}

static int limbs_scene (lua_State *L) {
  checklimbs(L);
  lua_getiuservalue(L, 1, 1);
  return 1;
}

static int limbs_update (lua_State *L) {
  return status(L, lsys_limbs_update(checklimbs(L)), "update");
}

static int limbs_plant (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  double p[3];
  int32_t id;
  int k;
  for (k = 0; k < 3; k++) p[k] = numarg(L, 2 + k);
  status(L, lsys_limbs_plant(g, p, &id), "plant");
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
  r = lsys_limbs_add(g, &s, &id);
  if (r == LSYS_ELIMIT) {
    lua_pushnil(L);
    lua_pushliteral(L, "cap");
    return 2;
  }
  status(L, r, "add");
  lua_pushinteger(L, (lua_Integer)id + 1);
  return 1;
}

static int limbs_begin (lua_State *L) { return status(L, lsys_limbs_begin(checklimbs(L)), "begin"); }
static int limbs_finish (lua_State *L) { return status(L, lsys_limbs_end(checklimbs(L)), "finish"); }

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
  lua_pushboolean(L, i >= 1 && (lua_Unsigned)i <= g->n && lsys_limbs_alive(g, (int32_t)(i - 1)));
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

static int living (lua_State *L, int start) {
  lsys_limbs *g = checklimbs(L);
  lua_Integer p;
  if (lua_isnoneornil(L, 2) && !start) {
    lua_pushinteger(L, (lua_Integer)g->nalive);
    return 1;
  }
  p = luaL_checkinteger(L, 2);
  luaL_argcheck(L, p >= 1 && (lua_Unsigned)p <= g->np, 2, "no such plant");
  lua_pushinteger(L, (lua_Integer)(start && g->intick ? g->pcount0 : g->pcount)[p - 1]);
  return 1;
}
static int limbs_living (lua_State *L) { return living(L, 0); }
static int limbs_living0 (lua_State *L) { return living(L, 1); }

static int limbs_base (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  int k;
  status(L, lsys_limbs_update(g), "base");
  for (k = 0; k < 3; k++) lua_pushnumber(L, g->wp[3 * i + k]);
  return 3;
}

static int limbs_tip (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double t[3];
  int k;
  status(L, lsys_limbs_update(g), "tip");
  lsys_limbs_tip(g, i, t);
  for (k = 0; k < 3; k++) lua_pushnumber(L, t[k]);
  return 3;
}

static int limbs_frame (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  int k;
  status(L, lsys_limbs_update(g), "frame");
  for (k = 0; k < 3; k++) lsys_pushnums(L, g->wm + 9 * i + 3 * k, 3);
  return 3;
}

/* }====================================================================== */

/* {======================================================================
** Setters
** ======================================================================= */

static int limbs_set_length (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double x = numarg(L, 3);
  luaL_argcheck(L, x >= 0, 3, "a length is >= 0");
  return status(L, lsys_limbs_set_length(g, i, x), "set_length");
}

static int limbs_set_radius (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double x = numarg(L, 3);
  luaL_argcheck(L, x >= 0, 3, "a radius is >= 0");
  return status(L, lsys_limbs_set_radius(g, i, x), "set_radius");
}

/* scale_length(i, f): the next length times f (so scales in one tick compound) */
static int limbs_scale_length (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double f = numarg(L, 3);
  luaL_argcheck(L, f >= 0, 3, "a scale factor is >= 0");
  return status(L, lsys_limbs_set_length(g, i, g->nlen[i] * f), "scale_length");
}

static int limbs_scale_radius (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double f = numarg(L, 3);
  luaL_argcheck(L, f >= 0, 3, "a scale factor is >= 0");
  return status(L, lsys_limbs_set_radius(g, i, g->nrad[i] * f), "scale_radius");
}

static void rgbarg (lua_State *L, int k, float c[3]) {
  int j;
  for (j = 0; j < 3; j++) c[j] = (float)numarg(L, k + j);
}

static int limbs_set_color (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  float c[3];
  rgbarg(L, 3, c);
  return status(L, lsys_limbs_set_color(g, i, c), "set_color");
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
  return status(L, lsys_limbs_set_color(g, i, c), "blend_color");
}

static int limbs_set_turn (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  int32_t i = limbarg(L, g, 2);
  double ax[3];
  int k;
  for (k = 0; k < 3; k++) ax[k] = numarg(L, 3 + k);
  luaL_argcheck(L, ax[0] != 0 || ax[1] != 0 || ax[2] != 0, 3, "the axis is zero");
  return status(L, lsys_limbs_set_turn(g, i, ax, numarg(L, 6), numarg(L, 7)), "set_turn");
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
  return status(L, lsys_limbs_add_leaves(g, i, (int)n, size, c), "add_leaves");
}

static int limbs_drop_leaves (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  return status(L, lsys_limbs_drop_leaves(g, limbarg(L, g, 2)), "drop_leaves");
}

static int limbs_remove (lua_State *L) {
  lsys_limbs *g = checklimbs(L);
  return status(L, lsys_limbs_remove(g, limbarg(L, g, 2)), "remove");
}

/* }====================================================================== */

static const luaL_Reg limbs_methods[] = {
  {"scene", limbs_scene}, {"update", limbs_update}, {"plant", limbs_plant}, {"add", limbs_add},
  {"begin", limbs_begin}, {"finish", limbs_finish}, {"ticking", limbs_ticking},
  {"started", limbs_started}, {"length", limbs_length}, {"radius", limbs_radius},
  {"age", limbs_age}, {"level", limbs_level}, {"plant_of", limbs_plant_of},
  {"leaves", limbs_leaves}, {"parent", limbs_parent}, {"alive", limbs_alive},
  {"color", limbs_color}, {"children", limbs_children}, {"count", limbs_count},
  {"living", limbs_living}, {"living0", limbs_living0}, {"base", limbs_base},
  {"tip", limbs_tip}, {"frame", limbs_frame}, {"set_length", limbs_set_length},
  {"set_radius", limbs_set_radius}, {"scale_length", limbs_scale_length},
  {"scale_radius", limbs_scale_radius}, {"set_color", limbs_set_color},
  {"blend_color", limbs_blend_color}, {"set_turn", limbs_set_turn},
  {"add_leaves", limbs_add_leaves}, {"drop_leaves", limbs_drop_leaves},
  {"remove", limbs_remove}, {"close", limbs_gc}, {NULL, NULL}
};

static const luaL_Reg limbs_meta[] = {
  {"__index", NULL}, {"__gc", limbs_gc}, {"__close", limbs_gc}, {NULL, NULL}
};

void lsys_open_grow (lua_State *L) {
  lsys_createmeta(L, LIMBS_T, limbs_meta, limbs_methods);
  lua_pushcfunction(L, l_limbs);
  lua_setfield(L, -2, "limbs");
}
