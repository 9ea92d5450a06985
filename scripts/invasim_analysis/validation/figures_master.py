"""Fig. 5 of the validation page, the master curve, laid out as the paper's: (a) A_n against
the measured 2 T_c/P, one colour per tau_p and one marker per beta, the passive curve as filled
black diamonds, the fits as lines; (b) the collapse on E_c^b; (c) the paper's inset, the fitted
a against c1 (1 + c2 beta/P) tau_g/tau_d with the line a = that. Same contract as
figures_tissue.py.

The analysis is master_curve.py's, by its own functions (master_curve/analysis.py: the
normalisation, the state points, the per-curve fits with plateaus shared by the figure's
curves, the midpoint rule and the fit of a; docs/sweeps_analysis.md): for the same jobs the
page's a, b, c1, c2 are master_curve.py's. The page's own choices: the curves of fig5_long
replace those of the same beta and tau_p, the passive curve is fitted (and shares the
plateaus) but never enters the fit of a, steadiness is the criterion's alone
(steady.point_steadiness; master_curve.py's --max-drift is not applied), and a curve with a
state point that is not steady is drawn hollow and enters neither the collapse nor the fit
of a (master_curve.py drops only that state point, as the page's fits do too)."""

import math
import textwrap

import numpy as np
from matplotlib.lines import Line2D

from .. import normalise, steady, workspace
from . import points, verdict
from .figures_tissue import pressure, tc_equals_ta_row, x_measured
from .plotting import T_PAPER, figure, label, log_axis, save

from ..errors import InputError as FitError
from ..master_curve import analysis, fits
from ..master_curve.analysis import build_points

MIN_ERROR = 1e-3  # floor of a state point's A_n error in the fits (master_curve.py's default)
POOL = 1  # neighbours on each side whose replicate variance is pooled (master_curve.py --pool)
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
    # A "long" curve replaces the curve of the same beta and tau_p only if its runs are
    # longer: the sweep files set their own lengths (fig5_active.lua 4e6 steps, fig5_long.lua
    # 1e6), and a shorter curve must not replace a longer one.
    short_by_key = workspace.group(jobs + (extra_jobs or []), ["beta", "tau_p"])
    long_by_key = workspace.group(long_jobs, ["beta", "tau_p"]) if long_jobs else {}
    for key, pts in (_curve_points(long_jobs, ["beta", "tau_p"]).items() if long_jobs else []):
        if key in curves:
            if _run_time(long_by_key[key]) <= _run_time(short_by_key[key]):
                continue  # not longer: the curve of jobs stays
            replaced[key] = curves[key]
        curves[key] = pts
    for key, pts in (_curve_points(passive_jobs, ["beta"]).items() if passive_jobs else []):
        curves[("passive", key[0])] = pts
    return curves, replaced


def _job_rows(curves, jobs_by_id):
    """The jobs of the fitted curves as the master curve's per-row arrays (what
    master_curve/analysis.py reads from results.csv, i.e. summary.json's means and errors):
    x = the measured 2 T_c/P, A_t, A_t^max and their errors; per row its state point (curve
    key, index); per state point (key, index) its rows; per row whether its state point is
    steady (steady.point_steadiness, set on the points as "steady")."""
    ids, point_of, rows_of, is_steady = [], [], {}, []
    for key, pts in curves.items():
        for k, p in enumerate(pts):
            p["steady"] = steady.point_steadiness([jobs_by_id[i] for i in p["jobs"]])[0]
            rows_of[(key, k)] = np.arange(len(ids), len(ids) + len(p["jobs"]))
            ids += p["jobs"]
            point_of += [(key, k)] * len(p["jobs"])
            is_steady += [p["steady"]] * len(p["jobs"])
    js = [jobs_by_id[i] for i in ids]
    return {"jobs": js, "point": point_of, "rows_of": rows_of, "steady": is_steady,
            "x": np.array([x_measured(j) for j in js]),
            "A_t": np.array([j.mean("A_t")[0] for j in js]),
            "A_t_error": np.array([j.mean("A_t")[1] for j in js]),
            "A_t_max": np.array([j.mean("A_t_max")[0] for j in js]),
            "A_t_max_error": np.array([j.mean("A_t_max")[1] for j in js])}


def _normalise(rows):
    """A_n of every job by the master curve's normalisation (analysis.a_n_by_partition): one
    partition, the whole figure (every fitted curve, the passive one included); the steady
    state points set the extremes, as in master_curve.py. When no state point of the figure
    is steady (runs too short to judge, as at the CI size), every one counts, for A_n and the
    fits, and the record says so (numbers: "basis"). Returns (basis rows, A_n and errors per
    row, the extremes for normalise.scale_like)."""
    n = len(rows["x"])
    basis = rows["steady"] if any(rows["steady"]) else [True] * n
    r_a, a_n, run_err, norm_err, info = analysis.a_n_by_partition(
        [()] * n, [], [True] * n, rows["A_t"], rows["A_t_max"], rows["A_t_error"],
        rows["A_t_max_error"], rows["point"], basis)
    extremes = {k: v for k, v in info[0].items() if k != "partition"}
    extremes["basis"] = ("the steady state points" if any(rows["steady"]) else
                         "every state point (none is steady)")
    norm = {"rA_t": r_a, "A_n": a_n, "run_error": run_err, "norm_error": norm_err}
    return basis, norm, extremes


def _points(idx, rows, norm, window=POOL):
    """State points of a curve from their rows, as master_curve.py makes them
    (analysis.build_points: replicate means, the pooled replicate error plus the
    normalisation's extremes' share, floored at MIN_ERROR), keyed by their rows."""
    out = build_points(idx, rows["x"], norm["A_n"], norm["run_error"], norm["norm_error"],
                       MIN_ERROR, window)
    return {tuple(p["rows"]): p for p in out}


def _fit_curve(key, pts, plain, rows, norm, basis):
    """One curve's record: its state points' A_n and errors (set on pts for the figure), and
    its min-max fit (analysis.min_max_fit) over the state points that count (the steady ones,
    as master_curve.py), kept under "_fit" for analysis.judge_fits; why there is none."""
    idx = [rows["rows_of"][(key, k)] for k in range(len(pts))]
    counted = [ix for ix in idx if basis[ix[0]]]
    fitted = _points(counted, rows, norm)
    for p, ix in zip(pts, idx):
        q = fitted.get(tuple(ix)) or _points([ix], rows, norm, window=0)[tuple(ix)]
        p["A_n"], p["A_n_error"] = q["A_n"], q["A_n_error"]
    entry = {"curve": plain, "key": list(key), "points": len(pts), "fitted_points": len(counted),
             "unsteady_points": ["2T_c/P = %.3g" % p["x"] for p in pts if not p["steady"]],
             "beta": key[1] if key[0] == "passive" else key[0], "_fit": None}
    try:
        if not counted:
            raise FitError("curve %s: no steady state point" % plain)
        if min(p["x"] for p in pts) <= 0:
            raise FitError("a non-positive temperature")
        entry["_fit"] = analysis.min_max_fit(plain, sorted(fitted.values(),
                                                            key=lambda p: p["x"]))
    except FitError as e:
        left = len(idx) - len(counted)
        entry["why_no_fit"] = str(e) + (" (%d state point%s not steady, left out)" % (
            left, "" if left == 1 else "s") if left else "")
    entry.update(_scale_inputs(key, [rows["jobs"][i] for ix in (counted or idx) for i in ix]))
    if entry["_fit"] is not None:
        entry["_fit"].update({k: entry[k] for k in ("beta", "P", "tau_g", "tau_d_error")},
                             tau_d=entry["tau_d"])
    return entry


def _scale_inputs(key, jobs):
    """beta, P, tau_g = m/gamma and tau_d of a curve as master_curve.py takes them
    (analysis.curve_scale_inputs: tau_d the mean over the curve's jobs, analysis.mean_tau_d;
    gamma from the state point, else analysis.DEFAULT_GAMMA), and why it cannot enter the
    fit of a (passive, or no finite tau_d)."""
    tau_d, tau_d_error, _ = analysis.mean_tau_d([j.scalar("tau_d") for j in jobs])
    pressures = {pressure(j) for j in jobs}
    gammas = {float(j.sp.get("gamma", analysis.DEFAULT_GAMMA)) for j in jobs}
    gamma = gammas.pop() if len(gammas) == 1 else math.nan
    why = None
    if key[0] == "passive":
        why = "passive (no tau_d of self-propulsion)"
    elif len(pressures) > 1 or not gamma > 0:
        why = "P or gamma varies within the curve, or gamma is not > 0"
    elif tau_d is None:
        why = "no finite tau_d"
    return {"P": pressures.pop() if len(pressures) == 1 else None,
            "tau_g": 1.0 / gamma if gamma > 0 else None,
            "tau_d": tau_d if tau_d is not None else math.nan, "tau_d_error": tau_d_error,
            "tau_d_rel_error": (tau_d_error or 0.0) / tau_d if tau_d else 0.0,
            "scale_input_problem": why}


FIT_FIELDS = ("a", "a_error", "b", "b_error", "log10_a", "log10_a_error", "chi2", "dof",
              "error_scale", "fit_note", "not_a_fit")


def _judge(fitted):
    """The fits with shared plateaus and the midpoint rule, by master_curve.py's own functions
    (analysis.judge_fits: plateaus.refine over the figure's one normalisation group, then
    fits.not_a_fit and fits.midpoint_not_located); then the page's own rule: a curve with a
    state point that is not steady enters neither the collapse nor the fit of a. Sets each
    curve's fit fields, plateaus, in_collapse and excluded_from_scale_fit; returns the record
    of the plateau fit."""
    fits_ = [f["_fit"] for f in fitted if f["_fit"] is not None]
    for c in fits_:
        c["excluded_from_scale_fit"] = None
    records = analysis.judge_fits(fits_, {c["name"]: True for c in fits_},
                                  {c["name"]: () for c in fits_})
    for f in fitted:
        c = f["_fit"]
        if c is None:
            why = "no sigmoid fit: " + f["why_no_fit"]
        else:
            f.update({k: c[k] for k in FIT_FIELDS}, plateaus=list(c["plateaus"]))
            why = ("not steady at " + ", ".join(f["unsteady_points"]) if f["unsteady_points"]
                   else c["excluded_from_scale_fit"])
        f["in_collapse"] = why is None
        problem = f.pop("scale_input_problem")
        f["excluded_from_scale_fit"] = why or problem
        if c is not None:
            c["excluded_from_scale_fit"] = f["excluded_from_scale_fit"]
    return [{k: v for k, v in r.items() if k != "partition"} for r in records]


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
        if f["in_collapse"]:  # the fit as master_curve.py draws it: L + (H - L) sigmoid
            lo, hi = f["plateaus"]
            xs = np.logspace(math.log10(pts[0]["x"]), math.log10(pts[-1]["x"]), 100)
            axes[0].plot(xs, lo + (hi - lo) * fits.sigmoid(xs, f["a"], f["b"]), color=c, lw=1)
            axes[1].plot([(p["x"] / f["a"]) ** f["b"] for p in pts],
                         [(p["A_n"] - lo) / (hi - lo) for p in pts],
                         marker=m, ls="none", color=c, ms=5)
    log_axis(axes[0], [p["x"] for pts in curves.values() for p in pts])
    axes[0].set_xlabel(T_PAPER, fontsize=8)
    axes[0].set_ylabel(label("A_n", ""))
    axes[0].set_title("(a) $A_n$, fits (Eq. (15), plateaus $L$, $H$ fitted) as lines",
                      fontsize=9)
    e = np.logspace(-2, 2, 100)
    axes[1].plot(e, fits.sigmoid(e, 1.0, 1.0), "k-", lw=1)  # the collapse: a = b = 1
    axes[1].set_xscale("log")
    axes[1].set_xlabel(r"$E_c^b = (x/a)^b$, $x = 2k_BT_c/(P\sigma^3)$ (dimensionless)", fontsize=8)
    axes[1].set_ylabel(r"$(A_n - L)/(H - L)$ (dimensionless)")
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
    """c1 (1 + c2 beta/P) tau_g/tau_d of a curve of the fit of a (q = beta/P and tau_g/tau_d as
    analysis.scale_fit took them) with the fitted c1, c2 (c2 = 0 if not fitted)."""
    return scale["c1"] * (1 + (scale.get("c2") or 0.0) * f["q"]) * f["tau_g_over_tau_d"]


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
    extra_jobs (fig5_extra_curves.lua): further curves, fitted like those of jobs. The fits
    are master_curve.py's (docs/sweeps_analysis.md): for the same jobs, the same a, b, L, H
    per curve, and the same c1, c2 over the same curves."""
    curves, replaced = _curves(jobs, passive_jobs, long_jobs, extra_jobs)
    for pts in curves.values():
        pts.sort(key=lambda p: p["x"])
    jobs_by_id = {j.id: j for j in jobs + (passive_jobs or []) + (long_jobs or []) + (extra_jobs or [])}
    short_t, long_t = _run_time(jobs), _run_time(long_jobs) if long_jobs else None
    rows = _job_rows(curves, jobs_by_id)
    basis, norm, extremes = _normalise(rows)
    for pts in replaced.values():
        for p in pts:
            p.update(normalise.scale_like(p, extremes))
    fitted = []
    for key, pts in curves.items():
        plain = ("beta = %g, passive" % key[1] if key[0] == "passive"
                 else "beta = %g, tau_p = %g" % (key[0], key[1]))
        if key in replaced:
            plain += " (t = %g)" % long_t
        fitted.append(_fit_curve(key, pts, plain, rows, norm, basis))
    plateau_fits = _judge(fitted)
    usable = [f for f in fitted if f["excluded_from_scale_fit"] is None]
    scale = _scale_fit(usable, fitted)
    fig, axes = figure(3, width=4.6)
    _plot_curves(axes, curves, fitted, replaced)
    _plot_inset(axes[2], usable, scale)
    _legend(fig, curves, replaced)
    images = [save(fig, out, "fig5_An.png", rect=(0, 0, 0.91, 1))]
    rows = _rows(fitted, usable, scale, curves, passive_jobs, plateau_fits)
    for f in fitted:
        f["steady"] = not f["unsteady_points"]
    numbers = {"curves": fitted, "scale_fit": scale, "normalisation": extremes,
               "plateau_fits": plateau_fits,
               "replaced_by_longer_runs": [
                   {"key": list(k), "t": short_t, "replaced_by_t": long_t,
                    "A_n": [p["A_n"] for p in sorted(v, key=lambda p: p["x"])]}
                   for k, v in replaced.items()]}
    if passive_jobs:
        numbers["passive_Tc_over_kT"] = [j.mean("T_c")[0] / float(j.sp["kT"])
                                         for j in passive_jobs if float(j.sp.get("kT", 0)) > 0]
    def key(j):
        return (float(j.sp["beta"]), float(j.sp["tau_p"]))
    kept = [j for j in jobs if key(j) not in replaced]
    # The long runs drawn: those that replaced a curve or added one (not the shorter ones).
    short_keys = {key(j) for j in jobs + (extra_jobs or [])}
    long_used = [j for j in (long_jobs or []) if key(j) in replaced or key(j) not in short_keys]
    return {"images": images, "rows": rows, "numbers": numbers,
            "steadiness": steady.steadiness_summary(kept + (passive_jobs or []) + long_used
                                                  + (extra_jobs or []))}


def _scale_fit(usable, fitted):
    """The fit of a = c1 (1 + c2 beta/P) tau_g/tau_d over the usable curves by
    master_curve.py's own function (analysis.scale_fit: fits.fit_scale, tau_d's standard
    error as effective variance), or {"why": ...}. Copies q = beta/P, tau_g/tau_d and the sigma
    of a in the fit onto the curves used, and drops the curves' fit objects."""
    excluded = _left_out(fitted)
    if len(usable) < 2:
        res = {"why": "%d curve%s with a located midpoint (needs 2)%s" % (
            len(usable), "" if len(usable) == 1 else "s", ": " + excluded if excluded else "")}
    else:
        try:
            res = analysis.scale_fit([f["_fit"] for f in fitted if f["_fit"] is not None], fits)
        except (FitError, RuntimeError, ValueError) as err:
            res = {"why": str(err)}
    for f in fitted:
        c = f.pop("_fit")
        for k in ("q", "tau_g_over_tau_d", "a_sigma_in_scale_fit"):
            if c is not None and k in c and f["excluded_from_scale_fit"] is None:
                f[k] = c[k]
    return res


def _left_out(fitted):
    return "; ".join("%s: %s" % (f["curve"], f["excluded_from_scale_fit"]) for f in fitted
                     if f["key"][0] != "passive" and f["excluded_from_scale_fit"])


def _plateau_text(plateau_fits):
    """"; plateaus L = .., H = .." of the shared plateau fit (plateaus.refine), or ""."""
    done = [p for p in plateau_fits if p.get("done")]
    if not done:
        return "; plateaus: the extremes, 0 and 1 (no shared fit)"
    fit = done[0]
    return "; plateaus fitted: L = %s, H = %s" % (verdict.fmt(fit["lo"], fit["lo_error"]),
                                                 verdict.fmt(fit["hi"], fit["hi_error"]))


def _rows(fitted, usable, scale, curves, passive_jobs, plateau_fits=()):
    """The verdict rows of Fig. 5. fig5_b_range: one row per curve (the variant), resting on
    all of the curve's state points (its b fitted on the steady ones, as master_curve.py).
    fig5_c1, fig5_c2, fig5_inset: on the active curves whose midpoint is located; the curves
    left out as not steady make them "not steady" when fewer than two remain."""
    rows = []
    sb = verdict.paper()["fig5_b_range"]
    for f in fitted:
        if "b" in f:
            ours, v = "b = %s" % verdict.fmt(f["b"], f["b_error"]), verdict.range_verdict(
                [(f["b"], f["b_error"])], sb["low"], sb["high"])
            if f["fitted_points"] < f["points"]:
                ours += " (fit of the %d steady of its %d state points)" % (
                    f["fitted_points"], f["points"])
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
            how = " (fit of a over %d curves, chi2/dof = %s%s%s)" % (
                scale["n_curves"], verdict.fmt(scale.get("chi2_dof")),
                _plateau_text(plateau_fits), "; left out: " + excluded if excluded else "")
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
