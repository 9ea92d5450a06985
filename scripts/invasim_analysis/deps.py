"""The Python modules an entry point needs (Debian 12: python3-numpy, python3-scipy,
python3-matplotlib): a python3 without them re-runs the entry point with /usr/bin/python3."""

import importlib.util
import os
import sys

SYSTEM_PYTHON = "/usr/bin/python3"
# Set when re-executed, so that it happens at most once.
NO_REEXEC = "INVASIM_ANALYSIS_NO_REEXEC"


def ensure_modules(prog, modules=("numpy", "scipy", "matplotlib"), no_reexec=NO_REEXEC):
    """Returns if every module of `modules` can be imported. Else re-runs the entry point
    (sys.argv[0]) with /usr/bin/python3 when that is another interpreter and `no_reexec` is
    not set in the environment, or exits 1 naming the Debian packages."""
    missing = [m for m in modules if importlib.util.find_spec(m) is None]
    if not missing:
        return
    here = os.path.realpath(sys.executable) if sys.executable else ""
    if (not os.environ.get(no_reexec) and os.path.exists(SYSTEM_PYTHON)
            and os.path.realpath(SYSTEM_PYTHON) != here):
        os.environ[no_reexec] = "1"
        sys.stdout.flush()
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, os.path.abspath(sys.argv[0])] + sys.argv[1:])
    print("%s: error: %s not available to %s; on Debian install: apt-get install %s"
          % (prog, " and ".join(missing), sys.executable or "python3",
             " ".join("python3-" + m for m in missing)), file=sys.stderr)
    sys.exit(1)
