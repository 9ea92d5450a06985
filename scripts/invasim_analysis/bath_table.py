"""Regenerates the vertex-bath tables of docs/model.md ("Vertex bath"): T_c/T_a and the measured
cancer-cell temperature on the reduced system, under each reading of the adipocyte vertices'
bath, over the active state points of the paper's Fig. 5 (tau_p = 25 and 2500, beta = 1e-3 and
1e-2, the f0 range of protocols/sweeps/fig5_active.lua, no background temperature unless the
reading adds one) and for passive cells (bath at kT, the vertices' reading unchanged).

The readings (docs/model.md, "Vertex bath", says what each one means):
  (a) background  Langevin cells and vertices at a common background T_0, the activity on top:
                  T_0 = T_act / r for r = T_act/T_0 in RATIOS, T_act the free-particle active
                  temperature (f0/gamma)^2 tau_p / (3 (tau_p + tau_g)), tau_g = m/gamma = 5;
  (b) damped      vertices damped with vertex_gamma in DAMPINGS, no noise in the active runs
                  (vertex_bath = langevin at the background kT = 0, which is plain damping;
                  the passive rows have the noise at their kT, so that they can equilibrate);
  (c) mass        vertices of mass m_v, damped with vertex_gamma (langevin as in (b)): m_v = the adipocyte's mass
                  spread over its 42 vertices (cell density, measured from the compressed
                  tissue) and a heavier one;
  (d) measured    Langevin vertices at the T_c measured under (b) with vertex_gamma = 0.2, a
                  reference the paper does not describe.

Every cell is one run of protocols/bath_cell.lua from one compressed tissue (--from), at
--threads 1 (a finished cell, with its summary.json, is not run again), quench 20000 steps and
a production of 40000 steps (tau_p = 2500: 100000, i.e. 2 tau_p), a sample every 200 steps.

  python3 scripts/bath_table.py [--bin build/invasim] [--runs out/bath] [--jobs 1]
         [--csv docs/data/bath_table.csv] [--model docs/model.md]
The tables go between the lines "<!-- bath_table.py: begin -->" and "<!-- bath_table.py: end -->"
of docs/model.md (the raw numbers to the CSV).
Plain python3, standard library only.
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

from . import atomic

P, GAMMA = 1.3e-3, 0.2
TAU_PS = (25.0, 2500.0, 0.02)
BETAS = (1e-3, 1e-2)
# f0 per tau_p: the Fig. 5 sweeps' range without background (tau_p = 0.02, shorter than dt, needs
# about 15 times the force for the same temperature, and at most 0.1, lib/model_limits.lua)
F0S = {25.0: (0.001, 0.003, 0.0065, 0.0105, 0.02), 2500.0: (0.001, 0.003, 0.0065, 0.0105, 0.02),
       0.02: (0.007, 0.022, 0.065, 0.1)}
PASSIVE_XS = (0.03, 0.3, 1.0)  # the paper's 2 k_B T/(P sigma^3) of the passive bath
RATIOS = (3.0, 1.0, 1.0 / 3.0, 1.0 / 6.0, 0.1)
DAMPINGS = (0.2, 0.02, 0.006, 0.002, 0.0)
HEAVY_MASS = 20.0
WINDOW = (1.0, 1.2)  # the paper's 1 < T_c/T_a < 1.2 for active runs
FIG5_RANGE = (0.005, 3.0)  # the measured 2 k_B T_c/(P sigma^3) the Fig. 5 sweeps span


def active_temperatures(binary, pairs, dt=0.05):
    """{(f0, tau_p): T_act} for the (f0, tau_p) pairs: the free-particle active temperature of
    Active{f0, tau_p, gamma} without noise, as the protocols compute it
    (protocols/lib/motion.lua, active_temperature), asked of the library through the binary
    (one `invasim run` of a generated script) so that the table and the protocols cannot
    disagree."""
    pairs = sorted(set(pairs))
    lines = ['package.path = %s .. "/?.lua;" .. package.path' % json.dumps(os.path.abspath("protocols")),
             'local motion = require("lib.motion")']
    lines += ['print(string.format("%%.17g", motion.active_temperature(%r, %r, %r, %r)))'
              % (f0, tau_p, GAMMA, dt) for f0, tau_p in pairs]
    fd, script = tempfile.mkstemp(suffix=".lua", prefix="bath_table_")
    try:
        with os.fdopen(fd, "w") as f:
            f.write("\n".join(lines) + "\n")
        done = subprocess.run([binary, "run", script], capture_output=True, text=True)
    finally:
        os.unlink(script)
    values = done.stdout.split()
    if done.returncode != 0 or len(values) != len(pairs):
        raise RuntimeError("asking lib.motion for the active temperatures failed: %s" % done.stderr.strip())
    return dict(zip(pairs, (float(v) for v in values)))


def readings(vertex_mass_adipocyte):
    """The readings: (id, group, description, --set values; kT and vertex_kT may be callables of
    the state point, 'measured' is filled from reading b0.2)."""
    out = []
    for r in RATIOS:
        out.append(("a_r%.3g" % r, "a", "background, T_act/T_0 = %.3g" % r,
                    {"vertex_bath": "langevin", "vertex_gamma": 0.2, "vertex_mass": 1.0,
                     "background_ratio": r}))
    for g in DAMPINGS:
        out.append(("b_g%g" % g, "b", "vertex_gamma = %g" % g,
                    {"vertex_bath": "langevin", "vertex_gamma": g, "vertex_mass": 1.0}))
    for m in (vertex_mass_adipocyte, HEAVY_MASS):
        for g in (0.2, 0.02):
            out.append(("c_m%.3g_g%g" % (m, g), "c", "vertex_mass = %.3g, vertex_gamma = %g" % (m, g),
                        {"vertex_bath": "langevin", "vertex_gamma": g, "vertex_mass": m}))
    out.append(("d_measured", "d", "Langevin at the measured T_c, vertex_gamma = 0.2",
                {"vertex_bath": "langevin", "vertex_gamma": 0.2, "vertex_mass": 1.0,
                 "vertex_kT": "measured"}))
    return out


def state_points(quick=False):
    """(name, motion, tau_p, beta, f0, passive x) of the table's rows; `quick`: one passive and
    one active point (the pipeline's test)."""
    if quick:
        return [("passive_x0.3", "passive", 0.0, 1e-2, 0.0, 0.3),
                ("tau25_beta0.01_f0.0105", "active", 25.0, 1e-2, 0.0105, None)]
    rows = [("passive_x%g" % x, "passive", 0.0, 1e-2, 0.0, x) for x in PASSIVE_XS]
    for tau_p in TAU_PS:
        for beta in BETAS:
            for f0 in F0S[tau_p]:
                rows.append(("tau%g_beta%g_f%g" % (tau_p, beta, f0), "active", tau_p, beta, f0, None))
    return rows


def run(cmd, log):
    with open(log, "w") as f:
        done = subprocess.run(["nice"] + cmd, stdout=f, stderr=subprocess.STDOUT)
    if done.returncode != 0:
        raise RuntimeError("failed (see %s): %s" % (log, " ".join(cmd)))


def adipocyte_vertex_mass(base):
    """An adipocyte's mass spread over its 42 vertices, at the cells' density (a cell of
    diameter sigma has m = 1): (phi_a V_box / N_a) / (pi/6) / 42, from the compressed tissue."""
    with open(os.path.join(base, "series.csv")) as f:
        row = next(csv.DictReader(f))
    params = json.load(open(os.path.join(base, "params.json")))
    n_c = 400 if params.get("N_c", 0) in (0, None) else params["N_c"]
    n_a = 8 if params.get("N_a", 0) in (0, None) else params["N_a"]
    mean_cell_volume = math.pi / 6 * (0.9 ** 3 + 1.1 ** 3) / 2
    box_volume = n_c * mean_cell_volume / float(row["phi_c"])
    v_adipocyte = float(row["phi_a"]) * box_volume / n_a
    return v_adipocyte / (math.pi / 6) / 42.0


def cell(a, base, reading, point, measured_T_c):
    rid, _, _, rset = reading
    name, motion, tau_p, beta, f0, x = point
    out = os.path.join(a.runs, "%s__%s" % (rid, name))
    kT = 0.0
    if motion == "passive":
        kT = x * P / 2.0
    elif "background_ratio" in rset:
        kT = a.t_act[(f0, tau_p)] / rset["background_ratio"]
    sets = {"vertex_bath": rset["vertex_bath"], "vertex_gamma": rset["vertex_gamma"],
            "vertex_mass": "%.6g" % rset["vertex_mass"], "kT": "%.6g" % kT, "f0": "%.6g" % f0,
            "tau_p": tau_p if tau_p else 25, "beta": beta, "P": P, "background_factor": 0,
            "quench_steps": a.quench_steps, "every": a.every,
            "steps": a.steps * 5 // 2 if tau_p >= 2500 else a.steps,  # 2 tau_p at 2500
            "snapshot_every": 0, "checkpoint_every": 0}
    if rset.get("vertex_kT") == "measured":
        sets["vertex_kT"] = "%.6g" % measured_T_c
    summary = os.path.join(out, "summary.json")
    if not os.path.exists(summary):
        cmd = [a.bin, "run", "protocols/bath_cell.lua", "--threads", "1", "--from", base, "--out", out]
        for k, v in sets.items():
            cmd += ["--set", "%s=%s" % (k, v)]
        run(cmd, out + ".log")
    s = json.load(open(summary))
    av = s["averages"]
    return {"reading": rid, "point": name, "motion": motion, "tau_p": tau_p, "beta": beta, "f0": f0,
            "kT": kT, "vertex_kT": float(sets.get("vertex_kT", 0.0)),
            "kT_c_over_P": s["derived"]["kT_over_P"], "kT_c_over_P_err": s["derived"]["kT_over_P_error"],
            "T_c_over_T_a": av["T_c_over_T_a"]["mean"], "T_c_over_T_a_err": av["T_c_over_T_a"]["error"],
            "T_a_over_P": av["T_a"]["mean"] / P}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default="build/invasim")
    ap.add_argument("--runs", default="out/bath", help="directory of the runs")
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time (one thread each)")
    ap.add_argument("--quick", action="store_true",
                    help="two state points and short runs: checks the pipeline, not the physics")
    ap.add_argument("--csv", default="docs/data/bath_table.csv")
    ap.add_argument("--model", default="docs/model.md",
                    help="page whose tables between the bath_table markers are replaced")
    a = ap.parse_args()
    a.quench_steps, a.steps, a.every = (200, 400, 100) if a.quick else (20000, 40000, 200)
    os.makedirs(a.runs, exist_ok=True)
    base = os.path.join(a.runs, "base")
    if not os.path.exists(os.path.join(base, "checkpoint", "compressed.ckpt")):
        run([a.bin, "run", "protocols/invasion.lua", "--threads", "1", "--out", base,
             "--set", "quench_steps=0", "--set", "steps=200", "--set", "every=200",
             "--set", "snapshot_every=0", "--set", "checkpoint_every=0", "--set", "correlate_every=0"],
            base + ".log")
    m_v = adipocyte_vertex_mass(base)
    all_readings = readings(m_v)
    points = state_points(a.quick)
    a.t_act = active_temperatures(a.bin, [(p[4], p[2]) for p in points if p[1] != "passive"])
    rows = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        # Every reading but (d) first; (d) needs the T_c measured under damped vertices at 0.2.
        first = [(r, p) for r in all_readings if r[0] != "d_measured" for p in points]
        for row in pool.map(lambda rp: cell(a, base, rp[0], rp[1], 0.0), first):
            rows.append(row)
            print("%-12s %-26s 2T_c/P = %.4g  T_c/T_a = %.4g +- %.2g" % (
                row["reading"], row["point"], 2 * row["kT_c_over_P"], row["T_c_over_T_a"],
                row["T_c_over_T_a_err"]), flush=True)
        ref = {r["point"]: r["kT_c_over_P"] * P for r in rows if r["reading"] == "b_g0.2"}
        d = [r for r in all_readings if r[0] == "d_measured"][0]
        for row in pool.map(lambda p: cell(a, base, d, p, ref[p[0]]), points):
            rows.append(row)
            print("%-12s %-26s 2T_c/P = %.4g  T_c/T_a = %.4g +- %.2g" % (
                row["reading"], row["point"], 2 * row["kT_c_over_P"], row["T_c_over_T_a"],
                row["T_c_over_T_a_err"]), flush=True)
    os.makedirs(os.path.dirname(a.csv) or ".", exist_ok=True)
    with atomic.open_text(a.csv) as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in r.items()})
    text = markdown(rows, all_readings, points, m_v)
    replace_between_markers(a.model, text)
    print("wrote", a.csv, "and the tables of", a.model)
    print(text)


BEGIN, END = "<!-- bath_table.py: begin -->", "<!-- bath_table.py: end -->"


def replace_between_markers(path, text):
    """Writes `text` between the BEGIN and END lines of `path` (atomically); refuses a page
    without exactly one pair, so that the tables cannot land in the wrong place."""
    page = open(path).read()
    if page.count(BEGIN) != 1 or page.count(END) != 1 or page.index(BEGIN) > page.index(END):
        sys.exit("%s: needs one line '%s' and, after it, one line '%s' around the tables" % (path, BEGIN, END))
    head, rest = page.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    atomic.write_text(path, head + BEGIN + "\n" + text + "\n" + END + tail)


def in_window(r):
    """T_c/T_a within the paper's window, allowing 2 errors."""
    lo, hi = WINDOW
    return lo - 2 * r["T_c_over_T_a_err"] <= r["T_c_over_T_a"] <= hi + 2 * r["T_c_over_T_a_err"]


def equilibrates(r):
    """Passive: T_c/T_a = 1 within 0.02 + 2 errors."""
    return abs(r["T_c_over_T_a"] - 1.0) <= 0.02 + 2 * r["T_c_over_T_a_err"]


def markdown(rows, all_readings, points, m_v):
    """The tables of docs/model.md: a summary per reading (how many active points fall in the
    window, whether passive cells and vertices equilibrate), then one table per reading group
    with a row per state point, each cell `T_c/T_a +- error (2 k_B T_c/(P sigma^3))`."""
    by = {(r["reading"], r["point"]): r for r in rows}
    lines = ["Adipocyte vertex mass of reading (c): %.3g m (the adipocyte's volume over a cell's, / 42)." % m_v, "",
             "| reading | active points in 1 <= T_c/T_a <= 1.2 (2 errors) | of those at 2 k_B T_c/(P sigma^3) in [%g, %g] (Fig. 5's range) | range of T_c/T_a (active) | passive T_c/T_a | passive equilibrates |" % FIG5_RANGE,
             "|---|---|---|---|---|---|"]
    for rid, _, desc, _ in all_readings:
        act = [by[(rid, p[0])] for p in points if p[1] == "active" and (rid, p[0]) in by]
        pas = [by[(rid, p[0])] for p in points if p[1] == "passive" and (rid, p[0]) in by]
        if not act:
            continue
        ratios = [r["T_c_over_T_a"] for r in act]
        fig5 = [r for r in act if FIG5_RANGE[0] <= 2 * r["kT_c_over_P"] <= FIG5_RANGE[1]]
        lines.append("| %s (%s) | %d of %d | %d of %d | %.3g to %.3g | %s | %s |" % (
            rid, desc, sum(in_window(r) for r in act), len(act), sum(in_window(r) for r in fig5),
            len(fig5), min(ratios), max(ratios),
            ", ".join("%.3g" % r["T_c_over_T_a"] for r in pas),
            "yes" if pas and all(equilibrates(r) for r in pas) else "no"))
    for group, title in (("a", "(a) a common background T_0 for cells and vertices, the activity on top"),
                         ("b", "(b) vertices damped with vertex_gamma, no background (passive rows: noise at kT)"),
                         ("c", "(c) a vertex mass other than the cells' (no background; passive rows: noise at kT)"),
                         ("d", "(d) reference only: vertices in a bath at the T_c measured under vertex_gamma = 0.2")):
        ids = [(rid, desc) for rid, g, desc, _ in all_readings if g == group]
        lines += ["", "**%s**" % title, "",
                  "| state point | " + " | ".join(desc for _, desc in ids) + " |",
                  "|---|" + "---|" * len(ids)]
        for name, motion, tau_p, beta, f0, x in points:
            label = ("passive, 2kT/P = %g" % x if motion == "passive"
                     else "tau_p = %g, beta = %g, f0 = %g" % (tau_p, beta, f0))
            cells = []
            for rid, _ in ids:
                r = by.get((rid, name))
                if not r:
                    cells.append("")
                    continue
                v, e = r["T_c_over_T_a"], r["T_c_over_T_a_err"]
                fmt = "%.3f +- %.3f (%.3g)" if v < 10 else "%.1f +- %.1f (%.3g)"
                cells.append(fmt % (v, e, 2 * r["kT_c_over_P"]))
            lines.append("| " + label + " | " + " | ".join(cells) + " |")
    return "\n".join(lines)
