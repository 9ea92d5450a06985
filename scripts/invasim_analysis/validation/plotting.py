"""Figure helpers of the validation figures: one matplotlib style, labels from
invasim_analysis/plot_labels.py (no raw column names), log axes where a quantity spans decades."""

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .. import atomic, plot_labels

# The one temperature axis of every figure: the measured cancer-cell temperature in the
# paper's convention (its Eq. (14): twice the equipartition T_c), for passive runs too.
T_PAPER = r"$k_B T/(P\sigma^3) = 2 k_B T_c/(P\sigma^3)$ (measured, paper's convention)"


def figure(ncols=1, width=5.2):
    fig, axes = plt.subplots(1, ncols, figsize=(width * ncols, 3.9), squeeze=False)
    return fig, list(axes[0])


def log_if_spans(ax, values, axis="x", decades=1.5):
    """A log scale on `axis` where the positive values span more than `decades`."""
    import numpy as np
    v = np.asarray([x for x in values if x > 0], float)
    if len(v) >= 2 and np.log10(v.max() / v.min()) > decades:
        (ax.set_xscale if axis == "x" else ax.set_yscale)("log")


def log_axis(ax, values, axis="x"):
    """A log scale on `axis` with plain-number labels ("0.03", not "3 x 10^-2"): ticks at
    1, 2, 5 x 10^k when the values span less than two decades, else at the decades, and no
    labels on the minor ticks (which crowd a narrow log axis)."""
    import numpy as np
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter
    v = np.asarray([x for x in values if x > 0], float)
    narrow = len(v) < 2 or np.log10(v.max() / v.min()) < 2
    (ax.set_xscale if axis == "x" else ax.set_yscale)("log")
    a = ax.xaxis if axis == "x" else ax.yaxis
    a.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0) if narrow else (1.0,)))
    a.set_major_formatter(FormatStrFormatter("%g"))
    a.set_minor_formatter(NullFormatter())


def save(fig, out_dir, name, rect=None):
    """Writes the figure atomically (rect: the part of the figure tight_layout fills, leaving room for a
    legend outside the axes)."""
    path = os.path.join(out_dir, name)
    fig.tight_layout(rect=rect)
    atomic.save_figure(fig, path, dpi=110)
    plt.close(fig)
    return name


def label(name, unit=""):
    return plot_labels.axis_label(plot_labels.label(name), unit)


def state(pairs):
    return plot_labels.state_label(pairs)
