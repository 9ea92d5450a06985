#!/usr/bin/env python3
"""Regenerates the vertex-bath table of docs/model.md ("Vertex bath"): T_c/T_a and the
measured k_B T_c/(P sigma^3) on the reduced system, for passive cells and active cells
(tau_p = 25, 2500) at background kT = x P (x = 0.03, 0.3, 1), under each reading of the
adipocyte vertices' bath (Langevin at kT; damped with vertex_gamma = 0.2, 0.02, 0.002).

Every cell is one run of protocols/bath_cell.lua from one compressed tissue (--from), at
--threads 1, one after the other (a finished cell, with its summary.json, is not run again).
Active cells get f0 such that the free-particle active temperature equals x P:
  m <v^2>/3 = (f0/gamma)^2 tau_p / (3 (tau_p + tau_g)),  tau_g = m/gamma,
so f0 = gamma sqrt(3 x P (tau_p + tau_g) / tau_p) (m = 1).

  python3 scripts/bath_table.py [--bin build/invasim] [--runs out/bath] [--csv docs/data/bath_table.csv]
Plain python3, standard library only.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

P, GAMMA, M = 1.3e-3, 0.2, 1.0
XS = (0.03, 0.3, 1.0)
MOTIONS = (("passive", 0.0), ("active", 25.0), ("active", 2500.0))
READINGS = (("langevin", 0.2), ("damped", 0.2), ("damped", 0.02), ("damped", 0.002))


def f0_for(x, tau_p):
    """Self-propulsion force whose free-particle active temperature is x P."""
    tau_g = M / GAMMA
    return GAMMA * math.sqrt(3.0 * x * P * (tau_p + tau_g) / tau_p)


def run(cmd, log):
    with open(log, "w") as f:
        done = subprocess.run(["nice"] + cmd, stdout=f, stderr=subprocess.STDOUT)
    if done.returncode != 0:
        sys.exit("failed (see %s): %s" % (log, " ".join(cmd)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="build/invasim")
    ap.add_argument("--runs", default="out/bath", help="directory of the runs")
    ap.add_argument("--csv", default="docs/data/bath_table.csv")
    ap.add_argument("--quench", type=int, default=20000)
    ap.add_argument("--steps", type=int, default=40000)
    ap.add_argument("--every", type=int, default=200)
    ap.add_argument("--readings", default="all",
                    help="comma-separated subset, e.g. langevin,damped:0.2 (default: all)")
    a = ap.parse_args()
    readings = READINGS if a.readings == "all" else [
        (r.split(":")[0], float(r.split(":")[1]) if ":" in r else 0.2) for r in a.readings.split(",")]
    os.makedirs(a.runs, exist_ok=True)
    base = os.path.join(a.runs, "base")
    if not os.path.exists(os.path.join(base, "checkpoint", "compressed.ckpt")):
        run([a.bin, "run", "protocols/invasion.lua", "--threads", "1", "--out", base,
             "--set", "quench_steps=0", "--set", "steps=%d" % a.every, "--set", "every=%d" % a.every,
             "--set", "snapshot_every=0", "--set", "checkpoint_every=0", "--set", "correlate_every=0"],
            base + ".log")
    rows = []
    for bath, vgamma in readings:
        for motion, tau_p in MOTIONS:
            for x in XS:
                kT = x * P
                f0 = f0_for(x, tau_p) if motion == "active" else 0.0
                name = "%s_%g_%s%s_x%g" % (bath, vgamma, motion, "" if tau_p == 0 else "%g" % tau_p, x)
                out = os.path.join(a.runs, name)
                summary = os.path.join(out, "summary.json")
                if not os.path.exists(summary):
                    sets = {"vertex_bath": bath, "vertex_gamma": vgamma, "kT": "%.6g" % kT,
                            "f0": "%.6g" % f0, "tau_p": tau_p if tau_p else 25, "P": P,
                            "quench_steps": a.quench, "steps": a.steps, "every": a.every,
                            "snapshot_every": 0, "checkpoint_every": 0}
                    cmd = [a.bin, "run", "protocols/bath_cell.lua", "--threads", "1", "--from", base,
                           "--out", out]
                    for k, v in sets.items():
                        cmd += ["--set", "%s=%s" % (k, v)]
                    print("running", name, flush=True)
                    run(cmd, out + ".log")
                s = json.load(open(summary))
                av = s["averages"]
                rows.append({
                    "vertex_bath": bath, "vertex_gamma": vgamma, "motion": motion,
                    "tau_p": tau_p if motion == "active" else "", "x": x, "kT": kT, "f0": f0,
                    "kT_c_over_P": s["derived"]["kT_over_P"],
                    "kT_c_over_P_err": s["derived"]["kT_over_P_error"],
                    "T_c_over_T_a": av["T_c_over_T_a"]["mean"],
                    "T_c_over_T_a_err": av["T_c_over_T_a"]["error"],
                    "T_a_over_P": av["T_a"]["mean"] / P, "samples": av["T_c_over_T_a"]["samples"],
                })
                print("%-36s kT_c/P = %.4g +- %.2g  T_c/T_a = %.4g +- %.2g" % (
                    name, rows[-1]["kT_c_over_P"], rows[-1]["kT_c_over_P_err"],
                    rows[-1]["T_c_over_T_a"], rows[-1]["T_c_over_T_a_err"]), flush=True)
    os.makedirs(os.path.dirname(a.csv) or ".", exist_ok=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    print("wrote", a.csv)
    print(markdown(rows))


def markdown(rows):
    """The table of docs/model.md: one row per (motion, x), one column per reading; each cell
    `T_c/T_a +- error (measured k_B T_c / (P sigma^3))`."""
    readings = []
    for r in rows:
        if (r["vertex_bath"], r["vertex_gamma"]) not in readings:
            readings.append((r["vertex_bath"], r["vertex_gamma"]))
    head = ["cells", "x = kT/(P sigma^3)"] + [
        "Langevin" if b == "langevin" else "damped, vertex_gamma = %g" % g for b, g in readings]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for motion, tau_p in MOTIONS:
        for x in XS:
            cells = []
            for b, g in readings:
                hit = [r for r in rows if (r["vertex_bath"], r["vertex_gamma"]) == (b, g)
                       and r["motion"] == motion and r["x"] == x
                       and (motion == "passive" or r["tau_p"] == tau_p)]
                if hit:
                    r, e = hit[0]["T_c_over_T_a"], hit[0]["T_c_over_T_a_err"]
                    fmt = "%.3f +- %.3f (%.3g)" if r < 10 else "%.1f +- %.1f (%.3g)"
                    cells.append(fmt % (r, e, hit[0]["kT_c_over_P"]))
                else:
                    cells.append("")
            name = "passive" if motion == "passive" else "active, tau_p = %g" % tau_p
            lines.append("| " + " | ".join([name, "%g" % x] + cells) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
