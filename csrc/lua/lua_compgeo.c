/*
** Lua binding of csrc/core/compgeo.h: the frames and the turtle writer of
** component graphs (lsys.components.expand and .emit). Indices are 1-based.
**
**   core.frames(seed) -> Frames             an empty arena with its generator
**   F:random() -> [0, 1)                     F:count() -> frames
**   F:add{p =, H =, U =, s = [, u =]} -> i   F:set(i, frame)
**   F:get(i) -> {p, H, U, s [, u]}           a new table each call (u: stem frames)
**   F:scale(i) -> s                          F:copy(i) -> j
**   F:transform(i, tx, ty, tz, rx, ry, rz, s) -> j     the basic parameters
**   F:ahead(i, d) -> j                       moved d (times its scale) along H
**   F:branch(first, nframes, u, roll, angle, scale) -> j   a Tree's branch at u
**   F:place(i, x, y, z, hx, hy, hz, ux, uy, uz, size) -> j a multiplier's child
**       (position and axes in the local axes X = U, Y = H x U, Z = H of frame i)
**   F:stem(i, len, segs, curv, twist, gnarl, trop, dev, bu, broll) -> first
**       trop: list of {direction {x, y, z} | function (x, y, z, hx, hy, hz) -> x, y, z,
**       strength}: a function of the position and the heading before the turn
**       bu, broll: the branches' places along the stem and rolls (nil: none)
**
**   core.cwriter(rules, frames) -> Cwriter  writes an Lstring owned by rules
**   W:symbol(name) -> id                     W:op(id, ...) a module of the current owner
**   W:open(inst, i)  W:close()              an instance's `[` (and the move to frame i), `]`
**   W:orient(i)  W:forward(d, draw)  W:setpos(i)
**   W:segment(j) -> length, u0, u1           orient to stem frame j, its piece from j - 1
**   W:turtle() -> p, H, U                    W:owner(k) -> instance   W:count() -> modules
**   W:range(inst) -> m0, m1, at (or nil)     W:lstring() -> the Lstring written
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "compgeo.h"

#define FRAMES_T  "lsys.Frames"
#define CWRITER_T "lsys.Cwriter"

typedef struct lframes {
  lsys_cframes a;
  int closed;
  int busy;                    /* held by F:stem (lsysL_hold): neither closed nor changed */
} lframes;

typedef struct lwriter {
  lsys_cwriter w;
  uint32_t nsym;               /* symbols below this are known to the alphabet */
  int closed;
} lwriter;

/* {======================================================================
** Frames
** ======================================================================= */

#define FRAMES_INUSE "cannot close the frames while they are in use"

static lsys_cframes *checkframes (lua_State *L, int i) {
  lframes *f = (lframes *)luaL_checkudata(L, i, FRAMES_T);
  if (f->closed) luaL_error(L, "the frames were closed");
  return &f->a;
}

/* The frames at 1 for a method that adds or rewrites frames: refused while
** F:stem holds them. */
static lsys_cframes *changeframes (lua_State *L) {
  lsys_cframes *a = checkframes(L, 1);
  lsysL_checkidle(L, ((lframes *)lua_touserdata(L, 1))->busy,
                  "cannot change the frames while they are in use");
  return a;
}

/* __gc and __close (and F:close): idempotent; refused while held. */
static int frames_close (lua_State *L) {
  lframes *f = (lframes *)luaL_checkudata(L, 1, FRAMES_T);
  if (!f->closed && !lsysL_finalizing(L)) lsysL_checkidle(L, f->busy, FRAMES_INUSE);
  if (!f->closed) lsys_compgeo_frames_free(&f->a);
  f->closed = 1;
  return 0;
}

static int l_frames (lua_State *L) {
  lua_Integer seed = luaL_optinteger(L, 1, 1);
  lframes *f = (lframes *)lua_newuserdatauv(L, sizeof *f, 0);
  lsys_compgeo_frames_init(&f->a, (int64_t)seed);
  f->closed = f->busy = 0;
  luaL_setmetatable(L, FRAMES_T);
  return 1;
}

/* The frame at stack index i (1-based index into the arena). */
static lsys_cframe *frameat (lua_State *L, lsys_cframes *a, int i) {
  lua_Integer k = luaL_checkinteger(L, i);
  luaL_argcheck(L, k >= 1 && (lua_Unsigned)k <= a->n, i, "no such frame");
  return &a->f[k - 1];
}

static double num (lua_State *L, int i) {
  double x = luaL_checknumber(L, i);
  if (!isfinite(x)) luaL_argerror(L, i, "not a finite number");
  return x;
}

static int pushnew (lua_State *L, lsys_cframes *a, const lsys_cframe *g) {
  size_t idx;
  if (lsys_compgeo_frames_add(a, g, &idx) != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_pushinteger(L, (lua_Integer)idx + 1);
  return 1;
}

#define pushvec(L, v) lsysL_pushnums((L), (v), 3)

static void readvec (lua_State *L, int t, const char *k, double v[3]) {
  int i;
  if (lua_getfield(L, t, k) != LUA_TTABLE) luaL_error(L, "frame: '%s' must be {x, y, z}", k);
  for (i = 0; i < 3; i++) {
    int ok;
    lua_rawgeti(L, -1, i + 1);
    v[i] = lua_tonumberx(L, -1, &ok);
    if (!ok || !isfinite(v[i])) luaL_error(L, "frame: '%s'[%d] must be a finite number", k, i + 1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

static void readframe (lua_State *L, int t, lsys_cframe *f) {
  luaL_checktype(L, t, LUA_TTABLE);
  readvec(L, t, "p", f->p);
  readvec(L, t, "H", f->H);
  readvec(L, t, "U", f->U);
  lua_getfield(L, t, "s");
  f->s = luaL_optnumber(L, -1, 1);
  lua_getfield(L, t, "u");
  f->u = luaL_optnumber(L, -1, 0);
  lua_pop(L, 2);
}

/* The frame tables are read before the frames are taken: their metamethods
** run Lua code. */
static int frames_add (lua_State *L) {
  lsys_cframe f;
  checkframes(L, 1);
  readframe(L, 2, &f);
  return pushnew(L, changeframes(L), &f);
}

static int frames_set (lua_State *L) {
  lsys_cframe g;
  frameat(L, checkframes(L, 1), 2);
  readframe(L, 3, &g);
  *frameat(L, changeframes(L), 2) = g;
  return 0;
}

/* F:get(i [, withu]): a copy of the frame, then the tables */
static int frames_get (lua_State *L) {
  lsys_cframe f = *frameat(L, checkframes(L, 1), 2);
  int withu = lua_toboolean(L, 3);
  lua_settop(L, 2);
  lua_createtable(L, 0, 5);
  pushvec(L, f.p);
  lua_setfield(L, -2, "p");
  pushvec(L, f.H);
  lua_setfield(L, -2, "H");
  pushvec(L, f.U);
  lua_setfield(L, -2, "U");
  lua_pushnumber(L, f.s);
  lua_setfield(L, -2, "s");
  if (withu) {
    lua_pushnumber(L, f.u);
    lua_setfield(L, -2, "u");
  }
  return 1;
}

static int frames_scale (lua_State *L) {
  lua_pushnumber(L, frameat(L, checkframes(L, 1), 2)->s);
  return 1;
}

static int frames_count (lua_State *L) {
  lua_pushinteger(L, (lua_Integer)checkframes(L, 1)->n);
  return 1;
}

static int frames_random (lua_State *L) {
  lua_pushnumber(L, lsys_compgeo_frames_random(checkframes(L, 1)));
  return 1;
}

static int frames_copy (lua_State *L) {
  lsys_cframes *a = changeframes(L);
  lsys_cframe g = *frameat(L, a, 2);
  g.u = 0;
  return pushnew(L, a, &g);
}

static int frames_transform (lua_State *L) {
  lsys_cframes *a = changeframes(L);
  lsys_cframe g, *f = frameat(L, a, 2);
  double t[3], r[3];
  int i;
  for (i = 0; i < 3; i++) { t[i] = num(L, 3 + i); r[i] = num(L, 6 + i); }
  lsys_compgeo_frame_transform(f, t, r, num(L, 9), &g);
  g.u = 0;
  return pushnew(L, a, &g);
}

static int frames_ahead (lua_State *L) {
  lsys_cframes *a = changeframes(L);
  lsys_cframe g = *frameat(L, a, 2);
  double d = num(L, 3);
  int i;
  for (i = 0; i < 3; i++) g.p[i] = g.p[i] + g.H[i] * (d * g.s);
  g.u = 0;
  return pushnew(L, a, &g);
}

/* F:branch(first, nframes, u, roll, angle, scale): between the stem frames
** around u (of nframes, the first at index first). */
static int frames_branch (lua_State *L) {
  lsys_cframes *a = changeframes(L);
  lua_Integer first = luaL_checkinteger(L, 2), nf = luaL_checkinteger(L, 3);
  double x, t, u = num(L, 4);
  lua_Integer ns = nf - 1, k;
  lsys_cframe g;
  luaL_argcheck(L, nf >= 2 && first >= 1 && (lua_Unsigned)nf <= a->n &&
                (lua_Unsigned)first <= a->n - (size_t)nf + 1, 3, "not a stem");
  x = u * (double)ns;
  k = (lua_Integer)floor(x);
  if (k >= ns) k = ns - 1;
  if (k < 0) k = 0;
  t = x - (double)k;
  lsys_compgeo_frame_branch(&a->f[first - 1 + k], &a->f[first + k], t, num(L, 5), num(L, 6),
                            num(L, 7), &g);
  return pushnew(L, a, &g);
}

static int frames_place (lua_State *L) {
  lsys_cframes *a = changeframes(L);
  lsys_cframe *f = frameat(L, a, 2), g;
  double X[3], Y[3], v[9];
  int i, j;
  for (i = 0; i < 9; i++) v[i] = num(L, 3 + i);
  X[0] = f->U[0]; X[1] = f->U[1]; X[2] = f->U[2];
  Y[0] = f->H[1] * f->U[2] - f->H[2] * f->U[1];
  Y[1] = f->H[2] * f->U[0] - f->H[0] * f->U[2];
  Y[2] = f->H[0] * f->U[1] - f->H[1] * f->U[0];
  for (j = 0; j < 3; j++) {
    const double *q = v + 3 * j;
    double w[3];
    for (i = 0; i < 3; i++) w[i] = X[i] * q[0] + Y[i] * q[1] + f->H[i] * q[2];
    if (j == 0) for (i = 0; i < 3; i++) g.p[i] = f->p[i] + f->s * w[i];
    else if (j == 1) memcpy(g.H, w, sizeof w);
    else memcpy(g.U, w, sizeof w);
  }
  g.s = f->s * num(L, 12);
  g.u = 0;
  return pushnew(L, a, &g);
}

/* The tropism field k: a Lua function of position and heading (x, y, z, hx,
** hy, hz), at k + 1 in the table at 'fns' (the stem's own: the caller's list
** is read once, before the stem). */
typedef struct fieldctx { lua_State *L; int fns; } fieldctx;

static int callfield (void *ud, int k, const double p[3], const double H[3], double T[3]) {
  fieldctx *c = (fieldctx *)ud;
  lua_State *L = c->L;
  int i;
  lua_rawgeti(L, c->fns, k + 1);
  for (i = 0; i < 3; i++) lua_pushnumber(L, p[i]);
  for (i = 0; i < 3; i++) lua_pushnumber(L, H[i]);
  lua_call(L, 6, 3);                   /* its error is the caller's */
  if (lua_isnil(L, -3)) { lua_pop(L, 3); return 0; }
  for (i = 0; i < 3; i++) {
    int ok;
    T[i] = lua_tonumberx(L, i - 3, &ok);
    if (!ok || !isfinite(T[i]))
      luaL_error(L, "a field function returned %s, not three finite numbers",
                 luaL_typename(L, i - 3));
  }
  lua_pop(L, 3);
  return 1;
}

/* Element k (1-based) of the list at stack index i: a finite number. */
static double elem (lua_State *L, int i, int k, const char *what) {
  int ok;
  double x;
  lua_rawgeti(L, i, k);
  x = lua_tonumberx(L, -1, &ok);
  if (!ok || !isfinite(x)) luaL_error(L, "%s[%d] must be a finite number", what, k);
  lua_pop(L, 1);
  return x;
}

#define MAXTROP 8

/* The tropisms of the list at 8 into trop (4 numbers each; a field: NaN,
** its function into the table at 'fns'); their number. */
static int readtrop (lua_State *L, double *trop, int fns) {
  int nt, k;
  luaL_checktype(L, 8, LUA_TTABLE);
  nt = (int)luaL_len(L, 8);
  luaL_argcheck(L, nt <= MAXTROP, 8, "too many tropisms");
  for (k = 0; k < nt; k++) {
    int t = lua_gettop(L) + 1, i;
    if (lua_rawgeti(L, 8, k + 1) != LUA_TTABLE)
      return luaL_error(L, "tropism %d must be {direction, strength}", k + 1);
    lua_rawgeti(L, t, 1);
    if (lua_isfunction(L, -1)) {
      trop[4 * k] = NAN;
      lua_pushvalue(L, -1);
      lua_rawseti(L, fns, k + 1);
    }
    else if (lua_istable(L, -1)) {
      for (i = 0; i < 3; i++) trop[4 * k + i] = elem(L, t + 1, i + 1, "a tropism direction");
    }
    else return luaL_error(L, "tropism %d: the direction must be {x, y, z} or a function",
                           k + 1);
    trop[4 * k + 3] = elem(L, t, 2, "a tropism");
    lua_settop(L, t - 1);
  }
  return nt < 0 ? 0 : nt;
}

/* The arguments are read first (luaL_len runs Lua code), then the frames
** are held: the field functions can neither close nor grow them. */
static int frames_stem (lua_State *L) {
  lsys_cframes *a;
  lsys_cstem st;
  double trop[4 * MAXTROP], *bb = NULL;
  fieldctx fc;
  lua_Integer segs, base;
  size_t first;
  int nt = 0, nb = 0, r, k;
  frameat(L, checkframes(L, 1), 2);
  st.len = num(L, 3);
  segs = luaL_checkinteger(L, 4);
  luaL_argcheck(L, segs >= 1 && segs <= 100000, 4, "segments must be from 1 to 100000");
  st.segs = (int)segs;
  st.curv = num(L, 5);
  st.twist = num(L, 6);
  st.gnarl = num(L, 7);
  st.dev = luaL_optnumber(L, 9, 0);
  lua_settop(L, 11);
  lua_newtable(L);                          /* 12: the field functions */
  if (!lua_isnil(L, 8)) nt = readtrop(L, trop, 12);
  if (!lua_isnil(L, 10)) {
    luaL_checktype(L, 10, LUA_TTABLE);
    luaL_checktype(L, 11, LUA_TTABLE);
    nb = (int)lua_rawlen(L, 10);
    luaL_argcheck(L, (int)lua_rawlen(L, 11) == nb, 11, "one roll per branch");
    bb = (double *)lua_newuserdatauv(L, 2 * (size_t)nb * sizeof *bb + 1, 0);   /* 13 */
    for (k = 0; k < nb; k++) {
      bb[k] = elem(L, 10, k + 1, "bu");
      bb[nb + k] = elem(L, 11, k + 1, "broll");
    }
  }
  st.ntrop = nt;
  st.trop = trop;
  fc.L = L;
  fc.fns = 12;
  st.field = callfield;
  st.ud = &fc;
  st.nb = nb;
  st.bu = bb;
  st.broll = bb ? bb + nb : NULL;
  changeframes(L);
  lsysL_hold(L, 1, &((lframes *)lua_touserdata(L, 1))->busy);
  a = checkframes(L, 1);                    /* again: the hold allocated */
  base = frameat(L, a, 2) - a->f;
  r = lsys_compgeo_frames_stem(a, (size_t)base, &st, &first);
  if (r != LSYS_OK) return luaL_error(L, "not enough memory");
  lua_pushinteger(L, (lua_Integer)first + 1);
  return 1;
}

/* }====================================================================== */

/* {======================================================================
** The writer
** ======================================================================= */

enum { UV_STRING = 1, UV_FRAMES = 2, UV_RULES = 3 };

static lwriter *checkwriter (lua_State *L, int i) {
  lwriter *w = (lwriter *)luaL_checkudata(L, i, CWRITER_T);
  if (w->closed) luaL_error(L, "the writer was closed");
  return w;
}

static int writer_free (lua_State *L) {
  lwriter *w = (lwriter *)luaL_checkudata(L, 1, CWRITER_T);
  if (!w->closed) lsys_compgeo_writer_free(&w->w);
  w->closed = 1;
  return 0;
}

/* The writer's frames (alive) and the frame at stack index i. */
static const lsys_cframe *wframe (lua_State *L, int i) {
  lsys_cframes *a;
  const lsys_cframe *f;
  lua_getiuservalue(L, 1, UV_FRAMES);
  a = checkframes(L, -1);
  f = frameat(L, a, i);
  lua_pop(L, 1);
  return f;
}

/* The string written, checked alive (an Lstring can be closed by the user)
** and not in use by a derivation or interpretation (which a rule function
** calling the writer would rewrite under them). */
static void checkstring (lua_State *L) {
  lua_getiuservalue(L, 1, UV_STRING);
  lsysL_checkwritable(L, -1, "cwriter");
  lua_pop(L, 1);
}

static int wcheck (lua_State *L, int r) {
  if (r == LSYS_OK) return 0;
  if (r == LSYS_EARG) return luaL_error(L, "the writer has no open instance");
  if (r == LSYS_ELIMIT) return luaL_error(L, "the string has too many modules");
  if (r == LSYS_ESYNTAX) return luaL_error(L, "a move or turn is not a finite number");
  return luaL_error(L, "not enough memory");
}

static uint32_t intern (lua_State *L, int ridx, const char *name) {
  lsys_lrules *R = lsysL_checkrules(L, ridx);
  lsys_error e;
  uint32_t id = lsys_alphabet_intern(R->m.ab, name, strlen(name), &e);
  if (id == 0) luaL_error(L, "%s", e.msg);
  return id;
}

static int l_cwriter (lua_State *L) {
  lwriter *w;
  lsys_lstring *s;
  lsysL_checkrules(L, 1);
  checkframes(L, 2);
  lua_settop(L, 2);
  w = (lwriter *)lua_newuserdatauv(L, sizeof *w, 3);       /* 3 */
  memset(w, 0, sizeof *w);
  w->closed = 1;                             /* until it is whole */
  luaL_setmetatable(L, CWRITER_T);
  s = lsysL_newlstring(L);                    /* 4 */
  lsysL_setowner(L, 4, 1);
  lsys_compgeo_writer_init(&w->w, s);
  lua_setiuservalue(L, 3, UV_STRING);
  lua_pushvalue(L, 2);
  lua_setiuservalue(L, 3, UV_FRAMES);
  lua_pushvalue(L, 1);
  lua_setiuservalue(L, 3, UV_RULES);
  w->w.sym_open = intern(L, 1, "[");
  w->w.sym_close = intern(L, 1, "]");
  w->w.sym_roll = intern(L, 1, "/");
  w->w.sym_pitch = intern(L, 1, "^");        /* H toward -U, as the writer's angles */
  w->w.sym_move = intern(L, 1, "f");
  w->w.sym_draw = intern(L, 1, "F");
  w->nsym = lsysL_checkrules(L, 1)->m.ab->n;
  w->closed = 0;
  return 1;
}

static int writer_symbol (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  size_t len;
  const char *name = luaL_checklstring(L, 2, &len);
  lsys_lrules *R;
  lsys_error e;
  uint32_t id;
  lua_getiuservalue(L, 1, UV_RULES);
  R = lsysL_checkrules(L, -1);
  luaL_argcheck(L, len > 0 && lsys_alphabet_scan(name, len, &R->decl) == len, 2,
                "not a module name");
  id = lsys_alphabet_intern(R->m.ab, name, len, &e);
  if (id == 0) return luaL_error(L, "%s", e.msg);
  w->nsym = R->m.ab->n;
  lua_pushinteger(L, (lua_Integer)id);
  return 1;
}

static int writer_op (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  lua_Integer sym = luaL_checkinteger(L, 2);
  int np = lua_gettop(L) - 2, k;
  double p[LSYS_MAXPARAMS];
  luaL_argcheck(L, sym >= 1 && (uint64_t)sym < w->nsym, 2, "not a symbol of W:symbol");
  luaL_argcheck(L, np <= LSYS_MAXPARAMS, 2 + LSYS_MAXPARAMS + 1, "too many parameters");
  for (k = 0; k < np; k++) p[k] = num(L, 3 + k);
  checkstring(L);
  return wcheck(L, lsys_compgeo_writer_op(&w->w, (uint32_t)sym, p, (uint32_t)np));
}

static int writer_open (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  lua_Integer inst = luaL_checkinteger(L, 2);
  const lsys_cframe *f = wframe(L, 3);
  luaL_argcheck(L, inst >= 1 && inst <= INT32_MAX / 4, 2, "not an instance index");
  checkstring(L);
  return wcheck(L, lsys_compgeo_writer_open(&w->w, (int32_t)inst, f));
}

static int writer_close (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  checkstring(L);
  return wcheck(L, lsys_compgeo_writer_close(&w->w));
}

static int writer_orient (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  const lsys_cframe *f = wframe(L, 2);
  double H[3], U[3];
  memcpy(H, f->H, sizeof H);
  memcpy(U, f->U, sizeof U);
  checkstring(L);
  return wcheck(L, lsys_compgeo_writer_orient(&w->w, H, U));
}

static int writer_forward (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  double d = num(L, 2);
  checkstring(L);
  return wcheck(L, lsys_compgeo_writer_forward(&w->w, d, lua_toboolean(L, 3)));
}

static int writer_setpos (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  const lsys_cframe *f = wframe(L, 2);
  memcpy(w->w.T.p, f->p, sizeof f->p);
  return 0;
}

/* W:segment(j): orients the turtle to stem frame j; returns the length of the
** piece from frame j - 1 and the two frames' places along the stem. */
static int writer_segment (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  const lsys_cframe *b = wframe(L, 2), *a;
  double H[3], U[3], d;
  luaL_argcheck(L, luaL_checkinteger(L, 2) >= 2, 2, "not the end of a piece");
  a = b - 1;
  d = sqrt((b->p[0] - a->p[0]) * (b->p[0] - a->p[0]) + (b->p[1] - a->p[1]) * (b->p[1] - a->p[1])
           + (b->p[2] - a->p[2]) * (b->p[2] - a->p[2]));
  lua_pushnumber(L, d);
  lua_pushnumber(L, a->u);
  lua_pushnumber(L, b->u);
  memcpy(H, b->H, sizeof H);
  memcpy(U, b->U, sizeof U);
  checkstring(L);
  wcheck(L, lsys_compgeo_writer_orient(&w->w, H, U));
  return 3;
}

static int writer_turtle (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  pushvec(L, w->w.T.p);
  pushvec(L, w->w.T.H);
  pushvec(L, w->w.T.U);
  return 3;
}

static int writer_count (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  lua_pushinteger(L, (lua_Integer)w->w.s->n);
  return 1;
}

static int writer_owner (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  lua_Integer k = luaL_checkinteger(L, 2);
  if (k < 1 || (size_t)k > w->w.s->n) return 0;
  lua_pushinteger(L, w->w.owner[k - 1]);
  return 1;
}

static int writer_range (lua_State *L) {
  lwriter *w = checkwriter(L, 1);
  lua_Integer i = luaL_checkinteger(L, 2);
  const int32_t *r;
  if (i < 1 || (lua_Unsigned)(i - 1) >= w->w.capi / 3) return 0;
  r = w->w.range + 3 * (i - 1);
  if (r[0] == 0 || r[1] == 0) return 0;
  lua_pushinteger(L, r[0]);
  lua_pushinteger(L, r[1]);
  lua_pushinteger(L, r[2]);
  return 3;
}

static int writer_lstring (lua_State *L) {
  checkwriter(L, 1);
  lua_getiuservalue(L, 1, UV_STRING);
  return 1;
}

/* }====================================================================== */

static const luaL_Reg frames_methods[] = {
  {"add", frames_add}, {"set", frames_set}, {"get", frames_get}, {"scale", frames_scale},
  {"count", frames_count}, {"random", frames_random}, {"copy", frames_copy},
  {"transform", frames_transform}, {"ahead", frames_ahead}, {"branch", frames_branch},
  {"place", frames_place}, {"stem", frames_stem}, {"close", frames_close},
  {NULL, NULL}
};

static const luaL_Reg frames_meta[] = {
  {"__index", NULL}, {"__gc", frames_close}, {"__close", frames_close}, {NULL, NULL}
};

static const luaL_Reg writer_methods[] = {
  {"symbol", writer_symbol}, {"op", writer_op}, {"open", writer_open}, {"close", writer_close},
  {"orient", writer_orient}, {"forward", writer_forward}, {"setpos", writer_setpos},
  {"segment", writer_segment}, {"turtle", writer_turtle}, {"count", writer_count},
  {"owner", writer_owner}, {"range", writer_range}, {"lstring", writer_lstring},
  {"free", writer_free}, {NULL, NULL}
};

static const luaL_Reg writer_meta[] = {
  {"__index", NULL}, {"__gc", writer_free}, {"__close", writer_free}, {NULL, NULL}
};

void lsysL_open_compgeo (lua_State *L) {
  lsysL_createmeta(L, FRAMES_T, frames_meta, frames_methods);
  lsysL_createmeta(L, CWRITER_T, writer_meta, writer_methods);
  lua_pushcfunction(L, l_frames);
  lua_setfield(L, -2, "frames");
  lua_pushcfunction(L, l_cwriter);
  lua_setfield(L, -2, "cwriter");
}
