# Sourced by the shell tests that need something a machine may lack (root, Slurm, git).
# skip_test REASON PACKAGES: the test cannot run here. Exits 77 (CTest SKIP_RETURN_CODE: a
# skip) unless INVASIM_REQUIRE_ALL_TESTS=1 (set by scripts/test.sh and .ci/run: on the
# project's machines every test must run), where the skip is a failure naming the missing
# prerequisite and its Debian packages.
skip_test() {
  if [ "${INVASIM_REQUIRE_ALL_TESTS:-0}" = 1 ]; then
    echo "FAILED: $1 (Debian: $2); with INVASIM_REQUIRE_ALL_TESTS=1 a skipped test fails" \
      "(INVASIM_REQUIRE_ALL_TESTS=0 allows skips)"
    exit 1
  fi
  echo "SKIPPED: $1 (Debian: $2)"
  exit 77
}
