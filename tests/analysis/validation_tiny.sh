#!/bin/bash
# The validation pipeline at the CI size (docs/validation.md, "CI"): every sweep file in
# protocols/sweeps/ is initialised with --tiny and run, then every figure of
# scripts/validation.py, the plan from the done points and the document. Fails if a sweep file,
# a protocol parameter, an analysis step or the generator breaks.
# Usage: validation_tiny.sh INVASIM REPO WORKDIR
set -euo pipefail
unset PYTHONOPTIMIZE  # the Python heredocs below check with assert
invasim=$1 repo=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cd "$work"
fail() { echo "validation_tiny: FAIL: $*" >&2; exit 1; }

# A point that fails to run fails the test, but only at the end: the done points of every
# sweep file are still analysed, so that one bad point does not hide the analysis' state.
failed_runs=()
for spec in "$repo"/protocols/sweeps/*.lua; do
  name=$(basename "$spec" .lua)
  grep -q "tiny = {" "$spec" || fail "$spec has no tiny = { ... } (the CI size)"
  "$invasim" sweep init "$spec" --tiny --workspace "ws/$name" > "ws_$name.log" \
    || { cat "ws_$name.log"; fail "sweep init --tiny $spec"; }
  if ! "$invasim" sweep run "ws/$name" --jobs 2 --threads 1 >> "ws_$name.log" 2>&1; then
    cat "ws_$name.log"
    grep -h "error:" ws/"$name"/workspace/*/run.log ws/"$name"/prep/run.log 2>/dev/null || true
    grep -q "failed: the shared preparation" "ws_$name.log" && fail "sweep run $name: the preparation"
    failed_runs+=("$name")
    echo "FAILED POINTS: $name (the done points are analysed; the test fails at the end)"
    continue
  fi
  echo "ok: $name ($(ls ws/$name/workspace | wc -l) points)"
done

"$repo/scripts/validation.py" all ws -o figures --invasim "$invasim" | tee figures.log
for fig in fig3 fig4a fig4b fig5 fig6 fig7a fig7b fig8 fig9; do
  [ -s "figures/$fig.json" ] || fail "figure $fig was not made"
done
# One temperature axis: every point's x is the measured kT_c_paper/P of its runs (summary.json
# for Fig. 3's end points; the series window for Fig. 4a's times), passive runs included.
/usr/bin/python3 - "$repo/scripts" ws figures <<'PY' || fail "a figure's temperature is not the measured 2 T_c/P"
import json, math, os, sys
from invasim_analysis import steady, workspace
ws, figs = sys.argv[2], sys.argv[3]
problems = []
jobs = workspace.load(os.path.join(ws, "fig3_passive_slices"))
want = sorted(j.mean("kT_c_paper")[0] / float(j.sp["P"]) for j in jobs)
got = sorted(e[0] for e in json.load(open(os.path.join(figs, "fig3.json")))["numbers"]["end_points"])
if len(got) != len(want) or not want or not all(abs(a - b) <= 1e-9 * abs(b) for a, b in zip(got, want)):
    problems.append("fig3 end points at %r, measured %r" % (got, want))
jobs = workspace.load(os.path.join(ws, "fig4a_passive"))
by_kT = {j.sp["kT"]: j for j in jobs}
points = json.load(open(os.path.join(figs, "fig4a.json")))["numbers"]["points"]
if not points or not all(points.values()):
    problems.append("fig4a has no points at some time: %r" % points)
for f, pts in points.items():
    for p in pts:
        j = by_kT[p["key"][0]]
        m = steady.window_mean(j, "kT_c_paper", float(f)) / float(j.sp["P"])
        if not abs(p["x"] - m) <= 1e-9 * abs(m):
            problems.append("fig4a at t = %s: x = %r, measured %r" % (f, p["x"], m))
if problems:
    sys.exit("\n".join(problems))
PY
# Fig. 5 reads its fourth workspace (fig5_extra_curves: beta = 1e-4) and has the inset's row;
# a workspace left out ('-') is named in the record and on the page.
/usr/bin/python3 - figures/fig5.json <<'PY' || fail "fig5: the extra curves or the inset row are missing"
import json, sys
rec = json.load(open(sys.argv[1]))
if not any(s.endswith("fig5_extra_curves.lua") for s in rec["specs"]) or rec["missing"]:
    sys.exit("specs %r, missing %r" % (rec["specs"], rec["missing"]))
if not any(c["key"][0] == 1e-4 for c in rec["numbers"]["curves"]):
    sys.exit("no beta = 1e-4 curve: %r" % [c["curve"] for c in rec["numbers"]["curves"]])
if "fig5_inset" not in {r["id"] for r in rec["rows"]}:
    sys.exit("no fig5_inset row")
PY
"$repo/scripts/validation.py" figure fig5 ws/fig5_active - ws/fig5_long -o fig5_missing \
  --invasim "$invasim" > fig5_missing.log
/usr/bin/python3 - fig5_missing/fig5.json <<'PY' || fail "fig5: the workspaces not given are not named"
import json, sys
missing = json.load(open(sys.argv[1]))["missing"]
if missing != ["fig5_passive", "fig5_extra_curves"]:
    sys.exit("missing %r" % missing)
PY
# Fig. 5 with longer runs: fig5_long.lua's points run twice as long, given as the third
# workspace: each of its curves replaces the same curve of the first, which is kept for
# comparison but not fitted. Runs of the same length (the workspace given twice) replace none.
# The Python checks below exit non-zero on a failed condition (no assert: python -O drops it).
"$invasim" sweep init "$repo/protocols/sweeps/fig5_long.lua" --tiny --set steps=800 \
  --workspace ws_longer/fig5_long > ws_longer.log && "$invasim" sweep run ws_longer/fig5_long \
  --jobs 2 --threads 1 >> ws_longer.log 2>&1 || { cat ws_longer.log; fail "the longer fig5_long runs"; }
for long in ws_longer/fig5_long ws/fig5_long; do
  out=fig5_long_from_${long%%/*}
  "$repo/scripts/validation.py" figure fig5 ws/fig5_long ws/fig5_passive "$long" -o "$out" \
    --invasim "$invasim" > "$out.log"
done
/usr/bin/python3 - fig5_long_from_ws/fig5.json <<'PY' || fail "fig5: runs of the same length replaced a curve"
import json, sys
if json.load(open(sys.argv[1]))["numbers"]["replaced_by_longer_runs"]:
    sys.exit("the same runs replaced their own curves")
PY
/usr/bin/python3 - fig5_long_from_ws_longer/fig5.json <<'PY' || fail "fig5: the longer runs did not replace the curves"
import json, sys
n = json.load(open(sys.argv[1]))["numbers"]
replaced = {tuple(r["key"]) for r in n["replaced_by_longer_runs"]}
active = [c for c in n["curves"] if c["key"][0] != "passive"]
if not (replaced and replaced == {tuple(c["key"]) for c in active}):
    sys.exit("replaced %r, active curves %r" % (replaced, active))
if not all("(t = " in c["curve"] for c in active):
    sys.exit("curves without their run length: %r" % [c["curve"] for c in active])
if not all("excluded_from_scale_fit" in c for c in n["curves"]):
    sys.exit("curves without excluded_from_scale_fit")
PY
# Fig. 8 scans both boxes of packing.lua (box = pressure, fixed): one figure and one set of
# rows each, the fixed box holding phi_a at its target.
/usr/bin/python3 - figures/fig8.json <<'PY' || fail "fig8: the two boxes were not analysed apart"
import json, sys
rec = json.load(open(sys.argv[1]))
if rec["images"] != ["fig8_An_dphi.png", "fig8_An_dphi_fixed.png"]:
    sys.exit("images %r" % rec["images"])
variants = {r.get("variant") for r in rec["rows"]}
if variants != {"pressure wall at P", "fixed box"}:
    sys.exit("variants %r" % variants)
fixed = rec["numbers"]["fixed"]["points"]
if not (fixed and all(abs(p["phi_a_measured"] - p["phi_a_target"]) < 0.01 for p in fixed)):
    sys.exit("fixed box points %r" % fixed)
PY
# One steady-state criterion: `sweep collect`'s A_t_drift and A_t_drift_error (C++,
# measure/quarter_drift.cpp) and A_t_error (the summary's, measure/mean_error.cpp) are the
# numbers the analysis computes from series.csv (steady.steadiness, Job.mean), on the tiny
# workspaces (2 rows per window: the drifts not judged) and on a synthetic one of 12 runs with
# windows of 40-51 rows (odd ones too) that ramp, wander and drift.
PYTHONPATH="$repo/tests/analysis:${PYTHONPATH:-}" /usr/bin/python3 - synthetic_ws <<'PY'
import sys
import numpy as np
import synthetic
rng, points = np.random.default_rng(3), []
for k in range(12):
    n = 80 + 2 * k + (k % 2) * 2
    a_t = (500 + 0.3 * np.cumsum(rng.normal(0, 1, n)) + rng.normal(0, 2, n)
           + np.linspace(0, 10 * (k % 3), n))
    points.append(({"kT": 1e-4 * (k + 1), "seed": k % 2 + 1}, "done", a_t, 1000.0, 0.1 * (k + 1)))
synthetic.write_workspace(sys.argv[1], points)
PY
for ws in ws/* synthetic_ws; do "$invasim" sweep collect "$ws" -o "$ws/results.csv" > /dev/null; done
/usr/bin/python3 - ws synthetic_ws <<'PY' || fail "sweep collect's drifts or errors differ from the analysis's"
import csv, math, os, sys
from invasim_analysis import steady, workspace
problems, judged = [], {}
workspaces = [os.path.join(sys.argv[1], n) for n in sorted(os.listdir(sys.argv[1]))] + [sys.argv[2]]
for ws in workspaces:
    rows = list(csv.DictReader(open(os.path.join(ws, "results.csv"))))
    if not any(r["status"] == "done" for r in rows):
        continue
    col = {h.split(" [")[0]: h for h in rows[0]}
    jobs = {j.id: j for j in workspace.load(ws)}
    for r in rows:
        if r["status"] != "done" or "A_t" not in col:
            continue
        j = jobs[r["job_id"]]
        s = steady.steadiness(j)
        got = {c: float(r[col[c]]) if r[col[c]] != "" else math.nan
               for c in ("A_t_drift", "A_t_drift_error", "A_t_error")}
        want = {"A_t_error": j.mean("A_t")[1], "A_t_drift_error": s["error"]}
        if s["steady"] is not None:  # judged: 2 rows per quarter at least
            want["A_t_drift"] = s["drift"]
            judged[ws] = judged.get(ws, 0) + 1
        for c, w in want.items():
            scale = 1e-9 * abs(j.mean("A_t")[0])
            if not (abs(got[c] - w) <= scale or (math.isnan(got[c]) and math.isnan(w))):
                problems.append("%s %s %s: collect %r, analysis %r" % (ws, r["job_id"][:8], c,
                                                                       got[c], w))
if problems or judged.get(sys.argv[2], 0) != 12:
    sys.exit("\n".join(problems) + "\njudged: %r" % judged)
print("ok: sweep collect's A_t drift, its error and A_t's error = the analysis's (%d judged)"
      % sum(judged.values()))
PY
"$repo/scripts/validation.py" plan --workspace ws/* --jobs 2 -o plan.json --invasim "$invasim" | tee plan.log
"$repo/scripts/validation.py" document figures --plan plan.json --done plan.json -o validation.md --ci-size

/usr/bin/python3 - "$work" <<'PY' || fail "the generated document or figure records are incomplete"
import json, os, sys
work = sys.argv[1]
doc = open(os.path.join(work, "validation.md")).read()
allowed = {"agrees", "agrees in trend only", "disagrees", "no data", "not testable",
           "paper inconsistent", "not steady"}
problems = []
for fig in ["fig3", "fig4a", "fig4b", "fig5", "fig6", "fig7a", "fig7b", "fig8", "fig9"]:
    rec = json.load(open(os.path.join(work, "figures", fig + ".json")))
    if not rec["rows"]:
        problems.append(fig + ": no rows")
    for r in rec["rows"]:
        if r["verdict"] not in allowed:
            problems.append("%s: verdict %r" % (r["id"], r["verdict"]))
    for img in rec["images"]:
        if not os.path.getsize(os.path.join(work, "figures", img)) > 1000:
            problems.append("%s: image %s is empty" % (fig, img))
    if "Regenerate: `%s`" % rec["command"] not in doc:
        problems.append(fig + ": its command is not under it")
    if "scripts/validation.py figure " + fig not in rec["command"]:
        problems.append(fig + ": command " + rec["command"])
# The plan of the done workspaces (made outside the repository) cites each sweep file inside it.
for e in json.load(open(os.path.join(work, "plan.json"))):
    if not e["spec"].startswith("protocols/sweeps/") or "/" in e["workspace"]:
        problems.append("plan entry %s (%s) names a path outside the repository"
                        % (e["spec"], e["workspace"]))
for text in ["CI size, not the campaign", "## The plan", "### As run", "| **total** |", "## Verdicts",
             "## Where the paper contradicts itself", "L_f"]:
    if text not in doc:
        problems.append("document lacks: " + text)
# The verdict classes: the paper's self-contradictions are "paper inconsistent", the factor-2
# check of our code stands in its own table and is not counted, the counts name every class.
rows = {r["id"]: r for fig in ["fig3", "fig5"]
        for r in json.load(open(os.path.join(work, "figures", fig + ".json")))["rows"]}
for sid in ("L_f", "fig3_At_min_over_max"):
    if rows.get(sid, {}).get("verdict") != "paper inconsistent":
        problems.append("%s: %r" % (sid, rows.get(sid, {}).get("verdict")))
if "Record from older criteria" in doc:
    problems.append("a record just written is taken for an older one (its criteria)")
verdicts = doc[doc.index("## Verdicts"):doc.index("### Checks of our code")]
checks = doc[doc.index("### Checks of our code"):doc.index("## Where the paper")]
if "fig5_factor2" in verdicts or "`fig5_factor2`" not in checks:
    problems.append("fig5_factor2 is not apart from the paper's verdicts")
for v in sorted(allowed):
    if " %s" % v not in verdicts.split("\n")[2]:
        problems.append("the counts line lacks %r: %s" % (v, verdicts.split("\n")[2]))
if problems:
    print("\n".join(problems))
    sys.exit(1)
print("validation_tiny: document and %d figure records complete" % 9)
PY
# Citations: every statement (the paper file and the figure records) cites its place in the
# paper and the paper's own figure numbers, and no text of the page cites a path outside the
# repository (the patterns of scripts/invasim_analysis/validation/citations.py, OUTSIDE). The generator refuses such a page; this checks
# the page it wrote, independently of it.
/usr/bin/python3 - "$repo/scripts" "$work" <<'PY' || fail "a statement or the page cites outside the paper and the repository"
import glob, json, os, sys
from invasim_analysis.validation import citations, verdict
work = sys.argv[2]
count, figures = citations.paper_figures()
statements, problems = list(verdict.paper().values()), []
for path in sorted(glob.glob(os.path.join(work, "figures", "*.json"))):
    rec = json.load(open(path))
    if "rows" in rec:
        statements += rec["rows"]
        if rec["figure"] not in figures:
            problems.append("%s: figure %r is not a figure of the paper's" % (path, rec["figure"]))
problems += citations.statement_problems(statements, count, figures)
problems += citations.page_problems(open(os.path.join(work, "validation.md")).read(), count, figures)
if problems:
    print("\n".join(dict.fromkeys(problems)))
    sys.exit(1)
print("validation_tiny: %d statements and the page cite the paper's figures (1-%d) and the "
      "repository only" % (len(statements), count))
PY
# The pressure sweep's analysis (scripts/pressure_sweep.py) on its tiny workspace, and its
# onsets on state points made up so that the answer is known.
"$repo/scripts/pressure_sweep.py" ws/pressure_fig5 -o pressure > pressure.log ||
  { cat pressure.log; fail "pressure_sweep.py"; }
[ -s pressure/pressure.png ] && grep -q '"points"' pressure/pressure.json || fail "pressure_sweep.py wrote no figure or table"
PYTHONPATH="$repo/scripts" /usr/bin/python3 - <<'PY' || fail "pressure onsets"
import math
from invasim_analysis.pressure import onsets
def pts(P, xs, rs, steady=True):
    return [{"P": P, "x": x, "ratio": r, "steady": steady} for x, r in zip(xs, rs)]
# Two pressures, A_t/A_t^max from 0.3 to 0.9, so half-way is 0.6: crossed log-midway between
# x = 0.1 and 10 (x = 1) at the first, between 1 and 10 (x = 10^0.5) at the second.
points = pts(1e-3, [0.1, 10.0], [0.3, 0.9]) + pts(2e-3, [1.0, 10.0, 100.0], [0.3, 0.9, 0.9])
x, half = onsets(points)
assert abs(half - 0.6) < 1e-12 and abs(x[1e-3] - 1.0) < 1e-12 and abs(x[2e-3] - 10 ** 0.5) < 1e-12, (x, half)
# Not steady: left out, unless provisional.
points[1]["steady"] = False
x, half = onsets(points)
assert math.isnan(x[1e-3]), x
x, half = onsets(points, steady_only=False)
assert abs(x[1e-3] - 1.0) < 1e-12, x
PY
# Workspaces combined: a state point (P, f0) comes from the last workspace that has it.
PYTHONPATH="$repo/scripts" /usr/bin/python3 - <<'PY' || fail "pressure workspaces combined"
from invasim_analysis import workspace
from invasim_analysis.pressure import combined_points, state_points
first, last = "ws/pressure_fig5", "ws/pressure_fig5_steady"
points, _ = combined_points([first, last])
keys_first = {(p["P"], p["f0"]) for p in state_points(first)}
keys_last = {(p["P"], p["f0"]) for p in state_points(last)}
assert len(points) == len(keys_first | keys_last), points
for p in points:
    want = "pressure_fig5_steady" if (p["P"], p["f0"]) in keys_last else "pressure_fig5"
    assert p["from"] == want, p
PY
"$repo/scripts/pressure_sweep.py" ws/pressure_fig5 ws/pressure_fig5_steady -o pressure2 > pressure2.log ||
  { cat pressure2.log; fail "pressure_sweep.py with two workspaces"; }
grep -q "pressure_fig5, pressure_fig5_steady" pressure2/pressure.json || fail "pressure.json names both workspaces"
[ ${#failed_runs[@]} -eq 0 ] || fail "points failed to run in: ${failed_runs[*]} (errors above)"
echo "validation_tiny: PASS"
