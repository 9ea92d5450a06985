"""The factor of a "2 errors" criterion for an error estimated from few replicates: with dof
degrees of freedom, 2 standard errors cover the truth less often than 95.4 % (70 % for one,
86 % for three), so the criterion takes t_0.977(dof) errors instead, the Student quantile of
the same coverage (docs/validation.md, Method). An error combined from several
(sum c_i e_i in quadrature) has the Welch-Satterthwaite degrees of freedom."""

import math

# The one-sided tail of 2 standard deviations of a normal distribution.
TWO_SIGMA_LEVEL = 0.97725


def factor(dof):
    """t_0.977(dof): 13.97 for 1 degree of freedom, 3.31 for 3, 2.28 for 10, 2 for many
    (dof None, 0 or inf: an error that is not a replicate estimate, e.g. a run's own)."""
    if dof is None or not dof > 0 or math.isinf(dof):
        return 2.0
    from scipy.stats import t  # slow import
    return float(t.ppf(TWO_SIGMA_LEVEL, dof))


def welch_dof(terms):
    """The degrees of freedom of sqrt(sum v_i^2) for terms [(v_i, dof_i)] (v_i an error's
    share, dof_i its degrees of freedom; None: many): (sum v^2)^2 / sum(v^4 / dof). None when
    every term has many."""
    finite = [(v, d) for v, d in terms if d is not None and d > 0 and not math.isinf(d)]
    if not finite:
        return None
    total = sum(v * v for v, _ in terms if math.isfinite(v))
    denominator = sum(v ** 4 / d for v, d in finite)
    return total ** 2 / denominator if denominator > 0 else None
