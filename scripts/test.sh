#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is missing, builds, and runs every test: the normal build, then the same
# tests built with AddressSanitizer and UndefinedBehaviorSanitizer, then each fuzz target
# for a fixed number of runs with a fixed seed (scripts/fuzz.sh --ci, about 40 s each).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
# Reference tools, pinned by tests/node/package-lock.json.
if [ ! -d tests/node/node_modules/gltf-validator ] || [ tests/node/package-lock.json -nt tests/node/node_modules/.package-lock.json ]; then
  (cd tests/node && npm ci --no-audit --no-fund --loglevel=error)
fi
echo "== build"
scripts/build.sh build
echo "== tests"
ctest --test-dir build --output-on-failure -j "$(nproc)"
echo "== tests under AddressSanitizer + UndefinedBehaviorSanitizer"
scripts/build.sh build-sanitize -DTANGENT_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug
# Left out here: the packaging tests (they build other trees with CMake and cpack; no code of
# ours runs in them that the normal run does not cover) and the viewer's rendering tests (label
# `render`: Mesa's software rasterizer dominates their time, and the viewer's bad-input test
# still runs under the sanitizers).
# The normal run takes the widest triangle pass this processor has (AVX2 on most); this one
# caps it at SSE2 (TANGENT_MAX_CPU_ISA), so that both run every test. The vector-width test
# compares all of them in both runs.
# The reference C differential draws 500 of its 2000 random meshes here (the same first 500
# seeds): under the sanitizers all of them took 188 s on a slow day, and the normal run
# compares every one.
TANGENT_DIFF_MESHES=500 TANGENT_MAX_CPU_ISA=sse2 ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" -LE 'packaging|render'
echo "== fuzz targets (libFuzzer, ASan + UBSan)"
scripts/fuzz.sh --ci
