#!/usr/bin/env bash
# The whole test suite under valgrind's memcheck, in one command:
#
#   tools/memcheck-all.sh [-j N] [-E REGEX] [REGEX]
#
# Builds build-memcheck/ (-O1 -g) and runs, each in its own valgrind, every C unit test,
# every fuzz-corpus replay and every busted spec file (N at a time, default nproc). The lsys
# program that specs start runs under valgrind too (LSYS_BIN is a wrapper); the programs
# that lsys and the specs run (cpp, dot, ffmpeg, GNU parallel, ...) are not checked. Invalid
# reads and writes, uses of uninitialised values and definite leaks in lsys's code fail the
# run; tools/valgrind.supp suppresses only what the OpenGL stack (OSMesa, llvmpipe, GLFW,
# X11) keeps for the process or computes in JIT code. REGEX selects the tests by name (e.g.
# 'safety|derive'), -E excludes. A test's output goes to build-memcheck/memcheck/<test>.log,
# valgrind's reports to <test>.<pid>.vg (one per process, the program's too); the summary
# lists each test with its time.
# Expect tens of minutes for the whole suite on 2 cores (the viewer specs are the slowest).
set -euo pipefail
cd "$(dirname "$0")/.."

JOBS=$(nproc 2>/dev/null || echo 2)
exclude='^$'
include='.'
while [ $# -gt 0 ]; do
  case $1 in
    -j) JOBS=${2:?-j needs a number}; shift 2 ;;
    -E) exclude=${2:?-E needs a regex}; shift 2 ;;
    -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) include=$1; shift ;;
  esac
done
command -v valgrind >/dev/null || { echo "memcheck-all.sh: valgrind is missing (apt-get install valgrind)" >&2; exit 2; }

B=${MEMCHECK_BUILD_DIR:-build-memcheck}
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" >/dev/null
cmake --build "$B" -j "$JOBS" >/dev/null
LOGS=$PWD/$B/memcheck     # absolute: children may run elsewhere
rm -rf "$LOGS"
mkdir -p "$LOGS"

# Only lsys's own processes are checked. The test process runs under valgrind without its
# children; the lsys program that specs start (through LSYS_BIN, also from sh, timeout, GNU
# parallel ...) is a wrapper that runs it under valgrind of its own, again without its
# children: the programs lsys and the specs run (cpp, dot, ffmpeg, ffprobe, perl, Xvfb, the
# shell) are not lsys's to check. Under a memory or file-size limit (ulimit -v, -f) the
# wrapper runs the program bare: valgrind needs more address space and writes its log.
VG=(valgrind --error-exitcode=9 --leak-check=full --errors-for-leak-kinds=definite
    --show-leak-kinds=definite --keep-debuginfo=yes "--suppressions=$PWD/tools/valgrind.supp"
    --trace-children=no --child-silent-after-fork=yes)
REAL=$PWD/$B/bin/lsys
WRAP=$LOGS/lsys
sq() { local s=${1//\'/\'\\\'\'}; printf "'%s'" "$s"; }   # one word for sh
{
  echo '#!/bin/sh'
  echo '# tools/memcheck-all.sh: the lsys program under valgrind, its report in the logs of'
  echo '# the test that started it (MEMCHECK_TEST)'
  echo 'if [ "$(ulimit -v)" != unlimited ] || [ "$(ulimit -f)" != unlimited ]; then'
  echo "  exec $(sq "$REAL") \"\$@\""
  echo 'fi'
  printf 'exec %s' "$(sq "$(command -v valgrind)")"       # by its path: specs change PATH
  for a in "${VG[@]:1}"; do printf ' %s' "$(sq "$a")"; done
  echo " $(sq "--log-file=$LOGS/")\"\${MEMCHECK_TEST:-lsys}\"'.%p.vg' $(sq "$REAL") \"\$@\""
} >"$WRAP"
chmod +x "$WRAP"
export LSYS_BIN=$WRAP LSYS_BUILD_DIR=$PWD/$B
export LSYS_TEST_SLOW=30       # the specs' waits (and the Lua fuzzer's budget), times 30
export LUA_PATH="$PWD/lua/?.lua;$PWD/lua/?/init.lua;;" LUA_CPATH="$PWD/$B/?.so;;"

# the tests: name and command
names=() cmds=()
for t in "$B"/test_*; do
  [ -x "$t" ] || continue
  names+=("$(basename "$t")"); cmds+=("$t")
done
for r in "$B"/replay_fuzz_*; do
  [ -x "$r" ] || continue
  n=${r##*/replay_fuzz_}
  d=tests/fuzz/corpus_$n
  [ -d "$d" ] || continue
  names+=("fuzz_corpus_$n"); cmds+=("$r $d")
done
for s in tests/*_spec.lua; do
  names+=("$(basename "$s" .lua)")
  cmds+=("$(command -v lua5.4) $(command -v busted) --output=plainTerminal --cpath=$PWD/$B/?.so $s")
done

run() {   # run NAME COMMAND...: one test under valgrind, its log and status
  local name=$1 start=$SECONDS st=0 f
  shift
  # valgrind's reports go to one file per process (the test's own output stays clean)
  MEMCHECK_TEST=$name "${VG[@]}" "--log-file=$LOGS/$name.%p.vg" "$@" >"$LOGS/$name.log" 2>&1 \
    || st=$?
  for f in "$LOGS/$name".*.vg; do
    [ -e "$f" ] || continue
    # (a process killed by its spec has no summary)
    if grep -qE "ERROR SUMMARY: [1-9]" "$f"; then st=9; fi
  done
  echo "$st $((SECONDS - start)) $name" >"$LOGS/$name.status"
}

running=0
for i in "${!names[@]}"; do
  n=${names[$i]}
  [[ $n =~ $include ]] || continue
  [[ $n =~ $exclude ]] && continue
  # shellcheck disable=SC2086
  run "$n" ${cmds[$i]} &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then wait -n || true; running=$((running - 1)); fi
done
wait || true

fail=0
printf '%-28s %8s  %s\n' test seconds result
for f in "$LOGS"/*.status; do
  [ -e "$f" ] || continue
  read -r st secs name <"$f"
  if [ "$st" = 0 ]; then r=ok
  elif [ "$st" = 9 ]; then r="MEMCHECK ERRORS (see $LOGS/$name.*.vg)"; fail=1
  else r="FAILED with status $st (see $LOGS/$name.log)"; fail=1
  fi
  printf '%-28s %8s  %s\n' "$name" "$secs" "$r"
done
exit $fail
