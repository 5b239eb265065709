# SPDX-License-Identifier: MIT
"""The skip rule of tests/python/conftest.py (skipped on a developer's machine, a failure in CI;
a run with skips exits 77), loaded from there under its own name."""
import importlib.util
import pathlib

_spec = importlib.util.spec_from_file_location(
    "tangent_skip_rule", pathlib.Path(__file__).resolve().parents[1] / "python" / "conftest.py")
_rule = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_rule)

skip_or_fail = _rule.skip_or_fail
pytest_sessionfinish = _rule.pytest_sessionfinish
