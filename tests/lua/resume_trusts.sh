#!/usr/bin/env bash
# What a --resume trusts (protocols/lib/resume_checks.lua): resume.txt describes the run; the
# other files must agree with it.
#  1. params.json with "P": 5 is refused, naming P in both files;
#  2. resume.txt with another P than its # run_id= line says is refused (params.json names it);
#  3. a protocol script changed since the start is refused, naming both content hashes; so is
#     a module of its lib/ (the observers that write series.csv), naming the module;
#  4. a finished run (its summary.json written) is not run again: exit 0, "nothing to resume";
#  5. params.json with another invasim_version continues with a warning on stderr and in log.txt
#     (a run without its summary.json, as one killed during its end-of-run analysis);
#  6. a run started with a relative protocol path resumes from another working directory
#     (resume.txt records the resolved path);
#  7. a run with an infinite parameter (--set tau_p=inf) resumes: params.json records it as
#     "inf" (JSON has no infinity), which the check reads back as the number.
# Usage: resume_trusts.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
cp -r "$here/../../protocols" "$work/protocols"  # a copy of the protocol to edit in part 3
dir=$work/run
"$invasim" run "$work/protocols/invasion.lua" --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200 \
  --set steps=400 --set every=200 --set snapshot_every=0 --out "$dir" > "$work/run.log" 2>&1 || fail "run" "$work/run.log"
cp "$dir/params.json" "$work/params.json"
cp "$dir/resume.txt" "$work/resume.txt"
refused() {  # refused NAME EXPECTED: --resume exits 1 with EXPECTED in its message
  local status=0
  "$invasim" run --resume "$dir" > "$work/$1.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] || fail "$1: --resume exited with $status (expected 1)" "$work/$1.log"
  grep -qF -- "$2" "$work/$1.log" || fail "$1: no message '$2'" "$work/$1.log"
}

# 1. params.json edited.
sed -i 's/"P": 0.0013,/"P": 5,/' "$dir/params.json"
grep -q '"P": 5,' "$dir/params.json" || fail "the test could not edit params.json" "$dir/params.json"
refused params "$dir/params.json does not agree with $dir/resume.txt, which this resume follows: P = 5 in params.json, 0.0013 in resume.txt"
cp "$work/params.json" "$dir/params.json"

# 2. resume.txt edited (the run's checkpoints set aside: their own refusal, naming P too,
#    would come first; stale_checkpoint.sh tests that one).
mv "$dir/checkpoint/state.ckpt" "$work/state.ckpt"
mv "$dir/checkpoint/compressed.ckpt" "$work/compressed.ckpt"
sed -i 's/^P=0.0013$/P=0.002/' "$dir/resume.txt"
refused resume_txt "P = 0.0013 in params.json, 0.002 in resume.txt"
cp "$work/resume.txt" "$dir/resume.txt"
mv "$work/state.ckpt" "$dir/checkpoint/state.ckpt"
mv "$work/compressed.ckpt" "$dir/checkpoint/compressed.ckpt"

# 3. The protocol changed.
recorded=$(sed -n 's/^# protocol_hash=//p' "$dir/resume.txt")
echo "-- an edit after the run started" >> "$work/protocols/invasion.lua"
refused protocol "the protocol $work/protocols/invasion.lua changed since this run started (content hash $recorded recorded in $dir/resume.txt"
cp "$here/../../protocols/invasion.lua" "$work/protocols/invasion.lua"
grep -q "^# module lib.observers=" "$dir/resume.txt" || fail "resume.txt records no lib.observers" "$dir/resume.txt"
recorded=$(sed -n 's/^# module lib.observers=//p' "$dir/resume.txt")
echo "-- an edit after the run started" >> "$work/protocols/lib/observers.lua"
refused module "the module lib.observers ($work/protocols/lib/observers.lua) changed since this run started (content hash $recorded recorded in $dir/resume.txt"
cp "$here/../../protocols/lib/observers.lua" "$work/protocols/lib/observers.lua"

# 4. A finished run.
cp "$dir/series.csv" "$work/series.csv"
"$invasim" run --resume "$dir" > "$work/finished.log" 2>&1 || fail "--resume of a finished run" "$work/finished.log"
grep -qF "run: $dir holds a finished run (its summary.json is written): nothing to resume" "$work/finished.log" ||
  fail "finished: no message" "$work/finished.log"
grep -q "production" "$work/finished.log" && fail "finished: the run was run again" "$work/finished.log"
cmp "$work/series.csv" "$dir/series.csv" || fail "finished: series.csv rewritten"

# 5. Another invasim version: a warning, and the run continues.
rm "$dir/summary.json"
sed -i 's/"invasim_version": "[^"]*"/"invasim_version": "9.9.9"/' "$dir/params.json"
"$invasim" run --resume "$dir" > "$work/version.log" 2> "$work/version.err" || fail "--resume with another version" "$work/version.err"
grep -q "^invasim: warning: this run was started by invasim 9.9.9 (.*) and is continued by invasim " "$work/version.err" ||
  fail "no warning on stderr" "$work/version.err"
grep -q "^run: warning: this run was started by invasim 9.9.9 " "$dir/log.txt" || fail "no warning in log.txt" "$dir/log.txt"

# 6. A relative protocol path, resumed elsewhere.
(cd "$work" && "$invasim" run protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 \
  --set quench_steps=200 --set steps=400 --set every=200 --set snapshot_every=0 --out relative) \
  > "$work/relative.log" 2>&1 || fail "run with a relative protocol path" "$work/relative.log"
[ "$(head -1 "$work/relative/resume.txt")" = "$work/protocols/invasion.lua" ] ||
  fail "resume.txt does not record the resolved protocol path" "$work/relative/resume.txt"
(cd / && "$invasim" run --resume "$work/relative") > "$work/elsewhere.log" 2>&1 ||
  fail "--resume from another working directory" "$work/elsewhere.log"
grep -qF "nothing to resume" "$work/elsewhere.log" || fail "elsewhere: no message" "$work/elsewhere.log"

# 7. An infinite parameter.
"$invasim" run "$here/../../protocols/invasion.lua" --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200 \
  --set steps=400 --set every=200 --set snapshot_every=0 --set tau_p=inf --out "$work/inf" > "$work/inf.log" 2>&1 ||
  fail "run with tau_p=inf" "$work/inf.log"
grep -q "tau_p = inf" "$work/inf.log" || fail "tau_p=inf did not reach the quench" "$work/inf.log"
grep -qF '"tau_p": "inf"' "$work/inf/params.json" || fail "params.json does not record tau_p as \"inf\"" "$work/inf/params.json"
rm "$work/inf/summary.json"
"$invasim" run --resume "$work/inf" > "$work/inf_resumed.log" 2>&1 || fail "--resume of the tau_p=inf run" "$work/inf_resumed.log"
grep -qF "resumed at step" "$work/inf_resumed.log" || fail "the tau_p=inf run did not resume" "$work/inf_resumed.log"
echo "resume_trusts passed: edited params.json, resume.txt, protocol and module refused; a finished run kept; another version warned; resumed from another directory; an infinite parameter resumed"
