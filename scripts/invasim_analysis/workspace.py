"""The one reader of a sweep workspace (docs/sweeps.md): a job's state point, job document,
summary.json and series.csv as Python objects. The master curve (its steadiness) and the
validation page read jobs only through it.

A Job is read from WS/workspace/<id>/. The figures of the reduced scale take the jobs whose
document says `done` (load); the paper-scale records take every job (load_all), a run still
going with its provisional averages (Job.provisional). The workspace's own files: meta
(invasim_sweep.json), document (a job's or the preparation's), prep_summary. numpy is
imported only to read series.csv: the rest serves plain python3 (sweep_results.py)."""

import csv
import json
import math
import os

from .errors import InputError


def _json(path, missing=None):
    """The JSON file at `path`; `missing` when it does not exist and that is not None."""
    if missing is not None and not os.path.exists(path):
        return missing
    with open(path) as f:
        return json.load(f)


def meta(ws):
    """WS/invasim_sweep.json (InputError if WS is not a sweep workspace)."""
    path = os.path.join(ws, "invasim_sweep.json")
    if not os.path.exists(path):
        raise InputError("%s is not a sweep workspace (no invasim_sweep.json)" % ws)
    return _json(path)


def statepoint(job_dir):
    """A job's state point (signac_statepoint.json)."""
    return _json(os.path.join(job_dir, "signac_statepoint.json"))


def document(job_dir):
    """A job's (or the preparation's, WS/prep) document, {} when it has none."""
    return _json(os.path.join(job_dir, "signac_job_document.json"), {})


def prep_summary(ws):
    """The shared preparation's summary.json (WS/prep), or None."""
    return _json(os.path.join(ws, "prep", "summary.json"), False) or None

class Job:
    """One point: sp (state point), doc, status, summary, series (lazy), path."""

    def __init__(self, path):
        self.path = path
        self.id = os.path.basename(path)
        self.sp = statepoint(path)
        self.doc = document(path)
        self.summary = _json(os.path.join(path, "summary.json"), {})
        self._series = None
        self._errors = {}  # _recomputed_error's, by column

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
        mean and error of every series column over the averaging window of the rows written
        so far (window()), as summary.json would hold them had it ended there."""
        if self.summary.get("averages") or not self.rows():
            return self
        import numpy as np

        from .steady import summary_error, window
        first, end = window(self)
        averages = {}
        for name, y in self.series.items():
            if name not in ("step", "time"):
                error, tau, resolved = summary_error(y[first:end])
                averages[name] = {"mean": float(np.mean(y[first:end])), "error": error,
                                  "samples": int(end - first), "tau_int": tau,
                                  "error_converged": resolved}
        self.summary = {"averages": averages, "provisional": True}
        return self

    def mean(self, name):
        """summary.json's averages[name] as (mean, error), or (nan, nan). A summary whose
        entry has no tau_int was written when the protocols' errors came from blocking, which
        is too small on these windows (docs/measurements_dynamics.md, "Summary"): its error is
        computed anew from series.csv's window by the summary's estimator (summary_error)."""
        entry = self.summary.get("averages", {}).get(name)
        if isinstance(entry, dict):
            error = float(entry.get("error", math.nan))
            if "tau_int" not in entry and isinstance(entry.get("samples"), int):
                error = self._recomputed_error(name, entry["samples"], error)
            return float(entry.get("mean", math.nan)), error
        if isinstance(entry, (int, float)):
            return float(entry), math.nan
        return math.nan, math.nan

    def _recomputed_error(self, name, samples, stored):
        """summary_error over the last `samples` rows of series.csv's column `name` (cached);
        `stored` when the run has no such column or rows."""
        cache = self._errors
        if name not in cache:
            from .steady import summary_error
            try:
                y = self.series.get(name)
            except InputError:
                y = None
            cache[name] = (summary_error(y[len(y) - samples:])[0]
                           if y is not None and 2 <= samples <= len(y) else stored)
        return cache[name]

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
            import numpy as np

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


