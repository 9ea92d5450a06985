#!/usr/bin/env bash
# scripts/campaign.sh on tests/app/sweeps/tiny.lua: a first campaign runs the 4 points and
# keeps them; with its workspaces gone (a new machine), a second campaign restores them and
# runs none again; a stop file stops it before its next sweep.
# Usage: campaign.sh INVASIM SPEC_DIR WORK_DIR REPO
set -euo pipefail
invasim=$1 specs=$2 work=$3 repo=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $1" >&2; if [ $# -gt 1 ]; then cat "$2" >&2; fi; exit 1; }
export INVASIM=$invasim JOBS=2
bash "$repo/scripts/campaign.sh" out keep "$specs/tiny.lua" > first.log 2>&1 || fail "first" first.log
grep -q "4 of 4 points done" first.log || fail "the first campaign did not finish" first.log
[ "$(ls keep/tiny | wc -l)" -eq 4 ] || fail "the first campaign kept $(ls keep/tiny | wc -l) points"
rm -rf out
bash "$repo/scripts/campaign.sh" out keep "$specs/tiny.lua" > second.log 2>&1 || fail "second" second.log
grep -q "restored 4 done point(s)" second.log && grep -q "0 done now, 4 done before" second.log ||
  fail "the second campaign did not take the kept points back" second.log
if grep -q "started [0-9a-f]\{8\}" second.log; then fail "a kept point ran again" second.log; fi
touch out/stop
bash "$repo/scripts/campaign.sh" out keep "$specs/tiny.lua" > third.log 2>&1 || fail "third" third.log
grep -q "out/stop found: stopping" third.log || fail "the stop file was not honoured" third.log
echo "campaign: points kept, restored on a fresh workspace, not run again"
