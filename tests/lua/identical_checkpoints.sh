#!/usr/bin/env bash
# Two identical runs write byte-identical checkpoints (state.ckpt and
# compressed.ckpt): the protocol's Lua state is written with its keys in a fixed order, and no
# wall-clock time goes into a checkpoint. Usage: identical_checkpoints.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
args=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=500
      --set steps=2000 --set every=200 --set checkpoint_every=1000)
for run in a b; do
  "$invasim" "${args[@]}" --out "$work/$run" > "$work/$run.log" 2>&1 || fail "run $run" "$work/$run.log"
done
for f in checkpoint/state.ckpt checkpoint/compressed.ckpt; do
  [ -s "$work/a/$f" ] || fail "run a wrote no $f"
  cmp "$work/a/$f" "$work/b/$f" || fail "$f differs between two identical runs"
done
echo "identical_checkpoints: two identical runs wrote byte-identical state.ckpt and compressed.ckpt"
