/*
** Lua binding of csrc/core/texture.h: the lsys.Texture userdata.
**
**   core.texture_load(path [, opts]) -> Texture
**     opts: mag, min = "linear" | "near" (or "l" | "n"; default "near"),
**           mode = "modulate" | "decal" (or "m" | "d"; default "modulate"),
**           per_surface = boolean (false), intensity = boolean (true for a
**           grey image, else false)
**   t:size() -> width, height          t:info() -> table of the settings
**
** A Texture is immutable once loaded: the renderer and the export writers
** read it while holding only a pointer taken from the Lua stack.
*/
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"

static const char *const optnames[] = {
  "mag", "min", "mode", "per_surface", "intensity", NULL
};

/* core.texture_load(path [, opts]): every option is checked before the file is read. */
static int l_texture_load (lua_State *L) {
  static const char *const filters[] = {"near", "n", "linear", "l", NULL};
  static const char *const modes[] = {"modulate", "m", "decal", "d", NULL};
  static const char *const fexpect = "'linear', 'near', 'l' or 'n'";
  const char *path = luaL_checkstring(L, 1);
  lsys_ltexture *u;
  lsys_texture *t;
  lsys_error e;
  int mag = 0, min = 0, mode = LSYS_TEX_MODULATE, per_surface = 0, intensity = -1;
  if (!lua_isnoneornil(L, 2)) {        /* long and one-letter names alternate: index / 2 */
    lsys_opts o = {2, NULL, "", LSYS_GOT_TYPE, 0};
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_settop(L, 2);
    o.pre = lua_pushfstring(L, "lsys.texture_load: '%s': opts.", path);     /* 3 */
    if (lsysL_optunknown(L, &o, optnames)) {
      const char *k = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1)
                                                      : luaL_typename(L, -1);
      return luaL_error(L, "lsys.texture_load: '%s': unknown option '%s' (known: mag, min, "
                        "mode, per_surface, intensity)", path, k);
    }
    mag = lsysL_optchoice(L, &o, "mag", 0, filters, fexpect) / 2;
    min = lsysL_optchoice(L, &o, "min", 0, filters, fexpect) / 2;
    mode = lsysL_optchoice(L, &o, "mode", 0, modes, "'modulate', 'decal', 'm' or 'd'") / 2;
    per_surface = lsysL_optbool(L, &o, "per_surface", -1) == 1;
    intensity = lsysL_optbool(L, &o, "intensity", -1);
  }
  u = (lsys_ltexture *)lua_newuserdatauv(L, sizeof *u, 0);
  t = &u->t;
  lsys_texture_init(t);                     /* valid before anything can fail */
  u->life.closed = u->life.kept = 0;
  luaL_setmetatable(L, TEXTURE_T);
  if (lsys_texture_load(t, path, &e) != LSYS_OK) {
    if (e.code == LSYS_ENOMEM) return luaL_error(L, "lsys.texture_load: '%s': not enough memory",
                                                 path);
    return luaL_error(L, "lsys.texture_load: %s", e.msg);
  }
  t->mag_linear = mag;
  t->min_linear = min;
  t->mode = mode;
  t->per_surface = per_surface;
  if (intensity >= 0) t->intensity = intensity;
  return 1;
}

/* __gc and __close: idempotent; a kept texture (a Scene's, or one an
** operation reads) is freed by the collector. */
static int texture_gc (lua_State *L) {
  lsys_ltexture *u = (lsys_ltexture *)luaL_checkudata(L, 1, TEXTURE_T);
  if (lsysL_life_end(L, &u->life)) lsys_texture_free(&u->t);
  return 0;
}

static int texture_size (lua_State *L) {
  const lsys_texture *t = lsysL_checktexture(L, 1);
  lua_pushinteger(L, t->w);
  lua_pushinteger(L, t->h);
  return 2;
}

/* t:info() -> { path =, width =, height =, mag =, min =, mode =, per_surface =,
** intensity =, alpha = } with the long names of the settings. */
static int texture_info (lua_State *L) {
  lsys_texture t = *lsysL_checktexture(L, 1);   /* a copy: the table is made after */
  lua_createtable(L, 0, 9);
  if (t.path != NULL) {                     /* the string is read again, alive */
    lua_pushstring(L, lsysL_checktexture(L, 1)->path);
    lua_setfield(L, -2, "path");
  }
  lua_pushinteger(L, t.w); lua_setfield(L, -2, "width");
  lua_pushinteger(L, t.h); lua_setfield(L, -2, "height");
  lua_pushstring(L, t.mag_linear ? "linear" : "near"); lua_setfield(L, -2, "mag");
  lua_pushstring(L, t.min_linear ? "linear" : "near"); lua_setfield(L, -2, "min");
  lua_pushstring(L, t.mode == LSYS_TEX_DECAL ? "decal" : "modulate");
  lua_setfield(L, -2, "mode");
  lua_pushboolean(L, t.per_surface); lua_setfield(L, -2, "per_surface");
  lua_pushboolean(L, t.intensity); lua_setfield(L, -2, "intensity");
  lua_pushboolean(L, lsys_texture_hasalpha(lsysL_checktexture(L, 1))); lua_setfield(L, -2, "alpha");
  return 1;
}

static int texture_tostring (lua_State *L) {
  lsys_ltexture *u = (lsys_ltexture *)luaL_checkudata(L, 1, TEXTURE_T);
  lsys_texture *t = &u->t;
  if (u->life.closed) {
    lua_pushliteral(L, "Texture (closed)");
    return 1;
  }
  lua_pushfstring(L, "Texture(%s, %dx%d)", t->path ? t->path : "?", t->w, t->h);
  return 1;
}

static const luaL_Reg texture_methods[] = {
  {"size", texture_size}, {"info", texture_info}, {NULL, NULL}
};

static const luaL_Reg texture_meta[] = {
  {"__index", NULL},  /* placeholder: set to the method table */
  {"__gc", texture_gc}, {"__close", texture_gc}, {"__tostring", texture_tostring},
  {NULL, NULL}
};

void lsysL_open_texture (lua_State *L) {
  lsysL_createmeta(L, TEXTURE_T, texture_meta, texture_methods);
  lua_pushcfunction(L, l_texture_load);
  lua_setfield(L, -2, "texture_load");
}
