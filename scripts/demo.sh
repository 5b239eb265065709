#!/usr/bin/env bash
# The main job on the bundled default: installs what is missing, builds, bakes tangents into
# data/demo/demo.gltf and prints what it did. Pass another asset to bake that instead.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh build >/dev/null
input=${1:-data/demo/demo.gltf}
mkdir -p build/demo
output=build/demo/$(basename "${input%.*}")-baked.glb
echo "== tangent info $input"
build/bin/tangent info "$input"
echo
echo "== tangent bake $input -o $output"
build/bin/tangent bake "$input" -o "$output" --report build/demo/report.json
echo
echo "baked asset: $output   (report: build/demo/report.json)"
