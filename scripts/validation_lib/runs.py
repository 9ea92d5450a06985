"""The runs of a sweep workspace (docs/sweeps.md) as Python objects: state point, job
document, summary.json, series.csv; the steady-state check and the paper's A_n.

A Job is read from WS/workspace/<id>/; only jobs whose document says `done` count."""

import csv
import json
import math
import os

import numpy as np


class InputError(Exception):
    """Bad or missing input, named in the message."""


class Job:
    """One finished point: sp (state point), doc, summary, series (lazy), path."""

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
                rows = list(csv.reader(f))
            if len(rows) < 2:
                raise InputError("%s: series.csv has no rows" % path)
            names = [h.split(" [")[0] for h in rows[0]]
            data = np.array([[float(v) for v in r] for r in rows[1:] if r], float)
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


def group(jobs, keys):
    """{tuple of sp values of `keys`: [jobs]} in sorted key order."""
    out = {}
    for j in jobs:
        out.setdefault(tuple(j.sp.get(k) for k in keys), []).append(j)
    def order(kv):  # numbers numerically, before strings
        return [(0, float(v), "") if isinstance(v, (int, float)) else (1, 0.0, str(v))
                for v in kv[0]]
    return dict(sorted(out.items(), key=order))


# A drift of A_t smaller than this fraction of the run's A_t^max moves A_n by less than about
# 0.015 (A_t^max / (A_t^max - min A_t) ~ 1.5 in these sweeps): below the precision of every
# statement on the page (0.05 and up), however many error bars it spans.
NEGLIGIBLE_DRIFT = 0.01


def steadiness(job, column="A_t"):
    """A_t over the last half of the run: the drift (mean of the last quarter minus that of
    the third) against the block error of the last-half mean (summary.json). Steady when
    |drift| <= 4 error (the difference of two quarter means has about twice the error of
    the half mean: a 2-sigma test), or when the drift is negligible, below NEGLIGIBLE_DRIFT
    of the run's mean A_t^max (a caged, de-mixed tissue ages by a few tenths of sigma^2 with
    an error bar smaller still). Returns a dict."""
    s = job.series
    y = s[column]
    half = y[len(y) // 2:]
    q = len(half) // 2
    mean, err = job.mean(column)
    if q < 1:
        return {"job": job.id, "drift": math.nan, "error": err, "steady": None,
                "samples": int(len(half))}
    drift = float(np.mean(half[q:]) - np.mean(half[:q]))
    steady = bool(abs(drift) <= 4 * err) if math.isfinite(err) and err > 0 else None
    negligible = None
    a_max = job.mean("A_t_max")[0]
    if column == "A_t" and math.isfinite(a_max) and a_max > 0:
        negligible = NEGLIGIBLE_DRIFT * a_max
        if steady is False and abs(drift) <= negligible:
            steady = True
    return {"job": job.id, "drift": drift, "error": err, "steady": steady,
            "samples": int(len(half)), "mean": mean, "negligible": negligible}


def steadiness_summary(jobs, column="A_t"):
    """The steady-state evidence of a set of jobs: counts and the largest |drift|/error."""
    rows = [steadiness(j, column) for j in jobs]
    judged = [r for r in rows if r["steady"] is not None]
    ratios = [abs(r["drift"]) / r["error"] for r in judged if r["error"] > 0]
    return {"jobs": len(rows), "judged": len(judged),
            "steady": sum(1 for r in judged if r["steady"]),
            "max_drift_over_error": max(ratios) if ratios else None, "rows": rows}


def unsteady_jobs(jobs, column="A_t"):
    """The ids of the jobs that are not steady by steadiness(): drifting, or not judged (no
    finite error or too few rows), since neither shows a steady state."""
    return [j.id for j in jobs if steadiness(j, column)["steady"] is not True]


def unsteady_points(points, jobs_by_id, name):
    """The names (name(point)) of the state points (dicts with "jobs": ids) that have a run
    that is not steady: a state point is steady when all its runs are."""
    return [name(p) for p in points
            if unsteady_jobs([jobs_by_id[i] for i in p["jobs"]])]


def window_mean(job, column, end_fraction, width=0.1):
    """The mean of a series column over the rows in (end - width, end] of the run (fractions
    of the production rows), at least one row."""
    y = job.series[column]
    end = max(1, int(round(end_fraction * len(y))))
    start = max(0, min(end - 1, end - int(round(width * len(y)))))
    return float(np.mean(y[start:end]))


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
