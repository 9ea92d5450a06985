#!/bin/bash
# The paper-scale sweep files (protocols/sweeps/paper_scale/) at their CI size: each must
# initialise at its full size (the "N points" its header promises are what `sweep init`
# makes) and run its `tiny = {...}` points to the end, so that no file rots before the
# cluster or the long campaign uses it. Then the paper-scale analysis (`scripts/validation.py
# paper`, docs/validation.md "At the paper's scale") reads the tiny workspaces under the
# campaign's names (ROOT/paper_<file>): a record per figure with its rows and the A_n(t)
# panels, the cost record, and a page with the section; and the analysis's mirror of the
# summary's errors (scripts/invasim_analysis/steady.py, summary_error) gives the errors,
# tau_int and error_converged summary.json holds (src/measure/mean_error.cpp).
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
  points=$(ls "full_$name/workspace" | wc -l)
  promised=$(sed -n '/^--/!q; s/.*[^0-9]\([0-9][0-9]*\) points.*/\1/p' "$spec" | head -1)
  [ -n "$promised" ] || fail "$spec: its header does not say how many points it has (\"N points\")"
  [ "$promised" = "$points" ] || fail "$name: the header promises $promised points, sweep init made $points"
  echo "ok: $name ($points points at full size, as its header says)"
  n=$((n + 1))
done
[ "$n" -ge 6 ] || fail "only $n paper-scale sweep files"

mkdir -p root
for name in fig3_passive_slices fig4a_passive fig4b_starts fig5_cohesive; do
  ln -s "../ws_$name" "root/paper_$name"
done
"$repo/scripts/validation.py" paper root -o records/paper --invasim "$invasim" \
  --plan "$repo/docs/validation/plan_paper_scale.json" > paper.log 2>&1 || { cat paper.log; fail "validation.py paper"; }
"$repo/scripts/validation.py" document records --paper records/paper -o page.md > document.log 2>&1 \
  || { cat document.log; fail "validation.py document --paper"; }
/usr/bin/python3 - "$repo/scripts" root records page.md <<'PY' || fail "the paper-scale records"
import json, math, os, sys
from invasim_analysis import steady, workspace
root, records, page = sys.argv[2:5]
problems = []
for fig in ("fig3", "fig4a", "fig4b", "fig5"):
    rec = json.load(open(os.path.join(records, "paper", "paper_%s.json" % fig)))
    if not rec["rows"] or not rec["runs"] or any(p["class"] != "done" for p in rec["runs"]):
        problems.append("%s: rows %r, runs %r" % (fig, rec["rows"], rec["runs"]))
    if not os.path.getsize(os.path.join(records, "paper", "%s_runs.png" % fig)) > 1000:
        problems.append("%s: no A_n(t) panels" % fig)
cost = json.load(open(os.path.join(records, "paper", "paper_cost.json")))
if not (cost["used_core_hours"] > 0 and cost["whole_paper"]["core_hours"] > 100):
    problems.append("cost %r" % cost)
text = open(page).read()
if "## At the paper's scale" not in text or "| `fig4b_An_at_0.3` |" not in text:
    problems.append("the page has no paper-scale section with the fig4b_An_at_0.3 row")
for ws in sorted(os.listdir(root)):
    for j in workspace.load(os.path.join(root, ws)):
        first, end = steady.window(j)
        got = steady.summary_error(j.series["A_t"][first:end])
        entry = j.summary["averages"]["A_t"]
        want = entry["error"], entry["tau_int"], entry["error_converged"]
        # series.csv holds 10 significant digits: the means it gives differ from the
        # protocol's by ~1e-10 of A_t
        if not (abs(got[0] - want[0]) <= 1e-6 * abs(want[0]) + 1e-8 * abs(entry["mean"]) and
                abs(got[1] - want[1]) <= 1e-6 * want[1] and got[2] == want[2]):
            problems.append("%s %s: summary_error %r, summary.json %r" % (ws, j.id, got, want))
if problems:
    sys.exit("\n".join(problems))
PY
echo "ok: validation.py paper ($(grep -c '' paper.log) lines)"
echo "paper_scale_tiny: $n sweep files initialise and run at their CI size"
