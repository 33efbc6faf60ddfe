#!/usr/bin/env bash
# Runs every fuzz target and grows its corpus: the libFuzzer targets of the core
# (tests/fuzz/fuzz_<name>.c) and the Lua-side targets (tests/fuzz/lua/targets/<name>.lua).
#
#   tools/fuzz.sh [SECONDS] [NAME...] [--c | --lua] [--no-merge]
#
# NAME: parsers contour surface derive expr png sgi export func (C), view palette ruleexpr sketch
# svg cpfg batch batchspec components grow import (Lua: every file of
# tests/fuzz/lua/targets/; lua-NAME names one too); default: all of them (--c: the C ones,
# --lua: the Lua ones). For the C targets it configures build-fuzz/ with clang and
# LSYS_BUILD_FUZZ=ON, builds the targets, then runs each for SECONDS (default 600), at most
# JOBS (default nproc) at a time, on a scratch copy of its
# corpus (build-fuzz/work/<name>/), with -max_total_time, -rss_limit_mb, -malloc_limit_mb (a
# larger single allocation is a finding: a PNG chunk once asked for 1.9 GB), its dictionary
# (tests/fuzz/<name>.dict) if there is one, and artifacts in build-fuzz/findings/<name>/.
# A target that stops on a finding is started again for the time left (at most 5 times).
# Then the new inputs that add coverage (edges: libFuzzer's -set_cover_merge=1 with
# -use_counters=0) are merged into tests/fuzz/corpus_<name>/, which only ever grows. At the
# end a table gives per target the executions, the final cov/ft, the corpus size before and
# after, and the findings (crash-*, leak-*, timeout-*, oom-*); the exit status is 1 when
# there are findings. Logs: build-fuzz/logs/<name>.<k>.log.
#
# The Lua targets run in the same pool through tests/fuzz/lua/fuzz.lua against the module
# in build/ (built first), on a scratch copy of tests/fuzz/corpus_<name>/; new inputs are
# merged with the Lua fuzzer's --merge (the hand-made seeds and what adds edges stay).
# --no-merge leaves tests/fuzz/ as it is. Environment: FUZZ_BUILD_DIR (build-fuzz), JOBS, RSS_MB (2048),
# MALLOC_MB (512), MAX_LEN (4096, the largest input libFuzzer makes), CORPUS_MAX (200 files:
# a warning above).
#
# A finding: minimize it with build-fuzz/fuzz_<name> -minimize_crash=1 -runs=10000 FILE,
# keep the reproducer under tests/fuzz/findings/<name>/ (never in the replayed corpus while
# the bug is open), replay it without libFuzzer with build/replay_fuzz_<name> FILE.
set -euo pipefail
cd "$(dirname "$0")/.."

ALL="parsers contour surface derive expr png sgi export func"
ALL_LUA=""
for t in tests/fuzz/lua/targets/*.lua; do [ -f "$t" ] && ALL_LUA="$ALL_LUA $(basename "$t" .lua)"; done
ALL_LUA=${ALL_LUA# }
secs=600
names=()
luanames=()
which=both
merge=1
for a in "$@"; do
  case $a in
    --lua) which=lua ;;
    --c) which=c ;;
    --no-merge) merge=0 ;;
    -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    ''|*[!0-9]*)
      case " $ALL " in
        *" $a "*) names+=("$a"); continue ;;
      esac
      case " $ALL_LUA " in
        *" ${a#lua-} "*) luanames+=("${a#lua-}"); continue ;;
      esac
      echo "fuzz.sh: unknown target '$a' (targets: $ALL $ALL_LUA)" >&2; exit 2 ;;
    *) secs=$a ;;
  esac
done
if [ ${#names[@]} -eq 0 ] && [ ${#luanames[@]} -eq 0 ]; then
  [ "$which" = lua ] || read -r -a names <<< "$ALL"
  [ "$which" = c ] || read -r -a luanames <<< "$ALL_LUA"
fi
B=${FUZZ_BUILD_DIR:-build-fuzz}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
RSS_MB=${RSS_MB:-2048}
MALLOC_MB=${MALLOC_MB:-512}
MAX_LEN=${MAX_LEN:-4096}
CORPUS_MAX=${CORPUS_MAX:-200}

# clang with its libFuzzer runtime (for the C targets)
if [ ${#names[@]} -gt 0 ]; then
  if ! command -v clang >/dev/null 2>&1; then
    echo "fuzz.sh: clang is missing: apt-get install clang libclang-rt-14-dev" >&2
    exit 2
  fi
  if [ ! -f "$(clang -print-file-name=libclang_rt.fuzzer-x86_64.a)" ] &&
     [ ! -f "$(clang -print-runtime-dir 2>/dev/null)/libclang_rt.fuzzer.a" ]; then
    v=$(clang -dumpversion | cut -d. -f1)
    echo "fuzz.sh: clang's libFuzzer runtime is missing: apt-get install libclang-rt-$v-dev" \
         "(libclang-common-$v-dev on older systems)" >&2
    exit 2
  fi

  echo "== configuring $B (clang, LSYS_BUILD_FUZZ=ON)"
  cmake -S . -B "$B" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLSYS_BUILD_FUZZ=ON -DLSYS_BUILD_TESTS=OFF >"$B.configure.log" 2>&1 \
    || { cat "$B.configure.log" >&2; exit 1; }
  rm -f "$B.configure.log"
  targets=()
  for n in "${names[@]}"; do targets+=("fuzz_$n"); done
  echo "== building ${targets[*]}"
  cmake --build "$B" -j "$JOBS" --target "${targets[@]}" >"$B/build.log" 2>&1 \
    || { tail -40 "$B/build.log" >&2; exit 1; }
fi
mkdir -p "$B/logs" "$B/work" "$B/findings"
if [ ${#luanames[@]} -gt 0 ]; then   # the module the Lua targets load
  echo "== building build/ (lsys.core for the Lua targets)"
  { [ -f build/CMakeCache.txt ] || cmake -S . -B build; } >"$B/lua-build.log" 2>&1
  cmake --build build -j "$JOBS" >>"$B/lua-build.log" 2>&1 \
    || { tail -40 "$B/lua-build.log" >&2; exit 1; }
fi

# run NAME: one target for $secs seconds on its scratch corpus, restarted after a finding
run() {
  local n=$1 left end k=0 dict=()
  end=$(( $(date +%s) + secs ))
  [ -f "tests/fuzz/$n.dict" ] && dict=("-dict=tests/fuzz/$n.dict")
  while :; do
    left=$(( end - $(date +%s) ))
    [ "$left" -gt 0 ] || break
    k=$((k + 1))
    if "$B/fuzz_$n" -max_total_time="$left" -rss_limit_mb="$RSS_MB" \
         -malloc_limit_mb="$MALLOC_MB" -max_len="$MAX_LEN" \
         -timeout=30 -print_final_stats=1 -artifact_prefix="$B/findings/$n/" \
         ${dict[@]+"${dict[@]}"} "$B/work/$n" >"$B/logs/$n.$k.log" 2>&1; then
      break
    fi
    [ "$k" -lt 5 ] || break
  done
}

# runlua NAME: one Lua target for $secs seconds on its scratch corpus. An input stuck in C,
# where no hook stops it, is stopped by timeout (twice the time, and 5 minutes more); the
# input is then FINDINGS/.current.
runlua() {
  local n=$1
  LUA_PATH="$PWD/lua/?.lua;$PWD/lua/?/init.lua;;" LUA_CPATH="$PWD/build/?.so;;" \
    timeout -k 10 $((2 * secs + 300)) \
    lua5.4 tests/fuzz/lua/fuzz.lua "$n" --time "$secs" --corpus "$B/work/lua-$n" \
    --findings "$B/findings/lua-$n" >"$B/logs/lua-$n.1.log" 2>&1 || true
  if [ -f "$B/findings/lua-$n/.current" ]; then
    echo "   lua-$n stopped by timeout on $B/findings/lua-$n/.current" >>"$B/logs/lua-$n.1.log"
    cp "$B/findings/lua-$n/.current" "$B/findings/lua-$n/timeout-current"
  fi
}

# prepare NAME WORKDIR: an empty scratch copy of tests/fuzz/corpus_NAME
declare -A before
prepare() {
  local n=$1 w=$2
  rm -rf "${B:?}/work/$w" "${B:?}/findings/$w" "$B/logs/$w".*.log
  mkdir -p "$B/work/$w" "$B/findings/$w"
  if [ -d "tests/fuzz/corpus_$n" ]; then
    cp -p "tests/fuzz/corpus_$n"/* "$B/work/$w/" 2>/dev/null || true
    before[$w]=$(find "tests/fuzz/corpus_$n" -maxdepth 1 -type f | wc -l)
  else
    before[$w]=0
  fi
}

echo "== fuzzing ${names[*]} ${luanames[*]} for $secs s each, $JOBS at a time"
for n in "${names[@]}"; do
  prepare "$n" "$n"
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
  echo "   $n"
  run "$n" &
done
for n in "${luanames[@]}"; do
  prepare "$n" "lua-$n"
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
  echo "   lua-$n"
  runlua "$n" &
done
wait

# merge what adds coverage into the checked-in corpora
if [ "$merge" = 1 ]; then
  echo "== merging new inputs into tests/fuzz/corpus_<name>"
  for n in "${names[@]}"; do
    mkdir -p "tests/fuzz/corpus_$n"
    "$B/fuzz_$n" -set_cover_merge=1 -use_counters=0 -rss_limit_mb="$RSS_MB" -max_len="$MAX_LEN" \
      -timeout=30 "tests/fuzz/corpus_$n" "$B/work/$n" >"$B/logs/$n.merge.log" 2>&1 \
      || echo "fuzz.sh: merging $n failed (see $B/logs/$n.merge.log)" >&2
  done
  for n in "${luanames[@]}"; do     # new files in, then keep the seeds and what adds edges
    mkdir -p "tests/fuzz/corpus_$n"
    cp -n "$B/work/lua-$n"/* "tests/fuzz/corpus_$n/" 2>/dev/null || true
    LUA_PATH="$PWD/lua/?.lua;$PWD/lua/?/init.lua;;" LUA_CPATH="$PWD/build/?.so;;" \
      lua5.4 tests/fuzz/lua/fuzz.lua "$n" --merge "tests/fuzz/corpus_$n" \
      >"$B/logs/lua-$n.merge.log" 2>&1 \
      || echo "fuzz.sh: merging lua-$n failed (see $B/logs/lua-$n.merge.log)" >&2
  done
fi

# the table
status=0
printf '\n%-16s %12s %7s %8s %15s  %s\n' target execs cov ft corpus findings
for n in "${names[@]}"; do
  execs=0; cov=-; ft=-
  for log in "$B/logs/$n".[0-9]*.log; do
    [ -f "$log" ] || continue
    e=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 |
        grep -o '[0-9]*$' || true)
    [ -n "$e" ] || e=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#' || true)
    execs=$((execs + ${e:-0}))
    c=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -1 || true)
    if [ -n "$c" ]; then cov=$(echo "$c" | cut -d' ' -f2); ft=$(echo "$c" | cut -d' ' -f4); fi
  done
  after=$(find "tests/fuzz/corpus_$n" -maxdepth 1 -type f 2>/dev/null | wc -l)
  list=$(cd "$B/findings/$n" && ls 2>/dev/null | grep -E '^(crash|leak|timeout|oom)-' |
         tr '\n' ' ' || true)
  [ -z "$list" ] || status=1
  printf '%-16s %12s %7s %8s %6s -> %-5s  %s\n' "$n" "$execs" "$cov" "$ft" "${before[$n]}" \
    "$after" "${list:-none}"
  if [ "$after" -gt "$CORPUS_MAX" ] ||
     [ "$(cat "tests/fuzz/corpus_$n"/* 2>/dev/null | wc -c)" -gt 1048576 ]; then
    echo "          (tests/fuzz/corpus_$n is over $CORPUS_MAX files or 1 MB: prune it with" \
         "-set_cover_merge=1 into a directory of the hand-made seeds)"
  fi
done
for n in "${luanames[@]}"; do     # the Lua targets: cov = edges, ft = features
  log=$B/logs/lua-$n.1.log
  line=$(grep -E "^fuzz $n: " "$log" 2>/dev/null | tail -1 || true)
  execs=$(echo "$line" | sed -n 's/.*: \([0-9]*\) executions.*/\1/p')
  cov=$(echo "$line" | sed -n 's/.* \([0-9]*\) edges covered.*/\1/p')
  ft=$(echo "$line" | sed -n 's/.*(\([0-9]*\) features).*/\1/p')
  after=$(find "tests/fuzz/corpus_$n" -maxdepth 1 -type f 2>/dev/null | wc -l)
  k=$(find "$B/findings/lua-$n" -maxdepth 1 -type f ! -name '*.txt' ! -name '.*' 2>/dev/null | wc -l)
  [ "$k" = 0 ] || status=1
  [ -n "$line" ] || { status=1; k="the run failed (see $log)"; }
  printf '%-16s %12s %7s %8s %6s -> %-5s  %s\n' "lua-$n" "${execs:-0}" "${cov:--}" "${ft:--}" \
    "${before[lua-$n]}" "$after" "$([ "$k" = 0 ] && echo none || echo "$k")"
done
[ "$status" = 0 ] || echo "findings: $B/findings/<target>/ (logs in $B/logs/)"
exit $status
