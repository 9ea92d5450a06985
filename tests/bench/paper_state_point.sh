#!/usr/bin/env bash
# Target 4 of docs/performance.md ("Targets"): one paper state point as the paper-scale sweeps
# run it (protocols/sweeps/paper_scale/fig5_cohesive.lua's settings: the paper's system, the
# default background, beta = 1e-2, tau_p = 25, f0 = 0.00265, A_t every 10000 steps, the
# correlators every 20), at THREADS threads. It does not run the 1e7 steps: from one compressed
# tissue (--from), it times two productions of S and 2 S steps (after the same 20000-step
# quench) and scales the difference, (t(2S) - t(S)) / S per step, to 1e7 steps, plus the
# fixed cost (compression, quench, the end-of-run measurements) from the first; and, less
# sensitive to one slow run, the same projection from the 2S run's own production time. Prints
# the timings and both projections, and says so: run it on an idle machine.
# Usage: tests/bench/paper_state_point.sh [build dir = build] [threads = 2] [S = 20000]
set -euo pipefail
build=${1:-build}
threads=${2:-2}
steps=${3:-20000}
bin="$build/invasim"
[ -x "$bin" ] || { echo "build first: $bin not found"; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
protocol="$here/../../protocols/invasion.lua"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(--set system=paper --set beta=1e-2 --set tau_p=25 --set f0=0.00265 --set every=10000
        --set snapshot_every=0 --set checkpoint_every=0 --threads "$threads")
seconds() {  # run the production of $1 steps from the compressed tissue, print wall seconds
  local start end
  start=$(date +%s.%N)
  "$bin" run "$protocol" "${common[@]}" --set steps="$1" --from "$work/prep" --out "$work/run_$1" \
    > "$work/run_$1.log" 2>&1 || { cat "$work/run_$1.log" >&2; return 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }'
}
start=$(date +%s.%N)
"$bin" run "$protocol" "${common[@]}" --set quench_steps=0 --set steps=0 --out "$work/prep" > "$work/prep.log" 2>&1 \
  || { cat "$work/prep.log"; exit 1; }
end=$(date +%s.%N)
compress=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')
(( steps >= 10000 )) || { echo "S = $steps: at least 10000 (A_t is sampled every 10000 steps)"; exit 1; }
t1=$(seconds "$steps") || exit 1
t2=$(seconds $((2 * steps))) || exit 1
# The 2S run's own production time (summary.json "seconds": the production stage's run, its
# measurements included): a second projection, c + (t2 - P) + P / (2S) x 1e7, that does not
# rest on the difference of two runs (one slow leg moves that one by minutes on a noisy host).
prod=$(grep -o '"seconds": *[0-9.eE+-]*' "$work/run_$((2 * steps))/summary.json" | head -1 | sed 's/.*: *//')
[ -n "$prod" ] || { echo "no production time in $work/run_$((2 * steps))/summary.json"; exit 1; }
awk -v c="$compress" -v t1="$t1" -v t2="$t2" -v s="$steps" -v th="$threads" -v p="$prod" 'BEGIN {
  per = (t2 - t1) / s; fixed = t1 - per * s
  printf "paper state point (28 adipocytes + 1500 cells, %d threads): compression %.1f s; quench + %d steps %.1f s; quench + %d steps %.1f s\n", th, c, s, t1, 2 * s, t2
  printf "per production step %.3g ms (%.3g site-steps/s over 2704 sites); projected for 1e7 steps: %.1f minutes (compression and quench included; scaled from %d steps, not run)\n", 1000 * per, 2704 / per, (c + fixed + per * 1e7) / 60, s
  rate = p / (2 * s)
  printf "from the %d-step run alone (its production %.1f s, %.3g site-steps/s): projected %.1f minutes (compression, quench and start-up as measured; not run)\n", 2 * s, p, 2704 / rate, (c + (t2 - p) + rate * 1e7) / 60
}'
