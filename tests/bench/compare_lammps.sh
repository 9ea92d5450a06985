#!/usr/bin/env bash
# Times invasim and LAMMPS (Debian's `lammps`, binary lmp) on benchmark workload (a) from the
# same relaxed start: N = 1500, 7000, 28000 cancer cells, phi = 0.65, Langevin, dt = 0.05,
# with 1 and 2 threads (LAMMPS: 1 and 2 MPI ranks; Debian's build has no OPENMP package), in
# three tables: repulsive at kT = 1e-3, cohesive (beta = 1e-2, alpha = 0.2) at kT = 1e-3, and
# repulsive at kT = 0.05 (frequent list rebuilds). Then the full system's rates (workload b,
# 28 adipocytes + 1500 cells and 128 + 7000) at 1 and 2 threads, and the shared-core check:
# a busy loop on one core while invasim runs with 1 and with 2 threads.
# LAMMPS stops ("Pair distance < table inner cutoff") if two cells come within 0.01 (a rare
# event of the hot case, kT = 0.05; cross_check_lammps.sh tabulates that case from 0.001).
# Rates are particle-steps per second of wall time; invasim's CPU-time rate at 1 thread is
# printed too (on a loaded machine compare those, or read the ratios).
# Usage: tests/bench/compare_lammps.sh [build dir = build] [steps = 2000] [sizes = "1500 7000 28000"]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
steps=${2:-2000}
sizes=${3:-"1500 7000 28000"}
bench="$build/tests/bench/bench_engine"
command -v lmp >/dev/null || { echo "needs LAMMPS: apt-get install lammps"; exit 1; }
[ -x "$bench" ] || { echo "build first: $bench not found"; exit 1; }
work=$(mktemp -d)
busy_pid=
cleanup() {
  [ -n "$busy_pid" ] && kill "$busy_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
# The contact law tabulated for LAMMPS (contact_table.sh).
source "$here/contact_table.sh"
contact_table 0.2 0 "$work/repulsive.table"
contact_table 0.2 0.01 "$work/cohesive.table"
for n in $sizes; do "$bench" lammps-data "$n" "$work/data.$n" >/dev/null; done

# One table: compare_case LABEL BETA KT TABLE CUT_FACTOR
compare_case() {
  echo
  echo "$1 ($steps steps)"
  echo "| N | invasim 1 thread | (CPU) | LAMMPS 1 rank | ratio | invasim 2 threads | LAMMPS 2 ranks | ratio |"
  echo "|---|---|---|---|---|---|---|---|"
  for n in $sizes; do
    row="| $n |"
    for p in 1 2; do
      read -r ours ours_cpu < <(OMP_NUM_THREADS=$p "$bench" single "$n" "$steps" "$2" "$3" 2>/dev/null)
      (cd "$work" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np "$p" lmp \
         -nocite -var data "data.$n" -var table "$4" -var steps "$steps" -var kT "$3" \
         -var c09 "$(awk -v f="$5" 'BEGIN { print 0.9 * f }')" -var c10 "$5" \
         -var c11 "$(awk -v f="$5" 'BEGIN { print 1.1 * f }')" -in "$here/in.cancer.lmp" \
         -log "log.$n.$p" >/dev/null)
      loop=$(grep "^Loop time" "$work/log.$n.$p" | tail -1 | awk '{print $4}')
      theirs=$(awk -v n="$n" -v s="$steps" -v t="$loop" 'BEGIN { printf "%.3e", n * s / t }')
      ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')
      if [ "$p" = 1 ]; then row="$row $ours | $ours_cpu | $theirs | $ratio |"
      else row="$row $ours | $theirs | $ratio |"; fi
    done
    echo "$row"
  done
}
compare_case "repulsive, kT = 1e-3" 0 1e-3 repulsive.table 1.0
compare_case "cohesive (alpha = 0.2, beta = 1e-2), kT = 1e-3" 0.01 1e-3 cohesive.table 1.2
compare_case "repulsive, kT = 0.05" 0 0.05 repulsive.table 1.0
echo "(particle-steps per second; ratio = invasim / LAMMPS; CPU = invasim's rate per CPU second)"

# The full system's 2-thread rate is the measured choice's (integrate/step_threads.hpp): it
# times windows of ~0.05 s with 1 and 2 threads and then holds its choice for 8+ windows, so a
# run of ~1000 steps shows its first decision more than the steady rate: at least 4000 steps.
full_steps=$(( steps > 4000 ? steps : 4000 ))
echo
echo "Full system, workload (b) ($full_steps steps)"
echo "| system | 1 thread | (CPU) | 2 threads | speed-up |"
echo "|---|---|---|---|---|"
for cells in 1500 7000; do
  read -r one one_cpu < <(OMP_NUM_THREADS=1 "$bench" full "$cells" "$full_steps")
  read -r two _ < <(OMP_NUM_THREADS=2 "$bench" full "$cells" "$full_steps")
  label=$([ "$cells" = 1500 ] && echo "28 + 1500" || echo "128 + 7000")
  echo "| $label | $one | $one_cpu | $two | $(awk -v a="$two" -v b="$one" 'BEGIN { printf "%.2f", a / b }') |"
done

echo
echo "Shared cores: a busy loop on core 0, workload (a) N = 7000, $steps steps, runs interleaved"
taskset -c 0 bash -c 'while :; do :; done' &
busy_pid=$!
echo "| run | 1 thread | 2 threads | 2 threads / 1 thread |"
echo "|---|---|---|---|"
for rep in 1 2; do
  read -r one _ < <(OMP_NUM_THREADS=1 "$bench" single 7000 "$steps" 2>/dev/null)
  read -r two _ < <(OMP_NUM_THREADS=2 "$bench" single 7000 "$steps" 2>/dev/null)
  echo "| $rep | $one | $two | $(awk -v a="$two" -v b="$one" 'BEGIN { printf "%.2f", a / b }') |"
done
kill "$busy_pid"
busy_pid=
echo "(target: 2 threads / 1 thread >= 0.9)"
