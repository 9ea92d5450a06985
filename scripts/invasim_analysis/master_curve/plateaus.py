"""The per-curve fits with the normalisation's extremes as fitted parameters
(docs/sweeps_analysis.md, "Plateaus fitted, not taken from the extremes").

A_n = (rA_t - min rA_t)/(max rA_t - min rA_t) takes its extremes from the noisiest numbers of
the sweep: the largest and the smallest of many noisy state-point means, biased outward (an
extreme of noisy means overshoots the plateau it estimates). When the noise grows with A_t
(a larger interface fluctuates more), the upper extreme overshoots most: every A_n is pulled
down, the fitted midpoint a comes out high (about 1.6 of its errors, c1 about 3.4, with 3 %
relative noise on A_t), b low. Fitting A_n = L + (H - L)(1/2)(tanh[b log10(x/a)] + 1) over all
curves of the normalisation group at once, with the plateaus L and H (nominally 0 and 1)
shared and fitted, removes that bias: a and b then no longer depend on which state point
happened to be the extreme, and the plateaus' own uncertainty enters a's and b's errors
through the joint covariance. Curves outside the group (e.g. tethered curves normalised by
the untethered sweep) are refitted on A_n rescaled to the fitted plateaus."""

import math
import warnings

import numpy as np
from scipy.optimize import OptimizeWarning, curve_fit

from . import fits


def _joint_model(layout):
    """The model of the stacked points of all curves: layout = per point its curve index and
    log10 x; parameters L, H, then (log10 a, b) per curve."""
    k, log_x = layout

    def model(_, lo, hi, *ab):
        ab = np.asarray(ab).reshape(-1, 2)
        return lo + (hi - lo) * fits.sigmoid_log(log_x, ab[k, 0], ab[k, 1])

    return model


def fit_joint(curves):
    """Fits the curves (each a dict with `points` whose A_n_error_own are the state points'
    errors without the extremes' share, and a first fit `log10_a`, `b`) with shared plateaus.
    Returns None if the joint fit is not possible (too few points, no convergence, undefined
    errors), else {lo, hi, their errors, chi2, dof, per_curve: [fit dicts as fits.fit_sigmoid
    returns]}."""
    k, log_x, y, sigma = [], [], [], []
    for n, c in enumerate(curves):
        for p in c["points"]:
            k.append(n)
            log_x.append(math.log10(p["x"]))
            y.append(p["A_n"])
            sigma.append(p["A_n_error_own"])
    k, log_x, y, sigma = (np.asarray(v) for v in (k, log_x, y, sigma))
    n_par = 2 + 2 * len(curves)
    if len(y) <= n_par or any(len(c["points"]) < 3 for c in curves):
        return None
    p0 = [0.0, 1.0] + [v for c in curves for v in (c["log10_a"], c["b"])]
    model = _joint_model((k, log_x))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            p, cov = curve_fit(model, np.zeros(len(y)), y, p0=p0, sigma=sigma,
                               absolute_sigma=True, maxfev=20000)
    except (RuntimeError, ValueError):
        return None
    if not np.all(np.isfinite(cov)) or not p[1] > p[0]:
        return None
    err = np.sqrt(np.diag(cov))
    residual = (y - model(None, *p)) / sigma
    chi2_all, dof_all = float(np.sum(residual ** 2)), int(len(y) - n_par)
    joint_scale = fits.error_scale(chi2_all, dof_all)  # the shared plateaus', as every fit's
    out = {"lo": float(p[0]), "lo_error": float(err[0]) * joint_scale, "hi": float(p[1]),
           "hi_error": float(err[1]) * joint_scale, "chi2": chi2_all, "dof": dof_all,
           "error_scale": joint_scale, "per_curve": []}
    for n, c in enumerate(curves):
        mine = k == n
        chi2 = float(np.sum(residual[mine] ** 2))
        dof = int(np.sum(mine)) - 2
        scale = fits.error_scale(chi2, dof)
        la, b = p[2 + 2 * n], p[3 + 2 * n]
        e_la, e_b = err[2 + 2 * n] * scale, err[3 + 2 * n] * scale
        a = 10.0 ** la
        out["per_curve"].append({"a": a, "a_error": a * math.log(10) * e_la, "log10_a": la,
                                 "log10_a_error": e_la, "b": b, "b_error": e_b, "chi2": chi2,
                                 "dof": dof, "error_scale": scale, "fit_note": None,
                                 "plateaus": (float(p[0]), float(p[1]))})
    return out


def refit_outside(c, lo, hi, lo_err, hi_err):
    """Refits a curve outside the normalisation group on A_n rescaled to the fitted plateaus,
    A_n' = (A_n - L)/(H - L), the plateaus' errors propagated as for the extremes."""
    span = hi - lo
    ys, errs = [], []
    for p in c["points"]:
        y = (p["A_n"] - lo) / span
        e = math.sqrt(p["A_n_error_own"] ** 2 + ((1 - y) * lo_err) ** 2 + (y * hi_err) ** 2)
        ys.append(y)
        errs.append(e / span)
    fit = fits.fit_sigmoid([p["x"] for p in c["points"]], ys, errs, c["name"])
    fit["plateaus"] = (lo, hi)
    return fit


def refine(curves, in_group, partition_of):
    """Replaces the per-curve fits by the joint fits with fitted plateaus, per normalisation
    partition. in_group[name]: True if every job of the curve is in the normalisation group;
    partition_of[name]: its partition (None if it spans several: left as it is). Returns the
    per-partition records of the fitted plateaus (for fits.json)."""
    records = []
    for part in sorted({v for v in partition_of.values() if v is not None}, key=repr):
        members = [c for c in curves if partition_of[c["name"]] == part]
        group = [c for c in members if in_group[c["name"]]
                 and fits.not_a_fit(c["a"], c["a_error"], c["b"], c["b_error"]) is None]
        joint = fit_joint(group) if group else None
        if joint is None:
            records.append({"partition": part, "done": False,
                            "reason": "no curve of the normalisation group fits, or too few "
                            "state points for the shared plateaus: the plateaus are the "
                            "extremes of the state-point means"})
            continue
        for c, fit in zip(group, joint.pop("per_curve")):
            c.update(fit)
        for c in members:
            if c in group:
                continue
            try:
                c.update(refit_outside(c, joint["lo"], joint["hi"], joint["lo_error"],
                                       joint["hi_error"]))
            except fits.InputError as e:  # no convergence: the min-max fit stands
                c["fit_note"] = "not refitted on the fitted plateaus (%s)" % e
        joint.update({"partition": part, "done": True,
                      "curves": [c["name"] for c in group]})
        records.append(joint)
    return records
