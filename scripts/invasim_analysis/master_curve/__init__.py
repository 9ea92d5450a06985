"""The master-curve analysis of an invasim sweep (scripts/master_curve.py): reading the
results table, the A_n normalisation, the sigmoid and scale fits, figures and fit tables.
Documented in docs/sweeps_analysis.md."""
