"""The normalised interfacial area A_n of the paper's Appendix C (docs/sweeps_analysis.md).

Per row (one job): rA_t = (A_t - dA)/(A_t^max - dA), dA = A_t^max - min A_t^max, i.e.
rA_t = 1 - (A_t^max - A_t)/min A_t^max. Then A_n = (rA_t - min rA_t)/(max rA_t - min rA_t).
The extremes (min A_t^max, min and max rA_t) are taken over the state points of the
normalisation group, each state point represented by the mean over its replicates (so that
one noisy replicate does not set the scale); rows outside the group are scaled the same way
and may fall outside [0, 1] (e.g. a tethered sweep normalised by its K_ecm = 0 sweep)."""

import math

import numpy as np

from .table import InputError


def point_means(values, points, rows):
    """{point: mean of values over `rows` of that point}."""
    sums = {}
    for i in rows:
        s = sums.setdefault(points[i], [0.0, 0])
        s[0] += values[i]
        s[1] += 1
    return {p: s[0] / s[1] for p, s in sums.items()}


def normalise(a_t, a_max, points, group, err_t=None, err_max=None, where="the sweep"):
    """Normalises one partition. a_t, a_max: per-row arrays; points: per-row state-point
    labels; group: per-row booleans (the normalisation group); err_t, err_max: per-row
    errors of the time averages (or None). Returns a dict with per-row rA, A_n and the run's
    own error of A_n (propagated, nan without error columns), and the extremes used."""
    a_t, a_max = np.asarray(a_t, float), np.asarray(a_max, float)
    members = [i for i in range(len(a_t)) if group[i]]
    if not members:
        raise InputError("the normalisation group of %s has no finished, steady job" % where)
    min_max = min(point_means(a_max, points, members).values())
    if min_max <= 0:
        raise InputError("the normalisation group of %s has min A_t^max = %g <= 0"
                         % (where, min_max))
    r_a = 1.0 - (a_max - a_t) / min_max
    means = point_means(r_a, points, members)
    lo, hi = min(means.values()), max(means.values())
    if not hi > lo:
        raise InputError("rA_t has the same mean (%g) at every state point of the "
                         "normalisation group of %s (%d state point%s): A_n is undefined"
                         % (lo, where, len(means), "" if len(means) == 1 else "s"))
    a_n = (r_a - lo) / (hi - lo)
    if err_t is not None:
        e_max = np.zeros_like(a_t) if err_max is None else np.asarray(err_max, float)
        run_err = np.sqrt(np.asarray(err_t, float) ** 2 + e_max ** 2) / min_max / (hi - lo)
    else:
        run_err = np.full_like(a_t, math.nan)
    extremes = {}
    for side, value in (("lo", lo), ("hi", hi)):
        point = next(p for p, m in means.items() if m == value)
        extremes[side] = _mean_error([i for i in members if points[i] == point], a_n, run_err)
    return {"rA_t": r_a, "A_n": a_n, "A_n_run_error": run_err, "min_A_t_max": min_max,
            "min_rA_t": lo, "max_rA_t": hi, "group_points": len(means),
            "group_rows": len(members), "error_lo": extremes["lo"],
            "error_hi": extremes["hi"]}


def _mean_error(rows, a_n, run_err):
    """Standard error of the mean A_n of the given rows (one row: its run's own error)."""
    if len(rows) > 1:
        return float(np.std(a_n[rows], ddof=1) / math.sqrt(len(rows)))
    return float(run_err[rows[0]])
