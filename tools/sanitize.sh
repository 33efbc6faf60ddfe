#!/usr/bin/env bash
# Builds lsys with AddressSanitizer and UndefinedBehaviorSanitizer and runs every test there
# (C tests, the fuzz-corpus replays, busted with the sanitized core.so and program, the
# viewer specs on a private Xvfb). Any sanitizer report fails the run.
#
#   tools/sanitize.sh [--cc gcc|clang|both] [ctest args]
#
# --cc both (the default when clang is installed) runs gcc's build (build-asan/) and then
# clang's (build-asan-clang/): clang's UBSan also reports what gcc's does not, such as
# arithmetic on a null pointer (NULL + 0). Leak detection is off: Mesa and GLFW keep
# allocations for the process (tools/memcheck-all.sh, under valgrind, checks lsys's own
# leaks). Environment: ASAN_BUILD_DIR, ASAN_CLANG_BUILD_DIR, JOBS.
set -euo pipefail
cd "$(dirname "$0")/.."

cc=
if command -v clang >/dev/null 2>&1; then cc=both; else cc=gcc; fi
args=()
while [ $# -gt 0 ]; do
  case $1 in
    --cc) cc=${2:?--cc needs gcc, clang or both}; shift 2 ;;
    --cc=*) cc=${1#--cc=}; shift ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done
case $cc in
  gcc|clang|both) ;;
  *) echo "sanitize.sh: --cc must be gcc, clang or both, got '$cc'" >&2; exit 2 ;;
esac
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}

# run COMPILER BUILD_DIR: configure, build and test one sanitized tree
run() {
  local compiler=$1 dir=$2 flags link runtime
  flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -g"
  link="-fsanitize=address,undefined"
  if [ "$compiler" = clang ]; then
    # the module is loaded by an unsanitized lua5.4: link the shared runtime and preload it
    flags="$flags -shared-libasan"
    link="$link -shared-libasan"
    runtime=$(clang -print-file-name=libclang_rt.asan-x86_64.so)
    if [ ! -f "$runtime" ]; then
      echo "sanitize.sh: clang's ASan runtime is missing: apt-get install libclang-rt-14-dev" >&2
      return 1
    fi
  else
    runtime="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)"
  fi
  echo "== $compiler: $dir"
  cmake -S . -B "$dir" -DCMAKE_C_COMPILER="$compiler" -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$link" \
    -DCMAKE_MODULE_LINKER_FLAGS="$link" -DCMAKE_SHARED_LINKER_FLAGS="$link" >/dev/null
  cmake --build "$dir" -j "$JOBS"
  # LSYS_TEST_SLOW: the specs' waits and the Lua fuzzer's replay budget (10 s of CPU an
  # input) times 4, for code that runs 2-4 times slower (as memcheck-all.sh sets 30)
  LD_PRELOAD="$runtime" LSYS_TEST_SLOW=${LSYS_TEST_SLOW:-4} \
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --test-dir "$dir" --output-on-failure -E memcheck ${args[@]+"${args[@]}"}
}

status=0      # both compilers run even when the first one fails
if [ "$cc" = gcc ] || [ "$cc" = both ]; then
  run gcc "${ASAN_BUILD_DIR:-build-asan}" || status=1
fi
if [ "$cc" = clang ] || [ "$cc" = both ]; then
  run clang "${ASAN_CLANG_BUILD_DIR:-build-asan-clang}" || status=1
fi
exit $status
