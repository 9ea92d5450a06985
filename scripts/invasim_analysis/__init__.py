"""invasim's analysis in Python: the entry points scripts/*.py are thin wrappers of it.

Shared by every analysis:
  workspace   the one reader of a sweep workspace's jobs (state point, document, summary.json,
              series.csv)
  steady      the one steady-state criterion (two quarter means of A_t, two starts)
  normalise   the one normalisation, A_n of the paper's Appendix C
  errors      InputError; deps: the modules an entry point needs (re-run with /usr/bin/python3);
  repo_paths  paths as the page shows them; plot_labels: the figures' label table
  atomic      every file the analysis writes, written atomically (temporary file, fsync,
              rename), so that an interrupted run never leaves a half-written file
master_curve/   the master-curve fit of a results table (scripts/master_curve.py)
validation/     the validation page and its figure records (scripts/validation.py)
plot_run, bath_table, sweep_results: scripts/plot_run.py, bath_table.py, sweep_results.py."""
