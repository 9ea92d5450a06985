#!/bin/sh
# Runs every fuzz target for SECONDS (default 1800: 30 minutes, docs/reliability.md) one after the other,
# at low priority, and prints each target's executions and findings; findings are saved to
# FINDINGS (default build/tests/fuzz/findings) for tests/fuzz/regression/<target>/.
#   tests/fuzz/run_bounded.sh [SECONDS] [BUILD_DIR] [SEED]
set -u
seconds=${1:-1800}
build=${2:-build}
seed=${3:-$(date +%s)}
fuzz="$build/tests/fuzz/invasim_fuzz"
findings="${FINDINGS:-$build/tests/fuzz/findings}"
[ -x "$fuzz" ] || { echo "run_bounded.sh: no $fuzz (cmake --build $build --target invasim_fuzz)" >&2; exit 2; }
status=0
for target in checkpoint vtk set keywords; do
  OMP_NUM_THREADS=1 nice -n 19 "$fuzz" run "$target" --seconds "$seconds" --seed "$seed" \
    --timeout 10 --findings "$findings" || status=1
done
exit $status
