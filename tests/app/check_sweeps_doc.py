#!/usr/bin/env python3
"""docs/sweeps.md's examples and point counts, checked by running them (CTest
app_sweeps_doc_examples):

1. every `build/invasim sweep init SPEC ...` line of the doc's shell blocks runs (into a
   temporary workspace), and where its comment says "N points" init reports N new points;
2. every count the prose gives for a sweep file ("`name.lua` ... (N points)", the results
   table's "| `name.lua` | N + preparation |") is what `sweep init` makes of that file;
3. the doc's first block (init, run, collect, analyze --group beta,tau_p) runs end to end on
   the spec's tiny size (where analyze collects and then refuses to fit two temperatures per
   curve, as it must);
4. every `sweep submit ... --slurm ...` line of the cluster walk-through is accepted as written
   (with --dry-run, on a tiny workspace);
5. the spec example runs at its tiny size, every point done.

Usage: check_sweeps_doc.py INVASIM REPO WORK_DIR
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

invasim, repo, work = sys.argv[1:4]
doc_path = os.path.join(repo, "docs", "sweeps.md")
doc = open(doc_path).read()
problems = []


def run(args, cwd=work):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True)


def init_count(spec, extra=(), name="count"):
    """The number of new points `sweep init` reports for spec (a path under the repo)."""
    ws = os.path.join(work, name)
    shutil.rmtree(ws, ignore_errors=True)
    r = run([invasim, "sweep", "init", os.path.join(repo, spec), *extra, "--workspace", ws])
    m = re.search(r"(\d+) new points", r.stdout)
    if r.returncode != 0 or not m:
        problems.append("sweep init %s %s failed: %s" % (spec, " ".join(extra), r.stderr.strip()))
        return None
    return int(m.group(1))


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
blocks = re.findall(r"```sh\n(.*?)```", doc, re.S)
lines = [l.strip() for b in blocks for l in b.splitlines() if l.strip()]

# 1. init lines and their counts.
inits = 0
for k, line in enumerate(lines):
    command, _, comment = line.partition("#")
    words = shlex.split(command)
    if words[:3] != ["build/invasim", "sweep", "init"]:
        continue
    spec, options = words[3], words[4:]
    if "--workspace" in options:
        i = options.index("--workspace")
        del options[i:i + 2]
    if "$" in spec:
        continue
    n = init_count(spec, options, "init%d" % k)
    inits += 1
    m = re.search(r"(\d+) points", comment)
    if n is not None and m and int(m.group(1)) != n:
        problems.append("%s: the doc says %s points, sweep init makes %d" % (line, m.group(1), n))

# 2. counts in the prose and the results table.
claims = re.findall(r"`(?:protocols/sweeps/)?((?:paper_scale/)?\w+\.lua)` \((\d+) points", doc)
claims += re.findall(r"\| `(\w+\.lua)` \| (\d+) \+ preparation", doc)
for name, count in claims:
    n = init_count(os.path.join("protocols", "sweeps", name))
    if n is not None and n != int(count):
        problems.append("the doc gives %s %s points; sweep init makes %d" % (name, count, n))

# 3. the first block end to end at the tiny size.
first = [shlex.split(l.partition("#")[0]) for l in blocks[0].splitlines() if l.strip()]
ws = os.path.join(work, "first")
for words in first:
    args = [invasim] + words[1:]
    if words[2] == "init":
        args = [invasim, "sweep", "init", os.path.join(repo, words[3]), "--tiny", "--workspace", ws]
    else:
        args = [ws if a.startswith("out/") and "/" not in a[4:] else a for a in args]
        args = [a.replace("out/fig5_corner", ws) for a in args]
    r = run(args)
    # At the tiny size (400 steps, two f0 per curve) the analysis has no curve to fit and says
    # so (exit 1, master_curve.py's refusal); the command line itself must be accepted and the
    # table collected.
    refused_fit = words[2] == "analyze" and r.returncode == 1 and "master_curve.py: error:" in r.stderr
    if r.returncode != 0 and not refused_fit:
        problems.append("%s (tiny): exit %d: %s" % (" ".join(words), r.returncode,
                                                    (r.stderr or r.stdout).strip()[-400:]))
        break
    if words[2] == "analyze" and not os.path.isfile(os.path.join(ws, "results.csv")):
        problems.append("%s (tiny): no results.csv collected" % " ".join(words))

# 4. the cluster walk-through's submit lines, as written, with --dry-run.
submits = 0
for line in lines:
    words = shlex.split(line.partition("#")[0])
    if words[:3] == ["build/invasim", "sweep", "submit"] and "--slurm" in words:
        args = [invasim, "sweep", "submit", ws] + words[4:] + ["--dry-run"]
        shutil.rmtree(os.path.join(ws, "slurm"), ignore_errors=True)
        r = run(args)
        submits += 1
        if r.returncode != 0:
            problems.append("%s: refused: %s" % (line, r.stderr.strip()))

# 5. the spec example ("The sweep spec") runs at its tiny size: every point done.
example = re.search(r"```lua\n(return \{.*?\n\})\n```", doc, re.S)
example_done = 0
if not example:
    problems.append("no spec example (a lua block `return { ... }`) in %s" % doc_path)
else:
    spec_path = os.path.join(work, "example.lua")
    with open(spec_path, "w") as f:
        f.write(example.group(1).replace('"../invasion.lua"',
                                         '"%s"' % os.path.join(repo, "protocols", "invasion.lua")))
    ws = os.path.join(work, "example")
    for args in (["init", spec_path, "--tiny", "--workspace", ws], ["run", ws, "--jobs", "1"],
                 ["status", ws]):
        r = run([invasim, "sweep"] + args)
        if r.returncode != 0:
            problems.append("the spec example: sweep %s: exit %d: %s" %
                            (args[0], r.returncode, (r.stderr or r.stdout).strip()[-400:]))
            break
    else:
        done = re.search(r"^  done: (\d+)$", r.stdout, re.M)
        failed = re.search(r"^  failed: (\d+)$", r.stdout, re.M)
        if done and failed and int(done.group(1)) > 0 and failed.group(1) == "0":
            example_done = int(done.group(1))
        else:
            problems.append("the spec example at its tiny size: not every point done:\n" + r.stdout)

if inits < 3 or len(claims) < 4 or submits < 2:
    problems.append("found only %d init lines, %d counts, %d submit lines in %s" %
                    (inits, len(claims), submits, doc_path))
for p in problems:
    print("FAIL:", p)
if problems:
    sys.exit(1)
print("check_sweeps_doc: %d init lines, %d counts, the first block, %d submit lines and the spec "
      "example (%d points done) agree with docs/sweeps.md" % (inits, len(claims), submits,
                                                               example_done))
