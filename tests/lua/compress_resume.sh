#!/usr/bin/env bash
# A run stopped by SIGTERM during its compression writes a checkpoint of the
# partly compressed tissue (checkpoint/compressing.ckpt, at the next FIRE iteration, with the
# minimiser's own state: the signal comes while a step's FIRE runs), and `invasim run --resume DIR` continues the compression to the same compressed
# tissue as a run never interrupted (byte-identical compressed.ckpt), then runs quench and
# production to the same end (identical series.csv, state.ckpt). The kill waits for an event
# (the third compression step in log.txt), never for a time. The partial checkpoint carries
# the run's identity: --resume refuses it once resume.txt describes another run. A signal
# during the final FIRE stops it at its next iteration too, and --resume goes on to the same end.
# Usage: compress_resume.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
args=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=500
      --set steps=1000 --set every=200 --set checkpoint_every=1000 --set snapshot_every=0)
"$invasim" "${args[@]}" --out "$work/straight" > "$work/straight.log" 2>&1 || fail "straight run" "$work/straight.log"

# The killed run waits inside compression step 4 (a test hook that only waits for the signal,
# numbers untouched), so the signal always lands during the compression, however fast it is.
INVASIM_TEST_PAUSE_AT_COMPRESSION_STEP=4 "$invasim" "${args[@]}" --out "$work/killed" > "$work/killed.log" 2>&1 &
pid=$!
wait_for "$pid" "the third compression step (its 'compress: step 3:' line in log.txt)" \
  grep -qs "^compress: step 3: " "$work/killed/log.txt" || { cat "$work/killed.log"; exit 1; }
stop_with_sigterm "$pid" "$work/killed.log" "the killed run"
grep -qF "checkpoint saved to $work/killed/checkpoint/compressing.ckpt; continue with: invasim run --resume $work/killed" "$work/killed.log" ||
  fail "no stop message naming the checkpoint and --resume" "$work/killed.log"
grep -q "stopped by SIGTERM during compression after step [0-9]*, inside the FIRE of step [0-9]* at iteration [0-9]* (phi = " "$work/killed.log" ||
  fail "the signal did not stop the compression inside a FIRE minimisation" "$work/killed.log"
stopped=$(grep -o "during compression after step [0-9]*" "$work/killed.log" | grep -o "[0-9]*$")
total=$(grep -o "^compress: phi = .* after [0-9]* steps" "$work/straight.log" | grep -o "[0-9]* steps$" | grep -o "^[0-9]*")
[ "$stopped" -ge 3 ] && [ "$stopped" -lt "$total" ] ||
  fail "stopped after compression step $stopped, not between step 3 and the last ($total)"
[ -f "$work/killed/checkpoint/compressing.ckpt" ] || fail "no checkpoint/compressing.ckpt"
for f in checkpoint/state.ckpt checkpoint/compressed.ckpt; do
  [ ! -e "$work/killed/$f" ] || fail "$f written by a run stopped during compression"
done

# The partial checkpoint belongs to its run: with resume.txt describing another P, refused.
cp -r "$work/killed" "$work/other"
sed -i 's/^P=.*/P=0.002/' "$work/other/resume.txt"
grep -qx "P=0.002" "$work/other/resume.txt" || fail "resume.txt records no P line" "$work/other/resume.txt"
status=0
"$invasim" run --resume "$work/other" > "$work/other.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "--resume with another run's partial checkpoint exited with $status" "$work/other.log"
grep -qF "refusing the checkpoint $work/other/checkpoint/compressing.ckpt: it was written by run" "$work/other.log" ||
  fail "the partial checkpoint of another run was not refused" "$work/other.log"
! grep -q "^compress: resumed" "$work/other.log" || fail "work started before the refusal" "$work/other.log"

"$invasim" run --resume "$work/killed" > "$work/resumed.log" 2>&1 || fail "--resume" "$work/resumed.log"
grep -q "^compress: resumed after $stopped compression steps (phi = " "$work/resumed.log" ||
  fail "the compression did not continue from step $stopped" "$work/resumed.log"
[ ! -e "$work/killed/checkpoint/compressing.ckpt" ] || fail "compressing.ckpt left after the compression"
grep "^compress: phi = " "$work/straight.log" | sed 's/; [0-9.]* s$//' > "$work/straight.compress"
grep "^compress: phi = " "$work/resumed.log" | sed 's/; [0-9.]* s$//' > "$work/resumed.compress"
cmp "$work/straight.compress" "$work/resumed.compress" ||
  fail "the compression report differs: $(cat "$work/straight.compress") vs $(cat "$work/resumed.compress")"
for f in checkpoint/compressed.ckpt series.csv checkpoint/state.ckpt; do
  cmp "$work/straight/$f" "$work/killed/$f" || fail "$f differs from the uninterrupted run"
done

# A signal during the final FIRE (after the line of the last compression step): the run stops at its next iteration, saving the tissue,
# the compression's report and the minimiser's state; --resume continues that FIRE to the
# same compressed tissue and the same end.
# (The final run waits at the start of its final FIRE, a test hook, so the signal lands inside it.)
INVASIM_TEST_PAUSE_IN_STOPPABLE_MINIMIZE=1 "$invasim" "${args[@]}" --out "$work/final" > "$work/final.log" 2>&1 &
pid=$!
wait_for "$pid" "the last compression step (its 'compress: step $total:' line in log.txt)" \
  grep -qs "^compress: step $total: " "$work/final/log.txt" || { cat "$work/final.log"; exit 1; }
stop_with_sigterm "$pid" "$work/final.log" "the run killed in its final FIRE"
grep -q "stopped by SIGTERM after compression step $total, inside the final FIRE at iteration [0-9]* (phi = 0.7200); checkpoint saved to $work/final/checkpoint/compressing.ckpt" "$work/final.log" ||
  fail "the signal during the final FIRE did not stop it at its next iteration" "$work/final.log"
iteration=$(grep -o "inside the final FIRE at iteration [0-9]*" "$work/final.log" | grep -o "[0-9]*$")
"$invasim" run --resume "$work/final" > "$work/final_resumed.log" 2>&1 || fail "--resume inside the final FIRE" "$work/final_resumed.log"
grep -q "^compress: resumed after $total compression steps and $iteration iterations of the final FIRE" "$work/final_resumed.log" ||
  fail "did not continue the final FIRE from iteration $iteration" "$work/final_resumed.log"
grep "^compress: phi = " "$work/final_resumed.log" | sed 's/; [0-9.]* s$//' > "$work/final.compress"
cmp "$work/straight.compress" "$work/final.compress" ||
  fail "the compression report differs: $(cat "$work/straight.compress") vs $(cat "$work/final.compress")"
[ "$(grep -c "^compress: step " "$work/final/log.txt")" -eq "$total" ] ||
  fail "the resumed run compressed again" "$work/final/log.txt"
[ ! -e "$work/final/checkpoint/compressing.ckpt" ] || fail "compressing.ckpt left after the final FIRE"
for f in checkpoint/compressed.ckpt series.csv checkpoint/state.ckpt; do
  cmp "$work/straight/$f" "$work/final/$f" || fail "$f differs after a stop in the final FIRE"
done
echo "compress_resume: stopped by SIGTERM after compression step $stopped of $total, and at iteration $iteration of the final FIRE; --resume gave the uninterrupted run's compressed.ckpt, series.csv and state.ckpt"
