#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configures and builds into build/ (or $1) with extra CMake arguments after it.
# Compiles through ccache where it is installed (scripts/install-deps.sh installs it), with
# paths taken relative to the folder above the checkout, so that other build trees of the same
# sources (the sanitizer build aside, whose flags differ; the option-matrix and package tests;
# other worktrees beside this one) reuse the objects instead of compiling them again.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
shift || true
launcher=()
if command -v ccache >/dev/null; then
  wrap="env;CCACHE_BASEDIR=$(cd .. && pwd);CCACHE_NOHASHDIR=true;ccache"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER="$wrap" -DCMAKE_C_COMPILER_LAUNCHER="$wrap")
fi
if [ ! -f "$build_dir/build.ninja" ]; then
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" "$@"
fi
cmake --build "$build_dir" --parallel "$(nproc)"
