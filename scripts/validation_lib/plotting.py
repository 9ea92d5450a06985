"""Figure helpers of the validation figures: one matplotlib style, labels from
scripts/plot_labels.py (no raw column names), log axes where a quantity spans decades."""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import plot_labels  # noqa: E402

T_PAPER = r"$2 k_B T_c/(P\sigma^3)$ (measured, the paper's convention)"
T_BATH = r"$k_B T/(P\sigma^3)$ (bath)"


def figure(ncols=1, width=5.2):
    fig, axes = plt.subplots(1, ncols, figsize=(width * ncols, 3.9), squeeze=False)
    return fig, list(axes[0])


def log_if_spans(ax, values, axis="x", decades=1.5):
    """A log scale on `axis` where the positive values span more than `decades`."""
    import numpy as np
    v = np.asarray([x for x in values if x > 0], float)
    if len(v) >= 2 and np.log10(v.max() / v.min()) > decades:
        (ax.set_xscale if axis == "x" else ax.set_yscale)("log")


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return name


def label(name, unit=""):
    return plot_labels.axis_label(plot_labels.label(name), unit)


def state(pairs):
    return plot_labels.state_label(pairs)
