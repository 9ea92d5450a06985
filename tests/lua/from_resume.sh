#!/usr/bin/env bash
# A run started with --from RUN_DIR and killed before its first checkpoint
# (here: during its quench) starts again, on --resume, from the same compressed tissue
# (resume.txt records --from), and ends exactly like the same run never interrupted.
# Usage: from_resume.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
base=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set every=200
      --set snapshot_every=0 --set correlate_every=0)
"$invasim" "${base[@]}" --set quench_steps=200 --set steps=200 --out "$work/first" > "$work/first.log" 2>&1 ||
  fail "first run" "$work/first.log"
first=$(cd "$work/first" && pwd -P)
second=("${base[@]}" --seed 7 --set P=2e-3 --set quench_steps=20000 --set steps=400 --from "$work/first")
"$invasim" "${second[@]}" --out "$work/straight" > "$work/straight.log" 2>&1 || fail "straight run" "$work/straight.log"

"$invasim" "${second[@]}" --out "$work/killed" > "$work/killed.log" 2>&1 &
pid=$!
# The quench's first line is logged before its steps, and its 20000 steps last ~1 s (3000
# were over before the signal on a fast machine): the signal lands in the quench.
wait_for "$pid" "the start of the quench (its 'quench: P =' line in log.txt)" \
  grep -qs "^quench: P = " "$work/killed/log.txt" || { cat "$work/killed.log"; exit 1; }
stop_with_sigterm "$pid" "$work/killed.log" "the killed run"
grep -q "stopped by SIGTERM during quench at step" "$work/killed.log" ||
  fail "the signal did not land in the quench" "$work/killed.log"
grep -qF "invasim run --resume $work/killed starts the run again from the compressed tissue of $work/first" "$work/killed.log" ||
  fail "the stop message does not name the way to continue" "$work/killed.log"
[ ! -e "$work/killed/checkpoint/state.ckpt" ] || fail "a checkpoint was written before production"

"$invasim" run --resume "$work/killed" > "$work/resumed.log" 2>&1 || fail "--resume" "$work/resumed.log"
grep -qF "run: no checkpoint of this run in $work/killed: --resume starts it again from the beginning" "$work/killed/log.txt" ||
  fail "log.txt does not say the resume starts again" "$work/killed/log.txt"
grep -qF "compress: skipped: the compressed tissue of $first" "$work/resumed.log" ||
  fail "the resumed run did not start from the first run's compressed tissue" "$work/resumed.log"
! grep -q "^compress: to phi" "$work/resumed.log" || fail "the resumed run compressed a new tissue" "$work/resumed.log"
grep -qxF -- "--from=$first" "$work/killed/resume.txt" || fail "resume.txt does not record --from" "$work/killed/resume.txt"
cmp "$work/straight/series.csv" "$work/killed/series.csv" || fail "series.csv differs from the uninterrupted run"
echo "from_resume: a --from run killed in its quench resumed from $first's tissue, identical to the uninterrupted run"
