"""The one steady-state criterion (docs/validation.md, Method, "Steady state"), the one every
figure, every verdict, the paper-scale records and the master curve use:
  the averaging window of a run is the last half of its production rows (what summary.json
  averages; for a run still going, the last half of the rows written so far); its two
  halves are the run's last two quarters. The run is steady when the means of the
  observable (A_t) over the two quarters, m3 and m4, agree within STEADY_FACTOR times their
  combined error, |m4 - m3| <= STEADY_FACTOR sqrt(e3^2 + e4^2), or when the drift is
  negligible, |m4 - m3| <= NEGLIGIBLE_DRIFT x the window's mean A_t^max.
  The quarter errors e_q = sqrt(var_q 2 tau_int / n_q) (var_q: the quarter's variance about
  the drift) come from the integrated autocorrelation time of the whole window
  (integrated_time, mean_error), measured on its fluctuations
  about the drift (each quarter's own mean and one common slope, so that a real step or ramp
  between the quarters inflates neither tau_int nor var_q) with Sokal's automatic window and
  the bias of the removed drift corrected. (summary.json's errors, summary_error, are the
  same estimator about the window's mean alone.)
  A state point is steady when every run of it is, and, where it was run from two starts
  (Fig. 4b: de-mixed and mixed), when the starts' means of the observable agree by the same
  test (start_agreement; a start with one run takes the error of its window's mean from the
  same estimator, window_error).
A run with fewer than two rows per quarter, or without a finite error, cannot be judged and
does not count as steady. Runs are workspace.Job objects (their series.csv)."""

import math

import numpy as np

from . import student
from .workspace import group

STEADY_FACTOR = 2.0
# A drift of A_t smaller than this fraction of the run's A_t^max moves A_n by less than about
# 0.015 (A_t^max / (A_t^max - min A_t) ~ 1.5 in these sweeps): below the precision of every
# statement on the page (0.05 and up), however many error bars it spans (a caged, de-mixed
# tissue ages by a few tenths of sigma^2 with an error bar smaller still).
NEGLIGIBLE_DRIFT = 0.01
# Sokal's automatic window: the autocorrelation is summed up to the smallest W with
# W >= SOKAL_C tau_int(W) (Madras and Sokal, J. Stat. Phys. 50, 109 (1988); 4-6 suits
# autocorrelations that decay about exponentially).
SOKAL_C = 5.0
# The window's cap: removing p fitted drift parameters from n rows biases every lag of the
# autocovariance by about -p C_F / n (C_F = 2 tau_int x variance), so the sum up to W is
# divided by 1 - p (2W + 1) / n (Wolff, Comput. Phys. Commun. 156, 143 (2004)); W is kept
# where p (2W + 1) / n <= MAX_FIT_SHARE, the correction at most a factor 3. That is the
# first-order form, which takes every lag's bias as the full p; the lag-t bias is really
# the lag-t diagonal sum of the fit's projection, smaller at large t, so at W = 13 on 124
# rows it over-corrects C_F by up to 1.4x, which about offsets the sum's truncation at the
# cap (tests/analysis/check_statistics.py, steady_*, measures the net false-alarm rates).
# A window of 124 rows (p = 3) allows W <= 13: a correlation time beyond ~3 rows then does
# not meet Sokal's criterion and tau_int is a lower bound (tau_capped).
MAX_FIT_SHARE = 2.0 / 3.0


def summary_error(y):
    """The standard error of a window's mean as summary.json's errors are computed
    (src/measure/mean_error.cpp): integrated_time on the fluctuations about the window's mean
    alone (one fitted parameter), then mean_error. Returns (error, tau_int, resolved: Sokal's
    criterion met, else both lower bounds); nan, nan, False for fewer than 2 values."""
    y = np.asarray(y, float)
    if len(y) < 2:
        return math.nan, math.nan, False
    r = y - y.mean()
    tau, removed, _, capped = integrated_time(r, 1)
    return mean_error(r, tau, removed), tau, not capped


def drift_residuals(y):
    """The fluctuations of a window (its last 2q rows, q = len // 2) about its drift, and the
    number of parameters fitted: each quarter's own mean plus one common slope, by least
    squares. The means take out a step between the quarters, the slope a ramp across them,
    so that neither counts as fluctuation in tau_int or in the quarters' variances."""
    y = np.asarray(y, float)
    q = len(y) // 2
    y = y[len(y) - 2 * q:]
    x = np.arange(q, dtype=float) - 0.5 * (q - 1)
    design = np.zeros((2 * q, 3))
    design[:q, 0] = design[q:, 1] = 1.0
    design[:q, 2] = design[q:, 2] = x
    coef = np.linalg.lstsq(design, y, rcond=None)[0]
    return y - design @ coef, design.shape[1]


def autocovariance(r, max_lag):
    """Gamma(t) = sum_i r_i r_(i+t) / n for t = 0..max_lag (Sokal's estimator: divided by n,
    not n - t, which keeps the long lags' noise down), by FFT."""
    n = len(r)
    f = np.fft.rfft(r, 2 * n)
    return np.fft.irfft(f * np.conj(f), 2 * n)[:max_lag + 1] / n


def integrated_time(r, fitted=1):
    """The integrated autocorrelation time of a series of fluctuations r (residuals about
    `fitted` least-squares drift parameters, drift_residuals), in rows, the factor by which
    correlation inflates the variance of a mean (2 tau_int, 1 for independent rows).
    Sokal's automatic window: tau_int(W) = 1/2 + sum_(t<=W) rho(t) up to the smallest W with
    W >= SOKAL_C tau_int(W), at most the cap of MAX_FIT_SHARE; then the bias of the fitted
    drift (Wolff 2004: every lag low by `fitted` C_F / n) corrected in C_F = 2 tau_int Gamma(0)
    and in the variance. tau_int is at least 1/2 (an anticorrelation is not credited).
    Returns (tau_int, removed = the variance the fit took out, W, capped: Sokal's criterion
    not met by the cap, tau_int then a lower bound)."""
    n = len(r)
    if n <= max(1, fitted):
        return math.nan, math.nan, 0, False
    w_max = max(0, int((MAX_FIT_SHARE * n / fitted - 1) / 2))
    gamma = autocovariance(np.asarray(r, float), min(w_max, n - 1))
    if not gamma[0] > 0.0:
        return 0.5, 0.0, 0, False
    running = 0.5 + np.cumsum(gamma) / gamma[0] - 1.0   # running[W] = tau_int(W)
    met = [w for w in range(1, len(gamma)) if w >= SOKAL_C * running[w]]
    window = met[0] if met else len(gamma) - 1
    c_f = 2.0 * running[window] * gamma[0] / (1.0 - fitted * (2 * window + 1) / n)
    variance = gamma[0] + fitted * c_f / n
    if c_f < variance:  # tau_int < 1/2: independent rows, the plain (n - fitted) variance
        variance = c_f = gamma[0] / (1.0 - fitted / n)
    return c_f / (2.0 * variance), variance - gamma[0], int(window), not met


def mean_error(r, tau_int, removed=0.0):
    """The standard error of a mean from its fluctuations r: sqrt(var 2 tau_int / n), var
    their mean square plus the variance the drift's fit took out (integrated_time's
    `removed`; with tau_int = 1/2 and one mean fitted, the usual std(ddof=1) / sqrt(n))."""
    r = np.asarray(r, float)
    return math.sqrt((float(np.mean(r ** 2)) + removed) * 2.0 * tau_int / len(r))


def window_error(y):
    """The error of a window's mean and its tau_int, by the criterion's estimator (the
    fluctuations about the quarters' drift, integrated_time): (error, tau_int). nan for
    fewer than two rows per quarter."""
    if len(y) // 2 < 2:
        return math.nan, math.nan
    r, fitted = drift_residuals(y)
    tau, removed = integrated_time(r, fitted)[:2]
    return mean_error(r, tau, removed), tau


def window(job, rows=None):
    """(first, end) row indices of the averaging window of the run's first `rows` rows (all by
    default): the last half of them (floor(n/2), as the protocols' summary, at least one);
    for a finished run, summary.json's `samples` of the
    column A_t when it states them."""
    n = len(job.series["time"]) if rows is None else rows
    samples = job.summary.get("averages", {}).get("A_t", {})
    samples = samples.get("samples") if isinstance(samples, dict) else None
    if rows is None and job.status == "done" and isinstance(samples, int) and 0 < samples <= n:
        return n - samples, n
    return window_rows(n, 1.0)


def steadiness(job, column="A_t", rows=None):
    """The criterion above for one run (over its first `rows` rows, all by default). Returns
    {job, steady (True/False/None: not judged), drift = m4 - m3, error = the combined error
    sqrt(e3^2 + e4^2), m3, m4, e3, e4 (each quarter's mean_error with the window's tau_int),
    tau_int (rows), tau_capped (Sokal's window capped: tau_int a lower bound), negligible
    (the floor, or None), samples (rows of the window), rows3, rows4 (the quarters'
    [first, end) rows)}."""
    s = job.series
    first, end = window(job, rows)
    y = s[column][first:end]
    q = len(y) // 2
    out = {"job": job.id, "samples": int(len(y)), "steady": None, "drift": math.nan,
           "error": math.nan, "negligible": None}
    if q < 2:
        return out
    a, b = y[len(y) - 2 * q:len(y) - q], y[len(y) - q:]
    r, fitted = drift_residuals(y)
    tau, removed, _, capped = integrated_time(r, fitted)
    m3, m4 = float(np.mean(a)), float(np.mean(b))
    e3, e4 = mean_error(r[:q], tau, removed), mean_error(r[q:], tau, removed)
    drift, err = m4 - m3, math.hypot(e3, e4)
    out.update({"drift": drift, "error": err, "m3": m3, "m4": m4, "e3": e3, "e4": e4,
                "tau_int": tau, "tau_capped": capped,
                "rows3": [end - 2 * q, end - q], "rows4": [end - q, end]})
    a_max = None
    if column == "A_t":
        a_max = (float(np.mean(s["A_t_max"][first:end])) if "A_t_max" in s
                 else job.mean("A_t_max")[0])
    out["steady"], out["negligible"] = judge(drift, err, a_max)
    return out


def judge(drift, error, a_max=None):
    """The criterion on one run's numbers (steadiness's; `sweep collect` writes them as the
    table's A_t_drift, A_t_drift_error and A_t_max): (steady: True, False or None when the
    error is not finite; the negligible-drift floor NEGLIGIBLE_DRIFT x a_max, or None)."""
    steady = bool(abs(drift) <= STEADY_FACTOR * error) if math.isfinite(error) else None
    negligible = None
    if a_max is not None and math.isfinite(a_max) and a_max > 0:
        negligible = NEGLIGIBLE_DRIFT * a_max
        if abs(drift) <= negligible:
            steady = True
    return steady, negligible


def run_reason(name, steady, drift, error):
    """Why a run named `name` does not count as steady (unsteady_runs', the master curve's)."""
    return "run %s %s" % (name, "drifts: m4 - m3 = %.3g +- %.2g" % (drift, error)
                          if steady is False else "not judged")


def start_agreement(jobs, key="start", column="A_t"):
    """The second half of a state point's criterion: the runs grouped by `key` (the start);
    each start's mean of `column` over its runs' averaging windows, its error the standard
    error over the runs (two or more) or, with one run, the error of its window's mean by the
    criterion's own estimator (window_error: tau_int of the window's fluctuations about
    its quarters' drift); the two starts agree when |difference| <= STEADY_FACTOR x the
    combined error (student.factor of its Welch-Satterthwaite degrees of freedom when the
    errors come from few runs) or is negligible (NEGLIGIBLE_DRIFT of the mean A_t^max).
    Returns {means: {start: (mean, error)}, difference, error, dof, agree} (agree None with
    fewer than two starts or without a finite error)."""
    means, amax, dofs = {}, [], []
    for (start,), reps in group(jobs, [key]).items():
        vals = []
        for j in reps:
            first, end = window(j)
            y = j.series[column][first:end]
            vals.append((float(np.mean(y)), window_error(y)[0]))
            if "A_t_max" in j.series:
                amax.append(float(np.mean(j.series["A_t_max"][first:end])))
        v = np.array([m for m, _ in vals])
        err = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) >= 2 else vals[0][1]
        means[str(start)] = (float(np.mean(v)), err)
        dofs.append(len(v) - 1 if len(v) >= 2 else None)
    out = {"means": means, "difference": math.nan, "error": math.nan, "dof": None,
           "agree": None}
    if len(means) != 2:
        return out
    (m1, e1), (m2, e2) = means.values()
    out["difference"], out["error"] = m2 - m1, math.hypot(e1, e2)
    out["dof"] = student.welch_dof([(e1, dofs[0]), (e2, dofs[1])])
    if math.isfinite(out["error"]):
        k = STEADY_FACTOR / 2.0 * student.factor(out["dof"])
        out["agree"] = bool(abs(m2 - m1) <= k * out["error"])
    if column == "A_t" and amax and abs(m2 - m1) <= NEGLIGIBLE_DRIFT * float(np.mean(amax)):
        out["agree"] = True
    return out


def point_steadiness(jobs, key="start"):
    """A state point's verdict by the criterion: (steady, reasons), steady when every run is
    steady and, if its runs differ in `key` (two starts), the starts agree; reasons name the
    runs that are not steady (or not judged) and a disagreement of the starts."""
    reasons = unsteady_runs(jobs)
    if len({str(j.sp.get(key)) for j in jobs}) == 2:
        a = start_agreement(jobs, key)
        if a["agree"] is not True:
            reasons.append("the starts %s: %s" % (
                "disagree" if a["agree"] is False else "cannot be compared",
                ", ".join("%s %.4g +- %.2g" % (k, m, e) for k, (m, e) in a["means"].items())))
    return not reasons, reasons


def unsteady_runs(jobs):
    """The first half of point_steadiness: the runs that are not steady (or not judged), each
    named with its drift. Alone it is the precondition of a row that compares the starts
    themselves (Fig. 4b's inset), which the second half would otherwise decide in advance."""
    reasons = []
    for j in jobs:
        s = steadiness(j)
        if s["steady"] is not True:
            reasons.append(run_reason(run_name(j.sp, j.id), s["steady"], s["drift"], s["error"]))
    return reasons


def run_name(sp, job_id):
    """A run as the page names it: its start and seed where its state point `sp` has them,
    else its id's first 8 characters."""
    parts = ["%s start" % sp["start"]] if "start" in sp else []
    parts += ["seed %s" % sp["seed"]] if "seed" in sp else []
    return ", ".join(parts) if parts else job_id[:8]


def steadiness_summary(jobs, column="A_t"):
    """The steady-state evidence of a set of jobs: counts and the largest |m4 - m3|/error."""
    rows = [steadiness(j, column) for j in jobs]
    judged = [r for r in rows if r["steady"] is not None]
    ratios = [abs(r["drift"]) / r["error"] for r in judged if r["error"] > 0]
    return {"jobs": len(rows), "judged": len(judged),
            "steady": sum(1 for r in judged if r["steady"]),
            "max_drift_over_error": max(ratios) if ratios else None, "rows": rows}


def unsteady_points(points, jobs_by_id, name):
    """The names (name(point)) of the state points (dicts with "jobs": ids) that are not
    steady by point_steadiness (a run not steady, or two starts that disagree)."""
    return [name(p) for p in points
            if not point_steadiness([jobs_by_id[i] for i in p["jobs"]])[0]]


def window_rows(rows, end_fraction):
    """(first, end) rows of the averaging window a run of `rows` rows would have had, had it
    ended at `end_fraction` of them: the last half of its first round(end_fraction x rows)
    rows (at least one row)."""
    end = max(1, int(round(end_fraction * rows)))
    return end - max(1, end // 2), end


def window_mean(job, column, end_fraction):
    """The mean of a series column over the window_rows of `end_fraction`."""
    y = job.series[column]
    first, end = window_rows(len(y), end_fraction)
    return float(np.mean(y[first:end]))


