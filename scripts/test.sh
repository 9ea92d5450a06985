#!/usr/bin/env bash
# Installs what is missing, builds, and runs the default test suite (everything but the
# "long" label; run those with: ctest --test-dir build -L long), two tests at a time: no test
# is timed, the tests of two-thread runs reserve both slots (PROCESSORS 2) and the Slurm test
# runs alone (RUN_SERIAL). (Not one per core: each test's OpenMP team is as wide as the
# machine.)
# Every test must run here: a test whose prerequisite is missing (root, Slurm, git, numpy, voro++)
# fails instead of being skipped (tests/support/prerequisites.sh); INVASIM_REQUIRE_ALL_TESTS=0
# allows the skips on a machine without them.
set -euo pipefail
export INVASIM_REQUIRE_ALL_TESTS=${INVASIM_REQUIRE_ALL_TESTS:-1}
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
ctest --test-dir build -LE long --output-on-failure -j2
