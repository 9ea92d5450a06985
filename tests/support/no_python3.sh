# Stands in for python3 in the tests of the Python scripts when CMake found no python3: the
# test is skipped (77), or fails under INVASIM_REQUIRE_ALL_TESTS=1 (prerequisites.sh).
source "$(dirname "$0")/prerequisites.sh"
skip_test "python3 was not found when CMake configured this build" \
  "python3 python3-numpy python3-scipy python3-matplotlib"
