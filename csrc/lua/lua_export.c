/*
** Binding of the export writers (export.h, docs/drawing.md section 5): Scene:save and
** the table of formats the command line and lsys.batch take their lists from.
**
**   core.formats()                -> the export formats of scene:save, in their order
**   scene:save(path [, opts])     -> what the file holds
*/
#include <math.h>
#include <string.h>

#include "lua_aux.h"
#include "lua_lsys.h"
#include "export.h"
#include "turtle.h"

/* The sides of exported tubes by default: the view's contour_sides when
** the scene was interpreted with one (its turtle options, a user value),
** else the turtle's default. */
static int tubesides (lua_State *L) {
  lsys_turtle_opts d;
  int sides;
  lsys_turtle_defaults(&d);
  sides = d.sides;
  if (lua_getiuservalue(L, 1, LSYS_SCENE_OPTS) == LUA_TTABLE &&
      lua_getfield(L, -1, "contour_sides") == LUA_TNUMBER) {
    double k = lua_tonumber(L, -1);               /* as the turtle read it (optwhole) */
    if (k >= 3 && k <= 1024) sides = (int)k;
  }
  lua_settop(L, 3);
  return sides;
}

/* The export formats' extensions as a message lists them: ".obj, .ply or .glb"
** (pushed). */
static const char *extlist (lua_State *L) {
  luaL_Buffer b;
  int k;
  luaL_buffinit(L, &b);
  for (k = 0; k < LSYS_NFORMATS; k++) {
    if (k > 0) luaL_addstring(&b, k + 1 < LSYS_NFORMATS ? ", " : " or ");
    luaL_addchar(&b, '.');
    luaL_addstring(&b, lsys_export_formats[k].ext);
  }
  luaL_pushresult(&b);
  return lua_tostring(L, -1);
}

/* core.formats() -> { {name=, ext=, title=, companion=, textures=, instancing=}, ... }:
** the export formats of scene:save (export.h), in their order. 'ext' and 'companion'
** (the extension of a file written beside it, absent when none) are lower case without
** the dot; 'textures': textured triangles name or embed their image; 'instancing': a
** population is written with instancing unless flattened. A new table each call. */
static int l_formats (lua_State *L) {
  int k;
  lua_createtable(L, LSYS_NFORMATS, 0);
  for (k = 0; k < LSYS_NFORMATS; k++) {
    const lsys_format *f = &lsys_export_formats[k];
    lua_createtable(L, 0, 6);
    lua_pushstring(L, f->name);
    lua_setfield(L, -2, "name");
    lua_pushstring(L, f->ext);
    lua_setfield(L, -2, "ext");
    lua_pushstring(L, f->title);
    lua_setfield(L, -2, "title");
    if (f->companion != NULL) {
      lua_pushstring(L, f->companion);
      lua_setfield(L, -2, "companion");
    }
    lua_pushboolean(L, f->textures);
    lua_setfield(L, -2, "textures");
    lua_pushboolean(L, f->instanced != NULL);
    lua_setfield(L, -2, "instancing");
    lua_rawseti(L, -2, k + 1);
  }
  return 1;
}

/* scene:save(path [, opts]) -> {vertices =, triangles =, lines =, instances =}, what
** the file holds (lsys_export_sizes); .obj (+ .mtl), .ply, .glb; opts.lines
** "lines" (default) or "tubes", with opts.sides and opts.pixel_size; for a
** population, opts.instancing (glb; default true) and opts.max_memory (the
** bytes its flattened copy may take) */
static int scene_save (lua_State *L) {
  static const char *const keys[] = {"lines", "sides", "pixel_size", "instancing",
                                     "max_memory", NULL};
  static const char *const lines[] = {"lines", "tubes", NULL};
  lsys_lscene *S = lsysL_checkscene(L, 1);
  const char *path = luaL_checkstring(L, 2);
  int format = lsys_export_format(path);
  lsys_export_sizes sz = {0, 0, 0, 0};
  lsys_export_opts xo = {0, 0, 0, 0, 0, &sz};
  lsys_error e;
  int st;
  memset(&e, 0, sizeof e);
  if (!lua_isnoneornil(L, 3)) {
    lsys_opts o = {3, "scene:save: opts.", "", LSYS_GOT_VALUE, 0};
    luaL_checktype(L, 3, LUA_TTABLE);
    if (lsysL_optunknown(L, &o, keys))
      return luaL_error(L, "scene:save: unknown option '%s' (use lines, sides, pixel_size, "
                        "instancing, max_memory)", luaL_tolstring(L, -1, NULL));
    xo.tubes = lsysL_optchoice(L, &o, "lines", 0, lines, "'lines' or 'tubes'");
    xo.sides = lsysL_optint(L, &o, "sides", 0, 3, 1024);
    xo.pixel = lsysL_optnum(L, &o, "pixel_size", 0, 0, HUGE_VAL, "a positive number");
    xo.flatten = !lsysL_optbool(L, &o, "instancing", 1);
    xo.max_memory = (size_t)lsysL_optnum(L, &o, "max_memory", 0, 0, 1.8e19,
                                         "a positive number of bytes");
  }
  lua_settop(L, 3);
  if (xo.sides == 0) xo.sides = tubesides(L);
  if (format < 0)
    return luaL_error(L, "scene:save: unknown format of '%s' (use %s)", path, extlist(L));
  S = lsysL_checkscene(L, 1);                /* again: the options ran Lua code */
  st = lsys_export_scene(&S->sc, format, path, &xo, &e);
  if (st != LSYS_OK) return lsysL_raise(L, st, &e, 1);
  lua_createtable(L, 0, 4);
  lua_pushinteger(L, (lua_Integer)sz.nv);
  lua_setfield(L, -2, "vertices");
  lua_pushinteger(L, (lua_Integer)sz.nt);
  lua_setfield(L, -2, "triangles");
  lua_pushinteger(L, (lua_Integer)sz.nl);
  lua_setfield(L, -2, "lines");
  lua_pushinteger(L, (lua_Integer)sz.ninst);
  lua_setfield(L, -2, "instances");
  return 1;
}

static const luaL_Reg scene_methods[] = {
  {"save", scene_save},
  {NULL, NULL}
};

/* Adds scene:save to the Scene's methods (after lsysL_open_scene) and core.formats. */
void lsysL_open_export (lua_State *L) {
  luaL_getmetatable(L, SCENE_T);
  lua_getfield(L, -1, "__methods");
  luaL_setfuncs(L, scene_methods, 0);
  lua_pop(L, 2);
  lua_pushcfunction(L, l_formats);
  lua_setfield(L, -2, "formats");
}
