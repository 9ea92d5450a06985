"""The normalised interfacial area A_n of the paper's Appendix C (docs/sweeps_analysis.md),
the one normalisation of the master curve and the validation page.

Per job or state point: rA_t = (A_t - dA)/(A_t^max - dA), dA = A_t^max - min A_t^max, i.e.
rA_t = 1 - (A_t^max - A_t)/min A_t^max. Then A_n = (rA_t - min rA_t)/(max rA_t - min rA_t).
The extremes (min A_t^max, min and max rA_t) are taken over the state points of the
normalisation group, each state point represented by the mean over its replicates (so that
one noisy replicate does not set the scale); anything outside the group is scaled the same way
and may fall outside [0, 1] (e.g. a tethered sweep normalised by its K_ecm = 0 sweep). The
run's own error of A_n is that of A_t (and A_t^max) over min A_t^max and the span of rA_t."""

import math

import numpy as np

from .errors import InputError


def relative_area(a_t, a_max, min_a_max):
    """rA_t = 1 - (A_t^max - A_t)/min A_t^max (numbers or arrays)."""
    return 1.0 - (a_max - a_t) / min_a_max


def scaled(r_a, lo, hi):
    """A_n = (rA_t - lo)/(hi - lo); nan when hi > lo does not hold."""
    return (r_a - lo) / (hi - lo) if hi > lo else math.nan


def run_error(err_t, err_max, min_a_max, lo, hi):
    """The error of A_n from those of A_t and A_t^max (err_max None: 0)."""
    if not hi > lo:
        return math.nan
    e_max = 0.0 if err_max is None else err_max
    return np.sqrt(err_t ** 2 + e_max ** 2) / min_a_max / (hi - lo)


def point_means(values, points, rows):
    """{point: mean of values over `rows` of that point}."""
    sums = {}
    for i in rows:
        s = sums.setdefault(points[i], [0.0, 0])
        s[0] += values[i]
        s[1] += 1
    return {p: s[0] / s[1] for p, s in sums.items()}


def extremes(a_t, a_max, points, members):
    """min A_t^max, and min and max rA_t, over the state points (labels `points`, per row) of
    the rows `members`, each state point its replicates' mean. Returns (min_a_max, lo, hi,
    {point: mean rA_t})."""
    min_max = min(point_means(a_max, points, members).values())
    means = point_means(relative_area(np.asarray(a_t, float), np.asarray(a_max, float),
                                      min_max), points, members)
    return float(min_max), float(min(means.values())), float(max(means.values())), means


def normalise_group(a_t, a_max, points, group, err_t=None, err_max=None, where="the sweep"):
    """Normalises one partition of jobs (the master curve). a_t, a_max: per-row arrays;
    points: per-row state-point labels; group: per-row booleans (the normalisation group);
    err_t, err_max: per-row errors of the time averages (or None). Returns a dict with per-row
    rA, A_n and the run's own error of A_n (propagated, nan without error columns), and the
    extremes used; InputError when the group cannot set them."""
    a_t, a_max = np.asarray(a_t, float), np.asarray(a_max, float)
    members = [i for i in range(len(a_t)) if group[i]]
    if not members:
        raise InputError("the normalisation group of %s has no finished, steady job" % where)
    min_max = min(point_means(a_max, points, members).values())
    if min_max <= 0:
        raise InputError("the normalisation group of %s has min A_t^max = %g <= 0"
                         % (where, min_max))
    min_max, lo, hi, means = extremes(a_t, a_max, points, members)
    if not hi > lo:
        raise InputError("rA_t has the same mean (%g) at every state point of the "
                         "normalisation group of %s (%d state point%s): A_n is undefined"
                         % (lo, where, len(means), "" if len(means) == 1 else "s"))
    r_a = relative_area(a_t, a_max, min_max)
    a_n = scaled(r_a, lo, hi)
    if err_t is not None:
        run_err = run_error(np.asarray(err_t, float),
                            None if err_max is None else np.asarray(err_max, float),
                            min_max, lo, hi)
    else:
        run_err = np.full_like(a_t, math.nan)
    ends = {}
    for side, value in (("lo", lo), ("hi", hi)):
        point = next(p for p, m in means.items() if m == value)
        ends[side] = _mean_error([i for i in members if points[i] == point], a_n, run_err)
    return {"rA_t": r_a, "A_n": a_n, "A_n_run_error": run_err, "min_A_t_max": min_max,
            "min_rA_t": lo, "max_rA_t": hi, "group_points": len(means),
            "group_rows": len(members), "error_lo": ends["lo"], "error_hi": ends["hi"]}


def _mean_error(rows, a_n, run_err):
    """Standard error of the mean A_n of the given rows (one row: its run's own error)."""
    if len(rows) > 1:
        return float(np.std(a_n[rows], ddof=1) / math.sqrt(len(rows)))
    return float(run_err[rows[0]])


def normalise(points):
    """The same over state points already averaged (the validation figures). `points`: list
    of dicts with A_t, A_t_max (replicate means) and A_t_error, all of them the group. Adds
    rA_t, A_n, A_n_error; returns the extremes (for scale_like)."""
    if not points:
        raise InputError("no state points to normalise")
    min_max, lo, hi, _ = extremes([p["A_t"] for p in points], [p["A_t_max"] for p in points],
                                  list(range(len(points))), range(len(points)))
    ext = {"min_A_t_max": min_max, "min_rA_t": lo, "max_rA_t": hi}
    for p in points:
        scale_like(p, ext)
    return ext


def scale_like(point, extremes):
    """A_n of a state point (dict with A_t, A_t_max, optionally A_gap_error or A_t_error)
    with the extremes of normalise(). A_n is linear in the gap A_t^max - A_t, so its error is
    the gap's (A_gap_error: validation/points.py, with the covariance of A_t and A_t^max);
    without it, A_t's alone."""
    lo, hi, min_max = extremes["min_rA_t"], extremes["max_rA_t"], extremes["min_A_t_max"]
    point["rA_t"] = relative_area(point["A_t"], point["A_t_max"], min_max)
    point["A_n"] = scaled(point["rA_t"], lo, hi)
    err = point.get("A_gap_error", point.get("A_t_error", math.nan))
    point["A_n_error"] = float(run_error(err, None, min_max, lo, hi))
    point["A_n_dof"] = point.get("A_gap_dof")  # A_n's error is a multiple of the gap's
    return point
