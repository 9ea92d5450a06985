#!/bin/bash
# The paper-scale sweep files (protocols/sweeps/paper_scale/) at their CI size: each must
# initialise at its full size (the point count its header promises is what `sweep init`
# makes) and run its `tiny = {...}` points to the end, so that no file rots before the
# cluster or the long campaign uses it.
# Usage: paper_scale_tiny.sh INVASIM REPO WORKDIR
set -euo pipefail
invasim=$1 repo=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cd "$work"
fail() { echo "paper_scale_tiny: FAIL: $*" >&2; exit 1; }
n=0
for spec in "$repo"/protocols/sweeps/paper_scale/*.lua; do
  name=$(basename "$spec" .lua)
  grep -q 'system = "paper"' "$spec" || fail "$spec does not run the paper's system"
  grep -q "steps = 10000000" "$spec" || fail "$spec does not run the paper's 1e7 steps"
  "$invasim" sweep init "$spec" --workspace "full_$name" > "full_$name.log" || { cat "full_$name.log"; fail "init $spec"; }
  "$invasim" sweep init "$spec" --tiny --workspace "ws_$name" > "ws_$name.log" || { cat "ws_$name.log"; fail "init --tiny $spec"; }
  "$invasim" sweep run "ws_$name" --jobs 2 --threads 1 >> "ws_$name.log" 2>&1 \
    || { cat "ws_$name.log"; fail "sweep run $name"; }
  "$invasim" sweep status "ws_$name" | grep -q "failed: 0" || fail "$name: failed points"
  echo "ok: $name ($(ls "full_$name/workspace" | wc -l) points at full size)"
  n=$((n + 1))
done
[ "$n" -ge 6 ] || fail "only $n paper-scale sweep files"
echo "paper_scale_tiny: $n sweep files initialise and run at their CI size"
