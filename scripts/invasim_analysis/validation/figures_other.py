"""The validation figures of Figs. 6 (cells only), 8 (packing scan) and 9 (slice shapes); same
contract as figures_tissue.py (Fig. 5: figures_master.py)."""

import csv
import math
import os

import numpy as np

from .. import normalise, steady, student, workspace
from . import points, verdict
from .plotting import figure, label, log_axis, log_if_spans, save, state

INTERMEDIATE = 10.0  # tau_p <= 10 tau_g: small and intermediate persistence (Fig. 6(b))


def fig6(jobs, out, invasim):
    """tau_d against tau_p per phi_c beside the exact free-particle value (Eq. (18))."""
    fig, (ax,) = figure()
    rows, table = [], []
    for (phi_c,), reps in workspace.group(jobs, ["phi_c"]).items():
        reps.sort(key=lambda j: float(j.sp["tau_p"]))
        tp = [float(j.sp["tau_p"]) for j in reps]
        td = [j.scalar("tau_d") for j in reps]
        ax.plot(tp, td, "o-", label=state({"phi_c": "%g" % phi_c}))
        for j, t, d in zip(reps, tp, td):
            window = j.scalar("correlation_window")
            n_windows = (j.scalar("steps") - j.scalar("equilibrate_steps")) * float(
                j.sp.get("dt", 0.05)) / window if verdict.finite(window) and window > 0 else math.nan
            table.append({"phi_c": float(phi_c), "tau_p": t, "tau_d": d,
                          "tau_d_free": j.scalar("tau_d_free"),
                          "windows": n_windows})
    free = sorted({(r["tau_p"], r["tau_d_free"]) for r in table})
    ax.plot([f[0] for f in free], [f[1] for f in free], "k--", lw=1, label="free particle (exact)")
    tau_g = sorted({j.scalar("tau_g") for j in jobs if verdict.finite(j.scalar("tau_g"))})
    for t in tau_g:  # the paper's horizontal line tau_d = tau_g (Fig. 6(b))
        ax.axhline(t, color="0.5", ls=":", lw=1, label=r"$\tau_d = \tau_\gamma$" if t == tau_g[0] else None)
    log_axis(ax, [r["tau_p"] for r in table], "x")
    log_if_spans(ax, [r["tau_d"] for r in table] + [f[1] for f in free], "y", 1.0)
    ax.set_xlabel(label("tau_p", "tau"))
    ax.set_ylabel(label("tau_d", "tau"))
    ax.legend(fontsize=8)
    images = [save(fig, out, "fig6_tau_d.png")]

    def tol(r):  # statistical precision of a tau_d from n windows, at least the paper's 10 %
        return max(0.1, 1 / math.sqrt(r["windows"])) if verdict.finite(r["windows"]) and r["windows"] > 0 else 0.1

    rows = _fig6_rows(table, tol)
    return {"images": images, "rows": rows, "numbers": {"points": table}, "steadiness": None}


def _fig6_rows(table, tol):
    """The rows of Fig. 6, each over every phi_c (the paper: tau_d -> tau_g as tau_p -> 0 for
    all phi_c; the free formula at small and intermediate tau_p; deviations at large tau_p
    growing with phi_c). tol(point): a ratio's tolerance."""
    rows = []
    phis = sorted({r["phi_c"] for r in table})
    ratio = {id(r): r["tau_d"] / r["tau_d_free"] for r in table}
    small = [min((r for r in table if r["phi_c"] == phi), key=lambda r: r["tau_p"]) for phi in phis]
    each = [verdict.value_verdict(ratio[id(r)], 0.0, 1.0, tol(r)) for r in small]
    rows.append(verdict.row(
        "fig6_small_tau_p", "tau_d/tau_d_free at the smallest tau_p: " + ", ".join(
            "%s (phi_c = %g, tau_p = %g)" % (verdict.fmt(ratio[id(r)]), r["phi_c"], r["tau_p"])
            for r in small), verdict.all_of(each),
        "at every phi_c, |ratio - 1| <= max(0.1, 1/sqrt(windows)) at the smallest tau_p"))
    tau_g = min(small, key=lambda r: r["tau_p"])["tau_d_free"] if small else math.nan
    free = [r for r in table if r["phi_c"] == 0.0 or r["tau_p"] <= INTERMEDIATE * tau_g]
    each = [verdict.value_verdict(ratio[id(r)], 0.0, 1.0, tol(r)) for r in free]
    worst = max(free, key=lambda r: abs(ratio[id(r)] - 1)) if free else None
    rows.append(verdict.row(
        "fig6_free_formula", "%d of %d points within; per phi_c the largest deviation: %s" % (
            each.count(verdict.AGREES), len(free), ", ".join(
                "tau_d/tau_d_free = %s (phi_c = %g, tau_p = %g)" % (
                    verdict.fmt(ratio[id(w)]), w["phi_c"], w["tau_p"]) for w in (
                    max((r for r in free if r["phi_c"] == phi), key=lambda r: abs(ratio[id(r)] - 1))
                    for phi in phis if any(r["phi_c"] == phi for r in free)))) if worst else "n/a",
        verdict.all_of(each),
        "each point |ratio - 1| <= max(0.1, 1/sqrt(windows)); rests on every phi_c at tau_p <= "
        "%g tau_g = %.3g (small and intermediate tau_p), and on phi_c = 0 at every tau_p"
        % (INTERMEDIATE, INTERMEDIATE * tau_g)))
    dense = [max((r for r in table if r["phi_c"] == phi), key=lambda r: r["tau_p"])
             for phi in phis if phi > 0]
    if dense:
        devs = [1 - ratio[id(r)] for r in dense]
        each = [verdict.trend_verdict(d, tol(r) / 2) for d, r in zip(devs, dense)]
        grows = all(b > a for a, b in zip(devs, devs[1:]))
        v = verdict.all_of(each)
        if v == verdict.AGREES and not grows:
            v = verdict.TREND
        rows.append(verdict.row(
            "fig6_dense_deviates", "1 - tau_d/tau_d_free at the largest tau_p: " + ", ".join(
                "%s (phi_c = %g, tau_p = %g)" % (verdict.fmt(d), r["phi_c"], r["tau_p"])
                for d, r in zip(devs, dense)) + ("; grows with phi_c" if grows else
                                                 "; does not grow with phi_c"),
            v, "at every phi_c > 0, 1 - ratio > 2 x half the tolerance max(0.1, "
            "1/sqrt(windows)), and growing with phi_c (else trend only)"))
    return rows


BOX_NAMES = {"pressure": "pressure wall at P", "fixed": "fixed box"}


def _box(job):
    """The packing scan's box after the rescale (packing.lua's `box`; runs from before the
    parameter existed ran under the pressure wall)."""
    return job.sp.get("box", "pressure")


def fig8(jobs, out, invasim):
    """The packing scan, one figure and one set of verdict rows per box (packing.lua's `box`:
    the pressure wall of docs/model.md protocol step 6, and the fixed box of the paper's text read
    literally), each normalised over its own scan (the paper's Appendix C per sweep)."""
    images, rows, numbers = [], [], {}
    boxes = sorted({_box(j) for j in jobs}, key=lambda b: (b != "pressure", b))
    for box in boxes:
        scan = [j for j in jobs if _box(j) == box]
        suffix = "" if box == "pressure" else "_" + box
        im, r, num = _fig8_scan(scan, out, box, "fig8_An_dphi%s.png" % suffix,
                                 variant=None if len(boxes) == 1 else BOX_NAMES.get(box, box))
        images += im
        rows += r
        numbers[box] = num
    return {"images": images, "rows": rows, "numbers": numbers,
            "steadiness": steady.steadiness_summary(jobs)}


def _fig8_scan(jobs, out, box, image, variant):
    """One box's scan: its state points (replicate means), normalised over the scan, its
    figure and its verdict rows."""
    pts = []
    for (lam, phi_a), reps in workspace.group(jobs, ["lambda", "phi_a"]).items():
        p = points.state_point(reps, lambda j: {
            "phi_a_measured": j.mean("phi_a")[0], "A_t": j.mean("A_t")[0],
            "A_t_max": j.mean("A_t_max")[0], "A_t_error": j.mean("A_t")[1],
            "phi_a_local_mean": j.mean("phi_a_local_mean")[0],
            "P_right": j.mean("P_right")[0], "T_c": j.mean("T_c")[0],
            "P": float(j.sp.get("P", math.nan)),
            "dphi": j.mean("phi_a_local_std")[0], "dphi_error": j.mean("phi_a_local_std")[1]})
        p["lambda"], p["phi_a_target"] = float(lam), float(phi_a)
        pts.append(p)
    for lam in {p["lambda"] for p in pts}:
        for name in ("A_gap", "dphi"):
            points.pooled_errors([p for p in pts if p["lambda"] == lam], name, "phi_a_target")
    extremes = normalise.normalise(pts)
    by_lambda = {lam: sorted((p for p in pts if p["lambda"] == lam),
                             key=lambda p: p["phi_a_measured"])
                 for lam in sorted({p["lambda"] for p in pts})}
    images = [_fig8_plot(by_lambda, box, out, image)]
    rows = _fig8_rows(pts, by_lambda, box, variant, {j.id: j for j in jobs})
    return images, rows, {"points": pts, "normalisation": extremes}


def _fig8_plot(by_lambda, box, out, image):
    """A_n, Delta phi_a and the raw A_t (with A_t^max) against the measured phi_a, one curve
    per lambda; returns the image's name."""
    fig, axes = figure(3, width=4.4)
    for lam, c in by_lambda.items():
        name = state({"lambda": "%g" % lam})
        axes[0].errorbar([p["phi_a_measured"] for p in c], [p["A_n"] for p in c],
                         yerr=[p["A_n_error"] if verdict.finite(p["A_n_error"]) else 0 for p in c],
                         marker="o", capsize=2, label=name)
        axes[1].errorbar([p["phi_a_measured"] for p in c], [p["dphi"] for p in c],
                         yerr=[p["dphi_error"] if verdict.finite(p["dphi_error"]) else 0 for p in c],
                         marker="s", capsize=2, label=name)
        line = axes[2].errorbar([p["phi_a_measured"] for p in c], [p["A_t"] for p in c],
                                yerr=[p["A_t_error"] if verdict.finite(p["A_t_error"]) else 0
                                      for p in c], marker="o", capsize=2, label=name)
        axes[2].plot([p["phi_a_measured"] for p in c], [p["A_t_max"] for p in c], ls="--",
                     color=line[0].get_color())
    measured = r"measured $\phi_a$ (dimensionless)"
    # Raw A_t beside A_t^max (dashed): A_n normalises by the smallest A_t^max of the scan,
    # which in a scan over box sizes (the fixed box) is the densest point's.
    axes[2].set_xlabel(measured)
    axes[2].set_ylabel(r"$A_t$ (solid), $A_t^\mathrm{max}$ (dashed) [$\sigma^2$]")
    axes[0].set_xlabel(measured)
    axes[0].set_ylabel(label("A_n", ""))
    axes[1].set_xlabel(measured)
    axes[1].set_ylabel(r"$\Delta\phi_a$, std of the local $\phi_a$ (dimensionless)")
    axes[0].legend(fontsize=8, title=BOX_NAMES.get(box, box), title_fontsize=8)
    return save(fig, out, image)


def difference_mean(pairs, dofs=None):
    """The mean of the differences base - other and its error, for pairs [(base key, base,
    base error, other, other error)] (a missing error counts as 0; a pair whose difference is
    not finite is left out). The mean is a linear combination of the state points' values:
    each other point enters with -1/n, a base point shared by m differences with m/n, so its
    error counts once with that summed weight, sqrt(sum c_i^2 e_i^2); summing the pairs'
    errors as if independent would count it m times with weight 1/n. dofs: per pair the
    degrees of freedom of (base error, other error), None for many. Returns (mean, error, n,
    dof: the error's Welch-Satterthwaite degrees of freedom, student.welch_dof), nan with
    n = 0 when no pair is finite."""
    dofs = dofs or [(None, None)] * len(pairs)
    kept = [(p, d) for p, d in zip(pairs, dofs) if verdict.finite(p[1] - p[3])]
    n = len(kept)
    if not n:
        return math.nan, math.nan, 0, None
    base = {}  # base key -> (the number of differences it is in, its error, its dof)
    for (key, _, e0, _, _), (d0, _) in kept:
        base[key] = (base.get(key, (0,))[0] + 1, e0 if verdict.finite(e0) else 0.0, d0)
    terms = [(m * e0 / n, d0) for m, e0, d0 in base.values()]
    terms += [(e / n, d) for (_, _, _, _, e), (_, d) in kept if verdict.finite(e)]
    error = math.sqrt(sum(v * v for v, _ in terms))
    mean = float(np.mean([b - a for (_, b, _, a, _), _ in kept]))
    return mean, error, n, student.welch_dof(terms)


def _step_error(a, b, name):
    """The error of b[name] - a[name] for two state points, and its degrees of freedom
    (student.welch_dof; a missing error counts as 0)."""
    terms = [(p[name + "_error"] if verdict.finite(p[name + "_error"]) else 0.0,
              p.get(name + "_dof")) for p in (a, b)]
    return math.hypot(*(v for v, _ in terms)), student.welch_dof(terms)


def _fig8_rows(pts, by_lambda, box, variant, jobs_by_id):
    """The verdict rows of one box's scan (variant: the box's name when both are shown). Each
    row rests on the state points it names (`on`): not steady if one of them is not."""
    rows = []

    def add(sid, ours, v, why, on=(), data=None):
        unsteady = steady.unsteady_points(list(on), jobs_by_id, lambda p: "lambda = %g, phi_a = %g"
                                        % (p["lambda"], p["phi_a_target"]))
        r = verdict.row(sid, ours, v, why + ("; rests on the state points it names, each steady"
                                             if on else ""), data=data, unsteady=unsteady)
        if variant:
            r["variant"] = variant
        rows.append(r)

    drift = ("the pressure wall lets the tissue move away from the target, so the measured "
             "phi_a is shown" if box == "pressure" else
             "the box keeps the rescaled size, so phi_a stays at the target")
    dense = [p for p in pts if p["phi_a_target"] >= 0.85 - 1e-9]
    s0 = verdict.paper()["fig8_zero_above"]
    if dense:
        m = max(dense, key=lambda p: p["A_n"])
        raw = [p for p in pts if verdict.finite(p["A_t"])]
        lo = min(raw, key=lambda p: p["phi_a_measured"]) if raw else m
        add("fig8_zero_above", "largest A_n at target phi_a >= 0.85: %s "
            "(target %.3g, measured %.3g, lambda = %g; there A_t = %.0f of A_t^max = %.0f, "
            "wall pressure %.2g = %.0f P, %s; at the scan's lowest phi_a %.3g: "
            "A_t = %.0f of %.0f, lambda = %g)" % (
                verdict.fmt(m["A_n"], m["A_n_error"]), m["phi_a_target"],
                m["phi_a_measured"], m["lambda"], m["A_t"], m["A_t_max"], m["P_right"],
                m["P_right"] / m["P"], verdict.fmt_temperature(2 * m["T_c"] / m["P"]),
                lo["phi_a_measured"], lo["A_t"],
                lo["A_t_max"], lo["lambda"]),
            verdict.value_verdict(m["A_n"], m["A_n_error"], 0.0, s0["tolerance"],
                                  dof=m.get("A_n_dof")),
            "A_n <= 0.1 + 2 errors; " + drift + ("" if box == "pressure" else
            "; A_n is normalised with the scan's smallest A_t^max (Appendix C), i.e. the "
            "densest box's, so where A_t^max shrinks with the box faster than A_t, A_n rises "
            "though A_t falls (third panel)"), on=[m])
    else:
        add("fig8_zero_above", "no point with a target phi_a >= 0.85",
            verdict.NO_DATA, "needs a target phi_a >= 0.85")
    lams = sorted(by_lambda)
    if len(lams) >= 2:
        # Pointwise: A_n(lambda = lowest) - A_n(lambda) at the same target phi_a (the scan's
        # state point), for every larger lambda; combined as the mean with its error.
        base = {p["phi_a_target"]: p for p in by_lambda[lams[0]]}
        pairs = [(lam, base[p["phi_a_target"]], p) for lam in lams[1:] for p in by_lambda[lam]
                 if p["phi_a_target"] in base]
        mean, err, n, dof = difference_mean(
            [(q0["phi_a_target"], q0["A_n"], q0["A_n_error"], q["A_n"], q["A_n_error"])
             for _, q0, q in pairs], [(q0.get("A_n_dof"), q.get("A_n_dof")) for _, q0, q in pairs])
        add("fig8_lambda_lowers", "A_n(lambda = %g) - A_n(lambda) at the same phi_a: %s; mean %s"
            % (lams[0], ", ".join("%s (lambda = %g, phi_a = %g)" % (
                verdict.fmt(q0["A_n"] - q["A_n"]), lam, q["phi_a_target"])
                for lam, q0, q in pairs) or "no shared phi_a", verdict.fmt(mean, err)),
            verdict.trend_verdict(mean, err, dof) if n else verdict.NO_DATA,
            "pointwise at each target phi_a shared by lambda = %g and a larger lambda, then "
            "the mean of the differences > 2 errors, its error that of the mean as a sum over "
            "the state points, each lambda = %g point once with the weight of all the "
            "differences it is in" % (lams[0], lams[0]),
            on=list({id(q): q for _, q0, q in pairs for q in (q0, q)}.values()),
            data={"mean": mean, "error": err, "differences": n, "dof": dof})
        tops = [(lam, max(by_lambda[lam], key=lambda p: p["dphi"])) for lam in lams]
        steps = [(b[1]["dphi"] - a[1]["dphi"], *_step_error(a[1], b[1], "dphi"))
                 for a, b in zip(tops, tops[1:])]
        add("fig8_dphi_grows", "max Delta phi_a = " + " -> ".join(
            "%s (lambda = %g)" % (verdict.fmt(t["dphi"], t["dphi_error"]), lam) for lam, t in tops),
            verdict.all_of([verdict.trend_verdict(d, e, dof) for d, e, dof in steps]),
            "each step in lambda raises max Delta phi_a by > 2 errors (trend only: every step "
            "positive)", on=[t for _, t in tops])
    for sid in ("fig8_dphi_0", "fig8_dphi_0.3", "fig8_dphi_1"):
        s = verdict.paper()[sid]
        c = by_lambda.get(s["lambda"])
        if not c:
            add(sid, "n/a (no lambda = %g)" % s["lambda"], verdict.NO_DATA, "")
            continue
        m = max(c, key=lambda p: p["dphi"])
        add(sid, "max Delta phi_a = %s (at phi_a = %.3g)" % (
            verdict.fmt(m["dphi"], m["dphi_error"]), m["phi_a_measured"]),
            verdict.value_verdict(m["dphi"], m["dphi_error"], s["value"], s["tolerance"],
                                  dof=m.get("dphi_dof")),
            "|ours - %g| <= %g + 2 errors" % (s["value"], s["tolerance"]), on=[m])
    return rows


def read_shapes(job):
    with open(os.path.join(job.path, "shapes.csv")) as f:
        r = list(csv.DictReader(f))
    lo = np.array([float(x["A2_lo"]) for x in r])
    hi = np.array([float(x["A2_hi"]) for x in r])
    return lo, hi, np.array([float(x["count"]) for x in r])


def fig9(jobs, out, invasim):
    fig, (ax,) = figure()
    means = []
    stat = "median"
    for (a0,), reps in workspace.group(jobs, ["A_0"]).items():
        lo, hi, count = read_shapes(reps[0])
        for j in reps[1:]:
            count = count + read_shapes(j)[2]
        width = hi - lo
        density = count / max(count.sum(), 1) / width
        ax.step(lo, density, where="post", label=state({"A_0": "%g" % a0}))
        # The median per run (robust to the sliver profiles of wrinkled bodies, see
        # docs/measurements_dynamics.md); runs from before it was written give their mean.
        m = [j.scalar("shape_2d_median") if verdict.finite(j.scalar("shape_2d_median"))
             else j.scalar("shape_2d_mean") for j in reps]
        if not all(verdict.finite(j.scalar("shape_2d_median")) for j in reps):
            stat = "mean"
        means.append((float(a0), float(np.mean(m)),
                      float(np.std(m, ddof=1) / math.sqrt(len(m))) if len(m) > 1 else math.nan,
                      int(count.sum())))
    ax.set_xlabel(r"slice shape parameter $A_\mathrm{2D} = p^2/(4\pi s)$ (dimensionless)")
    ax.set_ylabel(r"$P(A_\mathrm{2D})$ (dimensionless)")
    ax.set_xlim(1.0, 1.6)
    ax.legend(fontsize=8)
    images = [save(fig, out, "fig9_P_A2D.png")]
    means.sort()
    rows = [verdict.row("fig9_tissue", stat + " A_2D = " + ", ".join(
        "%s (A_0 = %g, %d slices)" % (verdict.fmt(m, e), a, n) for a, m, e, n in means),
        verdict.UNTESTABLE, "the paper's tissue slice data are not available to us")]
    if len(means) >= 2:
        d = means[-1][1] - means[0][1]
        e = math.hypot(*(x if verdict.finite(x) else 0 for x in (means[-1][2], means[0][2])))
        rows.append(verdict.row("fig9_shift", stat + " A_2D %s (A_0 = %g) -> %s (A_0 = %g)" % (
            verdict.fmt(means[0][1]), means[0][0], verdict.fmt(means[-1][1]), means[-1][0]),
            verdict.trend_verdict(d, e), "difference > 2 errors (replicate scatter)"))
    return {"images": images, "rows": rows, "numbers": {"means": means},
            "steadiness": steady.steadiness_summary(jobs)}
