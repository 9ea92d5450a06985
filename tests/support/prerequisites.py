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


def require_scientific_python():
    """Skips (skip_test) unless numpy, scipy and matplotlib import: the analysis needs all three."""
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
        import scipy  # noqa: F401
    except ImportError as missing:
        skip_test("%s cannot import %s" % (sys.executable, missing.name),
                  "python3-numpy python3-scipy python3-matplotlib")


def check(condition, detail=None):
    """An assert that python -O keeps: a failed check exits with status 1 naming the calling
    script's file and line (and the detail)."""
    if not condition:
        frame = sys._getframe(1)
        raise SystemExit("FAILED: %s:%d%s" % (os.path.basename(frame.f_code.co_filename),
                                              frame.f_lineno,
                                              "" if detail is None else ": %r" % (detail,)))
