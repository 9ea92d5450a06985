"""Skips for the Python tests (the shell tests' twin: tests/support/prerequisites.sh).

skip_test(reason, packages) exits 77 (CTest SKIP_RETURN_CODE) unless the environment sets
INVASIM_REQUIRE_ALL_TESTS=1 (scripts/test.sh and .ci/run do: on the project's machines every
test must run); then the skip is a failure naming the missing prerequisite."""

import os
import sys

SKIP = 77


def skip_test(reason, packages):
    if os.environ.get("INVASIM_REQUIRE_ALL_TESTS", "0") == "1":
        print("FAILED: %s (Debian: %s); with INVASIM_REQUIRE_ALL_TESTS=1 a skipped test fails "
              "(INVASIM_REQUIRE_ALL_TESTS=0 allows skips)" % (reason, packages))
        sys.exit(1)
    print("SKIPPED: %s (Debian: %s)" % (reason, packages))
    sys.exit(SKIP)
