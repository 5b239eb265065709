// SPDX-License-Identifier: MIT
// The executables of this build tree that tests run: TANGENT_CLI, TANGENT_VIEW and
// TANGENT_TEST_ASSETS. Their paths are compiled into support/build_paths.cpp alone (given to the
// tests that use them with -include), so that every other test object is the same in every
// build tree of these sources, and the option-matrix trees (tests/packaging) take those
// objects from ccache instead of compiling them again.
#pragma once

namespace tangent::testing {
const char* cliPath();         // tangent
const char* viewerPath();      // tangent-view
const char* testAssetsPath();  // tangent-test-assets
}  // namespace tangent::testing

#define TANGENT_CLI (::tangent::testing::cliPath())
#define TANGENT_VIEW (::tangent::testing::viewerPath())
#define TANGENT_TEST_ASSETS (::tangent::testing::testAssetsPath())
