/*
** lsys.core: the Lua entry point. Each binding file registers its own
** metatables and functions (lua_lsys.h); they share only the floor,
** lua_aux.h.
*/
#include "lua_aux.h"
#include "lua_lsys.h"

int luaopen_lsys_core (lua_State *L) {
  lsys_getalphabet(L);                /* the state's alphabet, before any model */
  lua_newtable(L);
  lsys_open_rules(L);
  lsys_open_lstring(L);
  lsys_open_scene(L);
  lsys_open_render(L);
  lsys_open_outfile(L);
  lsys_open_contour(L);
  lsys_open_surface(L);
  lsys_open_texture(L);
  lsys_open_viewer(L);
  lsys_open_ik(L);
  lsys_open_bspline(L);
  lsys_open_func(L);
  lsys_open_canvas(L);
  lsys_open_ffd(L);                   /* after lsys_open_scene: adds Scene methods */
  lsys_open_compgeo(L);
  lsys_open_grow(L);
  lsys_open_population(L);             /* after lsys_open_scene: adds Scene methods */
  lsys_open_sandbox(L);                /* after lsys_open_rules: adds a Rules method */
  lua_pushinteger(L, LSYS_MAXTROPISMS);   /* the view schema's limit comes from the turtle */
  lua_setfield(L, -2, "MAXTROPISMS");
  return 1;
}
