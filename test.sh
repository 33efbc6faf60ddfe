#!/usr/bin/env bash
# Installs what is missing, builds (./setup.sh --no-run) and runs every test with ctest:
# the C unit tests (tests/c/test_*.c) and the busted specs (tests/*_spec.lua).
# Extra arguments go to ctest, e.g. ./test.sh -R busted -V
set -euo pipefail
cd "$(dirname "$0")"
./setup.sh --no-run
# The Khronos glTF validator (npm) for the export spec, when npm is there; without it that
# one spec is reported pending.
if command -v npm >/dev/null 2>&1 && [ ! -d tools/node_modules/gltf-validator ]; then
  npm ci --prefix tools --no-audit --no-fund >/dev/null 2>&1 \
    || echo "test.sh: could not install the glTF validator (npm ci --prefix tools); skipping it"
fi
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure "$@"
