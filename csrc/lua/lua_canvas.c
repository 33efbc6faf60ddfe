/*
** Lua binding of csrc/core/canvas.h: the lsys.Canvas userdata.
**
**   core.canvas(w, h [, colour]) -> Canvas   (w, h in [1, 16384]; transparent black
**                                             unless a colour is given)
**   c:clear([colour])                        c:size() -> w, h
**   c:line(x0, y0, x1, y1 [, width [, colour]])
**   c:polyline(points [, width [, colour]])  points {{x, y}, ...} or {x1, y1, x2, y2, ...}
**   c:rect(x, y, w, h [, colour [, fill]])   c:circle(x, y, r [, colour])
**   c:text(x, y, s [, scale [, colour]]) -> width     c:text_width(s [, scale]) -> width
**   c:clip(x, y, w, h) / c:clip()            c:save(path)  (PNG, replaced atomically)
**   c:pixels() -> string of w * h * 4 bytes (RGBA, top row first)
**
** A colour is {r, g, b [, a]} with numbers in [0, 1], or "#rrggbb" / "#rrggbbaa";
** absent, it is opaque black (transparent black for the canvas and clear).
** Widths default to 1 and scales to 1. Coordinates may be any numbers: a
** shape with a NaN or infinite one is not drawn (a plot of a function
** with a pole draws what it can); sizes must be numbers >= 0 (widths > 0).
*/
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"

#define CANVAS_TOSTR "Canvas"

/* The canvas at 'i'; raises when it is not one or was closed. */
lsys_canvas *lsysL_checkcanvas (lua_State *L, int i) {
  lsys_canvas *c = (lsys_canvas *)luaL_checkudata(L, i, CANVAS_T);
  if (c->px == NULL) luaL_error(L, "the canvas was closed");
  return c;
}

static int hexdigit (int ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  return -1;
}

/* "#rrggbb" or "#rrggbbaa" into rgba; 0 when it is neither. */
static int hexcolour (const char *s, size_t n, double rgba[4]) {
  size_t k;
  if ((n != 7 && n != 9) || s[0] != '#') return 0;
  rgba[3] = 1;
  for (k = 0; 2 * k + 1 < n; k++) {
    int hi = hexdigit((unsigned char)s[2 * k + 1]), lo = hexdigit((unsigned char)s[2 * k + 2]);
    if (hi < 0 || lo < 0) return 0;
    rgba[k] = (hi * 16 + lo) / 255.0;
  }
  return 1;
}

/* The colour argument at 'i' (absent: 'def'). */
static void checkcolour (lua_State *L, int i, double rgba[4], const double def[4]) {
  static const char *const expect = "colour {r, g, b [, a]} with numbers in [0, 1] or "
                                    "\"#rrggbb\" expected";
  int t = lua_type(L, i);
  if (t == LUA_TNONE || t == LUA_TNIL) {
    memcpy(rgba, def, 4 * sizeof *rgba);
  } else if (t == LUA_TSTRING) {
    size_t n;
    const char *s = lua_tolstring(L, i, &n);
    if (!hexcolour(s, n, rgba))
      luaL_argerror(L, i, lua_pushfstring(L, "%s, got '%s'", expect, s));
  } else if (t == LUA_TTABLE) {
    lua_Integer n = luaL_len(L, i), k;
    if (n != 3 && n != 4) luaL_argerror(L, i, expect);
    rgba[3] = 1;
    for (k = 1; k <= n; k++) {
      int isnum;
      double v;
      lua_rawgeti(L, i, k);
      v = lua_tonumberx(L, -1, &isnum);
      lua_pop(L, 1);
      if (!isnum || !(v >= 0 && v <= 1)) luaL_argerror(L, i, expect);
      rgba[k - 1] = v;
    }
  } else {
    luaL_typeerror(L, i, "colour");
  }
}

static const double BLACK[4] = { 0, 0, 0, 1 }, CLEAR[4] = { 0, 0, 0, 0 };

/* A size argument: a number >= 0 (> 0 when 'positive'), 'def' when absent. */
static double checksize (lua_State *L, int i, double def, int positive) {
  double v = luaL_optnumber(L, i, def);
  luaL_argcheck(L, positive ? v > 0 && v <= HUGE_VAL : v >= 0 && v <= HUGE_VAL, i,
                positive ? "must be a number > 0" : "must be a number >= 0");
  return v;
}

/* core.canvas(w, h [, colour]) */
static int l_canvas (lua_State *L) {
  lua_Integer w = luaL_checkinteger(L, 1), h = luaL_checkinteger(L, 2);
  double rgba[4];
  lsys_canvas *c;
  lsys_error e;
  luaL_argcheck(L, w >= 1 && w <= LSYS_CANVAS_MAXSIZE, 1, "width must be in [1, 16384]");
  luaL_argcheck(L, h >= 1 && h <= LSYS_CANVAS_MAXSIZE, 2, "height must be in [1, 16384]");
  checkcolour(L, 3, rgba, CLEAR);
  c = (lsys_canvas *)lua_newuserdatauv(L, sizeof *c, 0);
  memset(c, 0, sizeof *c);                  /* valid (closed) before anything can fail */
  luaL_setmetatable(L, CANVAS_T);
  if (lsys_canvas_init(c, (int)w, (int)h, &e) != LSYS_OK)
    return luaL_error(L, "lsys.canvas: %s", e.msg);
  lsys_canvas_clear(c, rgba);
  return 1;
}

static int canvas_gc (lua_State *L) {         /* also __close: idempotent */
  lsys_canvas_free((lsys_canvas *)luaL_checkudata(L, 1, CANVAS_T));
  return 0;
}

/* Each method takes the canvas after reading its colour (luaL_len runs a
** table's metamethod, which may close the canvas). */
static int canvas_clear (lua_State *L) {
  double rgba[4];
  lsysL_checkcanvas(L, 1);
  checkcolour(L, 2, rgba, CLEAR);
  lsys_canvas_clear(lsysL_checkcanvas(L, 1), rgba);
  return 0;
}

static int canvas_size (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  lua_pushinteger(L, c->w);
  lua_pushinteger(L, c->h);
  return 2;
}

static int canvas_line (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  double x0 = luaL_checknumber(L, 2), y0 = luaL_checknumber(L, 3);
  double x1 = luaL_checknumber(L, 4), y1 = luaL_checknumber(L, 5);
  double width = checksize(L, 6, 1, 1), rgba[4];
  checkcolour(L, 7, rgba, BLACK);
  c = lsysL_checkcanvas(L, 1);
  lsys_canvas_line(c, x0, y0, x1, y1, width, rgba);
  return 0;
}

/* Point k (1-based) of the list at 'i', as {x, y} or as a flat list. */
static void getpoint (lua_State *L, int i, int flat, lua_Integer k, double *x, double *y) {
  int okx, oky;
  if (flat) {
    lua_rawgeti(L, i, 2 * k - 1);
    lua_rawgeti(L, i, 2 * k);
  } else {
    if (lua_rawgeti(L, i, k) != LUA_TTABLE)
      luaL_error(L, "bad argument #2 to 'polyline' (points[%I] must be {x, y}, got %s)",
                 (LUAI_UACINT)k, luaL_typename(L, -1));
    lua_rawgeti(L, -1, 1);
    lua_rawgeti(L, -2, 2);
    lua_remove(L, -3);
  }
  *x = lua_tonumberx(L, -2, &okx);
  *y = lua_tonumberx(L, -1, &oky);
  lua_pop(L, 2);
  if (!okx || !oky) {
    if (flat)
      luaL_error(L, "bad argument #2 to 'polyline' (points[%I] must be a number)",
                 (LUAI_UACINT)(okx ? 2 * k : 2 * k - 1));
    luaL_error(L, "bad argument #2 to 'polyline' (points[%I] must be {x, y} with two numbers)",
               (LUAI_UACINT)k);
  }
}

/* c:polyline(points [, width [, colour]]): segment by segment, nothing allocated. */
static int canvas_polyline (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  double width = checksize(L, 3, 1, 1), rgba[4], xy[4];
  lua_Integer n, k;
  int flat;
  luaL_checktype(L, 2, LUA_TTABLE);
  checkcolour(L, 4, rgba, BLACK);
  n = luaL_len(L, 2);
  c = lsysL_checkcanvas(L, 1);               /* nothing below runs Lua code */
  flat = n > 0 && lua_rawgeti(L, 2, 1) != LUA_TTABLE;
  if (n > 0) lua_pop(L, 1);
  if (flat) {
    luaL_argcheck(L, n % 2 == 0, 2, "a flat list of points must have an even length");
    n /= 2;
  }
  for (k = 1; k <= n; k++) {
    getpoint(L, 2, flat, k, &xy[2], &xy[3]);
    if (k > 1) lsys_canvas_polyline(c, xy, 2, width, rgba);
    xy[0] = xy[2];
    xy[1] = xy[3];
  }
  return 0;
}

static int canvas_rect (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  double x = luaL_checknumber(L, 2), y = luaL_checknumber(L, 3);
  double w = (luaL_checknumber(L, 4), checksize(L, 4, 0, 0));
  double h = (luaL_checknumber(L, 5), checksize(L, 5, 0, 0)), rgba[4];
  checkcolour(L, 6, rgba, BLACK);
  c = lsysL_checkcanvas(L, 1);
  lsys_canvas_rect(c, x, y, w, h, rgba, lua_toboolean(L, 7));
  return 0;
}

static int canvas_circle (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  double x = luaL_checknumber(L, 2), y = luaL_checknumber(L, 3), r, rgba[4];
  luaL_checknumber(L, 4);
  r = checksize(L, 4, 0, 0);
  checkcolour(L, 5, rgba, BLACK);
  c = lsysL_checkcanvas(L, 1);
  lsys_canvas_circle(c, x, y, r, rgba);
  return 0;
}

static int checkscale (lua_State *L, int i) {
  lua_Integer s = luaL_optinteger(L, i, 1);
  luaL_argcheck(L, s >= 1 && s <= 64, i, "scale must be an integer in [1, 64]");
  return (int)s;
}

static int canvas_text (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  double x = luaL_checknumber(L, 2), y = luaL_checknumber(L, 3), rgba[4];
  size_t n;
  const char *s = luaL_checklstring(L, 4, &n);
  int scale = checkscale(L, 5);
  checkcolour(L, 6, rgba, BLACK);
  c = lsysL_checkcanvas(L, 1);
  lsys_canvas_text(c, x, y, s, n, scale, rgba);
  lua_pushinteger(L, (lua_Integer)lsys_canvas_text_width(n, scale));
  return 1;
}

static int canvas_text_width (lua_State *L) {
  size_t n;
  lsysL_checkcanvas(L, 1);
  luaL_checklstring(L, 2, &n);
  lua_pushinteger(L, (lua_Integer)lsys_canvas_text_width(n, checkscale(L, 3)));
  return 1;
}

static int canvas_clip (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  if (lua_gettop(L) <= 1) {
    lsys_canvas_unclip(c);
  } else {
    double x = luaL_checknumber(L, 2), y = luaL_checknumber(L, 3);
    double w = (luaL_checknumber(L, 4), checksize(L, 4, 0, 0));
    double h = (luaL_checknumber(L, 5), checksize(L, 5, 0, 0));
    lsys_canvas_clip(c, x, y, w, h);
  }
  return 0;
}

static int canvas_save (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  const char *path = luaL_checkstring(L, 2);
  lsys_error e;
  c = lsysL_checkcanvas(L, 1);               /* again: converting a number allocates */
  if (lsys_canvas_save(c, path, &e) != LSYS_OK) return luaL_error(L, "save: %s", e.msg);
  return 0;
}

static int canvas_pixels (lua_State *L) {
  lsys_canvas *c = lsysL_checkcanvas(L, 1);
  lua_pushlstring(L, (const char *)c->px, (size_t)c->w * (size_t)c->h * 4);
  return 1;
}

static int canvas_tostring (lua_State *L) {
  lsys_canvas *c = (lsys_canvas *)luaL_checkudata(L, 1, CANVAS_T);
  if (c->px == NULL) lua_pushliteral(L, CANVAS_TOSTR " (closed)");
  else lua_pushfstring(L, CANVAS_TOSTR "(%dx%d)", c->w, c->h);
  return 1;
}

static const luaL_Reg canvas_methods[] = {
  {"clear", canvas_clear}, {"size", canvas_size}, {"line", canvas_line},
  {"polyline", canvas_polyline}, {"rect", canvas_rect}, {"circle", canvas_circle},
  {"text", canvas_text}, {"text_width", canvas_text_width}, {"clip", canvas_clip},
  {"save", canvas_save}, {"pixels", canvas_pixels}, {NULL, NULL}
};

static const luaL_Reg canvas_meta[] = {
  {"__index", NULL},  /* placeholder: set to the method table */
  {"__gc", canvas_gc}, {"__close", canvas_gc}, {"__tostring", canvas_tostring},
  {NULL, NULL}
};

void lsysL_open_canvas (lua_State *L) {
  lsysL_createmeta(L, CANVAS_T, canvas_meta, canvas_methods);
  lua_pushcfunction(L, l_canvas);
  lua_setfield(L, -2, "canvas");
}
