#!/usr/bin/env bash
# Test: protocols/tethered.lua inserts the tethers right after compression
# (rest lengths = the separations of the compressed tissue, docs/model.md, protocol step 4), with and
# without heterogeneity, and a run killed during production and resumed with --resume
# restores those tethers (same series.csv as the uninterrupted run).
# Usage: tethers_at_compression.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
. ./wait_for.sh
rm -rf "$work" && mkdir -p "$work"
size=(--set N_a=8 --set N_c=60 --set L0=40.0)
args=(run ../../protocols/tethered.lua "${size[@]}" --set quench_steps=300 --set equilibrate_steps=100
      --set every=100 --set snapshot_every=0 --set correlate_every=0 --set checkpoint_every=500)

# lambda = 0 compresses; the others start from its compressed tissue (--from: tethers on the
# tissue loaded from there), which is also what their rest lengths are checked against.
compressed="$work/run_0/checkpoint/compressed.ckpt"
for lambda in 0 0.3; do
  from=()
  [ "$lambda" = 0 ] || from=(--from "$work/run_0")
  "$invasim" "${args[@]}" "${from[@]}" --set steps=500 --set lambda=$lambda --out "$work/run_$lambda" > "$work/run_$lambda.log" 2>&1 ||
    { echo "FAILED: tethered run (lambda = $lambda)"; cat "$work/run_$lambda.log"; exit 1; }
  # The tether stage comes before the quench in the log.
  grep -o "^\(compress\|tether\|heterogeneity\|quench\|equilibrate\|production\):" "$work/run_$lambda.log" |
    uniq | tr -d ':' | tr '\n' ' ' > "$work/order_$lambda.txt"
  # (heterogeneity with lambda = 0 says so and leaves the rest lengths as they are)
  expected="compress tether heterogeneity quench equilibrate production "
  [ "$(cat "$work/order_$lambda.txt")" = "$expected" ] ||
    { echo "FAILED: stage order '$(cat "$work/order_$lambda.txt")', expected '$expected'"; exit 1; }
  "$invasim" run tether_rest_lengths.lua "${size[@]}" --set run="$work/run_$lambda" --set lambda=$lambda \
    --set compressed="$compressed" \
    --out "$work/check_$lambda" > "$work/check_$lambda.log" 2>&1 ||
    { echo "FAILED: rest lengths (lambda = $lambda)"; cat "$work/check_$lambda.log"; exit 1; }
done

# Kill during production, resume: the tethers (inserted before the quench) come back.
long=("${args[@]}" --from "$work/run_0" --set steps=8000 --set lambda=0.3)
"$invasim" "${long[@]}" --out "$work/straight" > "$work/straight.log" 2>&1
"$invasim" "${long[@]}" --out "$work/killed" > "$work/killed.log" 2>&1 &
pid=$!
# Wait for the first production checkpoint (an event, not a time), then stop the run.
wait_for "$pid" "the first production checkpoint (its line in log.txt)" \
  grep -qs "^production: checkpoint of step " "$work/killed/log.txt" || { cat "$work/killed.log"; exit 1; }
stop_with_sigterm "$pid" "$work/killed.log" "the killed run"
"$invasim" run --resume "$work/killed" > "$work/resumed.log" 2>&1 ||
  { echo "FAILED: resume"; cat "$work/resumed.log"; exit 1; }
grep -q "resumed at step" "$work/resumed.log" || { echo "FAILED: did not resume"; cat "$work/resumed.log"; exit 1; }
cmp "$work/straight/series.csv" "$work/killed/series.csv" || { echo "FAILED: series.csv differs after resume"; exit 1; }
"$invasim" run tether_rest_lengths.lua "${size[@]}" --set run="$work/killed" --set lambda=0.3 \
  --set compressed="$compressed" --out "$work/check_resumed" > "$work/check_resumed.log" 2>&1 ||
  { echo "FAILED: rest lengths after resume"; cat "$work/check_resumed.log"; exit 1; }
echo "tethers_at_compression: rest lengths = compressed separations (lambda 0 and 0.3), restored on resume"
