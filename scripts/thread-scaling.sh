#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Thread scaling of the plain-array call: the kernel benchmark's all-threads case pinned to
# 1, 2, 4, 8, ... CPUs (taskset; oneTBB uses the CPUs it is given), on single-primitive UV
# spheres, with meshoptimizer's MikkTSpace-compatible mode on one CPU in the same run.
# Prints a Markdown table of median wall times (ms) and speed-ups over one CPU.
# Usage: scripts/thread-scaling.sh [KERNEL_BENCH] [REPETITIONS] [BASELINE_BENCH]
#   KERNEL_BENCH: default build/bin/tangent-kernel-bench (scripts/build.sh builds it)
#   BASELINE_BENCH: another build's benchmark (say, main's) to compare with: each input and
#     CPU count is timed with both, one right after the other, and each gets its own row, then
#     a row of KERNEL_BENCH's time over BASELINE_BENCH's.
set -euo pipefail
cd "$(dirname "$0")/.."
bench=${1:-build/bin/tangent-kernel-bench}
reps=${2:-5}
baseline=${3:-}
for b in "$bench" ${baseline:+"$baseline"}; do
  [ -x "$b" ] || { echo "thread-scaling: $b not found (run scripts/build.sh first)" >&2; exit 1; }
done
command -v taskset >/dev/null || { echo "thread-scaling: taskset (util-linux) not found" >&2; exit 1; }
cpus=$(nproc)
counts=()
for ((n = 1; n <= cpus; n *= 2)); do counts+=("$n"); done
[ "${counts[-1]}" = "$cpus" ] || counts+=("$cpus")
# median wall milliseconds of one benchmark name of binary B pinned to the first N CPUs
wall() {  # wall B N FILTER
  taskset -c "0-$(($2 - 1))" "$1" --benchmark_filter="$3" --benchmark_repetitions="$reps" \
    --benchmark_report_aggregates_only=true 2>/dev/null | awk '$1 ~ /process_time(_median)?$/ {print $2; exit}'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.1fx", a / b}'; }
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p' | head -n 1), $cpus CPUs; $reps repetitions, medians (wall ms)."
if [ -n "$baseline" ]; then
  echo "Rows: $bench, then baseline $baseline, then their ratio (time of the first over the baseline's)."
fi
echo
header="| input |${baseline:+ build |} meshopt compatible, 1 CPU |"
rule="|---|${baseline:+---|}---:|"
for n in "${counts[@]}"; do header+=" library, $n CPU$([ "$n" = 1 ] || echo s) |"; rule+="---:|"; done
header+=" speed-up at $cpus |"; rule+="---:|"
echo "$header"
echo "$rule"
for input in sphere-1e5 sphere-1e6 sphere-4e6; do
  peer=$(wall "$bench" 1 "meshopt-compatible/$input/")
  times=()
  base=()
  for n in "${counts[@]}"; do
    times+=("$(wall "$bench" "$n" "library/tall/$input/")")
    [ -z "$baseline" ] || base+=("$(wall "$baseline" "$n" "library/tall/$input/")")
  done
  row() {  # row LABEL TIMES...
    local label=$1
    shift
    local r="| $input |${label:+ $label |} $peer |"
    for ms in "$@"; do r+=" $ms ($(ratio "$1" "$ms")) |"; done
    echo "$r $(ratio "$1" "${@: -1}") |"
  }
  if [ -z "$baseline" ]; then
    row "" "${times[@]}"
  else
    row "this" "${times[@]}"
    row "baseline" "${base[@]}"
    r="| $input | this / baseline | |"
    for i in "${!times[@]}"; do r+=" $(awk -v a="${times[$i]}" -v b="${base[$i]}" 'BEGIN {printf "%.3f", a / b}') |"; done
    echo "$r |"
  fi
done
