#!/usr/bin/env bash
# Test: every directory of docs/data/runs (the validation campaign's kept points) restores into
# a fresh workspace of its sweep file, as docs/data/runs/README.md says. A sweep file whose
# state points change (a parameter added to its `set`, an axis changed) strands its kept
# points: they can no longer be recomputed under changed criteria or continued.
# Stale: sweeps whose kept points were run under an earlier version of their sweep file (the
# Fig. 5 sweeps, whose files ask for 16 times longer runs than the kept ones). They must
# fail to restore, so that the list is emptied when their runs are replaced.
# Usage: kept_runs_restore.sh INVASIM REPO WORKDIR
set -euo pipefail
invasim=$1 repo=$2 work=$3
stale=" fig5_active fig5_extra_curves fig5_passive "
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "kept_runs_restore: FAIL: $*" >&2; exit 1; }
checked=0
for kept in "$repo"/docs/data/runs/*/; do
  name=$(basename "$kept")
  spec="$repo/protocols/sweeps/$name.lua"
  [ -f "$spec" ] || spec="$repo/protocols/sweeps/paper_scale/${name#paper_}.lua"
  [ -f "$spec" ] || fail "$name: no sweep file protocols/sweeps/$name.lua or paper_scale/${name#paper_}.lua"
  "$invasim" sweep init "$spec" --workspace "ws/$name" > "init_$name.log" 2>&1 ||
    { cat "init_$name.log"; fail "sweep init $spec"; }
  if "$repo/scripts/sweep_results.py" restore "$kept" "ws/$name" > "restore_$name.log" 2>&1; then
    [[ "$stale" == *" $name "* ]] && fail "$name restores now: take it off the stale list"
    grep -q "restored [1-9][0-9]* done point" "restore_$name.log" ||
      { cat "restore_$name.log"; fail "$name: no point restored"; }
    checked=$((checked + 1))
  else
    [[ "$stale" == *" $name "* ]] || { cat "restore_$name.log"; fail "$name does not restore"; }
    grep -q "is not in workspace" "restore_$name.log" ||
      { cat "restore_$name.log"; fail "$name: stale, but refused for another reason"; }
  fi
done
[ "$checked" -ge 20 ] || fail "only $checked directories restored"
echo "kept_runs_restore: $checked kept directories restore into their sweep files' workspaces"
