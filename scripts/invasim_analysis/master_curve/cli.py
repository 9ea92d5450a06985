"""The master curve of an invasim sweep (the paper's Fig. 5 analysis; docs/sweeps_analysis.md).

Usage: master_curve.py RESULTS.csv -o DIR [--group K1,K2] [--temperature kT|T_c|kT_c_paper]
                       [--normalise-by K=V[,K=V]] [--normalise-within K1,K2]
                       [--fixed K=V[,K=V]] [--replicate-key seed] [--tau-g T] [--pool N]
                       [--min-error E] [--max-drift K=F[,K=F]|none]
                       [--plateaus fitted|extremes] [--no-figures]

RESULTS.csv is what `invasim sweep collect WS -o results.csv` writes; only jobs with status
`done` count. Writes into DIR: fits.csv, fits.json, points.csv, rows.csv, An_vs_T.png,
collapse.png and (with at least two usable curves) a_vs_tau.png.

Needs numpy, scipy and matplotlib (Debian 12: apt-get install python3-numpy python3-scipy
python3-matplotlib); if the python3 running it lacks them, it re-runs itself with
/usr/bin/python3. Exit status: 0 on success, 1 on bad input or missing modules, 2 on a bad
command line.
"""

import argparse
import os
import sys

from ..deps import ensure_modules

DESCRIPTION = """\
Fits the paper's master curve to a sweep's results table.

0. Steadiness: a state point is not a steady state when (a) its runs fail the criterion of
   docs/validation.md (the means of A_t over the last two quarters of a run differ by more
   than 2 combined errors, from the integrated autocorrelation time, and by 1 % of A_t^max
   or more: the table's A_t_drift, A_t_drift_error and A_t_max; not judged, with a note,
   for a table without them); or (b) its quantity K drifts over the averaging window by more
   than F of its mean, averaged over replicates (|mean K_drift/K| > F, --max-drift, default
   L_x=0.05: a box still growing or shrinking under the barostat). Its jobs are scaled like
   the others (rows.csv, hollow in the figure) but set no normalisation and enter no fit.
1. Per job: rA_t = (A_t - dA)/(A_t^max - dA), dA = A_t^max - min A_t^max, and
   A_n = (rA_t - min rA_t)/(max rA_t - min rA_t). The minima and maxima are over the state
   points (each the mean over its replicates) of the normalisation group (--normalise-by;
   default: every finished job), separately in each --normalise-within partition. Jobs
   outside the group are scaled the same way (A_n may leave [0, 1]).
2. State point = the jobs equal in every state-point key but the replicate key (seed):
   x = mean of k_B T/(P sigma^3), A_n = mean over replicates, its error = the standard
   error over replicates (one replicate: the run's own error of A_t and A_t^max,
   propagated), at least --min-error.
3. Per curve (jobs equal in the --group keys), weighted least squares (absolute sigmas) of
   A_n = (1/2)(tanh[b log10(x/a)] + 1) for log10 a and b; a's error from log10 a's. Then
   the curves of the normalisation group are fitted together with the plateaus as shared
   parameters, A_n = L + (H - L)(1/2)(tanh[b log10(x/a)] + 1): the extremes of noisy means
   overshoot the plateaus and would bias a and b (docs/sweeps_analysis.md). A fit with b <= 0
   or an error above its value is not a fit: named, left out of the collapse and the fit of
   a; exit 1 if no curve gives a fit.
4. Across curves: a = c1 (1 + c2 beta eps_c/(P sigma^3)) tau_g/tau_d, tau_g = m/gamma
   (gamma from the state point or --fixed, else 0.2: tau_g = 5), tau_d = mean of the
   curve's tau_d column; sigmas: a's error and tau_d's standard error (effective
   variance). c2 only if beta/P differs between curves.
"""


def fail(message, status=1):
    print("master_curve.py: error: " + message, file=sys.stderr)
    sys.exit(status)


def parse_args(argv):
    p = argparse.ArgumentParser(prog="master_curve.py", description=DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results", help="results.csv of `invasim sweep collect`")
    p.add_argument("-o", "--out", required=True, metavar="DIR", help="output directory")
    p.add_argument("--group", default="", metavar="K1,K2",
                   help="state-point keys that make a curve (default: one curve)")
    p.add_argument("--temperature", default="kT_c_paper", choices=["kT", "T_c", "kT_c_paper"],
                   help="x axis: kT (the set background temperature), T_c (measured, "
                   "equipartition) or kT_c_paper (measured, = 2 T_c, the paper's convention; "
                   "default)")
    p.add_argument("--normalise-by", default="", metavar="K=V[,K=V]",
                   help="the normalisation group: the jobs with these values (default: all)")
    p.add_argument("--normalise-within", default="", metavar="K1,K2",
                   help="normalise separately within each combination of these keys")
    p.add_argument("--fixed", default="", metavar="K=V[,K=V]",
                   help="values of parameters that are not columns of RESULTS.csv "
                   "(e.g. P=1.3e-3,beta=0.01)")
    p.add_argument("--replicate-key", default="seed", metavar="K",
                   help="the key that numbers replicates of a state point (default: seed)")
    p.add_argument("--tau-g", type=float, default=None, metavar="T",
                   help="tau_g = m/gamma (default: from gamma, else 5)")
    p.add_argument("--pool", type=int, default=1, metavar="N",
                   help="pool the replicate variance of a state point with N neighbours on "
                   "each side along the curve (default: 1; 0: its own only)")
    p.add_argument("--min-error", type=float, default=1e-3, metavar="E",
                   help="floor of a state point's error of A_n (default: 1e-3)")
    p.add_argument("--max-drift", default="L_x=0.05", metavar="K=F[,K=F]",
                   help="state points whose K drifts by more than F of its mean over the "
                   "averaging window (mean over replicates) are not steady: not fitted "
                   "(default: L_x=0.05; none: no check)")
    p.add_argument("--plateaus", default="fitted", choices=["fitted", "extremes"],
                   help="the plateaus of A_n in the per-curve fits: fitted jointly over the "
                   "normalisation group's curves (default; unbiased), or the extremes of the "
                   "state-point means, 0 and 1 (the paper's normalisation as it stands: a, c1 "
                   "biased high when the noise grows with A_t)")
    p.add_argument("--no-figures", dest="figures", action="store_false",
                   help="write the tables only")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    if not args.min_error > 0:
        fail("--min-error %g: must be > 0" % args.min_error, 2)
    if args.pool < 0:
        fail("--pool %d: must be >= 0" % args.pool, 2)
    if args.tau_g is not None and not args.tau_g > 0:
        fail("--tau-g %g: must be > 0" % args.tau_g, 2)
    ensure_modules("master_curve.py")
    # numpy only: reading and checking the input stays fast (scipy is imported for the fits,
    # matplotlib for the figures).
    from . import analysis, output
    from .selection import parse_assignments, parse_keys, parse_limits
    from .table import InputError, Table

    try:
        opts = argparse.Namespace(
            group=parse_keys(args.group), within=parse_keys(args.normalise_within),
            selector=parse_assignments(args.normalise_by, "--normalise-by"),
            fixed=dict(parse_assignments(args.fixed, "--fixed")), temperature=args.temperature,
            replicate_key=args.replicate_key, tau_g=args.tau_g, min_error=args.min_error,
            window=args.pool, max_drift=parse_limits(args.max_drift, "--max-drift"),
            plateaus=args.plateaus)
        table = Table(args.results)
        for k in opts.fixed:
            if table.has(k):
                raise InputError("--fixed %s: '%s' is a column of %s; --fixed only supplies "
                                 "parameters that are not" % (k, k, args.results))
        result = analysis.analyse(table, opts)
    except InputError as e:
        fail(str(e))
    os.makedirs(args.out, exist_ok=True)
    settings = {"results": os.path.abspath(args.results), "temperature": args.temperature,
                "x_axis": analysis.TEMPERATURES[args.temperature][1], "group": opts.group,
                "normalise_by": dict(opts.selector), "normalise_within": opts.within,
                "fixed": opts.fixed, "replicate_key": opts.replicate_key,
                "tau_g": args.tau_g, "min_error": args.min_error, "pool": args.pool,
                "max_drift": dict(opts.max_drift), "plateaus": args.plateaus,
                "state_keys": result["state_keys"]}
    paths = output.write_tables(args.out, result, settings)
    if args.figures:
        from . import plots

        paths.update(plots.write_figures(args.out, result,
                                         analysis.TEMPERATURES[args.temperature][1]))
    report(result, paths)
    warn_bad_fits(result)


def warn_bad_fits(result):
    """Says on stderr which curves are not fits and which tau_d were dropped; exits 1 if no
    curve gives a fit (the tables and figures are written, to look at)."""
    for w in result["warnings"]:
        print("master_curve.py: warning: " + w, file=sys.stderr)
    for c in result["curves"]:
        for d in c["tau_d_dropped"]:
            print("master_curve.py: warning: curve %s: job %s has tau_d = %s: left out of the "
                  "curve's tau_d%s" % (c["name"], d["job"], d["tau_d"],
                                       "" if c["tau_d"] is not None else
                                       " (none left: the curve is left out of the fit of a)"),
                  file=sys.stderr)
        if c["not_a_fit"]:
            print("master_curve.py: warning: curve %s is not a fit: %s; it is left out of the "
                  "collapse and of the fit of a" % (c["name"], c["not_a_fit"]), file=sys.stderr)
    if not any(c["not_a_fit"] is None for c in result["curves"]):
        fail("no curve gives a fit (%d curve%s, none with b > 0 and errors below the values%s)"
             % (len(result["curves"]), "" if len(result["curves"]) == 1 else "s",
                "" if len(result["curves"]) > 1 else "; group the sweep into curves with --group"))


def report(result, paths):
    for key in result["unchecked_drift"]:
        print("note: no %s_drift column (a results.csv from an older `sweep collect`?): "
              "steadiness in %s not checked" % (key, key))
    if not result["runs_judged"]:
        print("note: no A_t_drift_error column (a results.csv from an older `sweep collect`: "
              "collect again): the steadiness of A_t's runs not judged")
    unsteady = [i for i, why in enumerate(result["unsteady"]) if why]
    if unsteady:
        print("not steady, so not fitted and not used to normalise (%d of %d jobs):"
              % (len(unsteady), len(result["rows"])))
        by_reason = {}
        for i in unsteady:
            r = result["rows"][i]
            by_reason.setdefault((result["curve_of"][i], result["unsteady"][i]), []).append(
                (r.get("job_id") or "line %d" % r["_line"])[:8])
        for (curve, why), jobs in by_reason.items():
            print("  %s: %s: %s" % (curve, why, ", ".join(jobs)))
    for c in result["curves"]:
        print("curve %s: %d state points, %d jobs: a = %.4g +- %.2g, b = %.4g +- %.2g, "
              "chi2/dof = %s" % (c["name"], len(c["points"]), c["jobs"], c["a"], c["a_error"],
                                 c["b"], c["b_error"],
                                 "%.3g" % (c["chi2"] / c["dof"]) if c["dof"] > 0 else "-"))
        if c["fit_note"]:
            print("  note: " + c["fit_note"])
        if c["not_a_fit"]:
            print("  NOT A FIT: " + c["not_a_fit"])
        if c["varying"]:
            print("  its state points differ in: %s" % ", ".join(c["varying"]))
    for p in result["plateau_fits"]:
        where = ", ".join("%s=%s" % kv for kv in p["partition"].items()) or "the whole sweep"
        if p["done"]:
            print("plateaus of A_n fitted over the %d curve%s of the normalisation group of %s: "
                  "L = %.3g +- %.2g, H = %.3g +- %.2g (the extremes of the means: 0 and 1)"
                  % (len(p["curves"]), "" if len(p["curves"]) == 1 else "s", where, p["lo"],
                     p["lo_error"], p["hi"], p["hi_error"]))
        else:
            print("plateaus of %s not fitted: %s" % (where, p["reason"]))
    s = result["scale_fit"]
    if s["done"]:
        line = "a = c1 (1 + c2 beta/P) tau_g/tau_d over %d curves: c1 = %.4g +- %.2g" % (
            s["n_curves"], s["c1"], s["c1_error"])
        if s["c2"] is not None:
            line += ", c2 = %.4g +- %.2g" % (s["c2"], s["c2_error"])
        print(line + ", chi2/dof = %s" % ("%.3g" % s["chi2_dof"] if s["chi2_dof"] else "-"))
    else:
        print("fit of a not done: " + s["reason"])
    print("wrote " + " ".join(sorted(paths.values())))
