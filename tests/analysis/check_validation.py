#!/usr/bin/env python3
"""Unit checks of scripts/invasim_analysis (docs/validation.md, "Method"): the verdict criteria
on hand-picked numbers, the A_n normalisation and the steady-state criterion on hand-made
runs, the plan's cost model and its replay of `sweep run --jobs N`, the citation checks
(paper figure numbers, sources in the paper), the figure command's errors, and the
paper-scale records (paper_scale.py) on synthetic workspaces (tests/analysis/synthetic.py):
steady and drifting runs, disagreeing starts, running and pending runs, the cost, and the
side-by-side rows of the page.
Usage: check_validation.py SCRIPTS_DIR WORKDIR. Without numpy/scipy/matplotlib: skipped (77),
or a failure under INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.py)."""

import json
import math
import os
import shutil
import statistics
import subprocess
import sys

from prerequisites import check, require_scientific_python

require_scientific_python()
import numpy as np  # noqa: E402


scripts, work = sys.argv[1], sys.argv[2]
from invasim_analysis import normalise, steady, workspace  # noqa: E402
from invasim_analysis.validation import plan, points, verdict as v  # noqa: E402

# Verdicts: numbers against the paper's value +- tolerance (+ 2 errors).
check(v.value_verdict(0.60, 0.01, 0.55, 0.1) == v.AGREES)
check(v.value_verdict(0.70, 0.03, 0.55, 0.1) == v.AGREES)           # 0.15 <= 0.1 + 0.06
check(v.value_verdict(0.70, 0.01, 0.55, 0.1) == v.DISAGREES)        # 0.15 > 0.12
check(v.value_verdict(0.70, 0.01, 0.55, 0.1, trend_holds=True) == v.TREND)
check(v.value_verdict(math.nan, 0.01, 0.55, 0.1) == v.NO_DATA)
# Trends: d > 2e agrees, 0 < d <= 2e trend only, -2e <= d <= 0 inconclusive, d < -2e disagrees.
check(v.trend_verdict(0.3, 0.1) == v.AGREES)
check(v.trend_verdict(0.15, 0.1) == v.TREND)
check(v.trend_verdict(-0.01, 0.1) == v.INCONCLUSIVE)
check(v.trend_verdict(-0.19, 0.1) == v.INCONCLUSIVE)
check(v.trend_verdict(-0.21, 0.1) == v.DISAGREES)
check(v.trend_verdict(-0.01, 0.0) == v.DISAGREES)
# A statement over several points: one disagreeing point decides, then an inconclusive one.
check(v.all_of([v.AGREES, v.INCONCLUSIVE, v.TREND]) == v.INCONCLUSIVE)
check(v.all_of([v.INCONCLUSIVE, v.DISAGREES]) == v.DISAGREES)
check(v.all_of([v.AGREES, v.TREND, v.NO_DATA]) == v.TREND)
# Log scale: within a factor 3 of 0.03.
check(v.log_verdict(0.08, 0.0, 0.03, 3.0) == v.AGREES)
check(v.log_verdict(0.2, 0.0, 0.03, 3.0) == v.DISAGREES)
check(v.log_verdict(0.2, 0.0, 0.03, 3.0, trend_holds=True) == v.TREND)
# Ranges: all inside, some, none.
check(v.range_verdict([(1.0, 0.1), (2.4, 0.0)], 0.5, 2.5) == v.AGREES)
check(v.range_verdict([(1.0, 0.1), (3.4, 0.1)], 0.5, 2.5) == v.TREND)
check(v.range_verdict([(13.0, 0.1)], 1.0, 1.2) == v.DISAGREES)
# The factor 2 of "2 errors" on each side of its edge (1.5 or 3 errors would flip one of each).
check(v.value_verdict(0.70, 0.02, 0.55, 0.1) == v.DISAGREES)        # 0.15 > 0.1 + 0.04
check(v.value_verdict(0.70, 0.026, 0.55, 0.1) == v.AGREES)          # 0.15 <= 0.1 + 0.052
check(v.trend_verdict(0.18, 0.1) == v.TREND)                        # 0.18 <= 0.2
check(v.trend_verdict(0.21, 0.1) == v.AGREES)
check(v.log_verdict(0.1, 0.004, 0.03, 3.0) == v.DISAGREES)          # 0.523 > 0.477 + 0.035
check(v.log_verdict(0.1, 0.006, 0.03, 3.0) == v.AGREES)             # 0.523 <= 0.477 + 0.052
check(v.range_verdict([(1.05, 0.02)], 0.0, 1.0) == v.DISAGREES)     # 1.05 > 1 + 0.04
check(v.range_verdict([(1.03, 0.02)], 0.0, 1.0) == v.AGREES)
# The glass temperature from tau_r (validation/relaxation.py): exact fits, then the verdict.
from invasim_analysis.validation import relaxation  # noqa: E402
xs = np.array([0.05, 0.07, 0.1, 0.14, 0.2])
a_fit, e_fit, cov_fit = relaxation.arrhenius_fit(xs, np.exp(2.0 + 0.6 / xs))
check(abs(a_fit - 2.0) < 1e-9 and abs(e_fit - 0.6) < 1e-9, (a_fit, e_fit))
tg_x, _ = relaxation.x_where(math.exp(2.0 + 0.6 / 0.04), a_fit, e_fit, cov_fit)
check(abs(tg_x - 0.04) < 1e-9, tg_x)                         # tau_r = 5e5-like target at 0.04
x0_fit = relaxation.vft_fit(xs, np.exp(1.0 + 0.5 / (xs - 0.03)))[0]
check(abs(x0_fit - 0.03) < 1e-6, x0_fit)                      # the VFT divergence recovered


class _Relax:  # a relaxation run as relaxation_points reads one
    def __init__(self, kt, tau, window):
        self.sp, self.id, self._v = {"kT": kt}, "r%g" % kt, {"tau_r": tau, "correlation_window": window}

    def scalar(self, name):
        return self._v[name]


short = [_Relax(k, t, 1e4) for k, t in [(1, math.nan), (2, 5e3), (3, 900.0), (4, 300.0)]]
long_ = [_Relax(1, 3e4, 5e4)]  # the longer window reaches tau_r where the short one did not
pts = relaxation.relaxation_points([short, long_], lambda j: 0.025 * j.sp["kT"])
check([p["tau_r"] for p in pts] == [3e4, 5e3, 900.0, 300.0], pts)
st_tg = {"value": 0.03, "log_factor": 3.0}
exact = [{"x": x, "tau_r": math.exp(2.0 + 0.6 / x), "window": 1e5} for x in xs]
row_tg = relaxation.tg_row(exact, st_tg, run_length=math.exp(2.0 + 0.6 / 0.04))
check(row_tg["verdict"] == v.AGREES and abs(row_tg["data"]["arrhenius"]["T_g"] - 0.04) < 1e-9,
      row_tg)
row_tg = relaxation.tg_row(exact, st_tg, run_length=math.exp(2.0 + 0.6 / 0.5))
check(row_tg["verdict"] == v.DISAGREES, row_tg)              # T_g 0.5: beyond a factor 3
check(relaxation.tg_row(exact[:2], st_tg)["verdict"] == v.NO_DATA)  # too few reached

# Every statement the figures use is in the paper file, with a source in the paper.
ids = v.paper()
for needed in ["fig3_invasion_grows", "fig4a_Tg", "fig4b_An_at_0.3", "fig5_b_range", "fig5_c1",
               "fig5_Tc_over_Ta", "fig5_factor2", "fig6_free_formula", "fig7a_onset",
               "fig8_dphi_1", "fig9_tissue", "L_f"]:
    check(needed in ids and ids[needed]["source"], needed)

# Citations (invasim_analysis/validation/citations.py): the paper's figure numbers, sources in the paper.
from invasim_analysis.validation import citations, document  # noqa: E402
count, figures = citations.paper_figures()
check(count == 11 and figures == {"fig3", "fig4a", "fig4b", "fig5", "fig6", "fig7a", "fig7b",
                                  "fig8", "fig9"}, (count, figures))
check(citations.statement_problems(list(ids.values()), count, figures) == [],
      citations.statement_problems(list(ids.values()), count, figures))
good = {"id": "fig5_x", "figure": "fig5", "text": "t", "source": "Results; Fig. 5(a)"}
check(citations.statement_problems([good], count, figures) == [])
planted = [  # (statement with a bad source or id, a word of the problem it must raise)
    (dict(good, source="MODEL.md, figure table, Fig. 5"), "'MODEL.md', outside the repository"),
    (dict(good, source="../shared/notes, Fig. 5"), "'../', outside the repository"),
    (dict(good, source="/work/paper.txt, Fig. 5"), "'/work/', outside the repository"),
    (dict(good, source="the figure table"), "names no place in the paper"),
    (dict(good, id="fig10_x", figure="fig10"), "id names fig10, not a figure of the paper's"),
    (dict(good, id="fig11_x", figure="fig11"), "figure 'fig11' is not a figure of the paper's"),
    (dict(good, id="fig6_x"), "id names fig6 but its figure is fig5"),
    (dict(good, text="as in Fig. 12"), "'Fig. 12' (the paper has Figs. 1-11)"),
]
for bad, word in planted:
    got = citations.statement_problems([bad], count, figures)
    check(len(got) >= 1 and any(word in p for p in got), (bad, got))
check(citations.page_problems("## Fig. 4a: x\nsee Fig. 3 and Eq. (14)", count, figures) == [])
got = citations.page_problems("x\n## Fig. 10: packing\nfrom ../shared/MODEL.md", count, figures)
check(any("page line 2: section 'Fig. 10'" in p for p in got)
      and any("page line 3 cites '../'" in p for p in got), got)
# The generator refuses such a page and writes nothing.
shutil.rmtree(work, ignore_errors=True)
os.makedirs(os.path.join(work, "records"))
row = dict(good, paper="t", ours="1", verdict=v.AGREES, why="w", id="fig3_x", figure="fig3")
with open(os.path.join(work, "records", "fig3.json"), "w") as f:
    json.dump({"rows": [dict(row, source="MODEL.md, Fig. 3")], "specs": ["s"], "runs": 1,
               "steps_range": "1", "images": [], "command": "c"}, f)
page = os.path.join(work, "page.md")
try:
    document.render(os.path.join(work, "records"), None, page)
    check(False, "a page citing a file outside the repository was written")
except workspace.InputError as e:
    check("not written: 1 citation problem" in str(e) and "statement fig3_x: source" in str(e), e)
check(not os.path.exists(page))
with open(os.path.join(work, "records", "fig3.json"), "w") as f:
    json.dump({"rows": [row], "specs": ["s"], "runs": 1, "steps_range": "1", "images": [],
               "command": "c"}, f)
document.render(os.path.join(work, "records"), None, page)
check(os.path.exists(page))

# The midpoint a of a sigmoid enters the fit of a = c1 (1 + c2 beta/P) tau_g/tau_d only for a
# rising curve (b > 0 and the data rising by more than 2 errors) whose midpoint the
# temperatures bracket (a factor 2 either side).
from invasim_analysis.master_curve import fits  # noqa: E402
xs, up, flat, e = [0.01, 0.1, 1.0], [0.1, 0.5, 0.9], [0.1, 0.12, 0.09], [0.02, 0.02, 0.02]
check(fits.midpoint_not_located(0.1, 0.01, 1.2, 0.1, xs, up, e) is None)
check(fits.midpoint_not_located(0.1, 0.05, 2.2, 1.2, xs, up, e) is None)          # b uncertain
check(fits.midpoint_not_located(1.9, 0.5, 1.2, 0.1, xs, up, e) is None)           # <= 2 x_max
check("rising" in fits.midpoint_not_located(0.1, 0.01, -0.8, 0.02, xs, up[::-1], e))  # falls
check("rising" in fits.midpoint_not_located(0.0, 0.0, -2.6e-6, 0.08, xs, flat, e))    # b ~ 0
check("rise" in fits.midpoint_not_located(2.8e10, 1.9e11, 0.086, 0.022, xs, flat, e))  # flat data
check("outside" in fits.midpoint_not_located(5.0, 1.0, 1.0, 0.1, xs, up, e))       # > 2 x_max
check("outside" in fits.midpoint_not_located(0.004, 0.001, 1.0, 0.1, xs, up, e))   # < x_min / 2
check("finite" in fits.midpoint_not_located(math.inf, math.inf, 1e-5, 0.4, xs, up, e))

# Normalisation by hand: A_t_max 1000, 1100; A_t 200, 500, 800.
pts = [{"A_t": 200.0, "A_t_max": 1000.0, "A_t_error": 10.0},
       {"A_t": 500.0, "A_t_max": 1100.0, "A_t_error": 10.0},
       {"A_t": 800.0, "A_t_max": 1000.0, "A_t_error": 10.0}]
ext = normalise.normalise(pts)
r = [1 - (1000 - 200) / 1000, 1 - (1100 - 500) / 1000, 1 - (1000 - 800) / 1000]  # .2 .4 .8
check(ext["min_A_t_max"] == 1000.0)
for p, want in zip(pts, [(x - 0.2) / 0.6 for x in r]):
    check(abs(p["A_n"] - want) < 1e-12, (p, want))
    check(abs(p["A_n_error"] - 10.0 / 1000 / 0.6) < 1e-12)
# The run's own error adds the independent errors of A_t and A_t^max in quadrature (3 and 4
# make 5), over min A_t^max and the span of rA_t.
check(abs(normalise.run_error(3.0, 4.0, 1000.0, 0.2, 0.8) - 5.0 / 1000 / 0.6) < 1e-12)
other = normalise.scale_like({"A_t": 650.0, "A_t_max": 1000.0, "A_t_error": 0.0}, ext)
check(abs(other["A_n"] - (0.65 - 0.2) / 0.6) < 1e-12)
check(abs(points.crossing([0.01, 0.1, 1.0], [0.0, 0.25, 0.75]) - 10 ** -0.5) < 1e-12)
# its error in log10: the larger bracketing error over the slope (0.5 per decade)
check(abs(points.crossing_log_error([0.01, 0.1, 1.0], [0.0, 0.25, 0.75], [0.1, 0.02, 0.05])
           - 0.05 / 0.5) < 1e-12)

# Steadiness on a hand-made run: 40 rows, the last half flat (steady) or rising (not).
def fake_job(path, last_half, error, a_t_max=None):
    os.makedirs(path, exist_ok=True)
    y = [500.0] * 20 + list(last_half)
    with open(os.path.join(path, "series.csv"), "w") as f:
        f.write("step,time [tau],A_t [sigma^2]\n")
        f.writelines("%d,%d,%r\n" % (i, i, a) for i, a in enumerate(y))
    json.dump({"a": 1}, open(os.path.join(path, "signac_statepoint.json"), "w"))
    json.dump({"status": "done"}, open(os.path.join(path, "signac_job_document.json"), "w"))
    averages = {"A_t": {"mean": float(np.mean(last_half)), "error": error}}
    if a_t_max is not None:
        averages["A_t_max"] = {"mean": a_t_max, "error": 0.1}
    json.dump({"averages": averages}, open(os.path.join(path, "summary.json"), "w"))
    return workspace.Job(path)

shutil.rmtree(work, ignore_errors=True)
flat = fake_job(os.path.join(work, "flat"), [600.0 + (1 if i % 2 else -1) for i in range(20)], 1.0)
rising = fake_job(os.path.join(work, "rising"), [600.0 + 2 * i for i in range(20)], 1.0)
s = steady.steadiness(flat)
check(s["steady"] is True and abs(s["drift"]) < 1e-12, s)
s = steady.steadiness(rising)
check(s["steady"] is False and abs(s["drift"] - 20.0) < 1e-12, s)   # 10 rows x 2 apart
# The quarters' errors come from their fluctuations about the window's drift (each quarter's
# own mean and one common slope, steady.drift_residuals): a straight rise is all drift and no
# fluctuation, errors zero up to rounding, and its drift/error beyond any bound.
check(s["e3"] < 1e-9 and s["e4"] < 1e-9 and s["error"] < 1e-9, s)
# The criterion's factor: quarters of 10 alternating values (tau_int 1/2: an anticorrelation
# is not credited; the fit's slope 2/33 leaves 20 - 20/33 as the sum of squares over 20 - 3
# degrees of freedom, so each quarter's error is sqrt(640/33/17/10), combined sqrt(2) x that;
# a step between the quarters leaves their fluctuations, hence the error, unchanged) whose
# means differ by 1.9 combined errors are steady, by 2.1 not.
e_alt = math.sqrt(2 * 640 / 33 / 17 / 10)
s = steady.steadiness(flat)
check(s["tau_int"] == 0.5 and abs(s["error"] - e_alt) < 1e-9, s)
for ratio, want in ((1.9, True), (2.1, False)):
    step = fake_job(os.path.join(work, "step_%g" % ratio),
                    [600.0 + (1 if i % 2 else -1) + (ratio * e_alt if i >= 10 else 0.0)
                     for i in range(20)], 1.0)
    s = steady.steadiness(step)
    check(s["steady"] is want and abs(s["drift"] / s["error"] - ratio) < 1e-9, (ratio, s))
summary = steady.steadiness_summary([flat, rising])
s = steady.steadiness(rising)
check(summary["steady"] == 1 and summary["jobs"] == 2
      and summary["max_drift_over_error"] == s["drift"] / s["error"] > 1e9, summary)
# A value at an earlier time is the mean over the averaging window ending there: at the end,
# the last half of the rows; at half the run (20 rows), rows 10-19 of the flat start.
check(abs(steady.window_mean(rising, "A_t", 1.0) - np.mean([600.0 + 2 * i for i in range(20)])) < 1e-12)
check(steady.window_mean(rising, "A_t", 0.5) == 500.0)
# The summary's error is that of src/measure/mean_error.cpp (tests/unit/test_mean_error.cpp
# works the same two by hand): 1..8, the cap W = 2 reached before Sokal's criterion, C_F =
# 2 tau_int(2) Gamma(0)/(1 - 5/8); alternating values, anticorrelated, the plain error.
c_f = 2 * (0.5 + 0.625 + 1.4375 / 5.25) * 5.25 / (1 - 5 / 8)
err, tau, resolved = steady.summary_error(list(range(1, 9)))
check(abs(err - math.sqrt(c_f / 8)) < 1e-12 and abs(tau - c_f / (2 * (5.25 + c_f / 8))) < 1e-12
      and resolved is False)
alt = [1.0 if i % 2 else -1.0 for i in range(40)]
err, tau, resolved = steady.summary_error(alt)
check(abs(err - math.sqrt(40 / 39 / 40)) < 1e-12 and tau == 0.5 and resolved is True)
# A summary written before the errors came from tau_int (no tau_int in its entry, `samples`
# given) has its error computed anew from series.csv; one with tau_int keeps its own.
old_summary = fake_job(os.path.join(work, "old_summary"), list(range(1, 9)), 99.0)
old_summary.summary["averages"]["A_t"]["samples"] = 8
check(abs(old_summary.mean("A_t")[1] - math.sqrt(c_f / 8)) < 1e-12, old_summary.mean("A_t"))
new_summary = fake_job(os.path.join(work, "new_summary"), list(range(1, 9)), 99.0)
new_summary.summary["averages"]["A_t"].update(samples=8, tau_int=1.93)
check(new_summary.mean("A_t")[1] == 99.0, new_summary.mean("A_t"))
# A drift of 20 error bars that is below 1 % of A_t^max (a caged tissue ageing) is negligible:
# steady; the same rise against a smaller A_t^max (20 > 1 % of 1500) is not.
creeping = fake_job(os.path.join(work, "creeping"), [600.0 + 0.2 * i for i in range(20)], 0.1, 2500.0)
s = steady.steadiness(creeping)
check(s["steady"] is True and abs(s["drift"] - 2.0) < 1e-9 and s["negligible"] == 25.0, s)
rising_big = fake_job(os.path.join(work, "rising_big"), [600.0 + 2 * i for i in range(20)], 1.0, 1500.0)
s = steady.steadiness(rising_big)
check(s["steady"] is False and s["negligible"] == 15.0, s)

# The plan: sweep run's order on N slots after the preparation.
check(plan.wall_time(5.0, [10, 10, 10], 2) == 25.0)
check(plan.wall_time(5.0, [10, 1, 1, 1], 2) == 15.0)
check(plan.wall_time(5.0, [], 2) == 5.0)
# A sweep file inside the repository is shown relative to it, whatever the plan's directory.
os.chdir(work)
from invasim_analysis import repo_paths  # noqa: E402
check(repo_paths.repo_path(os.path.join(repo_paths.REPO, "protocols", "sweeps", "x.lua"))
      == os.path.join("protocols", "sweeps", "x.lua"))
check(repo_paths.repo_path("/elsewhere/x.lua") == "/elsewhere/x.lua")
check(repo_paths.repo_path("/elsewhere/x.lua", "DIR") == "DIR")
check(repo_paths.repo_path("protocols/sweeps/recorded.lua") == "protocols/sweeps/recorded.lua")
check(plan.point_steps({"quench_steps": 10, "steps": 100}, {"quench_steps": 5, "steps": 1,
                                                             "equilibrate_steps": 7}, "x") == 117)
try:
    plan.point_steps({"steps": -1}, {"steps": 1}, "x.lua")
    raise AssertionError("steps = -1 accepted")
except workspace.InputError as e:
    check("x.lua: steps = -1 (automatic)" in str(e), e)

# The verdict classes (verdict.py): where the paper contradicts itself, a number's verdict
# becomes "paper inconsistent" (also for a record written before the class existed); a row
# resting on a state point that is not steady is "not steady"; the factor-2 check is a check
# of our code, not a statement of the paper's.
for sid in ("fig3_At_min_over_max", "L_f"):
    for given in (v.AGREES, v.DISAGREES):
        r = v.row(sid, "x", given, "w")
        check(r["verdict"] == v.PAPER_INCONSISTENT and given in r["why"], r)
    check(v.row(sid, "x", v.NO_DATA, "w")["verdict"] == v.NO_DATA)
check(v.row("fig4b_An_at_0.3", "x", v.AGREES, "w")["verdict"] == v.AGREES)
r = v.row("fig4b_An_at_0.3", "x", v.AGREES, "w", unsteady=["f0 = 0.1"])
check(r["verdict"] == v.NOT_STEADY and "not steady: f0 = 0.1" in r["why"], r)
check(v.is_code_check("fig5_factor2") and not v.is_code_check("fig5_c1"))
check(v.all_of([v.AGREES, v.AGREES, v.NO_DATA]) == v.AGREES)
check(v.all_of([v.AGREES, v.TREND]) == v.TREND and v.all_of([v.AGREES, v.DISAGREES]) == v.DISAGREES)
check(v.fmt_temperature(0.3) == "2T_c/P = 0.3 (T_c/P = 0.15)", v.fmt_temperature(0.3))
for needed in ["fig4a_Tc_equals_Ta", "fig5_Tc_equals_Ta", "fig5_inset", "fig7b_plateau_falls",
               "fig7b_onset", "fig8_dphi_grows"]:
    check(needed in ids and ids[needed]["source"], needed)

# The page: the counts name every class, the code check has its own table and is not
# counted, an old record's "disagrees" on L_f reads "paper inconsistent", a missing record
# and a missing workspace are named.
shutil.rmtree(work, ignore_errors=True)
os.makedirs(os.path.join(work, "records"))
def rec_row(sid, verdict_):
    s_ = ids[sid]
    return {"id": sid, "figure": s_["figure"], "paper": s_["text"], "source": s_["source"],
            "ours": "o", "verdict": verdict_, "why": "w", "data": {}}
with open(os.path.join(work, "records", "fig3.json"), "w") as f:
    json.dump({"rows": [rec_row("L_f", v.DISAGREES), rec_row("fig3_invasion_grows", v.AGREES)],
               "specs": ["s"], "runs": 1, "steps_range": "1", "images": [], "command": "c"}, f)
with open(os.path.join(work, "records", "fig5.json"), "w") as f:
    json.dump({"rows": [rec_row("fig5_factor2", v.AGREES),
                        dict(rec_row("fig5_b_range", v.NOT_STEADY), variant="beta = 0.001, tau_p = 2500")],
               "specs": ["s"], "runs": 1, "steps_range": "1", "images": [], "command": "c",
               "missing": ["fig5_extra_curves"]}, f)
counts = document.render(os.path.join(work, "records"), None, page)
text = open(page).read()
verdicts_part = text[text.index("## Verdicts"):text.index("### Checks of our code")]
checks_part = text[text.index("### Checks of our code"):text.index("## Where the paper")]
check(counts == {v.AGREES: 1, v.TREND: 0, v.INCONCLUSIVE: 0, v.DISAGREES: 0,
                 v.PAPER_INCONSISTENT: 1, v.NOT_STEADY: 1, v.NO_DATA: 0, v.UNTESTABLE: 0}, counts)
check("1 agrees, 0 agrees in trend only, 0 inconclusive, 0 disagrees, 1 paper inconsistent, "
      "1 not steady, 0 no data, 0 not testable" in verdicts_part, verdicts_part)
check("| fig3 | `L_f` | paper inconsistent |" in verdicts_part, verdicts_part)
check("fig5_factor2" not in verdicts_part and "| fig5 | `fig5_factor2` |" in checks_part, checks_part)
check("Not generated: no record `fig7b.json`" in text and "`out/fig7b_tethered`" in text)
check("Workspace not given for this record: `fig5_extra_curves`" in text)
check(text.count("**Record from older criteria.**") == 2, text)  # neither record has "criteria"

# Fig. 7's onset: where A_n first rises above its lowest-temperature value by more than 2
# combined errors (here 0.0566, crossed between 0.1 and 1), not the A_n = 0.25 crossing.
from invasim_analysis.validation import figures_other, figures_tethered, figures_tissue  # noqa: E402
got = figures_tethered.onset([0.01, 0.1, 1.0], [0.0, 0.05, 0.8], [0.02, 0.02, 0.02])
want = 10 ** (-1 + (2 * math.hypot(0.02, 0.02) - 0.05) / 0.75)
check(abs(got - want) < 1e-9, (got, want))
check(math.isnan(figures_tethered.onset([0.01, 0.1], [0.0, 0.01], [0.02, 0.02])))

# Fig. 6 holds for all phi_c: at phi_c = 0.5 the smallest tau_p gives tau_d/tau_d_free = 0.7,
# so "tau_d -> tau_g as tau_p -> 0" disagrees although phi_c = 0 agrees.
def p6(phi, tp, td, free):
    return {"phi_c": phi, "tau_p": tp, "tau_d": td, "tau_d_free": free, "windows": 50.0}
table6 = [p6(0.0, 0.02, 5.0, 5.0), p6(0.0, 2500.0, 2500.0, 2500.0),
          p6(0.5, 0.02, 3.5, 5.0), p6(0.5, 2500.0, 60.0, 2500.0)]
rows6 = {r["id"]: r for r in figures_other._fig6_rows(table6, lambda r: 0.1)}
check(rows6["fig6_small_tau_p"]["verdict"] == v.DISAGREES, rows6["fig6_small_tau_p"])
check(rows6["fig6_free_formula"]["verdict"] == v.DISAGREES, rows6["fig6_free_formula"])
check(rows6["fig6_dense_deviates"]["verdict"] == v.AGREES, rows6["fig6_dense_deviates"])

# Fig. 4b's A_n at 0.3 rests on the two end-of-run state points bracketing 2T_c/P = 0.3:
# one of them drifting makes the row "not steady"; all flat, it gets a number's verdict. The
# temperature is the measured kT_c_paper/P.
def tissue_job(path, f0, x, a_t, rising, sp=None, ys=None):
    os.makedirs(path, exist_ok=True)
    P = 1.3e-3
    ys = ys or [a_t + ((2.0 * i) if rising else (1 if i % 2 else -1)) for i in range(40)]
    with open(os.path.join(path, "series.csv"), "w") as f:
        f.write("step,time [tau],A_t [sigma^2],A_t_max [sigma^2],kT_c_paper [eps_c]\n")
        f.writelines("%d,%d,%r,1000.0,%r\n" % (i, i, y, x * P) for i, y in enumerate(ys))
    json.dump(dict({"f0": f0, "P": P, "steps": 40}, **(sp or {})), open(os.path.join(path, "signac_statepoint.json"), "w"))
    json.dump({"status": "done"}, open(os.path.join(path, "signac_job_document.json"), "w"))
    json.dump({"averages": {"A_t": {"mean": float(np.mean(ys[20:])), "error": 1.0},
                            "A_t_max": {"mean": 1000.0, "error": 1.0},
                            "kT_c_paper": {"mean": x * P, "error": 0.0}}},
              open(os.path.join(path, "summary.json"), "w"))
    return workspace.Job(path)

for drifting, want in ((True, {v.NOT_STEADY}), (False, {v.AGREES, v.DISAGREES})):
    shutil.rmtree(work, ignore_errors=True)
    jobs4 = [tissue_job(os.path.join(work, "j%d" % k), f0, x, a, drifting and k == 1)
             for k, (f0, x, a) in enumerate([(0.001, 0.1, 200.0), (0.002, 0.25, 500.0),
                                              (0.004, 0.4, 620.0)])]
    rec4 = figures_tissue.fig4b(jobs4, work, None)
    r03 = [r for r in rec4["rows"] if r["id"] == "fig4b_An_at_0.3"][0]
    check(r03["verdict"] in want and ("f0 = 0.002" in r03["why"]) == drifting, r03)
    xs4 = sorted(p["x"] for p in rec4["numbers"]["points"][1.0])
    check(len(xs4) == 3 and all(abs(a - b) < 1e-12 for a, b in zip(xs4, [0.1, 0.25, 0.4])), xs4)

# Curves at production times (the paper-scale Fig. 4a): a run that has not reached a time has
# no value there (its latest window is an earlier time), and a state point none of whose runs
# has reached it has no point; a finished run has one at every time it covers.
shutil.rmtree(work, ignore_errors=True)
done_job = tissue_job(os.path.join(work, "t_done"), 0.001, 0.1, 200.0, False, {"dt": 1.0})
run_job = tissue_job(os.path.join(work, "t_running"), 0.002, 0.25, 500.0, False, {"dt": 1.0})
with open(os.path.join(run_job.path, "series.csv")) as f:
    lines = f.readlines()
with open(os.path.join(run_job.path, "series.csv"), "w") as f:
    f.writelines(lines[:21])  # production times 0 .. 19 of 39
json.dump({"status": "running"}, open(os.path.join(run_job.path, "signac_job_document.json"), "w"))
run_job = workspace.Job(run_job.path)
check(figures_tissue.production_fraction(run_job, 30.0) is None)
check(figures_tissue.production_fraction(done_job, 30.0) is not None)
table_t, _ = figures_tissue.an_over_time([done_job, run_job], ["f0"], figures_tissue.x_measured,
                                         (10.0, 30.0), figures_tissue.production_fraction)
check(sorted(p["key"][0] for p in table_t[10.0]) == [0.001, 0.002], table_t[10.0])
check([p["key"][0] for p in table_t[30.0]] == [0.001], table_t[30.0])

# Fig. 4a's midpoint moving left when the first curve is below 1/2 everywhere (as at the
# paper's scale at t = 1e4): its midpoint lies above the hottest point, 2T_c/P = 1, and the
# move is at least log10(1 / the end's midpoint). Rows 0-19 at the first level, 20-39 at the
# second: A_n = 0, 0.025, 0.25 in the first quarter, 0, 0.75, 1 at the end.
check(points.crossing_bound([0.1, 0.3, 1.0], [0.0, 0.025, 0.25], [0.01] * 3) == ("above", 1.0))
check(points.crossing_bound([0.1, 0.3], [0.6, 0.9], [0.01] * 2) == ("below", 0.1))
check(points.crossing_bound([0.1, 0.3], [0.0, 0.49], [0.01] * 2)[0] is None)  # too close to say
check(points.crossing_bound([0.1, 0.3], [0.0, 0.9], [0.01] * 2)[0] is None)  # it crosses
shutil.rmtree(work, ignore_errors=True)
def two_levels(a1, a2):
    return [(a1 if i < 20 else a2) + (1 if i % 2 else -1) for i in range(40)]
jobs4a = [tissue_job(os.path.join(work, "a%d" % k), 0.0, x, 0.0, False, {"kT": x * 6.5e-4},
                     two_levels(a1, a2))
          for k, (x, a1, a2) in enumerate([(0.1, 100.0, 100.0), (0.3, 120.0, 700.0),
                                           (1.0, 300.0, 900.0)])]
rows4a = {r["id"]: r for r in figures_tissue.fig4a(jobs4a, work, None)["rows"]}
check(rows4a["fig4a_moves_left"]["verdict"] == v.AGREES, rows4a["fig4a_moves_left"])
check("above 1 (A_n < 1/2 at every temperature run) (t = 25%)" in rows4a["fig4a_moves_left"]["ours"]
      and "at least" in rows4a["fig4a_moves_left"]["why"], rows4a["fig4a_moves_left"])

# Fig. 8: lambda compared at the same phi_a. lambda = 1 has a higher A_n than lambda = 0 at
# both shared phi_a, but an extra dense point at A_n = 0 lowers its scan mean: pointwise, the
# statement disagrees. Delta phi_a rising 0.1 -> 0.2 -> 0.25 (errors 0.01) agrees. Each row
# rests on the state points it names: with the lambda = 1, phi_a = 0.5 point drifting, both
# become "not steady" (it is compared pointwise and holds lambda = 1's largest Delta phi_a).
def p8(lam, phi, an, dphi):
    return {"lambda": lam, "phi_a_target": phi, "phi_a_measured": phi, "A_n": an,
            "A_n_error": 0.01, "dphi": dphi, "dphi_error": 0.01, "A_t": 1.0, "A_t_max": 2.0,
            "P_right": 1.0, "P": 1.0, "T_c": 1.0}
for drifting in (False, True):
    shutil.rmtree(work, ignore_errors=True)
    pts8 = [p8(0.0, 0.5, 0.6, 0.1), p8(0.0, 0.6, 0.4, 0.05), p8(0.3, 0.5, 0.7, 0.2),
            p8(1.0, 0.5, 0.7, 0.25), p8(1.0, 0.6, 0.5, 0.1), p8(1.0, 0.9, 0.0, 0.1)]
    jobs8 = {}
    for k, p in enumerate(pts8):
        j = tissue_job(os.path.join(work, "f8_%d" % k), 0.001, 0.3, 500.0, drifting and k == 3)
        p["jobs"] = [j.id]
        jobs8[j.id] = j
    by8 = {lam: [p for p in pts8 if p["lambda"] == lam] for lam in (0.0, 0.3, 1.0)}
    rows8 = {r["id"]: r for r in figures_other._fig8_rows(pts8, by8, "fixed", None, jobs8)}
    if drifting:
        for sid in ("fig8_lambda_lowers", "fig8_dphi_grows"):
            check(rows8[sid]["verdict"] == v.NOT_STEADY
                  and "not steady: lambda = 1, phi_a = 0.5" in rows8[sid]["why"], rows8[sid])
    else:
        check(rows8["fig8_lambda_lowers"]["verdict"] == v.DISAGREES, rows8["fig8_lambda_lowers"])
        check(rows8["fig8_dphi_grows"]["verdict"] == v.AGREES, rows8["fig8_dphi_grows"])

# Fig. 7's rows use that onset: with K_ecm = 0.1 rising later but from the same point, the
# onsets agree (the A_n = 0.25 crossings would differ by a factor 2.5).
shutil.rmtree(work, ignore_errors=True)
jobs7 = [tissue_job(os.path.join(work, "k%dp%d" % (i, n)), 0.001 * (n + 1), x, a, False,
                    {"K_ecm": k}) for i, (k, ats) in enumerate([(0.0, (100.0, 150.0, 900.0)),
                                                                (0.1, (100.0, 150.0, 400.0))])
         for n, (x, a) in enumerate(zip((0.01, 0.1, 1.0), ats))]
rec7 = figures_tethered.fig7b(jobs7, work, None)
r7 = [r for r in rec7["rows"] if r["id"] == "fig7b_onset"][0]
check(r7["verdict"] == v.AGREES, r7)
check(os.path.exists(os.path.join(work, "fig7b_An.png")))
# ... and rest on their state points: a drifting K_ecm = 0.1 top point makes the plateau row
# "not steady"; the onset row (onsets near 0.011: it rests on the points up to the one that
# crosses, 0.01 and 0.1) keeps its verdict.
shutil.rmtree(work, ignore_errors=True)
jobs7 = [tissue_job(os.path.join(work, "k%dp%d" % (i, n)), 0.001 * (n + 1), x, a,
                    k == 0.1 and n == 2, {"K_ecm": k})
         for i, (k, ats) in enumerate([(0.0, (100.0, 150.0, 900.0)), (0.1, (100.0, 150.0, 400.0))])
         for n, (x, a) in enumerate(zip((0.01, 0.1, 1.0), ats))]
rec7 = figures_tethered.fig7b(jobs7, work, None)
r7 = {r["id"]: r for r in rec7["rows"]}
check(r7["fig7b_plateau_falls"]["verdict"] == v.NOT_STEADY
      and "not steady: K_ecm = 0.1, 2T_c/P = 1" in r7["fig7b_plateau_falls"]["why"], r7)
check(r7["fig7b_onset"]["verdict"] == v.AGREES, r7["fig7b_onset"])

# Fig. 5: a curve with a drifting state point gets "not steady" for its b and is left out of
# the collapse and the fit of a; the other curve keeps a number's verdict.
from invasim_analysis.validation import figures_master  # noqa: E402
shutil.rmtree(work, ignore_errors=True)
jobs5 = []
for c, (beta, tau_p) in enumerate([(1e-3, 25.0), (1e-3, 2500.0)]):
    for k, (x, a) in enumerate([(0.03, 150.0), (0.1, 300.0), (0.3, 600.0), (1.0, 760.0)]):
        jobs5.append(tissue_job(os.path.join(work, "c%dp%d" % (c, k)), 0.001 * (k + 1), x, a,
                                c == 1 and k == 2, {"beta": beta, "tau_p": tau_p}))
rec5 = figures_master.fig5(jobs5, work, None)
b_rows = {r["variant"]: r for r in rec5["rows"] if r["id"] == "fig5_b_range"}
check(b_rows["beta = 0.001, tau_p = 2500"]["verdict"] == v.NOT_STEADY, b_rows)
check(b_rows["beta = 0.001, tau_p = 25"]["verdict"] != v.NOT_STEADY, b_rows)
curves5 = {c["curve"]: c for c in rec5["numbers"]["curves"]}
check(not curves5["beta = 0.001, tau_p = 2500"]["in_collapse"]
      and "not steady" in curves5["beta = 0.001, tau_p = 2500"]["excluded_from_scale_fit"], curves5)
check(os.path.getsize(os.path.join(work, "fig5_An.png")) > 1000)

# fig5_long's curves replace those of the same beta and tau_p only when they ran longer: a
# main sweep file with longer runs (fig5_active.lua: 4e6 steps, fig5_long.lua: 1e6) keeps its own.
for long_steps, want_replaced in ((10, False), (80, True)):
    shutil.rmtree(work, ignore_errors=True)
    main5 = [tissue_job(os.path.join(work, "m%d" % k), 0.001 * (k + 1), x, a, False,
                        {"beta": 1e-3, "tau_p": 2500.0})
             for k, (x, a) in enumerate([(0.03, 150.0), (0.1, 300.0), (0.3, 600.0), (1.0, 760.0)])]
    long5 = [tissue_job(os.path.join(work, "l%d" % k), 0.001 * (k + 1), x, a, False,
                        {"beta": 1e-3, "tau_p": 2500.0, "steps": long_steps})
             for k, (x, a) in enumerate([(0.03, 100.0), (0.1, 200.0), (0.3, 500.0), (1.0, 700.0)])]
    curves, replaced = figures_master._curves(main5, None, long5, None)
    kept = sorted(p["A_t"] for p in curves[(1e-3, 2500.0)])
    # the top point's A_t: 760 from main5's runs (40 steps), 700 from long5's
    check(bool(replaced) == want_replaced and (kept[-1] < 730.0) == want_replaced,
          (long_steps, kept, list(replaced)))

# The command line: a wrong number of workspaces and a non-workspace are named.
cmd = [sys.executable, os.path.join(scripts, "validation.py"), "figure"]
out = subprocess.run(cmd + ["fig6", work, work, "-o", work + "/o"], capture_output=True, text=True)
check(out.returncode == 1 and "figure fig6 reads 1 workspace (fig6_cells_only); got 2" in out.stderr, out.stderr)
out = subprocess.run(cmd + ["fig6", work, "-o", work + "/o"], capture_output=True, text=True)
check(out.returncode == 1 and "is not a sweep workspace (no invasim_sweep.json)" in out.stderr, out.stderr)
out = subprocess.run(cmd + ["fig10", work, "-o", work + "/o"], capture_output=True, text=True)
check(out.returncode == 1 and "unknown figure 'fig10'" in out.stderr, out.stderr)  # the old name
# A workspace made from another checkout of the repository (a campaign's own clone) cites its
# spec by the same path inside this repository; a spec found nowhere here keeps its own path
# (and the page's citation check then refuses it).
from invasim_analysis.validation import cli  # noqa: E402
check(cli.repo_path("/elsewhere/clone/protocols/sweeps/fig3_passive_slices.lua")
      == "protocols/sweeps/fig3_passive_slices.lua")
check(cli.repo_path(os.path.join(cli.REPO, "protocols/sweeps/fig4a_passive.lua"))
      == "protocols/sweeps/fig4a_passive.lua")
check(cli.repo_path("/elsewhere/clone/protocols/sweeps/no_such_sweep.lua")
      == "/elsewhere/clone/protocols/sweeps/no_such_sweep.lua")

# The paper-scale records (invasim_analysis/validation/paper_scale.py, `validation.py paper`) on synthetic
# workspaces ROOT/paper_<sweep>: 80 rows per finished run (t = 0.05 x 100 steps per row, to
# t = 400), noise +-1 around its level, A_t^max = 1000 (the negligible drift: 10).
import synthetic  # noqa: E402
from invasim_analysis.validation import document_paper, paper_scale  # noqa: E402
rng = np.random.default_rng(7)


def level(a, n=80, slope=0.0):
    """A_t rows: a steady level with noise, or (slope) a steady rise per row."""
    return [a + slope * i + rng.uniform(-1, 1) for i in range(n)]


CURVE = [({"f0": 0.001, "beta": 0.01, "tau_p": 25.0, "seed": 1, "steps": 8000}, "done",
          level(200.0), 1000.0, 0.1),
         ({"f0": 0.0019, "beta": 0.01, "tau_p": 25.0, "seed": 1, "steps": 8000}, "done",
          level(500.0), 1000.0, 0.3),
         ({"f0": 0.004, "beta": 0.01, "tau_p": 25.0, "seed": 1, "steps": 8000}, "done",
          level(800.0), 1000.0, 0.6)]


def starts(demixed, mixed, status="done"):
    """Fig. 4b's point from both starts, two seeds each; the last run (mixed, seed 2) has
    `status` (running: 40 of its 80 rows)."""
    pts = []
    for start, rows in (("demixed", demixed), ("mixed", mixed)):
        for seed in (1, 2):
            last = start == "mixed" and seed == 2
            pts.append(({"f0": 0.0019, "start": start, "seed": seed, "steps": 8000},
                        status if last else "done",
                        rows[:40] if last and status == "running" else rows, 1000.0, 0.3))
    return pts


def paper_record(start_points, curve=CURVE, name="fig4b"):
    root = os.path.join(work, "root")
    shutil.rmtree(root, ignore_errors=True)
    synthetic.write_workspace(os.path.join(root, "paper_fig4b_starts"), start_points)
    synthetic.write_workspace(os.path.join(root, "paper_fig5_cohesive"), curve)
    rec = paper_scale.record(name, root, os.path.join(work, "paper"), None)
    return {r["id"]: r for r in rec["rows"]}, rec


shutil.rmtree(work, ignore_errors=True)
# A steady run and a drifting one (2 per row: the quarters 40 apart, beyond 2 errors and the
# negligible 10) get their verdicts from the criterion.
synthetic.write_workspace(os.path.join(work, "one"), [
    ({"seed": 1, "steps": 8000}, "done", level(500.0), 1000.0, 0.3),
    ({"seed": 2, "steps": 8000}, "done", level(420.0, slope=2.0), 1000.0, 0.3)])
steady_job, drifting_job = workspace.load(os.path.join(work, "one"))
s = steady.steadiness(steady_job)
check(s["steady"] is True and abs(s["drift"]) < 2 * s["error"] and s["samples"] == 40, s)
s = steady.steadiness(drifting_job)
check(s["steady"] is False and abs(s["drift"] - 40.0) < 2.0 and s["negligible"] == 10.0, s)
# At the paper's 0.55 point: all runs steady, both starts at A_t = 500, A_n = 0.5 (the curve
# normalises 200 -> 0, 800 -> 1): agrees.
rows, rec = paper_record(starts(level(500.0), level(500.0)))
check(rows["fig4b_An_at_0.3"]["verdict"] == v.AGREES
      and abs(rec["numbers"]["A_n"] - 0.5) < 0.01, rows["fig4b_An_at_0.3"])
check(rows["fig4b_inset_starts"]["verdict"] == v.AGREES, rows["fig4b_inset_starts"])
check(all(p["class"] == "done" and p["steadiness"]["steady"] for p in rec["runs"]), rec["runs"])
check("fig4b_runs.png" in rec["images"]
      and os.path.getsize(os.path.join(work, "paper", "fig4b_runs.png")) > 1000, rec["images"])
# One drifting run makes the point, hence both rows, not steady, naming the run.
drift = starts(level(500.0), level(500.0))
drift[0] = (drift[0][0], "done", level(440.0, slope=1.5), 1000.0, 0.3)
rows, rec = paper_record(drift)
check(rows["fig4b_An_at_0.3"]["verdict"] == v.NOT_STEADY
      and "run demixed start, seed 1 drifts" in rows["fig4b_An_at_0.3"]["why"], rows["fig4b_An_at_0.3"])
# Two starts, each steady, that disagree (de-mixed at 400, mixed at 600): the state point's
# A_n is not steady, however far the paper's tolerance (0.1 in A_n) would let the A_n of their
# mean agree; the inset's row, which tests the starts' agreement itself, rests on the runs
# alone and disagrees (A_n 1/3 apart), where the whole criterion would say "not steady" for
# every disagreement beyond 2 errors and the row could never disagree.
rows, rec = paper_record(starts(level(400.0), level(600.0)))
check(all(p["steadiness"]["steady"] for p in rec["runs"]), rec["runs"])
check(rows["fig4b_An_at_0.3"]["verdict"] == v.NOT_STEADY
      and "the starts disagree" in rows["fig4b_An_at_0.3"]["why"], rows["fig4b_An_at_0.3"])
check(rows["fig4b_inset_starts"]["verdict"] == v.DISAGREES
      and "not steady" not in rows["fig4b_inset_starts"]["why"], rows["fig4b_inset_starts"])
agreement = steady.start_agreement(workspace.load(os.path.join(work, "root", "paper_fig4b_starts")))
check(agreement["agree"] is False and abs(agreement["difference"] - 200.0) < 1.0, agreement)
# Each start's error is the standard error of its runs' window means, the sample variance
# with n - 1 (two runs per start, 10 apart), recomputed here from the runs' series.
pts = starts(level(400.0), level(600.0))
pts[1] = (pts[1][0], "done", level(410.0), 1000.0, 0.3)
pts[3] = (pts[3][0], "done", level(590.0), 1000.0, 0.3)
synthetic.write_workspace(os.path.join(work, "starts_error"), pts)
jobs = workspace.load(os.path.join(work, "starts_error"))
agreement = steady.start_agreement(jobs)
for (start,), reps in workspace.group(jobs, ["start"]).items():
    ms = [float(np.mean(j.series["A_t"][slice(*steady.window(j))])) for j in reps]
    want = statistics.stdev(ms) / math.sqrt(len(ms))
    got = agreement["means"][str(start)][1]
    check(len(ms) == 2 and want > 0 and abs(got - want) <= 1e-9 * want, (start, got, want))
# ... and with one of its runs drifting, the inset's row is not steady, naming that run.
drift = starts(level(400.0), level(600.0))
drift[0] = (drift[0][0], "done", level(340.0, slope=1.5), 1000.0, 0.3)
rows, rec = paper_record(drift)
check(rows["fig4b_inset_starts"]["verdict"] == v.NOT_STEADY
      and "run demixed start, seed 1 drifts" in rows["fig4b_inset_starts"]["why"]
      and "the starts" not in rows["fig4b_inset_starts"]["why"], rows["fig4b_inset_starts"])
# A running run (mixed, seed 2: 40 of 80 rows, no summary.json): reported as running with
# its progress, its values provisional; the rows are "running", never a final verdict.
rows, rec = paper_record(starts(level(500.0), level(500.0), status="running"))
run = [p for p in rec["runs"] if p["class"] == "running"]
check(len(run) == 1 and run[0]["t"] == 200.0 and run[0]["t_target"] == 400.0, rec["runs"])
check(paper_scale.progress_text(run[0]) == "running, t = 200 of 400 (50 %)",
      paper_scale.progress_text(run[0]))
for sid in ("fig4b_An_at_0.3", "fig4b_inset_starts"):
    check(rows[sid]["verdict"] == v.RUNNING and rows[sid]["provisional"] == v.AGREES
          and "provisional (1 running): agrees" in rows[sid]["why"], rows[sid])
# A run still writing: the partial last line of its series.csv is not read (a done run's is).
running_job = [j for j in workspace.load_all(os.path.join(work, "root", "paper_fig4b_starts"))
               if j.status == "running"][0]
with open(os.path.join(running_job.path, "series.csv"), "a") as f:
    f.write("4200,210.0,5e")
check(workspace.Job(running_job.path).rows() == 40, workspace.Job(running_job.path).rows())
check(workspace.Job(running_job.path).provisional().mean("A_t")[0] == float(np.mean(
    workspace.Job(running_job.path).series["A_t"][20:40])))
# A pending run (no row yet) is listed as pending and left out of the values.
pend = starts(level(500.0), level(500.0))
pend[3] = (pend[3][0], "pending", [], 1000.0, 0.3)
rows, rec = paper_record(pend)
check([p["class"] for p in rec["runs"]].count("pending") == 1
      and rows["fig4b_An_at_0.3"]["verdict"] == v.RUNNING
      and "1 pending" in rows["fig4b_An_at_0.3"]["why"], rows)
# A state point of the curve that sets A_n's range without a row yet: A_n rests on part of the
# range, so its row says nothing, not even provisionally; the inset (A_t/A_t^max) still does.
partial = CURVE[:2] + [(CURVE[2][0], "pending", [], 1000.0, 0.6)]
rows, rec = paper_record(starts(level(500.0), level(500.0)), curve=partial)
check(rows["fig4b_An_at_0.3"]["verdict"] == v.RUNNING
      and rows["fig4b_An_at_0.3"]["provisional"] == v.NO_DATA
      and "normalised over the range of paper_fig5_cohesive, and 1 of its 3 runs have no row yet"
      in rows["fig4b_An_at_0.3"]["why"], rows["fig4b_An_at_0.3"])
check(rows["fig4b_inset_starts"]["provisional"] == v.AGREES, rows["fig4b_inset_starts"])
# A figure whose runs cannot make a statement yet (Fig. 3's trend needs two temperatures with
# rows; one runs, the other waits): each statement is still listed, running, no data so far.
synthetic.write_workspace(os.path.join(work, "root3", "paper_fig3_passive_slices"), [
    ({"kT": 8.125e-07, "seed": 1, "steps": 8000}, "running", level(500.0)[:40], 1000.0, 0.00125),
    ({"kT": 8.125e-04, "seed": 1, "steps": 8000}, "pending", [], 1000.0, 1.25)])
rec3 = paper_scale.record("fig3", os.path.join(work, "root3"), os.path.join(work, "paper"), None)
check(sorted(r["id"] for r in rec3["rows"]) == sorted(paper_scale.STATEMENTS["fig3"])
      and all(r["verdict"] == v.RUNNING and r["provisional"] == v.NO_DATA
              and "not computable yet from the 1 of 2 runs" in r["why"] for r in rec3["rows"]),
      rec3["rows"])
# A figure whose workspace does not exist yet: its rows are pending.
rec3 = paper_scale.record("fig3", os.path.join(work, "root"), os.path.join(work, "paper"), None)
check(rec3["missing"] == ["paper_fig3_passive_slices"]
      and {r["verdict"] for r in rec3["rows"]} == {v.PENDING}, rec3)

# The page: the paper-scale row beside the reduced one, with whether the scale changes the
# verdict, the running run's progress and the cost. Reduced: fig4b_An_at_0.3 disagrees.
shutil.rmtree(work, ignore_errors=True)
root = os.path.join(work, "root")
synthetic.write_workspace(os.path.join(root, "paper_fig4b_starts"),
                          starts(level(500.0), level(500.0), status="running"))
synthetic.write_workspace(os.path.join(root, "paper_fig5_cohesive"), CURVE)
with open(os.path.join(root, "paper_fig4b_starts", "workspace", "%032x" % 1, "run.log"), "w") as f:
    f.write("== 2026-12-04T18:59:33Z invasim sweep run: invasim run x.lua --threads 1\n"
            "run: 1 threads\n== 2026-12-05T08:00:00Z invasim sweep run: invasim run --resume "
            "x --threads 2\n")
os.makedirs(os.path.join(work, "records"))
with open(os.path.join(work, "records", "fig4b.json"), "w") as f:
    red = dict(rec_row("fig4b_An_at_0.3", v.DISAGREES), ours="A_n = 0.0262 +- 0.022")
    json.dump({"rows": [red], "specs": ["s"], "runs": 1, "steps_range": "1", "images": [],
               "command": "c", "criteria": v.CRITERIA}, f)
plan_paper = [{"spec": "protocols/sweeps/paper_scale/%s.lua" % n, "points": k,
               "core_seconds": k * 2400.0} for n, k in (("fig4b_starts", 4), ("fig5_cohesive", 3),
                                                        ("fig5_all_curves", 144),
                                                        ("fig4a_passive", 8))]
with open(os.path.join(work, "plan_paper.json"), "w") as f:
    json.dump(plan_paper, f)
out = subprocess.run([sys.executable, os.path.join(scripts, "validation.py"), "paper", root,
                      "-o", os.path.join(work, "records", "paper"), "--plan",
                      os.path.join(work, "plan_paper.json")], capture_output=True, text=True)
check(out.returncode == 0 and "paper fig4b: fig4b_An_at_0.3: running" in out.stdout, out.stdout + out.stderr)
cost = json.load(open(os.path.join(work, "records", "paper", "paper_cost.json")))
c4b = [c for c in cost["sweeps"] if c["sweep"] == "fig4b_starts"][0]
# 3 done runs at 3600 s (the first with 2 threads at its last attempt), one at half way with
# 1800 s recorded: used 4 h + 0.5 h, projected + the half left of the done runs' mean core
# time (4/3 h); the whole paper: the plan's 159 x 2400 s.
check(abs(c4b["used_core_hours"] - 4.5) < 1e-9 and abs(c4b["projected_core_hours"] - 4.5 - 2 / 3) < 1e-9
      and c4b["counts"] == {"done": 3, "running": 1, "pending": 0, "failed": 0}, c4b)
check(abs(cost["whole_paper"]["core_hours"] - 159 * 2400 / 3600) < 1e-9, cost["whole_paper"])
# A sweep of the list with a plan but no workspace yet: all its points pending, the plan's cost.
c4a = [c for c in cost["sweeps"] if c["sweep"] == "fig4a_passive"][0]
check(c4a["counts"]["pending"] == 8 and abs(c4a["projected_core_hours"] - 8 * 2400 / 3600) < 1e-9,
      c4a)
c3 = [c for c in cost["sweeps"] if c["sweep"] == "fig3_passive_slices"][0]
check(c3["points"] == 0 and c3["projected_core_hours"] is None, c3)  # no workspace, no plan
page = os.path.join(work, "page.md")
document.render(os.path.join(work, "records"), None, page, paper_dir=os.path.join(work, "records", "paper"))
text = open(page).read()
part = text[text.index("## At the paper's scale"):text.index("## Where the paper")]
check("| `fig4b_An_at_0.3` | A_n = 0.0262 +- 0.022 | disagrees | A_n = " in part
      and "| running | not yet: running (provisionally disagrees -> agrees) |" in part, part)
check("| `fig4b_inset_starts` | n/a | n/a |" in part, part)
check("| start = mixed, seed = 2 | running, t = 200 of 400 (50 %) |" in part
      and "| paper_fig5_cohesive: f0 = 0.004, seed = 1 | done |" in part, part)
check("| `protocols/sweeps/paper_scale/fig4b_starts.lua` | 4 | 3 | 1 | 0 | 0 | 4.50 | 5.17 | 2.67 |"
      in part and "**106 core-hours** in all" in part, part)
check("![fig4b](records/paper/fig4b_runs.png)" in part, part)
check(document_paper.change(v.AGREES, {"verdict": v.DISAGREES}) == "yes: agrees -> disagrees")
check(document_paper.change(v.AGREES, {"verdict": v.AGREES}) == "no")
check(document_paper.change(v.AGREES, {"verdict": v.PENDING}) == "not yet: pending")
# ... and the sentence under the table sorts the statements by that column.
check("In short, the paper's scale does not settle 7: `fig3_invasion_grows` (not yet: pending)"
      in part and ", `fig4b_An_at_0.3` (not yet: running (provisionally disagrees -> agrees))"
      in part, part)
summary = document_paper.change_summary([
    ("`a`", "", "", "", "", "yes: agrees -> disagrees"), ("`b`", "", "", "", "", "no"),
    ("`c`", "", "", "", "", "no"), ("`d`", "", "", "", "", "cannot say: no data at the paper's scale")])
check(summary == "In short, the paper's scale changes the verdict of 1: `a` (agrees -> disagrees); "
      "it leaves the verdict of 2: `b`, `c`; it does not settle 1: `d` (cannot say: no data at "
      "the paper's scale).", summary)
# The Method states the criterion once.
check(text.count("|m4 - m3| <= 2 sqrt(e3^2 + e4^2)") == 1, text)
print("check_validation: all checks passed")
