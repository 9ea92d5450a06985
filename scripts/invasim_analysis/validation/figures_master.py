"""Fig. 5 of the validation page, the master curve, laid out as the paper's: (a) A_n against
the measured 2 T_c/P, one colour per tau_p and one marker per beta, the passive curve as filled
black diamonds, the fits as lines; (b) the collapse on E_c^b; (c) the paper's inset, the fitted
a against c1 (1 + c2 beta/P) tau_g/tau_d with the line a = that. Same contract as
figures_tissue.py. A curve with a state point that is not steady is drawn hollow and enters
neither the collapse nor the fit of a; a curve whose midpoint a is not located (b <= 0, no
rise, outside the temperatures; fits.midpoint_not_located) is drawn as data only."""

import math
import textwrap

import numpy as np
from matplotlib.lines import Line2D

from .. import normalise, steady, workspace
from . import points, verdict
from .figures_tissue import tc_equals_ta_row, x_measured
from .plotting import T_PAPER, figure, label, log_axis, save

from ..errors import InputError as FitError
from ..master_curve import fits
from ..master_curve.analysis import build_points

MIN_ERROR = 1e-3  # floor of a state point's A_n error in the fits (as master_curve.py)
POOL = 1  # neighbours on each side whose replicate variance is pooled (master_curve.py --pool)
TAU_G = 5.0  # tau_gamma = m/gamma of the protocols (docs/model.md), the tau_d of tau_p -> 0
P_DEFAULT = 1.3e-3
# The paper's Fig. 5(a): colours by tau_p, markers by beta.
TAU_P_COLOURS = {0.02: "tab:purple", 25.0: "tab:blue", 250.0: "magenta", 2500.0: "tab:orange"}
BETA_MARKERS = {1e-4: "^", 1e-3: "s", 1e-2: "D"}
OTHER_COLOURS = ["tab:green", "tab:brown", "tab:cyan", "tab:olive"]


def _near(table, value, default):
    """table's entry for a float key equal to value up to rounding."""
    for k, v in table.items():
        if value > 0 and abs(math.log10(value / k)) < 1e-6:
            return v
    return default


def colour(tau_p):
    others = OTHER_COLOURS[hash(float(tau_p)) % len(OTHER_COLOURS)]
    return _near(TAU_P_COLOURS, float(tau_p), others)


def marker(beta):
    return _near(BETA_MARKERS, float(beta), "o")


def _curve_points(jobs, keys):
    out = {}
    for key, reps in workspace.group(jobs, keys + ["f0", "kT"]).items():
        p = points.state_point(reps, lambda j: {
            "x": x_measured(j), "A_t": j.mean("A_t")[0], "A_t_max": j.mean("A_t_max")[0],
            "A_t_error": j.mean("A_t")[1], "tau_d": j.scalar("tau_d"),
            "T_c_over_T_a": j.mean("T_c_over_T_a")[0],
            "T_c_over_T_a_error": j.mean("T_c_over_T_a")[1]})
        out.setdefault(key[:len(keys)], []).append(p)
    return out


def _pooled_errors(pts, jobs_by_id, extremes):
    """The A_n errors of a curve's state points as master_curve.py computes them
    (analysis.build_points): the replicate variance pooled with POOL neighbours on each side
    along x, so that two replicates give usable weights (the standard error of two values
    alone can be near zero by chance and then dominates a fit), floored at MIN_ERROR."""
    groups = [[jobs_by_id[i] for i in p["jobs"]] for p in pts]
    rows = [j for g in groups for j in g]
    scaled = [normalise.scale_like({"A_t": j.mean("A_t")[0], "A_t_max": j.mean("A_t_max")[0],
                               "A_t_error": j.mean("A_t")[1]}, extremes) for j in rows]
    idx, k = [], 0
    for g in groups:
        idx.append(np.arange(k, k + len(g)))
        k += len(g)
    out = build_points(idx, np.array([x_measured(j) for j in rows]),
                       np.array([q["A_n"] for q in scaled]),
                       np.array([q["A_n_error"] for q in scaled]),
                       [(math.nan, math.nan)] * len(rows), MIN_ERROR, POOL)
    error_of = {tuple(o["rows"]): o["A_n_error"] for o in out}
    return [error_of[tuple(ix)] for ix in idx]


def _run_time(jobs):
    """The production run's length t of jobs (their longest), for labels."""
    return max(int(j.sp.get("steps", j.scalar("steps"))) * float(j.sp.get("dt", 0.05))
               for j in jobs)


def _curves(jobs, passive_jobs, long_jobs, extra_jobs):
    """{key: points} of every curve ((beta, tau_p), or ("passive", beta)), with the curves of
    long_jobs replacing those of jobs (returned apart) and extra_jobs' curves added."""
    curves = _curve_points(jobs, ["beta", "tau_p"])
    for key, pts in (_curve_points(extra_jobs, ["beta", "tau_p"]).items() if extra_jobs else []):
        curves.setdefault(key, []).extend(pts)
    replaced = {}
    for key, pts in (_curve_points(long_jobs, ["beta", "tau_p"]).items() if long_jobs else []):
        if key in curves:
            replaced[key] = curves[key]
        curves[key] = pts
    for key, pts in (_curve_points(passive_jobs, ["beta"]).items() if passive_jobs else []):
        curves[("passive", key[0])] = pts
    return curves, replaced


def _fit_curve(key, pts, plain, jobs_by_id, extremes):
    """One curve's record: its points, steadiness, sigmoid fit and why it is left out of the
    collapse (in_collapse) and of the fit of a (excluded_from_scale_fit)."""
    sig = _pooled_errors(pts, jobs_by_id, extremes)
    for p, e in zip(pts, sig):
        p["A_n_error"] = e
        p["steady"] = steady.point_steadiness([jobs_by_id[i] for i in p["jobs"]])[0]
    entry = {"curve": plain, "key": list(key), "points": len(pts),
             "unsteady_points": ["2T_c/P = %.3g" % p["x"] for p in pts if not p["steady"]],
             "beta": key[1] if key[0] == "passive" else key[0]}
    xs, ys = [p["x"] for p in pts], [p["A_n"] for p in pts]
    try:
        if min(xs) <= 0:
            raise FitError("a non-positive temperature")
        entry.update(fits.fit_sigmoid(xs, ys, sig, plain))
    except FitError as e:
        entry["why_no_fit"] = str(e)
    taus = [p["tau_d"] for p in pts if verdict.finite(p["tau_d"]) and p["tau_d"] > 0]
    entry["tau_d"] = float(np.mean(taus)) if taus else math.nan
    entry["tau_d_rel_error"] = (float(np.std(taus, ddof=1) / math.sqrt(len(taus)) /
                                      np.mean(taus)) if len(taus) > 1 else 0.0)
    if "a" not in entry:
        why = "no sigmoid fit: " + entry["why_no_fit"]
    elif entry["unsteady_points"]:
        why = "not steady at " + ", ".join(entry["unsteady_points"])
    else:
        why = fits.midpoint_not_located(entry["a"], entry["a_error"], entry["b"],
                                        entry["b_error"], xs, ys, sig)
    entry["in_collapse"] = why is None
    if key[0] == "passive":
        why = why or "passive (no tau_d of self-propulsion)"
    elif why is None and not verdict.finite(entry["tau_d"]):
        why = "no finite tau_d"
    entry["excluded_from_scale_fit"] = why
    return entry


def _plot_curves(axes, curves, fitted, replaced):
    """Panels (a) and (b): the data (hollow where not steady), the fits and the collapse of
    the curves whose midpoint is located."""
    for key, pts in replaced.items():
        pts.sort(key=lambda p: p["x"])
        axes[0].plot([p["x"] for p in pts], [p["A_n"] for p in pts], marker=marker(key[0]),
                     ls="none", mfc="none", ms=4, color="0.6")
    for (key, pts), f in zip(curves.items(), fitted):
        passive = key[0] == "passive"
        c, m = ("k", "D") if passive else (colour(key[1]), marker(key[0]))
        for p in pts:
            axes[0].errorbar([p["x"]], [p["A_n"]], yerr=[p["A_n_error"]], marker=m, ms=5,
                             color=c, mfc=c if p["steady"] else "none", ls="none", capsize=2)
        if f["in_collapse"]:
            xs = np.logspace(math.log10(pts[0]["x"]), math.log10(pts[-1]["x"]), 100)
            axes[0].plot(xs, fits.sigmoid(xs, f["a"], f["b"]), color=c, lw=1)
            axes[1].plot([(p["x"] / f["a"]) ** f["b"] for p in pts], [p["A_n"] for p in pts],
                         marker=m, ls="none", color=c, ms=5)
    log_axis(axes[0], [p["x"] for pts in curves.values() for p in pts])
    axes[0].set_xlabel(T_PAPER, fontsize=8)
    axes[0].set_ylabel(label("A_n", ""))
    axes[0].set_title("(a) $A_n$, fits (Eq. (15)) as lines", fontsize=9)
    e = np.logspace(-2, 2, 100)
    axes[1].plot(e, fits.sigmoid(e, 1.0, 1.0), "k-", lw=1)  # the collapse: a = b = 1
    axes[1].set_xscale("log")
    axes[1].set_xlabel(r"$E_c^b = (x/a)^b$, $x = 2k_BT_c/(P\sigma^3)$ (dimensionless)", fontsize=8)
    axes[1].set_ylabel(label("A_n", ""))
    axes[1].set_title("(b) collapse, line $(\\tanh[\\log_{10} E_c^b] + 1)/2$", fontsize=9)


def _plot_inset(ax, usable, scale):
    """Panel (c), the paper's inset: a against c1 (1 + c2 beta/P) tau_g/tau_d, line a = that."""
    ax.set_title("(c) inset: $a$ against the fitted form", fontsize=9)
    ax.set_xlabel(r"$c_1 (1 + c_2 \beta/(P\sigma^3))\,\tau_\gamma/\tau_d$ (dimensionless)",
                  fontsize=8)
    ax.set_ylabel(r"fitted $a$ (dimensionless)")
    if not scale or "c1" not in scale:
        why = textwrap.shorten((scale or {}).get("why", ""), 160)
        ax.text(0.5, 0.5, "no fit of a:\n" + textwrap.fill(why, 42), ha="center",
                va="center", fontsize=7, transform=ax.transAxes)
        return
    model = [_model(f, scale) for f in usable]
    for f, m in zip(usable, model):
        ax.errorbar([m], [f["a"]], yerr=[f["a_error"]], marker=marker(f["beta"]),
                    color=colour(f["key"][1]), ls="none", capsize=2)
    lo, hi = min(model + [f["a"] for f in usable]) / 2, max(model + [f["a"] for f in usable]) * 2
    ax.plot([lo, hi], [lo, hi], "k-", lw=1)
    log_axis(ax, model, "x")
    log_axis(ax, [f["a"] for f in usable], "y")


def _model(f, scale):
    """c1 (1 + c2 beta/P) tau_g/tau_d of a curve with the fitted c1, c2 (c2 = 0 if not fitted)."""
    return scale["c1"] * (1 + (scale.get("c2") or 0.0) * f["beta"] / P_DEFAULT) * TAU_G / f["tau_d"]


def _legend(fig, curves, replaced):
    """The key, outside the data: colours by tau_p, markers by beta, the passive curve, the
    hollow (not steady) and grey (replaced by longer runs) points, the fit line."""
    taus = sorted({k[1] for k in curves if k[0] != "passive"})
    betas = sorted({k[0] for k in curves if k[0] != "passive"})
    h = [Line2D([], [], color=colour(t), lw=6, label=r"$\tau_p$ = %g" % t) for t in taus]
    h += [Line2D([], [], color="0.3", marker=marker(b), ls="none", label=r"$\beta$ = %g" % b)
          for b in betas]
    if any(k[0] == "passive" for k in curves):
        h.append(Line2D([], [], color="k", marker="D", ls="none", label="passive"))
    h.append(Line2D([], [], color="0.3", marker="o", mfc="none", ls="none", label="not steady"))
    if replaced:
        h.append(Line2D([], [], color="0.6", marker="o", mfc="none", ms=4, ls="none",
                        label="shorter runs (replaced)"))
    h.append(Line2D([], [], color="0.3", lw=1, label="fit, Eq. (15)"))
    fig.legend(handles=h, loc="center right", fontsize=7, frameon=False)


def fig5(jobs, out, invasim, passive_jobs=None, long_jobs=None, extra_jobs=None):
    """long_jobs (fig5_long.lua): curves run longer; each replaces the curve of the same beta
    and tau_p of jobs, which is drawn for comparison (grey, hollow) but not fitted.
    extra_jobs (fig5_extra_curves.lua): further curves, fitted like those of jobs."""
    curves, replaced = _curves(jobs, passive_jobs, long_jobs, extra_jobs)
    extremes = normalise.normalise([p for pts in curves.values() for p in pts])
    for pts in replaced.values():
        for p in pts:
            p.update(normalise.scale_like(p, extremes))
    jobs_by_id = {j.id: j for j in jobs + (passive_jobs or []) + (long_jobs or []) + (extra_jobs or [])}
    short_t, long_t = _run_time(jobs), _run_time(long_jobs) if long_jobs else None
    fitted = []
    for key, pts in curves.items():
        pts.sort(key=lambda p: p["x"])
        plain = ("beta = %g, passive" % key[1] if key[0] == "passive"
                 else "beta = %g, tau_p = %g" % (key[0], key[1]))
        if key in replaced:
            plain += " (t = %g)" % long_t
        fitted.append(_fit_curve(key, pts, plain, jobs_by_id, extremes))
    usable = [f for f in fitted if f["excluded_from_scale_fit"] is None]
    scale = _scale_fit(usable, fitted)
    fig, axes = figure(3, width=4.6)
    _plot_curves(axes, curves, fitted, replaced)
    _plot_inset(axes[2], usable, scale)
    _legend(fig, curves, replaced)
    images = [save(fig, out, "fig5_An.png", rect=(0, 0, 0.91, 1))]
    rows = _rows(fitted, usable, scale, curves, passive_jobs)
    for f in fitted:
        f["steady"] = not f["unsteady_points"]
    numbers = {"curves": fitted, "scale_fit": scale, "normalisation": extremes,
               "replaced_by_longer_runs": [
                   {"key": list(k), "t": short_t, "replaced_by_t": long_t,
                    "A_n": [p["A_n"] for p in sorted(v, key=lambda p: p["x"])]}
                   for k, v in replaced.items()]}
    if passive_jobs:
        numbers["passive_Tc_over_kT"] = [j.mean("T_c")[0] / float(j.sp["kT"])
                                         for j in passive_jobs if float(j.sp.get("kT", 0)) > 0]
    kept = [j for j in jobs if (float(j.sp["beta"]), float(j.sp["tau_p"])) not in replaced]
    return {"images": images, "rows": rows, "numbers": numbers,
            "steadiness": steady.steadiness_summary(kept + (passive_jobs or []) + (long_jobs or [])
                                                  + (extra_jobs or []))}


def _scale_fit(usable, fitted):
    """The fit of a = c1 (1 + c2 beta/P) tau_g/tau_d over the usable curves, or {"why": ...}."""
    excluded = _left_out(fitted)
    if len(usable) < 2:
        return {"why": "%d curve%s with a located midpoint (needs 2)%s" % (
            len(usable), "" if len(usable) == 1 else "s", ": " + excluded if excluded else "")}
    try:
        return fits.fit_scale([f["a"] for f in usable], [f["a_error"] for f in usable],
                              [f["beta"] / P_DEFAULT for f in usable],
                              [TAU_G / f["tau_d"] for f in usable],
                              [f["tau_d_rel_error"] for f in usable])
    except (FitError, RuntimeError, ValueError) as err:
        return {"why": str(err)}


def _left_out(fitted):
    return "; ".join("%s: %s" % (f["curve"], f["excluded_from_scale_fit"]) for f in fitted
                     if f["key"][0] != "passive" and f["excluded_from_scale_fit"])


def _rows(fitted, usable, scale, curves, passive_jobs):
    """The verdict rows of Fig. 5. fig5_b_range: one row per curve (the variant), resting on
    all of the curve's state points. fig5_c1, fig5_c2, fig5_inset: on the active curves whose
    midpoint is located; the curves left out as not steady make them "not steady" when fewer
    than two remain."""
    rows = []
    sb = verdict.paper()["fig5_b_range"]
    for f in fitted:
        if "b" in f:
            ours, v = "b = %s" % verdict.fmt(f["b"], f["b_error"]), verdict.range_verdict(
                [(f["b"], f["b_error"])], sb["low"], sb["high"])
        else:
            ours, v = "n/a: %s" % f["why_no_fit"], verdict.NO_DATA
        r = verdict.row("fig5_b_range", ours, v, "b in [0.5, 2.5] within 2 errors; rests on "
                        "every state point of the curve, each steady (all its runs)",
                        unsteady=f["unsteady_points"])
        r["variant"] = f["curve"]
        rows.append(r)
    unsteady = [f["curve"] for f in fitted if f["key"][0] != "passive" and "a" in f
                and f["unsteady_points"]]
    blocked = unsteady if len(usable) < 2 else []
    excluded = _left_out(fitted)
    rests = ("rests on the active curves with a located midpoint and a finite tau_d (steady: "
             "a curve with a state point that is not steady is left out)")
    for sid, name in (("fig5_c1", "c1"), ("fig5_c2", "c2")):
        s = verdict.paper()[sid]
        v, e_ = scale.get(name), scale.get(name + "_error")
        how = ""
        if v is not None:
            how = " (fit of a over %d curves, chi2/dof = %s%s)" % (
                scale["n_curves"], verdict.fmt(scale.get("chi2_dof")),
                "; left out: " + excluded if excluded else "")
        if v is not None and name == "c1":  # a, hence c1, is a temperature: both conventions
            how = " (2T_c/P; by T_c/P: %s)%s" % (verdict.fmt(v / 2, e_ / 2), how)
        rows.append(verdict.row(
            sid, "%s = %s%s" % (name, verdict.fmt(v, e_), how) if v is not None else
            "n/a (%s)" % scale.get("why", "no fit"),
            verdict.log_verdict(v, e_, s["value"], s["log_factor"]) if v is not None
            else verdict.NO_DATA, "within a factor %g of %g; %s" % (s["log_factor"], s["value"], rests),
            unsteady=blocked))
    si = verdict.paper()["fig5_inset"]
    if "c1" in scale:
        pairs = [(f, _model(f, scale)) for f in usable]
        each = [verdict.log_verdict(f["a"] / m, f["a_error"] / m, si["value"], si["log_factor"])
                for f, m in pairs]
        ours = "a / (c1 (1 + c2 beta/P) tau_g/tau_d) = " + ", ".join(
            "%s (%s)" % (verdict.fmt(f["a"] / m, f["a_error"] / m), f["curve"]) for f, m in pairs)
        v = verdict.all_of(each)
    else:
        ours, v = "n/a (%s)" % scale.get("why", "no fit"), verdict.NO_DATA
    rows.append(verdict.row("fig5_inset", ours, v, "each curve's a within a factor %g of the "
                            "line with our fitted c1, c2 (+ 2 errors); %s" % (si["log_factor"], rests),
                            unsteady=blocked))
    ratios = [(p["T_c_over_T_a"], p["T_c_over_T_a_error"]) for k, pts in curves.items()
              if k[0] != "passive"
              for p in pts]
    st = verdict.paper()["fig5_Tc_over_Ta"]
    vals = [r for r, _ in ratios if verdict.finite(r)]
    rows.append(verdict.row(
        "fig5_Tc_over_Ta", "T_c/T_a from %s to %s over %d active state points" % (
            verdict.fmt(min(vals)) if vals else "n/a", verdict.fmt(max(vals)) if vals else "n/a",
            len(vals)), verdict.range_verdict(ratios, st["low"], st["high"]),
        "every state point's T_c/T_a in [1, 1.2] within 2 errors (replicate scatter)"))
    if passive_jobs:
        rows.append(tc_equals_ta_row("fig5_Tc_equals_Ta", passive_jobs, ["beta", "kT"]))
        eq = [j.mean("T_c")[0] / float(j.sp["kT"]) for j in passive_jobs if float(j.sp.get("kT", 0)) > 0]
        s2 = verdict.paper()["fig5_factor2"]
        m = float(np.mean(eq)) if eq else math.nan
        e_ = float(np.std(eq, ddof=1) / math.sqrt(len(eq))) if len(eq) > 1 else math.nan
        rows.append(verdict.row(
            "fig5_factor2", "passive bath: measured T_c/kT = %s (equipartition), so 2 T_c/kT = %s"
            % (verdict.fmt(m, e_), verdict.fmt(2 * m)),
            verdict.value_verdict(m, e_, s2["value"], s2["tolerance"]),
            "the equipartition T_c equals the bath kT (|T_c/kT - 1| <= 0.05 + 2 errors); the "
            "paper's formula would read twice that"))
    return rows
