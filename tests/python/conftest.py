# SPDX-License-Identifier: MIT
"""What a test does when something from outside the repository is absent (../shared, a Debian
package): skipped on a developer's machine, a failure in CI (CI=true, set by .ci/run). The
rule of tests/support/skip_or_fail.hpp for pytest.

A run in which any test skipped and none failed exits 77, the CTest entries'
SKIP_RETURN_CODE, so CTest reports it as skipped, never as passed."""
import os

import pytest

SKIPPED_EXIT_CODE = 77


def running_in_ci():
    return os.environ.get("CI") == "true"


def skip_or_fail(reason):
    if running_in_ci():
        pytest.fail("CI=true, so a missing input is a failure: " + reason, pytrace=False)
    pytest.skip(reason)


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if exitstatus == pytest.ExitCode.OK and reporter is not None and reporter.stats.get("skipped"):
        session.exitstatus = SKIPPED_EXIT_CODE
