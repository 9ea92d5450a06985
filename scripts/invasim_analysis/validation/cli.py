"""The validation campaign's analysis and document generator (docs/validation.md).

Usage:
  validation.py figure NAME WS [WS2] -o DIR [--invasim PATH]
      one figure from its sweep workspace(s): DIR/NAME.json (rows of the side-by-side
      table, verdicts, steady-state evidence, numbers, the command) and the images.
      NAME and workspaces: fig3 WS | fig4a WS [RELAX_WS [RELAX_LONG_WS]] | fig4b WS [INSET_WS] | fig5 ACTIVE_WS
      [PASSIVE_WS [LONG_WS [EXTRA_WS]]] | fig6 WS | fig7a WS | fig7b WS | fig8 WS | fig9 WS
      (LONG_WS: curves run longer, each replacing ACTIVE_WS's curve of the same beta and
      tau_p; EXTRA_WS: further curves; '-' for an optional workspace not given: the record
      and the page name it as missing)
  validation.py all ROOT -o DIR [--invasim PATH]
      every figure from the standard workspaces ROOT/<sweep file name> (out, out/tiny)
  validation.py plan SPEC... [--jobs N] [--delta STEPS] [-o plan.json] [--invasim PATH]
  validation.py plan --workspace WS... [--jobs N] [-o plan.json]
      points x steps x measured rate = core-hours and wall time with N jobs, by timing two
      short runs of each spec's first point, or from the wall_seconds of done points
  validation.py paper ROOT -o DIR [--plan plan_paper_scale.json] [--invasim PATH]
      the paper-scale records from the workspaces ROOT/paper_<sweep file> of
      protocols/sweeps/paper_scale/ (fig3_passive_slices, fig4a_passive, fig4b_starts,
      fig4b_starts_hot, fig5_cohesive), read as they are, points done, running or pending: DIR/paper_fig3.json,
      paper_fig4a.json, paper_fig4b.json, paper_fig5.json (rows with verdicts, a running run's
      values marked provisional; each run's progress and steadiness), the figures and the
      A_n(t) panels (DIR/<figure>_runs.png), and DIR/paper_cost.json (core-hours used and
      projected per sweep file; the whole paper at its scale from --plan)
  validation.py document DIR [--plan plan.json] [--done plan_done.json] [--paper PDIR]
                         -o docs/validation.md [--ci-size]
      assembles the page from DIR/*.json and the plan (--paper: the paper-scale records of
      `paper ... -o PDIR`, shown beside the reduced ones; --ci-size: the tiny-CI banner)

Needs numpy, scipy and matplotlib; if the python3 running it lacks them, it re-runs itself
with /usr/bin/python3. Exit status 0; 1 on bad input (named); 2 on a bad command line."""

import argparse
import json
import math
import os
import re
import sys

from .. import atomic
from ..deps import ensure_modules
from ..errors import InputError
from ..repo_paths import REPO, repo_path

# figure -> the sweep files (workspace names) it reads, in argument order
FIGURES = {
    "fig3": ["fig3_passive_slices"], "fig4a": ["fig4a_passive", "fig4a_relaxation", "fig4a_relaxation_long"],
    "fig4b": ["fig4b_cohesive", "fig4b_inset"],
    "fig5": ["fig5_active", "fig5_passive", "fig5_long", "fig5_extra_curves"],
    "fig6": ["fig6_cells_only"], "fig7a": ["fig7a_tethered"], "fig7b": ["fig7b_tethered"],
    "fig8": ["fig8_packing"], "fig9": ["fig9_shapes"],
}
NOT_GIVEN = "-"  # an optional workspace left out (figure fig5 A - LONG)
REQUIRED = {"fig4a": 1, "fig4b": 1, "fig5": 1}  # the others need all their workspaces


def default_invasim():
    return os.path.join(REPO, "build", "invasim")


def command_text(argv):
    return " ".join(["scripts/validation.py"] + argv)


def lf_row(ws, verdict):
    """The L_f contradiction from the workspace's shared preparation (the compressed box)."""
    from .. import workspace
    prep = workspace.prep_summary(ws)
    if prep is None:
        return None
    comp = prep.get("compression", {})
    box, phi = comp.get("box"), comp.get("phi")
    with open(os.path.join(REPO, "protocols", "lib", "presets.lua")) as f:
        presets = {m.group(1): (int(m.group(2)), int(m.group(3))) for m in re.finditer(
            r"(\w+) = \{ N_a = (\d+), N_c = (\d+)", f.read())}
    system = workspace.meta(ws).get("prep", {}).get("set", {}).get("system", "reduced")
    if not box or system not in presets:
        return None
    n_a, n_c = presets[system]
    p_a, p_c = presets["paper"]
    volume = phi * box[0] * box[1] * box[2]
    v_cell = math.pi / 6
    v_adipocyte = (volume - n_c * v_cell) / n_a
    l_paper = ((p_a * v_adipocyte + p_c * v_cell) / phi) ** (1 / 3)
    st = verdict.paper()["L_f"]
    return verdict.row(
        "L_f", "L = %.3g at phi = %.3g (%s system, %d + %d bodies); the paper-size system with "
        "the same bodies: %.3g" % (box[0], phi, system, n_a, n_c, l_paper),
        verdict.value_verdict(l_paper, 0.0, st["value"], st["tolerance"]),
        "we stop at phi = 0.72, as the paper's other numbers say; its 34 sigma would be phi = "
        "%.3g" % (phi * (l_paper / st["value"]) ** 3))


def figure(name, workspaces, out, invasim, argv):
    if name not in FIGURES:
        raise InputError("unknown figure '%s'; figures: %s" % (name, ", ".join(FIGURES)))
    most, least = len(FIGURES[name]), REQUIRED.get(name, len(FIGURES[name]))
    if not least <= len(workspaces) <= most:
        raise InputError("figure %s reads %s workspace%s (%s); got %d" % (
            name, least if least == most else "%d or %d" % (least, most),
            "" if most == 1 else "s", ", ".join(FIGURES[name]), len(workspaces)))
    if workspaces[0] == NOT_GIVEN:
        raise InputError("figure %s: its first workspace (%s) is required"
                         % (name, FIGURES[name][0]))
    from .. import workspace
    sets = [workspace.load(ws) if ws != NOT_GIVEN else None for ws in workspaces]
    from . import (figures_master, figures_other, figures_tethered,  # slow import
                    figures_tissue, verdict)
    funcs = {"fig3": figures_tissue.fig3, "fig4a": figures_tissue.fig4a,
             "fig4b": figures_tissue.fig4b, "fig7a": figures_tethered.fig7a,
             "fig7b": figures_tethered.fig7b, "fig5": figures_master.fig5,
             "fig6": figures_other.fig6, "fig8": figures_other.fig8, "fig9": figures_other.fig9}
    os.makedirs(out, exist_ok=True)
    rec = funcs[name](sets[0], out, invasim, *sets[1:])
    rec["missing"] = [FIGURES[name][k] for k in range(len(FIGURES[name]))
                      if k >= len(workspaces) or workspaces[k] == NOT_GIVEN]
    if name == "fig3":
        row = lf_row(workspaces[0], verdict)
        if row:
            rec["rows"].append(row)
    specs = []
    for ws in [w for w in workspaces if w != NOT_GIVEN]:
        specs.append(repo_path(workspace.meta(ws)["spec"]))
    jobs = [j for s in sets if s for j in s]
    steps = sorted(int(j.sp.get("steps", j.scalar("steps"))) for j in jobs)
    rec.update({"figure": name, "criteria": verdict.CRITERIA, "command": command_text(argv),
                "specs": specs,
                "runs": len(jobs), "steps_range": "%d" % steps[0] if steps[0] == steps[-1]
                else "%d-%d" % (steps[0], steps[-1])})
    write_json(os.path.join(out, name + ".json"), rec)
    for r in rec["rows"]:
        print("%s: %s: %s (%s)" % (name, r["id"], r["verdict"], r["ours"]))
    return rec


def paper(root, out, invasim, plan_path, argv):
    """The paper-scale records (validation/paper_scale.py), written atomically."""
    from . import paper_scale
    if not os.path.isdir(root):
        raise InputError("paper: %s is not a directory (the root of the workspaces "
                              "paper_<sweep file>)" % root)
    entries = None
    if plan_path:
        with open(plan_path) as fh:
            entries = json.load(fh)
    os.makedirs(out, exist_ok=True)
    shown = ["paper", repo_path(root, "ROOT"), "-o", repo_path(out, "DIR")]
    if plan_path:
        shown += ["--plan", repo_path(plan_path, "plan_paper_scale.json")]
    for name in paper_scale.SWEEPS:
        rec = paper_scale.record(name, root, out, invasim)
        rec["command"] = command_text(shown)
        write_json(os.path.join(out, "paper_%s.json" % name), rec)
        for r in rec["rows"]:
            print("paper %s: %s: %s (%s)" % (name, r["id"], r["verdict"], r["ours"]))
    cost = paper_scale.cost_record(root, entries)
    write_json(os.path.join(out, "paper_cost.json"), cost)
    print("paper: %.2f core-hours used, %.2f projected for this machine's list; the whole "
          "paper %.0f" % (cost["used_core_hours"], cost["projected_core_hours"],
                          cost["whole_paper"]["core_hours"]))


def write_json(path, obj):
    """JSON written atomically (atomic.py)."""
    with atomic.open_text(path) as f:
        json.dump(obj, f, indent=1, default=float)


def main(argv):
    ensure_modules("validation.py")
    ap = argparse.ArgumentParser(prog="validation.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="verb", required=True)
    f = sub.add_parser("figure")
    f.add_argument("name")
    f.add_argument("workspaces", nargs="+")
    f.add_argument("-o", dest="out", required=True)
    f.add_argument("--invasim", default=default_invasim())
    a = sub.add_parser("all")
    a.add_argument("root")
    a.add_argument("-o", dest="out", required=True)
    a.add_argument("--invasim", default=default_invasim())
    p = sub.add_parser("plan")
    p.add_argument("specs", nargs="*")
    p.add_argument("--workspace", nargs="+", default=[])
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--delta", type=int, default=10000)
    p.add_argument("--scratch", default="out/plan")
    p.add_argument("-o", dest="out")
    p.add_argument("--invasim", default=default_invasim())
    q = sub.add_parser("paper")
    q.add_argument("root")
    q.add_argument("-o", dest="out", required=True)
    q.add_argument("--plan", help="plan JSON of the paper-scale sweep files (projected cost)")
    q.add_argument("--invasim", default=default_invasim())
    d = sub.add_parser("document")
    d.add_argument("dir")
    d.add_argument("--plan")
    d.add_argument("--done", help="plan JSON of the done workspaces (plan --workspace): the campaign as run")
    d.add_argument("--paper", help="directory of the paper-scale records (validation.py paper)")
    d.add_argument("-o", dest="out", required=True)
    d.add_argument("--ci-size", action="store_true")
    args = ap.parse_args(argv)

    try:
        if args.verb == "figure":
            figure(args.name, args.workspaces, args.out, args.invasim, argv)
        elif args.verb == "all":
            for name, names in FIGURES.items():
                wss = [os.path.join(args.root, n) for n in names]
                present = [os.path.exists(os.path.join(w, "invasim_sweep.json")) for w in wss]
                # The first workspace is the figure's own; the others are optional extras,
                # passed as '-' when missing (the record names them).
                if not present[0] or sum(present) < REQUIRED.get(name, len(names)):
                    print("%s: skipped (no workspace %s)" % (name, ", ".join(
                        w for w, here in zip(wss, present) if not here)))
                    continue
                while not present[-1]:
                    wss, present = wss[:-1], present[:-1]
                wss = [w if here else NOT_GIVEN for w, here in zip(wss, present)]
                figure(name, wss, args.out, args.invasim, ["figure", name] + wss + ["-o", args.out])
        elif args.verb == "plan":
            from . import plan
            if args.jobs < 1:
                ap.error("--jobs must be >= 1")
            if not args.specs and not args.workspace:
                ap.error("plan needs sweep files (timing) or --workspace WS (done points)")
            entries = [plan.finish(plan.time_spec(args.invasim, s, args.scratch, args.delta), args.jobs)
                       for s in args.specs]
            entries += [plan.finish(plan.from_workspace(args.invasim, w), args.jobs)
                        for w in args.workspace]
            print(plan.table(entries))
            if args.out:
                os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
                with atomic.open_text(args.out) as fh:
                    json.dump(entries, fh, indent=1)
        elif args.verb == "paper":
            paper(args.root, args.out, args.invasim, args.plan, argv)
        elif args.verb == "document":
            from . import document
            entries = None
            if args.plan:
                with open(args.plan) as fh:
                    entries = json.load(fh)
            done = None
            if args.done:
                with open(args.done) as fh:
                    done = json.load(fh)
            counts = document.render(args.dir, entries, args.out, args.ci_size, done, args.paper)
            print("document: %s (%s)" % (args.out, ", ".join("%d %s" % (n, v) for v, n in counts.items())))
    except InputError as e:
        print("validation.py: error: %s" % e, file=sys.stderr)
        return 1
    return 0

