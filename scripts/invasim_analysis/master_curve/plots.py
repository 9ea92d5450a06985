"""The figures of the master-curve analysis (PNG, matplotlib's Agg backend): A_n against
k_B T/(P sigma^3) per curve with its fit, the collapse on E_c^b, a against tau_g/tau_d.
Legends name the curves by their state-point keys' symbols (plot_labels.py); the
labels drawn are recorded in figure_labels.json."""

import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .. import atomic  # noqa: E402
from ..plot_labels import state_label, unit_text  # noqa: E402

from .fits import sigmoid  # noqa: E402

MARKERS = "osD^vP*Xph<>"
NONE = unit_text("")  # "(dimensionless)": every axis of these figures is a pure number
A_N_LABEL = r"$A_n$, normalised interfacial area " + NONE


def _name(c):
    """A curve's legend name: "$\\beta$ = 0.01, $\\tau_p$ = 25" (its group keys)."""
    return state_label(c.get("group") or {})


def _record(fig):
    """The labels a figure shows, per panel (figure_labels.json)."""
    out = []
    for ax in fig.axes:
        legend = ax.get_legend()
        out.append({"xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
                    "xscale": ax.get_xscale(), "yscale": ax.get_yscale(),
                    "legend": [t.get_text() for t in legend.get_texts()] if legend else []})
    return {"title": fig._suptitle.get_text() if fig._suptitle else "", "axes": out}


def _style(k):
    return {"color": plt.cm.tab10(k % 10), "marker": MARKERS[(k // 10 + k) % len(MARKERS)]}


def _points(c):
    ps = sorted(c["points"], key=lambda p: p["x"])
    return (np.array([p["x"] for p in ps]), np.array([p["A_n"] for p in ps]),
            np.array([p["A_n_error"] for p in ps]))


def _unsteady_jobs(result, name):
    """x and A_n of the jobs of curve `name` that are not steady (drawn hollow, not fitted)."""
    idx = [i for i, why in enumerate(result["unsteady"])
           if why and result["curve_of"][i] == name]
    return result["x"][idx], result["A_n"][idx]


def curves_figure(path, result, x_label):
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    hollow = False
    for k, c in enumerate(result["curves"]):
        st = _style(k)
        x, y, e = _points(c)
        label = ("%s: not a fit" % _name(c) if c["not_a_fit"]
                 else "%s: $a$ = %.3g, $b$ = %.2f" % (_name(c), c["a"], c["b"]))
        ax.errorbar(x, y, yerr=e, ls="none", capsize=2, ms=5, color=st["color"],
                    marker=st["marker"], label=label)
        ux, uy = _unsteady_jobs(result, c["name"])
        if len(ux):
            hollow = True
            ax.plot(ux, uy, ls="none", ms=5, mfc="none", color=st["color"], marker=st["marker"])
        if c["not_a_fit"]:
            continue
        span = np.concatenate([x, ux])
        xs = np.logspace(np.log10(span.min()) - 0.2, np.log10(span.max()) + 0.2, 200)
        lo, hi = c["plateaus"]  # the fitted plateaus (plateaus.py), in A_n
        ax.plot(xs, lo + (hi - lo) * sigmoid(xs, c["a"], c["b"]), color=st["color"], lw=1.2)
    if hollow:
        ax.plot([], [], ls="none", marker="o", mfc="none", color="0.4",
                label="hollow: single jobs not steady (not fitted)")
    ax.set_xscale("log")
    ax.set_xlabel(x_label + " " + NONE)
    ax.set_ylabel(A_N_LABEL)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    atomic.save_figure(fig, path, dpi=120)
    labels = _record(fig)
    plt.close(fig)
    return labels


def collapse_figure(path, curves):
    """A_n against E_c^b of the curves that are fits (a curve that is not a fit has no E_c)."""
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    lo, hi = np.inf, -np.inf
    for k, c in enumerate(curves):
        if c["not_a_fit"]:
            continue
        st = _style(k)
        x, y, e = _points(c)
        lo, hi = c["plateaus"]  # A_n rescaled to the curve's fitted plateaus (plateaus.py)
        y, e = (y - lo) / (hi - lo), e / (hi - lo)
        ecb = (x / c["a"]) ** c["b"]
        lo, hi = min(lo, ecb.min()), max(hi, ecb.max())
        ax.errorbar(ecb, y, yerr=e, ls="none", capsize=2, ms=5, label=_name(c), **st)
    if not np.isfinite(lo):  # no curve is a fit: the reference curve alone, around E_c = 1
        lo, hi = 0.01, 100.0
    xs = np.logspace(np.log10(lo) - 0.2, np.log10(hi) + 0.2, 200)
    ax.plot(xs, sigmoid(xs, 1.0, 1.0), color="k", lw=1.2,  # the collapse: a = b = 1
            label=r"$(\tanh[\log_{10} E_c^b] + 1)/2$")
    ax.set_xscale("log")
    ax.set_xlabel(r"$E_c^b$, $E_c = k_B T/(a P \sigma^3)$ ($a$, $b$ fitted per curve) " + NONE)
    ax.set_ylabel(r"$(A_n - L)/(H - L)$, $L$, $H$: fitted plateaus " + NONE)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    atomic.save_figure(fig, path, dpi=120)
    labels = _record(fig)
    plt.close(fig)
    return labels


def scale_figure(path, curves, scale):
    """Left: a against tau_g/tau_d with the fitted line of each beta/P. Right: a against the
    fitted c1 (1 + c2 beta/P) tau_g/tau_d with the line a = that (the paper's Fig. 5b inset)."""
    used = [(k, c) for k, c in enumerate(curves) if c["name"] in scale["curves"]]
    c2 = scale["c2"] or 0.0
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.5, 4.6))
    for k, c in used:
        st = _style(k)
        model = scale["c1"] * (1 + c2 * c["q"]) * c["tau_g_over_tau_d"]
        for axis, x in ((ax, c["tau_g_over_tau_d"]), (bx, model)):
            axis.errorbar(x, c["a"], yerr=c["a_sigma_in_scale_fit"], ls="none", capsize=2,
                          ms=6, label=_name(c), **st)
    r = np.array([c["tau_g_over_tau_d"] for _, c in used])
    rs = np.logspace(np.log10(r.min()) - 0.3, np.log10(r.max()) + 0.3, 50)
    for n, q in enumerate(sorted({c["q"] for _, c in used})):
        ax.plot(rs, scale["c1"] * (1 + c2 * q) * rs, color="k", lw=1,
                ls=("-", "--", ":", "-.")[n % 4], label=r"fit, $\beta/(P\sigma^3)$ = %.3g" % q)
    lim = scale["c1"] * (1 + c2 * max(c["q"] for _, c in used)) * rs[[0, -1]]
    lim[0] = scale["c1"] * rs[0]
    bx.plot(lim, lim, color="k", lw=1, label="$a$ = fit")
    title = (r"$a = c_1(1 + c_2\beta\epsilon_c/(P\sigma^3))\,\tau_\gamma/\tau_d$: "
             r"$c_1$ = %.3g $\pm$ %.2g" % (scale["c1"], scale["c1_error"]))
    if scale["c2"] is not None:
        title += r", $c_2$ = %.3g $\pm$ %.2g" % (scale["c2"], scale["c2_error"])
    fig.suptitle(title, fontsize=9)
    for axis in (ax, bx):
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_ylabel(r"$a$, fitted scale of $k_B T/(P\sigma^3)$ " + NONE)
        axis.legend(fontsize=7, loc="best")
    ax.set_xlabel(r"$\tau_\gamma/\tau_d$ ($\tau_\gamma = m/\gamma$) " + NONE)
    bx.set_xlabel(r"$c_1(1 + c_2\beta\epsilon_c/(P\sigma^3))\,\tau_\gamma/\tau_d$ (fitted) " + NONE)
    fig.tight_layout()
    atomic.save_figure(fig, path, dpi=120)
    labels = _record(fig)
    plt.close(fig)
    return labels


def write_figures(out_dir, result, x_label):
    """Writes An_vs_T.png, collapse.png, (if the fit of a was done) a_vs_tau.png and
    figure_labels.json (figure -> its title and its panels' labels and scales)."""
    paths = {"An_vs_T.png": os.path.join(out_dir, "An_vs_T.png"),
             "collapse.png": os.path.join(out_dir, "collapse.png")}
    labels = {"An_vs_T.png": curves_figure(paths["An_vs_T.png"], result, x_label),
              "collapse.png": collapse_figure(paths["collapse.png"], result["curves"])}
    if result["scale_fit"]["done"]:
        paths["a_vs_tau.png"] = os.path.join(out_dir, "a_vs_tau.png")
        labels["a_vs_tau.png"] = scale_figure(paths["a_vs_tau.png"], result["curves"],
                                              result["scale_fit"])
    paths["figure_labels.json"] = os.path.join(out_dir, "figure_labels.json")
    with atomic.open_text(paths["figure_labels.json"]) as f:
        json.dump(labels, f, indent=1, ensure_ascii=False, sort_keys=True)
        f.write("\n")
    return paths
