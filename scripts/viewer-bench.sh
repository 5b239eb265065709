#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Frame time of tangent-view under Xvfb (Mesa llvmpipe on machines without a GPU): the median
# of N frames at 1280x720 for each asset (wall clock, and the CPU time of all the viewer's
# threads, which a loaded machine disturbs less), with the defaults (PBR, image-based lighting, the
# two-light default rig, shadows with PCF 3x3 and MSAA 4x, both off on a software rasteriser)
# and with each feature turned off or changed in turn.
# Usage: scripts/viewer-bench.sh [--frames N] [--defaults-only] [ASSET...]   (after scripts/build.sh)
# --defaults-only: the lit default view alone (what scripts/bench.sh reports).
# Without assets: a generated ~100k-triangle textured sphere, plus ../shared/assets' glTF files
# when that folder exists (said on stderr when it does not).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
frames=15
defaults_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=${2:?"viewer-bench: --frames needs a count"}; shift 2 ;;
    --defaults-only) defaults_only=1; shift ;;
    --*) echo "viewer-bench: unknown option $1 (usage: scripts/viewer-bench.sh [--frames N] [--defaults-only] [ASSET...])" >&2; exit 2 ;;
    *) break ;;
  esac
done
viewer=$root/build/bin/tangent-view
[ -x "$viewer" ] || { echo "viewer-bench: $viewer is missing: run scripts/build.sh first" >&2; exit 2; }
work=$(mktemp -d /tmp/viewer-bench-XXXXXX)
trap 'rm -rf "$work"' EXIT
assets=("$@")
if [ ${#assets[@]} -eq 0 ]; then
  "$root/build/bin/tangent-make-data" --sphere 224 "$work" >/dev/null
  assets=("$work/sphere-224.gltf")
  if [ -d "$root/../shared/assets" ]; then
    for file in "$root"/../shared/assets/*.glb "$root"/../shared/assets/*.gltf; do
      [ -f "$file" ] && assets+=("$file")
    done
  else
    echo "viewer-bench: $root/../shared/assets is absent: measuring the generated sphere only" >&2
  fi
fi
for asset in "${assets[@]}"; do
  [ -f "$asset" ] || { echo "viewer-bench: $asset does not exist" >&2; exit 2; }
done
configs=(
  "defaults: PBR, IBL, shadows|"
  "no shadows (no depth pass)|--no-shadows"
  "PCF off|--pcf 0"
  "PCF 3x3|--pcf 1"
  "PCF 5x5|--pcf 2"
  "shadow map 4096|--shadow-map-size 4096"
  "MSAA off|--msaa 0"
  "MSAA 4x|--msaa 4"
  "Blinn-Phong specular-map mode|--shading blinn-phong"
  "no normal mapping|--no-normal-map"
  "no specular|--no-specular"
  "sphere-map reflection 0.3|--reflectivity 0.3"
  "error heatmap view|--view error"
  "uv view (cheapest fragment shader)|--view uv"
  "depth pre-pass|--depth-prepass"
  "no tone mapping|--tone-map none"
  "no image-based lighting|--no-ibl"
)
[ $defaults_only = 1 ] && configs=("${configs[0]}")
printf "%-34s %-40s %10s %10s\n" "asset" "configuration" "median ms" "CPU ms"
for asset in "${assets[@]}"; do
  for config in "${configs[@]}"; do
    name=${config%%|*}
    flags=${config#*|}
    # shellcheck disable=SC2086  # flags are words
    line=$(xvfb-run -a -s "-screen 0 1280x1024x24" "$viewer" "$asset" --size 1280x720 --camera front \
           --screenshot "$work/frame.png" --frames "$frames" $flags 2>/dev/null) || line="failed"
    ms=$(sed -n 's/.*median frame \([0-9.]*\) ms.*/\1/p' <<<"$line")
    cpu=$(sed -n 's/.*median frame [0-9.]* ms (CPU \([0-9.]*\) ms).*/\1/p' <<<"$line")
    printf "%-34s %-40s %10s %10s\n" "$(basename "$asset")" "$name" "${ms:-failed}" "${cpu:--}"
  done
done
