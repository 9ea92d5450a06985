#!/usr/bin/env bash
# Test: `invasim run --from RUN_DIR` starts from the compressed tissue that RUN_DIR
# saved (no compression of its own), with its own seed and parameters.
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
args=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
      --set steps=400 --set every=200 --set snapshot_every=0)
"$invasim" "${args[@]}" --out "$work/first" > "$work/first.log" 2>&1
[ -f "$work/first/checkpoint/compressed.ckpt" ] || { echo "FAILED: no compressed.ckpt"; exit 1; }
"$invasim" "${args[@]}" --seed 7 --set P=2e-3 --from "$work/first" --out "$work/second" > "$work/second.log" 2>&1 ||
  { echo "FAILED: second run"; cat "$work/second.log"; exit 1; }
grep -q "compress: skipped: the compressed tissue of $work/first" "$work/second.log" ||
  { echo "FAILED: did not start from the first run"; cat "$work/second.log"; exit 1; }
first_box=$(grep -o "final box L_f = [0-9.]*" "$work/first.log" | grep -o "[0-9.]*$")
grep -q "compressed box L_f = $first_box" "$work/second.log" || { echo "FAILED: box"; exit 1; }
grep -q "quench: P = 0.002" "$work/second.log" || { echo "FAILED: own parameters"; exit 1; }
! "$invasim" "${args[@]}" --from "$work/missing" --out "$work/third" > "$work/third.log" 2>&1 ||
  { echo "FAILED: a missing run directory was accepted"; exit 1; }
grep -q "missing/checkpoint/compressed.ckpt" "$work/third.log" || { echo "FAILED: message"; cat "$work/third.log"; exit 1; }
# A tissue of another size is refused (groups and forces index the sites).
! "$invasim" run ../../protocols/invasion.lua --set N_a=4 --set N_c=61 --set L0=32.0 --from "$work/first" --out "$work/fourth" > "$work/fourth.log" 2>&1 ||
  { echo "FAILED: a tissue of another size was accepted"; exit 1; }
grep -q "holds 228 sites and 4 adipocytes, this System 229 sites" "$work/fourth.log" ||
  { echo "FAILED: size message"; cat "$work/fourth.log"; exit 1; }
echo "from_run: the second run started from the first run's compressed tissue (L_f = $first_box)"
