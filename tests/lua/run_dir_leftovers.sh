#!/usr/bin/env bash
# Leftovers of a run directory:
#  1. on --resume, snapshots/spheres.pvd lists only the run's own frame files that exist, up
#     to the checkpoint's step (hand-added entries naming the index itself, /dev/zero, a
#     missing frame, or an existing frame after the checkpoint's step are dropped);
#  2. a failed write of log.txt (here log.txt is a link to /dev/full: every write fails with
#     ENOSPC, as on a full disk) stops the run with exit 1 and a message naming the file.
# (Temporary files of killed writes: run_dir_lock.sh.)
# Usage: run_dir_leftovers.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
cd "$here"
run=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
     --set steps=400 --set every=200)

# 1. The ParaView index.
dir=$work/run
"$invasim" "${run[@]}" --set snapshot_every=200 --set checkpoint_every=200 --out "$dir" > "$work/run.log" 2>&1 ||
  fail "run" "$work/run.log"
pvd=$dir/snapshots/spheres.pvd
# The run ended at step 600 with a checkpoint there; a frame file of step 800 (as a run killed
# after its last checkpoint leaves) is listed too, and the summary is gone (a finished run is
# not resumed).
rm "$dir/summary.json"
cp "$dir/snapshots/spheres_000000600.vtp" "$dir/snapshots/spheres_000000800.vtp"
sed -i 's|  </Collection>|    <DataSet timestep="40" group="" part="0" file="spheres_000000800.vtp"/>\n    <DataSet timestep="40" group="" part="0" file="spheres.pvd"/>\n    <DataSet timestep="50" group="" part="0" file="/dev/zero"/>\n    <DataSet timestep="60" group="" part="0" file="spheres_000000900.vtp"/>\n  </Collection>|' "$pvd"
grep -q 'file="/dev/zero"' "$pvd" || fail "the test could not edit spheres.pvd" "$pvd"
"$invasim" run --resume "$dir" > "$work/resumed.log" 2>&1 || fail "--resume" "$work/resumed.log"
files=$(grep -o 'file="[^"]*"' "$pvd" | tr '\n' ' ')
[ "$files" = 'file="spheres_000000200.vtp" file="spheres_000000400.vtp" file="spheres_000000600.vtp" ' ] ||
  fail "spheres.pvd lists $files" "$pvd"

# 2. log.txt on a full disk.
mkdir -p "$work/full" && ln -s /dev/full "$work/full/log.txt"
status=0
"$invasim" "${run[@]}" --set snapshot_every=0 --out "$work/full" > "$work/full.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "a run whose log.txt cannot be written exited with $status (expected 1)" "$work/full.log"
grep -qF "cannot write the run's log $work/full/log.txt: No space left on device" "$work/full.log" ||
  fail "no message naming log.txt" "$work/full.log"
echo "run_dir_leftovers passed: spheres.pvd rebuilt on --resume; a failed log.txt write stopped the run"
