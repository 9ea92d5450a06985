"""The analysis has one path (scripts/invasim_analysis): one reader of a workspace's jobs
(workspace.py), one steady-state criterion (steady.py), one normalisation (normalise.py).

Usage: check_one_path.py REPO. Checks that
  - the master curve, the validation page and the other tools use those very modules and
    functions (identity, not copies), and the entry points scripts/*.py are the package's;
  - no other file under scripts/ defines a function of the criterion or the normalisation,
    a Job class, its constants, or reads a job's statepoint or document itself;
  - no file under scripts/ or tests/ puts a directory on sys.path.
Without numpy, scipy or matplotlib: skipped (77), or a failure under
INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.py)."""

import importlib.util
import os
import re
import sys

from prerequisites import skip_test  # tests/support, on PYTHONPATH (tests/CMakeLists.txt)

failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def identity():
    from invasim_analysis import normalise, steady, workspace
    from invasim_analysis import sweep_results
    from invasim_analysis.master_curve import analysis, cli as master_cli
    from invasim_analysis.validation import (cli as validation_cli, figures_master,
                                             figures_other, figures_tethered, figures_tissue,
                                             panels, paper_scale, plan)

    check(analysis.steady is steady and not hasattr(analysis, "workspace"),
          "the master curve judges steadiness with steady.py, from the table alone (no "
          "second reading of the runs)")
    check(analysis.normalise_group is normalise.normalise_group,
          "the master curve normalises with normalise.py")
    check(steady.group is workspace.group, "steady.py groups runs with workspace.py")
    for m in (figures_master, figures_other, figures_tethered, figures_tissue, paper_scale):
        check(m.steady is steady and m.normalise is normalise and m.workspace is workspace,
              "validation/%s uses steady.py, normalise.py and workspace.py"
              % m.__name__.rsplit(".", 1)[1])
    check(panels.steady is steady, "validation/panels uses steady.py")
    check(plan.workspace is workspace and sweep_results.workspace is workspace,
          "the plan and sweep_results.py read workspaces with workspace.py")
    # The page's Fig. 5 fits with the master curve's own functions.
    from invasim_analysis.master_curve import fits
    check(figures_master.fits is fits and figures_master.build_points is analysis.build_points
          and figures_master.analysis is analysis,
          "the page's Fig. 5 fits with the master curve's fits, state points and judgement")
    scripts = os.path.join(REPO, "scripts")
    for name, main in (("master_curve", master_cli.main), ("validation", validation_cli.main)):
        spec = importlib.util.spec_from_file_location("entry_" + name,
                                                      os.path.join(scripts, name + ".py"))
        entry = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(entry)
        check(entry.main is main, "scripts/%s.py runs the package's %s" % (name, main.__module__))


# name pattern -> the one file (under scripts/invasim_analysis/) allowed to define it
DEFINITIONS = [
    (r"^\s*def (summary_error|window|window_rows|window_mean|window_error|steadiness|judge|"
     r"point_steadiness|start_agreement|steadiness_summary|unsteady_points|drift_residuals|"
     r"autocovariance|integrated_time|mean_error)\(", "steady.py"),
    (r"^(STEADY_FACTOR|NEGLIGIBLE_DRIFT|SOKAL_C|MAX_FIT_SHARE) =", "steady.py"),
    (r"^\s*def (state_point|gap_error|job_areas|pooled_errors|least_dof)\(",
     os.path.join("validation", "points.py")),
    (r"^\s*def (factor|welch_dof)\(|^TWO_SIGMA_LEVEL =", "student.py"),
    (r"^\s*def (normalise\w*|scale_like|relative_area|scaled|run_error|point_means|"
     r"extremes)\(", "normalise.py"),
    (r"^\s*class Job\b", "workspace.py"),
    (r"signac_statepoint\.json|signac_job_document\.json|invasim_sweep\.json\"\)\)\s*as",
     "workspace.py"),
    (r"1(\.0)? - \(.*A_t_max.*\) /", "normalise.py"),  # rA_t written out again
]


def sources(root):
    for d, _, files in os.walk(root):
        for f in sorted(files):
            if f.endswith((".py", ".sh")):
                yield os.path.join(d, f)


def single_definitions():
    package = os.path.join(REPO, "scripts", "invasim_analysis")
    for path in sources(os.path.join(REPO, "scripts")):
        if not path.endswith(".py"):
            continue
        rel = os.path.relpath(path, package)
        with open(path) as f:
            for number, line in enumerate(f, 1):
                for pattern, home in DEFINITIONS:
                    if re.search(pattern, line) and rel != home:
                        check(False, "%s:%d: %s belongs in invasim_analysis/%s only"
                              % (os.path.relpath(path, REPO), number, line.strip(), home))
    check(True, "the criterion, the normalisation and the job reader are defined once")


def no_path_hacks():
    found = []
    for top in ("scripts", "tests"):
        for path in sources(os.path.join(REPO, top)):
            with open(path) as f:
                found += ["%s:%d" % (os.path.relpath(path, REPO), n)
                          for n, line in enumerate(f, 1)
                          if "sys.path." + "insert" in line or "sys.path." + "append" in line]
    check(not found, "no sys.path changes under scripts/ and tests/: %s" % (found or "none"))


def main():
    global REPO
    REPO = os.path.abspath(sys.argv[1])
    missing = [m for m in ("numpy", "scipy", "matplotlib") if importlib.util.find_spec(m) is None]
    if missing:
        skip_test("%s lacks %s" % (sys.executable, ", ".join(missing)),
                  "python3-numpy python3-scipy python3-matplotlib")
    identity()
    single_definitions()
    no_path_hacks()
    if failures:
        print("%d check(s) FAILED" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
