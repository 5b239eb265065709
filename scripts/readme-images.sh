#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Renders the viewer images of the README into docs/, headless (xvfb-run), with the build in
# build/ (or $1): the skinned and the morphing assets of `tangent-make-data --animated`, baked,
# in the tangent view during their "bend" animation, and the split compare view of the baked
# demo sphere, and the demo scene lit (the README's first picture).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/bin
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin/tangent-make-data" --animated "$out/animated" >/dev/null
for asset in animated/skinned animated/morphing; do
  "$bin/tangent" bake "$out/$asset.gltf" -o "$out/$(basename "$asset").glb" -q
done
"$bin/tangent" bake data/demo/sphere.gltf -o "$out/sphere.glb" -q
view() { xvfb-run -a "$bin/tangent-view" "$@" --msaa 4; }
view "$out/skinned.glb" --view tangent --animation bend --time 1 --size 360x270 --screenshot docs/skinned-tangent.png
view "$out/morphing.glb" --view tangent --animation bend --time 0.7 --size 360x270 --screenshot docs/morphing-tangent.png
# Left of the divider the file's TANGENT with w negated (as a baker of the other handedness
# convention would write it: the bumps read as dents), right of it MikkTSpace computed at load.
view "$out/sphere.glb" --negate-w --compare fresh --camera front --size 480x270 --screenshot docs/compare-split.png
# The demo scene as scripts/demo.sh bakes and shows it, with a GPU's defaults (MSAA 4x).
"$bin/tangent" bake data/demo/scene.gltf -o "$out/scene-baked.glb" -q
view "$out/scene-baked.glb" --size 1280x720 --screenshot docs/demo-scene.png
# The brushed disc of `tangent-make-data --materials` in the anisotropy-direction view with its
# glyphs (the lit disc beside the Khronos Sample Viewer's is ctest reference.khronos_sample_viewer's
# docs/khronos-sample-viewer-disc.png).
"$bin/tangent-make-data" --materials "$out/materials" >/dev/null
view "$out/materials/anisotropy_disc.gltf" --camera front --view anisotropy-direction --glyphs --size 240x240 --screenshot docs/anisotropy-direction.png
