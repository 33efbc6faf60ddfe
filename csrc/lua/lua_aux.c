/*
** The floor of the Lua bindings (lua_aux.h): metatables, the alphabet,
** errors, the shared userdata, running a model's operations, option readers.
*/
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "lua_aux.h"

#define ALPHABET_KEY "lsys.alphabet"   /* the state's alphabet, in the registry */

void lsysL_createmeta (lua_State *L, const char *tname, const luaL_Reg *meta,
                       const luaL_Reg *methods) {
  luaL_newmetatable(L, tname);
  luaL_setfuncs(L, meta, 0);
  if (methods != NULL) {
    int n = 0;
    while (methods[n].name != NULL) n++;
    lua_createtable(L, 0, n);
    luaL_setfuncs(L, methods, 0);
    lua_setfield(L, -2, "__index");
  }
  lua_pop(L, 1);
}

static int alphabet_gc (lua_State *L) {
  lsys_alphabet_free((lsys_alphabet *)luaL_checkudata(L, 1, ALPHABET_T));
  return 0;
}

lsys_alphabet *lsysL_getalphabet (lua_State *L) {
  lsys_alphabet *a;
  if (lua_getfield(L, LUA_REGISTRYINDEX, ALPHABET_KEY) == LUA_TUSERDATA) {
    a = (lsys_alphabet *)lua_touserdata(L, -1);
    lua_pop(L, 1);
    if (a->names == NULL) luaL_error(L, "the module names of lsys were finalized");
    return a;
  }
  lua_pop(L, 1);
  a = (lsys_alphabet *)lua_newuserdatauv(L, sizeof *a, 0);
  memset(a, 0, sizeof *a);
  if (luaL_newmetatable(L, ALPHABET_T)) {
    lua_pushcfunction(L, alphabet_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  if (lsys_alphabet_init(a) != LSYS_OK) luaL_error(L, "not enough memory");
  lua_setfield(L, LUA_REGISTRYINDEX, ALPHABET_KEY);
  return a;
}

/* The message is built as luaL_error builds its own (position, then text),
** so level 1 gives the same bytes as luaL_error(L, "%s", msg). */
int lsysL_raise (lua_State *L, int code, const lsys_error *e, int level) {
  if (level > 0) luaL_where(L, level);
  else lua_pushliteral(L, "");
  lua_pushstring(L, code == LSYS_ENOMEM ? "not enough memory" : e->msg);
  lua_concat(L, 2);
  return lua_error(L);
}

lsys_ins *lsysL_readcode (lua_State *L, int t, int *n) {
  lua_Integer k, len;
  lsys_ins *code;
  t = lua_absindex(L, t);
  luaL_checktype(L, t, LUA_TTABLE);
  len = luaL_len(L, t) / 3;
  if (len > LSYS_EXPR_MAXCODE) luaL_error(L, "program too long");
  code = (lsys_ins *)lua_newuserdatauv(L, (size_t)(len + 1) * sizeof *code, 0);
  for (k = 0; k < len; k++) {
    lua_rawgeti(L, t, 3 * k + 1);
    lua_rawgeti(L, t, 3 * k + 2);
    lua_rawgeti(L, t, 3 * k + 3);
    code[k].op = (int32_t)luaL_checkinteger(L, -3);
    code[k].a = (int32_t)luaL_checkinteger(L, -2);
    code[k].k = luaL_checknumber(L, -1);
    lua_pop(L, 3);
  }
  *n = (int)len;
  return code;
}

/* v is copied before the list is made: it may point into an object that a
** finalizer run by the allocation closes. */
void lsysL_pushnums (lua_State *L, const double *v, int n) {
  double d[LSYS_PUSHNUMS_MAX];
  int k;
  if (n > LSYS_PUSHNUMS_MAX) n = LSYS_PUSHNUMS_MAX;
  memcpy(d, v, (size_t)(n > 0 ? n : 0) * sizeof *d);
  lua_createtable(L, n, 0);
  for (k = 0; k < n; k++) {
    lua_pushnumber(L, (lua_Number)d[k]);
    lua_rawseti(L, -2, k + 1);
  }
}

int lsysL_readnames (lua_State *L, const char *s, lsys_names *d) {
  while (*s) {
    size_t n = 0;
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == ',') s++;
    while (s[n] && s[n] != ' ' && s[n] != '\t' && s[n] != '\n' && s[n] != ',') n++;
    if (n > 0 && lsys_alphabet_names_add(d, s, n) != LSYS_OK) return LSYS_ENOMEM;
    s += n;
  }
  (void)L;
  return LSYS_OK;
}

/* ---------------------------------------------------------------------- */
/* objects in use */

/* A hold: the count it incremented (NULL once released); user value 1: the
** userdata, so that it outlives the hold. */
typedef struct hold { int *busy; } hold;

/* __close and __gc: the collector finalizes a hold that a dead coroutine
** never closed before the userdata it holds (it was made after it). */
static int hold_release (lua_State *L) {
  hold *h = (hold *)luaL_checkudata(L, 1, HOLD_T);
  if (h->busy != NULL) (*h->busy)--;
  h->busy = NULL;
  return 0;
}

void lsysL_hold (lua_State *L, int idx, int *busy) {
  hold *h;
  idx = lua_absindex(L, idx);
  h = (hold *)lua_newuserdatauv(L, sizeof *h, 1);
  h->busy = NULL;
  if (luaL_newmetatable(L, HOLD_T)) {
    lua_pushcfunction(L, hold_release);
    lua_setfield(L, -2, "__close");
    lua_pushcfunction(L, hold_release);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  lua_pushvalue(L, idx);
  lua_setiuservalue(L, -2, 1);
  h->busy = busy;                       /* nothing below can fail */
  (*busy)++;
  lua_toclose(L, -1);
}

void lsysL_checkidle (lua_State *L, int busy, const char *msg) {
  if (busy) luaL_error(L, "%s", msg);
}

/* The collector calls a finalizer with the call marked so, which the debug
** interface names the metamethod "__gc"; Lua code calling a __gc by hand is
** named as its call site says (a field, a method, a local; a metamethod
** other than a finalizer is named without its underscores). */
int lsysL_finalizing (lua_State *L) {
  lua_Debug ar;
  if (!lua_getstack(L, 0, &ar) || !lua_getinfo(L, "n", &ar)) return 0;
  return ar.namewhat != NULL && strcmp(ar.namewhat, "metamethod") == 0 && ar.name != NULL &&
         strcmp(ar.name, "__gc") == 0;
}

int lsysL_life_end (lua_State *L, lsys_life *life) {
  life->closed = 1;
  return !life->kept || lsysL_finalizing(L);
}

/* ---------------------------------------------------------------------- */
/* lsys.Lstring */

lsys_lstring *lsysL_newlstring (lua_State *L) {
  lsys_lstr *u = (lsys_lstr *)lua_newuserdatauv(L, sizeof *u, 1);
  lsys_lstring_init(&u->s);           /* valid empty state before anything can fail */
  u->closed = u->busy = 0;
  luaL_setmetatable(L, LSTRING_T);
  return &u->s;
}

lsys_lstring *lsysL_checklstring_any (lua_State *L, int i) {
  lsys_lstr *u = (lsys_lstr *)luaL_checkudata(L, i, LSTRING_T);
  if (u->closed) luaL_error(L, "the Lstring was closed");
  return &u->s;
}

/* A narrow string (lstring.h) is made wide for everything but a derivation step. */
static lsys_lstring *wide (lua_State *L, lsys_lstring *s) {
  if (s->sym8 != NULL && lsys_lstring_widen(s) != LSYS_OK) luaL_error(L, "not enough memory");
  return s;
}

lsys_lstring *lsysL_checklstring (lua_State *L, int i) {
  return wide(L, lsysL_checklstring_any(L, i));
}

lsys_lstring *lsysL_checkwritable (lua_State *L, int i, const char *what) {
  lsys_lstr *u = (lsys_lstr *)luaL_checkudata(L, i, LSTRING_T);
  if (u->closed) luaL_error(L, "the Lstring was closed");
  if (u->busy) luaL_error(L, "%s: the Lstring is in use by a derivation or interpretation", what);
  return wide(L, &u->s);
}

void lsysL_lstring_busy (lua_State *L, int i, int delta) {
  ((lsys_lstr *)luaL_checkudata(L, i, LSTRING_T))->busy += delta;
}

void lsysL_setowner (lua_State *L, int idx, int owner) {
  idx = lua_absindex(L, idx);
  lua_pushvalue(L, owner);
  if (lua_type(L, -1) == LUA_TUSERDATA && lua_getmetatable(L, -1)) {
    lua_pop(L, 1);
    if (!luaL_testudata(L, -1, LSTRING_T)) { lua_setiuservalue(L, idx, 1); return; }
    lua_pop(L, 1);
    lua_getiuservalue(L, owner, 1);            /* an Lstring: share its owner */
  }
  lua_setiuservalue(L, idx, 1);
}

const lsys_names *lsysL_ownernames (lua_State *L, int idx) {
  lsys_lrules *R;
  const lsys_names *d = NULL;
  if (lua_getiuservalue(L, idx, 1) == LUA_TUSERDATA &&
      (R = (lsys_lrules *)luaL_testudata(L, -1, RULES_T)) != NULL && R->inited)
    d = &R->decl;
  lua_pop(L, 1);
  return d;          /* the owner stays alive: the Lstring refers to it */
}

/* ---------------------------------------------------------------------- */
/* lsys.Rules: running a core operation on a model */

lsys_lrules *lsysL_checkrules (lua_State *L, int i) {
  lsys_lrules *R = (lsys_lrules *)luaL_checkudata(L, i, RULES_T);
  if (!R->inited) luaL_error(L, "the model's rules were closed");
  return R;
}

/* The callback the core calls for rules that need Lua. */
static int rulefn (void *ud, lsys_rules *m, const lsys_rule *r, const double *args,
                   double *vals) {
  lsys_lrules *R = (lsys_lrules *)ud;
  lua_State *L = R->L;
  uint32_t k, nv;
  lua_rawgeti(L, R->fnidx, (lua_Integer)(r - m->rules) + 1);
  luaL_checkstack(L, (int)(r->nargs + r->nvals) + 4, "too many parameters");
  if (R->sb != NULL) {                         /* max_instructions is per call */
    lsysL_sandbox_collect(L, R->sb);
    R->sb->ran = 0;
    R->sb->strict = !(r->flags & LSYS_RF_DYN);
  }
  for (k = 0; k < r->nargs; k++) lua_pushnumber(L, args[k]);
  if (r->flags & LSYS_RF_DYN) {
    int keep = R->produced, res;
    R->produced = 0;
    lua_call(L, (int)r->nargs, 1);
    res = R->produced;               /* no produce: the rule does not apply */
    if (m->cpfgtry == 1 && m->cpfgtried) res = 1;   /* stopped at its mark: it applies */
    R->produced = keep;
    lua_pop(L, 1);
    if (res && lsys_lstring_unbalanced(&m->dyn) >= 0)
      return luaL_error(L, "unbalanced brackets in the produced successor");
    return res;
  }
  lua_call(L, (int)r->nargs, (int)r->nvals + 1);
  if (!lua_toboolean(L, -(int)r->nvals - 1)) {
    lua_pop(L, (int)r->nvals + 1);
    return 0;
  }
  /* stopped at its mark (cpfg's generator): the weight only, the rest when chosen */
  nv = m->cpfgtry == 1 && m->cpfgtried ? ((r->flags & LSYS_RF_WEXPR) ? 1 : 0) : r->nvals;
  for (k = 0; k < nv; k++) {
    int idx = -(int)r->nvals + (int)k;
    if (lua_type(L, idx) != LUA_TNUMBER)
      return luaL_error(L, "value %d is %s, not a number", (int)k + 1, luaL_typename(L, idx));
    vals[k] = lua_tonumber(L, idx);
    if (!isfinite(vals[k]))
      return luaL_error(L, "value %d is %s, not a finite number", (int)k + 1,
                        vals[k] != vals[k] ? "nan" : "infinite");
  }
  lua_pop(L, (int)r->nvals + 1);
  return 1;
}

/*
** The rule functions are callable from C while an operation runs (rulefn
** reads them from the closure table on the stack), and lsys.produce /
** lsys.ran find the model in the registry (LSYS_PRODUCING). It runs in
** protected mode, so that whatever a rule function does (raise, call this
** model again: refused, close the strings it works on: refused), the marks
** on the model and the Lstrings are undone before the error goes on.
*/
typedef struct runargs {
  lsys_ruleop op;
  void *ud;
  int st;
} runargs;

/* In protected mode: 1 = the rules, 2 = the runargs. */
static int protectedrun (lua_State *L) {
  runargs *a = (runargs *)lua_touserdata(L, 2);
  lsys_lrules *R = lsysL_checkrules(L, 1);
  lua_getiuservalue(L, 1, LSYS_RULES_FNS);
  R->L = L;
  R->fnidx = lua_gettop(L);
  R->m.fn = rulefn;
  R->m.fnud = R;
  R->m.cur_rule = -1;
  lua_pushvalue(L, 1);                      /* the rules producing now */
  lua_setfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING);
  a->st = a->op(L, &R->m, a->ud);
  return 0;
}

int lsysL_rules_run (lua_State *L, int ridx, const char *what, lsys_ruleop op, void *ud,
                     const int *lstr, int n) {
  lsys_lrules *R = lsysL_checkrules(L, ridx);
  runargs a;
  lsys_sandbox sb;
  int k, err;
  ridx = lua_absindex(L, ridx);
  if (R->m.busy) return luaL_error(L, "a rule called %s on the model it belongs to", what);
  for (k = 0; k < n; k++) lsysL_checklstring_any(L, lstr[k]);   /* alive, before any mark */
  lsysL_sandbox_enter(L, &sb, R);                        /* its value stays below */
  for (k = 0; k < n; k++) lsysL_lstring_busy(L, lstr[k], 1);
  a.op = op; a.ud = ud; a.st = LSYS_OK;
  lua_getfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING);   /* restored after */
  lua_pushcfunction(L, protectedrun);
  lua_pushvalue(L, ridx);
  lua_pushlightuserdata(L, &a);
  R->sb = &sb;
  err = lua_pcall(L, 2, 0, 0);
  R->sb = NULL;
  lsysL_sandbox_leave(L, &sb, err);
  for (k = 0; k < n; k++) lsysL_lstring_busy(L, lstr[k], -1);
  R->m.busy = 0;             /* the core sets it while it runs; an error skips the reset */
  lua_pushvalue(L, err != LUA_OK ? -2 : -1);
  lua_setfield(L, LUA_REGISTRYINDEX, LSYS_PRODUCING);
  if (err != LUA_OK) {
    lua_remove(L, -2);
    return lua_error(L);
  }
  lua_pop(L, 1);
  return a.st;
}

/* ---------------------------------------------------------------------- */
/* lsys.Scene; Contour, Surface, Texture */

/* Pushes a new, empty Scene (no palette yet, nothing to look at) and returns it. */
lsys_lscene *lsysL_newscene (lua_State *L) {
  lsys_lscene *S = (lsys_lscene *)lua_newuserdatauv(L, sizeof *S, LSYS_SCENE_NUV);
  memset(S, 0, sizeof *S);
  luaL_setmetatable(L, SCENE_T);
  lsys_scene_init(&S->sc);
  S->inited = 1;
  return S;
}

lsys_lscene *lsysL_checkscene (lua_State *L, int i) {
  lsys_lscene *S = (lsys_lscene *)luaL_checkudata(L, i, SCENE_T);
  if (!S->inited) luaL_error(L, "the scene was closed");
  return S;
}

lsys_lscene *lsysL_holdscene (lua_State *L, int i) {
  i = lua_absindex(L, i);
  lsysL_hold(L, i, &lsysL_checkscene(L, i)->busy);
  return lsysL_checkscene(L, i);             /* again: the hold allocated */
}

void lsysL_changescene (lua_State *L, const lsys_lscene *S) {
  lsysL_checkidle(L, S->busy, "cannot change a Scene while it is in use");
}

static const char *const kindname[] = {
  "none", "segment", "sphere", "disc", "polygon", "label", "system", "gcyl", "surface"
};
#define NKINDS ((int)(sizeof kindname / sizeof kindname[0]))

const char *lsysL_recordkind (int kind) {
  return kindname[kind >= 0 && kind < NKINDS ? kind : 0];
}

/* The immutable object at i of type 'tname', alive; its life is at 'off'. */
static void *checkimm (lua_State *L, int i, const char *tname, size_t off, const char *what,
                       int keep) {
  char *u = (char *)luaL_checkudata(L, i, tname);
  lsys_life *life = (lsys_life *)(void *)(u + off);
  if (life->closed) luaL_error(L, "the %s was closed", what);
  if (keep) life->kept = 1;
  return u;
}

#define CHECKIMM(T, tname, what, keep) \
  ((T *)checkimm(L, i, tname, offsetof(T, life), what, keep))

const lsys_contour *lsysL_checkcontour (lua_State *L, int i) {
  return &CHECKIMM(lsys_lcontour, CONTOUR_T, "contour", 0)->c;
}

const lsys_surface *lsysL_checksurface (lua_State *L, int i) {
  return &CHECKIMM(lsys_lsurface, SURFACE_T, "surface", 0)->s;
}

const lsys_texture *lsysL_checktexture (lua_State *L, int i) {
  return &CHECKIMM(lsys_ltexture, TEXTURE_T, "texture", 0)->t;
}

const lsys_func *lsysL_checkfunc (lua_State *L, int i) {
  return &CHECKIMM(lsys_lfunc, FUNC_T, "function", 0)->f;
}

const lsys_contour *lsysL_keepcontour (lua_State *L, int i) {
  return &CHECKIMM(lsys_lcontour, CONTOUR_T, "contour", 1)->c;
}

const lsys_surface *lsysL_keepsurface (lua_State *L, int i) {
  return &CHECKIMM(lsys_lsurface, SURFACE_T, "surface", 1)->s;
}

const lsys_texture *lsysL_keeptexture (lua_State *L, int i) {
  return &CHECKIMM(lsys_ltexture, TEXTURE_T, "texture", 1)->t;
}

const lsys_func *lsysL_keepfunc (lua_State *L, int i) {
  return &CHECKIMM(lsys_lfunc, FUNC_T, "function", 1)->f;
}

/* ---------------------------------------------------------------------- */
/* option readers */

/* A short description of the value at 'idx' for error messages (may push it). */
static const char *got (lua_State *L, int idx) {
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
      return luaL_tolstring(L, idx, NULL);
    case LUA_TSTRING:
      return lua_pushfstring(L, "'%s'", lua_tostring(L, idx));
    default:
      return luaL_typename(L, idx);
  }
}

/* Raises for the bad value of o[k] on top: "<option> must be <expect>", and
** what o shows of it; 'kind' names a value of the wrong type (NULL: the
** type is right, the value is not). */
static int bad (lua_State *L, const lsys_opts *o, const char *k, const char *expect,
                const char *kind) {
  if (o->got == LSYS_GOT_VALUE)
    return luaL_error(L, "%s%s%s must be %s, got %s", o->pre, k, o->post, expect, got(L, -1));
  if (o->got == LSYS_GOT_TYPE && kind != NULL)
    return luaL_error(L, "%s%s%s must be %s, got %s", o->pre, k, o->post, expect, kind);
  return luaL_error(L, "%s%s%s must be %s", o->pre, k, o->post, expect);
}

int lsysL_opterror (lua_State *L, const lsys_opts *o, const char *k, const char *expect) {
  return bad(L, o, k, expect, NULL);
}

int lsysL_optfield (lua_State *L, const lsys_opts *o, const char *k, int type,
                    const char *expect) {
  int ty;
  if (o->t == 0) return 0;
  ty = lua_getfield(L, o->t, k);
  if (ty == LUA_TNIL) { lua_pop(L, 1); return 0; }
  if (type != LUA_TNONE && ty != type) bad(L, o, k, expect, luaL_typename(L, -1));
  return 1;
}

int lsysL_optbool (lua_State *L, const lsys_opts *o, const char *k, int def) {
  int b;
  if (!lsysL_optfield(L, o, k, LUA_TBOOLEAN, "a boolean")) return def;
  b = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return b;
}

/* The bounds are checked before the conversion to int. */
int lsysL_optint (lua_State *L, const lsys_opts *o, const char *k, int def, int lo, int hi) {
  lua_Integer x;
  int isint;
  if (!lsysL_optfield(L, o, k, o->numerals ? LUA_TNONE : LUA_TNUMBER, "an integer")) return def;
  x = lua_tointegerx(L, -1, &isint);
  if (!isint || x < lo || x > hi) {
    char expect[64];
    snprintf(expect, sizeof expect, "an integer in [%d, %d]", lo, hi);
    bad(L, o, k, expect, NULL);
  }
  lua_pop(L, 1);
  return (int)x;
}

double lsysL_optnum (lua_State *L, const lsys_opts *o, const char *k, double def, double lo,
                     double hi, const char *expect) {
  double x = 0;
  int ok;
  if (expect == NULL) expect = "a finite number";
  if (!lsysL_optfield(L, o, k, LUA_TNONE, NULL)) return def;
  if (o->numerals) x = lua_tonumberx(L, -1, &ok);
  else if ((ok = lua_type(L, -1) == LUA_TNUMBER)) x = lua_tonumber(L, -1);
  if (!ok || !isfinite(x)) bad(L, o, k, expect, ok ? "a non-finite number" : luaL_typename(L, -1));
  if (!(x > lo && x < hi)) bad(L, o, k, expect, NULL);
  lua_pop(L, 1);
  return x;
}

int lsysL_optchoice (lua_State *L, const lsys_opts *o, const char *k, int def,
                     const char *const names[], const char *expect) {
  const char *s;
  int i;
  if (!lsysL_optfield(L, o, k, LUA_TNONE, NULL)) return def;
  if (lua_type(L, -1) != LUA_TSTRING) return bad(L, o, k, expect, luaL_typename(L, -1));
  s = lua_tostring(L, -1);
  for (i = 0; names[i] != NULL; i++)
    if (strcmp(s, names[i]) == 0) {
      lua_pop(L, 1);
      return i;
    }
  return luaL_error(L, "%s%s%s must be %s, got '%s'", o->pre, k, o->post, expect, s);
}

int lsysL_optunknown (lua_State *L, const lsys_opts *o, const char *const names[]) {
  if (o->t == 0) return 0;
  lua_pushnil(L);
  while (lua_next(L, o->t)) {
    int i;
    lua_pop(L, 1);
    for (i = 0; names[i] != NULL; i++)
      if (lua_type(L, -1) == LUA_TSTRING && strcmp(lua_tostring(L, -1), names[i]) == 0)
        break;
    if (names[i] == NULL) return 1;
  }
  return 0;
}

/* The list is copied with lua_geti (its metamethods run once per entry),
** then checked from the copy, after the array is made: nothing runs Lua code
** between the checks and the return. The array's user value is the copy. */
const lsys_texture *const *lsysL_opttextures (lua_State *L, int t, const char *who, int *ntex) {
  const lsys_texture **arr;
  lua_Integer n, k;
  *ntex = 0;
  if (t == 0 || lua_getfield(L, t, "textures") == LUA_TNIL) {
    if (t != 0) lua_pop(L, 1);
    lua_pushnil(L);
    return NULL;
  }
  if (lua_type(L, -1) != LUA_TTABLE)
    luaL_error(L, "%s: opts.textures must be a list of textures (lsys.texture_load), got %s",
               who, luaL_typename(L, -1));
  n = luaL_len(L, -1);
  if (n < 0 || n > 65535)
    luaL_error(L, "%s: opts.textures has %I entries; at most 65535", who, n);
  if (n == 0) {
    lua_pop(L, 1);
    lua_pushnil(L);
    return NULL;
  }
  lua_createtable(L, (int)n, 0);
  for (k = 1; k <= n; k++) {
    lua_geti(L, -2, k);
    lua_rawseti(L, -2, k);
  }
  arr = (const lsys_texture **)lua_newuserdatauv(L, (size_t)n * sizeof *arr, 1);
  for (k = 1; k <= n; k++) {
    const lsys_ltexture *u;
    lua_rawgeti(L, -2, k);
    u = (const lsys_ltexture *)luaL_testudata(L, -1, TEXTURE_T);
    if (u == NULL)
      luaL_error(L, "%s: opts.textures[%I] must be a texture (lsys.texture_load), got %s", who,
                 k, luaL_typename(L, -1));
    if (u->life.closed) luaL_error(L, "%s: opts.textures[%I] was closed", who, k);
    arr[k - 1] = lsysL_keeptexture(L, -1);
    lua_pop(L, 1);
  }
  lua_insert(L, -2);
  lua_setiuservalue(L, -2, 1);              /* the copy: the textures live with the array */
  lua_remove(L, -2);
  *ntex = (int)n;
  return arr;
}

/* ---------------------------------------------------------------------- */
/* how to look at a scene: core.interpret's view fields, lsys.render's opts */

/* Reads {x, y, z} (finite numbers; within [0, 1] for a colour); its
** messages never show the value. */
static int optvec3 (lua_State *L, const lsys_opts *o, const char *k, int colour, double v[3]) {
  int i, ok;
  if (!lsysL_optfield(L, o, k, LUA_TNONE, NULL)) return 0;
  ok = lua_type(L, -1) == LUA_TTABLE && luaL_len(L, -1) == 3;
  for (i = 0; ok && i < 3; i++) {
    ok = lua_rawgeti(L, -1, i + 1) == LUA_TNUMBER && isfinite(v[i] = lua_tonumber(L, -1)) &&
         (!colour || (v[i] >= 0 && v[i] <= 1));
    lua_pop(L, 1);
  }
  if (!ok)
    luaL_error(L, "%s%s%s must be %s", o->pre, k, o->post,
               colour ? "{r, g, b} with numbers in [0, 1]" : "{x, y, z} with 3 finite numbers");
  lua_pop(L, 1);
  return 1;
}

static int iszero (const double v[3]) {
  return v[0] == 0 && v[1] == 0 && v[2] == 0;
}

void lsysL_readbox (lua_State *L, int t, const char *what, double box[6]) {
  int i;
  for (i = 0; i < 6; i++) {
    lua_rawgeti(L, t, i + 1);
    if (!lua_isnumber(L, -1) || !isfinite(lua_tonumber(L, -1)))
      luaL_error(L, "%s must be a box {x0, y0, z0, x1, y1, z1} of finite numbers", what);
    box[i] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  for (i = 0; i < 3; i++)
    if (box[i] > box[i + 3]) luaL_error(L, "%s: its low corner is above its high one", what);
}

/* Field k of light i (the table on top) into v: three finite numbers, not
** negative for a 'colour' (above 1 brightens, as OpenGL allows). Returns 0
** when the light has no k. */
static int lightvec (lua_State *L, const lsys_opts *o, int i, const char *k, int colour,
                     double v[3]) {
  int j, ok;
  if (lua_getfield(L, -1, k) == LUA_TNIL) { lua_pop(L, 1); return 0; }
  ok = lua_type(L, -1) == LUA_TTABLE && luaL_len(L, -1) == 3;
  for (j = 0; ok && j < 3; j++) {
    ok = lua_rawgeti(L, -1, j + 1) == LUA_TNUMBER && isfinite(v[j] = lua_tonumber(L, -1)) &&
         (!colour || v[j] >= 0);
    lua_pop(L, 1);
  }
  if (!ok)
    luaL_error(L, "%slights[%d].%s%s must be %s", o->pre, i, k, o->post,
               colour ? "{r, g, b} with finite numbers >= 0" : "{x, y, z} with 3 finite numbers");
  lua_pop(L, 1);
  return 1;
}

/* Colour k of light i into c, 'def' grey when the light has none. */
static void lightcolour (lua_State *L, const lsys_opts *o, int i, const char *k, double def,
                         float c[3]) {
  double v[3] = {def, def, def};
  lightvec(L, o, i, k, 1, v);
  c[0] = (float)v[0]; c[1] = (float)v[1]; c[2] = (float)v[2];
}

/* opts.lights: a list of at most LSYS_SCENE_NLIGHTS lights, each { direction
** = {x, y, z} (towards the light) or position = {x, y, z}, ambient = (0),
** diffuse = (1), specular = (1) colours }, which replace the default ones;
** an empty list gives the default lights back. */
static void readlights (lua_State *L, const lsys_opts *o, lsys_scene *sc) {
  lua_Integer n, i;
  if (!lsysL_optfield(L, o, "lights", LUA_TTABLE, "a list of lights")) return;
  n = luaL_len(L, -1);
  if (n > LSYS_SCENE_NLIGHTS)
    luaL_error(L, "%slights%s has %d lights; at most %d can be drawn", o->pre, o->post,
               (int)n, LSYS_SCENE_NLIGHTS);
  for (i = 1; i <= n; i++) {
    lsys_slight *l = &sc->lights[i - 1];
    double v[3], p[3];
    int dir, pos;
    if (lua_rawgeti(L, -1, i) != LUA_TTABLE)
      luaL_error(L, "%slights[%d]%s must be a table", o->pre, (int)i, o->post);
    dir = lightvec(L, o, (int)i, "direction", 0, v);
    pos = lightvec(L, o, (int)i, "position", 0, p);
    if (dir == pos)
      luaL_error(L, "%slights[%d]%s needs a direction or a position (one of them)", o->pre,
                 (int)i, o->post);
    if (dir && iszero(v))
      luaL_error(L, "%slights[%d].direction%s must not be the zero vector", o->pre, (int)i,
                 o->post);
    memcpy(l->pos, dir ? v : p, sizeof v);
    l->pos[3] = dir ? 0 : 1;
    lightcolour(L, o, (int)i, "ambient", 0, l->ambient);
    lightcolour(L, o, (int)i, "diffuse", 1, l->diffuse);
    lightcolour(L, o, (int)i, "specular", 1, l->specular);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  sc->nlights = (int)n;
}

/* The look fields of the options at o->t (scene.h): each one given
** replaces the scene's; the messages begin with o->pre. */
void lsysL_readlook (lua_State *L, const lsys_opts *o, lsys_scene *sc) {
  static const char *const projections[] = {"perspective", "parallel", NULL};
  lsys_camera *cam = &sc->cam;
  double v[3];
  int p;
  if (optvec3(L, o, "background", 1, v)) {
    sc->background[0] = (float)v[0];
    sc->background[1] = (float)v[1];
    sc->background[2] = (float)v[2];
  }
  if (optvec3(L, o, "light", 0, v)) {
    if (iszero(v)) luaL_error(L, "%slight%s must not be the zero vector", o->pre, o->post);
    memcpy(sc->light, v, sizeof v);
  }
  readlights(L, o, sc);
  if (optvec3(L, o, "viewpoint", 0, cam->eye)) cam->has_eye = 1;
  if (optvec3(L, o, "target", 0, cam->target)) cam->has_target = 1;
  if (optvec3(L, o, "up", 0, cam->up)) {
    cam->has_up = 1;
    if (iszero(cam->up)) luaL_error(L, "%sup%s must not be the zero vector", o->pre, o->post);
  }
  if (optvec3(L, o, "direction", 0, cam->dir) && iszero(cam->dir))
    luaL_error(L, "%sdirection%s must not be the zero vector", o->pre, o->post);
  if (cam->has_eye && cam->has_target && cam->eye[0] == cam->target[0] &&
      cam->eye[1] == cam->target[1] && cam->eye[2] == cam->target[2])
    luaL_error(L, "%sviewpoint%s and %starget%s must differ", o->pre, o->post, o->pre,
               o->post);
  p = lsysL_optchoice(L, o, "projection", -1, projections, "'perspective' or 'parallel'");
  if (p >= 0) cam->projection = p == 0 ? LSYS_PERSPECTIVE : LSYS_PARALLEL;
  cam->fov = lsysL_optnum(L, o, "fov", cam->fov, 0, 180, "a number of degrees in (0, 180)");
  cam->twist = lsysL_optnum(L, o, "twist", cam->twist, -HUGE_VAL, HUGE_VAL, "a number of degrees");
  cam->zoom = lsysL_optnum(L, o, "zoom", cam->zoom, 0, HUGE_VAL, "a positive number");
  if (lsysL_optfield(L, o, "fit", LUA_TTABLE, "a box {x0, y0, z0, x1, y1, z1}")) {
    char what[96];
    snprintf(what, sizeof what, "%sfit%s", o->pre, o->post);
    lsysL_readbox(L, lua_gettop(L), what, cam->box);
    cam->has_box = 1;
    lua_pop(L, 1);
  }
}

/* ---------------------------------------------------------------------- */
/* lsys.render options (lua_render.c) */

#ifndef LSYS_NO_RENDER

/* A size in pixels or samples: a positive integer at most 'max', also as a
** numeral ("800": the sizes were always read so). */
static int optsize (lua_State *L, const lsys_opts *o, const char *k, int def, int max) {
  lua_Integer v;
  int isint;
  if (!lsysL_optfield(L, o, k, LUA_TNONE, NULL)) return def;
  v = lua_tointegerx(L, -1, &isint);
  if (!isint || v < 1 || v > max) {
    char expect[64];
    snprintf(expect, sizeof expect, "a positive integer at most %d", max);
    bad(L, o, k, expect, NULL);
  }
  lua_pop(L, 1);
  return (int)v;
}

static const char *const renderopts[] = {
  "out", "width", "height", "supersample", "background", "transparent", "light", "lights",
  "wireframe",
  "viewpoint", "target", "up", "direction", "projection", "fov", "twist", "zoom", "textures",
  "fit", "shade", NULL
};

void lsysL_readrenderopts (lua_State *L, int t, lsys_render_opts *o, lsys_scene *sc) {
  lsys_opts ro = {t, "lsys.render: opts.", "", LSYS_GOT_VALUE, 0};
  lsys_render_defaults(o);
  if (lsysL_optunknown(L, &ro, renderopts))          /* unknown keys are mistakes */
    luaL_error(L, "lsys.render: unknown option %s", got(L, -1));
  o->width = optsize(L, &ro, "width", o->width, 16384);
  o->height = optsize(L, &ro, "height", o->height, 16384);
  o->supersample = optsize(L, &ro, "supersample", o->supersample, 16);
  o->transparent = lsysL_optbool(L, &ro, "transparent", 0);
  o->wireframe = lsysL_optbool(L, &ro, "wireframe", 0);
  lsysL_readlook(L, &ro, sc);
}

#endif
