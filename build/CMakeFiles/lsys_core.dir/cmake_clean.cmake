file(REMOVE_RECURSE
  "lsys/core.pdb"
  "lsys/core.so"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/lsys_core.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
