#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the web viewer into build-web/ (index.html, tangent-view.js, tangent-view.wasm): the
# CMake viewer target (viewer/CMakeLists.txt) configured with Debian's emscripten (emcmake),
# WebGL2, the core single-threaded. The CMake tree in build-web/cmake is kept between runs, so
# a rebuild compiles only what changed.
# Usage: scripts/web.sh [--serve [PORT]]   (--serve: then serves build-web/ on 127.0.0.1 and
#        prints the URL; installs emscripten first where it is missing)
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v em++ >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq emscripten libstb-dev
fi
# emscripten's JS optimizer needs Debian's acorn where node is not Debian's own (TOOLCHAIN.md).
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
out=build-web
# Through ccache where it is installed, as scripts/build.sh does: it caches em++ too (measured:
# 361 s for a clean build on 2 busy cores, 62 s with a warm cache).
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER="env;CCACHE_BASEDIR=$(cd .. && pwd);CCACHE_NOHASHDIR=true;ccache")
fi
if [ ! -f "$out/cmake/build.ninja" ]; then
  emcmake cmake -S . -B "$out/cmake" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
fi
cmake --build "$out/cmake" --target tangent-view --parallel "${TANGENT_JOBS:-$(nproc)}"
cp "$out/cmake/bin/index.html" "$out/cmake/bin/tangent-view.js" "$out/cmake/bin/tangent-view.wasm" "$out/"
echo "built $out/index.html ($(( $(stat -c %s "$out/tangent-view.wasm") / 1024 )) KiB of wasm)"
if [ "${1:-}" = "--serve" ]; then
  port=${2:-8765}
  echo "serving http://127.0.0.1:$port/index.html  (open a .glb, or ?url=FILE&view=NAME; Ctrl-C stops)"
  cd "$out" && exec python3 -m http.server --bind 127.0.0.1 "$port"
fi
