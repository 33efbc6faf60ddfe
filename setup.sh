#!/usr/bin/env bash
# Installs the Debian packages lsys needs (only those missing), builds into build/ and renders
# the default plant headless to tree.png (OSMesa). Usage: ./setup.sh [--no-run | --packages]
#   --no-run     install and build only (./test.sh uses this)
#   --packages   list the packages it installs, one a line, and do nothing else
# Environment: BUILD_DIR (default build), BUILD_TYPE (default Release), JOBS (default nproc).
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(
  lua5.4 liblua5.4-dev lua-busted          # Lua, its headers, the test runner
  lua-cjson lua-expat                      # sketch files: JSON and SVG (lsys.sketch)
  lua-check                                # the luacheck test (.luacheckrc)
  cmake gcc libc6-dev make pkg-config      # the build
  libpng-dev libosmesa6-dev libglfw3-dev   # PNG output, offscreen GL, the viewer window
  libreadline-dev                          # line editing in the REPL
  libgl1-mesa-dri libglx-mesa0             # OpenGL in the window (and software GL on Xvfb)
  xvfb xauth xdotool                       # a virtual display and clicks for viewer tests
  valgrind                                 # the memcheck test (ctest -R memcheck)
  luarocks                                 # the rock test (ctest -R rock)
  graphviz                                 # `lsys components graph` pictures (dot)
  ffmpeg                                   # `lsys animate` videos and GIFs
  parallel                                 # GNU parallel: `lsys batch --shard` tests, bench
  slurmctld slurmd slurm-client munge      # a one-node Slurm for the job-array test (seconds)
  less tmux                                # the REPL's pager, and a terminal for its test
)
BUILD_DIR=${BUILD_DIR:-build}
BUILD_TYPE=${BUILD_TYPE:-Release}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}

run_example=1
for a in "$@"; do
  case $a in
    --no-run) run_example=0 ;;
    --packages) printf '%s\n' "${PACKAGES[@]}"; exit 0 ;;
    -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown argument '$a' (see ./setup.sh --help)" >&2; exit 2 ;;
  esac
done

install_missing() {
  local missing=() p
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' \
      || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if ! command -v apt-get >/dev/null; then
    echo "setup.sh: missing packages (no apt-get to install them): ${missing[*]}" >&2
    return 0  # try the build anyway: the tools may come from elsewhere
  fi
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  echo "setup.sh: installing ${missing[*]}"
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
}

build() {
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="$BUILD_TYPE"
  cmake --build "$BUILD_DIR" -j "$JOBS"
}

install_missing
build
if [ $run_example -eq 1 ]; then
  echo "+ $BUILD_DIR/bin/lsys render -o tree.png"
  "$BUILD_DIR/bin/lsys" render -o tree.png
fi
