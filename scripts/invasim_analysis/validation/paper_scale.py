"""The paper-scale records (docs/validation.md, "At the paper's scale"): the runs of
protocols/sweeps/paper_scale/ (28 adipocytes, 1500 cells, to t = 5e5) read while a campaign
runs them, each statement of Figs. 3, 4a, 4b and 5 that they test computed as at the reduced
scale (the same figure functions, the same steady-state criterion of steady.py) and written as
DIR/paper_<figure>.json beside the A_n(t) panels (panels.py).

A point is done, running (its series.csv has rows, but the run has not finished: running,
stopped or submitted) or pending (no row yet); a failed run is listed as failed and left out
of the values (`sweep run` tries it again).
Running runs enter with their averages so far (workspace.Job.provisional); a row that rests on a
run that is not done gets the verdict "running" (the verdict its values would give is kept
as `provisional`; so does a row while a run of its figure is pending or failed), a row
with no run yet "pending"."""

import math
import os
import re

from .. import normalise, steady, student, workspace  # noqa: F401 (normalise: via points)
from . import panels, points, verdict
from .figures_master import fig5 as reduced_fig5
from .figures_tissue import fig3 as reduced_fig3
from .figures_tissue import fig4a as reduced_fig4a
from .figures_tissue import fig4b as reduced_fig4b
from .figures_tissue import fmt_time, production_time, time_step, x_measured

# figure -> the paper-scale sweep files it reads (protocols/sweeps/paper_scale/), in order;
# their workspaces are ROOT/paper_<name> (the campaign's names).
SWEEPS = {"fig3": ["fig3_passive_slices"], "fig4a": ["fig4a_passive"],
          "fig4b": ["fig4b_starts", "fig5_cohesive", "fig4b_starts_hot"],
          "fig5": ["fig5_cohesive"]}
PREFIX = "paper_"
TIMES = (1e4, 1e5, 5e5)  # Fig. 4a's times (the paper's caption)
# The statements each figure's record carries (the others of the reduced figure are left out:
# they rest on workspaces the paper-scale list does not run).
STATEMENTS = {"fig3": ["fig3_invasion_grows", "fig3_At_min_over_max"],
              "fig4a": ["fig4a_moves_left", "fig4a_Tg"],
              "fig4b": ["fig4b_An_at_0.3", "fig4b_inset_starts"],
              "fig5": ["fig5_b_range"]}
DONE, RUNNING, PENDING, FAILED = "done", "running", "pending", "failed"
# The rows that rest on A_n and the sweep (index in SWEEPS) whose state points set its
# normalisation (0 and 1 at the ends of their range; normalise.py): while some of them have no
# row yet, the range, hence A_n, is not the sweep's, and these rows say nothing, not even
# provisionally.
NORMALISED_BY = {"fig4a": (0, STATEMENTS["fig4a"]), "fig4b": (1, ["fig4b_An_at_0.3"]),
                 "fig5": (0, STATEMENTS["fig5"])}
THREADS = re.compile(r"--threads (\d+)")  # of an attempt's line in run.log


def workspace_path(root, sweep):
    return os.path.join(root, PREFIX + sweep)


def progress(job):
    """One run's state for the page: class (done, running, pending, failed), the document's
    status, the production time reached and its target (steps x dt), rows, wall seconds."""
    rows = job.rows()
    status = job.status
    cls = (DONE if status == "done" else FAILED if status == "failed"
           else RUNNING if rows else PENDING)
    out = {"job": job.id, "class": cls, "status": status, "rows": rows,
           "wall_seconds": float(job.doc.get("wall_seconds") or 0.0), "threads": threads(job),
           "started_at": job.doc.get("started_at"), "sp": job.sp}
    if rows:
        out["t"] = float(production_time(job)[-1])
        out["t_target"] = float(int(job.sp.get("steps", 0)) * time_step(job))
    return out


def threads(job):
    """The threads the run was given: `--threads N` of the last attempt that `sweep run`
    logged in run.log ("== <time> invasim sweep run: ... --threads N"), else 1."""
    path = os.path.join(job.path, "run.log")
    n = 1
    if os.path.exists(path):
        with open(path, errors="replace") as f:
            for line in f:
                m = THREADS.search(line) if line.startswith("== ") else None
                n = int(m.group(1)) if m else n
    return n


def progress_text(p):
    """"running, t = 2.1e5 of 5e5 (42 %)" / "done" / "pending"."""
    if p["class"] == RUNNING and verdict.finite(p.get("t"), p.get("t_target")) and p["t_target"] > 0:
        return "running%s, t = %s of %s (%.0f %%)" % (
            "" if p["status"] == "running" else " (%s)" % p["status"], fmt_time(p["t"]),
            fmt_time(p["t_target"]), 100 * p["t"] / p["t_target"])
    return p["class"]


def _order(job):
    """Runs in the order of their varied parameters (numbers numerically, then by name)."""
    return [(0, float(v), "") if isinstance(v, (int, float)) else (1, 0.0, str(v))
            for v in (job.sp.get(k) for k in ("kT", "f0", "start", "seed")) if v is not None]


def point_name(p, keys):
    """A run by the parameters `keys` (its sweep's varied ones: varied_keys)."""
    return ", ".join("%s = %s" % (k, p["sp"][k]) for k in keys if k in p["sp"]) or p["job"][:8]


def varied_keys(progresses):
    """The parameters that tell a sweep's runs apart (of kT, f0, start, seed), seed always."""
    return [k for k in ("kT", "f0", "start", "seed")
            if k == "seed" or len({str(p["sp"].get(k)) for p in progresses}) > 1]


def _finalise(rows, progresses, used_ids):
    """The rows' verdicts by the state of the runs they rest on (the figure's usable runs):
    all done, the verdict stands; one not done, "running" (the verdict kept as provisional)."""
    running = [p for p in progresses if p["class"] == RUNNING and p["job"] in used_ids]
    pending = [p for p in progresses if p["class"] == PENDING]
    failed = [p for p in progresses if p["class"] == FAILED]  # sweep run tries them again
    for r in rows:
        if running or pending or failed:
            r["provisional"] = r["verdict"]
            r["verdict"] = verdict.RUNNING
            r["why"] += "; provisional (%s): %s" % (", ".join(
                "%d %s" % (len(ps), what) for ps, what in ((running, "running"), (pending, "pending"),
                                                         (failed, "failed")) if ps), r["provisional"])
    return rows


def _without_partial_range(name, rows, progresses, usable):
    """The rows on A_n as "no data" while state points of the sweep that sets A_n's range
    (NORMALISED_BY) have no row yet (usable: each sweep's runs with rows)."""
    if name not in NORMALISED_BY:
        return rows
    k, ids = NORMALISED_BY[name]
    if k >= len(progresses) or not progresses[k]:
        return rows
    with_rows = {j.id for j in usable[k]}
    without = [p for p in progresses[k] if p["job"] not in with_rows]
    if not without:
        return rows
    why = ("A_n is normalised over the range of %s%s, and %d of its %d runs have no row yet"
           % (PREFIX, SWEEPS[name][k], len(without), len(progresses[k])))
    return [dict(r, verdict=verdict.NO_DATA, why="%s; %s" % (r["why"], why))
            if r["id"] in ids and r["verdict"] != verdict.NO_DATA else r for r in rows]


def _pending_rows(name, why):
    return [dict(verdict.row(sid, "n/a", verdict.PENDING, why), provisional=None)
            for sid in STATEMENTS[name]]


def _every_statement(name, rows, usable, progresses):
    """The figure's rows with one for every statement: a statement its figure function could not
    make from the runs with rows so far (Fig. 3's trend needs two temperatures) has no data."""
    have = {r["id"] for r in rows}
    why = "not computable yet from the %d of %d runs of %s with rows" % (
        len(usable[0]), len(progresses[0]), PREFIX + SWEEPS[name][0])
    return rows + [verdict.row(sid, "n/a", verdict.NO_DATA, why)
                   for sid in STATEMENTS[name] if sid not in have]


def _keep(rows, name):
    return [r for r in rows if r["id"] in STATEMENTS[name]]


def fig3(sets, out, invasim):
    rec = reduced_fig3(sets[0], out, invasim)
    return _keep(rec["rows"], "fig3"), rec["images"], rec.get("numbers", {}), None


def fig4a(sets, out, invasim):
    rec = reduced_fig4a(sets[0], out, invasim, times=TIMES)
    return (_keep(rec["rows"], "fig4a"), rec["images"], rec.get("numbers", {}),
            rec["numbers"]["normalisation"])


def fig4b(sets, out, invasim):
    """The paper's 0.55 point from both starts: its A_n (every start run, normalised with the
    fig5_cohesive curve at the paper's scale, the same beta and tau_p) and the starts'
    agreement (the reduced figure's inset row)."""
    starts, curve = _inset_point(sets), sets[1] if len(sets) > 1 else None
    if not curve or len({j.sp.get("f0") for j in curve}) < 2:
        why = ("A_n needs the normalisation of the beta = 1e-2, tau_p = 25 curve at the paper's "
               "scale (%s): fewer than two of its state points have rows"
               % (PREFIX + SWEEPS["fig4b"][1]))
        inset = _inset_in_ratio(starts, why)
        if inset is None:
            raise workspace.InputError(why)
        an = verdict.row("fig4b_An_at_0.3", "n/a", verdict.NO_DATA, why)
        return [an, inset], [], {"starts_in_ratio": inset["data"]}, None
    rec = reduced_fig4b(curve, out, invasim, inset_jobs=starts)
    extremes = rec["numbers"]["normalisation"]
    vals, mean, err, dof = points.runs_a_n(starts, extremes)
    x = sum(x_measured(j) for j in starts) / len(starts)
    st = verdict.paper()["fig4b_An_at_0.3"]
    is_steady, reasons = steady.point_steadiness(starts)
    row = verdict.row(
        "fig4b_An_at_0.3", "A_n = %s at %s (the state point run from both starts: %d runs, "
        "normalised with the paper-scale curve)" % (verdict.fmt(mean, err),
                                                     verdict.fmt_temperature(x), len(starts)),
        verdict.value_verdict(mean, err, st["value"], st["tolerance"],
                              dof=dof),
        "|ours - 0.55| <= 0.1 + 2 errors (scatter of the runs); rests on the state point, "
        "steady (every run, and the two starts agreeing)", unsteady=reasons)
    rows = [row] + [r for r in rec["rows"] if r["id"] == "fig4b_inset_starts"]
    numbers = {"A_n_runs": [float(v) for v in vals], "A_n": mean, "A_n_error": err, "x": x,
               "starts": rec["numbers"].get("inset"), "normalisation": extremes}
    return rows, rec["images"], numbers, extremes


# The paper's temperature for Fig. 4b's A_n ~ 0.55 and its inset: 2 k_B T_c/(P sigma^3) ~ 0.3.
INSET_X = 0.3


def _inset_point(sets):
    """The runs of the inset's state point: of fig4b_starts (sets[0]) and fig4b_starts_hot
    (sets[2]), those run from both starts, the one whose measured 2 k_B T_c/(P sigma^3) is
    nearest the paper's 0.3 (fig4b_starts' f0 measured 0.233 at this size)."""
    candidates = [s for s in (sets[0], sets[2] if len(sets) > 2 else [])
                  if len({str(j.sp.get("start")) for j in s}) == 2]
    if not candidates:
        return sets[0]
    return min(candidates,
               key=lambda s: abs(sum(x_measured(j) for j in s) / len(s) - INSET_X))


def _inset_in_ratio(starts, why_no_an):
    """The inset's row before the paper-scale curve exists, from A_t/A_t^max. A_n = (A_t/A_t^max
    - lo) / (hi - lo) with 0 <= lo < hi <= 1, so a difference of the starts in A_n is at least
    their difference in A_t/A_t^max: beyond the tolerance (0.1 + 2 errors) here, the starts
    disagree in A_n too. A smaller difference cannot be judged yet (None)."""
    # Each start's mean over its runs' averaging windows and the standard error over its runs
    # (the criterion's own comparison of the starts, steady.start_agreement), with two runs or
    # more per start.
    runs = {str(k[0]): len(v) for k, v in workspace.group(starts, ["start"]).items()}
    if set(runs) != {"demixed", "mixed"} or min(runs.values()) < 2:
        return None
    agreement = steady.start_agreement(starts, "start", "A_ratio")
    means = {k: (m, err, runs[k]) for k, (m, err) in agreement["means"].items()}
    d, e = means["mixed"][0] - means["demixed"][0], agreement["error"]
    if not (verdict.finite(d) and verdict.finite(e)):
        return None
    tol = verdict.paper()["fig4b_inset_starts"]["tolerance"]
    if abs(d) - student.factor(agreement["dof"]) * e <= tol:
        return None
    x = sum(x_measured(j) for j in starts) / len(starts)
    # Each run's own steadiness; the starts' disagreement, the criterion's second half, is
    # what this row reports.
    runs_unsteady = steady.unsteady_runs(starts)
    return verdict.row(
        "fig4b_inset_starts", "A_t/A_t^max = %s (de-mixed, %d runs), %s (mixed, %d runs) at %s "
        "(t = 5e5)" % (verdict.fmt(*means["demixed"][:2]), means["demixed"][2],
                       verdict.fmt(*means["mixed"][:2]), means["mixed"][2],
                       verdict.fmt_temperature(x)), verdict.DISAGREES,
        "difference in A_t/A_t^max %s, beyond 0.1 + 2 errors; the difference in A_n is at least "
        "as large (A_n rescales A_t/A_t^max by 1/(max - min) >= 1), so the starts disagree "
        "whatever the normalisation (%s); every run steady by its own quarters unless said"
        % (verdict.fmt(d, e), why_no_an),
        data={"means": {k: list(v) for k, v in means.items()}, "difference": d, "error": e},
        unsteady=runs_unsteady)


def fig5(sets, out, invasim):
    rec = reduced_fig5(sets[0], out, invasim)
    curves = [{k: c.get(k) for k in ("curve", "a", "a_error", "b", "b_error", "points",
                                     "unsteady_points")} for c in rec["numbers"]["curves"]]
    return (_keep(rec["rows"], "fig5"), rec["images"], {"curves": curves},
            rec["numbers"]["normalisation"])


FUNCS = {"fig3": fig3, "fig4a": fig4a, "fig4b": fig4b, "fig5": fig5}


def record(name, root, out, invasim):
    """The record of one figure from ROOT/paper_<sweep>: rows (with their state), the runs'
    progress and steadiness, the panels."""
    wss = [workspace_path(root, s) for s in SWEEPS[name]]
    present = [os.path.exists(os.path.join(w, "invasim_sweep.json")) for w in wss]
    rec = {"figure": name, "sweeps": SWEEPS[name], "workspaces": [PREFIX + s for s in SWEEPS[name]],
           "missing": [PREFIX + s for s, here in zip(SWEEPS[name], present) if not here],
           "images": [], "numbers": {}, "runs": [], "criteria": verdict.CRITERIA}
    if not present[0]:
        rec["rows"] = _pending_rows(name, "workspace %s not started" % (PREFIX + SWEEPS[name][0]))
        return rec
    all_sets = [sorted(workspace.load_all(w), key=_order) if here else []
                for w, here in zip(wss, present)]
    progresses = [[progress(j) for j in jobs] for jobs in all_sets]
    usable = [[j.provisional() for j, p in zip(jobs, ps) if p["class"] in (DONE, RUNNING)]
              for jobs, ps in zip(all_sets, progresses)]
    flat = [p for ps in progresses for p in ps]
    used = {j.id for js in usable for j in js}
    for p in flat:
        p["steadiness"] = None
    by_id = {j.id: j for js in usable for j in js}
    for p in flat:
        if p["job"] in by_id:
            s = steady.steadiness(by_id[p["job"]])
            p["steadiness"] = {k: s.get(k) for k in ("steady", "drift", "error", "m3", "m4",
                                                     "negligible", "samples")}
    rec["runs"] = [{k: v for k, v in p.items() if k != "sp"} | {
        "name": point_name(p, varied_keys(ps)) if k == 0 else "%s: %s" % (
            rec["workspaces"][k], point_name(p, varied_keys(ps)))}
        for k, ps in enumerate(progresses) for p in ps]
    if not usable[0]:
        rec["rows"] = _pending_rows(name, "no run of %s has written a row yet" % rec["workspaces"][0])
        return rec
    os.makedirs(out, exist_ok=True)
    try:
        rows, images, numbers, extremes = FUNCS[name](usable, out, invasim)
    except (workspace.InputError, ValueError, ZeroDivisionError) as e:
        rows, images, numbers, extremes = [
            verdict.row(sid, "n/a", verdict.NO_DATA, str(e)) for sid in STATEMENTS[name]], [], {}, None
    rows = _without_partial_range(name, _every_statement(name, rows, usable, progresses), progresses,
                                  usable)
    rec["rows"] = _finalise(rows, flat, used)
    rec["numbers"] = numbers
    rec["images"] = images + panels.draw(usable[0], extremes, out, "%s_runs.png" % name, {
        r["job"]: "%s: %s" % (r["name"], progress_text(r)) for r in rec["runs"]})
    return rec


def cost(sweep, progresses, plan_entries):
    """A sweep's cost: core-hours used (the recorded wall_seconds of its runs times the
    threads each was given), the points by state, and the projected total: the done points'
    mean core time for each point not done (scaled by what it has left), or the plan's
    projected cost per point (plan_paper_scale.json, one thread per point) before any is
    done."""
    plan = next((e for e in plan_entries or [] if os.path.splitext(
        os.path.basename(e["spec"]))[0] == sweep), None)
    counts = {c: sum(1 for p in progresses if p["class"] == c)
              for c in (DONE, RUNNING, PENDING, FAILED)}
    used = sum(p["wall_seconds"] * p["threads"] for p in progresses)
    done = [p["wall_seconds"] * p["threads"] for p in progresses
            if p["class"] == DONE and p["wall_seconds"] > 0]
    per_point = (sum(done) / len(done) if done else
                 plan["core_seconds"] / plan["points"] if plan else math.nan)
    points = len(progresses) or (plan["points"] if plan else 0)
    left = 0.0
    for p in progresses:
        if p["class"] != DONE:
            f = p["t"] / p["t_target"] if verdict.finite(p.get("t"), p.get("t_target")) and p["t_target"] > 0 else 0.0
            left += (1 - min(1.0, f)) * per_point
    if not progresses:  # no workspace yet: every point pending; the plan's projection
        counts[PENDING] = points
        left = points * per_point if plan else None
    return {"sweep": sweep, "points": points, "counts": counts, "used_core_hours": used / 3600,
            "projected_core_hours": (used + left) / 3600 if verdict.finite(left) else None,
            "plan_core_hours": plan["core_seconds"] / 3600 if plan else None,
            "per_point_from": "done points" if done else "plan" if plan else "none"}


def cost_record(root, plan_entries):
    """The cost of the paper-scale campaign (DIR/paper_cost.json): per sweep file of this
    machine's list, cost() from its workspace (absent: all pending), and whole_paper()."""
    sweeps = []
    for s in dict.fromkeys(x for names in SWEEPS.values() for x in names):
        ws = workspace_path(root, s)
        jobs = workspace.load_all(ws) if os.path.exists(os.path.join(ws, "invasim_sweep.json")) else []
        sweeps.append(cost(s, [progress(j) for j in jobs], plan_entries))
    return {"sweeps": sweeps, "whole_paper": whole_paper(plan_entries),
            "used_core_hours": sum(c["used_core_hours"] for c in sweeps),
            "projected_core_hours": sum(c["projected_core_hours"] for c in sweeps
                                        if c["projected_core_hours"] is not None),
            "unprojected": [c["sweep"] for c in sweeps if c["projected_core_hours"] is None]}


def whole_paper(plan_entries):
    """The projected cost of every paper-scale sweep file (the whole paper at its scale, on a
    cluster: this machine's list plus fig5_all_curves and fig7_tethered), from the plan."""
    return {"sweeps": [{"spec": e["spec"], "points": e["points"],
                        "core_hours": e["core_seconds"] / 3600} for e in plan_entries or []],
            "core_hours": sum(e["core_seconds"] for e in plan_entries or []) / 3600}
