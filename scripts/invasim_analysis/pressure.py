"""E_c ~ 1/P (docs/beyond_the_paper.md): a sweep of one (beta, tau_p) curve at several
pressures P, read from its workspace. Per pressure and self-propulsion force: the measured
x = 2 k_B T_c/(P sigma^3) (the paper's convention, kT_c_paper/P), A_t/A_t^max and its error
over the seeds, and whether every run is steady (steady.steadiness); per pressure, the onset
x_half where A_t/A_t^max, rising, crosses half-way between the sweep's lowest and highest
steady state-point means (log-interpolated; nan where no steady pair brackets it). If
E_c = k_B T/(a P sigma^3) with a independent of P, the onsets agree; the paper's
a = c1 (1 + c2 beta eps_c/(P sigma^3)) tau_g/tau_d puts their ratio between two pressures at
(1 + c2 beta/P_1)/(1 + c2 beta/P_2) (c2 ~ 0.02) for equal tau_d.

Several workspaces of the same curve combine: a state point (P, f0) is taken from the last
workspace that has it, so that longer runs of some points (pressure_fig5_long.lua,
pressure_fig5_steady.lua) replace the shorter ones and the rest stay."""

import json
import math
import os

from . import atomic, steady, workspace
from .errors import InputError
from .validation import points as state

C2_PAPER = 0.02  # the paper's Fig. 5(b): a = c1 (1 + c2 beta/P) tau_g/tau_d


def state_points(ws, jobs=None):
    """[{P, f0, x, ratio, ratio_error, steady, runs}] sorted by P then x (jobs: the done jobs
    of ws, loaded when not given); means and errors over the seeds as the validation figures
    take them (validation/points.state_point)."""
    jobs = jobs if jobs is not None else workspace.load(ws)
    for key in ("P", "f0"):
        if not all(key in j.sp for j in jobs):
            raise InputError("%s: the pressure analysis needs P and f0 in every state point" % ws)
    out = []
    for (P, f0), runs in workspace.group(jobs, ["P", "f0"]).items():
        p = state.state_point(runs, lambda j: {
            "ratio": j.mean("A_ratio")[0], "ratio_error": j.mean("A_ratio")[1],
            "x": j.mean("kT_c_paper")[0] / P})
        out.append({"P": P, "f0": f0, "x": p["x"], "ratio": p["ratio"],
                    "ratio_error": p["ratio_error"], "runs": p["replicates"],
                    "steady": all(steady.steadiness(j)["steady"] for j in runs)})
    return sorted(out, key=lambda p: (p["P"], p["x"]))


def onsets(points, steady_only=True):
    """({P: x_half}, the level) from the steady state points (see the module's text), or from
    all of them (steady_only=False: provisional)."""
    steady_points = [p for p in points if p["steady"] or not steady_only]
    if len(steady_points) < 2:
        return {}, math.nan
    low = min(p["ratio"] for p in steady_points)
    high = max(p["ratio"] for p in steady_points)
    half = 0.5 * (low + high)
    out = {}
    for P in sorted({p["P"] for p in points}):
        pts = [p for p in steady_points if p["P"] == P]
        out[P] = state.crossing([p["x"] for p in pts], [p["ratio"] for p in pts], half)
    return out, half


def combined_points(workspaces):
    """The state points of several workspaces, each (P, f0) from the last one that has it
    (each marked with its workspace's name), and their jobs."""
    by_key, all_jobs = {}, []
    for ws in workspaces:
        jobs = workspace.load(ws)
        all_jobs += jobs
        for p in state_points(ws, jobs):
            p["from"] = os.path.basename(os.path.normpath(ws))
            by_key[(p["P"], p["f0"])] = p
    return sorted(by_key.values(), key=lambda p: (p["P"], p["x"])), all_jobs


def analyse(workspaces, out_dir, beta=None):
    """Writes pressure.json and pressure.png in out_dir; returns the record. `workspaces`: one
    workspace or a list (combined as the module's text says)."""
    workspaces = [workspaces] if isinstance(workspaces, str) else list(workspaces)
    points, jobs = combined_points(workspaces)
    x_half, half = onsets(points)
    provisional, provisional_half = onsets(points, steady_only=False)
    beta = beta if beta is not None else jobs[0].sp.get("beta")
    pressures = sorted(x_half)
    predicted = {}
    if beta is not None and pressures:
        ref = pressures[-1]
        for P in pressures:
            predicted[P] = (1 + C2_PAPER * beta / P) / (1 + C2_PAPER * beta / ref)
    rec = {"workspace": ", ".join(os.path.basename(os.path.normpath(w)) for w in workspaces),
           "points": points, "half": half,
           "onsets": {str(P): x for P, x in x_half.items()},
           "provisional_half": provisional_half,
           "provisional_onsets": {str(P): x for P, x in provisional.items()},
           "predicted_onset_ratio": {str(P): r for P, r in predicted.items()},
           "beta": beta, "c2": C2_PAPER}
    os.makedirs(out_dir, exist_ok=True)
    with atomic.open_text(os.path.join(out_dir, "pressure.json")) as f:
        json.dump(rec, f, indent=1, sort_keys=True)
    # The figure marks the steady onsets, or the provisional ones when no steady pair brackets.
    shown = (x_half, half) if any(math.isfinite(x) for x in x_half.values()) else (provisional, provisional_half)
    plot(points, shown[0], shown[1], os.path.join(out_dir, "pressure.png"))
    return rec


def plot(points, x_half, half, path):
    """A_t/A_t^max against 2 k_B T_c/(P sigma^3), one colour per pressure, not-steady hollow;
    the onsets x_half (dotted) at the level `half` (dashed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    for k, P in enumerate(sorted({p["P"] for p in points})):
        pts = [p for p in points if p["P"] == P]
        colour = "C%d" % k
        ax.plot([p["x"] for p in pts], [p["ratio"] for p in pts], "-", color=colour, lw=0.8)
        for p in pts:
            ax.errorbar(p["x"], p["ratio"], yerr=p["ratio_error"], fmt="o", color=colour,
                        mfc=colour if p["steady"] else "none", ms=5, capsize=2)
        ax.plot([], [], "o", color=colour, label=r"$P\sigma^3/\epsilon_c$ = %g" % P)
        if math.isfinite(x_half.get(P, math.nan)):
            ax.axvline(x_half[P], color=colour, ls=":", lw=0.8)
    if math.isfinite(half):
        ax.axhline(half, color="0.5", ls="--", lw=0.6)
    ax.set_xscale("log")
    ax.set_xlabel(r"$2 k_B T_c/(P\sigma^3)$ (measured)")
    ax.set_ylabel(r"$A_t/A_t^{max}$")
    ax.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    atomic.save_figure(fig, path, dpi=110)
    plt.close(fig)


def table(rec):
    """The state points as a markdown table."""
    lines = ["| P | f0 | 2 k_B T_c/(P sigma^3) | A_t/A_t^max | steady | runs of |",
             "|---|---|---|---|---|---|"]
    for p in rec["points"]:
        lines.append("| %g | %g | %.3g | %.3f +- %.3f | %s | %s |" % (
            p["P"], p["f0"], p["x"], p["ratio"], p["ratio_error"], "yes" if p["steady"] else "no",
            p.get("from", "")))
    return "\n".join(lines)


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(prog="pressure_sweep.py", description=__doc__)
    ap.add_argument("workspace", nargs="+",
                    help="one or more workspaces of the curve; a state point is taken from the "
                         "last that has it")
    ap.add_argument("-o", "--out", required=True)
    args = ap.parse_args(argv)
    try:
        rec = analyse(args.workspace, args.out)
    except InputError as e:
        raise SystemExit("pressure_sweep.py: error: %s" % e)
    print(table(rec))
    print("onset (A_t/A_t^max = %.3f, half-way between the steady extremes):" % rec["half"])
    for P, x in sorted(rec["onsets"].items(), key=lambda kv: float(kv[0])):
        print("  P = %s: 2 k_B T_c/(P sigma^3) = %s; the paper's a predicts %.3g x the highest "
              "pressure's" % (P, "%.3g" % x if math.isfinite(x) else "not bracketed by steady points",
                              rec["predicted_onset_ratio"].get(P, math.nan)))
    print("provisional, with the runs that are not steady (A_t/A_t^max = %.3f):"
          % rec["provisional_half"])
    for P, x in sorted(rec["provisional_onsets"].items(), key=lambda kv: float(kv[0])):
        print("  P = %s: 2 k_B T_c/(P sigma^3) = %s" % (P, "%.3g" % x if math.isfinite(x) else "none"))
    print("wrote %s" % ", ".join(os.path.join(args.out, f) for f in ("pressure.json", "pressure.png")))
