"""The validation figures of the tethered tissue (Figs. 7a and 7b: the same statements at two
tau_p and beta): A_n per K_ecm against the measured 2 T_c/P, normalised by the K_ecm = 0
sweep, with each K_ecm's plateau A_n^max dashed; the plateau and the onset against K_ecm.
Same contract as figures_tissue.py."""

import math

import matplotlib
import numpy as np
from matplotlib.lines import Line2D

from .. import normalise, steady, student, workspace
from . import points, verdict
from .figures_tissue import x_measured
from .plotting import T_PAPER, figure, label, log_axis, save, state


def _sorted_curve(xs, ans, errs):
    """One K_ecm's curve sorted by temperature, a missing error counting as 0 (as onset() and
    its error take them)."""
    order = np.argsort(xs)
    x, y = np.asarray(xs, float)[order], np.asarray(ans, float)[order]
    e = np.array([v if verdict.finite(v) else 0.0 for v in np.asarray(errs, float)[order]])
    return x, y, e


def _onset_bracket(x, y, e):
    """Where onset() places the crossing on a sorted curve: (k, t, interpolated), k the first
    point above the level y[0] + 2 hypot(e[0], e[k]), t the fraction of the log bracket
    (x[k-1], x[k]) where the line between them reaches that level, and whether the line placed
    it (False: the line reaches the level outside the bracket, so t is clamped to 0 or 1 -
    y[k-1] already above this level though not above its own, or y[k-1] above y[k] - or
    there is no line in log x). None when no point rises above its level."""
    for k in range(1, len(x)):
        level = y[0] + 2 * math.hypot(e[0], e[k])
        if y[k] > level:
            if x[k - 1] <= 0 or y[k] == y[k - 1]:
                return k, 1.0, False
            t = (level - y[k - 1]) / (y[k] - y[k - 1])
            return k, min(1.0, max(0.0, t)), 0.0 <= t <= 1.0
    return None


def onset(xs, ans, errs):
    """Where A_n first rises above zero: the lowest temperature whose A_n exceeds the
    lowest-temperature value by more than 2 combined errors, log-interpolated to that level
    from the point before it; nan when no point does (errors: a missing one counts as 0)."""
    x, y, e = _sorted_curve(xs, ans, errs)
    found = _onset_bracket(x, y, e)
    if found is None:
        return math.nan
    k, t, _ = found
    if t >= 1.0:  # no line to interpolate on
        return float(x[k])
    return float(10 ** (math.log10(x[k - 1]) + t * (math.log10(x[k]) - math.log10(x[k - 1]))))


def onset_log_error(xs, ans, errs):
    """The error of log10 onset(xs, ans, errs). Where the line between the bracketing points
    places the crossing, the A_n errors propagated through that interpolation, as
    points.crossing_log_error does for a midpoint: log10 onset = log10 x[k-1] + w t with
    t = (y[0] + 2 e_c - y[k-1])/(y[k] - y[k-1]), so the lowest point (it sets the level) and
    the two bracketing ones enter, each over the slope (y[k] - y[k-1])/w. Where it does not
    (onset() took a grid point), the crossing is known only to its bracket: the bracket's log
    width w over sqrt(12), the standard deviation of a position uniform in it. nan without
    an onset or without a log bracket (x[k-1] <= 0)."""
    x, y, e = _sorted_curve(xs, ans, errs)
    found = _onset_bracket(x, y, e)
    if found is None or x[found[0] - 1] <= 0:
        return math.nan
    k, t, interpolated = found
    w = math.log10(x[k]) - math.log10(x[k - 1])
    if not interpolated:
        return float(w / math.sqrt(12))
    if k == 1:  # y[0] is both the baseline and the bracket's foot: t = 2 e_c/(y[1] - y[0])
        # The data say only that the onset lies in the first bracket: the interpolation's
        # small error would claim more, so the bracket's own spread is the floor.
        a_err = t * math.hypot(e[0], e[1])
        return float(max(w * a_err / (y[1] - y[0]), w / math.sqrt(12)))
    a_err = math.sqrt(e[0] ** 2 + ((1 - t) * e[k - 1]) ** 2 + (t * e[k]) ** 2)
    return float(w * a_err / (y[k] - y[k - 1]))


def onset_ratios(onsets, within, dofs=None):
    """onset(K_ecm)/onset(0) with its error and verdict for each K_ecm. onsets: [(K_ecm, x,
    log10 error)], K_ecm = 0 first; dofs: per onset the degrees of freedom of its curve's
    A_n errors (None: many). The ratio's log10 error is the two onsets' in quadrature, with
    their Welch-Satterthwaite degrees of freedom; verdict.log_verdict takes it in the ratio's
    units (r ln10 times it). Returns [(K_ecm, ratio, log10 error, verdict)]."""
    dofs = dofs or [None] * len(onsets)
    _, base, base_err = onsets[0]
    out = []
    for (k, x, err), dof in zip(onsets[1:], dofs[1:]):
        r = x / base if verdict.finite(x, base) and base > 0 else math.nan
        e = math.hypot(err, base_err) if verdict.finite(err, base_err) else math.nan
        ratio_dof = student.welch_dof([(err, dof), (base_err, dofs[0])]) if verdict.finite(
            err, base_err) else None
        out.append((k, r, e, verdict.log_verdict(r, r * math.log(10) * e if verdict.finite(r, e)
                                                 else math.nan, 1.0, within, dof=ratio_dof)))
    return out


def fmt_log(v, log_err):
    """A positive number with its error in log10: "0.354 (+- 0.054 in log10)"."""
    if not verdict.finite(log_err):
        return verdict.fmt(v)
    return "%s (+- %.2g in log10)" % (verdict.fmt(v), log_err)


def fig7a(jobs, out, invasim):
    return fig7(jobs, out, "fig7a")


def fig7b(jobs, out, invasim):
    return fig7(jobs, out, "fig7b")


def fig7(jobs, out, name):
    """Fig. 7a or 7b (the same statements at another tau_p and beta): A_n per K_ecm,
    normalised by the K_ecm = 0 sweep; the plateau A_n^max and the onset against K_ecm."""
    pts = []
    for (k, f0), reps in workspace.group(jobs, ["K_ecm", "f0"]).items():
        p = points.state_point(reps, lambda j: {"x": x_measured(j), "A_t": j.mean("A_t")[0],
                                              "A_t_max": j.mean("A_t_max")[0],
                                              "A_t_error": j.mean("A_t")[1]})
        p["K_ecm"] = float(k)
        pts.append(p)
    for k in {p["K_ecm"] for p in pts}:
        points.pooled_errors([p for p in pts if p["K_ecm"] == k], "A_gap")
    free = [p for p in pts if p["K_ecm"] == 0.0]
    if not free:
        raise workspace.InputError("%s: no K_ecm = 0 points to normalise by" % name)
    extremes = normalise.normalise(free)
    for p in pts:
        if p["K_ecm"] != 0.0:
            normalise.scale_like(p, extremes)
    fig, axes = figure(2)
    jobs_by_id = {j.id: j for j in jobs}
    plateau, onsets = [], []
    # The state points each row rests on: the plateau row on each K_ecm's top point, the onset
    # row on each K_ecm's points up to its onset (all of them where it has none).
    plateau_points, onset_points = [], []
    ks = sorted({p["K_ecm"] for p in pts})
    greens = [matplotlib.cm.Greens(0.45 + 0.5 * (1 - i / max(1, len(ks) - 1))) for i in range(len(ks))]
    for i, k in enumerate(ks):
        c = sorted((p for p in pts if p["K_ecm"] == k), key=lambda p: p["x"])
        errs = [p["A_n_error"] if verdict.finite(p["A_n_error"]) else 0 for p in c]
        colour = "k" if k == 0 else greens[i]
        axes[0].errorbar([p["x"] for p in c], [p["A_n"] for p in c], yerr=errs, marker="o",
                         capsize=2, color=colour, label=state({"K_ecm": "%g" % k}))
        unsteady = [p for p in c if not steady.point_steadiness([jobs_by_id[i] for i in p["jobs"]])[0]]
        axes[0].plot([p["x"] for p in unsteady], [p["A_n"] for p in unsteady], "o", mfc="white",
                     mec=colour, zorder=3)  # hollow: not steady
        top = max(c, key=lambda p: p["A_n"])
        plateau.append((k, top["A_n"], top["A_n_error"]))
        axes[0].axhline(top["A_n"], color=colour, ls="--", lw=0.8)  # this K_ecm's A_n^max
        curve = ([p["x"] for p in c], [p["A_n"] for p in c], errs)
        onsets.append((k, onset(*curve), onset_log_error(*curve)))
        plateau_points.append(top)
        reached = [p for p in c if not verdict.finite(onsets[-1][1]) or p["x"] <= onsets[-1][1]]
        onset_points += reached + [p for p in c if p not in reached][:1]
    log_axis(axes[0], [p["x"] for p in pts])
    axes[0].set_xlabel(T_PAPER)
    axes[0].set_ylabel(label("A_n", "") + "\n" + r"(normalised by $K_\mathrm{ecm}$ = 0)")
    handles, _ = axes[0].get_legend_handles_labels()
    handles.append(Line2D([], [], marker="o", ls="", mfc="white", mec="k", label="not steady"))
    axes[0].legend(handles=handles, fontsize=7, title="dashed: each $A_n^\\mathrm{max}$",
                   title_fontsize=7)
    axes[1].errorbar([k for k, _, _ in plateau], [v for _, v, _ in plateau],
                     yerr=[e if verdict.finite(e) else 0 for _, _, e in plateau], marker="s",
                     color="k")
    axes[1].set_xlabel(label("K_ecm", "eps_c/sigma^2"))
    axes[1].set_ylabel(r"plateau $A_n^\mathrm{max}$ (dimensionless)")
    axes[1].set_title("inset: plateau against $K_\\mathrm{ecm}$", fontsize=9)
    images = [save(fig, out, name + "_An.png")]
    d = plateau[0][1] - plateau[-1][1]
    ends = [(x if verdict.finite(x) else 0.0, p.get("A_n_dof"))
            for x, p in ((plateau[0][2], plateau_points[0]), (plateau[-1][2], plateau_points[-1]))]
    e, d_dof = math.hypot(*(v for v, _ in ends)), student.welch_dof(ends)
    so = verdict.paper()[name + "_onset"]
    ratios = onset_ratios(onsets, so["log_factor"],
                          [points.least_dof([p for p in pts if p["K_ecm"] == k]) for k, _, _ in onsets])
    point_name = lambda p: "K_ecm = %g, 2T_c/P = %.3g" % (p["K_ecm"], p["x"])  # noqa: E731
    rows = [verdict.row(name + "_plateau_falls", "A_n^max = " + ", ".join(
                "%s (K_ecm = %g)" % (verdict.fmt(v, e_), k) for k, v, e_ in plateau),
                verdict.trend_verdict(d, e, d_dof) if len(plateau) > 1 else verdict.NO_DATA,
                "A_n^max(K_ecm = 0) - A_n^max(largest K_ecm) = %s (> 2 errors); rests on each "
                "K_ecm's top state point, each steady" % verdict.fmt(d, e),
                unsteady=steady.unsteady_points(plateau_points, jobs_by_id, point_name)),
            verdict.row(name + "_onset", "onset at 2T_c/P = " + ", ".join(
                "%s (K_ecm = %g)" % (fmt_log(x, e_), k) for k, x, e_ in onsets),
                verdict.all_of([v for _, _, _, v in ratios]) if ratios else verdict.NO_DATA,
                "the onset is where A_n first exceeds its lowest-temperature value by more than "
                "2 combined errors (log-interpolated), its error in log10 that of the "
                "interpolation (the A_n errors of the lowest and the two bracketing points over "
                "the slope), or the bracket's log width/sqrt(12) where it takes a grid point; "
                "onset(K_ecm)/onset(0) = %s, each within a factor %g (+ 2 errors in log10); "
                "rests on each K_ecm's state points up to its onset (and the one that crosses), "
                "each steady" % (", ".join("%s (K_ecm = %g)" % (fmt_log(r, e_), k)
                                           for k, r, e_, _ in ratios) or "n/a", so["log_factor"]),
                data={"onset": onsets, "ratio": [r[:3] for r in ratios]},
                unsteady=steady.unsteady_points(onset_points, jobs_by_id, point_name))]
    return {"images": images, "rows": rows,
            "numbers": {"plateau": plateau, "onset": onsets,
                        "onset_ratio": [r[:3] for r in ratios], "normalisation": extremes,
                        "points": pts}, "steadiness": steady.steadiness_summary(jobs)}
