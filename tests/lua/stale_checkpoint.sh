#!/usr/bin/env bash
# A run directory belongs to one run.
#  a) a new run into a directory that holds another run is refused before any work, naming
#     the directory and the ways out (--resume, another --out, --overwrite); nothing changes;
#  b) --resume refuses a checkpoint written by another run (a run with another P), naming
#     both run ids and the parameter that differs;
#  c) --overwrite deletes the old run's files before the new run starts, so a new run killed
#     before its first production checkpoint resumes with its own parameters (from the
#     beginning, its partial compression or its compressed tissue), not from the old run's
#     checkpoint (a stale-checkpoint scenario);
#  d) a run that stopped before saving anything (refused by the compression's check) leaves a
#     directory that a new run takes over without --overwrite, saying so.
# Usage: stale_checkpoint.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
small=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set steps=400 --set every=200 --set snapshot_every=200 --set checkpoint_every=200
       --set correlate_every=0)
run_id() { grep -o '^# run_id=[0-9a-f]*' "$1/resume.txt" | cut -d= -f2; }

# The first run, to the end: its directory holds state.ckpt, compressed.ckpt and snapshots.
"$invasim" "${small[@]}" --set quench_steps=200 --out "$work/run" > "$work/first.log" 2>&1 || fail "first run" "$work/first.log"
[ -f "$work/run/checkpoint/state.ckpt" ] || fail "the first run left no state.ckpt"
cp -r "$work/run" "$work/run_before"

# a) Another run (P = 2e-3) into the same directory is refused before any work.
status=0
"$invasim" "${small[@]}" --set quench_steps=200 --set P=2e-3 --out "$work/run" > "$work/refused.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "a) a new run into a directory holding a run exited with $status" "$work/refused.log"
first_id=$(run_id "$work/run")
[ ${#first_id} -eq 16 ] || fail "resume.txt records no run id" "$work/run/resume.txt"
grep -q "\"run_id\": *\"$first_id\"" "$work/run/params.json" || fail "params.json has no run_id" "$work/run/params.json"
grep -qF -- "--out $work/run already holds a run (run $first_id) (params.json, resume.txt, checkpoint/state.ckpt, checkpoint/compressed.ckpt): refusing to start another run (run " "$work/refused.log" ||
  fail "a) refusal message" "$work/refused.log"
grep -qF -- "invasim run --resume $work/run; or choose another --out; or add --overwrite" "$work/refused.log" ||
  fail "a) the way out is not named" "$work/refused.log"
! grep -q "^init:" "$work/refused.log" || fail "a) work started before the refusal" "$work/refused.log"
diff -r "$work/run_before" "$work/run" > /dev/null || fail "a) the refused run changed the directory"

# b) --resume with a checkpoint of another run: run B (P = 2e-3) to the end, then put run A's
# state.ckpt in place of its own.
"$invasim" "${small[@]}" --set quench_steps=200 --set P=2e-3 --out "$work/other" > "$work/other.log" 2>&1 || fail "run B" "$work/other.log"
other_id=$(run_id "$work/other")
[ "$other_id" != "$first_id" ] || fail "b) runs with another P have the same id $first_id"
cp "$work/run/checkpoint/state.ckpt" "$work/other/checkpoint/state.ckpt"
status=0
"$invasim" run --resume "$work/other" > "$work/stale.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "b) --resume with another run's checkpoint exited with $status" "$work/stale.log"
grep -qF -- "--resume $work/other: refusing the checkpoint $work/other/checkpoint/state.ckpt: it was written by run $first_id, not by the run $work/other/resume.txt describes (run $other_id)" "$work/stale.log" ||
  fail "b) refusal message" "$work/stale.log"
grep -qF "what differs: P = 0.0013 in the checkpoint, 0.002 in this run; to run" "$work/stale.log" ||
  fail "b) the differing parameter is not named" "$work/stale.log"
! grep -q "^init:\|resumed at step" "$work/stale.log" || fail "b) work started before the refusal" "$work/stale.log"

# c) --overwrite, and the run killed before its first production checkpoint (once its
# compression has begun: a SIGTERM there stops the run at a compression step boundary with a
# checkpoint of its own partly compressed tissue, or, if the compression is already over, in
# the quench), then --resume: it continues its own compression (or starts again from the
# beginning) at P = 2e-3, never from the old run's checkpoint.
"$invasim" "${small[@]}" --set P=2e-3 --set quench_steps=500 --overwrite \
  --out "$work/run" > "$work/killed.log" 2>&1 &
pid=$!
# (log.txt is the new run's once it says what --overwrite deleted.)
compressing() {
  grep -qs "^run: --overwrite: deleted" "$work/run/log.txt" && grep -qs "^compress: to phi" "$work/run/log.txt"
}
wait_for "$pid" "the compression of the new run (its 'compress:' line in log.txt)" compressing ||
  { cat "$work/killed.log"; exit 1; }
stop_with_sigterm "$pid" "$work/killed.log" "c) the killed run"
grep -qE "stopped by SIGTERM (during compression after step|after the compression|during quench at step)" "$work/killed.log" ||
  fail "c) the signal did not land before production" "$work/killed.log"
grep -qF "run: --overwrite: deleted the previous run's params.json, resume.txt, log.txt, series.csv, summary.json, shapes.csv, checkpoint, snapshots in $work/run" "$work/killed.log" ||
  fail "c) --overwrite did not report what it deleted" "$work/killed.log"
for f in checkpoint/state.ckpt series.csv summary.json snapshots; do
  [ ! -e "$work/run/$f" ] || fail "c) $f of the old run survived --overwrite"
done
[ "$(grep -c "^run: invasim" "$work/run/log.txt")" -eq 1 ] || fail "c) log.txt still holds the old run's lines" "$work/run/log.txt"
killed_id=$(run_id "$work/run")
"$invasim" run --resume "$work/run" > "$work/resumed.log" 2>&1 || fail "c) --resume" "$work/resumed.log"
! grep -q "resumed at step" "$work/resumed.log" || fail "c) resumed from a checkpoint" "$work/resumed.log"
grep -qE "^compress: (to phi|skipped: resumed from this run's compressed tissue $work/run/)" "$work/resumed.log" ||
  fail "c) did not start from its own compression" "$work/resumed.log"
grep -q "^quench: P = 0.002," "$work/resumed.log" || fail "c) not the new run's P" "$work/resumed.log"
grep -qE "run $killed_id(;|\) from its checkpoint)" "$work/resumed.log" || fail "c) not the same run id" "$work/resumed.log"
# d) A target below the dilute start is refused by the compression, after the run directory
# was made: nothing saved, so the corrected run needs no --overwrite.
status=0
"$invasim" "${small[@]}" --set phi=0.01 --out "$work/unsaved" > "$work/unsaved.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "d) the refused run exited with $status" "$work/unsaved.log"
grep -q "above the target 0.01; use rescale to expand" "$work/unsaved.log" || fail "d) not refused by the compression" "$work/unsaved.log"
[ -f "$work/unsaved/resume.txt" ] || fail "d) the refused run made no run directory (the case is gone?)"
unsaved_id=$(run_id "$work/unsaved")
"$invasim" "${small[@]}" --set quench_steps=200 --out "$work/unsaved" > "$work/taken.log" 2>&1 || fail "d) the corrected run" "$work/taken.log"
grep -qF "run: replaced run $unsaved_id in $work/unsaved, which stopped before saving anything (no checkpoint, no results): deleted its params.json, resume.txt, log.txt, checkpoint" "$work/taken.log" ||
  fail "d) the take-over is not reported" "$work/taken.log"
[ "$(grep -c "^run: invasim" "$work/unsaved/log.txt")" -eq 1 ] || fail "d) log.txt still holds the refused run's lines" "$work/unsaved/log.txt"
echo "stale_checkpoint: a run directory belongs to one run (refused new run, refused stale checkpoint $first_id for run $other_id, --overwrite, a run that saved nothing taken over)"
