"""The passive glass temperature by the paper's own definition (Fig. 4 caption, (a): T_g is
where the structural relaxation time tau_r diverges): tau_r of the relaxation sweeps
(protocols/sweeps/fig4a_relaxation*.lua, F_s(k = 2 pi/sigma, t) = 1/e, summary.json) against
the measured x = 2 k_B T_c/(P sigma^3). A divergence cannot be reached by a finite run, so the
verdict takes T_g as the temperature where tau_r reaches the paper's run length t = 5e5 (below
it the cells do not relax within the paper's runs), from ln tau_r = a + E/x (Arrhenius) through
the temperatures whose tau_r was reached; the Vogel-Fulcher-Tammann fit ln tau_r = A + B/(x -
x0) is reported beside it, its x0 being a divergence at a finite temperature when positive."""

import math

import numpy as np

from . import verdict
from .plotting import log_axis


def relaxation_points(job_sets, x_of):
    """One point per bath temperature (kT) over the given job sets: the measured x, tau_r
    where F_s fell to 1/e within the correlator window (the longest window that reached it),
    else the longest window as a lower bound."""
    by_kt = {}
    for jobs in job_sets:
        for j in jobs or []:
            by_kt.setdefault(float(j.sp.get("kT", 0.0)), []).append(j)
    pts = []
    for kt, reps in sorted(by_kt.items()):
        reached = [j for j in reps if verdict.finite(j.scalar("tau_r"))]
        best = max(reached or reps, key=lambda j: j.scalar("correlation_window") or 0.0)
        pts.append({"kT": kt, "x": x_of(best), "tau_r": best.scalar("tau_r"),
                    "window": best.scalar("correlation_window"), "run": best.id})
    return pts


def vft_fit(x, tau):
    """ln tau = A + B/(x - x0) by least squares over x0 < min(x): (x0, x0 error, A, B), the
    error from the covariance scaled by the residuals (nan for an exact fit of 3 points)."""
    from scipy.optimize import curve_fit
    x, y = np.asarray(x, float), np.log(np.asarray(tau, float))
    if len(x) < 3:
        return math.nan, math.nan, math.nan, math.nan

    def model(xx, a, b, x0):
        return a + b / (xx - x0)

    lo = x.min()
    best = None
    for x0 in np.linspace(0.0, lo * 0.95, 20):  # starts: the fit has local minima in x0
        b0 = (y.max() - y.min()) / max(1 / (x.min() - x0) - 1 / (x.max() - x0), 1e-12)
        try:
            p, cov = curve_fit(model, x, y, p0=(y.min() - b0 / (x.max() - x0), b0, x0),
                               bounds=([-np.inf, 0.0, -np.inf], [np.inf, np.inf, lo * 0.999]),
                               maxfev=20000)
        except (RuntimeError, ValueError):
            continue
        cost = float(np.sum((model(x, *p) - y) ** 2))
        if best is None or cost < best[0]:
            best = (cost, p, cov)
    if best is None:
        return math.nan, math.nan, math.nan, math.nan
    _, p, cov = best
    err = math.sqrt(cov[2, 2]) if len(x) > 3 and np.isfinite(cov[2, 2]) else math.nan
    return float(p[2]), err, float(p[0]), float(p[1])


def arrhenius_fit(x, tau):
    """ln tau = a + E/x by least squares: (a, E, their covariance 2x2); nan without 2 points."""
    x, y = np.asarray(x, float), np.log(np.asarray(tau, float))
    if len(x) < 2:
        return math.nan, math.nan, np.full((2, 2), math.nan)
    design = np.column_stack([np.ones_like(x), 1 / x])
    coef, *_ = np.linalg.lstsq(design, y, rcond=None)
    dof = len(x) - 2
    s2 = float(np.sum((design @ coef - y) ** 2)) / dof if dof > 0 else math.nan
    cov = s2 * np.linalg.inv(design.T @ design)
    return float(coef[0]), float(coef[1]), cov


def x_where(tau_target, a, e, cov):
    """The x where a + E/x = ln(tau_target), and its error from the fit's covariance."""
    lt = math.log(tau_target)
    if not verdict.finite(a, e) or e <= 0 or lt <= a:
        return math.nan, math.nan
    x = e / (lt - a)
    grad = np.array([e / (lt - a) ** 2, 1 / (lt - a)])  # d x / d (a, E)
    var = float(grad @ cov @ grad)
    return x, math.sqrt(var) if np.isfinite(var) and var >= 0 else math.nan


def tg_row(pts, statement, run_length=5e5):
    """The row of statement fig4a_Tg_relaxation: the x where tau_r reaches `run_length` (the
    paper's t = 5e5) against the paper's T_g within its factor (+ 2 errors), with the VFT
    divergence beside it."""
    fit_pts = [p for p in pts if verdict.finite(p["tau_r"]) and p["tau_r"] > 0]
    bounds = [p for p in pts if not verdict.finite(p["tau_r"])]
    xs, taus = [p["x"] for p in fit_pts], [p["tau_r"] for p in fit_pts]
    a, e, cov = arrhenius_fit(xs, taus) if len(fit_pts) >= 3 else (math.nan, math.nan, None)
    tg, tg_err = x_where(run_length, a, e, cov) if cov is not None else (math.nan, math.nan)
    x0, x0_err, va, vb = vft_fit(xs, taus) if len(fit_pts) >= 4 else (math.nan,) * 4
    ours = "tau_r = %s at 2T_c/P = %s%s; tau_r = %g at 2T_c/P = %s (Arrhenius through them); " \
        "VFT divergence at %s" % (
            ", ".join(verdict.fmt(t) for t in taus), ", ".join(verdict.fmt(x) for x in xs),
            "; not reached within windows of %s at %s" % (
                ", ".join(verdict.fmt(p["window"]) for p in bounds),
                ", ".join(verdict.fmt(p["x"]) for p in bounds)) if bounds else "",
            run_length, verdict.fmt(tg, tg_err), verdict.fmt(x0, x0_err))
    return verdict.row(
        "fig4a_Tg_relaxation", ours,
        verdict.log_verdict(tg, tg_err, statement["value"], statement["log_factor"]),
        "2T_c/P where tau_r reaches the paper's run length %g (ln tau_r = a + E/(2T_c/P) over the "
        "%d temperatures whose tau_r was reached) within a factor %g of %g (+ 2 errors)"
        % (run_length, len(fit_pts), statement["log_factor"], statement["value"]),
        data={"points": pts, "run_length": run_length,
              "arrhenius": {"a": a, "E": e, "T_g": tg, "T_g_error": tg_err},
              "vft": {"x0": x0, "x0_error": x0_err, "A": va, "B": vb}})


def plot(ax, pts, fits, paper_tg):
    """tau_r against x (log-log), the windows that tau_r exceeded as lower bounds, the
    Arrhenius line to the run length, and the paper's T_g."""
    reached = [p for p in pts if verdict.finite(p["tau_r"])]
    bounds = [p for p in pts if not verdict.finite(p["tau_r"])]
    ax.plot([p["x"] for p in reached], [p["tau_r"] for p in reached], "o", color="C0",
            label=r"$\tau_r$ ($F_s = 1/e$)")
    if bounds:
        ax.plot([p["x"] for p in bounds], [p["window"] for p in bounds], "^", color="C1",
                label=r"$\tau_r >$ window")
    arr = fits["arrhenius"]
    if verdict.finite(arr["a"], arr["E"], arr["T_g"]):
        xs = np.geomspace(arr["T_g"], max(p["x"] for p in pts), 200)
        ax.plot(xs, np.exp(arr["a"] + arr["E"] / xs), "-", color="0.3", lw=0.8,
                label="Arrhenius; $\\tau_r = %g$ at %.3g" % (fits["run_length"], arr["T_g"]))
    ax.axhline(fits["run_length"], color="0.7", ls=":", lw=0.8)
    ax.axvline(paper_tg, color="0.4", ls="--", lw=0.8)
    ax.text(paper_tg, 0.98, r" paper's $T_g$", fontsize=7, va="top", color="0.3",
            transform=ax.get_xaxis_transform())
    log_axis(ax, [p["x"] for p in pts] + [paper_tg])
    ax.set_yscale("log")
    ax.set_xlabel(r"$2 k_B T_c/(P\sigma^3)$")
    ax.set_ylabel(r"$\tau_r$")
    ax.legend(fontsize=7)
