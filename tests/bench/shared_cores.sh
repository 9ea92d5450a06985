#!/usr/bin/env bash
# The shared-core check of docs/performance.md ("Targets", standing checks): with a busy loop on core 0, is `--threads 2` ever more than 10 % slower
# than `--threads 1`? Times bench_engine's workloads (repulsive spheres N = 1500 and 7000 at
# kT = 1e-3, the full system 28 + 1500, 6000 free active particles: a light step) with 1 and 2
# threads, interleaved, next to the busy loop; prints wall-time rates and their ratio.
# BENCH_STEP_THREADS=all in the environment forces every step onto both threads (the parallel
# step without the measured choice, for comparison).
# Usage: tests/bench/shared_cores.sh [build dir = build] [repetitions = 2]
set -euo pipefail
build=${1:-build}
reps=${2:-2}
bench="$build/tests/bench/bench_engine"
[ -x "$bench" ] || { echo "build first: $bench not found"; exit 1; }
busy_pid=
cleanup() { [ -n "$busy_pid" ] && kill "$busy_pid" 2>/dev/null; busy_pid=; }
trap cleanup EXIT
taskset -c 0 sh -c 'while :; do :; done' &
busy_pid=$!
echo "Shared cores: a busy loop on core 0 (load at start: $(cut -d' ' -f1 /proc/loadavg))"
echo "| workload | run | 1 thread | 2 threads | 2 threads / 1 thread | steps with 2 threads |"
echo "|---|---|---|---|---|---|"
while read -r label args; do
  for rep in $(seq "$reps"); do
    read -r one _ < <(OMP_NUM_THREADS=1 "$bench" $args 2>/dev/null)
    read -r two _ < <(OMP_NUM_THREADS=2 "$bench" $args 2>"$build/shared_cores.err")
    team=$(sed -n 's/^steps with all threads: //p' "$build/shared_cores.err")
    echo "| $label | $rep | $one | $two | $(awk -v a="$two" -v b="$one" 'BEGIN { printf "%.2f", a / b }') | $team |"
  done
done <<'LIST'
single-1500-repulsive single 1500 8000
single-7000-repulsive single 7000 2000
full-28+1500 full 1500 2000
free-6000-light free 6000 4000
LIST
cleanup
echo "(target: 2 threads / 1 thread >= 0.9)"
