/*
** lsys.core: the Lua entry point. Each binding file registers its own
** metatables and functions (lua_lsys.h); they share only the floor,
** lua_aux.h.
*/
#include "lua_aux.h"
#include "lua_lsys.h"

int luaopen_lsys_core (lua_State *L) {
  lsysL_getalphabet(L);                /* the state's alphabet, before any model */
  lua_newtable(L);
  lsysL_open_rules(L);
  lsysL_open_lstring(L);
  lsysL_open_scene(L);
  lsysL_open_export(L);                 /* after lsysL_open_scene: adds a Scene method */
  lsysL_open_render(L);
  lsysL_open_outfile(L);
  lsysL_open_envproc(L);
  lsysL_open_light(L);
  lsysL_open_shadow(L);
  lsysL_open_space(L);
  lsysL_open_contour(L);
  lsysL_open_surface(L);
  lsysL_open_texture(L);
  lsysL_open_viewer(L);
  lsysL_open_ik(L);
  lsysL_open_bspline(L);
  lsysL_open_func(L);
  lsysL_open_canvas(L);
  lsysL_open_ffd(L);                   /* after lsysL_open_scene: adds Scene methods */
  lsysL_open_compgeo(L);
  lsysL_open_grow(L);
  lsysL_open_population(L);             /* after lsysL_open_scene: adds Scene methods */
  lsysL_open_sandbox(L);                /* after lsysL_open_rules: adds a Rules method */
  lua_pushinteger(L, LSYS_MAXTROPISMS);   /* the view schema's limit comes from the turtle */
  lua_setfield(L, -2, "MAXTROPISMS");
  return 1;
}
