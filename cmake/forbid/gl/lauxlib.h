/* cmake/forbid/gl/lauxlib.h stands in for <lauxlib.h> on the include path of csrc/gl: the GL layer (csrc/gl) must not include Lua headers: Lua belongs in csrc/lua */
#error "the GL layer (csrc/gl) must not include Lua headers: Lua belongs in csrc/lua"
