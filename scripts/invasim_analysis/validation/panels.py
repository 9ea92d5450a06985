"""A_n(t) panels of single runs (docs/validation.md, "At the paper's scale"): per run, A_t(t)
over its production with the averaging window shaded and the two quarter means of the
steady-state criterion (steady.steadiness) drawn as bars with their errors; the right axis
reads A_n, the same A_t through the figure's normalisation (Appendix C, at the window's mean
A_t^max), so the panel shows A_n(t) and exactly what the criterion compares."""

import math

import numpy as np

from .. import steady
from .figures_tissue import production_time
from .plotting import label, save  # (sets the Agg backend before pyplot)

import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = 4


def _an_axis(ax, job, extremes, first, end):
    """The right axis in A_n: A_n = (1 - (A_t^max - A_t)/min A_t^max - lo)/(hi - lo), linear
    in A_t at the window's mean A_t^max."""
    if not extremes or "A_t_max" not in job.series:
        return
    amax = float(np.mean(job.series["A_t_max"][first:end]))
    lo, hi, amin = extremes["min_rA_t"], extremes["max_rA_t"], extremes["min_A_t_max"]
    if not hi > lo:
        return

    def to_an(a):
        return (1 - (amax - a) / amin - lo) / (hi - lo)

    def to_at(an):
        return amax - amin * (1 - lo - an * (hi - lo))

    sec = ax.secondary_yaxis("right", functions=(to_an, to_at))
    sec.set_ylabel(label("A_n", ""), fontsize=7)
    sec.tick_params(labelsize=6)


def draw(jobs, extremes, out, name, titles):
    """One PNG of panels, one per run (jobs with rows); titles: {job id: the run's name and
    state ("kT = ..., seed = 1: running, t = ... of ...")}. Returns [name], or [] without runs."""
    if not jobs:
        return []
    ncols = min(COLUMNS, len(jobs))
    nrows = int(math.ceil(len(jobs) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(3.4 * ncols, 2.7 * nrows), squeeze=False)
    for ax, job in zip(axes.flat, jobs):
        t = production_time(job)
        y = job.series["A_t"]
        ax.plot(t, y, lw=0.7, color="0.3")
        first, end = steady.window(job)
        s = steady.steadiness(job)
        ax.axvspan(t[first], t[end - 1], color="0.92", zorder=0)
        if "m3" in s:
            for (i0, i1), m, e, c in ((s["rows3"], s["m3"], s["e3"], "C0"),
                                      (s["rows4"], s["m4"], s["e4"], "C3")):
                ax.hlines(m, t[i0], t[i1 - 1], color=c, lw=2)
                if math.isfinite(e):
                    ax.fill_between([t[i0], t[i1 - 1]], m - e, m + e, color=c, alpha=0.3, lw=0)
        verdict_text = {True: "steady", False: "drifting", None: "not judged"}[s["steady"]]
        ax.set_title("%s\n%s (m4 - m3 = %.3g +- %.2g)" % (
            titles.get(job.id, job.id[:8]), verdict_text, s["drift"], s["error"]), fontsize=6)
        ax.tick_params(labelsize=6)
        ax.set_xlabel(label("time", "tau") + " (production)", fontsize=7)
        ax.set_ylabel(label("A_t", "sigma^2"), fontsize=7)
        _an_axis(ax, job, extremes, first, end)
    for ax in list(axes.flat)[len(jobs):]:
        ax.set_visible(False)
    return [save(fig, out, name)]
