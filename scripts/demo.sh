#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job on the bundled default: installs what is missing, builds, bakes tangents into
# data/demo/scene.gltf, prints what it did, checks the result, and shows it in tangent-view:
# in a window when there is a display, otherwise as a headless screenshot (Xvfb).
# Pass another asset to bake and show that instead.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh build >/dev/null
input=${1:-data/demo/scene.gltf}
mkdir -p build/demo
output=build/demo/$(basename "${input%.*}")-baked.glb
echo "== tangent info $input"
build/bin/tangent info "$input"
echo
echo "== tangent bake $input -o $output"
build/bin/tangent bake "$input" -o "$output" --report build/demo/report.json
echo
echo "== tangent check $output"
build/bin/tangent check "$output"
echo
if [ -n "${DISPLAY:-}" ]; then
  echo "== tangent-view $output (close the window to finish)"
  build/bin/tangent-view "$output"
else
  screenshot=build/demo/$(basename "${input%.*}")-baked.png
  echo "== no display: tangent-view renders $screenshot headless"
  xvfb-run -a -s "-screen 0 1280x1024x24" build/bin/tangent-view "$output" --screenshot "$screenshot" --size 1280x720
fi
