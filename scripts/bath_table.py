#!/usr/bin/env python3
"""Regenerates the vertex-bath tables of docs/model.md: invasim_analysis/bath_table.py.
Usage and options: bath_table.py --help. A thin entry point: Python's path starts with this
file's directory, which holds the package invasim_analysis."""

from invasim_analysis.bath_table import main

if __name__ == "__main__":
    main()
