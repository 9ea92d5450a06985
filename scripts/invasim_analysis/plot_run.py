"""Plots the time series of an invasim run directory.

Usage: plot_run.py RUN_DIR

Reads RUN_DIR/series.csv (a header row of `name [unit]` or `name` entries, then one row of
numbers per sample) and writes PNG plots into RUN_DIR/plots/, one per group of columns that is
present: A_t.png (A_t, A_t_max, A_wall_a and, below, A_ratio = A_t/A_t^max),
temperature.png (T_c, T_a, on a log scale when they span a decade or more, and T_c/T_a
below), pressure.png (P_left, P_right), box_length.png (L_x), packing.png (phi, phi_c,
phi_a and, on its own axis below, the standard deviation phi_a_local_std), growth.png (the
number of cancer cells N_c, the adipocytes' mean reference volume V0_ratio and N_touched, of
proliferation and lipolysis runs). Missing columns
are skipped. The horizontal axis is `time` if present, else `step`. Every axis carries its
unit and every legend entry a human label from plot_labels.py; the labels drawn are
recorded in RUN_DIR/plots/labels.json (figure -> axes -> x/y label, y scale, legend).

Needs numpy and matplotlib (Debian 12: apt-get install python3-numpy python3-matplotlib). If
the python3 running this script lacks them, it re-runs itself with /usr/bin/python3.
Exit status: 0 on success, 1 on an error (unreadable or malformed series.csv, missing
modules), 2 on a bad command line.
"""

import argparse
import math
import os
import sys

from . import atomic, csv_header, plot_labels  # plot_labels: the figures' label table
from .deps import ensure_modules

NO_REEXEC = "INVASIM_PLOT_NO_REEXEC"  # set when re-executed, so it happens at most once

# Plot groups: output file, then its panels from top to bottom as (columns in legend order,
# what the axis shows). A panel's columns share the unit of the first.
GROUPS = [
    ("temperature.png", [(["T_c", "T_a"], "temperature"),
                         (["T_c_over_T_a"], plot_labels.symbol("T_c_over_T_a"))]),
    ("pressure.png", [(["P_left", "P_right"], "pressure on the walls")]),
    ("box_length.png", [(["L_x"], "box length " + plot_labels.symbol("L_x"))]),
    ("packing.png", [(["phi", "phi_c", "phi_a", "phi_a_local_mean"], "packing fraction"),
                     (["phi_a_local_std"], plot_labels.symbol("phi_a_local_std")
                      + r", std of the local $\phi_a$")]),
    ("growth.png", [(["N_c"], "number of cancer cells"),
                    (["V0_ratio"], plot_labels.symbol("V0_ratio") + ", adipocyte volume"),
                    (["N_touched"], "adipocytes touched by cancer cells")]),
]


class SeriesError(Exception):
    """A series.csv that cannot be read or is malformed (the message names file and line)."""


def fail(message, status=1):
    print("plot_run.py: " + message, file=sys.stderr)
    sys.exit(status)


def import_plotting():
    """Returns (numpy, pyplot) with the Agg backend. If a module is missing, re-runs the script
    with /usr/bin/python3 when that is another interpreter, else exits naming the packages."""
    ensure_modules("plot_run.py", ("numpy", "matplotlib"), NO_REEXEC)
    import numpy
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot

    return numpy, pyplot


def read_series(path):
    """Returns (names, units, columns): column name -> list of floats (empty field: nan)."""
    rows = csv_header.read_rows(path, SeriesError)
    names, units = [], {}
    for k, entry in enumerate(rows[0]):
        parsed = csv_header.header_entry(entry)
        if parsed is None:
            raise SeriesError("%s: line 1, column %d: bad header entry '%s' (expected "
                              "'name [unit]' or 'name')" % (path, k + 1, entry))
        if parsed[0] in units:
            raise SeriesError("%s: line 1: column '%s' appears twice" % (path, parsed[0]))
        names.append(parsed[0])
        units[parsed[0]] = parsed[1]
    columns = {n: [] for n in names}
    data = [(i + 2, r) for i, r in enumerate(rows[1:]) if any(field.strip() for field in r)]
    for index, (line, row) in enumerate(data):
        if len(row) != len(names):
            if index == len(data) - 1 and len(row) < len(names):
                # A run killed while writing its last row: keep every complete row.
                print("plot_run.py: %s: line %d is incomplete (%d of %d fields), ignored"
                      % (path, line, len(row), len(names)), file=sys.stderr)
                break
            raise SeriesError("%s: line %d has %d fields, the header has %d"
                              % (path, line, len(row), len(names)))
        for name, field in zip(names, row):
            text = field.strip()
            try:
                value = float(text) if text else math.nan
            except ValueError:
                raise SeriesError("%s: line %d, column '%s': '%s' is not a number"
                                  % (path, line, name, field))
            columns[name].append(value)
    if not columns[names[0]]:
        raise SeriesError("%s has a header but no data rows" % path)
    return names, units, columns


def axis_label(text, unit):
    return plot_labels.axis_label(text, unit)


def save(figure, path):
    """Writes the figure as PNG atomically (atomic.py)."""
    atomic.save_figure(figure, path, format="png", dpi=120)


def spans_decades(np, arrays):
    """Whether positive data spanning a factor 10 or more (e.g. T_a next to T_c) calls for a
    log scale; never for data with zeros or negative values."""
    values = np.concatenate([np.asarray(a, float) for a in arrays])
    values = values[np.isfinite(values)]
    return values.size > 0 and values.min() > 0 and values.max() >= 10.0 * values.min()


def record(axes_list):
    """The labels a figure shows, per panel (for labels.json and its test)."""
    out = []
    for ax in axes_list:
        handles, legend = ax.get_legend_handles_labels()
        out.append({"xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
                    "yscale": ax.get_yscale(), "legend": legend if ax.get_legend() else []})
    return out


def plot_panels(np, plt, x, x_label, panels, units, columns, path):
    """One PNG with a panel per (columns, axis text) against x; returns its labels."""
    figure, axes = plt.subplots(len(panels), 1, figsize=(6.4, 3.0 * len(panels) + 1.0),
                                sharex=True, squeeze=False, constrained_layout=True)
    axes = axes[:, 0]
    for ax, (names, text) in zip(axes, panels):
        data = [np.asarray(columns[n]) for n in names]
        for name, y in zip(names, data):
            ax.plot(x, y, label=plot_labels.label(name))
        if spans_decades(np, data):
            ax.set_yscale("log")
        ax.set_ylabel(axis_label(text, units[names[0]]))
        if len(names) > 1:
            ax.legend()
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(x_label)
    save(figure, path)
    labels = record(axes)
    plt.close(figure)
    return labels


def plot_interface(np, plt, x, x_label, units, columns, path):
    """A_t.png: A_t, A_t_max and A_wall_a on top; A_t/A_t^max below when known. Returns the
    columns shown (A_ratio computed from A_t and A_t_max if the file has no A_ratio column)
    and the labels drawn."""
    areas = [n for n in ("A_t", "A_t_max", "A_wall_a") if n in columns]
    shown = list(areas)
    ratio = None
    if "A_ratio" in columns:
        ratio = np.asarray(columns["A_ratio"])
        shown.append("A_ratio")
    elif "A_t" in columns and "A_t_max" in columns:
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.asarray(columns["A_t"]) / np.asarray(columns["A_t_max"])
        shown.append("A_t/A_t_max (computed)")
    panels = (1 if areas else 0) + (1 if ratio is not None else 0)
    figure, axes = plt.subplots(panels, 1, figsize=(6.4, 3.2 * panels + 0.8), sharex=True,
                                squeeze=False, constrained_layout=True)
    axes = axes[:, 0]
    if areas:
        for name in areas:
            axes[0].plot(x, np.asarray(columns[name]), label=plot_labels.label(name))
        axes[0].set_ylabel(axis_label("interfacial area", units[areas[0]]))
        axes[0].legend()
        axes[0].grid(alpha=0.3)
    if ratio is not None:
        axes[-1].plot(x, ratio, color="C2")
        axes[-1].set_ylabel(axis_label(plot_labels.symbol("A_ratio"), ""))
        axes[-1].grid(alpha=0.3)
    axes[-1].set_xlabel(x_label)
    save(figure, path)
    labels = record(axes)
    plt.close(figure)
    return shown, labels


def write_labels(out_dir, labels):
    """plots/labels.json: figure -> its panels' labels (written atomically)."""
    import json

    path = os.path.join(out_dir, "labels.json")
    with atomic.open_text(path) as f:
        json.dump(labels, f, indent=1, ensure_ascii=False, sort_keys=True)
        f.write("\n")


def main():
    parser = argparse.ArgumentParser(
        description="Plots RUN_DIR/series.csv of an invasim run into RUN_DIR/plots/*.png.")
    parser.add_argument("run_dir", metavar="RUN_DIR", help="run directory holding series.csv")
    args = parser.parse_args()  # exits with status 2 on a bad command line
    np, plt = import_plotting()

    series = os.path.join(args.run_dir, "series.csv")
    if not os.path.isdir(args.run_dir):
        fail("run directory '%s' does not exist" % args.run_dir)
    if not os.path.isfile(series):
        fail("'%s' not found (is '%s' an invasim run directory?)" % (series, args.run_dir))
    try:
        names, units, columns = read_series(series)
    except SeriesError as e:
        fail(str(e))

    if "time" in columns:
        x, x_label = np.asarray(columns["time"]), axis_label("time $t$", units["time"] or "tau")
    elif "step" in columns:
        x, x_label = np.asarray(columns["step"]), "step (completed integration steps)"
    else:
        x, x_label = np.arange(len(columns[names[0]])), "sample (row of series.csv)"

    out_dir = os.path.join(args.run_dir, "plots")
    os.makedirs(out_dir, exist_ok=True)
    written, skipped, labels = [], [], {}
    if any(n in columns for n in ("A_t", "A_t_max", "A_ratio")):
        path = os.path.join(out_dir, "A_t.png")
        shown, labels["A_t.png"] = plot_interface(np, plt, x, x_label, units, columns, path)
        written.append((path, shown))
    else:
        skipped.append("A_t.png (A_t, A_t_max, A_ratio)")
    for file_name, panels in GROUPS:
        present = [([n for n in wanted if n in columns], text) for wanted, text in panels]
        present = [(names, text) for names, text in present if names]
        if not present:
            skipped.append("%s (%s)" % (file_name, ", ".join(panels[0][0])))
            continue
        path = os.path.join(out_dir, file_name)
        labels[file_name] = plot_panels(np, plt, x, x_label, present, units, columns, path)
        written.append((path, [n for names, _ in present for n in names]))
    if written:
        write_labels(out_dir, labels)

    rows = len(columns[names[0]])
    for path, shown in written:
        print("wrote %s: %s" % (path, ", ".join(shown)))
    if skipped:
        print("skipped (no such columns): " + "; ".join(skipped))
    if not written:
        fail("%s (%d rows) has none of the plotted columns" % (series, rows))
    print("plot_run.py: %d plot%s of %d rows in %s"
          % (len(written), "" if len(written) == 1 else "s", rows, out_dir))
