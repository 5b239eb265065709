#!/bin/sh
# SPDX-License-Identifier: MIT
# skip_or_fail.sh MESSAGE: the rule of skip_or_fail.hpp for CTest's shell tests. Prints the
# message and exits 77 (the tests' SKIP_RETURN_CODE: reported as skipped), or 1 under CI=true.
echo "$1"
if [ "${CI:-}" = true ]; then
  echo "CI=true, so a missing input is a failure"
  exit 1
fi
exit 77
