"""Assembles docs/validation.md from the figure records (DIR/<figure>.json, written by
`scripts/validation.py figure`) and the plan (plan.json, `scripts/validation.py plan`).
Prose lives here (the template); every number comes from the records."""

import json
import os

from . import citations, document_paper
from .. import atomic
from . import plan as plan_mod
from ..errors import InputError
from .verdict import CRITERIA, DISAGREES, VERDICTS, is_code_check, paper, paper_verdict

ORDER = ["fig3", "fig4a", "fig4b", "fig5", "fig6", "fig7a", "fig7b", "fig8", "fig9"]
# The sweep files (workspaces) of each figure, as scripts/validation.py's FIGURES.
SWEEPS = {"fig3": "fig3_passive_slices", "fig4a": "fig4a_passive", "fig4b": "fig4b_cohesive",
          "fig5": "fig5_active", "fig6": "fig6_cells_only", "fig7a": "fig7a_tethered",
          "fig7b": "fig7b_tethered", "fig8": "fig8_packing", "fig9": "fig9_shapes"}
TITLES = {
    "fig3": "Fig. 3: passive repulsive cells, A_t(t) and slices",
    "fig4a": "Fig. 4a: passive repulsive cells, A_n against temperature at several times",
    "fig4b": "Fig. 4b: cohesive active cells (beta = 1e-2, tau_p = 25), with the mixed-start inset",
    "fig5": "Fig. 5: the master curve over beta x tau_p, plus the passive curve (tau_p = 2500: "
            "the longer runs of fig5_long; beta = 1e-4 and tau_p = 250: fig5_extra_curves)",
    "fig6": "Fig. 6: cells only, tau_d against tau_p",
    "fig7a": "Fig. 7a: tethered tissue, K_ecm (tau_p = 25, beta = 1e-2)",
    "fig7b": "Fig. 7b: tethered tissue, K_ecm (tau_p = 2500, beta = 1e-3)",
    "fig8": "Fig. 8: the adipocyte packing-fraction scan",
    "fig9": "Fig. 9: slice shape distributions",
}

CONTRADICTIONS = """\
## Where the paper contradicts itself

Some statements of the paper cannot all hold. We do not tune towards any of them; the rows
named below show what we get, computed from the runs. Where the paper contradicts itself on a
number (`L_f`, `A_t^min`/`A_t^max`) the row's verdict is *paper inconsistent*, not
*disagrees*:

- **`L_f`** (row `L_f`): the paper's final box `L_f = 34 sigma` contradicts its own
  `L_0 = 70`, `phi: 0.01 -> 0.72`, which give 16.8 sigma. Our compression stops at the target
  `phi = 0.72`; the row gives the box it reached and, from the body volumes of our run, the
  box the paper-size system would reach.
- **`A_t^min`/`A_t^max`** (row `fig3_At_min_over_max`): 470 (text) or 610 (Fig. 3 caption)
  against 2000 cannot both hold under the paper's definition of `A_t^max` (both walls fully
  covered plus the adipocytes' Voronoi surfaces). We follow the definition; the ratio at the
  lowest temperature is what we compare, `A_n` does not depend on it.
- **The factor 2 in `k_B T`** (check `fig5_factor2`, under "Checks of our code"): the
  paper's temperature formula has an extra factor 2. A passive bath shows it directly: the
  equipartition `T_c` equals the bath `kT`; the paper's convention `kT_c_paper = 2 T_c` is
  what every figure's temperature axis uses, passive runs included (Method).
- **`T_c/T_a`** (row `fig5_Tc_over_Ta`): the paper reports `1 < T_c/T_a < 1.2` in active
  runs but gives its vertices damping without noise, which without a background heats them
  only through contacts (`T_c/T_a` from 1.7 to 73 at the cells' damping). docs/model.md
  ("Vertex bath") measures the readings; the protocols run the one that holds the window
  over Fig. 5's range: a background temperature six times the activity's free-particle
  temperature for cells and vertices (`background_factor = 6`). The row shows what it gives
  in the campaign.
- **`phi_a` up to 0.9 under the pressure wall** (Fig. 8): the paper rescales the box to
  `0.4 < phi_a < 0.9` (with `phi = phi_c + phi_a`, so `phi > 1` at the top) and quotes one
  `k_B T/(P sigma^3) = 0.37` for the scan; docs/model.md (protocol step 6) runs it under the
  pressure wall at `P`. Both cannot hold: under the piston the tissue expands back to the packing that `P`
  sets, whatever the target. `packing.lua` takes `box = pressure` (the piston at `P`) or `box = fixed`
  (the box keeps the rescaled size, the wall pressure is measured, not set); Fig. 8 shows
  both scans with their own rows.
"""

METHOD = """\
## Method: how the campaign is run and this page regenerated

Every figure below comes from one sweep file in `protocols/sweeps/` (its header says how to
run it) and one analysis command (printed under the figure). The whole campaign:

```sh
scripts/validation.py plan protocols/sweeps/{fig3_passive_slices,fig4a_passive,fig4b_cohesive,fig4b_inset,fig5_active,fig5_passive,fig5_long,fig5_extra_curves,fig6_cells_only,fig7a_tethered,fig7b_tethered,fig8_packing,fig9_shapes}.lua --jobs 2 -o docs/validation/plan.json
for s in fig3_passive_slices fig4a_passive fig4b_cohesive fig4b_inset fig5_active fig5_passive \\
         fig5_long fig5_extra_curves fig6_cells_only fig7a_tethered fig7b_tethered fig8_packing \\
         fig9_shapes; do
  build/invasim sweep init protocols/sweeps/$s.lua && build/invasim sweep run out/$s --jobs 2
done
scripts/validation.py all out -o docs/validation     # every figure command below, then:
scripts/validation.py plan --workspace out/fig3_passive_slices ... -o docs/validation/plan_done.json
scripts/validation.py document docs/validation --plan docs/validation/plan.json --done docs/validation/plan_done.json --paper docs/validation/paper -o docs/validation.md
```

At the paper's scale (section "At the paper's scale"), the workspaces `ROOT/paper_<sweep
file>` of `protocols/sweeps/paper_scale/` (each file's header gives its `sweep init` and
`sweep run` lines) are read as they are, while the campaign runs:

```sh
scripts/validation.py paper ROOT -o docs/validation/paper --plan docs/validation/plan_paper_scale.json
```

and the `document` line above with `--paper docs/validation/paper` puts them on the page.

The analysis reads the run directories of each workspace (`summary.json`: means and
errors (from the autocorrelation time) over the last half of the production; `series.csv`; `shapes.csv`; `snapshots/`).
`A_n` is the paper's Appendix C normalisation over the figure's state points (replicate means;
docs/sweeps_analysis.md). Its error is that of the gap `A_t^max - A_t` it is linear in,
covariance included: the replicates' standard error, their variance pooled with the neighbouring
state point on each side of the curve (`validation/points.py`), whose degrees of freedom (two
seeds alone give one) turn "2 errors" into `t_0.977(dof)` errors
(`scripts/invasim_analysis/student.py`; Welch-Satterthwaite for a combination), so that it keeps
its 95 % coverage: 3.3 for three, 2.3 for ten. With no replicates near, the error is the run's
own, a lower bound: two seeds of a state point differ in `A_t` by a median 8 of `summary.json`'s
errors (0.67 expected). Curves are fitted with `master_curve/fits.py`; Fig. 5 with
`master_curve.py`'s own functions (docs/sweeps_analysis.md; its unsteady state points enter no
fit), so that from one workspace without an unsteady curve it gets that tool's `a`, `b`, `c1`,
`c2`. `scripts/validation.py all` passes a missing optional workspace as `-` (e.g. Fig. 5
without `fig5_long`); the record names it and the figure's section says which workspaces were
not given.

**One temperature axis.** Every figure's `k_B T/(P sigma^3)` is the measured cancer-cell
temperature in the paper's convention, `2 k_B T_c/(P sigma^3)` (`kT_c_paper/P` of
`summary.json` and `series.csv`; the paper's Eq. (14) has an extra factor 2 over
equipartition), for the passive runs too: their baths are set to `kT = x P / 2` so that the
measured value is about the paper's `x`, and Fig. 3 names both. The paper's thresholds
(`T_g ~ 0.03`, Fig. 4b's 0.3, Fig. 8's 0.37) are in this convention; rows that quote a
compared temperature give both, `2T_c/P` and the equipartition `T_c/P`.

The two plan files are kept beside the figure records (`docs/validation/plan.json`,
`plan_done.json`), so that this page can be regenerated without the workspaces; the
workspaces themselves (about 1 GB) are not kept. A figure without a record says so ("Not
generated"); a record from older criteria is marked under its figure.

**Steady state** (`scripts/invasim_analysis/steady.py`, `steadiness`, `point_steadiness`; the
one criterion of every figure, every verdict and the paper-scale rows). The averaging window of
a run is the last half of its production rows (what `summary.json` averages; for a run still
going, the last half of the rows written so far). Its two halves are the run's last two
quarters: the run is steady when the means of `A_t` over them, `m3` and `m4`, agree within twice
their combined error, `|m4 - m3| <= 2 sqrt(e3^2 + e4^2)`, each `e = sqrt(var 2 tau_int / n)`
with `tau_int` the integrated autocorrelation time of the whole window's fluctuations about its
drift (each quarter's mean and one common slope), by Sokal's automatic window (at most 13 of 124
rows) corrected for the fitted drift. Stationary windows of 124 rows with correlation times of
2, 5, 10, 25 rows are called drifting 6.5, 8, 11.5, 21 % of the time (4.6 % nominal). Or the drift is negligible when
`|m4 - m3| <= 1 %` of the window's mean `A_t^max` (it moves `A_n` by less than about 0.015,
under the precision of every statement here: a caged, de-mixed tissue ages by a few tenths of
`sigma^2` per quarter with an error smaller still, which the 2-sigma test alone would call
drifting forever). A run with fewer than two rows per quarter or without a finite error cannot
be judged and does not count as steady. A state point is steady when all its runs are and, where
it was run from two starts (Fig. 4b's de-mixed and mixed starts), when the starts agree by the
same test: their means of `A_t` over the averaging windows (each start's mean over its seeds,
its error the standard error over the seeds, or with one seed its window's by the same
estimator) differ by at most twice the combined error (`t_0.977(dof)` times with few seeds), or
by less than 1 % of `A_t^max`. Each figure says how many of its runs pass. A row that rests on
state points (its criterion names them: Fig. 4b's two points bracketing 0.3, every point of a
Fig. 5 curve) gets the verdict *not steady* when one of them is not steady, and names the runs
and the starts that fail (the inset's row, which tests the starts' agreement itself, rests on
its runs alone); a Fig. 5 curve that is not steady is drawn hollow and left out of the collapse
and of the fit of `a`. Rows about the approach in time (Fig. 3's `A_t(t)`, Fig. 4a's curve at
three times) do not rest on a steady state. A value at an earlier time (Fig. 4a's curves at a
quarter and half of the run, or at `t = 1e4` and `1e5` at the paper's scale) is the mean over
the averaging window the run would have had, had it ended there.

**Verdicts** (`scripts/invasim_analysis/validation/verdict.py`). The paper's statements and
their stated precision are in `scripts/validation_paper.json` (each citing its place in the
paper: section, figure, equation). A number agrees when `|ours - paper| <= tolerance + 2 errors`
(2 read as `t_0.977(dof)` for an error of pooled replicates, above) (or within the stated factor
on a log scale); it *agrees in trend only* when the number is off but the trend the figure is
about holds; a trend (a difference the paper says is positive) agrees when it exceeds 2 errors,
agrees in trend only when it has the right sign within 2 errors, is *inconclusive* with the
wrong sign within 2 errors, and disagrees below -2 errors. *No data*: too few points for the
number (always the case at the CI size for fits); *not testable*: the paper compares with data
we do not have; *not steady*: above; *paper inconsistent*: the paper contradicts itself on the
number (its `inconsistent` in `scripts/validation_paper.json`; the row keeps what the verdict
against one of its values would be). A statement marked `"check": "code"` tests our code, not
the paper: it is listed under "Checks of our code" and not counted. Statements that must hold at
several points (all `phi_c` of Fig. 6, all `K_ecm` of Fig. 7) agree when every point agrees,
disagree when one disagrees, and are inconclusive when one is. Fig. 7's onset (where `A_n` first
exceeds its lowest-temperature value by 2 combined errors) has an error in `log10 x`: the `A_n`
errors of the lowest and the two bracketing points through the interpolation, or the bracket's
log width/sqrt(12) where it falls on a grid point. Fig. 8's mean of
`A_n(lambda = 0) - A_n(lambda)` counts each `lambda = 0` point once, with the weight of all the
differences it is in.

**CI.** `tests/analysis/validation_tiny.sh` (CTest `validation_pipeline_tiny`, about 75 s at 2 jobs) runs every
campaign sweep file at its CI size (`invasim sweep init SPEC --tiny`: each file's
`tiny = {...}`, two values per axis, one seed, a few hundred steps), then every figure command,
the plan from the done points and this document, so that no part of the pipeline can rot.
A point that fails to run fails the test at its end, after the done points are analysed. The
unit test (`analysis_validation_unit`) holds each verdict class and per-point criterion on
hand-made runs and numbers.

**Citations** (`scripts/invasim_analysis/validation/citations.py`). Figures, sections and statement ids
carry the paper's own figure numbers (its Figs. 3-9; `figures` in
`scripts/validation_paper.json`), and every statement's source is its place in the paper
(section, figure, equation, numbered as in the paper). `scripts/validation.py document`
refuses to write a page whose statements or text cite a path outside the repository or a
figure the paper does not have, and the CI test checks the page it wrote again.
"""


def _load(dir_):
    recs = {}
    for name in ORDER:
        p = os.path.join(dir_, name + ".json")
        if os.path.exists(p):
            with open(p) as f:
                recs[name] = json.load(f)
    return recs


def _cell(text):
    """Table-cell text: a '|' (as in |drift|) would end the cell."""
    return str(text).replace("|", "\\|")


def _paper_text(row):
    """The paper's statement, with the variant of the protocol the row tested (e.g. Fig. 8's
    box) when a figure tests one statement more than once."""
    return row["paper"] + (" (%s)" % row["variant"] if row.get("variant") else "")


def _statement(row):
    """The statement's id in code font, with the variant."""
    return "`%s`" % row["id"] + (" (%s)" % row["variant"] if row.get("variant") else "")


def _rel(path, base):
    return os.path.relpath(path, base)


def render(fig_dir, plan_entries, out_path, ci_size=False, done_entries=None, paper_dir=None):
    """Writes the page; paper_dir: the paper-scale records (validation.py paper), whose
    section stands after the verdicts."""
    recs = _load(fig_dir)
    base = os.path.dirname(os.path.abspath(out_path))
    L = ["# Validation: the paper's figures at reduced scale", ""]
    if ci_size:
        L += ["> **CI size, not the campaign.** The numbers and figures on this page come from "
              "the tiny CI runs (a few hundred steps, two state points per axis, one seed); "
              "they only show that the pipeline works. The campaign's results replace them "
              "when the lead runs it (Method, below). Verdicts here mean nothing physical.", ""]
    L += ["This page is generated by `scripts/validation.py document` from the figure records "
          "in `%s/` (relative to this page); do not edit it by hand."
          % _rel(os.path.abspath(fig_dir), base), ""]
    L += ["## The plan", ""]
    if plan_entries:
        L += ["Produced by `scripts/validation.py plan` (the command is under Method): state "
              "points x steps x the measured rate, per sweep file; the rate and the fixed cost "
              "per point (start-up, compression or rescale) come from two short timing runs of "
              "the file's first point in CPU time, or from the recorded wall times of done "
              "points (column 'from'). One thread per point, %d points at a time. The tissue "
              "figures use the reduced system (8 adipocytes, 400 cells); Fig. 6 has 500 cells "
              "and no adipocytes. The paper's size (28, 1500) is about four times the cost per "
              "step and does not fit the budget (about 6 core-hours); the statements that "
              "need it are run at the paper's scale apart (section \"At the paper's scale\", "
              "when its records are given)."
              % plan_entries[0]["jobs"], "", plan_mod.table(plan_entries), ""]
    else:
        L += ["(no plan given: `scripts/validation.py document ... --plan plan.json`)", ""]
    if done_entries:
        L += ["### As run", "",
              "The campaign as it ran (`scripts/validation.py plan --workspace ...`: the points "
              "of each workspace and their recorded wall times; the rates are wall-clock rates "
              "of the runs, %d at a time, on a machine shared with the development work, so they "
              "are lower than the timing runs' CPU rates above)." % done_entries[0]["jobs"], "",
              plan_mod.table(done_entries), ""]
    all_rows, checks = [], []
    for name in ORDER:
        rec = recs.get(name)
        L += ["## %s" % TITLES[name], ""]
        if not rec:
            L += ["Not generated: no record `%s.json`. Its workspace `out/%s` has not been "
                  "analysed (run it as under Method, then `scripts/validation.py figure %s "
                  "out/%s ... -o docs/validation`); its statements are not on this page and not "
                  "counted." % (name, SWEEPS[name], name, SWEEPS[name]), ""]
            continue
        L += ["Sweep%s: %s; %d runs, %s steps per run." % (
            "s" if len(rec["specs"]) > 1 else "", ", ".join("`%s`" % s for s in rec["specs"]),
            rec["runs"], rec["steps_range"]), ""]
        if rec.get("criteria", 1) < CRITERIA:
            L += ["**Record from older criteria.** This record was written before the current "
                  "criteria (Method: one temperature axis, the per-point rows, *not steady*, "
                  "the steady-state criterion of the two quarter means); "
                  "its rows, texts and figures are as it computed them, only the verdict classes "
                  "*paper inconsistent* and the checks of our code are applied here. Rerun the "
                  "command below on the workspaces to update it.", ""]
        if rec.get("missing"):
            L += ["Workspace%s not given for this record: %s; the curves and rows that need "
                  "%s are absent." % ("s" if len(rec["missing"]) > 1 else "",
                                      ", ".join("`%s`" % m for m in rec["missing"]),
                                      "them" if len(rec["missing"]) > 1 else "it"), ""]
        for img in rec["images"]:
            L += ["![%s](%s)" % (name, _rel(os.path.join(os.path.abspath(fig_dir), img), base))]
            if rec.get("captions", {}).get(img):
                L += ["", "*%s*" % rec["captions"][img], ""]
        L += ["", "Regenerate: `%s`" % rec["command"], ""]
        st = rec.get("steadiness")
        if st:
            # Records before criteria 3 hold |drift| over the last-half mean's error.
            ratio = ("|m4 - m3|/(combined error)" if rec.get("criteria", 1) >= 3
                     else "|drift|/error")
            L += ["Steady state: %d of %d runs steady by the criterion (%d judged); largest "
                  "%s %s." % (st["steady"], st["jobs"], st["judged"], ratio,
                                         "%.2g" % st["max_drift_over_error"]
                                         if st["max_drift_over_error"] is not None else "n/a"), ""]
        L += ["| paper | ours | verdict | criterion |", "|---|---|---|---|"]
        for r in rec["rows"]:
            r = dict(r)
            r["verdict"], r["why"] = paper_verdict(paper().get(r["id"], {}), r["verdict"], r["why"])
            (checks if is_code_check(r["id"]) else all_rows).append(r)
            L.append("| %s | %s | **%s** | %s |" % tuple(
                _cell(v) for v in (_paper_text(r), r["ours"], r["verdict"], r["why"])))
        L.append("")
    L += ["## Verdicts", ""]
    counts = {v: sum(1 for r in all_rows if r["verdict"] == v) for v in VERDICTS}
    L += [", ".join("%d %s" % (n, v) for v, n in counts.items()) + " (the paper's statements; "
          "the checks of our code below are not counted)", "",
          "| figure | statement | verdict |", "|---|---|---|"]
    L += ["| %s | %s | %s |" % (r["figure"], _statement(r), r["verdict"]) for r in all_rows]
    bad = [r for r in all_rows if r["verdict"] == DISAGREES]
    if bad:
        L += ["", "Disagreements, each with what we get and the criterion it fails:", ""]
        L += ["- %s (%s): %s. Ours: %s. Criterion: %s." % (
            _statement(r), r["figure"], r["paper"], r["ours"], r["why"]) for r in bad]
    L += ["", "### Checks of our code", "",
          "Statements that test our code against the paper's formulas rather than the paper's "
          "results (`\"check\": \"code\"` in `scripts/validation_paper.json`); their rows "
          "stand under their figures and are not counted above.", ""]
    if checks:
        L += ["| figure | check | ours | verdict |", "|---|---|---|---|"]
        L += ["| %s | %s | %s | %s |" % tuple(_cell(v) for v in (
            r["figure"], _statement(r), r["ours"], r["verdict"])) for r in checks]
    else:
        L += ["(none in the records)"]
    L.append("")
    if paper_dir:
        L += document_paper.section(paper_dir, recs, fig_dir, base)
    L += [CONTRADICTIONS, METHOD]
    text = "\n".join(L)
    _check_citations(list(paper().values()) + all_rows, text, out_path)
    atomic.write_text(out_path, text)
    return counts


def _check_citations(statements, text, out_path):
    """Refuses the page (InputError, nothing written) when a statement or the page cites a
    file outside the repository or a figure number the paper does not have (citations.py)."""
    count, figures = citations.paper_figures()
    problems = citations.statement_problems(statements, count, figures)
    problems += citations.page_problems(text, count, figures)
    if problems:
        raise InputError("%s not written: %d citation problem%s (scripts/validation_paper.json, "
                         "the figure records, scripts/invasim_analysis/validation/document.py):\n  %s" % (
                             out_path, len(problems), "" if len(problems) == 1 else "s",
                             "\n  ".join(dict.fromkeys(problems))))
