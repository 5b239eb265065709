#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Bakes inputs into a fresh folder (float TANGENT, and normalized SHORT and BYTE with
# --tangent-format, which must also check clean) and runs the Khronos glTF validator on each
# output: 0 errors required. `generated`: every generated test asset and the bundled demo; `shared`: the
# shared sample assets (../shared/assets), skipped where absent (exit 77; a failure under
# CI=true, tests/support/skip_or_fail.sh). `materials`: the scenes of `tangent-make-data
# --materials` (given as the third argument) as written, not baked: they carry their TANGENT, which
# `tangent check` must pass.
# Usage: run_validator.sh generated|shared|materials TANGENT_CLI TEST_ASSETS_TOOL|MAKE_DATA SOURCE_DIR
set -euo pipefail
mode=$1 tangent=$2 make_assets=$3 source=$4
node_dir=$source/tests/node
if [ ! -d "$node_dir/node_modules/gltf-validator" ]; then
  echo "gltf-validator is not installed: run scripts/test.sh (it runs npm ci in tests/node)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case "$mode" in
  generated)
    "$make_assets" "$work/in" > "$work/inputs.txt"
    inputs=($(cat "$work/inputs.txt") "$source/data/demo/demo.gltf")
    ;;
  materials)
    "$make_assets" --materials "$work/materials" > /dev/null
    for scene in "$work/materials"/*.gltf; do
      "$tangent" check "$scene" > "$work/check.txt" || { cat "$work/check.txt" >&2; exit 1; }
    done
    node "$node_dir/validate.mjs" "$work/materials"/*.gltf
    echo "validated the material scenes as written: 0 errors"
    exit 0
    ;;
  shared)
    shared=$source/../shared/assets
    [ -d "$shared" ] || exec "$source/tests/support/skip_or_fail.sh" "$shared is absent: shared sample assets not validated"
    inputs=("$shared"/*.glb)
    ;;
  *) echo "usage: run_validator.sh generated|shared|materials TANGENT_CLI TEST_ASSETS_TOOL|MAKE_DATA SOURCE_DIR" >&2; exit 2 ;;
esac
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
  # Quantized TANGENT (KHR_mesh_quantization): normalized SHORT and BYTE, which must check clean too.
  for format in short byte; do
    out="$work/out/${name%.*}-$format.glb"
    "$tangent" bake "$input" -o "$out" --quiet --overwrite --tangent-format "$format"
    "$tangent" check "$out" > "$work/check.txt" || { cat "$work/check.txt" >&2; exit 1; }
    outputs+=("$out")
  done
done
node "$node_dir/validate.mjs" "${outputs[@]}"
echo "validated ${#outputs[@]} baked outputs: 0 errors"
