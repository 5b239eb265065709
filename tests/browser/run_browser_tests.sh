#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest `wasm.browser`: the npm package in headless Chromium (Debian's chromium), from the
# tarball wasm.package packed (its fixture): natively as ES modules and through an esbuild
# bundle, on the main thread and in a module worker (package_test.py); the example page built as
# its README says, baking the demo quad and ../shared/assets (example_test.py). Every tangent is
# compared with the C++ library's bits (tangent-arrays-tool).
# Usage: run_browser_tests.sh SOURCE_DIR WORK_DIR ARRAYS_TOOL
set -euo pipefail
source_dir=$1 work=$2 tool=$3
skip_or_fail=$source_dir/tests/support/skip_or_fail.sh
command -v chromium >/dev/null ||
  exec "$skip_or_fail" "chromium is not installed (scripts/install-deps.sh installs Debian's chromium): browser tests not run"
tarballs=("$source_dir"/wasm/libtangent-wasm-*.tgz)
[ -f "${tarballs[0]}" ] || { echo "no wasm/libtangent-wasm-*.tgz: wasm.package packs it (ctest runs it first)" >&2; exit 1; }
esbuild=$source_dir/tests/node/node_modules/.bin/esbuild
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 "$source_dir/tests/browser/package_test.py" "$work/package" "${tarballs[0]}" "$tool" "$esbuild"
shared=$source_dir/../shared/assets
assets=()
[ -d "$shared" ] && assets+=("$shared"/*.glb)
/usr/bin/python3 "$source_dir/tests/browser/example_test.py" "$source_dir" "$work/example" "${tarballs[0]}" "$tool" "${assets[@]}"
[ -d "$shared" ] || exec "$skip_or_fail" "$shared is absent: the example page baked the demo quad only"
