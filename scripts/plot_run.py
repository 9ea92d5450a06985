#!/usr/bin/env python3
"""Plots the time series of an invasim run directory: invasim_analysis/plot_run.py.
Usage and options: plot_run.py --help. A thin entry point: Python's path starts with this
file's directory, which holds the package invasim_analysis."""

from invasim_analysis.plot_run import main

if __name__ == "__main__":
    main()
