"""The two fits of the master-curve analysis (docs/sweeps_analysis.md; the paper's Eq. (15)).

Per curve: A_n = (1/2)(tanh[b log10(x/a)] + 1), x = k_B T/(P sigma^3), fitted for
(log10 a, b) by weighted least squares with the state points' standard errors as absolute
sigmas. Across curves: a = c1 (1 + c2 q) r, q = beta eps_c/(P sigma^3), r = tau_g/tau_d."""

import math
import warnings

import numpy as np
from scipy.optimize import OptimizeWarning, curve_fit

from ..errors import InputError


def error_scale(chi2, dof):
    """The PDG scale factor of a fit's errors: sqrt(chi2/dof) when above 1 (the points scatter
    more than their errors: the scatter sets the errors), else 1; 1 without degrees of freedom."""
    return max(1.0, math.sqrt(chi2 / dof)) if dof > 0 else 1.0


def sigmoid_log(log_x, log_a, b):
    """The paper's Eq. (fitA) in log10 x and log10 a: the one form that fit_sigmoid, the joint
    fit with plateaus (plateaus.py) and the figures (sigmoid) use."""
    return 0.5 * (np.tanh(b * (log_x - log_a)) + 1.0)


def sigmoid(x, a, b):
    """The paper's Eq. (fitA): A_n as a function of x = k_B T/(P sigma^3) (the fitted function,
    as the figures draw it)."""
    return sigmoid_log(np.log10(np.asarray(x, float)), np.log10(a), b)


def _start(log_x, y):
    """Starting point: log10 a where the data cross 1/2 (else the middle), b = +-1 by trend."""
    order = np.argsort(log_x)
    lx, ly = log_x[order], y[order]
    slope = 1.0 if ly[-1] >= ly[0] else -1.0
    crossing = np.nonzero(np.diff(np.sign(ly - 0.5)))[0]
    if crossing.size:
        k = crossing[0]
        d = ly[k + 1] - ly[k]
        t = 0.5 if d == 0 else (0.5 - ly[k]) / d
        return lx[k] + t * (lx[k + 1] - lx[k]), slope
    return 0.5 * (lx[0] + lx[-1]), slope


def fit_sigmoid(x, y, sigma, name):
    """Fits one curve; x > 0, sigma > 0. Returns a, b, their standard errors (absolute:
    from the given sigmas), log10 a and its error, chi2, dof."""
    x, y, sigma = (np.asarray(v, float) for v in (x, y, sigma))
    if len(np.unique(x)) < 3:
        raise InputError("curve %s: %d state point%s at distinct temperatures, the sigmoid "
                         "fit (2 parameters) needs at least 3"
                         % (name, len(np.unique(x)), "" if len(np.unique(x)) == 1 else "s"))
    log_x = np.log10(x)
    p0 = _start(log_x, y)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            p, cov = curve_fit(sigmoid_log, log_x, y, p0=p0, sigma=sigma, absolute_sigma=True,
                               maxfev=20000)
    except (RuntimeError, ValueError) as e:
        raise InputError("curve %s: the sigmoid fit did not converge (%s)" % (name, e))
    note = None
    if np.all(np.isfinite(cov)):
        err = np.sqrt(np.diag(cov))
    else:
        err = np.array([math.inf] * 2)
        note = "the errors of a and b could not be estimated (the data do not constrain them)"
    chi2 = float(np.sum(((y - sigmoid_log(log_x, *p)) / sigma) ** 2))
    dof = len(x) - 2
    scale = error_scale(chi2, dof)
    err = err * scale
    # A flat curve (b ~ 0) puts its midpoint anywhere: log10 a may be beyond a double's range,
    # and a is then inf or 0 (numpy's values, not_a_fit names the curve) without a warning.
    with np.errstate(over="ignore"):
        a = np.float64(10.0) ** np.float64(p[0])
    return {"a": a, "a_error": a * math.log(10) * err[0], "log10_a": p[0],
            "log10_a_error": err[0], "b": p[1], "b_error": err[1], "chi2": chi2,
            "dof": dof, "error_scale": scale, "fit_note": note}


def not_a_fit(a, a_err, b, b_err):
    """Why a curve's sigmoid fit is not a fit, or None: a or b or an error is not finite,
    an error exceeds its parameter's magnitude (the data do not determine it: `b = -49 +- 62`
    is any slope, `a = 3e-5 +- 7e-5` any midpoint), or b is not positive (A_n must rise with
    the temperature for a to be the midpoint of the invasion). Such a curve is reported, drawn
    without its line, and left out of the collapse and of the fit of a."""
    if not all(math.isfinite(v) for v in (a, a_err, b, b_err)):
        return "a, b or their errors are not finite (a = %.3g +- %.2g, b = %.3g +- %.2g)" % (
            a, a_err, b, b_err)
    if not b > 0:
        return "b = %.3g +- %.2g is not positive (A_n does not rise with T)" % (b, b_err)
    if b_err > abs(b):
        return "the error of b exceeds b (b = %.3g +- %.2g)" % (b, b_err)
    if a_err > abs(a):
        return "the error of a exceeds a (a = %.3g +- %.2g)" % (a, a_err)
    return None


def midpoint_not_located(a, a_err, b, b_err, xs, ys, errs):
    """Why a curve's fitted midpoint a cannot enter the fit of a = c1 (1 + c2 q) r, or None.
    a is the temperature at A_n = 1/2 only for a rising sigmoid: b > 0, and the data rise
    (A_n at the highest temperature above that at the lowest by more than 2 combined errors;
    with b ~ 0 any a fits, with b < 0 A_n falls with T). The data must also bracket the
    midpoint, up to a factor 2 beyond the measured temperatures on either side."""
    if not all(math.isfinite(v) for v in (a, a_err, b, b_err)):
        return "the sigmoid fit has no finite a, b and errors"
    if not b > 0:
        return "not a rising sigmoid (b = %.3g +- %.2g): a is not a midpoint" % (b, b_err)
    lo, hi = int(np.argmin(xs)), int(np.argmax(xs))
    rise, e = ys[hi] - ys[lo], math.hypot(errs[hi], errs[lo])
    if not rise > 2 * e:
        return ("A_n does not rise across the measured temperatures (%.3g to %.3g, +- %.2g): "
                "a is not a midpoint" % (ys[lo], ys[hi], e))
    reach_hi = max(y + 2 * e for y, e in zip(ys, errs))
    reach_lo = min(y - 2 * e for y, e in zip(ys, errs))
    if not reach_lo <= 0.5 <= reach_hi:
        return ("A_n stays %s 1/2 at every measured temperature (beyond 2 errors): the midpoint "
                "a = %.3g is an extrapolation" % ("below" if reach_hi < 0.5 else "above", a))
    if not xs[lo] / 2 <= a <= 2 * xs[hi]:
        return ("the midpoint a = %.3g lies outside the measured temperatures %.3g-%.3g "
                "(a factor 2 either side allowed)" % (a, xs[lo], xs[hi]))
    return None


def _scale_model(qr, c1, c2):
    q, r = qr
    return c1 * (1.0 + c2 * q) * r


def _scale_model_c1(qr, c1):
    return c1 * qr[1]


def fit_scale(a, a_err, q, r, r_rel_err, iterations=20):
    """Fits a = c1 (1 + c2 q) r over curves (q = beta/P, r = tau_g/tau_d). Sigmas: the
    effective variance a_err^2 + (model * relative error of r)^2, iterated to a fixed point.
    c2 is fitted only if q takes at least two values; else only c1 (c2 = None). Returns a
    dict with c1, c2, errors (scaled by error_scale = max(1, sqrt(chi2/dof))), chi2, dof,
    chi2_dof (None if dof = 0), error_scale, n_curves, sigma."""
    a, a_err, q, r, r_rel = (np.asarray(v, float) for v in (a, a_err, q, r, r_rel_err))
    r_rel = np.where(np.isfinite(r_rel), r_rel, 0.0)
    with_c2 = len(np.unique(q)) >= 2
    n_par = 2 if with_c2 else 1
    if len(a) < n_par:
        raise InputError("%d curve%s usable for the fit of a (needs %d)"
                         % (len(a), "" if len(a) == 1 else "s", n_par))
    # Linear start: a/r = c1 + (c1 c2) q.
    if with_c2:
        k, c = np.polyfit(q, a / r, 1)
        p = np.array([c, k / c if c != 0 else 0.0])
        model = _scale_model
    else:
        p = np.array([np.mean(a / r)])
        model = _scale_model_c1
    sigma = a_err.copy()
    for _ in range(iterations):
        p_new, cov = curve_fit(model, (q, r), a, p0=p, sigma=sigma, absolute_sigma=True,
                               maxfev=20000)
        sigma = np.sqrt(a_err ** 2 + (model((q, r), *p_new) * r_rel) ** 2)
        done = np.allclose(p_new, p, rtol=1e-10, atol=0)
        p = p_new
        if done:
            break
    chi2 = float(np.sum(((a - model((q, r), *p)) / sigma) ** 2))
    dof = len(a) - n_par
    scale = error_scale(chi2, dof)  # as fit_sigmoid's: the curves' own scatter may set them
    err = np.sqrt(np.diag(cov)) * scale
    return {"c1": float(p[0]), "c1_error": float(err[0]),
            "c2": float(p[1]) if with_c2 else None,
            "c2_error": float(err[1]) if with_c2 else None,
            "chi2": chi2, "dof": dof, "chi2_dof": chi2 / dof if dof > 0 else None,
            "error_scale": scale, "n_curves": len(a), "sigma": sigma.tolist()}
