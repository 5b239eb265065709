#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Thread scaling of the plain-array call: the kernel benchmark's all-threads case pinned to
# 1, 2, 4, 8, ... CPUs (taskset; oneTBB uses the CPUs it is given), on single-primitive UV
# spheres, with meshoptimizer's MikkTSpace-compatible mode on one CPU in the same run.
# Prints a Markdown table of median wall times (ms) and speed-ups over one CPU.
# Usage: scripts/thread-scaling.sh [KERNEL_BENCH] [REPETITIONS]
#   KERNEL_BENCH: default build/bin/tangent-kernel-bench (scripts/build.sh builds it)
set -euo pipefail
cd "$(dirname "$0")/.."
bench=${1:-build/bin/tangent-kernel-bench}
reps=${2:-5}
[ -x "$bench" ] || { echo "thread-scaling: $bench not found (run scripts/build.sh first)" >&2; exit 1; }
command -v taskset >/dev/null || { echo "thread-scaling: taskset (util-linux) not found" >&2; exit 1; }
cpus=$(nproc)
counts=()
for ((n = 1; n <= cpus; n *= 2)); do counts+=("$n"); done
[ "${counts[-1]}" = "$cpus" ] || counts+=("$cpus")
# median wall milliseconds of one benchmark name pinned to the first N CPUs
wall() {  # wall N FILTER
  taskset -c "0-$(($1 - 1))" "$bench" --benchmark_filter="$2" --benchmark_repetitions="$reps" \
    --benchmark_report_aggregates_only=true 2>/dev/null | awk '$1 ~ /process_time(_median)?$/ {print $2; exit}'
}
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $cpus CPUs; $reps repetitions, medians (wall ms)."
echo
header="| input | meshopt compatible, 1 CPU |"
rule="|---|---:|"
for n in "${counts[@]}"; do header+=" library, $n CPU$([ "$n" = 1 ] || echo s) |"; rule+="---:|"; done
header+=" speed-up at $cpus |"; rule+="---:|"
echo "$header"
echo "$rule"
for input in sphere-1e5 sphere-1e6 sphere-4e6; do
  peer=$(wall 1 "meshopt-compatible/$input/")
  row="| $input | $peer |"
  one=""
  last=""
  for n in "${counts[@]}"; do
    ms=$(wall "$n" "library/tall/$input/")
    [ -n "$one" ] || one=$ms
    last=$ms
    row+=" $ms ($(awk -v a="$one" -v b="$ms" 'BEGIN {printf "%.1fx", a / b}')) |"
  done
  row+=" $(awk -v a="$one" -v b="$last" 'BEGIN {printf "%.1fx", a / b}') |"
  echo "$row"
done
