/*
** Lua binding of csrc/surface.h (being written).
*/
#include "lua_lsys.h"

void lsys_open_surface (lua_State *L) {
  (void)L;
}
