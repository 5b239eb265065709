#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Baking 200 files three ways, medians of 3 runs each (wall seconds): `tangent bake` once per
# file in a shell loop, `tangent bake --recursive` (one process), and examples/bake_dask.py on a
# 2-worker LocalCluster. The files: 40 copies of five demo glTFs (demo, quad, cube, sphere,
# torus). Every run starts from an empty output folder (--force semantics: nothing skipped).
# Writes docs/batch-bench.md. Needs build/ (scripts/build.sh build) and python3-distributed.
set -euo pipefail
cd "$(dirname "$0")/.."
python=/usr/bin/python3
work=build/batch-bench
rm -rf "$work" && mkdir -p "$work/in"
for k in $(seq -w 1 40); do
  mkdir -p "$work/in/set$k"
  cp data/demo/{demo,quad,cube,sphere,torus}.gltf data/demo/{demo,quad,cube,sphere,torus}.bin data/demo/*.png "$work/in/set$k/"
done
count=$(find "$work/in" -name '*.gltf' | wc -l)
seconds() { local start end; start=$(date +%s.%N); "$@" >/dev/null 2>&1; end=$(date +%s.%N); echo "$end - $start" | bc; }
median() { printf '%s\n' "$@" | sort -g | sed -n 2p; }
loop() {
  find "$work/in" -name '*.gltf' | while read -r f; do
    rel=${f#"$work/in/"}; mkdir -p "$work/out/$(dirname "$rel")"
    build/bin/tangent bake "$f" -o "$work/out/$rel" -q
  done
}
declare -a a b c
for run in 1 2 3; do
  rm -rf "$work/out"; a+=("$(seconds loop)")
  rm -rf "$work/out"; b+=("$(seconds build/bin/tangent bake "$work/in" --recursive --out-dir "$work/out" -q)")
  rm -rf "$work/out"; c+=("$(seconds env PYTHONPATH=build/python $python examples/bake_dask.py "$work/in" "$work/out" --workers 2)")
done
ta=$(median "${a[@]}"); tb=$(median "${b[@]}"); tc=$(median "${c[@]}")
{
  echo "# Baking $count files (scripts/batch-bench.sh)"
  echo
  echo "$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), medians of 3 runs, wall seconds."
  echo
  echo "| how | seconds | files/s | vs shell loop |"
  echo "|---|---:|---:|---:|"
  printf '| `tangent bake` per file in a shell loop | %.2f | %.0f | 1.00x |\n' "$ta" "$(echo "$count / $ta" | bc -l)"
  printf '| `tangent bake --recursive` | %.2f | %.0f | %.2fx |\n' "$tb" "$(echo "$count / $tb" | bc -l)" "$(echo "$ta / $tb" | bc -l)"
  printf '| `examples/bake_dask.py`, LocalCluster of 2 workers | %.2f | %.0f | %.2fx |\n' "$tc" "$(echo "$count / $tc" | bc -l)" "$(echo "$ta / $tc" | bc -l)"
  echo
  echo "Runs: loop ${a[*]}; recursive ${b[*]}; dask ${c[*]}."
} > docs/batch-bench.md
cat docs/batch-bench.md
