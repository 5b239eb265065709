#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every combination of TANGENT_BUILD_{GLTF,TOOLS,VIEWER,TESTS} configures and builds, each in
# its own tree with the main build's compiler, ccache launcher, flags and build type, so objects
# come from the cache and only links are new work. ccache's paths are relative to the build
# tree, so the trees sit where the main build sits, one level below the checkout
# (SOURCE_DIR/build-matrix-*, removed once built and checked); logs go to WORK_DIR.
# TANGENT_BUILD_BENCHMARKS and TANGENT_BUILD_PYTHON are off in every tree to keep it cheap (the
# main build has them).
# Each tree must build exactly the parts its options allow (configure prints them), with a
# message for an option left out. Where neither the tools nor the viewer are built, OpenGL,
# GLFW, Dear ImGui and OpenImageIO are made unfindable (CMAKE_DISABLE_FIND_PACKAGE_<name>,
# pkg-config pointed at an empty folder) and the cache must show that none was looked up.
# A combination is built unless every command of its build (ninja -t commands, the tree's own
# path left out) is a command of a tree built before, which then built it all: a combination
# the options switch off to the same parts (the tools and viewer need the glTF layer), or one
# that only lacks the tests of a built one. The order builds the supersets first. Where the
# tests are built without the tools, the core's tests and the README's C++ blocks run: they
# must pass where the `tangent` command (or the glTF layer) is missing.
#   option_matrix.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source=$(cd "$1" && pwd) build=$2 work=$3
. "$(dirname "$0")/common.sh"
mapfile -t settings < <(main_build_settings "$build")
rm -rf "$work" "$source"/build-matrix-*
mkdir -p "$work/empty-pkgconfig"
fail() { echo "FAIL: $*"; exit 1; }

# combo GLTF TOOLS VIEWER TESTS: sets name, tree, expected (the parts it must build), no_gui
# (neither tools nor viewer: the GUI and image libraries made unfindable), args and environment.
combo() {
  local gltf=$1 tools=$2 viewer=$3 tests=$4
  name=gltf-$gltf.tools-$tools.viewer-$viewer.tests-$tests
  tree=$source/build-matrix-$name
  args=(-S "$source" -B "$tree" -G Ninja "${settings[@]}" -DTANGENT_BUILD_GLTF=$gltf -DTANGENT_BUILD_TOOLS=$tools
        -DTANGENT_BUILD_VIEWER=$viewer -DTANGENT_BUILD_TESTS=$tests -DTANGENT_BUILD_BENCHMARKS=OFF -DTANGENT_BUILD_PYTHON=OFF)
  environment=()
  expected=core
  [ $gltf = ON ] && expected+=" gltf"
  [ $gltf = ON ] && [ $tools = ON ] && expected+=" tools"
  [ $gltf = ON ] && [ $viewer = ON ] && expected+=" viewer"
  [ $tests = ON ] && expected+=" tests"
  no_gui=false
  if ! grep -qE 'tools|viewer' <<<"$expected"; then
    no_gui=true
    args+=(-DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON -DCMAKE_DISABLE_FIND_PACKAGE_imgui=ON
           -DCMAKE_DISABLE_FIND_PACKAGE_OpenImageIO=ON)
    environment=(PKG_CONFIG_LIBDIR="$work/empty-pkgconfig" PKG_CONFIG_PATH="$work/empty-pkgconfig")
  fi
}
combos=()
for gltf in ON OFF; do for tools in ON OFF; do for viewer in ON OFF; do for tests in ON OFF; do
  combos+=("$gltf $tools $viewer $tests")
done; done; done; done

# Configuring is mostly one process waiting on small compiler checks: as many at once as cores.
start=$SECONDS
for options in "${combos[@]}"; do
  # shellcheck disable=SC2086
  combo $options
  ( env "${environment[@]}" cmake "${args[@]}" >"$work/$name.configure.log" 2>&1; echo $? >"$work/$name.configure.rc" ) &
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
done
wait
echo "${#combos[@]} combinations configured in $((SECONDS - start)) s"

built=()   # the combinations built, whose command lists the others are compared with
tested=()  # those of them whose tests ran
builds=0
for options in "${combos[@]}"; do
  # shellcheck disable=SC2086
  combo $options
  read -r gltf tools viewer tests <<<"$options"
  echo "== $name (builds: $expected$($no_gui && echo '; GL, GLFW, ImGui, OpenImageIO unfindable'))"
  [ "$(cat "$work/$name.configure.rc")" = 0 ] || { cat "$work/$name.configure.log"; fail "$name: configure"; }
  got=$(sed -n 's/^-- libtangent builds: //p' "$work/$name.configure.log")
  [ "$got" = "$expected" ] || fail "$name: builds '$got', expected '$expected'"
  if [ $gltf = OFF ]; then
    [ $tools = OFF ] || grep -q "TANGENT_BUILD_TOOLS is ON but needs TANGENT_BUILD_GLTF" "$work/$name.configure.log" \
      || fail "$name: no message that the tools are left out"
    [ $viewer = OFF ] || grep -q "TANGENT_BUILD_VIEWER is ON but needs TANGENT_BUILD_GLTF" "$work/$name.configure.log" \
      || fail "$name: no message that the viewer is left out"
  fi
  if $no_gui && grep -E '^(IMGUI|GLFW|EPOXY|OpenImageIO|OPENGL|FREETYPE|STB)[A-Za-z_]*:' "$tree/CMakeCache.txt"; then
    fail "$name: looked up a GUI or image library (above)"
  fi
  ninja -C "$tree" -t commands all | sed "s|$tree|TREE|g" | LC_ALL=C sort -u >"$work/$name.commands"
  # The tests of a combination without the tools run in its own tree, or in one with the same
  # commands whose tests ran.
  run_tests=false
  [ $tests = ON ] && ! grep -q tools <<<"$expected" && run_tests=true
  if $run_tests; then
    # The shell tests of the tools are registered at configure time (the gtest ones after a build).
    registered=$(ctest --test-dir "$tree" -N -R '^(validator|compressed|data|bench|malformed|python)\.')
    grep -q 'Total Tests: 0' <<<"$registered" || { echo "$registered"; fail "$name: tests that need the tools are registered"; }
  fi
  candidates=("${built[@]}")
  $run_tests && candidates=("${tested[@]}")
  covered=
  for other in "${candidates[@]}"; do
    if [ -z "$(LC_ALL=C comm -23 "$work/$name.commands" "$work/$other.commands")" ]; then
      covered=$other
      break
    fi
  done
  if [ -n "$covered" ]; then
    echo "   each of its $(wc -l <"$work/$name.commands") build commands ran in $covered"
    rm -rf "$tree"
    continue
  fi
  start=$SECONDS
  cmake --build "$tree" >"$work/$name.build.log" 2>&1 || { tail -n 60 "$work/$name.build.log"; fail "$name: build"; }
  builds=$((builds + 1))
  built+=("$name")
  echo "   built in $((SECONDS - start)) s"
  if $run_tests; then
    ctest --test-dir "$tree" -R '^(Core|Workspace|readme)' --output-on-failure -j "$(nproc)" >"$work/$name.ctest.log" 2>&1 || { cat "$work/$name.ctest.log"; fail "$name: core tests"; }
    echo "   $(grep -E 'tests passed' "$work/$name.ctest.log")"
    tested+=("$name")
  fi
  rm -rf "$tree"
done
echo "${#combos[@]} combinations configured and checked, $builds of them built"
