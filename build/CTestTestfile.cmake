# CMake generated Testfile for 
# Source directory: /work/main
# Build directory: /work/main/build
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
add_test([=[busted]=] "/usr/bin/lua5.4" "/usr/bin/busted" "--output=plainTerminal" "--cpath=/work/main/build/?.so")
set_tests_properties([=[busted]=] PROPERTIES  ENVIRONMENT "LSYS_BUILD_DIR=/work/main/build;LSYS_BIN=/work/main/build/bin/lsys" WORKING_DIRECTORY "/work/main" _BACKTRACE_TRIPLES "/work/main/CMakeLists.txt;209;add_test;/work/main/CMakeLists.txt;0;")
