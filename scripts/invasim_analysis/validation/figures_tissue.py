"""The validation figures of the invasion sweeps (Figs. 3, 4a, 4b; Figs. 7a, 7b:
figures_tethered.py): each function takes
the done jobs of its workspace(s) and the output directory, draws the figure and returns the
figure's record (images, rows of the side-by-side table, steady-state evidence, numbers).
Every temperature axis is the measured cancer-cell temperature in the paper's convention,
2 k_B T_c/(P sigma^3) (x_measured), passive runs included."""

import math
import os
import re
import subprocess

import numpy as np

from .. import normalise, steady, student, workspace
from . import points, relaxation, verdict
from .plotting import T_PAPER, figure, label, log_axis, save

P_DEFAULT = 1.3e-3


def pressure(job):
    return float(job.sp.get("P", P_DEFAULT))


def x_stands_for(job):
    """The paper's k_B T/(P sigma^3) a passive run stands for: its bath is set to kT = x P / 2
    (the sweep files of Figs. 3 and 4a), so that the measured 2 T_c/P is about x."""
    return 2 * float(job.sp.get("kT", 0.0)) / pressure(job)


def x_measured(job, end_fraction=None):
    """2 k_B T_c/(P sigma^3), measured (over the averaging window, or a window of series)."""
    if end_fraction is None:
        return job.mean("kT_c_paper")[0] / pressure(job)
    return steady.window_mean(job, "kT_c_paper", end_fraction) / pressure(job)


def an_over_time(jobs, keys, xfun, fractions, fraction_of=None):
    """A_n of every state point (keys) at several times, normalised together (one set of
    extremes over all points and times, so that curves at different times compare). A time
    is a fraction of each run's rows, or (fraction_of(job, mark) given) a mark each run maps
    to its own fraction (production_fraction: a time t). The values at a time are those of
    the averaging window ending there (steady.window_mean). A run that has not reached a mark
    (fraction_of gives None) has no value there, and a state point none of whose runs has, no
    point. Returns {mark: [points]}, extremes."""
    table, flat = {}, []
    for f in fractions:
        table[f] = []
        for key, reps in workspace.group(jobs, keys).items():
            at = {id(j): (fraction_of(j, f) if fraction_of else f) for j in reps}
            reached = [j for j in reps if at[id(j)] is not None]
            if not reached:
                continue
            p = points.state_point(reached, lambda j: _window_values(j, xfun, at[id(j)]))
            p["key"] = list(key)
            table[f].append(p)
            flat.append(p)
        points.pooled_errors(table[f], "A_gap")
    extremes = normalise.normalise(flat)
    return table, extremes


def _window_values(job, xfun, fraction):
    return {"x": xfun(job, fraction), "A_t": steady.window_mean(job, "A_t", fraction),
            "A_t_max": steady.window_mean(job, "A_t_max", fraction),
            "A_t_error": job.mean("A_t")[1], "A_gap_error": points.gap_error(job, fraction)}


def fmt_time(t):
    """A time as the paper writes it: 1e4, 5e5 (%g below 1000)."""
    if t < 1000:
        return "%g" % t
    m, e = ("%.1e" % t).split("e")
    return "%se%d" % (m.rstrip("0").rstrip("."), int(e))


def production_time(job):
    """The production time of every row of series.csv (time since the production began:
    the state point's quench_steps and equilibrate_steps are before it; dt from the rows)."""
    start = sum(int(job.sp.get(k, 0)) for k in ("quench_steps", "equilibrate_steps"))
    return (job.series["step"] - start) * time_step(job)


def time_step(job):
    """dt of a run: the state point's, else time/step of its first row (time = step x dt)."""
    s = job.series
    return float(job.sp["dt"]) if "dt" in job.sp else float(s["time"][0] / s["step"][0])


def production_fraction(job, t):
    """The fraction of the run's rows written by production time t (at least one row), or
    None for a run whose production has not reached t (its latest window is an earlier time,
    not a value at t)."""
    pt = production_time(job)
    if len(pt) == 0 or pt[-1] < t * (1.0 - 1e-9):
        return None
    return max(1, int(np.searchsorted(pt, t, side="right"))) / len(pt)


def run_time(jobs, fraction):
    """The time at the end of the window `fraction` of the first job's production."""
    t = jobs[0].series["time"]
    return float(t[max(0, int(round(fraction * len(t))) - 1)])


def plot_an_times(ax, table, xlabel, jobs, times=False):
    for f, pts in sorted(table.items()):
        pts = sorted(pts, key=lambda p: p["x"])
        ax.errorbar([p["x"] for p in pts], [p["A_n"] for p in pts],
                    yerr=[p["A_n_error"] if verdict.finite(p["A_n_error"]) else 0 for p in pts],
                    marker="o", capsize=2,
                    label=(r"$t$ = %s $\tau$" % fmt_time(f)) if times else
                    r"$t$ = %.4g $\tau$ (%.0f%% of the run)" % (run_time(jobs, f), 100 * f))
    xs = [p["x"] for pts in table.values() for p in pts]
    if xs and min(xs) > 0:
        log_axis(ax, xs)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(label("A_n", ""))
    ax.axhline(0.5, color="0.7", lw=0.8, ls=":")
    ax.legend(fontsize=8, loc="center left")  # rising curves: the upper left holds labels


def fig3(jobs, out, invasim):
    """A_t/A_t^max over time per temperature, labelled with the paper's value each run stands
    for and the measured one (both 2 T_c/P), and slices of each run's last snapshot."""
    fig, (ax,) = figure()
    ends, captions = [], {}
    for (kT,), reps in workspace.group(jobs, ["kT"]).items():
        j = reps[0]
        s = j.series
        ax.plot(s["time"], s["A_ratio"], label=r"paper %.3g, measured %.3g" % (
            x_stands_for(j), x_measured(j)))
        ends.append((x_measured(j),) + j.mean("A_ratio") + j.mean("A_t") + j.mean("A_t_max")
                    + (x_stands_for(j),))
    ax.set_xlabel(label("time", "tau"))
    ax.set_ylabel(label("A_ratio", ""))
    ax.legend(fontsize=7, title=r"$2 k_B T_c/(P\sigma^3)$", title_fontsize=7)
    images = [save(fig, out, "fig3_At.png")]
    for (kT,), reps in workspace.group(jobs, ["kT"]).items():
        j = reps[0]
        name = "fig3_slice_T%.3g.svg" % x_stands_for(j)
        made = render_slice(j, out, name, invasim)
        images += made
        if made:
            captions[name] = ("slice z = L_z/2 of the last snapshot: the paper's k_B T/(P "
                              "sigma^3) = %.3g, measured %s" % (
                                  x_stands_for(j), verdict.fmt_temperature(x_measured(j))))
    ends.sort()
    rows = []
    if len(ends) >= 2:
        d = ends[-1][1] - ends[0][1]
        e = math.hypot(ends[-1][2], ends[0][2])
        rows.append(verdict.row(
            "fig3_invasion_grows",
            "A_t/A_t^max = %s at %s, %s at %s" % (
                verdict.fmt(ends[0][1], ends[0][2]), verdict.fmt_temperature(ends[0][0]),
                verdict.fmt(ends[-1][1], ends[-1][2]), verdict.fmt_temperature(ends[-1][0])),
            verdict.trend_verdict(d, e),
            "difference %s (criterion: > 2 errors)" % verdict.fmt(d, e)))
        lo = ends[0]
        st = verdict.paper()["fig3_At_min_over_max"]
        rows.append(verdict.row(
            "fig3_At_min_over_max",
            "A_t = %s, A_t^max = %s at the lowest temperature (%s): ratio %s" % (
                verdict.fmt(lo[3], lo[4]), verdict.fmt(lo[5], lo[6]),
                verdict.fmt_temperature(lo[0]), verdict.fmt(lo[1], lo[2])),
            verdict.value_verdict(lo[1], lo[2], st["value"], st["tolerance"]),
            "ours follows the paper's definition of A_t^max; A_n does not depend on the ratio"))
    return {"images": images, "captions": captions, "rows": rows,
            "numbers": {"end_points": ends}, "steadiness": steady.steadiness_summary(jobs)}


def render_slice(job, out, name, invasim):
    """`invasim render` of the job's last snapshot at z = L_z/2 (none without snapshots or
    without a binary, invasim None)."""
    snap_dir = os.path.join(job.path, "snapshots")
    if invasim is None or not os.path.isdir(snap_dir):
        return []
    frames = sorted(f for f in os.listdir(snap_dir) if re.match(r"cells_\d+\.xyz$", f))
    if not frames:
        return []
    z = job.summary.get("box", [0, 0, 0])[2] / 2
    subprocess.run([invasim, "render", os.path.join(snap_dir, frames[-1]), "--slice",
                    "z=%g" % z, "-o", os.path.join(out, name)], check=True,
                   stdout=subprocess.DEVNULL)
    return [name]


def fig4a(jobs, out, invasim, *relaxation_sets, times=None):
    """A_n against the measured 2 T_c/P at three times (a quarter, half and all of the run;
    or the production times `times`, the paper's t = 1e4, 1e5, 5e5); the midpoint's move
    between the first and the last, and T_g at the last; with the relaxation sweeps' jobs,
    T_g where tau_r diverges (relaxation.py)."""
    fractions = tuple(times) if times else (0.25, 0.5, 1.0)
    table, extremes = an_over_time(jobs, ["kT"], x_measured, fractions,
                                   production_fraction if times else None)
    fig, (ax,) = figure()
    plot_an_times(ax, table, T_PAPER, jobs, times=bool(times))
    st = verdict.paper()["fig4a_Tg"]
    ax.axvline(st["value"], color="0.4", ls="--", lw=0.8)
    ax.text(st["value"], 0.98, r" paper's $T_g$", fontsize=7, va="top", color="0.3",
            transform=ax.get_xaxis_transform())
    images = [save(fig, out, "fig4a_An.png")]
    mids = {f: points.crossing([p["x"] for p in pts], [p["A_n"] for p in pts])
            for f, pts in table.items()}
    errs = {f: points.crossing_log_error([p["x"] for p in pts], [p["A_n"] for p in pts],
                                       [p["A_n_error"] for p in pts]) for f, pts in table.items()}
    bounds = {f: points.crossing_bound([p["x"] for p in pts], [p["A_n"] for p in pts],
                                       [p["A_n_error"] for p in pts]) for f, pts in table.items()}
    first, last = fractions[0], fractions[-1]
    # A curve wholly below 1/2 at the first time (or above it at the last) bounds its
    # midpoint by the scanned range's edge: the shift is then at least the one to that edge.
    start = mids[first] if verdict.finite(mids[first]) else (
        bounds[first][1] if bounds[first][0] == "above" else math.nan)
    end = mids[last] if verdict.finite(mids[last]) else (
        bounds[last][1] if bounds[last][0] == "below" else math.nan)
    moves = start > end if verdict.finite(start, end) else None
    shift = math.log10(start / end) if moves is not None else math.nan
    shift_err = math.hypot(*(e if verdict.finite(e) else 0.0 for e in (errs[first], errs[last])))
    end_err = (mids[last] * math.log(10) * errs[last] if verdict.finite(mids[last], errs[last])
               else math.nan)
    # The crossings' errors come from A_n errors of pooled replicates: their fewest degrees of
    # freedom set the criterion's factor (student.factor).
    dof_last = points.least_dof(table[last])
    dof_both = points.least_dof(table[first] + table[last])
    rows = [
        verdict.row("fig4a_moves_left",
                    "midpoint (A_n = 1/2) at 2T_c/P = %s" % ", ".join(
                        "%s (%s)" % (midpoint_text(mids[f], bounds[f]),
                                     ("t = %s" % fmt_time(f)) if times else
                                     "t = %.0f%%" % (100 * f)) for f in fractions),
                    verdict.trend_verdict(shift, shift_err, dof_both),
                    "log10 of the midpoint's ratio, %s over the end: %s%s (> 2 errors; "
                    "the error from the A_n errors and the slope at the crossing)"
                    % ("t = %s" % fmt_time(first) if times else "first quarter",
                       "at least " if not verdict.finite(mids[first], mids[last]) else "",
                       verdict.fmt(shift, shift_err))),
        verdict.row("fig4a_Tg", "midpoint at the end%s: %s" % (
                        " (t = %s)" % fmt_time(last) if times else "",
                        verdict.fmt_temperature(mids[last], end_err)),
                    verdict.log_verdict(mids[last], end_err, st["value"], st["log_factor"], moves,
                                        dof_last),
                    "2T_c/P within a factor %g of %g (+ 2 errors), the paper's convention"
                    % (st["log_factor"], st["value"])),
        tc_equals_ta_row("fig4a_Tc_equals_Ta", jobs, ["kT"])]
    if any(relaxation_sets):
        pts = relaxation.relaxation_points(relaxation_sets, x_measured)
        row = relaxation.tg_row(pts, verdict.paper()["fig4a_Tg_relaxation"])
        fig, (ax,) = figure()
        relaxation.plot(ax, pts, row["data"], st["value"])
        images.append(save(fig, out, "fig4a_tau_r.png"))
        rows.append(row)
    return {"images": images, "rows": rows,
            "numbers": {"midpoints": {str(f): m for f, m in mids.items()},
                        "normalisation": extremes, "points": table},
            "steadiness": steady.steadiness_summary(jobs)}


def midpoint_text(mid, bound):
    """A midpoint, or the bound crossing_bound gives where the curve does not cross 1/2."""
    if verdict.finite(mid) or bound[0] is None:
        return verdict.fmt(mid)
    return "%s %s (A_n %s 1/2 at every temperature run)" % (
        bound[0], verdict.fmt(bound[1]), "<" if bound[0] == "above" else ">")


def tc_equals_ta_row(sid, jobs, keys):
    """The passive runs' T_c/T_a (summary.json) against 1: every state point within the
    statement's tolerance (2 %, the precision docs/model.md's bath table asks of an
    equilibrated bath) + 2 errors (replicate scatter, or the run's own error)."""
    tolerance = verdict.paper()[sid]["tolerance"]
    pts = []
    for key, reps in workspace.group(jobs, keys).items():
        p = points.state_point(reps, lambda j: {
            "r": j.mean("T_c_over_T_a")[0], "r_error": j.mean("T_c_over_T_a")[1],
            "x": x_measured(j)})
        pts.append(p)
    each = [verdict.value_verdict(p["r"], p["r_error"], 1.0, tolerance) for p in pts]
    worst = max(pts, key=lambda p: abs(p["r"] - 1) if verdict.finite(p["r"]) else -1)
    return verdict.row(
        sid, "T_c/T_a = %s; farthest from 1: %s at %s; %d of %d state points within" % (
            ", ".join(verdict.fmt(p["r"], p["r_error"]) for p in pts),
            verdict.fmt(worst["r"], worst["r_error"]), verdict.fmt_temperature(worst["x"]),
            each.count(verdict.AGREES), len(pts)),
        verdict.all_of(each), "every passive state point |T_c/T_a - 1| <= %g + 2 errors" % tolerance,
        data={"points": pts})


def fig4b(jobs, out, invasim, inset_jobs=None):
    fractions = (0.25, 0.5, 1.0)
    table, extremes = an_over_time(jobs, ["f0"], x_measured, fractions)
    fig, axes = figure(3 if inset_jobs else 1)
    plot_an_times(axes[0], table, T_PAPER, jobs)
    end = sorted(table[1.0], key=lambda p: p["x"])
    st = verdict.paper()["fig4b_An_at_0.3"]
    for ax in axes:  # the paper's steady A_n ~ 0.55 (its black dashed line)
        ax.axhline(st["value"], color="k", ls="--", lw=0.9)
    axes[0].axvline(st["at"], color="0.5", ls=":", lw=0.8)
    an03 = points.interpolate_log([p["x"] for p in end], [p["A_n"] for p in end], st["at"])
    err03 = float(np.nanmax([p["A_n_error"] for p in end])) if end else math.nan
    # The row rests on the two end-of-run state points that bracket 0.3 (the interpolation's).
    jobs_by_id = {j.id: j for j in jobs}
    below = [p for p in end if p["x"] <= st["at"]]
    above = [p for p in end if p["x"] > st["at"]]
    bracket = ([below[-1]] if below else []) + ([above[0]] if above else [])
    unsteady03 = steady.unsteady_points(bracket, jobs_by_id, lambda p: "f0 = %g (2T_c/P = %.3g)"
                                      % (p["key"][0], p["x"])) if len(bracket) == 2 else []
    mids = {f: points.crossing([p["x"] for p in pts], [p["A_n"] for p in pts])
            for f, pts in table.items()}
    sw = verdict.paper()["fig4b_weak_time"]
    ratio = mids[0.5] / mids[1.0] if verdict.finite(mids[0.5], mids[1.0]) else math.nan
    rows = [verdict.row("fig4b_An_at_0.3", "A_n = %s at 2T_c/P = %g (T_c/P = %g; interpolated "
                        "between the end-of-run state points at 2T_c/P = %s)" % (
                            verdict.fmt(an03, err03), st["at"], st["at"] / 2,
                            " and ".join(verdict.fmt(p["x"]) for p in bracket) or "n/a"),
                        verdict.value_verdict(an03, err03, st["value"], st["tolerance"],
                                              dof=points.least_dof(end)),
                        "|ours - 0.55| <= 0.1 + 2 errors; rests on the two state points "
                        "bracketing 2T_c/P = 0.3, each steady (all its runs)",
                        unsteady=unsteady03),
            verdict.row("fig4b_weak_time", "midpoint at half time / at the end = %s" %
                        verdict.fmt(ratio),
                        verdict.log_verdict(ratio, math.nan, 1.0, sw["log_factor"]),
                        "within a factor %g" % sw["log_factor"])]
    numbers = {"midpoints": {str(f): m for f, m in mids.items()}, "normalisation": extremes,
               "A_n_at_0.3": an03, "points": table}
    images_extra = []
    evidence = steady.steadiness_summary(jobs + (inset_jobs or []))
    if inset_jobs:
        by_start = {}
        for (start,), reps in workspace.group(inset_jobs, ["start"]).items():
            vals, mean, err, dof = points.runs_a_n(reps, extremes)
            by_start[start] = (mean, err, float(np.mean([x_measured(j) for j in reps])), dof)
            axes[1].plot([start] * len(vals), vals, "o", alpha=0.6)
            axes[1].errorbar([start], [by_start[start][0]], yerr=[by_start[start][1] if
                             verdict.finite(by_start[start][1]) else 0], fmt="s",
                             color="k", capsize=3)
        axes[1].set_ylabel(label("A_n", ""))
        axes[1].set_xlabel("initial placement (start)")
        axes[1].set_title("inset: de-mixed vs mixed start", fontsize=9)
        # The paper's inset: A_n(t) from both starts (each run's series, normalised like the
        # state points; the dashed line marks the start of the averaged last half).
        colours = {"demixed": "C0", "mixed": "C3"}
        for j in inset_jobs:
            ser = j.series
            trace = [normalise.scale_like({"A_t": a, "A_t_max": m}, extremes)["A_n"]
                     for a, m in zip(ser["A_t"], ser["A_t_max"])]
            start = str(j.sp.get("start"))
            axes[2].plot(ser["time"], trace, lw=0.8, color=colours.get(start, "k"),
                         label=start if start not in axes[2].get_legend_handles_labels()[1] else None)
        t_end = max(float(j.series["time"][-1]) for j in inset_jobs)
        t_prod = min(float(j.series["time"][0]) for j in inset_jobs)
        axes[2].axvline(t_prod + 0.5 * (t_end - t_prod), color="0.6", ls="--", lw=0.8)
        axes[2].set_xlabel(label("time", "tau"))
        axes[2].set_ylabel(label("A_n", ""))
        axes[2].set_title("inset: A_n(t) from both starts", fontsize=9)
        axes[2].legend(fontsize=7)
        if "demixed" in by_start and "mixed" in by_start:
            d = by_start["mixed"][0] - by_start["demixed"][0]
            e = math.hypot(by_start["mixed"][1], by_start["demixed"][1])
            dof = student.welch_dof([(by_start[k][1], by_start[k][3]) for k in by_start])
            si = verdict.paper()["fig4b_inset_starts"]
            rows.append(verdict.row(
                "fig4b_inset_starts", "A_n = %s (de-mixed), %s (mixed) at %s" % (
                    verdict.fmt(*by_start["demixed"][:2]), verdict.fmt(*by_start["mixed"][:2]),
                    verdict.fmt_temperature(by_start["demixed"][2])),
                verdict.value_verdict(d, e, si["value"], si["tolerance"], dof=dof),
                "difference %s; |difference| <= 0.1 + 2 errors; rests on every run of the "
                "inset's state point, each steady (its starts' agreement, the criterion's second "
                "half, is what this row tests)" % verdict.fmt(d, e),
                unsteady=steady.unsteady_runs(inset_jobs)))
        numbers["inset"] = by_start
    images = [save(fig, out, "fig4b_An.png")] + images_extra
    return {"images": images, "rows": rows, "numbers": numbers, "steadiness": evidence}
