#!/usr/bin/env bash
# Times invasim and LAMMPS (Debian's `lammps`, binary lmp) on benchmark workload (a) from the
# same relaxed start: N = 1500, 7000, 28000 cancer cells, phi = 0.65, Langevin, dt = 0.05,
# with 1 and 2 threads (LAMMPS: 1 and 2 MPI ranks; Debian's build has no OPENMP package).
# Usage: tests/bench/compare_lammps.sh [build dir = build] [steps = 2000]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
steps=${2:-2000}
bench="$build/tests/bench/bench_engine"
command -v lmp >/dev/null || { echo "needs LAMMPS: apt-get install lammps"; exit 1; }
[ -x "$bench" ] || { echo "build first: $bench not found"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Linear spring table: F(r) = (1/s)(1 - r/s), E(r) = (1/2)(1 - r/s)^2, r in [0.01, s].
for s in 0.9 1.0 1.1; do
  label="S$(echo "$s" | tr -d .)"
  awk -v s="$s" -v label="$label" 'BEGIN {
    n = 2000; lo = 0.01; printf "%s\nN %d R %.10f %.10f\n\n", label, n, lo, s;
    for (i = 1; i <= n; ++i) { r = lo + (s - lo) * (i - 1) / (n - 1); x = 1 - r / s;
      printf "%d %.12f %.15e %.15e\n", i, r, 0.5 * x * x, x / s } print "" }' >> "$work/spring.table"
done
echo "| N | invasim 1 thread | LAMMPS 1 rank | ratio | invasim 2 threads | LAMMPS 2 ranks | ratio |"
echo "|---|---|---|---|---|---|---|"
for n in 1500 7000 28000; do
  "$bench" lammps-data "$n" "$work/data.$n" >/dev/null
  row="| $n |"
  for p in 1 2; do
    ours=$(OMP_NUM_THREADS=$p "$bench" single "$n" "$steps")
    (cd "$work" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np "$p" lmp -nocite \
       -var data "data.$n" -var table spring.table -var steps "$steps" -in "$here/in.cancer.lmp" \
       -log "log.$n.$p" >/dev/null)
    loop=$(grep "^Loop time" "$work/log.$n.$p" | tail -1 | awk '{print $4}')
    theirs=$(awk -v n="$n" -v s="$steps" -v t="$loop" 'BEGIN { printf "%.3e", n * s / t }')
    ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')
    row="$row $ours | $theirs | $ratio |"
  done
  echo "$row"
done
echo "(particle-steps per second; ratio = invasim / LAMMPS; $steps steps each)"
