#!/usr/bin/env bash
# Installs what is missing, builds (./setup.sh --no-run) and runs every test with ctest:
# the C unit tests (tests/c/test_*.c) and the busted specs (tests/*_spec.lua).
# Extra arguments go to ctest, e.g. ./test.sh -R busted -V
set -euo pipefail
cd "$(dirname "$0")"
./setup.sh --no-run
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure "$@"
