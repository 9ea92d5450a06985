#!/usr/bin/env bash
# A run stopped after its compression and before its first production checkpoint (here: by
# SIGTERM in its quench) keeps its compressed tissue: --resume starts again from it and ends
# exactly like the same run never interrupted (series.csv, the final checkpoint and the
# summary's numbers). The stop message and the resumed log say where the run continues from.
#   own:  the run's own checkpoint/compressed.ckpt (tissue and compression report) is loaded
#         instead of compressing again;
#   from: a run started with --from RUN_DIR starts again from the same --from tissue
#         (resume.txt records --from).
# Usage: quench_resume.sh INVASIM WORKDIR own|from
set -euo pipefail
invasim=$1
work=$2
mode=$3
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
base=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set every=200
      --set snapshot_every=0 --set correlate_every=0)
# The quench's first line is logged before its 20000 steps (about 1 s; 3000 were over before
# the signal on a fast machine): the signal lands in the quench.
args=("${base[@]}" --set quench_steps=20000 --set steps=400 --set checkpoint_every=200)
if [ "$mode" = from ]; then
  "$invasim" "${base[@]}" --set quench_steps=200 --set steps=200 --out "$work/first" > "$work/first.log" 2>&1 ||
    fail "first run" "$work/first.log"
  first=$(cd "$work/first" && pwd -P)
  args+=(--seed 7 --set P=2e-3 --from "$work/first")
  restart="the compressed tissue of $work/first"
  loaded="compress: skipped: the compressed tissue of $first"
else
  restart="its compressed tissue ($work/killed/checkpoint/compressed.ckpt)"
  loaded="compress: skipped: resumed from this run's compressed tissue $work/killed/checkpoint/compressed.ckpt"
fi
"$invasim" "${args[@]}" --out "$work/straight" > "$work/straight.log" 2>&1 || fail "straight run" "$work/straight.log"

"$invasim" "${args[@]}" --out "$work/killed" > "$work/killed.log" 2>&1 &
pid=$!
wait_for "$pid" "the start of the quench (its 'quench: P =' line in log.txt)" \
  grep -qs "^quench: P = " "$work/killed/log.txt" || { cat "$work/killed.log"; exit 1; }
stop_with_sigterm "$pid" "$work/killed.log" "the killed run"
grep -q "stopped by SIGTERM during quench at step" "$work/killed.log" ||
  fail "the signal did not land in the quench" "$work/killed.log"
grep -qF "invasim run --resume $work/killed starts the run again from $restart" "$work/killed.log" ||
  fail "the stop message does not say where --resume continues from" "$work/killed.log"
[ ! -e "$work/killed/checkpoint/state.ckpt" ] || fail "a checkpoint was written before production"

"$invasim" run --resume "$work/killed" > "$work/resumed.log" 2>&1 || fail "--resume" "$work/resumed.log"
grep -qF "$loaded" "$work/resumed.log" || fail "the resumed run did not load the compressed tissue" "$work/resumed.log"
! grep -q "^compress: to phi" "$work/resumed.log" || fail "the resumed run compressed again" "$work/resumed.log"
grep -q "^quench: P = " "$work/resumed.log" || fail "the resumed run did not quench" "$work/resumed.log"
if [ "$mode" = from ]; then
  grep -qxF -- "--from=$first" "$work/killed/resume.txt" || fail "resume.txt does not record --from" "$work/killed/resume.txt"
  grep -qF "run: no checkpoint of this run in $work/killed: --resume starts it again from $restart" "$work/killed/log.txt" ||
    fail "log.txt does not say where the resume starts" "$work/killed/log.txt"
else
  cmp "$work/straight/checkpoint/compressed.ckpt" "$work/killed/checkpoint/compressed.ckpt" ||
    fail "compressed.ckpt differs from the uninterrupted run's"
fi
cmp "$work/straight/series.csv" "$work/killed/series.csv" || fail "series.csv differs from the uninterrupted run"
cmp "$work/straight/checkpoint/state.ckpt" "$work/killed/checkpoint/state.ckpt" ||
  fail "the final checkpoint differs from the uninterrupted run's"
numbers() { grep -E "^summary: (A_t|T_c|P_|compressed)" "$1"; }
[ -n "$(numbers "$work/straight.log")" ] || fail "no summary lines to compare" "$work/straight.log"
diff <(numbers "$work/straight.log") <(numbers "$work/resumed.log") ||
  fail "the summary differs from the uninterrupted run's"
echo "quench_resume ($mode): a run killed in its quench resumed from $restart, identical to the uninterrupted run"
