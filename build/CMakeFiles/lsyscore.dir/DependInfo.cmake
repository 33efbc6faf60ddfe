
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/csrc/alphabet.c" "CMakeFiles/lsyscore.dir/csrc/alphabet.c.o" "gcc" "CMakeFiles/lsyscore.dir/csrc/alphabet.c.o.d"
  "/work/main/csrc/common.c" "CMakeFiles/lsyscore.dir/csrc/common.c.o" "gcc" "CMakeFiles/lsyscore.dir/csrc/common.c.o.d"
  "/work/main/csrc/derive.c" "CMakeFiles/lsyscore.dir/csrc/derive.c.o" "gcc" "CMakeFiles/lsyscore.dir/csrc/derive.c.o.d"
  "/work/main/csrc/grammar.c" "CMakeFiles/lsyscore.dir/csrc/grammar.c.o" "gcc" "CMakeFiles/lsyscore.dir/csrc/grammar.c.o.d"
  "/work/main/csrc/lstring.c" "CMakeFiles/lsyscore.dir/csrc/lstring.c.o" "gcc" "CMakeFiles/lsyscore.dir/csrc/lstring.c.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
