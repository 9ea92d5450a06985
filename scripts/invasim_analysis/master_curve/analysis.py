"""The analysis from a results table to fitted curves: per-row temperatures and A_n, state
points (replicate means), curves and their fits, the fit of the scale a across curves."""

import math

import numpy as np

from .. import steady
from ..errors import InputError
from ..normalise import normalise_group
from .selection import Keys, canonical, group_indices, matches

# --temperature: column read per row, and the axis label (the convention said plainly).
TEMPERATURES = {
    "kT": ("kT", r"$k_B T/(P\sigma^3)$, $k_B T$ = the set background temperature (state point kT)"),
    "T_c": ("T_c", r"$k_B T_c/(P\sigma^3)$, measured, equipartition $k_B T_c = (m/3N)\sum v^2$"),
    "kT_c_paper": ("kT_c_paper", r"$k_B T/(P\sigma^3)$, measured, the paper's "
                   r"$k_B T = (2m/3N)\sum v^2 = 2\,k_B T_c$"),
}
DEFAULT_GAMMA = 0.2  # gamma = 0.2 sqrt(m eps_c)/sigma, tau_g = m/gamma = 5 (m = 1): docs/model.md


def _sem(values):
    """Standard error of the mean (nan for a single value)."""
    v = np.asarray(values, float)
    return float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) > 1 else math.nan


def _constant(keys, rows, key, why):
    """The value of `key` if it is the same on every row (None if not, or if it is absent)."""
    if not keys.known(key):
        return None
    values = {keys.number(r, key, why) for r in rows}
    return values.pop() if len(values) == 1 else None


def row_values(table, keys, rows, temperature):
    """Per-row arrays: x = T/P in the chosen convention, A_t, A_t^max and their errors."""
    column = TEMPERATURES[temperature][0]
    why_t = "for the temperature axis (--temperature %s)" % temperature
    x, a_t, a_max = [], [], []
    for r in rows:
        t = (keys.number(r, column, why_t) if column in keys.state_keys or column in keys.fixed
             else table.number(r, column, why_t))
        p = keys.number(r, "P", "to scale the temperature, k_B T/(P sigma^3)")
        if not (t > 0 and p > 0):
            raise InputError("%s: %s = %g and P = %g: k_B T/(P sigma^3) must be > 0 for the "
                             "logarithmic fit (--temperature %s)"
                             % (table.where(r), column, t, p, temperature))
        x.append(t / p)
        a_t.append(table.number(r, "A_t", "for A_n"))
        a_max.append(table.number(r, "A_t_max", "for A_n"))
    errors = [None, None]
    for k, name in enumerate(("A_t_error", "A_t_max_error")):
        if table.has(name):
            errors[k] = np.array([table.number(r, name, "", allow_missing=True) for r in rows])
    return np.array(x), np.array(a_t), np.array(a_max), errors[0], errors[1]


def same_number_written_twice(keys, rows):
    """Warnings for state-point values that are one number written two ways (tau_p = 25 and
    25.0: two jobs, as `sweep collect` keeps an integer and a float apart, docs/sweeps.md),
    which the analysis compares as numbers and so puts in one state point; and for jobs
    that are then the same state point and the same replicate twice."""
    out = []
    for key in keys.state_keys:
        texts = {}
        for r in rows:
            texts.setdefault(canonical(r[key]), set()).add(r[key])
        for value, written in texts.items():
            if len(written) > 1:
                out.append("%s: %s are one value written %d ways (different jobs of the sweep): "
                           "analysed as one state point" % (key, " and ".join(sorted(written)),
                                                            len(written)))
    seen = {}
    for r in rows:
        label = keys.label(r, keys.state_keys)
        if label in seen:
            out.append("jobs %s and %s have the same state point and replicate (%s): both "
                       "count as replicates" % (seen[label], r.get("job_id") or r["_line"],
                                                ", ".join("%s=%s" % kv for kv in
                                                          zip(keys.state_keys, label))))
        else:
            seen[label] = r.get("job_id") or r["_line"]
    return out


def drift_steadiness(table, rows, max_drift, point_of):
    """Per row: None if its state point is steady, else why not. A state point is not steady
    when a quantity's relative drift over the averaging window, averaged over its replicates,
    exceeds the limit: mean over replicates of K_drift/K > limit in magnitude (K_drift: the
    `<K>_drift` column of `sweep collect`, the second half's mean minus the first half's).
    Averaging over replicates keeps one fluctuating replicate from deciding. Returns the
    reasons and the keys that could not be checked (no `<K>_drift` column)."""
    reasons, unchecked = [None] * len(rows), []
    for key, limit in max_drift:
        if not (table.has(key) and table.has(key + "_drift")):
            unchecked.append(key)
            continue
        relative = {}
        for i, r in enumerate(rows):
            mean = table.number(r, key, "for --max-drift", allow_missing=True)
            drift = table.number(r, key + "_drift", "for --max-drift", allow_missing=True)
            if math.isfinite(mean) and math.isfinite(drift) and mean != 0:
                relative.setdefault(point_of[i], []).append(drift / mean)
        for i in range(len(rows)):
            values = relative.get(point_of[i])
            if values and abs(np.mean(values)) > limit:
                why = ("%s drifts by %+.3g of its mean over the averaging window (mean of %d "
                       "replicate%s; limit %g)" % (key, np.mean(values), len(values),
                                                   "" if len(values) == 1 else "s", limit))
                reasons[i] = why if reasons[i] is None else reasons[i] + "; " + why
    return reasons, unchecked


def runs_steadiness(table, rows, point_of):
    """Per row: None if its state point is steady by the one steady-state criterion
    (steady.judge on each run's A_t_drift, A_t_drift_error and A_t_max, which `sweep
    collect` computes from the run's series.csv as steady.steadiness does), else why not: a
    state point is steady when all its runs are. None (not judged) for a table without the
    A_t_drift_error column (from an older `sweep collect`)."""
    if not (table.has("A_t_drift") and table.has("A_t_drift_error") and table.has("A_t_max")):
        return None
    reasons = [None] * len(rows)
    for idx in group_indices(point_of).values():
        why = []
        for i in idx:
            r = rows[i]
            drift, error, a_max = (table.number(r, name, "for the steadiness of A_t",
                                                allow_missing=True)
                                   for name in ("A_t_drift", "A_t_drift_error", "A_t_max"))
            # A drift without an error (fewer than 2 rows per half) is not judged, as
            # steady.steadiness does not judge such a window.
            ok = (steady.judge(drift, error, a_max)[0]
                  if math.isfinite(drift) and math.isfinite(error) else None)
            if ok is not True:
                sp = {k: r[k] for k in ("start", "seed") if r.get(k, "") != ""}
                why.append(steady.run_reason(steady.run_name(sp, r.get("job_id", "")), ok,
                                             drift, error))
        if why:
            for i in idx:
                reasons[i] = "A_t not steady: " + "; ".join(why)
    return reasons


def a_n_by_partition(part_of, within, in_group, a_t, a_max, err_t, err_max, point_of,
                     is_steady):
    """A_n per row, normalised separately in each partition (part_of: per row its values of
    the --normalise-within keys `within`); the rows in_group (--normalise-by) that are steady
    set the extremes, the others are scaled like them (docs/sweeps_analysis.md, steps 0-1).
    Also the validation page's Fig. 5 (one partition, every curve of the figure)."""
    n = len(part_of)
    r_a, a_n, run_err = np.empty(n), np.empty(n), np.empty(n)
    norm_err = np.empty((n, 2))
    info = []
    parts = group_indices(part_of)
    for part, idx in parts.items():
        where = ", ".join("%s=%s" % kv for kv in zip(within, part)) or "the whole sweep"
        sel = [in_group[i] and is_steady[i] for i in idx]
        res = normalise_group(a_t[idx], a_max[idx], [point_of[i] for i in idx], sel,
                        None if err_t is None else err_t[idx],
                        None if err_max is None else err_max[idx], where)
        r_a[idx], a_n[idx], run_err[idx] = res["rA_t"], res["A_n"], res["A_n_run_error"]
        norm_err[idx] = (res["error_lo"], res["error_hi"])
        info.append({"partition": dict(zip(within, part)), "min_A_t_max": res["min_A_t_max"],
                     "min_rA_t": res["min_rA_t"], "max_rA_t": res["max_rA_t"],
                     "group_state_points": res["group_points"], "group_jobs": res["group_rows"],
                     "A_n_error_of_min": res["error_lo"], "A_n_error_of_max": res["error_hi"]})
    return r_a, a_n, run_err, norm_err, info


def build_points(idx, x, a_n, run_err, norm_err, min_error, window=1):
    """State points of one curve: mean x and A_n over replicates. The error of A_n is the
    standard error over replicates, with the replicate variance pooled over the state point
    and its `window` neighbours on each side along x (dof-weighted), so that 2-4 replicates
    give usable weights; a state point without replicates anywhere in its window takes its
    run's own propagated error (floored at min_error: A_n_error_own, the sigma of the fit
    with fitted plateaus, plateaus.py). The errors of the two state points that set the
    normalisation (norm_err: per row, of the min and of the max) are added in quadrature,
    weighted (1 - A_n) and A_n (A_n_error_raw). Floored at min_error: A_n_error."""
    out = []
    for i_rows in idx:
        y = a_n[i_rows]
        n = len(i_rows)
        out.append({"rows": i_rows, "x": float(np.mean(x[i_rows])), "x_error": _sem(x[i_rows]),
                    "A_n": float(np.mean(y)), "replicates": n,
                    "var": float(np.var(y, ddof=1)) if n > 1 else 0.0, "dof": n - 1})
    out.sort(key=lambda p: p["x"])
    for k, p in enumerate(out):
        near = out[max(0, k - window):k + window + 1]
        dof = sum(q["dof"] for q in near)
        if dof > 0:
            err = math.sqrt(sum(q["dof"] * q["var"] for q in near) / dof / p["replicates"])
        else:
            err = float(np.mean(run_err[p["rows"]])) / math.sqrt(p["replicates"])
        p["A_n_error_own"] = max(err, min_error) if math.isfinite(err) else min_error
        lo, hi = norm_err[p["rows"][0]]
        a = p["A_n"]
        if math.isfinite(lo) and math.isfinite(hi):
            err = math.sqrt(err ** 2 + ((1 - a) * lo) ** 2 + (a * hi) ** 2)
        p["A_n_error_raw"] = err
        p["A_n_error"] = max(err, min_error) if math.isfinite(err) else min_error
    for p in out:
        del p["var"], p["dof"]
    return out


def curve_scale_inputs(keys, table, rows, tau_g_opt):
    """beta, P, tau_g, mean tau_d and its standard error for one curve (None where absent or
    not constant over the curve), with the reason a curve cannot enter the fit of a."""
    beta = _constant(keys, rows, "beta", "for the fit of a")
    p = _constant(keys, rows, "P", "for the fit of a")
    if tau_g_opt is not None:
        tau_g = tau_g_opt
    elif keys.known("gamma"):
        g = _constant(keys, rows, "gamma", "for tau_g = m/gamma")
        tau_g = None if g is None or g <= 0 else 1.0 / g
    else:
        tau_g = 1.0 / DEFAULT_GAMMA
    tau_d = np.array([table.number(r, "tau_d", "for the fit of a", allow_missing=True)
                      for r in rows]) if table.has("tau_d") else np.array([])
    mean, error, used = mean_tau_d(tau_d)
    # Jobs whose tau_d is empty, NaN, infinite or not positive: named, left out of the mean.
    dropped = [{"job": r.get("job_id") or "line %d" % r["_line"], "tau_d": r["tau_d"] or "(empty)"}
               for r, ok in zip(rows, used) if not ok]
    tau_d = tau_d[used]
    reason = None
    if not keys.known("beta"):
        reason = "no beta column (give it with --fixed beta=VALUE)"
    elif beta is None:
        reason = "beta varies within the curve (add beta to --group)"
    elif p is None:
        reason = "P varies within the curve (add P to --group)"
    elif tau_g is None:
        reason = "gamma is not > 0 or varies within the curve (add gamma to --group)"
    elif not table.has("tau_d"):
        reason = "no tau_d column"
    elif tau_d.size == 0:
        reason = "no finite, positive tau_d in the curve"
    return {"beta": beta, "P": p, "tau_g": tau_g, "tau_d": mean, "tau_d_error": error,
            "tau_d_jobs": int(tau_d.size), "tau_d_dropped": dropped,
            "excluded_from_scale_fit": reason}


def mean_tau_d(values):
    """A curve's tau_d for the fit of a (docs/sweeps_analysis.md, step 4): the mean of its
    jobs' tau_d that are finite and positive, the standard error of that mean (None for
    fewer than two; None, None for none), and per job whether it was used."""
    v = np.asarray(values, float)
    used = np.isfinite(v) & (v > 0)
    kept = v[used]
    return (float(np.mean(kept)) if kept.size else None,
            _sem(kept) if kept.size > 1 else None, used)


def min_max_fit(name, points):
    """A curve's first fit (step 3): the sigmoid with the plateaus at the normalisation's
    extremes, 0 and 1, its sigmas the state points' errors with the extremes' share
    (A_n_error of build_points). judge_fits then replaces it by the fit with shared plateaus.
    InputError when the points do not allow a fit (fits.fit_sigmoid)."""
    from . import fits  # scipy: imported only once the input has been read and checked

    fit = fits.fit_sigmoid([p["x"] for p in points], [p["A_n"] for p in points],
                           [p["A_n_error"] for p in points], name)
    return dict(fit, name=name, points=points, plateaus=(0.0, 1.0))


def judge_fits(curves, in_group, partition_of, plateaus_mode="fitted"):
    """The end of step 3 and the curves' admission to step 4: the fits with plateaus shared by
    the curves of a normalisation group (plateaus.refine; "extremes" keeps the min-max fits,
    biased), then per curve not_a_fit (fits.not_a_fit) and, unless excluded_from_scale_fit
    already gives a reason, whether a is a located midpoint (fits.midpoint_not_located, on
    A_n rescaled to the curve's plateaus). Returns the records of the plateau fits, each
    with its partition label as partition_of gives it."""
    from . import fits, plateaus

    if plateaus_mode == "fitted":
        plateau_fits = plateaus.refine(curves, in_group, partition_of)
    else:  # --plateaus extremes: the paper's min-max normalisation as it stands
        plateau_fits = [{"partition": part, "done": False, "reason": "--plateaus extremes"}
                        for part in sorted(set(partition_of.values()) - {None}, key=repr)]
    for curve in curves:
        curve["not_a_fit"] = fits.not_a_fit(curve["a"], curve["a_error"], curve["b"],
                                            curve["b_error"])
        if curve["not_a_fit"] is not None:
            curve["excluded_from_scale_fit"] = "not a fit: " + curve["not_a_fit"]
        elif curve.get("excluded_from_scale_fit") is None:
            lo, hi = curve["plateaus"]
            points = curve["points"]
            curve["excluded_from_scale_fit"] = fits.midpoint_not_located(
                curve["a"], curve["a_error"], curve["b"], curve["b_error"],
                [p["x"] for p in points], [(p["A_n"] - lo) / (hi - lo) for p in points],
                [p["A_n_error"] / (hi - lo) for p in points])
    return plateau_fits


def analyse(table, opts):
    """Runs the whole analysis; returns {rows, points, curves, scale_fit, normalisation}."""
    rows = table.done_rows()
    keys = Keys(table, table.state_keys(), opts.fixed)
    keys.check(opts.group, "--group")
    keys.check(opts.within, "--normalise-within")
    keys.check([k for k, _ in opts.selector], "--normalise-by")
    point_keys = [k for k in keys.state_keys if k != opts.replicate_key]
    point_of = [keys.label(r, point_keys) for r in rows]
    warnings = same_number_written_twice(keys, rows)
    x, a_t, a_max, err_t, err_max = row_values(table, keys, rows, opts.temperature)
    unsteady, unchecked = drift_steadiness(table, rows, opts.max_drift, point_of)
    by_runs = runs_steadiness(table, rows, point_of)
    if by_runs is not None:
        unsteady = [a if b is None else b if a is None else b + "; " + a
                    for a, b in zip(unsteady, by_runs)]
    is_steady = [why is None for why in unsteady]
    if not any(is_steady):
        raise InputError("%s: no finished job is steady (A_t, --max-drift %s): %s" % (
            table.path, ",".join("%s=%g" % kv for kv in opts.max_drift), unsteady[0]))
    in_selector = [matches(keys, r, opts.selector) for r in rows]
    r_a, a_n, run_err, norm_err, norm_info = a_n_by_partition(
        [keys.label(r, opts.within) for r in rows], opts.within, in_selector, a_t, a_max,
        err_t, err_max, point_of, is_steady)
    from . import fits  # scipy: imported only once the input has been read and checked

    curves, curve_of = [], [None] * len(rows)
    in_group, partition_of = {}, {}
    for label, all_idx in group_indices([keys.label(r, opts.group) for r in rows]).items():
        name = ", ".join("%s=%s" % kv for kv in zip(opts.group, label)) or "all"
        for i in all_idx:
            curve_of[i] = name
        idx = [i for i in all_idx if is_steady[i]]
        if not idx:
            continue
        by_point = group_indices([point_of[i] for i in idx])
        points = build_points([np.array([idx[j] for j in js]) for js in by_point.values()],
                              x, a_n, run_err, norm_err, opts.min_error, opts.window)
        try:
            curve = min_max_fit(name, points)
        except InputError as e:
            left_out = len(all_idx) - len(idx)
            if not left_out:
                raise
            raise InputError("%s (%d job%s of the curve left out as not steady: see --max-drift)"
                             % (e, left_out, "" if left_out == 1 else "s"))
        varying = [k for k in point_keys if k not in opts.group
                   and len({keys.label(rows[i], [k]) for i in idx}) > 1]
        curve.update(group=dict(zip(opts.group, label)), jobs=len(idx), varying=varying)
        curve.update(curve_scale_inputs(keys, table, [rows[i] for i in idx], opts.tau_g))
        in_group[name] = all(in_selector[i] for i in idx)
        parts = {keys.label(rows[i], opts.within) for i in idx}
        partition_of[name] = parts.pop() if len(parts) == 1 else None
        curves.append(curve)
    plateau_fits = judge_fits(curves, in_group, partition_of,
                              getattr(opts, "plateaus", "fitted"))
    for record in plateau_fits:
        record["partition"] = dict(zip(opts.within, record["partition"]))
    scale = scale_fit(curves, fits)
    return {"rows": rows, "x": x, "rA_t": r_a, "A_n": a_n, "curves": curves,
            "curve_of": curve_of, "unsteady": unsteady, "unchecked_drift": unchecked,
            "runs_judged": by_runs is not None,
            "scale_fit": scale, "normalisation": norm_info, "plateau_fits": plateau_fits,
            "warnings": warnings,
            "state_keys": keys.state_keys}


def scale_fit(curves, fits):
    """The fit of a = c1 (1 + c2 beta/P) tau_g/tau_d over the usable curves, or a dict with
    the reason it was not done."""
    use = [c for c in curves if c["excluded_from_scale_fit"] is None]
    for c in use:
        c["tau_g_over_tau_d"] = c["tau_g"] / c["tau_d"]
        c["q"] = c["beta"] / c["P"]
    if len(use) < 2:
        return {"done": False, "reason": "%d usable curve%s (needs at least 2): %s"
                % (len(use), "" if len(use) == 1 else "s",
                   "; ".join("%s: %s" % (c["name"], c["excluded_from_scale_fit"])
                             for c in curves if c["excluded_from_scale_fit"]) or "group the "
                   "sweep into curves with --group")}
    rel = [(c["tau_d_error"] or 0.0) / c["tau_d"] for c in use]
    res = fits.fit_scale([c["a"] for c in use], [c["a_error"] for c in use],
                         [c["q"] for c in use], [c["tau_g_over_tau_d"] for c in use], rel)
    for c, s in zip(use, res.pop("sigma")):
        c["a_sigma_in_scale_fit"] = s
    res["done"] = True
    res["curves"] = [c["name"] for c in use]
    if res["c2"] is None:
        res["note"] = "beta/P is the same on every curve: only c1 is fitted"
    return res
