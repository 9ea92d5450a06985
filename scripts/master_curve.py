#!/usr/bin/env python3
"""The master curve of an invasim sweep (docs/sweeps_analysis.md): invasim_analysis/master_curve/.
Usage and options: master_curve.py --help. A thin entry point: Python's path starts with this
file's directory, which holds the package invasim_analysis."""

import sys

from invasim_analysis.master_curve.cli import main

if __name__ == "__main__":
    main(sys.argv[1:])
