/* cmake/forbid/core/lua.h stands in for <lua.h> on the include path of csrc/core: the core (csrc/core) must not include Lua headers: Lua belongs in csrc/lua */
#error "the core (csrc/core) must not include Lua headers: Lua belongs in csrc/lua"
