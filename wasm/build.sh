#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the WebAssembly package (wasm/package/dist) with Debian's emscripten: the core's
# array call (every method), single-threaded (TANGENT_SERIAL), no OpenMesh, the triangle pass
# four triangles at a time in SIMD128 (-msimd128: Node 16.4+ and current browsers), and the
# core's SSE2 paths too (-msse2: emscripten maps each SSE2 intrinsic the core uses onto SIMD128,
# exact operations all, so the same bits; the bucket pass's small-fan test, scalar otherwise,
# took half the pairing time at 1e6 triangles: 85-93 -> 40 ms in Node). The sources are compiled
# once and linked twice, the .wasm embedded in each (-sSINGLE_FILE: nothing to locate at run
# time, in Node, in a browser or in a bundler's output):
#   dist/tangent_wasm.cjs          Node (CommonJS factory; index.mjs wraps it)
#   dist/tangent_wasm.browser.mjs  browsers and workers (ES module factory, no Node code)
#   dist/browser.mjs               index.mjs with its module taken from the browser build:
#                                  the package's "browser" export (package.json)
# and the threaded builds (the package's "./threads" export): the same sources with the core's
# own pool of standard threads (TANGENT_STD_THREADS) on emscripten's pthreads, which start as a
# pool of workers when the module loads (one fewer than the machine's cores, at most 15: the
# calling thread is the other; in Node LIBTANGENT_WASM_THREADS sets the total):
#   dist/threads.mjs               Node: index.mjs with its module taken from the threaded build
#   dist/tangent_wasm_threads.cjs  its module, and tangent_wasm_threads.worker.js its workers'
#                                  script (pthreads need one file of their own in emscripten
#                                  3.1.6); dist/package.json makes that .js file CommonJS.
#   dist/threads.browser.mjs       pages served cross-origin isolated (COOP/COEP): the same on
#                                  tangent_wasm_threads.browser.mjs and .browser.worker.js
# emscripten 3.1.6's ES module output cannot serve Node (it uses __dirname), hence two links.
# Usage: wasm/build.sh   (installs emscripten first where it is missing)
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v em++ >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq emscripten
fi
out=wasm/package/dist
objects=$out/obj
rm -rf "$out" && mkdir -p "$objects"
# emscripten's JS optimizer needs Debian's acorn where node is not Debian's own.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
mkdir -p "$objects/serial" "$objects/threads"
sources=(libtangent/core/src/*.cpp libtangent/core/src/mikktspace/*.cpp wasm/src/bindings.cpp)
# compile VARIANT FLAGS...: every source into $objects/VARIANT, two at a time.
compile() {
  local variant=$1
  shift
  for source in "${sources[@]}"; do
    # The core's own sources see its private headers; the bindings only its public ones.
    private=-Ilibtangent/core/src
    [[ $source == wasm/* ]] && private=
    em++ -std=c++20 -O3 -msimd128 -msse2 -fexceptions "$@" -DNDEBUG -I libtangent/core/include $private \
      -c "$source" -o "$objects/$variant/$(tr / _ <<<"$source").o" &
    while [ "$(jobs -rp | wc -l)" -ge 2 ]; do wait -n; done
  done
  wait
}
compile serial -DTANGENT_SERIAL
compile threads -pthread -DTANGENT_STD_THREADS
exports=_malloc,_free,_tangent_run,_tangent_share_begin,_tangent_stage_corners,_tangent_shares_on_threads,_tangent_share_add,_tangent_error,_tangent_corner_tangents,_tangent_corner_vertices,_tangent_vertex_tangents,_tangent_vertex_sources,_tangent_report
settings=(-sMODULARIZE=1 -sEXPORT_NAME=createTangentModule -sSINGLE_FILE=1 -sALLOW_MEMORY_GROWTH=1 -sMAXIMUM_MEMORY=4GB
  -sFILESYSTEM=0 -sEXPORTED_FUNCTIONS=$exports -sEXPORTED_RUNTIME_METHODS=UTF8ToString,stringToUTF8,lengthBytesUTF8)
link=(em++ -O3 -fexceptions "$objects"/serial/*.o "${settings[@]}")
"${link[@]}" -sENVIRONMENT=node -o "$out/tangent_wasm.cjs"
"${link[@]}" -sENVIRONMENT=web,worker -sEXPORT_ES6=1 -o "$out/tangent_wasm.browser.mjs"
# The pool's size is a JavaScript expression, evaluated as the module loads.
pool='Math.max(1,Math.min(15,(+process.env.LIBTANGENT_WASM_THREADS||require("os").cpus().length)-1))'
threads=(em++ -O3 -fexceptions -pthread "$objects"/threads/*.o "${settings[@]}" -Wno-pthreads-mem-growth)
"${threads[@]}" -sENVIRONMENT=node,worker "-sPTHREAD_POOL_SIZE=$pool" -o "$out/tangent_wasm_threads.cjs"
# In a page: workers as the browser reports cores (a cross-origin isolated page only: shared
# memory needs COOP/COEP); its workers' script loads the module by a dynamic import.
browser_pool='Math.max(1,Math.min(15,(navigator.hardwareConcurrency||2)-1))'
"${threads[@]}" -sENVIRONMENT=web,worker -sEXPORT_ES6=1 "-sPTHREAD_POOL_SIZE=$browser_pool" \
  -o "$out/tangent_wasm_threads.browser.mjs"
echo '{ "type": "commonjs" }' >"$out/package.json"
rm -rf "$objects"
# The browser entry: index.mjs as it is, its one import of the Node build swapped for the
# browser build (one API source for both; a second relative import would need mapping here).
node_import="import createTangentModule from './dist/tangent_wasm.cjs';"
if [ "$(grep -c "^import .* from '\.\{1,2\}/" wasm/package/index.mjs)" != 1 ] || ! grep -qxF "$node_import" wasm/package/index.mjs; then
  echo "wasm/build.sh: index.mjs must have exactly one relative import, \"$node_import\"" >&2
  exit 1
fi
sed "s|^import createTangentModule from './dist/tangent_wasm.cjs';\$|import createTangentModule from './tangent_wasm.browser.mjs';|" \
  wasm/package/index.mjs >"$out/browser.mjs"
sed "s|^import createTangentModule from './dist/tangent_wasm.cjs';\$|import createTangentModule from './tangent_wasm_threads.cjs';|" \
  wasm/package/index.mjs >"$out/threads.mjs"
sed "s|^import createTangentModule from './dist/tangent_wasm.cjs';\$|import createTangentModule from './tangent_wasm_threads.browser.mjs';|" \
  wasm/package/index.mjs >"$out/threads.browser.mjs"
cp LICENSE wasm/package/LICENSE
for file in tangent_wasm.cjs tangent_wasm.browser.mjs browser.mjs tangent_wasm_threads.cjs tangent_wasm_threads.worker.js threads.mjs \
    tangent_wasm_threads.browser.mjs tangent_wasm_threads.browser.worker.js threads.browser.mjs; do
  echo "built $out/$file ($(stat -c %s "$out/$file") bytes)"
done
