"""The runs of a sweep workspace (docs/sweeps.md) as Python objects: state point, job
document, summary.json, series.csv; the steady-state criterion and the paper's A_n.

A Job is read from WS/workspace/<id>/. The figures of the reduced scale take the jobs whose
document says `done` (load); the paper-scale records take every job (load_all), a run still
going with its provisional averages (Job.provisional)."""

import csv
import json
import math
import os

import numpy as np


class InputError(Exception):
    """Bad or missing input, named in the message."""


class Job:
    """One point: sp (state point), doc, status, summary, series (lazy), path."""

    def __init__(self, path):
        self.path = path
        self.id = os.path.basename(path)
        with open(os.path.join(path, "signac_statepoint.json")) as f:
            self.sp = json.load(f)
        with open(os.path.join(path, "signac_job_document.json")) as f:
            self.doc = json.load(f)
        summary = os.path.join(path, "summary.json")
        self.summary = {}
        if os.path.exists(summary):
            with open(summary) as f:
                self.summary = json.load(f)
        self._series = None

    @property
    def status(self):
        """The job document's status (docs/sweeps.md: pending, submitted, running, done,
        failed, interrupted)."""
        return self.doc.get("status", "pending")

    def rows(self):
        """The number of rows of series.csv written so far (0 without one)."""
        if not os.path.exists(os.path.join(self.path, "series.csv")):
            return 0
        try:
            return len(self.series["time"])
        except InputError:
            return 0

    def provisional(self):
        """For a run without summary.json (still going, or stopped): its averages so far, the
        mean and block error of every series column over the averaging window of the rows
        written so far (window()), as summary.json would hold them had it ended there."""
        if self.summary.get("averages") or not self.rows():
            return self
        first, end = window(self)
        self.summary = {"averages": {
            name: {"mean": float(np.mean(y[first:end])), "error": block_error(y[first:end]),
                   "samples": int(end - first)}
            for name, y in self.series.items() if name not in ("step", "time")},
            "provisional": True}
        return self

    def mean(self, name):
        """summary.json's averages[name] as (mean, error), or (nan, nan)."""
        entry = self.summary.get("averages", {}).get(name)
        if isinstance(entry, dict):
            return float(entry.get("mean", math.nan)), float(entry.get("error", math.nan))
        if isinstance(entry, (int, float)):
            return float(entry), math.nan
        return math.nan, math.nan

    def scalar(self, name):
        """A number of summary.json (top level or averages), or nan."""
        if isinstance(self.summary.get(name), (int, float)):
            return float(self.summary[name])
        return self.mean(name)[0]

    @property
    def series(self):
        """series.csv as {bare column name: numpy array}."""
        if self._series is None:
            path = os.path.join(self.path, "series.csv")
            if not os.path.exists(path):
                raise InputError("%s: no series.csv (the run wrote none)" % self.path)
            with open(path) as f:
                text = f.read()
            if self.status != "done" and not text.endswith("\n"):
                text = text[:text.rfind("\n") + 1]  # a run still writing: a partial last line
            rows = list(csv.reader(text.splitlines()))
            if len(rows) < 2:
                raise InputError("%s: series.csv has no rows" % path)
            names = [h.split(" [")[0] for h in rows[0]]
            body = [r for r in rows[1:] if r]
            if not body:
                raise InputError("%s: series.csv has no complete row" % path)
            data = np.array([[float(v) for v in r] for r in body], float)
            self._series = {n: data[:, i] for i, n in enumerate(names)}
        return self._series


def load(workspace):
    """The done jobs of a workspace (InputError if it is none or has no done job)."""
    root = os.path.join(workspace, "workspace")
    if not os.path.exists(os.path.join(workspace, "invasim_sweep.json")):
        raise InputError("%s is not a sweep workspace (no invasim_sweep.json): run "
                         "`invasim sweep init SPEC --workspace %s` first" % (workspace, workspace))
    jobs, counts = [], {}
    for name in sorted(os.listdir(root)):
        job = Job(os.path.join(root, name))
        status = job.doc.get("status", "pending")
        counts[status] = counts.get(status, 0) + 1
        if status == "done":
            jobs.append(job)
    if not jobs:
        raise InputError("%s: no point is done (%s): run `invasim sweep run %s`" % (
            workspace, ", ".join("%d %s" % (n, s) for s, n in sorted(counts.items())) or
            "no points", workspace))
    return jobs


def load_all(workspace):
    """Every job of a workspace, whatever its status (InputError if it is not one)."""
    if not os.path.exists(os.path.join(workspace, "invasim_sweep.json")):
        raise InputError("%s is not a sweep workspace (no invasim_sweep.json)" % workspace)
    root = os.path.join(workspace, "workspace")
    return [Job(os.path.join(root, n)) for n in sorted(os.listdir(root))]


def group(jobs, keys):
    """{tuple of sp values of `keys`: [jobs]} in sorted key order."""
    out = {}
    for j in jobs:
        out.setdefault(tuple(j.sp.get(k) for k in keys), []).append(j)
    def order(kv):  # numbers numerically, before strings
        return [(0, float(v), "") if isinstance(v, (int, float)) else (1, 0.0, str(v))
                for v in kv[0]]
    return dict(sorted(out.items(), key=order))


# The steady-state criterion (docs/validation.md, Method, "Steady state"), the one every
# figure, every verdict and the paper-scale record use:
#   the averaging window of a run is the last half of its production rows (what summary.json
#   averages; for a run still going, the last half of the rows written so far); its two
#   halves are the run's last two quarters. The run is steady when the means of the
#   observable (A_t) over the two quarters, m3 and m4, agree within STEADY_FACTOR times their
#   combined block error, |m4 - m3| <= STEADY_FACTOR sqrt(e3^2 + e4^2), or when the drift is
#   negligible, |m4 - m3| <= NEGLIGIBLE_DRIFT x the window's mean A_t^max.
#   A state point is steady when every run of it is, and, where it was run from two starts
#   (Fig. 4b: de-mixed and mixed), when the starts' means of the observable agree by the same
#   test (start_agreement).
# A run with fewer than two rows per quarter, or without a finite error, cannot be judged and
# does not count as steady.
STEADY_FACTOR = 2.0
# A drift of A_t smaller than this fraction of the run's A_t^max moves A_n by less than about
# 0.015 (A_t^max / (A_t^max - min A_t) ~ 1.5 in these sweeps): below the precision of every
# statement on the page (0.05 and up), however many error bars it spans (a caged, de-mixed
# tissue ages by a few tenths of sigma^2 with an error bar smaller still).
NEGLIGIBLE_DRIFT = 0.01
# Levels of the blocking analysis with fewer blocks are not used (src/measure/block_average.hpp).
MIN_BLOCKS = 16


def block_error(y):
    """The standard error of the mean of a correlated series by blocking, as the summary's
    errors are computed (src/measure/block_average.cpp: pairs averaged level by level; the
    smallest block size B with B^3 > 2 n (error_B/error_1)^4 among the levels with at least
    MIN_BLOCKS blocks, else the last such level, else level 0). nan for fewer than 2 values."""
    m = np.asarray(y, float)
    n = len(m)
    if n < 2:
        return math.nan
    levels = []
    block = 1
    while len(m) >= 2:
        nb = len(m)
        levels.append((block, nb, math.sqrt(float(np.sum((m - m.mean()) ** 2)) / nb / (nb - 1))))
        m = 0.5 * (m[0:2 * (nb // 2):2] + m[1:2 * (nb // 2):2])
        block *= 2
    e1 = levels[0][2]
    chosen = None
    for b, nb, err in levels:
        if nb < MIN_BLOCKS:
            break
        chosen = err
        ratio = err / e1 if e1 > 0 else 1.0
        if e1 == 0.0 or b ** 3 > 2.0 * n * ratio ** 4:
            break
    return levels[0][2] if chosen is None else chosen


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
    return n - max(1, n // 2), n


def steadiness(job, column="A_t", rows=None):
    """The criterion above for one run (over its first `rows` rows, all by default). Returns
    {job, steady (True/False/None: not judged), drift = m4 - m3, error = the combined error
    sqrt(e3^2 + e4^2), m3, m4, e3, e4, negligible (the floor, or None), samples (rows of the
    window), rows3, rows4 (the quarters' [first, end) rows)}."""
    s = job.series
    first, end = window(job, rows)
    y = s[column][first:end]
    q = len(y) // 2
    out = {"job": job.id, "samples": int(len(y)), "steady": None, "drift": math.nan,
           "error": math.nan, "negligible": None}
    if q < 2:
        return out
    a, b = y[len(y) - 2 * q:len(y) - q], y[len(y) - q:]
    m3, m4, e3, e4 = float(np.mean(a)), float(np.mean(b)), block_error(a), block_error(b)
    drift, err = m4 - m3, math.hypot(e3, e4)
    out.update({"drift": drift, "error": err, "m3": m3, "m4": m4, "e3": e3, "e4": e4,
                "rows3": [end - 2 * q, end - q], "rows4": [end - q, end]})
    if math.isfinite(err):
        out["steady"] = bool(abs(drift) <= STEADY_FACTOR * err)
    if column == "A_t":
        a_max = (float(np.mean(s["A_t_max"][first:end])) if "A_t_max" in s
                 else job.mean("A_t_max")[0])
        if math.isfinite(a_max) and a_max > 0:
            out["negligible"] = NEGLIGIBLE_DRIFT * a_max
            if abs(drift) <= out["negligible"]:
                out["steady"] = True
    return out


def start_agreement(jobs, key="start", column="A_t"):
    """The second half of a state point's criterion: the runs grouped by `key` (the start);
    each start's mean of `column` over its runs' averaging windows, its error the standard
    error over the runs (two or more) or the run's block error; the two starts agree when
    |difference| <= STEADY_FACTOR x the combined error or is negligible (NEGLIGIBLE_DRIFT of
    the mean A_t^max). Returns {means: {start: (mean, error)}, difference, error, agree}
    (agree None with fewer than two starts or without a finite error)."""
    means, amax = {}, []
    for (start,), reps in group(jobs, [key]).items():
        vals = []
        for j in reps:
            first, end = window(j)
            y = j.series[column][first:end]
            vals.append((float(np.mean(y)), block_error(y)))
            if "A_t_max" in j.series:
                amax.append(float(np.mean(j.series["A_t_max"][first:end])))
        v = np.array([m for m, _ in vals])
        err = float(np.std(v, ddof=1) / math.sqrt(len(v))) if len(v) >= 2 else vals[0][1]
        means[str(start)] = (float(np.mean(v)), err)
    out = {"means": means, "difference": math.nan, "error": math.nan, "agree": None}
    if len(means) != 2:
        return out
    (m1, e1), (m2, e2) = means.values()
    out["difference"], out["error"] = m2 - m1, math.hypot(e1, e2)
    if math.isfinite(out["error"]):
        out["agree"] = bool(abs(m2 - m1) <= STEADY_FACTOR * out["error"])
    if column == "A_t" and amax and abs(m2 - m1) <= NEGLIGIBLE_DRIFT * float(np.mean(amax)):
        out["agree"] = True
    return out


def point_steadiness(jobs, key="start"):
    """A state point's verdict by the criterion: (steady, reasons), steady when every run is
    steady and, if its runs differ in `key` (two starts), the starts agree; reasons name the
    runs that are not steady (or not judged) and a disagreement of the starts."""
    reasons = []
    for j in jobs:
        s = steadiness(j)
        if s["steady"] is not True:
            reasons.append("run %s %s" % (_run_name(j), "drifts: %s" % _drift_text(s)
                                          if s["steady"] is False else "not judged"))
    if len({str(j.sp.get(key)) for j in jobs}) == 2:
        a = start_agreement(jobs, key)
        if a["agree"] is not True:
            reasons.append("the starts %s: %s" % (
                "disagree" if a["agree"] is False else "cannot be compared",
                ", ".join("%s %.4g +- %.2g" % (k, m, e) for k, (m, e) in a["means"].items())))
    return not reasons, reasons


def _run_name(job):
    """A run as the page names it: its start and seed where it has them, else its id."""
    parts = ["%s start" % job.sp["start"]] if "start" in job.sp else []
    parts += ["seed %s" % job.sp["seed"]] if "seed" in job.sp else []
    return ", ".join(parts) if parts else job.id[:8]


def _drift_text(s):
    return "m4 - m3 = %.3g +- %.2g" % (s["drift"], s["error"])


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


def window_mean(job, column, end_fraction):
    """The mean of a series column over the averaging window the run would have had, had it
    ended at `end_fraction` of its rows: the last half of its first round(end_fraction x rows)
    rows (at least one row)."""
    y = job.series[column]
    end = max(1, int(round(end_fraction * len(y))))
    return float(np.mean(y[end - max(1, end // 2):end]))


def normalise(points):
    """The paper's Appendix C over state points. `points`: list of dicts with A_t, A_t_max
    (replicate means) and A_t_error. Adds rA_t, A_n, A_n_error; returns the extremes.
    rA_t = 1 - (A_t^max - A_t)/min A_t^max; A_n = (rA_t - min)/(max - min)."""
    if not points:
        raise InputError("no state points to normalise")
    amax_min = min(p["A_t_max"] for p in points)
    for p in points:
        p["rA_t"] = 1.0 - (p["A_t_max"] - p["A_t"]) / amax_min
    lo = min(p["rA_t"] for p in points)
    hi = max(p["rA_t"] for p in points)
    span = hi - lo
    for p in points:
        p["A_n"] = (p["rA_t"] - lo) / span if span > 0 else math.nan
        p["A_n_error"] = (p.get("A_t_error", math.nan) / amax_min / span) if span > 0 else math.nan
    return {"min_A_t_max": amax_min, "min_rA_t": lo, "max_rA_t": hi}


def scale_like(point, extremes):
    """A_n of a point with another set's normalisation (extremes from normalise())."""
    r = 1.0 - (point["A_t_max"] - point["A_t"]) / extremes["min_A_t_max"]
    span = extremes["max_rA_t"] - extremes["min_rA_t"]
    point["rA_t"] = r
    point["A_n"] = (r - extremes["min_rA_t"]) / span if span > 0 else math.nan
    point["A_n_error"] = (point.get("A_t_error", math.nan) / extremes["min_A_t_max"] / span
                          if span > 0 else math.nan)
    return point


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
