#!/usr/bin/env python3
"""Analysis of cross_check_lammps.sh: one code treats both programs' output.

  cross_check_lammps.py reduce RUN_DIR invasim|lammps EQ DATA
      one run's means and curves -> RUN_DIR/reduced.npz (DATA: the start's data file)
  cross_check_lammps.py table WORK
      per case (WORK/<case>/{invasim,lammps}/seed*/reduced.npz): each quantity's mean +-
      standard error over the seeds in both programs and their difference in combined standard
      errors; exit status 1 if any |difference| >= 3 of them
  cross_check_lammps.py static DIR
      per state (DIR/<state>.data): the start as each program placed it (positions, sizes),
      energy, virial and per-cell forces; exit status 1 if the starts are not the same
  cross_check_lammps.py xyz2data XYZ DATA
      an invasim XYZ frame as a LAMMPS data file (types 1/2 = diameters 0.9/1.1)

Quantities per run (production samples only, steps > EQ): mean contact energy per cell u,
kinetic temperature kT = sum m v^2 / 3N, virial pressure P_vir = sum_a W_aa / 3V and
P = N kT / V + P_vir; g(r) of all pairs and of the three size pairs from the snapshots; MSD and
F_s(k = 2 pi) (isotropic: <sin(k dr) / (k dr)>) of the unwrapped positions at every sample lag,
averaged over time origins every ORIGIN_EVERY samples (the estimator of invasim's Correlator,
whose own MSD is kept for comparison).
"""
import glob
import json
import os
import sys

import numpy as np

ORIGIN_EVERY = 5
RMAX, DR = 3.0, 0.02
FINE = (0.6, 1.4, 0.0005)  # the first peak: fine bins, then smoothed over PEAK_SMOOTH
PEAK_SMOOTH = 0.005
MSD_LAGS = (1, 10, 100)  # in samples: units of tau with every = 20 steps of dt = 0.05
DIAMETER = {1: 0.9, 2: 1.1}  # by LAMMPS atom type (bench_engine lammps-data)
DT = 0.05


# ---------------------------------------------------------------- readers
def read_xyz(path):
    """invasim's XYZ snapshot -> step, box lengths, origin, positions, diameters."""
    with open(path) as f:
        n = int(f.readline())
        head = f.readline()
    lat = [float(x) for x in head.split('Lattice="')[1].split('"')[0].split()]
    org = [float(x) for x in head.split('Origin="')[1].split('"')[0].split()]
    step = int(head.split("Step=")[1].split()[0])
    a = np.loadtxt(path, skiprows=2, usecols=(1, 2, 3, 4), max_rows=n)
    return step, np.array(lat)[[0, 4, 8]], np.array(org), a[:, :3], 2 * a[:, 3]


def read_dump(path):
    """LAMMPS text dump sorted by id -> [(step, box lengths, columns after the id)]."""
    lines = open(path).read().splitlines()
    frames = []
    k = 0
    while k < len(lines):
        assert lines[k].startswith("ITEM: TIMESTEP"), f"{path}: line {k + 1}"
        step, n = int(lines[k + 1]), int(lines[k + 3])
        bounds = np.array([[float(x) for x in lines[k + 5 + a].split()[:2]] for a in range(3)])
        cols = np.array(" ".join(lines[k + 9:k + 9 + n]).split(), dtype=float).reshape(n, -1)
        frames.append((step, bounds[:, 1] - bounds[:, 0], cols[:, 1:]))
        k += 9 + n
    return frames


def read_data(path):
    """LAMMPS 'atomic' data file -> box lengths, types, positions (in id order)."""
    lines = open(path).read().splitlines()
    box = {}
    for k, line in enumerate(lines):
        w = line.split()
        if len(w) == 2 and w[1] == "atoms":
            n = int(w[0])
        if len(w) == 4 and w[2][1:] == "lo":
            box[w[2][0]] = (float(w[0]), float(w[1]))
        if w and w[0] == "Atoms":
            rows = np.array([l.split()[:5] for l in lines[k + 2:k + 2 + n]], dtype=float)
            break
    rows = rows[np.argsort(rows[:, 0])]
    return np.array([box[a][1] - box[a][0] for a in "xyz"]), rows[:, 1].astype(int), rows[:, 2:5]


# ---------------------------------------------------------------- measurements
def pair_distances(x, L, rmax):
    """Minimum-image distances r < rmax of the pairs i < j, with i and j (rmax < L/2)."""
    assert rmax < 0.5 * L.min(), "g(r) needs RMAX below half the box"
    n, out = len(x), ([], [], [])
    for a in range(0, n, 256):
        d = x[a:a + 256, None, :] - x[None, :, :]
        d -= L * np.round(d / L)
        r = np.sqrt((d * d).sum(-1))
        i, j = np.nonzero((r < rmax) & (np.arange(n)[None, :] > np.arange(a, a + len(r))[:, None]))
        for lst, v in zip(out, (i + a, j, r[i, j])):
            lst.append(v)
    return [np.concatenate(v) for v in out]


def gofr(frames, diam):
    """g(r) of all pairs and of the pairs (0.9, 0.9), (0.9, 1.1), (1.1, 1.1) in bins of DR, and
    on the fine bins of FINE; the closest pair seen."""
    edges = np.arange(0.0, RMAX + DR / 2, DR)
    fine = np.arange(FINE[0], FINE[1] + FINE[2] / 2, FINE[2])
    small = diam < 1.0
    n, ns = len(diam), int(small.sum())
    counts = {k: np.zeros(len(edges) - 1) for k in ("all", "ss", "sl", "ll")}
    fcounts = {k: np.zeros(len(fine) - 1) for k in counts}
    rmin = np.inf
    for L, x in frames:
        i, j, r = pair_distances(x, L, RMAX)
        rmin = min(rmin, r.min())
        a, b = small[i], small[j]
        for key, sel in (("all", slice(None)), ("ss", a & b), ("sl", a != b), ("ll", ~a & ~b)):
            counts[key] += np.histogram(r[sel], edges)[0]
            fcounts[key] += np.histogram(r[sel], fine)[0]
    V, nf = np.prod(frames[0][0]), len(frames)
    pairs = {"all": n * (n - 1) / 2, "ss": ns * (ns - 1) / 2, "sl": ns * (n - ns),
             "ll": (n - ns) * (n - ns - 1) / 2}
    shell = lambda e: 4.0 / 3.0 * np.pi * (e[1:] ** 3 - e[:-1] ** 3)
    g = {k: counts[k] / (nf * pairs[k] / V * shell(edges)) for k in counts}
    gf = {k: fcounts[k] / (nf * pairs[k] / V * shell(fine)) for k in counts}
    return 0.5 * (edges[1:] + edges[:-1]), g, 0.5 * (fine[1:] + fine[:-1]), gf, rmin


def msd_fs(traj, k=2 * np.pi, lags=101):
    """MSD and isotropic F_s at lags 0..lags-1 samples, origins every ORIGIN_EVERY samples."""
    S = len(traj)
    msd, fs = np.zeros(lags), np.zeros(lags)
    for lag in range(lags):
        origins = np.arange(0, S - lag, ORIGIN_EVERY)
        if len(origins) == 0:
            msd[lag] = fs[lag] = np.nan
            continue
        d = traj[origins + lag] - traj[origins]
        r = np.sqrt((d * d).sum(-1))
        msd[lag] = (r * r).mean()
        kr = k * r
        fs[lag] = np.where(kr > 0, np.sin(kr) / np.where(kr > 0, kr, 1), 1.0).mean()
    return msd, fs


def unwrap(wrapped, L):
    d = np.diff(wrapped, axis=0)
    d -= L * np.round(d / L)
    return np.concatenate([wrapped[:1], wrapped[:1] + np.cumsum(d, axis=0)])


# ---------------------------------------------------------------- one run
def reduce_run(run, code, eq, data):
    out = {}
    if code == "invasim":
        info = json.load(open(os.path.join(run, "info.json")))
        n, V, L = info["N"], info["volume"], np.array(info["box"])
        th = np.genfromtxt(os.path.join(run, "thermo.csv"), delimiter=",", names=True)
        keep = th["step"] > eq
        u, T, W = th["U"][keep] / n, th["kT"][keep], th["W"][keep]
        pvir = W / (3 * V)
        wrapped = np.fromfile(os.path.join(run, "positions.bin"), dtype="<f8").reshape(-1, n, 3)
        traj = unwrap(wrapped, L)
        frames, diam = [], None
        for s in sorted(glob.glob(os.path.join(run, "snapshots", "cells_*.xyz"))):
            step, lat, org, x, dm = read_xyz(s)
            if step > eq:
                frames.append((lat, x - org))
                diam = dm
        c = np.genfromtxt(os.path.join(run, "msd.csv"), delimiter=",", names=True)
        out["own_msd"] = c["msd"]
    else:
        th = np.loadtxt(os.path.join(run, "thermo.txt"))
        keep = th[:, 0] > eq
        L, types, _ = read_data(data)
        n, V = len(types), np.prod(L)
        diam = np.vectorize(DIAMETER.get)(types)
        u, T, pvir = th[keep, 1] / n, th[keep, 2], th[keep, 3]
        out["P_lammps"] = th[keep, 4]
        traj = np.array([x for step, _, x in read_dump(os.path.join(run, "traj.txt")) if step > eq])
        frames = [(b, x) for step, b, x in read_dump(os.path.join(run, "snap.txt")) if step > eq]
    if len(u) < 2 or not frames:
        sys.exit(f"{run}: too short a run for the analysis (samples {len(u)}, g(r) frames "
                 f"{len(frames)}): give more STEPS")
    out.update(u=u, T=T, pvir=pvir, P=n * T / V + pvir, n=n, V=V)
    out["msd"], out["fs"] = msd_fs(traj)
    out["r"], g, out["r_fine"], gf, out["rmin"] = gofr(frames, diam)
    for k in g:
        out["g_" + k] = g[k]
        out["gfine_" + k] = gf[k]
    out["n_frames"] = len(frames)
    out["n_samples"] = len(u)
    np.savez(os.path.join(run, "reduced.npz"), **out)


# ---------------------------------------------------------------- the table
def smooth(y, sigma):
    """Gaussian smoothing of sigma bins (truncated at 4 sigma), edges repeated."""
    m = int(4 * sigma + 0.5)
    w = np.exp(-0.5 * (np.arange(-m, m + 1) / sigma) ** 2)
    return np.convolve(np.pad(y, m, mode="edge"), w / w.sum(), mode="valid")


def peak(r, g):
    """First peak of g on the fine bins after a Gaussian smoothing of PEAK_SMOOTH: height and
    position (parabola through the top three points), continuous in the data."""
    gs = smooth(g, PEAK_SMOOTH / (r[1] - r[0]))
    i = int(np.argmax(gs))
    y0, y1, y2 = gs[i - 1], gs[i], gs[i + 1]
    shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
    return y1 - 0.25 * (y0 - y2) * shift, r[i] + shift * (r[1] - r[0])


def per_run(z):
    row = {"u": z["u"].mean(), "kT": z["T"].mean(), "P_vir": z["pvir"].mean(), "P": z["P"].mean()}
    for lag in MSD_LAGS:
        row[f"MSD({lag})"] = z["msd"][lag]
    for lag in MSD_LAGS:
        row[f"F_s({lag})"] = z["fs"][lag]
    for key in ("ss", "sl", "ll"):  # (the total g's first peak has three sub-peaks)
        row[f"g_{key} peak"], row[f"g_{key} r_peak"] = peak(z["r_fine"], z["gfine_" + key])
    return row


def mean_err(values):
    v = np.array(values)
    return v.mean(), v.std(ddof=1) / np.sqrt(len(v))


def fmt(m, e):
    return f"{m:.6g} +- {e:.2g}"


def table(work):
    verdict = []
    for case in sorted(os.listdir(work)):
        cdir = os.path.join(work, case)
        if not os.path.isdir(os.path.join(cdir, "invasim")):
            continue
        runs = {code: [np.load(p) for p in sorted(glob.glob(os.path.join(cdir, code, "*",
                                                                         "reduced.npz")))]
                for code in ("invasim", "lammps")}
        if min(len(v) for v in runs.values()) < 2:
            sys.exit(f"{case}: fewer than 2 runs per program: no standard error")
        rows = {code: [per_run(z) for z in runs[code]] for code in runs}
        print(f"\n## {case}: {len(rows['invasim'])} invasim and {len(rows['lammps'])} LAMMPS "
              f"runs, {int(runs['invasim'][0]['n_samples'])} samples and "
              f"{int(runs['invasim'][0]['n_frames'])} g(r) frames each")
        kT = float(open(os.path.join(cdir, "kT")).read())
        if min(len(rows["invasim"]), len(rows["lammps"])) < 8:
            print("(fewer than 8 runs per program: their standard errors are unreliable)")
        print("| quantity | invasim | LAMMPS | difference / sigma |")
        print("|---|---|---|---|")
        for q in rows["invasim"][0]:
            a = mean_err([r[q] for r in rows["invasim"]])
            b = mean_err([r[q] for r in rows["lammps"]])
            z = (a[0] - b[0]) / np.hypot(a[1], b[1])
            flag = "" if abs(z) < 3 else "  **DISCREPANCY**"
            verdict.append((case, q, z))
            print(f"| {q} | {fmt(*a)} | {fmt(*b)} | {z:+.2f}{flag} |")
        dev = [mean_err([r["kT"] / kT - 1 for r in rows[c]]) for c in ("invasim", "lammps")]
        print(f"kinetic temperature / bath kT - 1: invasim {fmt(*dev[0])} "
              f"({dev[0][0] / dev[0][1]:+.1f} sigma), LAMMPS {fmt(*dev[1])} "
              f"({dev[1][0] / dev[1][1]:+.1f} sigma)")
        # The whole g(r) curves: bin by bin, in combined standard errors (printed, not judged:
        # with ~100 bins a few beyond 3 are expected).
        for key in ("all", "ss", "sl", "ll"):
            ga = np.array([z["g_" + key] for z in runs["invasim"]])
            gb = np.array([z["g_" + key] for z in runs["lammps"]])
            d = ga.mean(0) - gb.mean(0)
            s = np.hypot(ga.std(0, ddof=1) / np.sqrt(len(ga)), gb.std(0, ddof=1) / np.sqrt(len(gb)))
            ok = s > 0
            zz = d[ok] / s[ok]
            print(f"g_{key}(r), {ok.sum()} bins of {DR} up to {RMAX}: chi2/bins = "
                  f"{(zz ** 2).mean():.3f}, max |diff|/sigma = {np.abs(zz).max():.2f} "
                  f"(at r = {runs['invasim'][0]['r'][ok][np.argmax(np.abs(zz))]:.2f}), "
                  f"max |diff| = {np.abs(d).max():.3g}")
        rel = max(np.nanmax(np.abs(z["own_msd"][1:] / z["msd"][1:len(z["own_msd"])] - 1))
                  for z in runs["invasim"])
        print(f"invasim's own Correlator MSD against this script's on its positions: "
              f"max relative difference {rel:.1e}")
        pl = np.concatenate([z["P_lammps"] for z in runs["lammps"]])
        pm = np.concatenate([z["P"] for z in runs["lammps"]])
        print(f"LAMMPS press against N kT/V + P_vir: max relative difference "
              f"{np.abs(pl / pm - 1).max():.1e}; closest pair seen: invasim "
              f"{min(z['rmin'] for z in runs['invasim']):.3f}, LAMMPS "
              f"{min(z['rmin'] for z in runs['lammps']):.3f}")
    bad = [v for v in verdict if abs(v[2]) >= 3]
    print(f"\n{len(verdict)} comparisons, {len(bad)} beyond 3 sigma; "
          f"chi2/n = {np.mean([v[2] ** 2 for v in verdict]):.2f}")
    for case, q, z in bad:
        print(f"  beyond 3 sigma: {case} {q} ({z:+.2f})")
    return 1 if bad else 0


# ---------------------------------------------------------------- static check
def static(d):
    """Per state: the start as placed by invasim (NAME.start.bin) against LAMMPS's first frame
    (NAME.dump: id type x y z), then energy, virial and forces. The forces come from one step
    from rest without damping or noise: x1 = x0 + dt^2/2 F(x0) exactly in both programs'
    velocity Verlet (mass 1), so F = 2 (x1 - x0) / dt^2."""
    print("| state | start: max |dx| | sizes differ | U invasim | U LAMMPS | rel. diff | "
          "W invasim | W LAMMPS | rel. diff | max |dF| | rms |F| |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    status = 0
    for s in sorted(p[:-len(".data")] for p in glob.glob(os.path.join(d, "*.data"))):
        L = read_data(s + ".data")[0]
        inv = json.load(open(s + ".invasim.json"))
        start = np.fromfile(s + ".start.bin", dtype="<f8").reshape(-1, 4)
        x0i, x1i = start[:, :3], np.fromfile(s + ".step.bin", dtype="<f8").reshape(-1, 3)
        (_, _, f0), (_, _, f1) = read_dump(s + ".dump")
        x0l, x1l, types = f0[:, 1:4], f1[:, 1:4], f0[:, 0].astype(int)
        mi = lambda dx: dx - L * np.round(dx / L)
        dx = np.abs(mi(x0i - x0l)).max()
        sizes = int((start[:, 3] != np.vectorize(DIAMETER.get)(types)).sum())
        if dx > 1e-12 * L.max() or sizes:
            status = 1
        fi, fl = (2 * mi(x1 - x0) / DT ** 2 for x0, x1 in ((x0i, x1i), (x0l, x1l)))
        lt = dict(l.split() for l in open(s + ".lammps.txt"))
        ul, wl = float(lt["pe"]), float(lt["wvir"]) * 3 * np.prod(L)
        print(f"| {os.path.basename(s)} | {dx:.1e} | {sizes} | {inv['U']:.10g} | {ul:.10g} | "
              f"{inv['U'] / ul - 1:.1e} | {inv['W']:.10g} | {wl:.10g} | {inv['W'] / wl - 1:.1e} | "
              f"{np.abs(fi - fl).max():.1e} | {np.sqrt((fi * fi).sum(1).mean()):.3g} |")
    if status:
        print("the two programs did not start from the same state (positions or sizes)")
    return status


def xyz2data(xyz, data):
    step, lat, org, x, diam = read_xyz(xyz)
    with open(data, "w") as f:
        f.write(f"invasim frame {os.path.basename(xyz)}\n\n{len(x)} atoms\n2 atom types\n\n")
        for a in range(3):
            f.write(f"0 {lat[a]:.17g} {'xyz'[a]}lo {'xyz'[a]}hi\n")
        f.write("\nMasses\n\n1 1\n2 1\n\nAtoms # atomic\n\n")
        for i, (r, dm) in enumerate(zip(np.mod(x - org, lat), diam)):
            f.write(f"{i + 1} {1 if dm < 1 else 2} {r[0]:.17g} {r[1]:.17g} {r[2]:.17g}\n")


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "reduce":
        reduce_run(sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5])
    elif cmd == "table":
        sys.exit(table(sys.argv[2]))
    elif cmd == "static":
        sys.exit(static(sys.argv[2]))
    elif cmd == "xyz2data":
        xyz2data(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
