#!/usr/bin/env python3
"""Every test the docs cite exists (CTest app_docs_cite_registered_tests).

docs/reliability.md and the other pages name the test that fails if a protection is removed,
as CTest names: `test_fire:FIRE stopped ... and resumed`, `cli_blow_up_stops_...`,
`test_setup` (every case of an executable). A cited name must be the start of a registered
test's name, where "..." stands for any text and "{a,b}" for either; a test renamed or
removed without its citation fails here. Build programs that the docs name as programs
(`regression_forces`) are accepted too.

Usage: check_doc_test_names.py REPO BUILD_DIR
"""
import glob
import os
import re
import subprocess
import sys

repo, build = sys.argv[1:3]
listing = subprocess.run(["ctest", "--test-dir", build, "-N"], capture_output=True, text=True,
                         check=True).stdout
names = [m.group(1) for m in re.finditer(r"^\s*Test\s+#\d+: (.*)$", listing, re.M)]
if len(names) < 100:
    sys.exit(f"ctest -N listed only {len(names)} tests:\n{listing}")
programs = {os.path.basename(p) for p in glob.glob(os.path.join(build, "**", "*"), recursive=True)
            if os.path.isfile(p) and os.access(p, os.X_OK)}

CITED = re.compile(r"`((?:test|cli|app|regression|analysis|fuzz|io|measure|validation)_"
                   r"[A-Za-z0-9_{},]*(?::[^`]*)?)`")


def expansions(token):
    m = re.search(r"\{([^{}]*)\}", token)
    if not m:
        return [token]
    return [e for alt in m.group(1).split(",")
            for e in expansions(token[:m.start()] + alt + token[m.end():])]


def registered(token):
    for name in expansions(token):
        if name in programs:
            return True
        pattern = "".join(".*" if part == "..." else re.escape(part)
                          for part in re.split(r"(\.\.\.)", name.rstrip(". ")))
        if not any(re.match(pattern, n) for n in names):
            return False
    return True


checked, missing = 0, []
pages = sorted(glob.glob(os.path.join(repo, "docs", "*.md"))) + [os.path.join(repo, "README.md")]
for page in pages:
    for number, line in enumerate(open(page, encoding="utf-8"), 1):
        for m in CITED.finditer(line):
            checked += 1
            if not registered(m.group(1)):
                missing.append(f"{os.path.relpath(page, repo)}:{number}: `{m.group(1)}`")
if missing:
    sys.exit("cited tests that are not registered (ctest -N):\n" + "\n".join(missing))
if checked < 100:
    sys.exit(f"only {checked} test citations found: is the pattern still right?")
print(f"all {checked} test citations in the docs name registered tests")
