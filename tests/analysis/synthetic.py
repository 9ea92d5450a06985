"""Synthetic results tables for the tests of scripts/master_curve.py: jobs whose A_n follows
the paper's sigmoid with known a and b per curve, a = c1 (1 + c2 beta/P) tau_g/tau_d, plus
noise on A_n, on the measured temperature and on tau_d. The A_n noise is largest mid-curve
and small on the plateaus, as in the simulations (de-mixed and mixed states fluctuate
little). Or (relative_a_t_noise) noise proportional to A_t itself: a larger interface
fluctuates more, so the invaded plateau is the noisiest."""

import csv
import math

import numpy as np

P = 1.3e-3
TAU_G = 5.0
HEADER = ["job_id", "status", "wall_seconds [s]", "P", "beta", "tau_p", "f0", "seed",
          "A_ratio", "A_ratio_error", "A_t [sigma^2]", "A_t_error [sigma^2]",
          "A_t_max [sigma^2]", "A_t_max_error [sigma^2]", "T_c [eps_c]", "T_c_error [eps_c]",
          "T_c_over_T_a", "T_c_over_T_a_error", "kT_c_paper [eps_c]",
          "kT_c_paper_error [eps_c]", "tau_d [tau]", "tau_r [tau]"]


def sigmoid(x, a, b):
    return 0.5 * (np.tanh(b * np.log10(x / a)) + 1.0)


def make_truth(c1=0.06, c2=0.1):
    """Six curves: beta in {1e-4, 1e-3, 1e-2} x tau_p in {25, 2500}, with tau_d and b."""
    curves = []
    for beta, b_base in ((1e-4, 0.9), (1e-3, 1.4), (1e-2, 2.0)):
        for tau_p, tau_d, db in ((25.0, 18.0, 0.0), (2500.0, 420.0, 0.3)):
            a = c1 * (1 + c2 * beta / P) * TAU_G / tau_d
            curves.append({"beta": beta, "tau_p": tau_p, "tau_d": tau_d, "a": a,
                           "b": b_base + db})
    return {"c1": c1, "c2": c2, "curves": curves}


def write_table(path, rng, truth, points=13, span=2.6, replicates=4, noise=0.08,
                floor=0.003, tau_d_noise=0.05, relative_a_t_noise=None):
    """Writes results.csv; returns the rows' true A_n (by job id). With relative_a_t_noise
    = r, each job's A_t is the true A_t times (1 + r N(0, 1)) instead of the noise on A_n."""
    rows, true_an = [], {}
    m0 = 1300.0
    for k, c in enumerate(truth["curves"]):
        for j, lx in enumerate(np.linspace(-span, span, points)):
            x = c["a"] * 10 ** lx
            an = float(sigmoid(x, c["a"], c["b"]))
            for s in range(1, replicates + 1):
                job = "c%dp%02ds%d" % (k, j, s)
                sd = floor + noise * math.sqrt(an * (1 - an))
                draw = rng.standard_normal()
                an_obs = an if relative_a_t_noise else an + sd * draw
                # Dilation: A_t^max grows with the temperature; A_t^max - A_t is the
                # non-invaded area, 0.8 m0 in the de-mixed state, 0 when fully invaded.
                a_max = m0 * (1 + 0.03 * max(lx, 0)) + 0.5 * rng.standard_normal()
                a_t = a_max - 0.8 * m0 * (1 - an_obs)
                if relative_a_t_noise:
                    a_t *= 1 + relative_a_t_noise * draw
                kt_paper = x * P * (1 + 0.002 * rng.standard_normal())
                tau_d = c["tau_d"] * (1 + tau_d_noise * rng.standard_normal())
                rows.append([job, "done", "12.5", repr(P), repr(c["beta"]), repr(c["tau_p"]),
                             "%.6g" % (x * 7.7), str(s), repr(a_t / a_max), "0.001", repr(a_t),
                             "2.0", repr(a_max), "1.0", repr(kt_paper / 2), "1e-7", "1.05",
                             "0.01", repr(kt_paper), "2e-7", repr(tau_d), "100.0"])
                true_an[job] = an
    # A failed job: ignored by the analysis (its measurement fields are empty).
    rows.append(["failed1", "failed", "3.0", repr(P), "0.01", "25.0", "1", "9"]
                + [""] * (len(HEADER) - 8))
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(HEADER)
        w.writerows(rows)
    return true_an


def write_workspace(path, points, every=100, quench_steps=100, dt=0.05):
    """A sweep workspace as `invasim sweep init`/`run` leave it (docs/sweeps.md), for the tests
    of scripts/invasim_analysis: points is a list of (state point, status, A_t series,
    A_t_max, x) with x the measured 2 T_c/P. A point's series.csv has one row per A_t value
    (step = quench_steps + every (i + 1), time = step x dt); a done point also has summary.json
    (the mean and error over the last half of the rows, as the protocols write it, with
    steady.summary_error); a pending point has neither. Returns the job ids."""
    import json
    import os
    from invasim_analysis import steady
    ids = []
    for k, (sp, status, a_t, a_t_max, x) in enumerate(points):
        sp = dict({"P": P, "quench_steps": quench_steps, "every": every}, **sp)
        job = "%032x" % (k + 1)
        d = os.path.join(path, "workspace", job)
        os.makedirs(d)
        ids.append(job)
        with open(os.path.join(d, "signac_statepoint.json"), "w") as f:
            json.dump(sp, f)
        with open(os.path.join(d, "signac_job_document.json"), "w") as f:
            json.dump({"status": status, "wall_seconds": 3600.0 if status == "done" else 1800.0
                       if len(a_t) else 0.0}, f)
        if not len(a_t):
            continue
        cols = {"A_t": list(a_t), "A_t_max": [a_t_max] * len(a_t), "kT_c_paper": [x * P] * len(a_t),
                "A_ratio": [a / a_t_max for a in a_t]}
        with open(os.path.join(d, "series.csv"), "w") as f:
            f.write("step,time [tau],A_t [sigma^2],A_t_max [sigma^2],kT_c_paper [eps_c],A_ratio\n")
            for i in range(len(a_t)):
                step = quench_steps + every * (i + 1)
                f.write("%d,%r,%r,%r,%r,%r\n" % (step, step * dt, cols["A_t"][i], cols["A_t_max"][i],
                                                 cols["kT_c_paper"][i], cols["A_ratio"][i]))
        if status == "done":
            half = len(a_t) // 2
            averages = {n: {"mean": float(np.mean(v[-half:])),
                            "error": steady.summary_error(v[-half:])[0], "samples": half}
                        for n, v in cols.items()}
            with open(os.path.join(d, "summary.json"), "w") as f:
                json.dump({"averages": averages}, f)
    with open(os.path.join(path, "invasim_sweep.json"), "w") as f:
        json.dump({"points": ids, "prep": None, "protocol": "invasion.lua",
                   "spec": "protocols/sweeps/paper_scale/x.lua"}, f)
    return ids
