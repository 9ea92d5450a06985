"""Test of scripts/plot_run.py (Python standard library only).

Usage: check_plot_run.py PLOT_RUN_PY SCRATCH_DIR

Writes small series.csv files into SCRATCH_DIR, runs plot_run.py on them with this
interpreter and checks the PNGs it writes (valid PNG files of a plausible size) and the ones
it must skip, its messages on malformed input, and the message naming the Debian packages
when numpy/matplotlib cannot be imported. When this interpreter cannot import numpy and
matplotlib: skipped (77), or a failure under INVASIM_REQUIRE_ALL_TESTS=1
(tests/support/prerequisites.py).
"""

import os
import shutil
import struct
import subprocess
import sys

from prerequisites import skip_test  # noqa: E402
FULL_HEADER = ("step,time [tau],T_c [eps_c],T_a [eps_c],P_left [eps_c/sigma^3],"
               "P_right [eps_c/sigma^3],L_x [sigma],phi,phi_c,phi_a,A_t [sigma^2],"
               "A_t_max [sigma^2],A_ratio")
# The header of the main job's series.csv (protocols/invasion.lua).
MAIN_JOB_HEADER = ("step,time [tau],T_c [eps_c],T_a [eps_c],T_c_over_T_a,kT_c_paper [eps_c],"
                   "P_left [eps_c/sigma^3],P_right [eps_c/sigma^3],L_x [sigma],phi,phi_c,phi_a,"
                   "A_t [sigma^2],A_t_max [sigma^2],A_ratio,phi_a_local_mean,phi_a_local_std,"
                   "A_wall_a [sigma^2]")
ALL_PLOTS = ["A_t.png", "temperature.png", "pressure.png", "box_length.png", "packing.png"]
failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def run(script, run_dir, flags=(), env_extra=None):
    env = dict(os.environ)
    env.update(env_extra or {})
    p = subprocess.run([sys.executable, *flags, script, run_dir], capture_output=True,
                       text=True, env=env)
    print("$ plot_run.py %s -> exit %d\n%s%s" % (run_dir, p.returncode, p.stdout, p.stderr))
    return p


def make_run(scratch, name, text):
    run_dir = os.path.join(scratch, name)
    os.makedirs(run_dir)
    with open(os.path.join(run_dir, "series.csv"), "w") as f:
        f.write(text)
    return run_dir


def png_size(path):
    """(width, height) of a PNG file, or None if it is not one."""
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_labels(path, script):
    """The labels plot_run.py recorded for the main job's figures, and its label table."""
    from invasim_analysis import plot_labels

    # The table: every column of the main job's series.csv has a human label; an unknown
    # name is an error naming it, never printed raw.
    for entry in MAIN_JOB_HEADER.split(","):
        name = entry.split(" [")[0]
        check(not plot_labels.raw_names(plot_labels.label(name)),
              "label table: '%s' -> '%s'" % (name, plot_labels.label(name)))
    try:
        plot_labels.label("no_such_column")
        check(False, "label table: an unknown column is refused")
    except plot_labels.LabelError as e:
        check("no_such_column" in str(e), "label table: an unknown column is refused by name")
    check(plot_labels.raw_names("phi_a_local_std (x)") == ["phi_a_local_std"]
          and plot_labels.raw_names(r"$\phi_a$ [$\sigma^2$]") == [],
          "label table: raw names are found outside $...$ only")

    import json

    check(os.path.isfile(path), "labels.json written")
    if not os.path.isfile(path):
        return
    with open(path) as f:
        figures = json.load(f)
    check(sorted(figures) == sorted(ALL_PLOTS), "labels.json: every figure (%s)" % sorted(figures))
    for name, panels in figures.items():
        for k, panel in enumerate(panels):
            where = "%s panel %d" % (name, k + 1)
            texts = [panel["xlabel"], panel["ylabel"]] + panel["legend"]
            check(not [t for t in texts if plot_labels.raw_names(t)],
                  "%s: no raw column name in %s" % (where, texts))
            check("[" in panel["ylabel"] or "(dimensionless)" in panel["ylabel"],
                  "%s: the y axis has a unit: %s" % (where, panel["ylabel"]))
        check(panels[-1]["xlabel"] == "time $t$ [$\\tau$]",
              "%s: time axis in tau (%s)" % (name, panels[-1]["xlabel"]))
    packing = figures.get("packing.png", [])
    check(len(packing) == 2 and "packing fraction" in packing[0]["ylabel"]
          and len(packing[0]["legend"]) == 4
          and not [t for t in packing[0]["legend"] if "Delta" in t or "std" in t],
          "packing.png: phi, phi_c, phi_a and the mean local phi_a share the packing-fraction "
          "axis, without the std")
    check(len(packing) == 2 and packing[1]["ylabel"].startswith(r"$\Delta\phi_a$"),
          "packing.png: the std of the local phi_a on its own axis")
    temperature = figures.get("temperature.png", [])
    check(len(temperature) == 2 and temperature[0]["yscale"] == "log"
          and temperature[0]["ylabel"] == r"temperature [$\epsilon_c$]",
          "temperature.png: T_c and T_a (a decade apart) on a log scale, in eps_c")
    check(len(temperature) == 2 and temperature[1]["ylabel"].startswith("$T_c/T_a$"),
          "temperature.png: T_c/T_a on its own axis")


def main():
    script, scratch = sys.argv[1], sys.argv[2]
    probe = subprocess.run([sys.executable, "-c", "import numpy, matplotlib"],
                           capture_output=True)
    if probe.returncode != 0:
        skip_test("%s cannot import numpy and matplotlib" % sys.executable,
                  "python3-numpy python3-matplotlib")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)

    # Every column: all five plots.
    rows = ["%d,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g" % (
        100 * k, 5.0 * k, 1e-3 + 1e-5 * k, 1e-4, 2e-3 - 1e-6 * k, 1.9e-3, 100 - 0.1 * k,
        0.8, 0.6, 0.9 + 1e-3 * k, 100 + 3 * k, 400, (100 + 3 * k) / 400) for k in range(30)]
    full = make_run(scratch, "full", FULL_HEADER + "\n" + "\n".join(rows) + "\n")
    p = run(script, full)
    check(p.returncode == 0, "full series: exit status 0")
    for name in ALL_PLOTS:
        path = os.path.join(full, "plots", name)
        size = png_size(path) if os.path.isfile(path) else None
        check(size is not None and size[0] >= 300 and size[1] >= 200
              and os.path.getsize(path) > 5000, "full series: %s is a PNG image" % name)
    check("A_t.png: A_t, A_t_max, A_ratio" in p.stdout, "full series: A_t.png shows A_t, "
          "A_t_max and A_ratio")
    check("temperature.png: T_c, T_a" in p.stdout, "full series: temperature.png shows T_c, T_a")
    check("pressure.png: P_left, P_right" in p.stdout, "full series: pressure.png shows both")
    check("packing.png: phi, phi_c, phi_a" in p.stdout, "full series: packing.png shows phi*")
    check("30 rows" in p.stdout, "full series: 30 rows read")
    check(not [f for f in os.listdir(os.path.join(full, "plots")) if ".tmp" in f],
          "full series: no temporary files left")

    # The main job's columns (protocols/invasion.lua): the figures' labels, as recorded in
    # plots/labels.json, are human (no raw column name), carry units, keep the standard
    # deviation off the packing-fraction axis and put T_c next to a much colder T_a on a log
    # scale.
    rows = ["%d,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g,%g" % (
        100 * k, 5.0 * k, 1e-4 * (1 + 0.01 * k), 8e-6, 12.5, 2e-4, 1.3e-3, 1.4e-3, 13.3, 0.6,
        0.13, 0.47, 480 + k, 1300, (480 + k) / 1300, 0.62, 0.16 - 1e-3 * k, 117)
        for k in range(20)]
    main_job = make_run(scratch, "main_job", MAIN_JOB_HEADER + "\n" + "\n".join(rows) + "\n")
    p = run(script, main_job)
    check(p.returncode == 0, "main-job series: exit status 0")
    check_labels(os.path.join(main_job, "plots", "labels.json"), script)

    # Some columns only (A_t without A_t_max: no ratio), an empty field, no time column.
    partial = make_run(scratch, "partial", "step,T_c [eps_c],phi_a,A_t [sigma^2]\n"
                       "0,1e-3,0.9,100\n10,,0.91,101\n20,1.2e-3,0.92,103\n")
    p = run(script, partial)
    check(p.returncode == 0, "partial series: exit status 0")
    present = sorted(f for f in os.listdir(os.path.join(partial, "plots")) if f != "labels.json")
    check(present == ["A_t.png", "packing.png", "temperature.png"],
          "partial series: exactly A_t, packing and temperature plots (got %s)" % present)
    check("A_t.png: A_t\n" in p.stdout, "partial series: A_t.png shows A_t only")
    check("temperature.png: T_c\n" in p.stdout, "partial series: temperature.png shows T_c")
    check("skipped (no such columns): pressure.png (P_left, P_right); box_length.png (L_x)"
          in p.stdout, "partial series: pressure and box length reported as skipped")

    # A proliferation and lipolysis run (protocols/growth.lua): N_c, V0_ratio, N_touched.
    growth = make_run(scratch, "growth", "step,time [tau],N_c [cells],V0_ratio,"
                      "N_touched [adipocytes]\n0,0,400,1,3\n100,5,410,0.99,4\n200,10,431,0.97,5\n")
    p = run(script, growth)
    check(p.returncode == 0 and "growth.png: N_c, V0_ratio, N_touched\n" in p.stdout,
          "growth series: growth.png shows N_c, V0_ratio and N_touched")
    check(png_size(os.path.join(growth, "plots", "growth.png")) is not None, "growth.png is a PNG")

    # A_t and A_t_max without A_ratio: the ratio is computed.
    ratio = make_run(scratch, "ratio", "time [tau],A_t [sigma^2],A_t_max [sigma^2]\n"
                     "0,10,40\n1,12,40\n")
    p = run(script, ratio)
    check(p.returncode == 0 and "A_t.png: A_t, A_t_max, A_t/A_t_max (computed)" in p.stdout,
          "A_ratio computed from A_t and A_t_max")

    # A run killed while writing its last row: the complete rows are plotted.
    killed = make_run(scratch, "killed", "step,L_x [sigma]\n0,10\n10,9.9\n20\n")
    p = run(script, killed)
    check(p.returncode == 0 and "line 4 is incomplete" in p.stderr and "2 rows" in p.stdout,
          "incomplete last row ignored with a note")

    # Errors: each names the file (and the line) and exits 1; nothing crashes.
    cases = [
        ("missing_dir", None, "run directory '%s' does not exist"),
        ("no_series", "", "series.csv' not found"),
        ("text_field", "step,L_x [sigma]\n0,10\n10,abc\n", "line 3, column 'L_x': 'abc' is not a number"),
        ("long_row", "step,L_x\n0,10,3\n1,2\n", "line 2 has 3 fields, the header has 2"),
        ("header_only", "step,L_x [sigma]\n", "has a header but no data rows"),
        ("empty", "\n", "is empty (no header row)"),
        ("nothing_to_plot", "step,time [tau],energy\n0,0,1\n", "has none of the plotted columns"),
    ]
    for name, text, message in cases:
        run_dir = os.path.join(scratch, name)
        if text is not None:
            os.makedirs(run_dir)
            if text:
                with open(os.path.join(run_dir, "series.csv"), "w") as f:
                    f.write(text)
        p = run(script, run_dir)
        if "%s" in message:
            message = message % run_dir
        check(p.returncode == 1 and message in p.stderr and "Traceback" not in p.stderr,
              "error '%s': exit 1 with '%s'" % (name, message))
    p = subprocess.run([sys.executable, script], capture_output=True, text=True)
    check(p.returncode == 2 and "RUN_DIR" in p.stderr, "no argument: usage, exit 2")

    # Without numpy/matplotlib (-S -E hides site-packages; no re-exec): a message naming the
    # Debian packages. Only if that really hides them here.
    hidden = subprocess.run([sys.executable, "-S", "-E", "-c", "import matplotlib"],
                            capture_output=True)
    if hidden.returncode != 0:
        p = run(script, full, flags=("-S", "-E"), env_extra={"INVASIM_PLOT_NO_REEXEC": "1"})
        check(p.returncode == 1 and "apt-get install" in p.stderr
              and "python3-matplotlib" in p.stderr and "Traceback" not in p.stderr,
              "missing matplotlib: exit 1 naming python3-matplotlib")
    else:
        print("note: -S -E does not hide matplotlib here; the missing-module message is not "
              "checked")

    print("%d checks failed" % len(failures) if failures else "plot_run: all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
