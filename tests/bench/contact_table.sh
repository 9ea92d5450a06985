# shellcheck shell=bash
# The contact law (src/forces/contact_force.cpp) as LAMMPS pair_style table input, for the
# scripts that run LAMMPS on invasim's cells (compare_lammps.sh, cross_check_lammps.sh).
# Sourced, not run. Sections S09, S10, S11 for s = 0.9, 1.0, 1.1 with eps = 1, x = 1 - r/s:
# repulsive (beta = 0): F = x/s, E = x^2/2 for r < s; cohesive (r_a = (1+alpha)s,
# r_b = (1+beta)s, k = beta/((alpha-beta)s^2)): F = x/s, E = (x^2 - alpha beta)/2 for r <= r_b,
# F = k (r - r_a), E = -k (r_a - r)^2/2 for r_b < r <= r_a. POINTS points from R_MIN to the
# cutoff (s or r_a): LAMMPS stops when a pair comes closer than R_MIN, so a hot fluid, whose
# cells meet closer, needs a smaller R_MIN (and more points, to keep the spacing).
# Usage: contact_table ALPHA BETA FILE [POINTS = 2000] [R_MIN = 0.01]   (appends to FILE)
contact_table() {
  local s
  for s in 0.9 1.0 1.1; do
    awk -v s="$s" -v label="S$(echo "$s" | tr -d .)" -v a="$1" -v b="$2" -v n="${4:-2000}" \
        -v lo="${5:-0.01}" 'BEGIN {
      hi = b > 0 ? (1 + a) * s : s; ra = (1 + a) * s; rb = (1 + b) * s;
      k = b > 0 ? b / ((a - b) * s * s) : 0;
      printf "%s\nN %d R %.10f %.10f\n\n", label, n, lo, hi;
      for (i = 1; i <= n; ++i) { r = lo + (hi - lo) * (i - 1) / (n - 1); x = 1 - r / s;
        if (b <= 0 || r <= rb) { f = x / s; e = 0.5 * (x * x - a * b) }
        else { f = k * (r - ra); e = -0.5 * k * (ra - r) * (ra - r) }
        if (b <= 0 && r >= s) { f = 0; e = 0 }
        printf "%d %.12f %.15e %.15e\n", i, r, e, f } print "" }' >> "$3"
  done
}
