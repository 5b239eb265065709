// SPDX-License-Identifier: MIT
// What a test does when something it needs from outside the repository is absent (../shared,
// Debian's assimp-testmodels): on a developer's machine it is skipped, and CTest reports it
// as skipped (gtest_discover_tests sets SKIP_REGULAR_EXPRESSION for GTEST_SKIP's output); in
// CI (the environment variable CI=true, set by .ci/run), where everything is installed, it
// fails. tests/support/skip_or_fail.sh is the same rule for CTest's shell tests and
// tests/python/conftest.py for pytest.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

namespace tangent::testing {

inline bool runningInCi() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::string_view(ci) == "true";
}

}  // namespace tangent::testing

// Returns from the test: GTEST_SKIP() with the message, or FAIL() with it under CI=true.
#define TANGENT_SKIP_OR_FAIL(message)                                         \
  do {                                                                        \
    if (::tangent::testing::runningInCi()) {                                  \
      FAIL() << "CI=true, so a missing input is a failure: " << message;      \
    }                                                                         \
    GTEST_SKIP() << message;                                                  \
  } while (0)
