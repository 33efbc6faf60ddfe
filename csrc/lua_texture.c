/*
** Lua binding of csrc/texture.h (being written).
*/
#include "lua_lsys.h"

void lsys_open_texture (lua_State *L) {
  (void)L;
}
