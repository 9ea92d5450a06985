"""State points of the validation figures and the temperatures where their curves cross a
level."""

import math

import numpy as np

def state_point(jobs, values):
    """Replicate means of named per-job values: values(job) -> {name: value}. The error of
    each is the standard error over replicates (n >= 2), else the job's own `<name>_error`."""
    rows = [values(j) for j in jobs]
    out = {"replicates": len(jobs), "jobs": [j.id for j in jobs]}
    for name in rows[0]:
        if name.endswith("_error"):
            continue
        v = np.array([r[name] for r in rows], float)
        out[name] = float(np.mean(v))
        if len(v) >= 2:
            out[name + "_error"] = float(np.std(v, ddof=1) / math.sqrt(len(v)))
        else:
            out[name + "_error"] = float(rows[0].get(name + "_error", math.nan))
    return out


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
