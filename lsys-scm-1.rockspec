-- luarocks make                   (in a checkout: builds with CMake and installs lsys)
-- luarocks test                   (runs the busted specs)
rockspec_format = "3.0"
package = "lsys"
version = "scm-1"
source = {
  url = "git+file://.",  -- replace with the repository address when it is published
}
description = {
  license = "MIT",
  homepage = "https://example.invalid/lsys",  -- replace with the project page when it is published
  summary = "L-systems for modelling plants: a Lua 5.4 library with a C core",
  detailed = [[
lsys derives L-systems written as Lua tables (cpfg rule language: context, parametric,
stochastic, decomposition, homomorphism rules), with the derivation in C. It installs the
module `lsys` (Lua files and lsys/core.so) and the `lsys` program (REPL, script runner,
`lsys derive MODEL`).
]],
}
dependencies = {
  "lua >= 5.4",
  "lua-cjson",     -- sketch files (lsys.sketch) and batch manifests (lsys.batch): JSON
  "luaexpat",      -- sketch files: SVG
}
build_dependencies = {}
test_dependencies = {
  "busted",
}
build = {
  type = "cmake",
  variables = {
    CMAKE_BUILD_TYPE = "Release",
    CMAKE_C_FLAGS = "$(CFLAGS)",
    CMAKE_INSTALL_PREFIX = "$(PREFIX)",  -- the rock's directory: share/lsys/examples go there
    LUA_INCLUDE_DIR = "$(LUA_INCDIR)",
    LIBDIR = "$(LIBDIR)",
    LUADIR = "$(LUADIR)",
    BINDIR = "$(BINDIR)",
    LSYS_BUILD_TESTS = "OFF",
  },
}
test = {
  type = "busted",
}
