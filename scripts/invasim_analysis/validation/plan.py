"""The campaign plan (docs/validation.md, "The plan"): per sweep file, points x steps x the
measured rate = core-hours, and the wall time with --jobs N.

Cost model of a point: fixed + steps/rate, with steps = the sum of the point's integer
parameters named *steps (quench_steps, equilibrate_steps, steps; the protocol's default
where the spec leaves one out). Two ways to get `fixed` and `rate`:
- timing (plan SPEC): two short runs of the spec's first point (`invasim sweep job`, one
  thread), differing only in `steps` (S = 2 x every and S + delta, all other *steps at 0),
  after its shared preparation if it has one, each measured in CPU time (so that a busy
  machine does not skew the rate): rate = delta/(cpu_B - cpu_A), fixed = cpu_A - S/rate
  (start-up, compression, rescale: per point); the two runs are two workspaces (a fixed
  parameter's other value is another sweep), each with its preparation, whose first CPU
  time counts once. The
  first point's rate stands for all points of the spec. Core-hours and wall times are then
  those of an idle machine;
- done points (plan --workspace WS): the wall_seconds that `sweep run` recorded; the points
  not done yet are estimated with the mean wall time per step of the done ones.
The wall time with N jobs replays `sweep run`: the preparation alone, then the points in
order, each on the first free of N slots."""

import os
import resource
import shutil
import subprocess

from .. import workspace
from ..errors import InputError
from ..repo_paths import repo_path


def declared_steps(invasim, protocol):
    """{name: default} of the protocol's integer parameters named *steps."""
    text = subprocess.run([invasim, "params", protocol], check=True, capture_output=True,
                          text=True).stdout
    out = {}
    for line in text.splitlines()[2:]:
        f = line.split()
        if len(f) >= 3 and f[0].endswith("steps") and f[1] == "integer":
            out[f[0]] = int(f[2])
    return out


def point_steps(sp, steps_defaults, spec):
    total = 0
    for name, default in steps_defaults.items():
        v = int(sp.get(name, default))
        if v < 0:
            raise InputError("%s: %s = %d (automatic) in a state point: the plan needs explicit "
                             "step counts; set it in the spec" % (spec, name, v))
        total += v
    return total


def statepoints(ws):
    meta = workspace.meta(ws)
    return meta, [(i, workspace.statepoint(os.path.join(ws, "workspace", i)))
                  for i in meta["points"]]


def _cpu_seconds(cmd):
    """The CPU seconds (user + system) of one child process run to completion."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    _run(cmd)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise InputError("%s failed (exit %d):\n%s%s" % (" ".join(cmd), r.returncode, r.stdout,
                                                         r.stderr))
    return r.stdout


def wall_time(prep, costs, jobs):
    slots = [prep] * max(1, jobs)
    for c in costs:
        k = slots.index(min(slots))
        slots[k] += c
    return max(slots) if costs else prep


def time_spec(invasim, spec, scratch, delta):
    """The timing of one spec: fixed seconds per point, rate in steps/s, preparation seconds,
    and the spec's points with their step counts."""
    name = os.path.splitext(os.path.basename(spec))[0]
    full, timing = os.path.join(scratch, name, "full"), os.path.join(scratch, name, "timing")
    shutil.rmtree(os.path.join(scratch, name), ignore_errors=True)
    _run([invasim, "sweep", "init", spec, "--workspace", full])
    meta, sps = statepoints(full)
    steps = declared_steps(invasim, meta["protocol"])
    first = sps[0][1]
    base = ["--set", "checkpoint_every=0"]
    zeroed = [n for n in steps if n != "steps"]
    s_a = int(first.get("every", 1000)) * 2
    sets = base + sum((["--set", "%s=0" % n] for n in zeroed), [])
    if "snapshot_every" in first:
        sets += ["--set", "snapshot_every=0"]
    # One workspace per step count: a workspace holds one sweep, and steps is fixed in each.
    cpu, prep = {}, 0.0
    for s in (s_a, s_a + delta):
        ws = "%s_%d" % (timing, s)
        _run([invasim, "sweep", "init", spec, "--workspace", ws, "--take", "1",
              "--set", "steps=%d" % s] + sets)
        meta_t, tsps = statepoints(ws)
        if meta_t.get("prep"):
            seconds = _cpu_seconds([invasim, "sweep", "job", ws, "prep", "--threads", "1"])
            prep = prep or seconds
        for i, sp in tsps:
            cpu[int(sp["steps"])] = _cpu_seconds([invasim, "sweep", "job", ws, i, "--threads", "1"])
    if cpu[s_a + delta] <= cpu[s_a]:
        raise InputError("%s: the timing is inconclusive (%d steps took %.2f CPU s, %d steps "
                         "%.2f CPU s); try a larger --delta" % (spec, s_a, cpu[s_a], s_a + delta,
                                                                cpu[s_a + delta]))
    rate = delta / (cpu[s_a + delta] - cpu[s_a])
    fixed = max(0.0, cpu[s_a] - s_a / rate)
    how = "CPU time of %d and %d steps" % (s_a, s_a + delta)
    shutil.rmtree(os.path.join(scratch, name), ignore_errors=True)
    counts = [point_steps(sp, steps, spec) for _, sp in sps]
    return {"spec": repo_path(spec), "points": len(sps), "steps": counts, "rate": rate, "fixed": fixed,
            "prep": prep, "source": "timing of the first point (%s)" % how,
            "costs": [fixed + n / rate for n in counts]}


def from_workspace(invasim, ws):
    """The plan of a workspace from the wall_seconds of its done points."""
    meta, sps = statepoints(ws)
    steps = declared_steps(invasim, meta["protocol"])
    counts = [point_steps(sp, steps, ws) for _, sp in sps]
    walls = [workspace.document(os.path.join(ws, "workspace", i)).get("wall_seconds")
             if workspace.document(os.path.join(ws, "workspace", i)).get("status") == "done" else None
             for i, _ in sps]
    done = [(w, n) for w, n in zip(walls, counts) if w is not None]
    if not done:
        raise InputError("%s: no point is done: run it, or plan the spec (timing)" % ws)
    per_step = sum(w for w, _ in done) / max(1, sum(n for _, n in done))
    costs = [w if w is not None else n * per_step for w, n in zip(walls, counts)]
    prep = workspace.document(os.path.join(ws, "prep")).get("wall_seconds", 0.0) if meta.get("prep") else 0.0
    return {"spec": repo_path(meta.get("spec", ws)), "workspace": os.path.basename(os.path.normpath(ws)), "points": len(sps), "steps": counts,
            "rate": sum(n for _, n in done) / max(1e-9, sum(w for w, _ in done)), "fixed": None,
            "prep": prep, "source": "wall_seconds of %d done points" % len(done), "costs": costs}


def finish(entry, jobs):
    entry["core_seconds"] = entry["prep"] + sum(entry["costs"])
    entry["wall_seconds"] = wall_time(entry["prep"], entry["costs"], jobs)
    entry["jobs"] = jobs
    return entry


def table(entries):
    """The plan as Markdown."""
    lines = ["| sweep file | points | steps per point | rate [steps/s] | fixed [s/point] | "
             "preparation [s] | core-hours | wall [h] (jobs) | from |", "|" + "---|" * 9]
    for e in entries:
        lo, hi = min(e["steps"]), max(e["steps"])
        lines.append("| `%s` | %d | %s | %.0f | %s | %.1f | %.2f | %.2f (%d) | %s |" % (
            repo_path(e["spec"]), e["points"],
            "%d" % lo if lo == hi else "%d-%d" % (lo, hi), e["rate"],
            "%.1f" % e["fixed"] if e["fixed"] is not None else "-", e["prep"],
            e["core_seconds"] / 3600, e["wall_seconds"] / 3600, e["jobs"], e["source"]))
    core = sum(e["core_seconds"] for e in entries) / 3600
    wall = sum(e["wall_seconds"] for e in entries) / 3600
    lines.append("| **total** | %d | | | | | **%.2f** | **%.2f** | |" % (
        sum(e["points"] for e in entries), core, wall))
    return "\n".join(lines)
