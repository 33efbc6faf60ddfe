file(REMOVE_RECURSE
  "CMakeFiles/lsyscore.dir/csrc/alphabet.c.o"
  "CMakeFiles/lsyscore.dir/csrc/alphabet.c.o.d"
  "CMakeFiles/lsyscore.dir/csrc/common.c.o"
  "CMakeFiles/lsyscore.dir/csrc/common.c.o.d"
  "CMakeFiles/lsyscore.dir/csrc/derive.c.o"
  "CMakeFiles/lsyscore.dir/csrc/derive.c.o.d"
  "CMakeFiles/lsyscore.dir/csrc/grammar.c.o"
  "CMakeFiles/lsyscore.dir/csrc/grammar.c.o.d"
  "CMakeFiles/lsyscore.dir/csrc/lstring.c.o"
  "CMakeFiles/lsyscore.dir/csrc/lstring.c.o.d"
  "liblsyscore.a"
  "liblsyscore.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/lsyscore.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
