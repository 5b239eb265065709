#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer) and runs
# each for SECONDS (default 40) on a copy of its committed seed corpus. A crash, hang (10 s per
# input), leak or sanitizer report fails the script; the input that caused it is copied to
# tests/fuzz/regressions/TARGET/, where CTest replays it from then on.
#   scripts/fuzz.sh --ci       # what scripts/test.sh runs: a fixed seed and a fixed number of
#                              # runs per target (about 40 s each here), so CI is repeatable
#   scripts/fuzz.sh 3600       # an hour per target, a fresh random seed
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-40}
declare -A ci_runs=([gltf]=150000 [mesh_file]=25000 [core]=30000 [reports]=40000)
build=build-fuzz
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTANGENT_FUZZ=ON >/dev/null
fi
cmake --build "$build" --parallel "$(nproc)" --target fuzz_gltf fuzz_mesh_file fuzz_core fuzz_reports
status=0
for target in gltf mesh_file core reports; do
  work="$build/fuzz-work/$target"
  rm -rf "$work" && mkdir -p "$work/corpus" "$work/artifacts"
  cp tests/fuzz/corpus/$target/* "$work/corpus/"
  dict=()
  [ "$target" = gltf ] && dict=(-dict=tests/fuzz/gltf.dict)
  if [ "$seconds" = --ci ]; then
    budget=(-seed=1 -runs="${ci_runs[$target]}")
    echo "== fuzz_$target: ${ci_runs[$target]} runs, seed 1"
  else
    budget=(-max_total_time="$seconds")
    echo "== fuzz_$target for ${seconds} s"
  fi
  if ! "$build/bin/fuzz_$target" "$work/corpus" "${dict[@]}" "${budget[@]}" -timeout=10 \
       -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/artifacts/" \
       >"$work/log.txt" 2>&1; then
    status=1
    echo "fuzz_$target FAILED; last lines of $work/log.txt:"
    tail -40 "$work/log.txt"
    mkdir -p "tests/fuzz/regressions/$target"
    cp "$work"/artifacts/* "tests/fuzz/regressions/$target/" 2>/dev/null || true
  fi
  grep -aE "stat::number_of_executed_units|stat::peak_rss_mb" "$work/log.txt" | sed "s/^/  /"
done
exit $status
