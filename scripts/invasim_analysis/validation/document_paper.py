"""The section "At the paper's scale" of docs/validation.md (document.py calls section()):
from the records of `scripts/validation.py paper` (paper_<figure>.json, paper_cost.json),
each statement's paper-scale value and verdict beside the reduced-scale ones, whether the
paper's scale changes the verdict, the state of every run, its A_n(t) panel and the cost."""

import json
import os

from .paper_scale import DONE, FAILED, PENDING, RUNNING, SWEEPS, progress_text
from .verdict import NO_DATA
from .verdict import PENDING as V_PENDING
from .verdict import RUNNING as V_RUNNING
from .verdict import fmt, paper, paper_verdict

TITLES = {"fig3": "Fig. 3: passive repulsive cells, A_t(t) and A_t^min/A_t^max",
          "fig4a": "Fig. 4a: passive repulsive cells, A_n at t = 1e4, 1e5, 5e5 and T_g",
          "fig4b": "Fig. 4b: the 0.55 point (beta = 1e-2, tau_p = 25) from both starts",
          "fig5": "Fig. 5: the beta = 1e-2, tau_p = 25 curve"}


def _cell(text):
    return str(text).replace("|", "\\|")


def load(paper_dir):
    """{figure: record} and the cost record of a paper-scale directory (absent: empty)."""
    recs = {}
    for name in SWEEPS:
        p = os.path.join(paper_dir, "paper_%s.json" % name)
        if os.path.exists(p):
            with open(p) as f:
                recs[name] = json.load(f)
    cost = None
    p = os.path.join(paper_dir, "paper_cost.json")
    if os.path.exists(p):
        with open(p) as f:
            cost = json.load(f)
    return recs, cost


def _key(row):
    return row["id"], row.get("variant")


def change(reduced_verdict, paper_row):
    """Whether the paper's scale changes the statement's verdict, as the page says it."""
    v = paper_row["verdict"]
    if v == V_RUNNING:
        return "not yet: running (provisionally %s)" % (
            "the same" if paper_row.get("provisional") == reduced_verdict
            else "%s -> %s" % (reduced_verdict or "none", paper_row.get("provisional")))
    if v == V_PENDING:
        return "not yet: pending"
    if reduced_verdict is None:
        return "no reduced-scale record"
    if v == NO_DATA:
        return "cannot say: no data at the paper's scale"
    return "no" if v == reduced_verdict else "yes: %s -> %s" % (reduced_verdict, v)


def side_by_side(recs, reduced):
    """The rows of the comparison table: (statement, reduced ours, reduced verdict, paper
    ours, paper verdict, change) for every paper-scale row."""
    by_key = {}
    for rec in reduced.values():
        for r in rec.get("rows", []):
            r = dict(r)
            r["verdict"], r["why"] = paper_verdict(paper().get(r["id"], {}), r["verdict"], r["why"])
            by_key[_key(r)] = r
    out = []
    for name in SWEEPS:
        for r in recs.get(name, {}).get("rows", []):
            red = by_key.get(_key(r))
            stmt = "`%s`%s" % (r["id"], " (%s)" % r["variant"] if r.get("variant") else "")
            out.append((stmt, red["ours"] if red else "n/a", red["verdict"] if red else "n/a",
                        r["ours"], r["verdict"], change(red["verdict"] if red else None, r)))
    return out


def change_summary(rows):
    """One sentence from the table's last column: which statements the paper's scale changes,
    which it leaves as they were, and which it cannot yet settle (running, pending, no data)."""
    groups = {"yes": [], "no": [], "open": []}
    for stmt, _, _, _, _, what in rows:
        kind = "yes" if what.startswith("yes") else "no" if what == "no" else "open"
        groups[kind].append("%s (%s)" % (stmt, what[5:]) if kind == "yes" else
                            stmt if kind == "no" else "%s (%s)" % (stmt, what))
    parts = []
    for kind, lead in (("yes", "changes the verdict of"), ("no", "leaves the verdict of"),
                       ("open", "does not settle")):
        if groups[kind]:
            parts.append("%s %d: %s" % (lead, len(groups[kind]), ", ".join(groups[kind])))
    return "In short, the paper's scale %s." % "; it ".join(parts) if parts else ""


def _runs_table(rec):
    lines = ["| run | state | steady state (m4 - m3 against 2 x its error) |", "|---|---|---|"]
    for p in rec.get("runs", []):
        s = p.get("steadiness")
        if not s:
            st = "n/a"
        else:
            st = "%s: m4 - m3 = %s" % ({True: "steady", False: "drifting", None: "not judged"}[
                s["steady"]], fmt(s["drift"], s["error"]))
            if s["steady"] is not None and s["negligible"] is not None:
                st += " (negligible below %s)" % fmt(s["negligible"])
        lines.append("| %s | %s | %s |" % tuple(_cell(v) for v in (
            p["name"], progress_text(p), st)))
    return lines


def _cost(cost):
    if not cost:
        return ["(no cost record: `scripts/validation.py paper ROOT -o DIR --plan "
                "docs/validation/plan_paper_scale.json`)", ""]
    lines = ["Core-hours used are the recorded wall times of the runs (`wall_seconds` of the job "
             "documents, summed over attempts; a run's current attempt counts once it stops) "
             "times the threads each was given (`--threads` of its last attempt in its "
             "`run.log`). The projected total adds, for each point not done, the mean core "
             "time of the done points of its sweep (before any is done: the plan's cost per "
             "point at one thread) times the fraction of its run still to go.", "",
             "| sweep file | points | done | running | pending | failed | core-hours used | "
             "projected total | plan |", "|---|---|---|---|---|---|---|---|---|"]
    for c in cost["sweeps"]:
        n = c["counts"]
        lines.append("| `protocols/sweeps/paper_scale/%s.lua` | %d | %d | %d | %d | %d | %.2f | "
                     "%s | %s |" % (c["sweep"], c["points"], n[DONE], n[RUNNING], n[PENDING],
                                    n[FAILED], c["used_core_hours"],
                                    "-" if c["projected_core_hours"] is None
                                    else "%.2f" % c["projected_core_hours"],
                                      "%.2f" % c["plan_core_hours"] if c["plan_core_hours"]
                                      is not None else "-"))
    lines.append("| **this machine's list** | | | | | | **%.2f** | **%.2f**%s | |" % (
        cost["used_core_hours"], cost["projected_core_hours"],
        " (without %s: no workspace, no plan)" % ", ".join(cost["unprojected"])
        if cost.get("unprojected") else ""))
    w = cost["whole_paper"]
    if w["sweeps"]:
        lines += ["", "The whole paper at its scale on a cluster (every file of "
                  "`protocols/sweeps/paper_scale/`, projected by `scripts/validation.py plan` at "
                  "one thread per point): %s; **%.0f core-hours** in all." % (
                      ", ".join("`%s` %d points, %.1f" % (os.path.basename(s["spec"]), s["points"],
                                                          s["core_hours"]) for s in w["sweeps"]),
                      w["core_hours"])]
    return lines + [""]


def section(paper_dir, reduced, fig_base, page_base):
    """The lines of the section; reduced: the reduced-scale records by figure."""
    recs, cost = load(paper_dir)
    rel = os.path.relpath(os.path.abspath(paper_dir), page_base)
    L = ["## At the paper's scale", "",
         "The statements that our reduced system (8 adipocytes, 400 cells, `t` up to 7.5e4) "
         "may not hold at steady state, run at the paper's size (28 adipocytes, 1500 cells, "
         "`system = paper`) to the paper's `t = 5e5` (1e7 steps): the sweep files of "
         "`protocols/sweeps/paper_scale/`, analysed by `scripts/validation.py paper` into "
         "`%s/`. Each row is computed as at the reduced scale, with the same steady-state "
         "criterion (Method). A row resting on a run that has not finished is *running*: it "
         "shows the values so far and, as provisional, the verdict they would give; a row "
         "with no run started is *pending*." % rel, ""]
    rows = side_by_side(recs, reduced)
    if rows:
        L += ["| statement | reduced scale | verdict | paper's scale | verdict | does the "
              "paper's scale change the verdict? |", "|---|---|---|---|---|---|"]
        L += ["| %s |" % " | ".join(_cell(v) for v in r) for r in rows]
        L += ["", change_summary(rows), ""]
    else:
        L += ["No paper-scale record in `%s/`." % rel, ""]
    for name in SWEEPS:
        rec = recs.get(name)
        if not rec:
            continue
        L += ["### %s" % TITLES[name], ""]
        if rec.get("missing"):
            L += ["Workspace%s not started: %s." % ("s" if len(rec["missing"]) > 1 else "",
                                                    ", ".join("`%s`" % m for m in rec["missing"])), ""]
        if rec.get("runs"):
            L += _runs_table(rec) + [""]
        for r in rec.get("rows", []):
            L += ["- `%s`%s: %s; %s." % (r["id"], " (%s)" % r["variant"] if r.get("variant")
                                         else "", r["verdict"], r["why"])]
        L.append("")
        for img in rec.get("images", []):
            L += ["![%s](%s/%s)" % (name, rel, img), ""]
            if img.endswith("_runs.png"):
                L += ["*Each run's `A_t(t)` over its production (right axis: `A_n`, the same "
                      "`A_t` through the figure's normalisation); grey: the averaging window; "
                      "blue and red bars: the means of its two quarters with their "
                      "errors, which the steady-state criterion compares.*", ""]
        if rec.get("command"):
            L += ["Regenerate: `%s`" % rec["command"], ""]
    L += ["### Cost and progress", ""] + _cost(cost)
    return L
