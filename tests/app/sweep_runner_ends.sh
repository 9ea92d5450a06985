#!/usr/bin/env bash
# How `sweep run` ends, on tests/app/sweeps/tiny.lua (4 points and a shared preparation):
#  1. a point held by another runner (its lock taken, its document "running") is skipped, and
#     the run exits 1 listing it as running elsewhere with the holder's pid; once the holder
#     is gone the next run finishes it and exits 0;
#  2. a runner killed with SIGKILL leaves its children running; each point's document then
#     ends in the state its run ended in ("done"), none stays "running" or reads interrupted;
#  3. a point stopped by SIGINT logs "invasim: stopped by SIGINT ..." (not an error) and names
#     the sweep's own command to continue it, not `invasim run --resume`.
# Usage: sweep_runner_ends.sh INVASIM SPEC_DIR WORK_DIR
set -euo pipefail
invasim=$1 specs=$2 work=$3
source "$(dirname "$0")/../lua/wait_for.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# signal_once_running WS SIGNAL: a new workspace WS of tiny.lua run by `sweep run` (output in
# WS.log), sent SIGNAL once a point has written a checkpoint; returns when the runner ended.
# The points run 100000 steps (seconds, not tiny.lua's milliseconds), so the point whose
# checkpoint was seen is still in production when the signal arrives.
signal_once_running() {
  "$invasim" sweep init "$specs/tiny.lua" --workspace "$1" --set steps=100000 \
    --set checkpoint_every=2000 > /dev/null
  "$invasim" sweep run "$1" --jobs 2 --threads 1 > "$1.log" 2>&1 &
  local runner=$!
  wait_for $runner "a checkpoint of a point" \
    bash -c "ls $1/workspace/*/checkpoint/state.ckpt > /dev/null 2>&1"
  kill -"$2" $runner
  wait $runner 2> /dev/null || true
}

# 1. One point held elsewhere.
"$invasim" sweep init "$specs/tiny.lua" --workspace ws > /dev/null
held=$(ls ws/workspace | head -1)
echo '{"status": "running", "pid": 4242, "host": "elsewhere"}' \
  > "ws/workspace/$held/signac_job_document.json"
flock -F "ws/workspace/$held/run.lock" sleep 600 &
holder=$!
trap 'kill $holder 2> /dev/null || true' EXIT  # a failure must not leave the holder behind
wait_for $holder "the holder's lock" bash -c "! flock -n ws/workspace/$held/run.lock true"
status=0
"$invasim" sweep run ws --jobs 2 --threads 1 > run1.log 2>&1 || status=$?
[ $status -eq 1 ] || fail "a run that left a point held elsewhere exited $status, not 1" run1.log
grep -q "3 of 4 points done; 1 not done:" run1.log || fail "no count of the points left" run1.log
grep -q "^  ${held:0:8} (.*): running elsewhere (pid 4242 on elsewhere" run1.log ||
  fail "the held point is not listed as running elsewhere" run1.log
kill $holder
wait $holder 2> /dev/null || true
"$invasim" sweep run ws --jobs 2 --threads 1 > run2.log 2>&1 || fail "the second run" run2.log
grep -q "4 of 4 points done$" run2.log || fail "the second run did not finish" run2.log

# 2. The runner SIGKILLed while points run.
signal_once_running killed KILL
sleep 600 &
guard=$!
trap 'kill $guard 2> /dev/null || true' EXIT
wait_for $guard "the orphaned points' end" bash -c "! pgrep -f 'sweep jo[b] $PWD/killed ' > /dev/null"
kill $guard
started=0
for d in killed/workspace/*/; do
  grep -q '"status": "pending"\|^{}$' "$d/signac_job_document.json" 2> /dev/null && continue
  [ -f "$d/run.log" ] || continue
  started=$((started + 1))
  grep -q '"status": "done"' "$d/signac_job_document.json" ||
    fail "a point the killed runner started did not end done" "$d/signac_job_document.json"
done
[ $started -ge 1 ] || fail "no point had started when the runner was killed" killed.log
"$invasim" sweep status killed > killed_status.log
grep -q "interrupted: 0" killed_status.log && grep -q "running: 0" killed_status.log ||
  fail "status after the killed runner" killed_status.log

# 3. A stop by SIGINT names the sweep's command.
#    A point in production continues from its checkpoint; one still in its quench (the other
#    job may be) starts again from its compressed tissue; either way the line names the
#    sweep's command.
signal_once_running stopped INT
logs=$(grep -l "stopped by SIGINT" stopped/workspace/*/run.log || true)
[ -n "$logs" ] || fail "no point logged its stop" stopped.log
continued=0
for log in $logs; do
  if grep -q "^invasim: stopped by SIGINT at step .*continue with: invasim sweep run $PWD/stopped$" "$log"; then
    continued=$((continued + 1))
  else
    grep -q "^invasim: stopped by SIGINT during quench at step .*: invasim sweep run $PWD/stopped starts the run again from its compressed tissue (.*/checkpoint/compressed.ckpt)$" "$log" ||
      fail "the stop does not name the sweep's command" "$log"
  fi
  if grep -q "invasim: error:\|invasim run --resume" "$log"; then
    fail "the stop reads as an error or names invasim run --resume" "$log"
  fi
done
[ $continued -ge 1 ] || fail "no point stopped in production (the one with a checkpoint)" stopped.log
grep -q "interrupted (continue with sweep run" stopped.log || fail "the runner's list" stopped.log
echo "sweep_runner_ends: held points listed with exit 1, orphans record their end, stops name the sweep"
