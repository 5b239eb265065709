// SPDX-License-Identifier: MIT
#include "support/build_paths.hpp"

// tests/CMakeLists.txt defines the paths of the executables this build tree has; calling for
// one it lacks is a link error, not an empty path.
#ifdef TANGENT_CLI_PATH
const char* tangent::testing::cliPath() { return TANGENT_CLI_PATH; }
#endif
#ifdef TANGENT_VIEW_PATH
const char* tangent::testing::viewerPath() { return TANGENT_VIEW_PATH; }
#endif
#ifdef TANGENT_TEST_ASSETS_PATH
const char* tangent::testing::testAssetsPath() { return TANGENT_TEST_ASSETS_PATH; }
#endif
