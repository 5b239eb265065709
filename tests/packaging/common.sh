# SPDX-License-Identifier: MIT
# Sourced by the packaging tests (bash): the main build's settings, and the consumer project
# (tests/consumer) configured, built and run against an installed package.

# cache_value BUILD_DIR NAME: a value from BUILD_DIR/CMakeCache.txt (empty when unset).
cache_value() {
  sed -n "s/^$2:[A-Z]*=//p" "$1/CMakeCache.txt" | head -n 1
}

# The compiler, launcher (ccache), flags and build type of the main build, as -D arguments,
# so that other build trees of the same sources compile the same objects and hit the cache.
main_build_settings() {
  local build=$1 name value
  for name in CMAKE_BUILD_TYPE CMAKE_CXX_COMPILER CMAKE_C_COMPILER CMAKE_CXX_FLAGS CMAKE_CXX_COMPILER_LAUNCHER \
              CMAKE_C_COMPILER_LAUNCHER TANGENT_PEERS_DIR; do
    value=$(cache_value "$build" "$name")
    [ -n "$value" ] && printf '%s\n' "-D$name=$value"
  done
  return 0
}

# The glTF layer's dependencies, made unfindable for a program that asks for the core alone.
gltf_dependency_disables=(-DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
                          -DCMAKE_DISABLE_FIND_PACKAGE_glm=ON -DCMAKE_DISABLE_FIND_PACKAGE_draco=ON
                          -DCMAKE_DISABLE_FIND_PACKAGE_meshoptimizer=ON)

# build_consumer SOURCE WORK PREFIX MAIN_BUILD ON|OFF: configures tests/consumer against the
# package installed under PREFIX (with the OpenMesh and glTF programs, or the core alone with
# OpenMesh and the glTF layer's dependencies unfindable), checks that the package came from
# PREFIX, builds, runs.
build_consumer() {
  local source=$1 work=$2 prefix=$3 main=$4 with_gltf=$5
  local args=(-DCMAKE_PREFIX_PATH="$prefix" -DCONSUMER_WITH_GLTF="$with_gltf" -DCONSUMER_WITH_OPENMESH="$with_gltf"
              -DCMAKE_BUILD_TYPE="$(cache_value "$main" CMAKE_BUILD_TYPE)" -DCMAKE_CXX_COMPILER="$(cache_value "$main" CMAKE_CXX_COMPILER)")
  [ "$with_gltf" = ON ] || args+=("${gltf_dependency_disables[@]}" -DCMAKE_DISABLE_FIND_PACKAGE_OpenMesh=ON)
  rm -rf "$work"
  echo "== consumer (glTF $with_gltf) against $prefix"
  cmake -S "$source" -B "$work" -G Ninja "${args[@]}" >"$work.configure.log" 2>&1 || { cat "$work.configure.log"; return 1; }
  local found
  found=$(cache_value "$work" tangent_DIR)
  case "$found" in
    "$prefix"/*) echo "find_package(tangent) found $found" ;;
    *) echo "FAIL: find_package(tangent) found '$found', not the package under $prefix"; return 1 ;;
  esac
  cmake --build "$work" >"$work.build.log" 2>&1 || { cat "$work.build.log"; return 1; }
  "$work/consumer_core"
  if [ "$with_gltf" = ON ]; then
    "$work/consumer_openmesh"
    "$work/consumer_gltf" "$work/bake"
  else
    [ ! -e "$work/consumer_gltf" ] || { echo "FAIL: the core-only consumer built the glTF program"; return 1; }
    [ ! -e "$work/consumer_openmesh" ] || { echo "FAIL: the core-only consumer built the OpenMesh program"; return 1; }
  fi
}

# The control for the core-only consumer: asking for gltf with its dependencies unfindable must
# fail at configure time, or the core-only run proves nothing.
consumer_control() {
  local source=$1 work=$2 prefix=$3
  rm -rf "$work"
  if cmake -S "$source" -B "$work" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCONSUMER_WITH_GLTF=ON \
       "${gltf_dependency_disables[@]}" >"$work.configure.log" 2>&1; then
    echo "FAIL: COMPONENTS gltf configured although its dependencies were made unfindable"
    return 1
  fi
  echo "control: COMPONENTS gltf with its dependencies unfindable fails to configure, as it must"
  rm -rf "$work"
  if cmake -S "$source" -B "$work" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" -DCONSUMER_WITH_GLTF=OFF -DCONSUMER_WITH_OPENMESH=ON \
       -DCMAKE_DISABLE_FIND_PACKAGE_OpenMesh=ON >"$work.configure.log" 2>&1; then
    echo "FAIL: COMPONENTS openmesh configured although OpenMesh was made unfindable"
    return 1
  fi
  echo "control: COMPONENTS openmesh with OpenMesh unfindable fails to configure, as it must"
}

# no_build_paths PACKAGE_DIR PATH...: the installed CMake package names none of the build
# machine's folders (it must be relocatable).
no_build_paths() {
  local dir=$1 path
  shift
  for path in "$@"; do
    if grep -rlF "$path" "$dir"; then
      echo "FAIL: the installed CMake package above names $path"
      return 1
    fi
  done
  echo "the installed CMake package names no build-machine folder ($*)"
}
