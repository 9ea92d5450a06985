#!/usr/bin/env python3
"""Keeps a sweep's done points and puts them back (docs/sweeps.md):
invasim_analysis/sweep_results.py.
Usage and options: sweep_results.py --help. A thin entry point: Python's path starts with this
file's directory, which holds the package invasim_analysis."""

import sys

from invasim_analysis.sweep_results import main

if __name__ == "__main__":
    sys.exit(main(sys.argv))
