/*
** Lua binding of csrc/contour.h (being written).
*/
#include "lua_lsys.h"

void lsys_open_contour (lua_State *L) {
  (void)L;
}
