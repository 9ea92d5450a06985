#!/usr/bin/env python3
"""The validation campaign's analysis and document generator (docs/validation.md):
invasim_analysis/validation/.
Usage and options: validation.py --help. A thin entry point: Python's path starts with this
file's directory, which holds the package invasim_analysis."""

import sys

from invasim_analysis.validation.cli import main

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
