/*
** Rendering and PNG functions of lsys.core: render, png_read, png_write,
** has_render.
*/
#include <math.h>
#include <string.h>

#include "lua_geom.h"
#include "outfile.h"
#include "pngio.h"

#define PIXELS_T "lsys.Pixels"   /* a malloc'd pixel block owned by Lua until copied */

#ifndef LSYS_NO_RENDER

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

/* Pushes opts[key]; returns 0 (and pops it) when it is nil. */
static int field (lua_State *L, int t, const char *key) {
  if (t == 0) return 0;
  if (lua_getfield(L, t, key) == LUA_TNIL) { lua_pop(L, 1); return 0; }
  return 1;
}

static int getint (lua_State *L, int t, const char *key, int lo, int hi, int def) {
  lua_Integer v;
  int isint;
  if (!field(L, t, key)) return def;
  v = lua_tointegerx(L, -1, &isint);
  if (!isint || v < lo || v > hi) {
    if (lo == 1)
      luaL_error(L, "lsys.render: opts.%s must be a positive integer at most %d, got %s",
                 key, hi, got(L, -1));
    luaL_error(L, "lsys.render: opts.%s must be an integer in [%d, %d], got %s", key, lo, hi,
               got(L, -1));
  }
  lua_pop(L, 1);
  return (int)v;
}

/* A number in (lo, hi) (open interval; infinities for no bound). */
static double getnum (lua_State *L, int t, const char *key, double lo, double hi,
                      const char *what, double def) {
  double x;
  if (!field(L, t, key)) return def;
  x = lua_type(L, -1) == LUA_TNUMBER ? lua_tonumber(L, -1) : NAN;
  if (!isfinite(x) || !(x > lo) || !(x < hi))
    luaL_error(L, "lsys.render: opts.%s must be %s, got %s", key, what, got(L, -1));
  lua_pop(L, 1);
  return x;
}

static int getbool (lua_State *L, int t, const char *key) {
  int b;
  if (!field(L, t, key)) return 0;
  if (!lua_isboolean(L, -1))
    luaL_error(L, "lsys.render: opts.%s must be a boolean, got %s", key, got(L, -1));
  b = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return b;
}

/* Reads {x, y, z} (finite numbers; within [0, 1] for a colour). */
static int getvec3 (lua_State *L, int t, const char *key, int colour, double v[3]) {
  int i, ok;
  if (!field(L, t, key)) return 0;
  ok = lua_type(L, -1) == LUA_TTABLE && luaL_len(L, -1) == 3;
  for (i = 0; ok && i < 3; i++) {
    ok = lua_rawgeti(L, -1, i + 1) == LUA_TNUMBER && isfinite(v[i] = lua_tonumber(L, -1)) &&
         (!colour || (v[i] >= 0 && v[i] <= 1));
    lua_pop(L, 1);
  }
  if (!ok) {
    if (colour)
      luaL_error(L, "lsys.render: opts.%s must be {r, g, b} with numbers in [0, 1]", key);
    luaL_error(L, "lsys.render: opts.%s must be {x, y, z} with 3 finite numbers", key);
  }
  lua_pop(L, 1);
  return 1;
}

static const char *const optnames[] = {
  "out", "width", "height", "supersample", "background", "transparent", "light", "wireframe",
  "viewpoint", "target", "up", "direction", "projection", "fov", "twist", "zoom", "textures",
  NULL
};

/* Fills 'o' from the options table at 't' (0: none), checking every field. */
void lsys_readrenderopts (lua_State *L, int t, lsys_render_opts *o) {
  lsys_camera *cam = &o->cam;
  double v[3];
  lsys_render_defaults(o);
  if (t != 0) {                       /* unknown keys are mistakes */
    lua_pushnil(L);
    while (lua_next(L, t)) {
      int i;
      lua_pop(L, 1);
      for (i = 0; optnames[i]; i++)
        if (lua_type(L, -1) == LUA_TSTRING && strcmp(lua_tostring(L, -1), optnames[i]) == 0)
          break;
      if (optnames[i] == NULL)
        luaL_error(L, "lsys.render: unknown option %s", got(L, -1));
    }
  }
  o->width = getint(L, t, "width", 1, 16384, o->width);
  o->height = getint(L, t, "height", 1, 16384, o->height);
  o->supersample = getint(L, t, "supersample", 1, 16, o->supersample);
  if (getvec3(L, t, "background", 1, v)) {
    o->background[0] = (float)v[0];
    o->background[1] = (float)v[1];
    o->background[2] = (float)v[2];
  }
  o->transparent = getbool(L, t, "transparent");
  if (getvec3(L, t, "light", 0, o->light) && o->light[0] == 0 && o->light[1] == 0 &&
      o->light[2] == 0)
    luaL_error(L, "lsys.render: opts.light must not be the zero vector");
  o->wireframe = getbool(L, t, "wireframe");
  cam->has_eye = getvec3(L, t, "viewpoint", 0, cam->eye);
  cam->has_target = getvec3(L, t, "target", 0, cam->target);
  cam->has_up = getvec3(L, t, "up", 0, cam->up);
  if (cam->has_up && cam->up[0] == 0 && cam->up[1] == 0 && cam->up[2] == 0)
    luaL_error(L, "lsys.render: opts.up must not be the zero vector");
  if (getvec3(L, t, "direction", 0, cam->dir) && cam->dir[0] == 0 && cam->dir[1] == 0 &&
      cam->dir[2] == 0)
    luaL_error(L, "lsys.render: opts.direction must not be the zero vector");
  if (cam->has_eye && cam->has_target && cam->eye[0] == cam->target[0] &&
      cam->eye[1] == cam->target[1] && cam->eye[2] == cam->target[2])
    luaL_error(L, "lsys.render: opts.viewpoint and opts.target must differ");
  if (field(L, t, "projection")) {
    const char *p = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "";
    if (strcmp(p, "perspective") == 0) cam->projection = LSYS_PERSPECTIVE;
    else if (strcmp(p, "parallel") == 0) cam->projection = LSYS_PARALLEL;
    else
      luaL_error(L, "lsys.render: opts.projection must be 'perspective' or 'parallel', got %s",
                 got(L, -1));
    lua_pop(L, 1);
  }
  cam->fov = getnum(L, t, "fov", 0, 180, "a number of degrees in (0, 180)", cam->fov);
  cam->twist = getnum(L, t, "twist", -HUGE_VAL, HUGE_VAL, "a number of degrees", 0);
  cam->zoom = getnum(L, t, "zoom", 0, HUGE_VAL, "a positive number", 1);
}

#endif

/*
** core.render(scene [, opts]): draws the scene offscreen. With opts.out,
** writes that PNG file (RGB, or RGBA with opts.transparent) and returns
** true; otherwise returns the RGBA pixels (a string, top row first), the
** width and the height. opts.textures is the list of lsys.Texture that the
** scene's texture indices refer to (index k: the k-th); the options table
** keeps them alive during the call. The supersampling factor is lowered
** when the supersampled image would exceed OSMesa's maximum size or
** LSYS_RENDER_MAX_SAMPLES; width and height themselves must fit OSMesa.
*/
static int l_render (lua_State *L) {
#ifdef LSYS_NO_RENDER
  return luaL_error(L, "lsys was built without OSMesa: install libosmesa6-dev and rebuild "
                       "(./setup.sh does)");
#else
  const lsys_material *pal;
  size_t npal, n;
  const lsys_mesh *m = lsys_checkscene(L, 1, &pal, &npal);
  const char *out = NULL;
  lsys_render_opts o;
  lsys_error e;
  luaL_Buffer b;
  uint8_t *px;
  int t = lua_isnoneornil(L, 2) ? 0 : 2, maxw, maxh;
  if (t) luaL_checktype(L, 2, LUA_TTABLE);
  lsys_readrenderopts(L, t, &o);
  o.tex = lsys_opttextures(L, t, "lsys.render", &o.ntex);   /* pushes one value */
  if (field(L, t, "out")) {
    if (lua_type(L, -1) != LUA_TSTRING)
      luaL_error(L, "lsys.render: opts.out must be a file name, got %s", got(L, -1));
    out = lua_tostring(L, -1);        /* stays on the stack */
  }
  o.pal = pal;
  o.npal = npal;
  if (lsys_render_maxsize(&maxw, &maxh, &e) != LSYS_OK)
    return luaL_error(L, "lsys.render: %s", e.msg);
  if (o.width > maxw || o.height > maxh)
    return luaL_error(L, "lsys.render: %dx%d is larger than OSMesa's limit of %dx%d",
                      o.width, o.height, maxw, maxh);
  n = (size_t)o.width * (size_t)o.height * 4;
  if ((double)n * 3 > (double)lsys_memory_limit()) {   /* the picture, colour and depth */
    char b1[32], b2[32];
    return luaL_error(L, "lsys.render: a %dx%d picture needs %s, more than max_memory (%s)",
                      o.width, o.height, lsys_fmtsize(b1, n * 3),
                      lsys_fmtsize(b2, lsys_memory_limit()));
  }
  /* the pixels live in Lua memory, so an error cannot leak them */
  px = out ? (uint8_t *)lua_newuserdatauv(L, n, 0) : (uint8_t *)luaL_buffinitsize(L, &b, n);
  if (lsys_render_offscreen(m, &o, px, &e) != LSYS_OK)
    return luaL_error(L, "lsys.render: %s", e.msg);
  if (out) {
    if (lsys_png_write(out, px, o.width, o.height, o.transparent, &e) != LSYS_OK)
      return luaL_error(L, "lsys.render: %s", e.msg);
    lua_pushboolean(L, 1);
    return 1;
  }
  luaL_pushresultsize(&b, n);
  lua_pushinteger(L, o.width);
  lua_pushinteger(L, o.height);
  return 3;
#endif
}

static int pixels_gc (lua_State *L) {
  uint8_t **p = (uint8_t **)luaL_checkudata(L, 1, PIXELS_T);
  LSYS_FREE(*p);
  *p = NULL;
  return 0;
}

/* core.png_read(path): the RGBA pixels (a string, top row first), width, height. */
static int l_png_read (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  uint8_t **box = (uint8_t **)lua_newuserdatauv(L, sizeof *box, 0);
  int w, h;
  lsys_error e;
  *box = NULL;
  luaL_setmetatable(L, PIXELS_T);
  if (lsys_png_read(path, box, &w, &h, &e) != LSYS_OK) return lsys_raise(L, e.code, &e);
  lua_pushlstring(L, (const char *)*box, (size_t)w * h * 4);
  LSYS_FREE(*box);
  *box = NULL;
  lua_pushinteger(L, w);
  lua_pushinteger(L, h);
  return 3;
}

/*
** core.png_write(path, pixels, w, h [, alpha]): writes RGBA pixels (top row
** first) as a PNG; RGBA when 'alpha' is true, RGB when false, and when it
** is absent RGBA only if some pixel is not opaque. Returns true.
*/
static int l_png_write (lua_State *L) {
  size_t len, i;
  const char *path = luaL_checkstring(L, 1);
  const uint8_t *px = (const uint8_t *)luaL_checklstring(L, 2, &len);
  lua_Integer w = luaL_checkinteger(L, 3), h = luaL_checkinteger(L, 4);
  int alpha = 0;
  lsys_error e;
  luaL_argcheck(L, w > 0 && w <= LSYS_PNG_MAXSIZE, 3, "width out of range");
  luaL_argcheck(L, h > 0 && h <= LSYS_PNG_MAXSIZE, 4, "height out of range");
  if (len != (size_t)w * (size_t)h * 4)
    return luaL_error(L, "lsys.png_write: %I x %I RGBA pixels need %I bytes, got %I", w, h,
                      (lua_Integer)(w * h * 4), (lua_Integer)len);
  if (lua_isnoneornil(L, 5)) {
    for (i = 3; i < len && !alpha; i += 4) alpha = px[i] != 255;
  } else {
    luaL_checktype(L, 5, LUA_TBOOLEAN);
    alpha = lua_toboolean(L, 5);
  }
  if (lsys_png_write(path, px, (int)w, (int)h, alpha, &e) != LSYS_OK)
    return lsys_raise(L, e.code, &e);
  lua_pushboolean(L, 1);
  return 1;
}

/* core.write_file(path, bytes): writes the string atomically (outfile.h). */
static int l_write_file (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  size_t len;
  const char *bytes = luaL_checklstring(L, 2, &len);
  lsys_outfile out;
  lsys_error e;
  int st = lsys_outfile_open(&out, path, &e);
  if (st == LSYS_OK) {
    lsys_outfile_write(&out, bytes, len);
    st = lsys_outfile_commit(&out, &e);
  }
  if (st != LSYS_OK) return lsys_raise(L, st, &e);
  lua_pushboolean(L, 1);
  return 1;
}

/* core.read_file(path, max) -> the bytes of a regular file of at most 'max'
** bytes, or nil and a message naming the file (lsys_readfile) */
static int l_read_file (lua_State *L) {
  const char *path = luaL_checkstring(L, 1);
  lua_Number max = luaL_checknumber(L, 2);
  lsys_error e;
  size_t len;
  char *text;
  luaL_argcheck(L, max >= 0 && max < 1e15, 2, "a number of bytes expected");
  text = lsys_readfile(path, (size_t)max, &len, &e);
  if (text == NULL) {
    lua_pushnil(L);
    lua_pushstring(L, e.msg);
    return 2;
  }
  lua_pushlstring(L, text, len);     /* may raise: a leak only on a memory error */
  LSYS_FREE(text);
  return 1;
}

static const luaL_Reg render_funcs[] = {
  {"render", l_render}, {"png_read", l_png_read}, {"png_write", l_png_write},
  {"write_file", l_write_file}, {"read_file", l_read_file}, {NULL, NULL}
};

#ifndef LSYS_NO_RENDER
/* At lua_close: the offscreen context and its scratch are freed before the C
** library is unloaded (they would show as leaks). */
static int renderstate_gc (lua_State *L) {
  (void)L;
  lsys_render_shutdown();
  return 0;
}
#endif

void lsys_open_render (lua_State *L) {
  luaL_newmetatable(L, PIXELS_T);
  lua_pushcfunction(L, pixels_gc);
  lua_setfield(L, -2, "__gc");
  lua_pop(L, 1);
#ifndef LSYS_NO_RENDER
  if (lua_getfield(L, LUA_REGISTRYINDEX, "lsys.renderstate") == LUA_TNIL) {
    lua_newuserdatauv(L, 0, 0);
    lua_newtable(L);
    lua_pushcfunction(L, renderstate_gc);
    lua_setfield(L, -2, "__gc");
    lua_setmetatable(L, -2);
    lua_setfield(L, LUA_REGISTRYINDEX, "lsys.renderstate");
  }
  lua_pop(L, 1);
#endif
  luaL_setfuncs(L, render_funcs, 0);
#ifdef LSYS_NO_RENDER
  lua_pushboolean(L, 0);
#else
  lua_pushboolean(L, 1);
#endif
  lua_setfield(L, -2, "has_render");
}
