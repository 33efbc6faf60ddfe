/*
** Binding of the turtle and of lsys.Scene (docs/architecture.md, docs/drawing.md): interpret an
** Lstring into a scene, fill query modules, read turtle states back.
**
**   core.interpret(rules, lstring, opts) -> Scene
**   core.query(rules, lstring, opts)     -> number of query modules filled
**   core.turtle_state(rules, lstring, i, opts) -> pos, H, L, U  (after module i, 1-based)
**   core.symbols()                       -> the turtle's symbol table (symbols.h)
**   core.scene_options(scene)            -> the options table a scene keeps
**
** 'opts' is the normalised view under the names of its schema, which owns
** names, defaults and checks (lua/lsys/view.lua): angle, step, line_width,
** width_increment, color, color_increment, line_style, contour_sides,
** tropisms and torques = {{vector=, angle=, elasticity=, increment=,
** torque=}}, contours, surfaces, textures, minimize_twist, palette = {[0]=material, material, ...} with materials
** {diffuse={r,g,b[,a]}, ambient=, specular=, emission=, shininess=};
** and the call's allow_system_calls, records, homomorphism. What C checks
** again only protects memory (sizes, counts, indices).
*/
#include <limits.h>
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "interpret.h"
#include "population.h"
#include "symbols.h"

/* A turtle for one call, owned by the Lua stack: a rule function raising an
** error while the homomorphism is streamed leaves it to the collector. */
static int turtle_gc (lua_State *L) {
  lsys_turtle_free((lsys_turtle *)luaL_checkudata(L, 1, TURTLE_T));
  return 0;
}

static lsys_turtle *newturtle (lua_State *L, int mode) {
  lsys_turtle *t = (lsys_turtle *)lua_newuserdatauv(L, sizeof *t, 0);
  lsys_turtle_init(t);
  t->mode = mode;
  luaL_setmetatable(L, TURTLE_T);
  return t;
}

/* ---------------------------------------------------------------------- */
/* options: the view's fields, numbers also as numerals */

/* The options in the table at 't', named "view option 'k'" in messages. */
static lsys_opts viewopts (lua_State *L, int t) {
  lsys_opts o = {0, "view option '", "'", LSYS_GOT_TYPE, 1};
  o.t = lua_absindex(L, t);
  return o;
}

/* An integer option: a number in [lo, hi], its fraction dropped. Not
** lsysL_optint: its message shows the number, and a fraction is no error. */
static int optwhole (lua_State *L, const lsys_opts *o, const char *k, int def, int lo, int hi) {
  double x = lsysL_optfinite(L, o, k, def);
  if (!(x >= lo && x <= hi)) {
    char got[32];
    snprintf(got, sizeof got, "%g", x);
    luaL_error(L, "%s%s%s must be between %d and %d, got %s", o->pre, k, o->post, lo, hi, got);
  }
  return (int)x;
}

/* A tropism's vector {x, y, z}; the messages name the tropism ('what'). */
static void readvector (lua_State *L, int t, const char *k, double v[3], const char *what) {
  int i;
  if (lua_getfield(L, t, k) != LUA_TTABLE)
    luaL_error(L, "%s: '%s' must be a list of 3 numbers", what, k);
  for (i = 0; i < 3; i++) {
    int ok;
    lua_geti(L, -1, i + 1);
    v[i] = lua_tonumberx(L, -1, &ok);
    if (!ok || !isfinite(v[i]))
      luaL_error(L, "%s: '%s'[%d] must be a finite number", what, k, i + 1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* opts.contours = {[id] = Contour}: an array by id (NULL holes) in a
** userdata left on the stack, which keeps it and its contours alive for the
** run (its user value lists them: the view's table may change meanwhile). */
static void readcontours (lua_State *L, int t, lsys_turtle_opts *o) {
  const lsys_contour **c;
  lua_Integer max = 0;
  if (lua_getfield(L, t, "contours") != LUA_TTABLE) { lua_pop(L, 1); return; }
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_Integer id = lua_isinteger(L, -2) ? lua_tointeger(L, -2) : 0;
    if (id < 1 || id > 65535) luaL_error(L, "view contours: ids must be integers from 1 to 65535");
    if (id > max) max = id;
    lua_pop(L, 1);
  }
  c = (const lsys_contour **)lua_newuserdatauv(L, (size_t)(max + 1) * sizeof *c, 1);
  memset(c, 0, (size_t)(max + 1) * sizeof *c);
  lua_createtable(L, (int)max, 0);
  lua_pushnil(L);                           /* no Lua code runs in this loop */
  while (lua_next(L, -4)) {
    lua_Integer id = lua_tointeger(L, -2);
    c[id] = lsysL_keepcontour(L, -1);
    lua_rawseti(L, -3, id);
  }
  lua_setiuservalue(L, -2, 1);
  lua_remove(L, -2);                        /* keep the array, drop the table */
  o->contours = c;
  o->ncontours = (int)max + 1;
}

/* opts.surfaces = {[name] = {surface=, scale=, texture=, s=, t=}}, copied
** once (the entries' metamethods may change the table) into the user value
** of the array left on the stack: names, entries and surfaces alive. */
static void readsurfaces (lua_State *L, int t, lsys_turtle_opts *o) {
  lsys_surfuse *u;
  int n = 0, k, refs;
  if (lua_getfield(L, t, "surfaces") != LUA_TTABLE) { lua_pop(L, 1); return; }
  lua_newtable(L);                          /* name, entry, surface of each */
  refs = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, -3)) {
    if (lua_type(L, -2) != LUA_TSTRING || lua_type(L, -1) != LUA_TTABLE)
      luaL_error(L, "view surfaces: entries must be name = {surface = ..., ...}");
    if (n >= 4096) luaL_error(L, "view surfaces: at most 4096 surfaces");
    lua_rawseti(L, refs, 3 * n + 2);
    lua_pushvalue(L, -1);
    lua_rawseti(L, refs, 3 * n + 1);
    n++;
  }
  u = (lsys_surfuse *)lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1) * sizeof *u, 1);
  for (k = 0; k < n; k++) {
    lsys_opts e;
    lua_rawgeti(L, refs, 3 * k + 2);
    e = viewopts(L, -1);
    lua_getfield(L, -1, "surface");
    u[k].s = lsysL_keepsurface(L, -1);
    lua_rawseti(L, refs, 3 * k + 3);
    lua_rawgeti(L, refs, 3 * k + 1);
    u[k].name = lua_tostring(L, -1);        /* alive in refs */
    lua_pop(L, 1);
    u[k].scale = lsysL_optfinite(L, &e, "scale", 1);
    u[k].texture = optwhole(L, &e, "texture", 0, 0, 65535);
    u[k].ns = optwhole(L, &e, "s", 4, 1, 256);
    u[k].nt = optwhole(L, &e, "t", u[k].ns, 1, 256);
    lua_pop(L, 1);
  }
  lua_pushvalue(L, refs);
  lua_setiuservalue(L, -2, 1);
  lua_replace(L, refs - 1);                 /* the array where the table was */
  lua_settop(L, refs - 1);
  o->surfaces = u;
  o->nsurfaces = n;
}

/* The tropisms then the torques of the view, {{vector=, angle=, elasticity=,
** increment=, torque=}} each, into o->trop. */
static void readtropisms (lua_State *L, int t, lsys_turtle_opts *o) {
  static const char *const lists[2] = {"tropisms", "torques"};
  int l, n = 0;
  for (l = 0; l < 2; l++) {
    int m, k, tt;
    if (lua_getfield(L, t, lists[l]) != LUA_TTABLE) { lua_pop(L, 1); continue; }
    m = (int)luaL_len(L, -1);
    tt = lua_gettop(L);
    if (m > LSYS_MAXTROPISMS - n)
      luaL_error(L, "the view has %d tropisms and torques; at most %d are supported",
                 n + m, LSYS_MAXTROPISMS);
    for (k = 0; k < m; k++) {
      lsys_tropism *tp = &o->trop[n];
      lsys_opts e;
      char what[48];
      snprintf(what, sizeof what, "view tropism %d", ++n);
      if (lua_geti(L, tt, k + 1) != LUA_TTABLE) luaL_error(L, "%s must be a table", what);
      e = viewopts(L, -1);
      readvector(L, e.t, "vector", tp->vec, what);
      tp->angle = lsysL_optfinite(L, &e, "angle", 0);
      tp->elasticity = lsysL_optfinite(L, &e, "elasticity", 0);
      tp->increment = lsysL_optfinite(L, &e, "increment", 0);
      tp->intensity = lsysL_optfinite(L, &e, "intensity", 1);
      lua_getfield(L, -1, "torque");
      tp->torque = lua_toboolean(L, -1);
      lua_pop(L, 2);
    }
    lua_pop(L, 1);
  }
  o->ntrop = n;
  /* old_tropism = {vector =, elasticity =, increment =} (lsys.view checked it) */
  if (lua_getfield(L, t, "old_tropism") == LUA_TTABLE) {
    lsys_opts e = viewopts(L, -1);
    double len;
    readvector(L, e.t, "vector", o->otrop, "view old_tropism");
    len = sqrt(o->otrop[0] * o->otrop[0] + o->otrop[1] * o->otrop[1] +
               o->otrop[2] * o->otrop[2]);
    if (!(len > 0) || !isfinite(len))
      luaL_error(L, "view old_tropism: the vector must be finite and not 0");
    o->otrop[0] /= len; o->otrop[1] /= len; o->otrop[2] /= len;
    o->oelast = lsysL_optfinite(L, &e, "elasticity", 0);
    o->oincr = lsysL_optfinite(L, &e, "increment", 0);
  }
  lua_pop(L, 1);
}

/* Reads the turtle options from the table at 't'. Leaves three values on
** the stack that keep the contour, surface and texture arrays alive. */
static void readopts (lua_State *L, int t, lsys_turtle_opts *o) {
  lsys_opts v;
  const char *style;
  luaL_checktype(L, t, LUA_TTABLE);
  v = viewopts(L, t);
  lsys_turtle_defaults(o);
  o->angle = lsysL_optfinite(L, &v, "angle", o->angle);
  o->step = lsysL_optfinite(L, &v, "step", o->step);
  o->width = lsysL_optfinite(L, &v, "line_width", o->width);
  o->dwidth = lsysL_optfinite(L, &v, "width_increment", o->dwidth);
  o->color = optwhole(L, &v, "color", o->color, 0, 65535);
  o->dcolor = optwhole(L, &v, "color_increment", o->dcolor, -65535, 65535);
  o->sides = optwhole(L, &v, "contour_sides", o->sides, 3, 1024);
  lua_getfield(L, t, "allow_system_calls");
  o->allow_system = lua_toboolean(L, -1);
  lua_getfield(L, t, "records");
  o->norecords = lua_type(L, -1) == LUA_TBOOLEAN && !lua_toboolean(L, -1);
  lua_pop(L, 2);
  lua_getfield(L, t, "line_style");
  style = lua_isnil(L, -1) ? "line" : lua_tostring(L, -1);
  if (style == NULL) luaL_error(L, "view option 'line_style' must be a string");
  if (strcmp(style, "line") == 0) o->style = LSYS_STYLE_LINE;
  else if (strcmp(style, "polygon") == 0) o->style = LSYS_STYLE_POLYGON;
  else if (strcmp(style, "cylinder") == 0) o->style = LSYS_STYLE_CYLINDER;
  else luaL_error(L, "view option 'line_style' must be \"line\", \"polygon\" or \"cylinder\", "
                  "got \"%s\"", style);
  lua_pop(L, 1);
  readtropisms(L, t, o);
  lua_getfield(L, t, "minimize_twist");
  o->minimize_twist = lua_isnil(L, -1) || lua_toboolean(L, -1);
  lua_pop(L, 1);
  readcontours(L, t, o);
  if (o->contours == NULL) lua_pushnil(L);
  readsurfaces(L, t, o);
  if (o->surfaces == NULL) lua_pushnil(L);
  o->tex = lsysL_opttextures(L, t, "view", &o->ntex);
}

static void readcolor (lua_State *L, int t, const char *k, float *c, int required) {
  int i, n;
  if (lua_getfield(L, t, k) != LUA_TTABLE) {
    if (required) luaL_error(L, "palette material: '%s' must be a list {r, g, b}", k);
    lua_pop(L, 1);
    return;
  }
  n = (int)luaL_len(L, -1);
  if (n < 3 || n > 4) luaL_error(L, "palette material: '%s' must have 3 or 4 components", k);
  for (i = 0; i < n; i++) {
    int ok;
    lua_geti(L, -1, i + 1);
    c[i] = (float)lua_tonumberx(L, -1, &ok);
    if (!ok || !(c[i] >= 0 && c[i] <= 1))
      luaL_error(L, "palette material: '%s'[%d] must be a number in [0, 1]", k, i + 1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* palette = {[0] = m0, m1, m2, ...}: index c uses entry c % n */
static void readpalette (lua_State *L, int t, lsys_lscene *S) {
  lua_Integer n, k;
  if (lua_getfield(L, t, "palette") != LUA_TTABLE) {
    lua_pop(L, 1);
    S->sc.pal = (lsys_material *)LSYS_MALLOC(sizeof *S->sc.pal);
    if (S->sc.pal == NULL) luaL_error(L, "not enough memory");
    lsys_mesh_material_color(S->sc.pal, 0.6, 0.6, 0.6);
    S->sc.npal = S->sc.palcap = 1;
    return;
  }
  n = luaL_len(L, -1) + 1;
  if (n > 65536) luaL_error(L, "the palette has more than 65536 entries");
  S->sc.pal = (lsys_material *)LSYS_MALLOC((size_t)n * sizeof *S->sc.pal);
  if (S->sc.pal == NULL) luaL_error(L, "not enough memory");
  S->sc.npal = S->sc.palcap = (size_t)n;
  for (k = 0; k < n; k++) {
    lsys_material *m = &S->sc.pal[k];
    lsys_opts e;
    lsys_mesh_material_color(m, 0.6, 0.6, 0.6);
    if (lua_geti(L, -1, k) != LUA_TTABLE) {
      if (k == 0) { lua_pop(L, 1); continue; }
      luaL_error(L, "palette entry %d must be a material table", (int)k);
    }
    e = viewopts(L, -1);
    readcolor(L, -1, "diffuse", m->diffuse, 1);
    m->ambient[0] = 0.3f * m->diffuse[0];
    m->ambient[1] = 0.3f * m->diffuse[1];
    m->ambient[2] = 0.3f * m->diffuse[2];
    m->ambient[3] = m->diffuse[3];
    readcolor(L, -1, "ambient", m->ambient, 0);
    readcolor(L, -1, "specular", m->specular, 0);
    readcolor(L, -1, "emission", m->emission, 0);
    m->shininess = (float)lsysL_optfinite(L, &e, "shininess", m->shininess);
    if (m->shininess < 0 || m->shininess > 128)
      luaL_error(L, "palette entry %d: shininess must be in [0, 128]", (int)k);
    lua_pop(L, 1);
  }
  if (n > 1) {                                /* no [0]: it repeats entry 1 */
    if (lua_geti(L, -1, 0) == LUA_TNIL) S->sc.pal[0] = S->sc.pal[1];
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

/* ---------------------------------------------------------------------- */
/* running the turtle with the homomorphism streamed from the rules */

/* What the protected run of the turtle needs (lsysL_rules_run). */
typedef struct turtlecall {
  lsys_turtle *t;
  lsys_lstring *s;
  int homo;
} turtlecall;

/* The turtle's run with the model bound: interpret.h streams the
** homomorphism and attaches the model's memory budget. */
static int doturtle (lua_State *L, lsys_rules *m, void *ud) {
  turtlecall *x = (turtlecall *)ud;
  return lsys_interpret_run(m, x->t, x->s, lsysL_getalphabet(L), x->homo);
}

/* Runs the turtle over the Lstring at 2 with the rules at 1 and options at
** 'opt'. Raises on error (after cleaning up). */
static void turtlerun (lua_State *L, lsys_turtle *t, lsys_turtle_opts *o, int opt) {
  static const int lstr[1] = {2};
  turtlecall x;
  int st;
  x.s = t->mode == LSYS_TURTLE_DRAW ? lsysL_checklstring_any(L, 2) : checklstring(L, 2);
  x.t = t;
  readopts(L, opt, o);
  lua_getfield(L, opt, "homomorphism");
  x.homo = lua_isnil(L, -1) || lua_toboolean(L, -1);
  lua_pop(L, 1);
  t->o = o;
  st = lsysL_rules_run(L, 1, "interpret", doturtle, &x, lstr, 1);
  if (st != LSYS_OK) lsysL_raise(L, st, &t->err, 1);
  if (t->warn.code != 0) {             /* through warn(), as the library's warnings go */
    lua_warning(L, "lsys: ", 1);
    lua_warning(L, t->warn.msg, 0);
  }
}

/* core.interpret(rules, lstring, opts) -> Scene */
static int l_interpret (lua_State *L) {
  lsys_turtle *t;
  lsys_turtle_opts o;
  lsys_opts look;
  lsys_lscene *S;
  luaL_checktype(L, 3, LUA_TTABLE);
  lua_settop(L, 3);
  S = lsysL_newscene(L);      /* 4 */
  readpalette(L, 3, S);
  look = viewopts(L, 3);                   /* how to look at the scene, from the view */
  lsysL_readlook(L, &look, &S->sc);
  t = newturtle(L, LSYS_TURTLE_DRAW);                        /* 5 */
  t->scene = &S->sc;
  turtlerun(L, t, &o, 3);
  lsys_turtle_free(t);
  S->sc.tex = o.tex;            /* kept: readopts left their array on top */
  S->sc.ntex = o.tex != NULL ? o.ntex : 0;
  lua_setiuservalue(L, 4, LSYS_SCENE_TEX);
  lua_pushvalue(L, 1); lua_setiuservalue(L, 4, LSYS_SCENE_RULES);
  lua_pushvalue(L, 2); lua_setiuservalue(L, 4, LSYS_SCENE_LSTRING);
  lua_pushvalue(L, 3); lua_setiuservalue(L, 4, LSYS_SCENE_OPTS);
  lua_gc(L, LUA_GCSTEP, (int)((S->sc.mesh.nv * 41 + S->sc.mesh.nt * 12 +
                               S->sc.nrec * sizeof *S->sc.rec +
                               S->sc.nshape * sizeof *S->sc.shape +
                               S->sc.npt * 3 * sizeof *S->sc.recpt) >> 10));
  lua_settop(L, 4);
  return 1;
}

/* core.query(rules, lstring, opts) -> number of query modules filled */
static int l_query (lua_State *L) {
  lsys_turtle *t;
  lsys_turtle_opts o;
  size_t n;
  luaL_checktype(L, 3, LUA_TTABLE);
  lua_settop(L, 3);
  t = newturtle(L, LSYS_TURTLE_QUERY);
  turtlerun(L, t, &o, 3);
  n = t->nqueries;
  lsys_turtle_free(t);
  lua_pushinteger(L, (lua_Integer)n);
  return 1;
}

#define pushvec(L, v) lsysL_pushnums((L), (v), 3)

static int envq_gc (lua_State *L) {
  lsys_turtle_envfree((lsys_envqueries *)luaL_checkudata(L, 1, ENVQ_T));
  return 0;
}

/* A list of n numbers at p, on the stack. */
static void pushlist (lua_State *L, const double *p, uint32_t n) {
  uint32_t k;
  lua_createtable(L, (int)n, 0);
  for (k = 0; k < n; k++) {
    lua_pushnumber(L, p[k]);
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
}

/* One query of 'Q' as a table: index (nil for a module the homomorphism made), params,
** position, heading, left, up, width, scale, and following with following_params (nil
** at the end of the string or of the expansion). */
static void pushenvquery (lua_State *L, const lsys_envqueries *Q, const lsys_envquery *q,
                          const lsys_lstring *s, const lsys_alphabet *ab) {
  int made = q->mod == LSYS_ENVQ_MADE;
  lua_createtable(L, 0, 12);
  if (!made) {
    lua_pushinteger(L, (lua_Integer)q->mod + 1);
    lua_setfield(L, -2, "index");
  }
  pushlist(L, (made ? Q->pool : s->par) + q->par, q->np);
  lua_setfield(L, -2, "params");
  pushvec(L, q->pos); lua_setfield(L, -2, "position");
  pushvec(L, q->H); lua_setfield(L, -2, "heading");
  pushvec(L, q->L); lua_setfield(L, -2, "left");
  pushvec(L, q->U); lua_setfield(L, -2, "up");
  lua_pushnumber(L, q->width); lua_setfield(L, -2, "width");
  lua_pushnumber(L, q->scale); lua_setfield(L, -2, "scale");
  lua_pushinteger(L, q->color); lua_setfield(L, -2, "color");
  if (q->next != LSYS_ENVQ_NONE) {
    lua_pushstring(L, lsys_alphabet_name(ab, q->next));
    lua_setfield(L, -2, "following");
    pushlist(L, (made ? Q->pool : s->par) + q->nextpar, q->nextnp);
    lua_setfield(L, -2, "following_params");
  }
}

/* What one query takes as a Lua table with its lists (pushenvquery), about. */
#define ENVQ_TABLE_BYTES 1024

/* cpfg's ids of the queries (lsys.environment.program): the byte offset of each ?E of the
** string in cpfg's string, from the first one's (a module takes its name's bytes, and
** 1 + 5n for n > 0 parameters; a ?E is two modules there, ? and E, whose sizes add to the
** same), 1 for a ?E the homomorphism made. The queries of the string come in its order. */
static void cpfgids (const lsys_envqueries *Q, const lsys_lstring *s, const lsys_alphabet *ab,
                     double *id) {
  size_t k, i = 0, at = 0, first = (size_t)-1;
  for (k = 0; k < Q->n; k++) {
    const lsys_envquery *q = &Q->q[k];
    if (q->mod == LSYS_ENVQ_MADE) { id[k] = 1; continue; }
    for (; i < q->mod && i < s->n; i++) {
      uint16_t c = s->sym8 != NULL ? (uint16_t)LSYS_CODE(s->sym8[i], 0) : s->code[i];
      uint32_t np = LSYS_CNP(c);
      if (first != (size_t)-1)
        at += strlen(lsys_alphabet_name(ab, LSYS_CSYM(c))) + (np > 0 ? 1 + 5 * (size_t)np : 0);
    }
    if (first == (size_t)-1) first = q->mod;
    id[k] = (double)at;
  }
}

/* core.environment(rules, lstring, opts) -> queries, filled: the query pass of an open
** L-system (docs/open.md): fills ?P ?H ?U ?L as core.query does and returns the ?E
** modules met, each a table (pushenvquery), in the order the turtle met them. */
static int l_environment (lua_State *L) {
  lsys_turtle *t;
  lsys_turtle_opts o;
  lsys_envqueries *Q;
  lsys_lstring *s = checklstring(L, 2);
  const lsys_lrules *R = lsysL_checkrules(L, 1);
  lsys_meter mt = {0, 0, 0, NULL};
  double *ids;
  size_t n, k;
  char b[32];
  luaL_checktype(L, 3, LUA_TTABLE);
  lua_settop(L, 3);
  /* the queries and the tables they become are the model's memory too (max_memory) */
  mt.limit = R->m.max_memory != 0 ? R->m.max_memory : lsys_common_memory_limit();
  Q = (lsys_envqueries *)lua_newuserdatauv(L, sizeof *Q, 0);    /* 4: freed however it ends */
  memset(Q, 0, sizeof *Q);
  luaL_setmetatable(L, ENVQ_T);
  t = newturtle(L, LSYS_TURTLE_QUERY);                         /* 5 */
  t->envq = Q;
  t->meter = &mt;
  turtlerun(L, t, &o, 3);
  n = t->nqueries;
  lsys_turtle_free(t);
  if (!lsys_common_meter_fits(&mt, Q->n * ENVQ_TABLE_BYTES))
    return luaL_error(L, "the environment's %I queries would need more than max_memory (%s) "
                      "as Lua tables (set max_memory in the model, or LSYS_MAX_MEMORY)",
                      (lua_Integer)Q->n, lsys_common_fmtsize(b, mt.limit));
  s = checklstring(L, 2);          /* a rule function may have closed nothing, but check */
  luaL_checkstack(L, 4, "too many queries");
  ids = (double *)lua_newuserdatauv(L, (Q->n + 1) * sizeof *ids, 0);     /* 6 */
  cpfgids(Q, s, lsysL_getalphabet(L), ids);
  lua_createtable(L, Q->n > INT_MAX ? INT_MAX : (int)Q->n, 0);
  for (k = 0; k < Q->n; k++) {
    pushenvquery(L, Q, &Q->q[k], s, lsysL_getalphabet(L));
    lua_pushinteger(L, (lua_Integer)ids[k]);
    lua_setfield(L, -2, "cpfg_id");
    lua_rawseti(L, -2, (lua_Integer)k + 1);
  }
  lsys_turtle_envfree(Q);
  lua_pushinteger(L, (lua_Integer)n);
  return 2;
}

static void pushvecf (lua_State *L, const float *v) {
  double d[3] = {v[0], v[1], v[2]};
  pushvec(L, d);
}

/* core.turtle_state(rules, lstring, i, opts) -> pos, H, L, U, width, color */
static int l_turtle_state (lua_State *L) {
  lsys_turtle *t;
  lsys_turtle_opts o;
  lsys_lstring *s = checklstring(L, 2);
  lua_Integer i = luaL_checkinteger(L, 3);
  luaL_argcheck(L, i >= 0 && (size_t)i <= s->n, 3, "module index out of range");
  luaL_checktype(L, 4, LUA_TTABLE);
  lua_settop(L, 4);
  t = newturtle(L, LSYS_TURTLE_STATE);
  t->stop = (size_t)i;
  turtlerun(L, t, &o, 4);
  pushvec(L, t->state.pos);
  pushvec(L, t->state.H);
  pushvec(L, t->state.L);
  pushvec(L, t->state.U);
  lua_pushnumber(L, t->state.width);
  lua_pushinteger(L, t->state.color);
  lsys_turtle_free(t);
  return 6;
}

/* ---------------------------------------------------------------------- */
/* Scene */

/* __gc and __close: idempotent; every method of a closed scene raises. A
** held scene is not closed (the collector cannot finalize it: a running
** method holds it on the stack, but Lua code can call __close). */
static int scene_gc (lua_State *L) {
  lsys_lscene *S = (lsys_lscene *)luaL_checkudata(L, 1, SCENE_T);
  if (S->inited) {
    if (!lsysL_finalizing(L))
      lsysL_checkidle(L, S->busy, "cannot close a Scene while it is in use");
    lsys_scene_free(&S->sc);
    S->inited = 0;
  }
  return 0;
}

static size_t countrec (const lsys_lscene *S, int kind) {
  size_t k, n = 0;
  for (k = 0; k < S->sc.nrec; k++) n += lsys_scene_reckind(&S->sc, k) == kind;
  return n;
}

/* The sizes of a scene as drawn: a population's instances written out. */
static int scene_index (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  const char *k = luaL_checkstring(L, 2);
  size_t nv, nt, nl;
  S = lsysL_checkscene(L, 1);                /* again: converting a number allocates */
  lsys_population_size(&S->sc, &nv, &nt, &nl);
  if (strcmp(k, "ntriangles") == 0) lua_pushinteger(L, (lua_Integer)nt);
  else if (strcmp(k, "nvertices") == 0) lua_pushinteger(L, (lua_Integer)nv);
  else if (strcmp(k, "nlines") == 0) lua_pushinteger(L, (lua_Integer)nl);
  else if (strcmp(k, "ninstances") == 0) lua_pushinteger(L, (lua_Integer)S->sc.ninst);
  else if (strcmp(k, "nprototypes") == 0)
    lua_pushinteger(L, (lua_Integer)(S->sc.ninst > 0 ? S->sc.nparts : 0));
  else if (strcmp(k, "bytes") == 0) lua_pushinteger(L, (lua_Integer)lsys_scene_bytes(&S->sc));
  else if (strcmp(k, "nrecords") == 0) lua_pushinteger(L, (lua_Integer)S->sc.nrec);
  else if (strcmp(k, "nsegments") == 0)
    lua_pushinteger(L, (lua_Integer)countrec(S, LSYS_REC_SEGMENT));
  else if (strcmp(k, "lstring") == 0) lua_getiuservalue(L, 1, LSYS_SCENE_LSTRING);
  else {
    lua_getmetatable(L, 1);
    lua_getfield(L, -1, "__methods");
    lua_getfield(L, -1, k);
  }
  return 1;
}

static int scene_tostring (lua_State *L) {
  lsys_lscene *S = (lsys_lscene *)luaL_checkudata(L, 1, SCENE_T);
  if (!S->inited) {
    lua_pushliteral(L, "lsys.Scene (closed)");
    return 1;
  }
  if (S->sc.ninst > 0) {
    size_t nv, nt, nl;
    lsys_population_size(&S->sc, &nv, &nt, &nl);
    lua_pushfstring(L, "lsys.Scene: a population of %d plant%s of %d prototype%s, %d "
                    "triangles, %d line segments", (int)S->sc.ninst, S->sc.ninst == 1 ? "" : "s",
                    (int)S->sc.nparts, S->sc.nparts == 1 ? "" : "s", (int)nt, (int)nl);
    return 1;
  }
  lua_pushfstring(L, "lsys.Scene: %d triangles, %d line segments, %d turtle records",
                  (int)S->sc.mesh.nt, (int)S->sc.mesh.nl, (int)S->sc.nrec);
  return 1;
}

/* scene:bounds() -> {xmin, ymin, zmin}, {xmax, ymax, zmax} (nil when empty) */
static int scene_bounds (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  double lo[3], hi[3];
  if (!lsys_scene_bounds(&S->sc, lo, hi)) { lua_pushnil(L); return 1; }
  pushvec(L, lo);
  pushvec(L, hi);
  return 2;
}

/* scene:area() -> total area of the triangles (as drawn: a population's instances) */
static int scene_area (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_pushnumber(L, lsys_population_area(&S->sc));
  return 1;
}

/* Pushes the table of record k (0-based) of S: the record (and its
** stiffness) is copied first, the tables are made from the copy (an
** allocation may run a finalizer that closes S). */
static void pushrecord (lua_State *L, const lsys_lscene *S, size_t k) {
  lsys_trec rec, *r = &rec;
  float l[3], st[3];
  lsys_scene_record(&S->sc, k, &rec);
  if (r->stiff != LSYS_NOREC) memcpy(st, S->sc.stiff + 3 * r->stiff, sizeof st);
  l[0] = r->H[1] * r->U[2] - r->H[2] * r->U[1];          /* L = H x U */
  l[1] = r->H[2] * r->U[0] - r->H[0] * r->U[2];
  l[2] = r->H[0] * r->U[1] - r->H[1] * r->U[0];
  lua_createtable(L, 0, 12);
  lua_pushstring(L, lsysL_recordkind(r->kind)); lua_setfield(L, -2, "kind");
  lua_pushinteger(L, (lua_Integer)r->module + 1); lua_setfield(L, -2, "module");
  if (r->parent != LSYS_NOREC) {
    lua_pushinteger(L, (lua_Integer)r->parent + 1);
    lua_setfield(L, -2, "parent");
  }
  {
    float p0[3];
    int j;
    for (j = 0; j < 3; j++) p0[j] = r->p1[j] - r->len * r->H[j];
    pushvecf(L, p0); lua_setfield(L, -2, "p0");
  }
  lua_pushnumber(L, r->len); lua_setfield(L, -2, "length");
  pushvecf(L, r->p1); lua_setfield(L, -2, "p1");
  pushvecf(L, r->H); lua_setfield(L, -2, "H");
  pushvecf(L, l); lua_setfield(L, -2, "L");
  pushvecf(L, r->U); lua_setfield(L, -2, "U");
  lua_pushnumber(L, r->w0); lua_setfield(L, -2, "w0");
  lua_pushnumber(L, r->w1); lua_setfield(L, -2, "w1");
  lua_pushinteger(L, r->color); lua_setfield(L, -2, "color");
  if (r->stiff != LSYS_NOREC) {
    pushvecf(L, st);
    lua_setfield(L, -2, "stiffness");
  }
}

/* scene:record(k) -> table for turtle record k (1-based), or nil */
static int scene_record (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  if (k < 1 || (size_t)k > S->sc.nrec) { lua_pushnil(L); return 1; }
  pushrecord(L, S, (size_t)k - 1);
  return 1;
}

static int records_iter (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2) + 1;
  if (k < 1 || (size_t)k > S->sc.nrec) return 0;
  lua_pushinteger(L, k);
  pushrecord(L, S, (size_t)k - 1);
  return 2;
}

/* for k, rec in scene:records() do ... end */
static int scene_records (lua_State *L) {
  lsysL_checkscene(L, 1);
  lua_pushcfunction(L, records_iter);
  lua_pushvalue(L, 1);
  lua_pushinteger(L, 0);
  return 3;
}

/* scene:find(module) -> index of the first record of module i (1-based), or nil */
static int scene_find (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer m = luaL_checkinteger(L, 2);
  size_t k;
  for (k = 0; k < S->sc.nrec; k++)
    if ((lua_Integer)S->sc.rec[k].module + 1 == m) {
      lua_pushinteger(L, (lua_Integer)k + 1);
      return 1;
    }
  lua_pushnil(L);
  return 1;
}

/* scene:edges(k) -> the wireframe of what record k drew: a list of edges
** {{x, y, z}, {x, y, z}} of its triangles (empty for lines and records that
** drew none; a leaf or flower gives its whole outline and inner edges) */
static int scene_edges (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  const lsys_rshape *r;
  uint32_t *e;
  size_t n, i;
  S = lsysL_holdscene(L, 1);
  if (k < 1 || (size_t)k > S->sc.nrec) return luaL_error(L, "scene:edges: no record %d", (int)k);
  r = lsys_scene_recshape(&S->sc, (size_t)k - 1);
  e = (uint32_t *)lua_newuserdatauv(L, 6 * (size_t)r->ntri * sizeof *e + 1, 0);
  n = lsys_mesh_edges(&S->sc.mesh, r->tri0, r->ntri, e);
  lua_createtable(L, (int)n, 0);
  for (i = 0; i < n; i++) {
    lua_createtable(L, 2, 0);
    pushvecf(L, S->sc.mesh.pos + 3 * (size_t)e[2 * i]);
    lua_rawseti(L, -2, 1);
    pushvecf(L, S->sc.mesh.pos + 3 * (size_t)e[2 * i + 1]);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, (lua_Integer)i + 1);
  }
  return 1;
}

/* scene:vertices(k) -> the vertices record k's triangles use, in the order the
** turtle made them: for a polygon its vertices as the turtle gave them (the mesh
** keeps them in order; ear clipping only indexes them); {} for a record without
** triangles. A list of {x, y, z}. */
static int scene_vertices (lua_State *L) {
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  const lsys_rshape *r;
  uint32_t lo = UINT32_MAX, hi = 0, i;
  size_t t;
  S = lsysL_holdscene(L, 1);
  if (k < 1 || (size_t)k > S->sc.nrec)
    return luaL_error(L, "scene:vertices: no record %d", (int)k);
  r = lsys_scene_recshape(&S->sc, (size_t)k - 1);
  for (t = 0; t < 3 * (size_t)r->ntri; t++) {
    uint32_t v = S->sc.mesh.tri[3 * (size_t)r->tri0 + t];
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  lua_createtable(L, r->ntri > 0 ? (int)(hi - lo + 1) : 0, 0);
  if (r->ntri > 0)
    for (i = lo; i <= hi; i++) {
      pushvecf(L, S->sc.mesh.pos + 3 * (size_t)i);
      lua_rawseti(L, -2, (lua_Integer)(i - lo) + 1);
    }
  return 1;
}

/* scene:turtle(i) -> pos, H, L, U, width, color after module i (0: the start) */
static int scene_turtle (lua_State *L) {
  lua_Integer i;
  if (lsysL_checkscene(L, 1)->sc.ninst > 0)
    return luaL_error(L, "scene:turtle: a population has no Lstring of its own (its prototypes' "
                      "are in scene:prototype(k).lstring)");
  i = luaL_checkinteger(L, 2);
  lua_settop(L, 2);
  lua_getiuservalue(L, 1, LSYS_SCENE_LSTRING);
  {
    lsys_lstring *s = checklstring(L, -1);
    if (i < 0 || (size_t)i > s->n)
      return luaL_error(L, "scene:turtle: no module %I (the scene's Lstring has %I; 0 is the "
                        "start)", (LUAI_UACINT)i, (LUAI_UACINT)s->n);
  }
  lua_pop(L, 1);
  lua_pushcfunction(L, l_turtle_state);
  lua_getiuservalue(L, 1, LSYS_SCENE_RULES);
  lua_getiuservalue(L, 1, LSYS_SCENE_LSTRING);
  lua_pushinteger(L, i);
  lua_getiuservalue(L, 1, LSYS_SCENE_OPTS);
  lua_call(L, 4, 6);
  return 6;
}

/* scene:colors() -> {[c] = n}: triangles and line segments drawn in colour index c */
static int scene_colors (lua_State *L) {
  uint32_t *n = (uint32_t *)lua_newuserdatauv(L, LSYS_MESH_NCOLORS * sizeof *n, 0);
  size_t c;
  lsys_mesh_color_counts(&lsysL_checkscene(L, 1)->sc.mesh, n);    /* checked after allocating */
  lua_newtable(L);
  for (c = 0; c < LSYS_MESH_NCOLORS; c++)
    if (n[c] > 0) { lua_pushinteger(L, (lua_Integer)n[c]); lua_rawseti(L, -2, (lua_Integer)c); }
  return 1;
}

/* scene:look(opts): how the scene is looked at from now on (its camera,
** light and background: the look fields of a view, lsysL_readlook). */
static int scene_look (lua_State *L) {
  static const char *const keys[] = {
    "background", "light", "lights", "viewpoint", "target", "up", "direction", "projection",
    "fov", "twist", "zoom", "fit", NULL
  };
  lsys_lscene *S = lsysL_checkscene(L, 1);
  lsys_opts o = {2, "scene:look: opts.", "", LSYS_GOT_TYPE, 0};
  lsys_scene sc;
  luaL_checktype(L, 2, LUA_TTABLE);
  if (lsysL_optunknown(L, &o, keys))
    return luaL_error(L, "scene:look: unknown option '%s'", luaL_tolstring(L, -1, NULL));
  sc = S->sc;                   /* read into a copy: an error leaves the scene as it was */
  lsysL_readlook(L, &o, &sc);
  S = lsysL_checkscene(L, 1);
  S->sc.cam = sc.cam;
  memcpy(S->sc.light, sc.light, sizeof sc.light);
  memcpy(S->sc.lights, sc.lights, sizeof sc.lights);
  S->sc.nlights = sc.nlights;
  memcpy(S->sc.background, sc.background, sizeof sc.background);
  return 0;
}

/* core.scene_options(scene) -> the options table the scene keeps: the view it was
** interpreted with, or what lsys.population gave it ({population = true, view = ...});
** nil when it keeps none. Raises for anything but a Scene; answers for a closed one
** too, as it reads only the user value, which a close leaves (lsys.render of a closed
** population then raises what the renderer says). */
static int l_scene_options (lua_State *L) {
  luaL_checkudata(L, 1, SCENE_T);
  lua_getiuservalue(L, 1, LSYS_SCENE_OPTS);
  return 1;
}

/* core.symbols() -> { {name=, op=, split=, query=}, ... }: the rows of the turtle's
** symbol table (symbols.h) that have a module name, in its order. 'split' is how the
** parallel turtle treats the symbol ("cross": keeps the string on one thread, "state",
** "open", "close", "segment", "shape", "record"); 'query' is true for the query modules.
** A new table each call. */
static int l_symbols (lua_State *L) {
  static const char *const split[] = {"cross", "state", "open", "close", "segment", "shape",
                                      "record"};
  int k, n = 0;
  lua_createtable(L, LSYS_NSYMBOLS, 0);
  for (k = 0; k < LSYS_NSYMBOLS; k++) {
    const lsys_symbol *r = &lsys_symbols[k];
    if (r->name == NULL) continue;
    lua_createtable(L, 0, 4);
    lua_pushstring(L, r->name);
    lua_setfield(L, -2, "name");
    lua_pushstring(L, r->op);
    lua_setfield(L, -2, "op");
    lua_pushstring(L, r->split < sizeof split / sizeof split[0] ? split[r->split] : "cross");
    lua_setfield(L, -2, "split");
    lua_pushboolean(L, r->query);
    lua_setfield(L, -2, "query");
    lua_rawseti(L, -2, ++n);
  }
  return 1;
}

static const luaL_Reg scene_methods[] = {
  {"bounds", scene_bounds},
  {"look", scene_look},
  {"area", scene_area},
  {"record", scene_record},
  {"records", scene_records},
  {"find", scene_find},
  {"edges", scene_edges},
  {"vertices", scene_vertices},
  {"turtle", scene_turtle},
  {"colors", scene_colors},
  {NULL, NULL}
};

static const luaL_Reg scene_meta[] = {
  {"__gc", scene_gc},
  {"__close", scene_gc},
  {"__index", scene_index},
  {"__tostring", scene_tostring},
  {NULL, NULL}
};

static const luaL_Reg scene_funcs[] = {
  {"interpret", l_interpret},
  {"query", l_query},
  {"environment", l_environment},
  {"turtle_state", l_turtle_state},
  {"symbols", l_symbols},
  {"scene_options", l_scene_options},
  {NULL, NULL}
};

static const luaL_Reg turtle_meta[] = {
  {"__gc", turtle_gc}, {NULL, NULL}
};

static const luaL_Reg envq_meta[] = {
  {"__gc", envq_gc}, {NULL, NULL}
};

/* The Scene's __index (scene_index) finds its methods in __methods. */
void lsysL_open_scene (lua_State *L) {
  lsysL_createmeta(L, SCENE_T, scene_meta, NULL);
  luaL_getmetatable(L, SCENE_T);
  luaL_newlib(L, scene_methods);
  lua_setfield(L, -2, "__methods");
  lua_pop(L, 1);
  lsysL_createmeta(L, TURTLE_T, turtle_meta, NULL);
  lsysL_createmeta(L, ENVQ_T, envq_meta, NULL);
  luaL_setfuncs(L, scene_funcs, 0);
}
