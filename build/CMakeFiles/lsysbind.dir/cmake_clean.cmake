file(REMOVE_RECURSE
  "CMakeFiles/lsysbind.dir/csrc/lua_lstring.c.o"
  "CMakeFiles/lsysbind.dir/csrc/lua_lstring.c.o.d"
  "CMakeFiles/lsysbind.dir/csrc/lua_lsys.c.o"
  "CMakeFiles/lsysbind.dir/csrc/lua_lsys.c.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/lsysbind.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
