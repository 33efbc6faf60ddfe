#!/usr/bin/env bash
# Installs what is missing, builds (./setup.sh --no-run) and runs the tests with ctest: the C
# unit tests (tests/c/test_*.c), each busted spec (tests/*_spec.lua) as busted_<name>, the
# fuzz-corpus replays, luacheck, the rock and memcheck, one test per core at a time (JOBS,
# or ctest's -j); `--fast` leaves out the tests labelled slow (the loop to run
# while working; CONTRIBUTING.md gives both durations). Other arguments go to ctest, e.g.
#   ./test.sh -R busted_context -V
#   ./test.sh --fast -R busted
set -euo pipefail
cd "$(dirname "$0")"
fast=()
args=()
for a in "$@"; do
  if [ "$a" = "--fast" ]; then fast=(-LE slow); else args+=("$a"); fi
done
./setup.sh --no-run
# The Khronos glTF validator (npm) for the export spec, when npm is there; without it that
# one spec is reported pending.
if command -v npm >/dev/null 2>&1 && [ ! -d tools/node_modules/gltf-validator ]; then
  npm ci --prefix tools --no-audit --no-fund >/dev/null 2>&1 \
    || echo "test.sh: could not install the glTF validator (npm ci --prefix tools); skipping it"
fi
jobs="${JOBS:-$(nproc 2>/dev/null || echo 2)}"
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "$jobs" ${fast[@]+"${fast[@]}"} \
  ${args[@]+"${args[@]}"}
