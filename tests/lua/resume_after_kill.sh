#!/usr/bin/env bash
# Test: a run killed by SIGTERM during production and continued with
# `invasim run --resume DIR` ends exactly like a run that was never interrupted: the last
# snapshot (positions, velocities, orientations in shortest round-trip form), series.csv and
# correlations.csv are identical. The kill waits for the first checkpoint of production (an
# event, not a time). Further arguments go to both runs (e.g. --set lipolysis_rate=1e-3:
# the reference volumes change during the run and the checkpoints hold them; --set
# division_rate=...: the number of cells changes).
# PROTOCOL (default protocols/invasion.lua) names another protocol taking the same parameters.
# Usage: resume_after_kill.sh INVASIM WORKDIR [ARGS...]
set -euo pipefail
invasim=$1
work=$2
shift 2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
# A background kT: the cells, the Langevin vertices and the piston all draw noise.
args=(run "${PROTOCOL:-../../protocols/invasion.lua}" --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=500 --set background_factor=0 --set kT=1e-4
      --set steps=30000 --set every=200 --set snapshot_every=30000 --set checkpoint_every=1000
      --set correlate_every=10 "$@")

"$invasim" "${args[@]}" --out "$work/straight" > "$work/straight.log" 2>&1

"$invasim" "${args[@]}" --out "$work/killed" > "$work/killed.log" 2>&1 &
pid=$!
# Wait for the first periodic checkpoint (the file, and log.txt saying production wrote it),
# however long compression and quench take, then stop the run as a batch system would.
. ./wait_for.sh
checkpoint_written() {
  [ -f "$work/killed/checkpoint/state.ckpt" ] &&
    grep -q "^production: checkpoint of step [0-9]* written" "$work/killed/log.txt" 2> /dev/null
}
wait_for "$pid" "the first production checkpoint (checkpoint/state.ckpt and its line in log.txt)" \
  checkpoint_written || { cat "$work/killed.log"; exit 1; }
first=$(grep -o "^production: checkpoint of step [0-9]*" "$work/killed/log.txt" | head -1 | grep -o "[0-9]*$")
stop_with_sigterm "$pid" "$work/killed.log" "the killed run"
grep -q "stopped by SIGTERM at step [0-9]*.*checkpoint saved to .*continue with: invasim run --resume" "$work/killed.log" ||
  { echo "FAILED: no stop message from production"; cat "$work/killed.log"; exit 1; }
# Its last progress line says the production stopped, not that it is done.
grep -q "^production: step [0-9]*/[0-9]* .*stopped after [0-9:]*$" "$work/killed.log" &&
  ! grep -q "^production: .*done in" "$work/killed.log" ||
  { echo "FAILED: the progress of the stopped production does not end with 'stopped after'"; cat "$work/killed.log"; exit 1; }
# The run's own log ends with the same message (invasim.at_error, lib/log.lua).
tail -1 "$work/killed/log.txt" | grep -q "^end: stopped by SIGTERM at step [0-9]*.*continue with: invasim run --resume" ||
  { echo "FAILED: log.txt does not end with the stop message"; tail -3 "$work/killed/log.txt"; exit 1; }
# The signal landed in production, after the checkpoint we waited for.
stopped=$(grep -o "stopped by SIGTERM at step [0-9]*" "$work/killed.log" | grep -o "[0-9]*$")
if [ "$stopped" -lt "$first" ]; then
  echo "FAILED: stopped at step $stopped, before the checkpoint of step $first"; exit 1
fi

"$invasim" run --resume "$work/killed" > "$work/resumed.log" 2>&1 ||
  { echo "FAILED: resume"; cat "$work/resumed.log"; exit 1; }
grep -q "resumed at step" "$work/resumed.log" || { echo "FAILED: did not resume"; cat "$work/resumed.log"; exit 1; }
# The log names the program and threads of each part of the run.
grep -q "^run: resuming the run in .* from its checkpoint; invasim .* [0-9]* threads$" "$work/killed/log.txt" ||
  { echo "FAILED: log.txt does not record the resumed part's threads"; cat "$work/killed/log.txt"; exit 1; }

# RESUME_COMPARE names other files to compare (a run without correlators has no
# correlations.csv).
for f in ${RESUME_COMPARE:-series.csv correlations.csv snapshots/cells_000030000.xyz checkpoint/state.ckpt}; do
  cmp "$work/straight/$f" "$work/killed/$f" || { echo "FAILED: $f differs"; exit 1; }
done
echo "resume_after_kill: identical after SIGTERM at $(grep -o 'at step [0-9]*' "$work/killed.log" | head -1) and --resume"
