file(REMOVE_RECURSE
  "CMakeFiles/lsys.dir/csrc/lua_main.c.o"
  "CMakeFiles/lsys.dir/csrc/lua_main.c.o.d"
  "bin/lsys"
  "bin/lsys.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/lsys.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
