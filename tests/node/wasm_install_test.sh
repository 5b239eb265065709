#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The WebAssembly package as a user gets it, by the documents' own blocks (docs/npm.md, and the
# js block of the README's "## npm" section), run as written: docs/npm.md's first (sh) at the
# repository root builds and packs it; the package is installed from that tarball into a new
# project (beside glTF-Transform, from the npm cache that tests/node's npm ci filled); there
# the js blocks and the last sh block run on a copy of ASSET as in.glb, and what they write
# must pass the Khronos validator.
# Usage: wasm_install_test.sh SOURCE_DIR WORK_DIR ASSET
set -euo pipefail
source_dir=$1 work=$2 asset=$3
rm -rf "$work" && mkdir -p "$work/project" "$work/blocks"
python3 - "$source_dir" "$work/blocks" <<'PY'
import re, sys
source, out = sys.argv[1], sys.argv[2]
page = open(f"{source}/docs/npm.md").read()
blocks = re.findall(r"```(sh|js)\n(.*?)```", page, re.S)
assert [lang for lang, _ in blocks] == ["sh", "js", "sh"], [lang for lang, _ in blocks]
for i, (lang, body) in enumerate(blocks):
    open(f"{out}/{i}.{lang}", "w").write(body)
readme = open(f"{source}/README.md").read()
start = readme.index("\n## npm (glTF-Transform, Node)\n")
section = readme[start:readme.index("\n## ", start + 1)]
js = re.findall(r"```js\n(.*?)```", section, re.S)
assert len(js) == 1, js
open(f"{out}/readme.js", "w").write(js[0])
PY
(cd "$source_dir" && bash -euo pipefail "$work/blocks/0.sh")
tarball=$(ls "$source_dir"/wasm/libtangent-wasm-*.tgz)
# The tarball: README and LICENSE, both builds, the entry of every export.
contents=$(tar tzf "$tarball")
for file in README.md LICENSE package.json index.mjs index.d.ts require.cjs dist/tangent_wasm.cjs dist/tangent_wasm.browser.mjs dist/browser.mjs \
    dist/threads.mjs dist/tangent_wasm_threads.cjs dist/tangent_wasm_threads.worker.js dist/package.json; do
  grep -qx "package/$file" <<<"$contents" || { echo "the tarball lacks $file" >&2; exit 1; }
done
cd "$work/project"
npm init -y >/dev/null
npm install --prefer-offline --no-audit --no-fund --loglevel=error "$tarball" \
  @gltf-transform/core@4.5.1 @gltf-transform/extensions@4.5.1 @gltf-transform/functions@4.5.1
# Node: import takes the Node build; require() says the package is an ES module and how to load it.
node --input-type=module -e "
  import { generateTangents } from 'libtangent-wasm';
  const t = generateTangents(new Float32Array([0,0,0, 1,0,0, 0,1,0]), new Float32Array([0,0,1, 0,0,1, 0,0,1]), new Float32Array([0,0, 1,0, 0,1]));
  if (t.length !== 12 || t[0] !== 1 || t[3] !== 1) throw new Error('import: unexpected tangents ' + t);"
# The threaded build's export: its pool as big as asked, the same tangents, and the process
# ends by itself (timeout: an idle worker would keep it running).
LIBTANGENT_WASM_THREADS=2 timeout 120 node --input-type=module -e "
  import { generateTangents, maxThreads } from 'libtangent-wasm/threads';
  if (maxThreads !== 2) throw new Error('libtangent-wasm/threads: maxThreads ' + maxThreads + ', not 2');
  const t = generateTangents(new Float32Array([0,0,0, 1,0,0, 0,1,0]), new Float32Array([0,0,1, 0,0,1, 0,0,1]), new Float32Array([0,0, 1,0, 0,1]), { threads: 2 });
  if (t.length !== 12 || t[0] !== 1 || t[3] !== 1) throw new Error('libtangent-wasm/threads: unexpected tangents ' + t);"
if message=$(node -e "require('libtangent-wasm')" 2>&1); then echo "require() of the ES module package succeeded silently" >&2; exit 1; fi
grep -q "libtangent-wasm is an ES module package and cannot be loaded with require(): use .import" <<<"$message" ||
  { echo "require() failed without saying the package is an ES module: $message" >&2; exit 1; }
cp "$asset" in.glb
cp "$work/blocks/1.js" readme.mjs
node readme.mjs
node "$source_dir/tests/node/validate.mjs" out.glb
rm out.glb
cp "$work/blocks/readme.js" readme-short.mjs
node readme-short.mjs
node "$source_dir/tests/node/validate.mjs" out.glb
rm out.glb
bash -euo pipefail "$work/blocks/2.sh"
node "$source_dir/tests/node/validate.mjs" out.glb
# Never over its input; an existing output only with --force (--overwrite, which means
# "recompute valid tangents" in tangent bake and glTF-Transform, is refused).
if npx --no-install tangent-wasm out.glb out.glb 2>/dev/null; then echo "tangent-wasm overwrote its input" >&2; exit 1; fi
if npx --no-install tangent-wasm in.glb out.glb 2>/dev/null; then echo "tangent-wasm replaced an output without --force" >&2; exit 1; fi
if npx --no-install tangent-wasm in.glb out.glb --overwrite 2>/dev/null; then echo "tangent-wasm took --overwrite" >&2; exit 1; fi
npx --no-install tangent-wasm in.glb out.glb --force >/dev/null
echo "installed package: ok"
# --help exits 0 with the usage on standard output.
help=$(npx --no-install tangent-wasm --help) || { echo "tangent-wasm --help exited non-zero" >&2; exit 1; }
grep -q "^usage: tangent-wasm" <<<"$help" || { echo "tangent-wasm --help printed no usage: $help" >&2; exit 1; }
# npm pack never makes a package without its builds: the package folder copied out of the
# checkout, dist/ removed, is refused by the prepack step, naming what to run.
mkdir -p "$work/no-dist" && cp -r "$source_dir/wasm/package/." "$work/no-dist/package" && rm -rf "$work/no-dist/package/dist"
if refused=$(cd "$work/no-dist/package" && npm pack --pack-destination "$work/no-dist" 2>&1); then
  echo "npm pack made a package without dist/" >&2; exit 1
fi
grep -q "wasm/build.sh" <<<"$refused" || { echo "npm pack without dist/ did not say what to run: $refused" >&2; exit 1; }
if ls "$work/no-dist"/*.tgz >/dev/null 2>&1; then echo "npm pack left a tarball without dist/" >&2; exit 1; fi
