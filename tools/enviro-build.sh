#!/usr/bin/env bash
# Builds vlab's environmental programs (the "field" processes that cpfg, and lsys, talk to
# through ?E modules: `cpfg -e file.e`, `lsys derive model.l --environment file.e`;
# docs/open.md) from a clone of vlab, for the tests that run them (LSYS_ENVIRO_BIN) and for
# comparing lsys with cpfg. vlab is GPL-3: this builds it on your machine; nothing of it
# goes into lsys.
#
# Usage:  tools/enviro-build.sh VLAB_GIT_DIR [PREFIX]
#   then: LSYS_ENVIRO_BIN=PREFIX/bin ./test.sh -R busted_open
#   VLAB_GIT_DIR: a git directory (bare, or a clone's .git) of github:AlgorithmicBotany/vlab
#   PREFIX:       where to build and install (default: ./enviro-oracle)
#   VLAB_REV:     environment, the commit to build (default HEAD; tested with 9bf820d)
#   JOBS:         make jobs for the two Qt programs (default 2)
#
# Result: PREFIX/bin/<program> for every program below, PREFIX/VLAB_COMMIT, sources and
# objects in PREFIX/src.  Put PREFIX/bin on PATH when running cpfg: cpfg starts the program
# named in the .e file's "executable:" line through the shell (files/memory) or through
# `which` + execv (pipes), so it must be findable by name.
#
# What is built, and how:
#   * libcomm.a from libs/comm (comm_master.c comm_slave.c communication.c compression.c)
#     and message.o (libs/comm/message.c: the Message() the library calls, to stderr),
#     compiled with plain gcc -DVLAB_LINUX -DLINUX.  VLAB_LINUX matters: it selects the
#     4-argument semctl() calls in communication.c.
#   * image.o from libs/image/image.c (SGI .rgb reader/writer: iopen/getrow/putrow) for
#     density, clover, soil, ornament.
#   * the console programs, each with plain gcc from the SOURCES of its ENVIRO/<p>/<p>.pro
#     (the .pro files say QT += opengl, but none of these uses Qt or OpenGL):
#       honda81 ecosystem chiba density density3d takenaka arvo radiosity MonteCarlo
#       clover soil ornament multiple
#   * QuasiMC and shadowpyramid with qmake (Qt5): QuasiMC is a Qt GUI program (debug
#     window, QGLWidget; needs libqt5opengl5-dev and GLU); shadowpyramid is C++ and needs
#     lpfg/include.  Skipped with a message if qmake is missing.  Headless runs of QuasiMC
#     probably need QT_QPA_PLATFORM=offscreen (untested).
#   * obcheck, the model-local program of vlab's CPFG-CelticKnot object (oofs/.../CPFG-
#     CelticKnot/obcheck.c; that object ships a Mach-O libcomm.a, useless on Linux).  The
#     model's .e runs it as ./obcheck: copy PREFIX/bin/obcheck into the model folder.
#   Not built: ENVIRO/Meadow (not in ENVIRO.pro, no .pro), soil/main.c (an old, unused
#   master-side copy of the protocol), the *.vcxproj Windows projects.
#
# Packages (Debian 12): gcc make; for the Qt two: qtbase5-dev qt5-qmake qtbase5-dev-tools
#   libqt5opengl5-dev libglu1-mesa-dev (cpfg-build.sh installs most of these).
set -euo pipefail

GITDIR=${1:?usage: enviro-build.sh VLAB_GIT_DIR [PREFIX]}
PREFIX=$(realpath -m "${2:-./enviro-oracle}")
REV=${VLAB_REV:-HEAD}
JOBS=${JOBS:-2}

# --- 1. sources ---------------------------------------------------------------------
SRC=$PREFIX/src
rm -rf "$SRC"; mkdir -p "$SRC" "$PREFIX/bin"
git --git-dir="$GITDIR" rev-parse "$REV" > "$PREFIX/VLAB_COMMIT"
echo "vlab commit: $(cat "$PREFIX/VLAB_COMMIT")"
git --git-dir="$GITDIR" archive "$REV" ENVIRO libs/comm libs/image lpfg/include \
    common.pri expand_my_name.pri | tar x -C "$SRC"
# the CelticKnot object's own program (optional: the path may move between revisions)
CK=oofs/ext/10-manuals/ext/20-EnviroPgms/ext/CPFG-CelticKnot
git --git-dir="$GITDIR" archive "$REV" "$CK/obcheck.c" 2>/dev/null | tar x -C "$SRC" || true

CFLAGS="-O2 -w -DVLAB_LINUX -DLINUX"
INC="-I$SRC/libs/comm -I$SRC/libs -I$SRC/libs/image"
OBJ=$SRC/obj; mkdir -p "$OBJ"

# --- 2. libcomm.a, message.o, image.o -----------------------------------------------
for f in comm_master comm_slave communication compression message; do
  gcc $CFLAGS $INC -c "$SRC/libs/comm/$f.c" -o "$OBJ/$f.o"
done
ar rcs "$OBJ/libcomm.a" "$OBJ"/comm_master.o "$OBJ"/comm_slave.o \
       "$OBJ"/communication.o "$OBJ"/compression.o
gcc $CFLAGS $INC -c "$SRC/libs/image/image.c" -o "$OBJ/image.o"

# --- 3. console programs ------------------------------------------------------------
# name : sources in ENVIRO/<name>/ (from its .pro, without message.c) : extra objects
PROGRAMS="
honda81:honda81.c:
ecosystem:ecosystem.c grid.c:
chiba:chiba.c sphere.c:
takenaka:takenaka.c:
density:density.c targa.c:image
density3d:density3d.c octree.c:
arvo:arvo.c matrix.c scene3d.c:
radiosity:radiosity.c scene3d.c sky.c matrix.c:
MonteCarlo:MonteCarlo.c matrix.c scene3d.c sky.c:
clover:clover.c targa.c lodepng.c:image
soil:soil2d.c matrix.c triangulate.c soil3d.c targa.c lodepng.c:image
ornament:ornament.c targa.c:image
multiple:multiple.c:
"
failed=""
while IFS=: read -r name srcs extra; do
  [ -n "$name" ] || continue
  objs="$OBJ/message.o"; [ "$extra" = image ] && objs="$objs $OBJ/image.o"
  echo "building $name"
  if ! ( cd "$SRC/ENVIRO/$name" && gcc $CFLAGS $INC $srcs $objs "$OBJ/libcomm.a" -lm \
           -o "$PREFIX/bin/$name" ) > "$SRC/build-$name.log" 2>&1; then
    echo "  FAILED, see $SRC/build-$name.log"; failed="$failed $name"
  fi
done <<< "$PROGRAMS"

if [ -f "$SRC/$CK/obcheck.c" ]; then
  echo "building obcheck (CPFG-CelticKnot)"
  gcc $CFLAGS $INC "$SRC/$CK/obcheck.c" "$OBJ/message.o" "$OBJ/libcomm.a" -lm \
      -o "$PREFIX/bin/obcheck" || failed="$failed obcheck"
fi

# --- 4. Qt programs (qmake) ---------------------------------------------------------
if command -v qmake >/dev/null 2>&1; then
  export QT_SELECT=qt5
  for d in libs/comm ENVIRO/QuasiMC ENVIRO/shadowpyramid; do
    echo "building $d (qmake)"
    log="$SRC/build-$(echo $d | tr / -).log"
    if ! ( cd "$SRC/$d" && qmake > "$log" 2>&1 && make -j"$JOBS" >> "$log" 2>&1 ); then
      echo "  FAILED, see $log"; failed="$failed $d"
    fi
  done
  for p in QuasiMC shadowpyramid; do
    [ -x "$SRC/.binaries/bin/$p" ] && install -m 755 "$SRC/.binaries/bin/$p" "$PREFIX/bin/$p"
  done
else
  echo "qmake not found: QuasiMC and shadowpyramid skipped"
fi

# --- 5. smoke test: honda81 alone, speaking the pipe protocol on stdin/stdout ---------
# Two points 0.001 apart with equal vigor collide (answer 0), a far one does not (1).
# (honda81 exits with status 1 even when all is well, hence the "|| true".)
T=$(mktemp -d)
printf 'executable: honda81 t.spec\ncommunication type: pipes\nturtle position: P:%%g %%g %%g\n' > "$T/t.e"
printf 'radius: 0.01\n3d case: on\n' > "$T/t.spec"
got=$(cd "$T" && printf '0 E(0.5)]\n P:0 0 0\n7 E(0.5)]\n P:0 0 0.001\n12 E(0.7)\n P:5 5 5\nControl: 5 1\nControl: 8 0\n' \
      | { "$PREFIX/bin/honda81" -e t.e t.spec 2>/dev/null || true; } | od -An -c | tr -s ' \n' ' ')
want=$(printf '\0010 E(0)\n7 E(0)\n12 E(1)\nControl: 5\nControl: 5\n\001' | od -An -c | tr -s ' \n' ' ')
rm -rf "$T"
[ "$got" = "$want" ] || { echo "smoke test: got '$got', want '$want'"; exit 1; }

echo "environmental programs built in $PREFIX/bin (vlab $(cut -c1-7 "$PREFIX/VLAB_COMMIT"))"
[ -z "$failed" ] || { echo "failed:$failed"; exit 1; }
