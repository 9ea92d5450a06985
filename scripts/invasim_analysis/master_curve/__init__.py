"""The master-curve analysis of an invasim sweep (scripts/master_curve.py, cli.py): reading the
results table, the sigmoid and scale fits, figures and fit tables; the normalisation and the
steady-state criterion are the package's own (normalise.py, steady.py).
Documented in docs/sweeps_analysis.md."""
