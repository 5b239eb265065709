#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A program of someone else's (tests/consumer) built against `cmake --install` of the build
# tree into a temporary prefix, and run: the core alone (OpenMesh and the glTF layer's
# dependencies made unfindable, with controls showing that this bites, and a compile-time check
# that its headers include no OpenMesh header), and core + OpenMesh + glTF where the build has it.
#   consumer_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
source=$1 build=$2 work=$3
. "$(dirname "$0")/common.sh"
rm -rf "$work"
mkdir -p "$work"
prefix=$(mktemp -d /tmp/libtangent-consumer-XXXXXX)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
package_dir=$(dirname "$(find "$prefix" -name tangentConfig.cmake)")
no_build_paths "$package_dir" "$(cd "$source" && pwd)" "$(cd "$build" && pwd)"
build_consumer "$source/tests/consumer" "$work/core" "$prefix" "$build" OFF
consumer_control "$source/tests/consumer" "$work/control" "$prefix"
if [ "$(cache_value "$build" TANGENT_BUILD_GLTF)" = ON ]; then
  build_consumer "$source/tests/consumer" "$work/gltf" "$prefix" "$build" ON
fi
echo "consumer built and ran against the installed package"
