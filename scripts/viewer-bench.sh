#!/usr/bin/env bash
# Frame time of tangent-view under Xvfb (Mesa llvmpipe on machines without a GPU): median of
# N frames at 1280x720, for NormalTangentTest and a generated ~100k-triangle textured sphere,
# with every feature on and with each feature turned off or changed in turn.
# Usage: scripts/viewer-bench.sh [FRAMES]   (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-15}
mkdir -p build/bench
build/bin/tangent-make-data --sphere 224 build/bench >/dev/null
assets=(build/bench/sphere-224.gltf)
[ -f ../shared/assets/NormalTangentTest.glb ] && assets=(../shared/assets/NormalTangentTest.glb "${assets[@]}")
configs=(
  "shadows + PCF 3x3 (reference)|"
  "no shadows (no depth pass)|--no-shadows"
  "PCF off|--pcf 0"
  "PCF 5x5|--pcf 2"
  "shadow map 4096|--shadow-map-size 4096"
  "no normal mapping|--no-normal-map"
  "no specular|--no-specular"
  "sphere-map reflection 0.3|--reflectivity 0.3"
  "error heatmap view|--view error"
)
printf "%-42s %-34s %10s\n" "asset" "configuration" "median ms"
for asset in "${assets[@]}"; do
  for config in "${configs[@]}"; do
    name=${config%%|*}
    flags=${config#*|}
    line=$(xvfb-run -a -s "-screen 0 1280x1024x24" build/bin/tangent-view "$asset" --size 1280x720 --camera front \
           --screenshot build/bench/frame.png --frames "$frames" $flags 2>/dev/null)
    ms=$(sed -n 's/.*median frame \([0-9.]*\) ms.*/\1/p' <<<"$line")
    printf "%-42s %-34s %10s\n" "$(basename "$asset")" "$name" "$ms"
  done
done
