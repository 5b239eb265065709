#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CTest `wasm.package`: the install test (builds and packs the package from the checkout by
# the README's block, installs it into a new project, runs the README's blocks there), its
# command's test there (tangent_wasm_cli_test.sh), then
# wasm_test.mjs (against the C++ library, through glTF-Transform, the validator) on the
# generated test assets and ../shared/assets where present.
# Usage: run_wasm_tests.sh SOURCE_DIR WORK_DIR ARRAYS_TOOL TEST_ASSETS_TOOL
set -euo pipefail
source_dir=$1 work=$2 tool=$3 make_assets=$4
rm -rf "$work" && mkdir -p "$work"
"$make_assets" "$work/assets" >/dev/null
"$source_dir/tests/node/wasm_install_test.sh" "$source_dir" "$work/install" "$work/assets/second_uv_set.glb"
# The package's command as users break it, in the project that test installed.
"$source_dir/tests/node/tangent_wasm_cli_test.sh" "$source_dir" "$work/install/project" "$work/cli" "$work/assets/second_uv_set.glb"
assets=("$work"/assets/*.glb)
shared=$source_dir/../shared/assets
[ -d "$shared" ] && assets+=("$shared"/*.glb)
(cd "$source_dir/tests/node" && node wasm_test.mjs "$tool" "$work/arrays" "${assets[@]}")
# The rest ran; without the shared assets the test still reports itself skipped (a failure under CI=true).
[ -d "$shared" ] || exec "$source_dir/tests/support/skip_or_fail.sh" "$shared is absent: the shared assets were left out"
