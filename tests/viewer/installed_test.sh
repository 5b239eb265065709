#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The installed viewer works away from the source tree: `cmake --install` into a temporary
# prefix, then the installed tangent-view renders its demo scene from another folder, reading
# its shaders and demo data from PREFIX/share/libtangent.
#   installed_test.sh BUILD_DIR XVFB_RUN
set -euo pipefail
build=$1 xvfb=$2
prefix=$(mktemp -d /tmp/libtangent-install-XXXXXX)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix" >/dev/null
cd "$prefix"
output=$("$xvfb" -a -s "-screen 0 1280x1024x24" "$prefix/bin/tangent-view" --screenshot "$prefix/demo.png" --size 320x180 2>&1)
echo "$output"
[ -s "$prefix/demo.png" ] || { echo "FAIL: no screenshot"; exit 1; }
grep -q "$prefix/share/libtangent/data/demo/scene.gltf" <<<"$output" || { echo "FAIL: the demo did not come from the prefix"; exit 1; }
echo "installed viewer rendered the demo from $prefix"
