#!/usr/bin/env bash
# Physics cross-check of invasim against LAMMPS (Debian's `lammps`, binary lmp): N = 1500
# bidisperse thermal cancer cells (diameters 0.9 / 1.1), fully periodic, phi = 0.65, Langevin
# (gamma = 0.2, dt = 0.05), from one common start: the data file of bench_engine lammps-data,
# read by LAMMPS (read_data) and by invasim (cross_check_lammps.lua places the cells where it
# says). The contact law is tabulated for LAMMPS by contact_table.sh, as for compare_lammps.sh.
# Cases (names for CASES):
#   repulsive_kT1e-3, cohesive_kT1e-3 (alpha = 0.2, beta = 1e-2): compare_lammps.sh's tables
#     (2000 points from r = 0.01, read into 2000);
#   repulsive_kT0.05 (a fluid): 20000 points from r = 0.001, read into 100000 (the coarse
#     table stops LAMMPS when a pair comes within 0.01, which happens there, and is off by up
#     to 30 % in force below r = 0.05).
# Per case SEEDS independent runs per program (same start, other noise): EQ steps, then STEPS of
# production sampled every 20 steps (1 tau). cross_check_lammps.py reduces both programs' output
# with one code: contact energy per cell, kinetic temperature, virial and total pressure, g(r)
# (first peaks of the three size pairs, whole curves), MSD and F_s(k = 2 pi) at lags 1, 10,
# 100 tau; mean +- standard error over the seeds and the difference in combined standard
# errors. Then a static check on the start and on each case's last state (seed 1's last
# snapshot): the start as both programs placed it (positions and sizes must be the same),
# energy, virial trace and every cell's force from one step from rest.
# Prints the tables; exit status 1 if any quantity differs by 3 combined standard errors or
# more, or if the two programs' starts differ. One thread, one rank, one simulation at a time:
# about 30 min with the defaults.
# Usage: tests/bench/cross_check_lammps.sh [build dir = build]
# Environment: SEEDS (10; below 8 the tables warn that the errors are unreliable), EQ (4000),
# STEPS (40000, at least 3000), CASES (all three), WORK (a directory to work in and keep; cases
# not in CASES keep their earlier results there and join the tables; default a temporary one,
# removed at the end unless KEEP is set), KEEP=all also keeps the trajectories (70-140 MB per
# run; otherwise each is removed once reduced).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-build}
seeds=${SEEDS:-10}
eq=${EQ:-4000}
steps=${STEPS:-40000}
cases=${CASES:-repulsive_kT1e-3 cohesive_kT1e-3 repulsive_kT0.05}
n=1500
invasim="$build/invasim"
bench="$build/tests/bench/bench_engine"
py=$(command -v /usr/bin/python3 || command -v python3 || true)
command -v lmp >/dev/null || { echo "needs LAMMPS: apt-get install lammps"; exit 1; }
[ -n "$py" ] && "$py" -c "import numpy" 2>/dev/null || { echo "needs python3 with numpy: apt-get install python3-numpy"; exit 1; }
[ -x "$invasim" ] && [ -x "$bench" ] || { echo "build first: $invasim or $bench not found"; exit 1; }
[ "$steps" -ge 3000 ] || { echo "STEPS >= 3000: the MSD at 100 tau needs 2000 steps, g(r) the snapshots every 1000"; exit 1; }
[ "$seeds" -ge 2 ] || { echo "SEEDS >= 2: the errors come from the spread over the seeds"; exit 1; }
if [ -n "${WORK:-}" ]; then
  mkdir -p "$WORK"
  work=$(cd "$WORK" && pwd)
else
  work=$(mktemp -d)
fi
cleanup() {
  if [ -z "${WORK:-}" ] && [ -z "${KEEP:-}" ]; then rm -rf "$work"; else echo "kept $work" >&2; fi
}
trap cleanup EXIT
export OMP_NUM_THREADS=1
start_time=$SECONDS

# The common start and the tables (contact_table.sh): the benchmark's, and a fine one.
source "$here/contact_table.sh"
"$bench" lammps-data "$n" "$work/data.$n" >/dev/null
rm -f "$work"/*.table
contact_table 0.2 0 "$work/repulsive.table"
contact_table 0.2 0.01 "$work/cohesive.table"
contact_table 0.2 0 "$work/repulsive_fine.table" 20000 0.001

# Each case: beta, kT, table, LAMMPS's internal table points, cutoff factor (s or (1+alpha) s).
declare -A setup=(
  [repulsive_kT1e-3]="0 1e-3 repulsive.table 2000 1.0"
  [cohesive_kT1e-3]="0.01 1e-3 cohesive.table 2000 1.2"
  [repulsive_kT0.05]="0 0.05 repulsive_fine.table 100000 1.0"
)
for c in $cases; do [ -n "${setup[$c]:-}" ] || { echo "unknown case $c (cases: ${!setup[*]})"; exit 1; }; done

# lammps_vars TABLE NTAB CUT_FACTOR: the table and the cutoffs of sizes 0.9, 1.0, 1.1.
lammps_vars() {
  echo -var table "$work/$1" -var ntab "$2" -var c09 "$(awk -v f="$3" 'BEGIN { print 0.9 * f }')" \
    -var c10 "$3" -var c11 "$(awk -v f="$3" 'BEGIN { print 1.1 * f }')"
}

# run_case NAME: SEEDS runs of each program, each reduced by cross_check_lammps.py.
run_case() {
  local beta kT tab ntab cut seed a b
  read -r beta kT tab ntab cut <<<"${setup[$1]}"
  rm -rf "${work:?}/$1"
  mkdir -p "$work/$1"
  echo "$kT" >"$work/$1/kT"
  for seed in $(seq 1 "$seeds"); do
    echo "$1: seed $seed of $seeds ($((SECONDS - start_time)) s)" >&2
    a="$work/$1/invasim/seed$seed" b="$work/$1/lammps/seed$seed"
    mkdir -p "$b"
    "$invasim" run "$here/cross_check_lammps.lua" --threads 1 --out "$a" \
      --set "data=$work/data.$n" --set "beta=$beta" --set "kT=$kT" --set "seed=$seed" \
      --set "eq_steps=$eq" --set "steps=$steps" >/dev/null
    # shellcheck disable=SC2046  # (lammps_vars's words)
    (cd "$b" && lmp -nocite -log log.lammps -var mode run -var data "$work/data.$n" \
       $(lammps_vars "$tab" "$ntab" "$cut") -var kT "$kT" -var seed "$seed" -var eq "$eq" \
       -var steps "$steps" -var every 20 -var snap_every 1000 \
       -in "$here/cross_check_lammps.lmp" >/dev/null) ||
      { echo "LAMMPS failed: $b/log.lammps"; tail -3 "$b/log.lammps"; exit 1; }
    "$py" "$here/cross_check_lammps.py" reduce "$a" invasim "$eq" "$work/data.$n"
    "$py" "$here/cross_check_lammps.py" reduce "$b" lammps "$eq" "$work/data.$n"
    [ "${KEEP:-}" = all ] || rm -f "$a/positions.bin" "$b/traj.txt"
  done
}

# static_state NAME DATA CASE: the start, energy, virial and forces of both programs on the
# state in DATA, with CASE's contacts and table.
static_state() {
  local beta tab ntab cut
  read -r beta _ tab ntab cut <<<"${setup[$3]}"
  [ "$2" = "$work/static/$1.data" ] || cp "$2" "$work/static/$1.data"
  "$invasim" run "$here/cross_check_lammps.lua" --threads 1 --out "$work/static" \
    --set mode=static --set "data=$2" --set "name=$1" --set "beta=$beta" >/dev/null
  # shellcheck disable=SC2046
  (cd "$work/static" && lmp -nocite -log none -var mode static -var data "$1.data" -var out "$1" \
     $(lammps_vars "$tab" "$ntab" "$cut") -in "$here/cross_check_lammps.lmp" >/dev/null) ||
    { echo "LAMMPS failed on the static state $1"; exit 1; }
}

for c in $cases; do run_case "$c"; done

# The static check: the start (both contact laws) and each case's last state, with its table.
rm -rf "$work/static"
mkdir -p "$work/static"
static_state start_repulsive "$work/data.$n" repulsive_kT1e-3
static_state start_cohesive "$work/data.$n" cohesive_kT1e-3
for c in "${!setup[@]}"; do
  [ -d "$work/$c/invasim/seed1/snapshots" ] || continue
  last=$(ls "$work/$c/invasim/seed1/snapshots/"cells_*.xyz | tail -1)
  "$py" "$here/cross_check_lammps.py" xyz2data "$last" "$work/static/end_$c.data"
  static_state "end_$c" "$work/static/end_$c.data" "$c"
done

echo "# invasim against LAMMPS: N = $n, phi = 0.65, periodic, Langevin gamma = 0.2, dt = 0.05"
echo "# ($("$invasim" --version | head -1); LAMMPS $(lmp -h | sed -n 's/^Large-scale Atomic.Molecular Massively Parallel Simulator - //p' | head -1))"
echo
echo "## Static check (start as placed, energy U, virial trace W, forces from one step from rest)"
status=0
"$py" "$here/cross_check_lammps.py" static "$work/static" || status=1
"$py" "$here/cross_check_lammps.py" table "$work" || status=1
times >"$work/times.txt"  # (the shell's user and system time, then its children's)
cpu=$(tail -1 "$work/times.txt" | awk '{ split($1, u, /[ms]/); split($2, s, /[ms]/);
                                         printf "%.0f", 60 * (u[1] + s[1]) + u[2] + s[2] }')
echo
echo "(cases run: $cases; SEEDS = $seeds, EQ = $eq, STEPS = $steps; wall $((SECONDS - start_time)) s;" \
     "CPU of the programs and analysis $cpu s)"
exit $status
