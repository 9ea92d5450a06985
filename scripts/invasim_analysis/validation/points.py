"""State points of the validation figures and the temperatures where their curves cross a
level."""

import math

import numpy as np

from .. import normalise, steady


def state_point(jobs, values):
    """Replicate means of named per-job values: values(job) -> {name: value}. The error of
    each is the standard error over replicates (n >= 2), else the job's own `<name>_error`.
    Where the values hold A_t and A_t_max, also the gap A_t_max - A_t that A_n is made of
    (normalise.py), whose error A_gap_error carries the covariance of the two: the
    replicates' scatter of the gap, or the run's own error of its window's gap (gap_error)."""
    rows = [values(j) for j in jobs]
    if "A_t" in rows[0] and "A_t_max" in rows[0]:
        for j, r in zip(jobs, rows):
            r["A_gap"] = r["A_t_max"] - r["A_t"]
            if "A_gap_error" not in r:
                r["A_gap_error"] = gap_error(j)
    out = {"replicates": len(jobs), "jobs": [j.id for j in jobs]}
    for name in rows[0]:
        if name.endswith("_error"):
            continue
        v = np.array([r[name] for r in rows], float)
        out[name] = float(np.mean(v))
        if len(v) >= 2:
            out[name + "_error"] = float(np.std(v, ddof=1) / math.sqrt(len(v)))
            out[name + "_dof"] = len(v) - 1
        else:
            out[name + "_error"] = float(rows[0].get(name + "_error", math.nan))
    return out


def pooled_errors(curve, name, axis="x", window=1):
    """Replaces the replicate errors of `name` of the state points of one curve (dicts from
    state_point, ordered by `axis` here) by standard errors from the replicate variance pooled
    over each point and its `window` neighbours on each side along it (dof-weighted, as the
    master curve pools A_n: master_curve/analysis.py, build_points), and sets name_dof, their
    degrees of freedom: two replicates alone give one, and a standard error from them is near
    zero by chance often enough that "2 errors" covers the truth 70 % of the time, not 95 %;
    the verdicts take student.factor(dof) errors instead of 2. A point with no replicates in
    its window keeps its run's own error (name_dof None)."""
    pts = sorted(curve, key=lambda p: p[axis])
    spread = [(p["replicates"] - 1, p[name + "_error"] ** 2 * p["replicates"])
              if p["replicates"] >= 2 else (0, 0.0) for p in pts]
    for k, p in enumerate(pts):
        near = spread[max(0, k - window):k + window + 1]
        dof = sum(d for d, _ in near)
        p[name + "_dof"] = dof if dof > 0 else None
        if dof > 0:
            var = sum(d * v for d, v in near) / dof
            p[name + "_error"] = math.sqrt(var / p["replicates"])
    return curve


def least_dof(pts, name="A_n"):
    """The fewest degrees of freedom of the points' `name` errors (None: every one a run's
    own), for a row that rests on several of them through a maximum or an interpolation."""
    dofs = [p.get(name + "_dof") for p in pts]
    finite = [d for d in dofs if d is not None]
    return min(finite) if finite else None


def runs_a_n(jobs, extremes):
    """A_n of each run scaled with `extremes` (normalise.scale_like of job_areas), and their
    mean, its error and that error's degrees of freedom: the standard error over the runs
    (n - 1), or with one run its own error (None: many)."""
    pts = [normalise.scale_like(job_areas(j), extremes) for j in jobs]
    vals = np.array([p["A_n"] for p in pts])
    if len(vals) > 1:
        return vals, float(vals.mean()), float(vals.std(ddof=1) / math.sqrt(len(vals))), len(vals) - 1
    return vals, float(vals.mean()), pts[0]["A_n_error"], None


def gap_error(job, end_fraction=None):
    """The run's own error of the mean of A_t_max - A_t over its averaging window (the series,
    so that the covariance of A_t and A_t^max is in it; they move together as the box
    breathes), by the same estimator as the steady-state test's errors (steady.window_error);
    with end_fraction, over the window steady.window_mean takes for that time."""
    s = job.series
    if "A_t" not in s or "A_t_max" not in s:
        return math.nan
    if end_fraction is None:
        first, end = steady.window(job)
    else:
        first, end = steady.window_rows(len(s["A_t"]), end_fraction)
    return steady.window_error(np.asarray(s["A_t_max"][first:end], float)
                               - np.asarray(s["A_t"][first:end], float))[0]


def job_areas(job):
    """One run as a state point of its own, for normalise.scale_like: its means of A_t and
    A_t_max (summary.json), the error of A_t and the error of the gap (gap_error)."""
    return {"A_t": job.mean("A_t")[0], "A_t_max": job.mean("A_t_max")[0],
            "A_t_error": job.mean("A_t")[1], "A_gap_error": gap_error(job)}


def crossing(x, y, level=0.5):
    """The x (log-interpolated) where y first crosses `level` going up, or nan."""
    order = np.argsort(x)
    x, y = np.asarray(x, float)[order], np.asarray(y, float)[order]
    for k in range(len(x) - 1):
        if y[k] < level <= y[k + 1] and x[k] > 0 and x[k + 1] > 0:
            t = (level - y[k]) / (y[k + 1] - y[k])
            return float(10 ** (math.log10(x[k]) + t * (math.log10(x[k + 1]) - math.log10(x[k]))))
    return math.nan


def crossing_bound(x, y, err, level=0.5):
    """Where the curve lies wholly on one side of `level` (so crossing(x, y) is nan), the side
    and the edge of the scanned range it bounds: ("above", max x) when every y is below level
    by more than 2 errors (the crossing lies above the hottest point), ("below", min x) when
    every y is above it; (None, nan) otherwise (a crossing, or points too close to level to
    say)."""
    x, y, err = (np.asarray(v, float) for v in (x, y, err))
    if len(x) == 0:
        return None, math.nan
    err = np.where(np.isfinite(err), err, 0.0)
    if np.all(y + 2 * err < level):
        return "above", float(np.max(x))
    if np.all(y - 2 * err >= level):
        return "below", float(np.min(x))
    return None, math.nan


def crossing_log_error(x, y, err, level=0.5):
    """The error of log10 of crossing(x, y): the larger A_n error of the two bracketing points
    over the slope dA_n/dlog10 x between them (nan without a crossing or errors)."""
    order = np.argsort(x)
    x, y, err = (np.asarray(v, float)[order] for v in (x, y, err))
    for k in range(len(x) - 1):
        if y[k] < level <= y[k + 1] and x[k] > 0 and x[k + 1] > 0:
            slope = (y[k + 1] - y[k]) / (math.log10(x[k + 1]) - math.log10(x[k]))
            return float(max(err[k], err[k + 1]) / slope)
    return math.nan


def interpolate_log(x, y, at):
    """y at x = `at`, linear in log10 x between the nearest points, or nan outside."""
    order = np.argsort(x)
    x, y = np.asarray(x, float)[order], np.asarray(y, float)[order]
    if len(x) < 2 or not (x[0] <= at <= x[-1]):
        return math.nan
    return float(np.interp(math.log10(at), np.log10(x), y))
