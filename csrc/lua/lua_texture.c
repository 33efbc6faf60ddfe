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

#include "lua_geom.h"

#define TEXTURE_T "lsys.Texture"
/* The Texture at 'i'; raises when it was closed (a live one has pixels). */
static lsys_texture *checktex (lua_State *L, int i) {
  lsys_texture *t = (lsys_texture *)luaL_checkudata(L, i, TEXTURE_T);
  if (t->rgba == NULL) luaL_error(L, "the texture was closed");
  return t;
}

const lsys_texture *lsys_checktexture (lua_State *L, int idx) {
  return checktex(L, idx);
}

static const char *const optnames[] = {
  "mag", "min", "mode", "per_surface", "intensity", NULL
};

/* A string option out of 'names' (long and one-letter forms alternate);
** returns the index of its long form / 2, or 'def' when absent. */
static int getchoice (lua_State *L, const char *path, const char *key,
                      const char *const names[], const char *expect, int def) {
  int i;
  const char *s;
  if (lua_getfield(L, 2, key) == LUA_TNIL) {
    lua_pop(L, 1);
    return def;
  }
  s = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
  for (i = 0; s != NULL && names[i] != NULL; i++)
    if (strcmp(s, names[i]) == 0) {
      lua_pop(L, 1);
      return i / 2;
    }
  if (s != NULL)
    return luaL_error(L, "lsys.texture_load: '%s': opts.%s must be %s, got '%s'", path, key,
                      expect, s);
  return luaL_error(L, "lsys.texture_load: '%s': opts.%s must be %s, got %s", path, key,
                    expect, luaL_typename(L, -1));
}

/* A boolean option: 1, 0, or -1 when absent. */
static int getflag (lua_State *L, const char *path, const char *key) {
  int b;
  if (lua_getfield(L, 2, key) == LUA_TNIL) {
    lua_pop(L, 1);
    return -1;
  }
  if (!lua_isboolean(L, -1))
    return luaL_error(L, "lsys.texture_load: '%s': opts.%s must be a boolean, got %s", path,
                      key, luaL_typename(L, -1));
  b = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return b;
}

/* core.texture_load(path [, opts]): every option is checked before the file is read. */
static int l_texture_load (lua_State *L) {
  static const char *const filters[] = {"near", "n", "linear", "l", NULL};
  static const char *const modes[] = {"modulate", "m", "decal", "d", NULL};
  static const char *const fexpect = "'linear', 'near', 'l' or 'n'";
  const char *path = luaL_checkstring(L, 1);
  lsys_texture *t;
  lsys_error e;
  int mag = 0, min = 0, mode = LSYS_TEX_MODULATE, per_surface = 0, intensity = -1;
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    lua_pushnil(L);
    while (lua_next(L, 2)) {
      int i;
      lua_pop(L, 1);
      for (i = 0; optnames[i] != NULL; i++)
        if (lua_type(L, -1) == LUA_TSTRING && strcmp(lua_tostring(L, -1), optnames[i]) == 0)
          break;
      if (optnames[i] == NULL) {
        const char *k = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1)
                                                        : luaL_typename(L, -1);
        return luaL_error(L, "lsys.texture_load: '%s': unknown option '%s' (known: mag, min, "
                          "mode, per_surface, intensity)", path, k);
      }
    }
    mag = getchoice(L, path, "mag", filters, fexpect, 0);
    min = getchoice(L, path, "min", filters, fexpect, 0);
    mode = getchoice(L, path, "mode", modes, "'modulate', 'decal', 'm' or 'd'", 0);
    per_surface = getflag(L, path, "per_surface") == 1;
    intensity = getflag(L, path, "intensity");
  }
  t = (lsys_texture *)lua_newuserdatauv(L, sizeof *t, 0);
  lsys_texture_init(t);                     /* valid before anything can fail */
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

static int texture_gc (lua_State *L) {       /* also __close: idempotent */
  lsys_texture_free((lsys_texture *)luaL_checkudata(L, 1, TEXTURE_T));
  return 0;
}

static int texture_size (lua_State *L) {
  lsys_texture *t = checktex(L, 1);
  lua_pushinteger(L, t->w);
  lua_pushinteger(L, t->h);
  return 2;
}

/* t:info() -> { path =, width =, height =, mag =, min =, mode =, per_surface =,
** intensity =, alpha = } with the long names of the settings. */
static int texture_info (lua_State *L) {
  lsys_texture *t = checktex(L, 1);
  lua_createtable(L, 0, 9);
  if (t->path != NULL) {
    lua_pushstring(L, t->path);
    lua_setfield(L, -2, "path");
  }
  lua_pushinteger(L, t->w); lua_setfield(L, -2, "width");
  lua_pushinteger(L, t->h); lua_setfield(L, -2, "height");
  lua_pushstring(L, t->mag_linear ? "linear" : "near"); lua_setfield(L, -2, "mag");
  lua_pushstring(L, t->min_linear ? "linear" : "near"); lua_setfield(L, -2, "min");
  lua_pushstring(L, t->mode == LSYS_TEX_DECAL ? "decal" : "modulate");
  lua_setfield(L, -2, "mode");
  lua_pushboolean(L, t->per_surface); lua_setfield(L, -2, "per_surface");
  lua_pushboolean(L, t->intensity); lua_setfield(L, -2, "intensity");
  lua_pushboolean(L, lsys_texture_hasalpha(t)); lua_setfield(L, -2, "alpha");
  return 1;
}

static int texture_tostring (lua_State *L) {
  lsys_texture *t = (lsys_texture *)luaL_checkudata(L, 1, TEXTURE_T);
  if (t->rgba == NULL) {
    lua_pushliteral(L, "Texture (closed)");
    return 1;
  }
  lua_pushfstring(L, "Texture(%s, %dx%d)", t->path ? t->path : "?", t->w, t->h);
  return 1;
}

/* ---------------------------------------------------------------------- */

const lsys_texture *const *lsys_opttextures (lua_State *L, int t, const char *who, int *ntex) {
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
  arr = (const lsys_texture **)lua_newuserdatauv(L, (size_t)n * sizeof *arr, 0);
  for (k = 1; k <= n; k++) {
    lua_geti(L, -2, k);
    arr[k - 1] = (const lsys_texture *)luaL_testudata(L, -1, TEXTURE_T);
    if (arr[k - 1] == NULL)
      luaL_error(L, "%s: opts.textures[%I] must be a texture (lsys.texture_load), got %s", who,
                 k, luaL_typename(L, -1));
    if (arr[k - 1]->rgba == NULL)
      luaL_error(L, "%s: opts.textures[%I] was closed", who, k);
    lua_pop(L, 1);
  }
  lua_remove(L, -2);                        /* the list stays referenced by the table */
  *ntex = (int)n;
  return arr;
}

static const luaL_Reg texture_methods[] = {
  {"size", texture_size}, {"info", texture_info}, {NULL, NULL}
};

static const luaL_Reg texture_meta[] = {
  {"__index", NULL},  /* placeholder: set to the method table */
  {"__gc", texture_gc}, {"__close", texture_gc}, {"__tostring", texture_tostring},
  {NULL, NULL}
};

void lsys_open_texture (lua_State *L) {
  luaL_newmetatable(L, TEXTURE_T);
  luaL_setfuncs(L, texture_meta, 0);
  luaL_newlib(L, texture_methods);
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
  lua_pushcfunction(L, l_texture_load);
  lua_setfield(L, -2, "texture_load");
}
