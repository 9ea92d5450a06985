#!/usr/bin/env python3
"""E_c ~ 1/P from a pressure sweep's workspace (protocols/sweeps/pressure_fig5.lua;
invasim_analysis/pressure.py). Usage: pressure_sweep.py WS [WS ...] -o DIR. A thin entry point:
Python's path starts with this file's directory, which holds the package invasim_analysis."""

import sys

from invasim_analysis.deps import ensure_modules

ensure_modules("pressure_sweep.py")

from invasim_analysis.pressure import main  # noqa: E402

if __name__ == "__main__":
    main(sys.argv[1:])
