#!/usr/bin/env bash
# The shared-core check of docs/performance.md ("Targets", standing checks) for the compression: the paper-size init + compress (bench_compression,
# the protocol's dt_max = 0.15) with 1 and with 2 threads while a busy loop keeps core 0 busy,
# with the default passive wait policy and with a bounded spin (GOMP_SPINCOUNT=10000).
# Prints wall seconds per run (the iteration counts and final energy must agree).
# Usage: tests/bench/compress_shared.sh [build dir = build] [system = paper]
set -euo pipefail
build=${1:-build}
system=${2:-paper}
bench="$build/tests/bench/bench_compression"
[ -x "$bench" ] || { echo "build first: $bench not found"; exit 1; }
busy_pid=
cleanup() { [ -n "$busy_pid" ] && kill "$busy_pid" 2>/dev/null; busy_pid=; }
trap cleanup EXIT
taskset -c 0 sh -c 'while :; do :; done' &
busy_pid=$!
echo "Compression ($system) next to a busy loop on core 0"
echo "| wait policy | threads | wall [s] | FIRE iterations (steps + final) | final energy |"
echo "|---|---|---|---|---|"
for policy in OMP_WAIT_POLICY=passive GOMP_SPINCOUNT=10000; do
  for t in 1 2; do
    start=$(date +%s.%N)
    out=$(env "$policy" OMP_NUM_THREADS=$t "$bench" "$system" "$t" 0 dt_max=0.15 2>&1)
    end=$(date +%s.%N)
    iters=$(sed -n 's/.* \([0-9]*\) FIRE iterations.*/\1/p; s/^final FIRE: *\([0-9]*\) iterations.*/\1/p' <<<"$out" | paste -sd+)
    energy=$(sed -n 's/.*energy \([0-9.e+-]*\),.*/\1/p' <<<"$out" | tail -1)
    echo "| $policy | $t | $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') | $iters | $energy |"
  done
done
