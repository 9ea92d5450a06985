#!/usr/bin/env bash
# `sweep init` writes only its own workspaces, and atomically (docs/sweeps.md, "The
# workspace"; src/sweep/init_workspace.hpp):
#  1. a spec of 10^6 points is refused at once with its count, and nothing is written;
#     --max-points below a spec's count refuses it, at its count accepts it;
#  2. a second init of the same spec changes nothing ("0 new points, 4 kept"); another sweep
#     (another axis, another value of a fixed parameter) is refused naming both specs and
#     what differs, and the workspace stays as it was;
#  3. a run directory and a non-empty directory that is not a workspace are refused; an
#     empty directory becomes the workspace;
#  4. an init SIGKILLed midway (test hook INVASIM_TEST_KILL_SWEEP_INIT_AFTER) leaves no
#     workspace, only its temporary sibling, which the next init removes; a grown init killed
#     midway leaves the workspace listing its old points, and the next init completes it;
#  5. a damaged invasim_sweep.json is refused naming the file, line and column.
# Usage: sweep_workspace.sh INVASIM SPEC_DIR WORK_DIR
set -euo pipefail
invasim=$1 specs=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $1" >&2; if [ $# -gt 1 ]; then cat "$2" >&2; fi; exit 1; }
refused() {  # refused LOG REGEX ARGS...: sweep init ARGS exits 1 with REGEX in LOG
  local log=$1 regex=$2; shift 2
  local rc=0
  # (the KILL after 20 s bounds what a missing count check would write: a guard, not a wait)
  timeout -s KILL 20 "$invasim" sweep init "$@" > "$log" 2>&1 || rc=$?
  [ "$rc" -eq 1 ] || fail "sweep init $* exited $rc, expected 1" "$log"
  grep -qE "$regex" "$log" || fail "sweep init $*: no match for: $regex" "$log"
}
listed() { grep -cE '^    "[0-9a-f]{32}"' "$1/invasim_sweep.json"; }

# 1. The point count, before anything is written.
refused big.log "million.lua has 1000000 points \(f0: 100 x kT: 100 x tau_p: 100\), more than the limit of 10000 points per workspace: nothing written; give --max-points 1000000" \
  "$specs/million.lua" --workspace big
[ -z "$(ls -A | grep -v '\.log$')" ] || fail "the refused 10^6-point init wrote: $(ls -A)"
refused small.log "tiny.lua has 4 points \(kT: 2 x seed: 2\), more than the limit of 3 points" \
  "$specs/tiny.lua" --workspace small --max-points 3
[ ! -e small ] || fail "the refused init wrote small/"
"$invasim" sweep init "$specs/tiny.lua" --workspace small --max-points 4 > /dev/null || fail "--max-points 4"

# 2. The same sweep again; other sweeps refused.
"$invasim" sweep init "$specs/tiny.lua" --workspace ws > init.log || fail "init" init.log
cp ws/invasim_sweep.json config.before
"$invasim" sweep init "$specs/tiny.lua" --workspace ws > again.log || fail "init again" again.log
grep -q "0 new points, 4 kept" again.log || fail "re-init of the same spec" again.log
refused other.log "ws holds the points of .*tiny.lua, another sweep than .*tiny_other_axis.lua: its points give other parameters \(only there: kT; only in .*tiny_other_axis.lua: f0\)" \
  "$specs/tiny_other_axis.lua" --workspace ws
refused fixed.log "ws holds the points of .*tiny.lua, another sweep than .*tiny.lua as given now \(--set, --tiny and --take change it\): its point [0-9a-f]{32} has steps = 1000, .*tiny.lua fixes steps = 500" \
  "$specs/tiny.lua" --workspace ws --set steps=500
cmp -s config.before ws/invasim_sweep.json || fail "a refused init changed invasim_sweep.json"
[ "$(ls ws/workspace | wc -l)" -eq 4 ] || fail "a refused init added job directories"

# 3. Directories that are not workspaces.
mkdir run_dir && touch run_dir/resume.txt run_dir/params.json
refused run.log "run_dir is a run directory \(it holds resume.txt or params.json\), not a sweep workspace" \
  "$specs/tiny.lua" --workspace run_dir
mkdir other && touch other/notes.txt
refused nonempty.log "other is not empty and is not a sweep workspace \(no invasim_sweep.json\)" \
  "$specs/tiny.lua" --workspace other
[ "$(ls -A run_dir | wc -l)" -eq 2 ] && [ "$(ls -A other)" = notes.txt ] || fail "a refused directory was changed"
mkdir empty
"$invasim" sweep init "$specs/tiny.lua" --workspace empty > empty.log || fail "empty directory" empty.log
[ "$(listed empty)" -eq 4 ] || fail "the empty directory did not become a workspace of 4 points"

# 4. Killed inits.
rc=0
INVASIM_TEST_KILL_SWEEP_INIT_AFTER=2 "$invasim" sweep init "$specs/tiny.lua" --workspace killed \
  > killed.log 2>&1 || rc=$?
[ "$rc" -eq 137 ] || fail "the test hook did not SIGKILL the init (exit $rc)" killed.log
[ ! -e killed ] || fail "a killed init left a partial workspace: $(find killed | head)"
ls -d .killed.init.* > /dev/null 2>&1 || fail "the killed init left no temporary sibling"
"$invasim" sweep init "$specs/tiny.lua" --workspace killed > killed2.log || fail "init after kill" killed2.log
grep -q "4 new points, 0 kept" killed2.log || fail "init after the kill" killed2.log
! ls -d .killed.init.* > /dev/null 2>&1 || fail "the stale temporary sibling was not removed"
rc=0
INVASIM_TEST_KILL_SWEEP_INIT_AFTER=1 "$invasim" sweep init "$specs/tiny_grown.lua" --workspace ws \
  > grown_killed.log 2>&1 || rc=$?
[ "$rc" -eq 137 ] || fail "the test hook did not SIGKILL the grown init (exit $rc)" grown_killed.log
cmp -s config.before ws/invasim_sweep.json || fail "a killed grown init changed invasim_sweep.json"
"$invasim" sweep status ws > status.log || fail "status after a killed grown init" status.log
"$invasim" sweep init "$specs/tiny_grown.lua" --workspace ws > grown.log || fail "grown init" grown.log
grep -q "2 new points, 4 kept" grown.log || fail "the grown init after the kill" grown.log
[ "$(listed ws)" -eq 6 ] && [ "$(ls ws/workspace | wc -l)" -eq 6 ] || fail "not 6 points after the grown init"
! ls -d ws/.init.* > /dev/null 2>&1 || fail "the stale staging directory was not removed"
# 5. A damaged configuration is named with the place of the damage.
cp ws/invasim_sweep.json config.good
echo '{"points": [' > ws/invasim_sweep.json
rc=0
"$invasim" sweep status ws > damaged.log 2>&1 || rc=$?
[ "$rc" -eq 1 ] || fail "sweep status of a damaged workspace exited $rc, expected 1" damaged.log
grep -q "'ws/invasim_sweep.json': malformed JSON: parse error at line 2, column 1" damaged.log ||
  fail "a damaged invasim_sweep.json is not named with its line and column" damaged.log
cp config.good ws/invasim_sweep.json
echo "sweep_workspace: counted, refused and atomic"
