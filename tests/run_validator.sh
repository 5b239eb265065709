#!/usr/bin/env bash
# Bakes every generated test asset, the bundled demo and the shared sample assets into a
# fresh folder and runs the Khronos glTF validator on each output: 0 errors required.
# Usage: run_validator.sh TANGENT_CLI TEST_ASSETS_TOOL SOURCE_DIR
set -euo pipefail
tangent=$1 make_assets=$2 source=$3
node_dir=$source/tests/node
if [ ! -d "$node_dir/node_modules/gltf-validator" ]; then
  echo "gltf-validator is not installed: run scripts/test.sh (it runs npm ci in tests/node)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$make_assets" "$work/in" > "$work/inputs.txt"
inputs=($(cat "$work/inputs.txt") "$source/data/demo/demo.gltf")
shared=$source/../shared/assets
if [ -d "$shared" ]; then
  inputs+=("$shared"/*.glb)
else
  echo "note: $shared is absent; shared sample assets not validated"
fi
mkdir -p "$work/out"
outputs=()
for input in "${inputs[@]}"; do
  name=$(basename "$input")
  # .gltf inputs go out as .glb and .glb as .gltf too, so both writers are validated.
  case "$name" in
    *.gltf) outs=("$work/out/${name%.gltf}.gltf" "$work/out/${name%.gltf}-as.glb") ;;
    *.glb)  outs=("$work/out/${name%.glb}.glb" "$work/out/${name%.glb}-as.gltf") ;;
  esac
  for out in "${outs[@]}"; do
    "$tangent" bake "$input" -o "$out" --quiet --overwrite
    outputs+=("$out")
  done
done
node "$node_dir/validate.mjs" "${outputs[@]}"
echo "validated ${#outputs[@]} baked outputs: 0 errors"
