#!/usr/bin/env bash
# scripts/sweep_results.py keeps a sweep's done points and puts them back into a fresh
# workspace (docs/sweeps.md, "A campaign over several machines"), on tests/app/sweeps/tiny.lua:
#  1. `save` keeps each done point's statepoint, job document and result files, and no
#     checkpoint, snapshot or lock;
#  2. `restore` into a fresh workspace of the same sweep file makes `sweep status` count the
#     points done, `sweep run` starts none of them, and `sweep collect` gives the same rows;
#  3. a kept point whose statepoint was changed, or a workspace of another sweep file, is
#     refused with a message naming the point.
# Usage: sweep_results.sh INVASIM SPEC_DIR WORK_DIR PYTHON3 SCRIPTS_DIR
set -euo pipefail
invasim=$1 specs=$2 work=$3 python=$4 scripts=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $1" >&2; if [ $# -gt 1 ]; then cat "$2" >&2; fi; exit 1; }
keep() { "$python" "$scripts/sweep_results.py" "$@"; }

"$invasim" sweep init "$specs/tiny.lua" --workspace ws > /dev/null
"$invasim" sweep run ws --jobs 2 --threads 1 > run.log 2>&1 || fail "sweep run" run.log
"$invasim" sweep collect ws -o before.csv > /dev/null

keep save ws kept > save.log || fail "save" save.log
grep -q "saved 4 done point(s)" save.log || fail "save did not keep 4 points" save.log
for d in kept/*/; do
  for f in signac_statepoint.json signac_job_document.json summary.json series.csv; do
    [ -f "$d$f" ] || fail "save did not keep $d$f"
  done
done
if find kept \( -name checkpoint -o -name '*.lock' -o -name '*.ckpt' -o -name '*.vtp' \) |
   grep -q .; then
  fail "save kept a checkpoint, snapshot or lock: $(find kept | head -20)"
fi

"$invasim" sweep init "$specs/tiny.lua" --workspace fresh > /dev/null
keep restore kept fresh > restore.log || fail "restore" restore.log
grep -q "restored 4 done point(s)" restore.log || fail "restore did not put back 4" restore.log
"$invasim" sweep status fresh > status.log
grep -Eq "done: 4" status.log || fail "status does not count the restored points done" status.log
"$invasim" sweep run fresh --jobs 2 --threads 1 > rerun.log 2>&1 || fail "sweep run" rerun.log
if grep -q "started [0-9a-f]\{8\}" rerun.log; then
  fail "sweep run redid a restored point" rerun.log
fi
"$invasim" sweep collect fresh -o after.csv > /dev/null
cmp -s before.csv after.csv || fail "collect differs after the restore: $(diff before.csv after.csv)"

# A kept point with another statepoint, and a workspace of another sweep, are refused.
one=$(ls kept | head -1)
sed -i 's/"seed": *[0-9]*/"seed": 99/' "kept/$one/signac_statepoint.json"
"$invasim" sweep init "$specs/tiny.lua" --workspace again > /dev/null
if keep restore kept again > bad.log 2>&1; then fail "a changed statepoint was restored" bad.log; fi
grep -q "point $one has another statepoint" bad.log || fail "the refusal names no point" bad.log
"$invasim" sweep init "$specs/tiny_other_axis.lua" --workspace other > /dev/null
if keep restore kept other > other.log 2>&1; then fail "another sweep's workspace" other.log; fi
grep -q "is not in workspace other" other.log || fail "the refusal names no workspace" other.log
echo "sweep_results: done points kept and restored; sweep run skips them"
