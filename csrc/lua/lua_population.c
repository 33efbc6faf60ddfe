/*
** Binding of populations (population.h, docs/population.md): the core of
** lsys.population (lua/lsys/population.lua), and the Scene methods that
** look at instances.
**
**   core.population(opts) -> Scene     an empty population; opts: its look (the
**                                      view's camera, light, background fields)
**                                      and the table the Scene keeps (user value
**                                      OPTS: its textures, prototypes, view)
**   core.population_add(pop, scene, records [, plants, held]) -> k   scene appended as
**                                      prototype k, with room for 'plants' instances; the
**                                      budget counts 'held' bytes the caller keeps too
**   core.population_place(pop, k, x1, x2, x3, y1, y2, y3, z1, z2, z3, t1, t2, t3)
**                                      an instance of prototype k: the images of the
**                                      axes, then the translation -> instances so far
**   scene:instance(i), scene:prototype(k), scene:flatten([opts])
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "population.h"

/* A population: a Scene whose OPTS user value says so (read before the
** scene is taken: a metamethod of that table may close it). */
static lsys_lscene *checkpop (lua_State *L, int i, const char *who) {
  int top = lua_gettop(L), pop = 0;
  lsysL_checkscene(L, i);
  if (lua_getiuservalue(L, i, LSYS_SCENE_OPTS) == LUA_TTABLE) {
    lua_getfield(L, -1, "population");
    pop = lua_toboolean(L, -1);
  }
  lua_settop(L, top);
  if (!pop) luaL_error(L, "%s: a population expected (lsys.population)", who);
  return lsysL_checkscene(L, i);
}

/* core.population(opts) -> an empty population Scene */
static int l_population (lua_State *L) {
  lsys_opts look = {1, "lsys.population: view.", "", LSYS_GOT_TYPE, 0};
  lsys_lscene *S;
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_settop(L, 1);
  S = lsysL_newscene(L);
  lsysL_readlook(L, &look, &S->sc);
  lua_pushboolean(L, 1);
  lua_setfield(L, 1, "population");
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, 2, LSYS_SCENE_OPTS);
  return 1;
}

/* Index of 'tex' in the list at 'list' (1-based), appended when absent. */
static lua_Integer texindex (lua_State *L, int list, int tex) {
  lua_Integer n = luaL_len(L, list), k;
  for (k = 1; k <= n; k++) {
    int same = lua_geti(L, list, k) != LUA_TNIL && lua_rawequal(L, -1, tex);
    lua_pop(L, 1);
    if (same) return k;
  }
  if (n >= 65535) luaL_error(L, "lsys.population: more than 65535 textures");
  lua_pushvalue(L, tex);
  lua_seti(L, list, n + 1);
  return n + 1;
}

/* The texture map of scene 'src' (at 2, whose OPTS user value lists its
** textures) into the population's list (at 'list'): a userdata left on the
** stack, or NULL (and nil) when src has no textures. */
static uint16_t *texmap (lua_State *L, int list, const lsys_lscene *src) {
  uint16_t *map;
  int k, n = src->sc.ntex;
  if (n <= 0 || lua_getiuservalue(L, 2, LSYS_SCENE_OPTS) != LUA_TTABLE ||
      lua_getfield(L, -1, "textures") != LUA_TTABLE) {
    lua_settop(L, list);
    lua_pushnil(L);
    return NULL;
  }
  map = (uint16_t *)lua_newuserdatauv(L, ((size_t)n + 1) * sizeof *map, 0);
  map[0] = 0;
  for (k = 1; k <= n; k++) {
    lua_geti(L, -2, k);
    map[k] = (uint16_t)(luaL_testudata(L, -1, TEXTURE_T) ? texindex(L, list, lua_gettop(L)) : 0);
    lua_pop(L, 1);
  }
  lua_replace(L, list + 1);
  lua_settop(L, list + 1);
  return map;
}

/* Points the population's textures at its list (OPTS.textures). */
static void settextures (lua_State *L, int popidx, int opts) {
  lsys_lscene *S;
  int ntex;
  const lsys_texture *const *tex = lsysL_opttextures(L, opts, "lsys.population", &ntex);
  S = lsysL_checkscene(L, popidx);
  S->sc.tex = tex;
  S->sc.ntex = tex != NULL ? ntex : 0;
  lua_setiuservalue(L, popidx, LSYS_SCENE_TEX);
}

/* core.population_add(pop, scene, records [, plants, held]) -> k (1-based) */
static int l_population_add (lua_State *L) {
  lsys_lscene *P = checkpop(L, 1, "lsys.population"), *S = lsysL_checkscene(L, 2);
  int records = lua_toboolean(L, 3), opts, list, st;
  lua_Integer plants = luaL_optinteger(L, 4, 0);
  lua_Number held = luaL_optnumber(L, 5, 0);
  uint16_t *map;
  lsys_meter mt;
  size_t part;
  luaL_argcheck(L, plants >= 0 && plants <= UINT32_MAX, 4, "a number of plants expected");
  luaL_argcheck(L, held >= 0 && held < 1e18, 5, "a number of bytes expected");
  if (S == P) return luaL_error(L, "lsys.population: a population cannot hold itself");
  if (S->sc.ninst > 0)
    return luaL_error(L, "lsys.population: a prototype must be a plant, not a population");
  lua_settop(L, 3);
  lua_getiuservalue(L, 1, LSYS_SCENE_OPTS);                     /* 4 */
  opts = 4;
  if (lua_getfield(L, opts, "textures") != LUA_TTABLE) {        /* 5 */
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, opts, "textures");
  }
  list = 5;
  map = texmap(L, list, S);                                     /* 6 */
  P = lsysL_checkscene(L, 1);                   /* again: the lists ran Lua code */
  S = lsysL_checkscene(L, 2);
  lsysL_changescene(L, P);
  mt.limit = lsys_common_memory_limit();
  mt.used = lsys_scene_bytes(&P->sc) + (size_t)held;     /* the caller's tables count too */
  mt.hit = 0;
  mt.lock = NULL;
  st = lsys_population_reserve(&P->sc, (size_t)plants, &mt);
  if (st == LSYS_EMEMORY) {
    char b1[32], b2[32];
    double need = (double)mt.used + (double)plants * sizeof *P->sc.inst;
    return luaL_error(L, "lsys.population: %I plants need %s, more than max_memory (%s)",
                      plants, lsys_common_fmtsize(b1, (size_t)need),
                      lsys_common_fmtsize(b2, mt.limit));
  }
  if (st != LSYS_OK) return luaL_error(L, "not enough memory");
  P->sc.meter = P->sc.mesh.meter = &mt;
  st = lsys_population_add(&P->sc, &S->sc, map, records, &part);
  P->sc.meter = P->sc.mesh.meter = NULL;
  if (st == LSYS_EMEMORY) {
    char b[32];
    return luaL_error(L, "lsys.population: the prototypes need more than max_memory (%s)",
                      lsys_common_fmtsize(b, mt.limit));
  }
  if (st == LSYS_ELIMIT)
    return luaL_error(L, "lsys.population: too many prototypes: more than 2^32 vertices or "
                      "65536 palette entries");
  if (st != LSYS_OK) return luaL_error(L, "not enough memory");
  if (map != NULL) settextures(L, 1, opts);
  lua_pushinteger(L, (lua_Integer)part + 1);
  return 1;
}

/* core.population_place(pop, k, 12 numbers) -> the number of instances */
static int l_population_place (lua_State *L) {
  lsys_lscene *P = checkpop(L, 1, "lsys.population");
  lua_Integer k = luaL_checkinteger(L, 2);
  float m[16];
  int i;
  luaL_argcheck(L, k >= 1 && (size_t)k <= P->sc.nparts, 2, "no such prototype");
  memset(m, 0, sizeof m);
  for (i = 0; i < 12; i++) {
    double x = luaL_checknumber(L, 3 + i);
    if (!isfinite(x) || fabs(x) > 3.4e38)
      return luaL_error(L, "lsys.population: a transform must be made of finite numbers");
    m[4 * (i / 3) + i % 3] = (float)x;
  }
  m[15] = 1;
  lsysL_changescene(L, P);
  if (lsys_scene_add_instance(&P->sc, (size_t)k - 1, m) != LSYS_OK)
    return luaL_error(L, "not enough memory");
  lua_pushinteger(L, (lua_Integer)P->sc.ninst);
  return 1;
}

/* ---------------------------------------------------------------------- */
/* Scene methods */

static void setnums (lua_State *L, const char *k, const float *v, int n) {
  double d[16];
  int i;
  for (i = 0; i < n; i++) d[i] = v[i];
  lsysL_pushnums(L, d, n);
  lua_setfield(L, -2, k);
}

/* scene:instance(i) -> { prototype =, matrix = {16, column-major}, at =, rotation =
** {x, y, z, w}, scale = } (rotation and scale when the matrix is T R S), or nil */
static int scene_instance (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  const lsys_instance *in;
  float t[3], q[4], s[3];
  S = lsysL_holdscene(L, 1);                 /* the tables are made as it reads */
  if (i < 1 || (size_t)i > S->sc.ninst) { lua_pushnil(L); return 1; }
  in = &S->sc.inst[i - 1];
  lua_createtable(L, 0, 5);
  lua_pushinteger(L, (lua_Integer)in->part + 1);
  lua_setfield(L, -2, "prototype");
  setnums(L, "matrix", in->m, 16);
  setnums(L, "at", in->m + 12, 3);
  if (lsys_population_trs(in->m, t, q, s)) {
    setnums(L, "rotation", q, 4);
    setnums(L, "scale", s, 3);
  }
  return 1;
}

/* scene:prototype(k) -> { vertices =, triangles =, lines =, records =, instances = }
** with the fields lsys.population keeps about it (model, seed, steps, lstring, ...),
** or nil */
static int scene_prototype (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  const lsys_part *p;
  size_t i, n = 0;
  lua_settop(L, 2);
  S = lsysL_holdscene(L, 1);                 /* 3: the OPTS table's metamethods run */
  if (k < 1 || (size_t)k > S->sc.nparts) { lua_pushnil(L); return 1; }
  p = &S->sc.parts[k - 1];
  for (i = 0; i < S->sc.ninst; i++) n += S->sc.inst[i].part == (uint32_t)(k - 1);
  lua_createtable(L, 0, 12);
  if (lua_getiuservalue(L, 1, LSYS_SCENE_OPTS) == LUA_TTABLE &&
      lua_getfield(L, -1, "prototypes") == LUA_TTABLE &&
      lua_geti(L, -1, k) == LUA_TTABLE) {
    lua_pushnil(L);
    while (lua_next(L, -2)) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_settable(L, -7);
    }
  }
  lua_settop(L, 4);
  lua_pushinteger(L, (lua_Integer)p->nv); lua_setfield(L, -2, "vertices");
  lua_pushinteger(L, (lua_Integer)p->nt); lua_setfield(L, -2, "triangles");
  lua_pushinteger(L, (lua_Integer)p->nl); lua_setfield(L, -2, "lines");
  lua_pushinteger(L, (lua_Integer)p->nr); lua_setfield(L, -2, "records");
  lua_pushinteger(L, (lua_Integer)n); lua_setfield(L, -2, "instances");
  return 1;
}

/* scene:flatten([opts]) -> a new Scene: every instance written out (opts.max_memory:
** the bytes it may take, default the process's budget) */
static int scene_flatten (lua_State *L) {
  static const char *const keys[] = {"max_memory", NULL};
  lsys_lscene *S = lsysL_checkscene(L, 1), *F;
  lsys_meter mt = {0, 0, 0, NULL};
  int st;
  mt.limit = lsys_common_memory_limit();
  if (!lua_isnoneornil(L, 2)) {
    lsys_opts o = {2, "scene:flatten: opts.", "", LSYS_GOT_VALUE, 0};
    luaL_checktype(L, 2, LUA_TTABLE);
    if (lsysL_optunknown(L, &o, keys))
      return luaL_error(L, "scene:flatten: unknown option '%s' (use max_memory)",
                        luaL_tolstring(L, -1, NULL));
    mt.limit = (size_t)lsysL_optnum(L, &o, "max_memory", (double)mt.limit, 0, 1.8e19,
                                    "a positive number of bytes");
  }
  lua_settop(L, 1);
  F = lsysL_newscene(L);
  S = lsysL_checkscene(L, 1);
  st = lsys_population_flatten(&F->sc, &S->sc, &mt);
  if (st == LSYS_EMEMORY) {
    char b1[32], b2[32];
    return luaL_error(L, "scene:flatten: the flattened scene needs %s, more than max_memory "
                      "(%s)", lsys_common_fmtsize(b1, lsys_population_flatbytes(&S->sc)),
                      lsys_common_fmtsize(b2, mt.limit));
  }
  if (st == LSYS_ELIMIT)
    return luaL_error(L, "scene:flatten: more than 2^32 vertices or line segments");
  if (st != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_getiuservalue(L, 1, LSYS_SCENE_OPTS);      /* the textures stay alive with it */
  lua_setiuservalue(L, 2, LSYS_SCENE_OPTS);
  lua_getiuservalue(L, 1, LSYS_SCENE_TEX);
  lua_setiuservalue(L, 2, LSYS_SCENE_TEX);
  return 1;
}

static const luaL_Reg pop_funcs[] = {
  {"population", l_population}, {"population_add", l_population_add},
  {"population_place", l_population_place}, {NULL, NULL}
};

static const luaL_Reg scene_methods[] = {
  {"instance", scene_instance}, {"prototype", scene_prototype}, {"flatten", scene_flatten},
  {NULL, NULL}
};

/* After lsysL_open_scene: adds the methods to the Scene's __methods. */
void lsysL_open_population (lua_State *L) {
  luaL_getmetatable(L, SCENE_T);
  lua_getfield(L, -1, "__methods");
  luaL_setfuncs(L, scene_methods, 0);
  lua_pop(L, 2);
  luaL_setfuncs(L, pop_funcs, 0);
}
