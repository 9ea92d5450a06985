"""The validation figures of Fig. 5 (the master curve), 6 (cells only), 8 (packing scan) and
9 (slice shapes); same contract as figures_tissue.py."""

import csv
import math
import os
import sys

import numpy as np

from . import runs, verdict
from .figures_tissue import x_measured
from .plotting import T_PAPER, figure, label, log_if_spans, save, state

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from master_curve_lib import fits  # noqa: E402
from master_curve_lib.analysis import build_points  # noqa: E402
from master_curve_lib.table import InputError as FitError  # noqa: E402

MIN_ERROR = 1e-3  # floor of a state point's A_n error in the fits (as master_curve.py)
POOL = 1  # neighbours on each side whose replicate variance is pooled (master_curve.py --pool)


def _curve_points(jobs, keys):
    out = {}
    for key, reps in runs.group(jobs, keys + ["f0", "kT"]).items():
        p = runs.state_point(reps, lambda j: {
            "x": x_measured(j), "A_t": j.mean("A_t")[0], "A_t_max": j.mean("A_t_max")[0],
            "A_t_error": j.mean("A_t")[1], "tau_d": j.scalar("tau_d"),
            "T_c_over_T_a": j.mean("T_c_over_T_a")[0]})
        out.setdefault(key[:len(keys)], []).append(p)
    return out


def _pooled_errors(pts, jobs_by_id, extremes):
    """The A_n errors of a curve's state points as master_curve.py computes them
    (analysis.build_points): the replicate variance pooled with POOL neighbours on each side
    along x, so that two replicates give usable weights (the standard error of two values
    alone can be near zero by chance and then dominates a fit), floored at MIN_ERROR."""
    groups = [[jobs_by_id[i] for i in p["jobs"]] for p in pts]
    rows = [j for g in groups for j in g]
    scaled = [runs.scale_like({"A_t": j.mean("A_t")[0], "A_t_max": j.mean("A_t_max")[0],
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


def fig5(jobs, out, invasim, passive_jobs=None, long_jobs=None):
    """long_jobs (fig5_long.lua): curves run longer; each replaces the curve of the same beta
    and tau_p of jobs, which is drawn for comparison (hollow markers) but not fitted."""
    curves = _curve_points(jobs, ["beta", "tau_p"])
    replaced = {}
    if long_jobs:
        for key, pts in _curve_points(long_jobs, ["beta", "tau_p"]).items():
            if key in curves:
                replaced[key] = curves[key]
            curves[key] = pts
    if passive_jobs:
        for key, pts in _curve_points(passive_jobs, ["beta"]).items():
            curves[("passive", key[0])] = pts
    extremes = runs.normalise([p for pts in curves.values() for p in pts])
    for pts in replaced.values():
        for p in pts:
            p.update(runs.scale_like(p, extremes))
    jobs_by_id = {j.id: j for j in jobs + (passive_jobs or []) + (long_jobs or [])}
    fig, axes = figure(2)
    fitted, rows = [], []
    short_t, long_t = _run_time(jobs), _run_time(long_jobs) if long_jobs else None
    for key, pts in replaced.items():
        pts.sort(key=lambda p: p["x"])
        axes[0].plot([p["x"] for p in pts], [p["A_n"] for p in pts], marker="o", ls="none",
                     mfc="none", color="0.5", label=state({"beta": "%g" % key[0], "tau_p": "%g"
                                                           % key[1]}) + ", t = %g" % short_t)
    for key, pts in curves.items():
        pts.sort(key=lambda p: p["x"])
        name = (state({"beta": "%g" % key[1]}) + ", passive" if key[0] == "passive"
                else state({"beta": "%g" % key[0], "tau_p": "%g" % key[1]}))
        sig = _pooled_errors(pts, jobs_by_id, extremes)
        for p, e in zip(pts, sig):
            p["A_n_error"] = e
        if key in replaced:
            name += ", t = %g" % long_t
        h = axes[0].errorbar([p["x"] for p in pts], [p["A_n"] for p in pts], yerr=sig,
                             marker="o", ls="none", capsize=2, label=name)
        plain = ("beta = %g, passive" % key[1] if key[0] == "passive"
                 else "beta = %g, tau_p = %g" % (key[0], key[1]))
        if key in replaced:
            plain += " (t = %g)" % long_t
        entry = {"curve": plain, "key": list(key), "points": len(pts),
                 "data": ([p["x"] for p in pts], [p["A_n"] for p in pts], sig)}
        try:
            if min(p["x"] for p in pts) <= 0:
                raise FitError("a non-positive temperature")
            f = fits.fit_sigmoid([p["x"] for p in pts], [p["A_n"] for p in pts], sig, plain)
            entry.update(f)
            xs = np.logspace(math.log10(pts[0]["x"]), math.log10(pts[-1]["x"]), 100)
            axes[0].plot(xs, fits.sigmoid(xs, f["a"], f["b"]), color=h[0].get_color(), lw=1)
            if f["a"] > 0:
                axes[1].plot([(p["x"] / f["a"]) ** f["b"] for p in pts],
                             [p["A_n"] for p in pts], "o", color=h[0].get_color())
        except FitError as e:
            entry["why_no_fit"] = str(e)
        taus = [p["tau_d"] for p in pts if verdict.finite(p["tau_d"]) and p["tau_d"] > 0]
        entry["tau_d"] = float(np.mean(taus)) if taus else math.nan
        entry["tau_d_rel_error"] = (float(np.std(taus, ddof=1) / math.sqrt(len(taus)) /
                                          np.mean(taus)) if len(taus) > 1 else 0.0)
        entry["beta"] = key[1] if key[0] == "passive" else key[0]
        fitted.append(entry)
    axes[0].set_xscale("log")
    axes[0].set_xlabel(T_PAPER)
    axes[0].set_ylabel(label("A_n", ""))
    axes[0].legend(fontsize=7)
    e = np.logspace(-2, 2, 100)
    axes[1].plot(e, 0.5 * (np.tanh(np.log10(e)) + 1), "k-", lw=1,
                 label=r"$(\tanh[\log_{10} E_c^b] + 1)/2$")
    axes[1].set_xscale("log")
    axes[1].legend(fontsize=8)
    axes[1].set_xlabel(r"$E_c^b = (x/a)^b$ (dimensionless)")
    axes[1].set_ylabel(label("A_n", ""))
    axes[1].set_title("collapse with each curve's fitted a, b", fontsize=9)
    images = [save(fig, out, "fig5_An.png")]

    sb = verdict.paper()["fig5_b_range"]
    bs = [(f["b"], f["b_error"]) for f in fitted if "b" in f]
    rows.append(verdict.row("fig5_b_range", "b = " + (", ".join(
        "%s (%s)" % (verdict.fmt(f["b"], f["b_error"]), f["curve"]) for f in fitted if "b" in f)
        or "n/a: " + "; ".join(f.get("why_no_fit", "") for f in fitted)),
        verdict.range_verdict(bs, sb["low"], sb["high"]), "every b in [0.5, 2.5] within 2 errors"))
    # The curves whose midpoint a enters the fit of a (the same rule as master_curve.py).
    for f in fitted:
        if f["key"][0] == "passive":
            f["excluded_from_scale_fit"] = "passive (no tau_d of self-propulsion)"
        elif "a" not in f:
            f["excluded_from_scale_fit"] = "no sigmoid fit: " + f.get("why_no_fit", "")
        elif not verdict.finite(f["tau_d"]):
            f["excluded_from_scale_fit"] = "no finite tau_d"
        else:
            f["excluded_from_scale_fit"] = fits.midpoint_not_located(
                f["a"], f["a_error"], f["b"], f["b_error"], *f["data"])
        f.pop("data")
    usable = [f for f in fitted if f["excluded_from_scale_fit"] is None]
    excluded = "; ".join("%s: %s" % (f["curve"], f["excluded_from_scale_fit"])
                         for f in fitted if f["key"][0] != "passive" and f["excluded_from_scale_fit"])
    scale = None
    if len(usable) < 2:
        scale = {"why": "%d curve%s with a located midpoint (needs 2)%s" % (
            len(usable), "" if len(usable) == 1 else "s", ": " + excluded if excluded else "")}
    else:
        tau_g = 5.0
        try:
            scale = fits.fit_scale([f["a"] for f in usable], [f["a_error"] for f in usable],
                                   [f["beta"] / P for f, P in zip(usable, [1.3e-3] * len(usable))],
                                   [tau_g / f["tau_d"] for f in usable],
                                   [f["tau_d_rel_error"] for f in usable])
        except (FitError, RuntimeError, ValueError) as err:
            scale = {"why": str(err)}
    for sid, name in (("fig5_c1", "c1"), ("fig5_c2", "c2")):
        s = verdict.paper()[sid]
        v = scale.get(name) if scale else None
        e_ = scale.get(name + "_error") if scale else None
        how = ""
        if v is not None:
            how = " (fit of a over %d curves, chi2/dof = %s%s)" % (
                scale["n_curves"], verdict.fmt(scale.get("chi2_dof")),
                "; left out: " + excluded if excluded else "")
        rows.append(verdict.row(
            sid, "%s = %s%s" % (name, verdict.fmt(v, e_), how) if v is not None else
            "n/a (%s)" % (scale.get("why") if scale else "fewer than two fitted curves with tau_d"),
            verdict.log_verdict(v, e_, s["value"], s["log_factor"]) if v is not None
            else verdict.NO_DATA, "within a factor %g of %g" % (s["log_factor"], s["value"])))
    ratios = [(p["T_c_over_T_a"], 0.0) for k, pts in curves.items() if k[0] != "passive"
              for p in pts]
    st = verdict.paper()["fig5_Tc_over_Ta"]
    vals = [r for r, _ in ratios if verdict.finite(r)]
    rows.append(verdict.row(
        "fig5_Tc_over_Ta", "T_c/T_a from %s to %s over %d active state points" % (
            verdict.fmt(min(vals)) if vals else "n/a", verdict.fmt(max(vals)) if vals else "n/a",
            len(vals)), verdict.range_verdict(ratios, st["low"], st["high"]),
        "every state point's T_c/T_a in [1, 1.2]"))
    numbers = {"curves": fitted, "scale_fit": scale, "normalisation": extremes,
               "replaced_by_longer_runs": [
                   {"key": list(k), "t": short_t, "replaced_by_t": long_t,
                    "A_n": [p["A_n"] for p in sorted(v, key=lambda p: p["x"])]}
                   for k, v in replaced.items()]}
    if passive_jobs:
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
        numbers["passive_Tc_over_kT"] = eq
    kept = [j for j in jobs if (float(j.sp["beta"]), float(j.sp["tau_p"])) not in replaced]
    return {"images": images, "rows": rows, "numbers": numbers,
            "steadiness": runs.steadiness_summary(kept + (passive_jobs or []) + (long_jobs or []))}


def fig6(jobs, out, invasim):
    fig, (ax,) = figure()
    rows, table = [], []
    for (phi_c,), reps in runs.group(jobs, ["phi_c"]).items():
        reps.sort(key=lambda j: float(j.sp["tau_p"]))
        tp = [float(j.sp["tau_p"]) for j in reps]
        td = [j.scalar("tau_d") for j in reps]
        ax.plot(tp, td, "o-", label=state({"phi_c": "%g" % phi_c}))
        for j, t, d in zip(reps, tp, td):
            window = j.scalar("correlation_window")
            n_windows = (j.scalar("steps") - j.scalar("equilibrate_steps")) * float(
                j.sp.get("dt", 0.05)) / window if verdict.finite(window) and window > 0 else math.nan
            table.append({"phi_c": float(phi_c), "tau_p": t, "tau_d": d,
                          "tau_d_free": j.scalar("tau_d_free"),
                          "windows": n_windows})
    free = sorted({(r["tau_p"], r["tau_d_free"]) for r in table})
    ax.plot([f[0] for f in free], [f[1] for f in free], "k--", lw=1, label="free particle (exact)")
    log_if_spans(ax, [r["tau_p"] for r in table], "x", 1.0)
    log_if_spans(ax, [r["tau_d"] for r in table] + [f[1] for f in free], "y", 1.0)
    ax.set_xlabel(label("tau_p", "tau"))
    ax.set_ylabel(label("tau_d", "tau"))
    ax.legend(fontsize=8)
    images = [save(fig, out, "fig6_tau_d.png")]

    def tol(r):  # statistical precision of a tau_d from n windows, at least the paper's 10 %
        return max(0.1, 1 / math.sqrt(r["windows"])) if verdict.finite(r["windows"]) and r["windows"] > 0 else 0.1

    zero = [r for r in table if r["phi_c"] == 0.0]
    if zero:
        small = min(zero, key=lambda r: r["tau_p"])
        ratio = small["tau_d"] / small["tau_d_free"]
        rows.append(verdict.row("fig6_small_tau_p", "tau_d/tau_d_free = %s at tau_p = %g, phi_c = 0"
                                % (verdict.fmt(ratio), small["tau_p"]),
                                verdict.value_verdict(ratio, 0.0, 1.0, tol(small)),
                                "|ratio - 1| <= max(0.1, 1/sqrt(windows))"))
        worst = max(zero, key=lambda r: abs(r["tau_d"] / r["tau_d_free"] - 1))
        verdicts = [verdict.value_verdict(r["tau_d"] / r["tau_d_free"], 0.0, 1.0, tol(r)) for r in zero]
        rows.append(verdict.row("fig6_free_formula", "largest deviation at phi_c = 0: tau_d/tau_d_free = %s "
                                "(tau_p = %g), %d of %d within" % (
                                    verdict.fmt(worst["tau_d"] / worst["tau_d_free"]), worst["tau_p"],
                                    verdicts.count(verdict.AGREES), len(zero)),
                                verdict.AGREES if all(v == verdict.AGREES for v in verdicts)
                                else (verdict.TREND if verdict.AGREES in verdicts else verdict.DISAGREES),
                                "each point |ratio - 1| <= max(0.1, 1/sqrt(windows))"))
    dense = [r for r in table if r["phi_c"] == max(t["phi_c"] for t in table)]
    if dense and max(t["phi_c"] for t in table) > 0:
        big = max(dense, key=lambda r: r["tau_p"])
        d = 1 - big["tau_d"] / big["tau_d_free"]
        rows.append(verdict.row("fig6_dense_deviates", "tau_d/tau_d_free = %s at phi_c = %g, tau_p = %g"
                                % (verdict.fmt(big["tau_d"] / big["tau_d_free"]), big["phi_c"], big["tau_p"]),
                                verdict.trend_verdict(d, tol(big) / 2),
                                "1 - ratio > 2 x half the tolerance max(0.1, 1/sqrt(windows))"))
    return {"images": images, "rows": rows, "numbers": {"points": table}, "steadiness": None}


BOX_NAMES = {"pressure": "pressure wall at P", "fixed": "fixed box"}


def _box(job):
    """The packing scan's box after the rescale (packing.lua's `box`; runs from before the
    parameter existed ran under the pressure wall)."""
    return job.sp.get("box", "pressure")


def fig8(jobs, out, invasim):
    """The packing scan, one figure and one set of verdict rows per box (packing.lua's `box`:
    the pressure wall of docs/model.md protocol step 6, and the fixed box of the paper's text read
    literally), each normalised over its own scan (the paper's Appendix C per sweep)."""
    images, rows, numbers = [], [], {}
    boxes = sorted({_box(j) for j in jobs}, key=lambda b: (b != "pressure", b))
    for box in boxes:
        scan = [j for j in jobs if _box(j) == box]
        suffix = "" if box == "pressure" else "_" + box
        im, r, num = _fig8_scan(scan, out, box, "fig8_An_dphi%s.png" % suffix,
                                 variant=None if len(boxes) == 1 else BOX_NAMES.get(box, box))
        images += im
        rows += r
        numbers[box] = num
    return {"images": images, "rows": rows, "numbers": numbers,
            "steadiness": runs.steadiness_summary(jobs)}


def _fig8_scan(jobs, out, box, image, variant):
    """One box's scan: its state points (replicate means), normalised over the scan, its
    figure and its verdict rows."""
    pts = []
    for (lam, phi_a), reps in runs.group(jobs, ["lambda", "phi_a"]).items():
        p = runs.state_point(reps, lambda j: {
            "phi_a_measured": j.mean("phi_a")[0], "A_t": j.mean("A_t")[0],
            "A_t_max": j.mean("A_t_max")[0], "A_t_error": j.mean("A_t")[1],
            "phi_a_local_mean": j.mean("phi_a_local_mean")[0],
            "P_right": j.mean("P_right")[0], "T_c": j.mean("T_c")[0],
            "P": float(j.sp.get("P", math.nan)),
            "dphi": j.mean("phi_a_local_std")[0], "dphi_error": j.mean("phi_a_local_std")[1]})
        p["lambda"], p["phi_a_target"] = float(lam), float(phi_a)
        pts.append(p)
    extremes = runs.normalise(pts)
    by_lambda = {lam: sorted((p for p in pts if p["lambda"] == lam),
                             key=lambda p: p["phi_a_measured"])
                 for lam in sorted({p["lambda"] for p in pts})}
    images = [_fig8_plot(by_lambda, box, out, image)]
    rows = _fig8_rows(pts, by_lambda, box, variant)
    return images, rows, {"points": pts, "normalisation": extremes}


def _fig8_plot(by_lambda, box, out, image):
    """A_n, Delta phi_a and the raw A_t (with A_t^max) against the measured phi_a, one curve
    per lambda; returns the image's name."""
    fig, axes = figure(3, width=4.4)
    for lam, c in by_lambda.items():
        name = state({"lambda": "%g" % lam})
        axes[0].errorbar([p["phi_a_measured"] for p in c], [p["A_n"] for p in c],
                         yerr=[p["A_n_error"] if verdict.finite(p["A_n_error"]) else 0 for p in c],
                         marker="o", capsize=2, label=name)
        axes[1].errorbar([p["phi_a_measured"] for p in c], [p["dphi"] for p in c],
                         yerr=[p["dphi_error"] if verdict.finite(p["dphi_error"]) else 0 for p in c],
                         marker="s", capsize=2, label=name)
        line = axes[2].errorbar([p["phi_a_measured"] for p in c], [p["A_t"] for p in c],
                                yerr=[p["A_t_error"] if verdict.finite(p["A_t_error"]) else 0
                                      for p in c], marker="o", capsize=2, label=name)
        axes[2].plot([p["phi_a_measured"] for p in c], [p["A_t_max"] for p in c], ls="--",
                     color=line[0].get_color())
    measured = r"measured $\phi_a$ (dimensionless)"
    # Raw A_t beside A_t^max (dashed): A_n normalises by the smallest A_t^max of the scan,
    # which in a scan over box sizes (the fixed box) is the densest point's.
    axes[2].set_xlabel(measured)
    axes[2].set_ylabel(r"$A_t$ (solid), $A_t^\mathrm{max}$ (dashed) [$\sigma^2$]")
    axes[0].set_xlabel(measured)
    axes[0].set_ylabel(label("A_n", ""))
    axes[1].set_xlabel(measured)
    axes[1].set_ylabel(r"$\Delta\phi_a$, std of the local $\phi_a$ (dimensionless)")
    axes[0].legend(fontsize=8, title=BOX_NAMES.get(box, box), title_fontsize=8)
    return save(fig, out, image)


def _fig8_rows(pts, by_lambda, box, variant):
    """The verdict rows of one box's scan (variant: the box's name when both are shown)."""
    rows = []

    def add(sid, ours, v, why):
        r = verdict.row(sid, ours, v, why)
        if variant:
            r["variant"] = variant
        rows.append(r)

    drift = ("the pressure wall lets the tissue move away from the target, so the measured "
             "phi_a is shown" if box == "pressure" else
             "the box keeps the rescaled size, so phi_a stays at the target")
    dense = [p for p in pts if p["phi_a_target"] >= 0.85 - 1e-9]
    s0 = verdict.paper()["fig8_zero_above"]
    if dense:
        m = max(dense, key=lambda p: p["A_n"])
        raw = [p for p in pts if verdict.finite(p["A_t"])]
        lo = min(raw, key=lambda p: p["phi_a_measured"]) if raw else m
        add("fig8_zero_above", "largest A_n at target phi_a >= 0.85: %s "
            "(target %.3g, measured %.3g, lambda = %g; there A_t = %.0f of A_t^max = %.0f, "
            "wall pressure %.2g = %.0f P, T_c = %.2g; at the scan's lowest phi_a %.3g: "
            "A_t = %.0f of %.0f, lambda = %g)" % (
                verdict.fmt(m["A_n"], m["A_n_error"]), m["phi_a_target"],
                m["phi_a_measured"], m["lambda"], m["A_t"], m["A_t_max"], m["P_right"],
                m["P_right"] / m["P"], m["T_c"], lo["phi_a_measured"], lo["A_t"],
                lo["A_t_max"], lo["lambda"]),
            verdict.value_verdict(m["A_n"], m["A_n_error"], 0.0, s0["tolerance"]),
            "A_n <= 0.1 + 2 errors; " + drift + ("" if box == "pressure" else
            "; A_n is normalised with the scan's smallest A_t^max (Appendix C), i.e. the "
            "densest box's, so where A_t^max shrinks with the box faster than A_t, A_n rises "
            "though A_t falls (third panel)"))
    else:
        add("fig8_zero_above", "no point with a target phi_a >= 0.85",
            verdict.NO_DATA, "needs a target phi_a >= 0.85")
    lams = sorted(by_lambda)
    if len(lams) >= 2:
        a0 = np.mean([p["A_n"] for p in by_lambda[lams[0]]])
        a1 = np.mean([p["A_n"] for p in by_lambda[lams[-1]]])
        e = math.hypot(*[np.sqrt(np.nansum(np.square([p["A_n_error"] for p in by_lambda[l]]))) /
                         len(by_lambda[l]) for l in (lams[0], lams[-1])])
        add("fig8_lambda_lowers", "mean A_n over the scan: %s (lambda = %g), %s "
            "(lambda = %g)" % (verdict.fmt(a0), lams[0], verdict.fmt(a1), lams[-1]),
            verdict.trend_verdict(a0 - a1, e), "difference > 2 errors")
    for sid in ("fig8_dphi_0", "fig8_dphi_0.3", "fig8_dphi_1"):
        s = verdict.paper()[sid]
        c = by_lambda.get(s["lambda"])
        if not c:
            add(sid, "n/a (no lambda = %g)" % s["lambda"], verdict.NO_DATA, "")
            continue
        m = max(c, key=lambda p: p["dphi"])
        add(sid, "max Delta phi_a = %s (at phi_a = %.3g)" % (
            verdict.fmt(m["dphi"], m["dphi_error"]), m["phi_a_measured"]),
            verdict.value_verdict(m["dphi"], m["dphi_error"], s["value"], s["tolerance"]),
            "|ours - %g| <= %g + 2 errors" % (s["value"], s["tolerance"]))
    return rows


def read_shapes(job):
    with open(os.path.join(job.path, "shapes.csv")) as f:
        r = list(csv.DictReader(f))
    lo = np.array([float(x["A2_lo"]) for x in r])
    hi = np.array([float(x["A2_hi"]) for x in r])
    return lo, hi, np.array([float(x["count"]) for x in r])


def fig9(jobs, out, invasim):
    fig, (ax,) = figure()
    means = []
    stat = "median"
    for (a0,), reps in runs.group(jobs, ["A_0"]).items():
        lo, hi, count = read_shapes(reps[0])
        for j in reps[1:]:
            count = count + read_shapes(j)[2]
        width = hi - lo
        density = count / max(count.sum(), 1) / width
        ax.step(lo, density, where="post", label=state({"A_0": "%g" % a0}))
        # The median per run (robust to the sliver profiles of wrinkled bodies, see
        # docs/measurements_dynamics.md); runs from before it was written give their mean.
        m = [j.scalar("shape_2d_median") if verdict.finite(j.scalar("shape_2d_median"))
             else j.scalar("shape_2d_mean") for j in reps]
        if not all(verdict.finite(j.scalar("shape_2d_median")) for j in reps):
            stat = "mean"
        means.append((float(a0), float(np.mean(m)),
                      float(np.std(m, ddof=1) / math.sqrt(len(m))) if len(m) > 1 else math.nan,
                      int(count.sum())))
    ax.set_xlabel(r"slice shape parameter $A_\mathrm{2D} = p^2/(4\pi s)$ (dimensionless)")
    ax.set_ylabel(r"$P(A_\mathrm{2D})$ (dimensionless)")
    ax.set_xlim(1.0, 1.6)
    ax.legend(fontsize=8)
    images = [save(fig, out, "fig9_P_A2D.png")]
    means.sort()
    rows = [verdict.row("fig9_tissue", stat + " A_2D = " + ", ".join(
        "%s (A_0 = %g, %d slices)" % (verdict.fmt(m, e), a, n) for a, m, e, n in means),
        verdict.UNTESTABLE, "the paper's tissue slice data are not available to us")]
    if len(means) >= 2:
        d = means[-1][1] - means[0][1]
        e = math.hypot(*(x if verdict.finite(x) else 0 for x in (means[-1][2], means[0][2])))
        rows.append(verdict.row("fig9_shift", stat + " A_2D %s (A_0 = %g) -> %s (A_0 = %g)" % (
            verdict.fmt(means[0][1]), means[0][0], verdict.fmt(means[-1][1]), means[-1][0]),
            verdict.trend_verdict(d, e), "difference > 2 errors (replicate scatter)"))
    return {"images": images, "rows": rows, "numbers": {"means": means},
            "steadiness": runs.steadiness_summary(jobs)}
