#!/usr/bin/env bash
# Builds lsys with AddressSanitizer and UndefinedBehaviorSanitizer into build-asan/ and runs
# every test there (C tests, busted with the sanitized core.so and program, the viewer specs
# on a private Xvfb). Any sanitizer report fails the run. Usage: tools/sanitize.sh [ctest args]
# Leak detection is off: Mesa and GLFW keep allocations for the process (memcheck, the
# valgrind test, checks lsys's own leaks).
set -euo pipefail
cd "$(dirname "$0")/.."
B=${ASAN_BUILD_DIR:-build-asan}
FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -g"
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_FLAGS="$FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$B" -j "$(nproc 2>/dev/null || echo 2)"
# lua5.4 itself is not sanitized: preload the runtimes for core.so
export LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)"
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
ctest --test-dir "$B" --output-on-failure -E memcheck "$@"
