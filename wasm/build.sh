#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the WebAssembly package (wasm/package/dist/tangent_wasm.cjs, the .wasm embedded) with
# Debian's emscripten: the core's array call (every method), single-threaded (TANGENT_SERIAL), no OpenMesh.
# Usage: wasm/build.sh   (installs emscripten first where it is missing)
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v em++ >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq emscripten
fi
out=wasm/package/dist
mkdir -p "$out"
# emscripten's JS optimizer needs Debian's acorn where node is not Debian's own.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
em++ -std=c++20 -O3 -fexceptions -DTANGENT_SERIAL -DNDEBUG \
  -I libtangent/core/include \
  libtangent/core/src/*.cpp libtangent/core/src/mikktspace/*.cpp wasm/src/bindings.cpp \
  -sMODULARIZE=1 -sEXPORT_NAME=createTangentModule -sSINGLE_FILE=1 -sALLOW_MEMORY_GROWTH=1 -sMAXIMUM_MEMORY=4GB \
  -sENVIRONMENT=web,worker,node -sFILESYSTEM=0 \
  -sEXPORTED_FUNCTIONS=_malloc,_free,_tangent_run,_tangent_error,_tangent_corner_tangents,_tangent_corner_vertices,_tangent_vertex_tangents,_tangent_vertex_sources,_tangent_report \
  -sEXPORTED_RUNTIME_METHODS=UTF8ToString,stringToUTF8,lengthBytesUTF8 \
  -o "$out/tangent_wasm.cjs"
echo "built $out/tangent_wasm.cjs ($(stat -c %s "$out/tangent_wasm.cjs") bytes)"
