"""The side-by-side rows and their verdicts (docs/validation.md, "How a verdict is reached").

Two kinds of statement, each with an explicit criterion:
- a number (the paper's value p with its stated precision tol, from validation_paper.json):
  agrees               |ours - p| <= tol + 2 err
  agrees in trend only the number is off, but the statement's trend holds (given by the
                       figure: e.g. the sigmoid moves left in time, but its midpoint is far)
  disagrees            otherwise
- a trend (a signed difference d with error e that the paper says is > 0):
  agrees               d > 2 e
  agrees in trend only 0 < d <= 2 e (the right sign, not significant at 2 sigma)
  inconclusive         -2 e <= d <= 0 (the wrong sign, not significant either: a true
                       d = 0 lands here or in "trend only", never in "disagrees")
  disagrees            d < -2 e
A row whose numbers are missing or not finite (too few points, e.g. at the CI size) gets
"no data" with the reason; a statement that needs data we do not have gets "not testable".
Two classes say why a number is not compared:
- paper inconsistent  the paper contradicts itself on the statement (its `inconsistent` in
                      validation_paper.json says how); the row shows ours and what the
                      number's verdict against one of the paper's values would be
- not steady          a state point the row rests on (named in the row's criterion) is not
                      steady by steady.point_steadiness: a run drifting or not judged, or its
                      two starts disagreeing
Two more say why a paper-scale row (paper_scale.py) has no final verdict yet:
- running             a run the row rests on has not finished: the row shows the values so
                      far and the verdict they would give (provisional), never as final
- pending             no run the row rests on has written a row yet
A statement with `"check": "code"` tests our code, not the paper (e.g. the factor 2 of k_B T):
docs/validation.md lists it apart and leaves it out of the verdict counts."""

import json
import math
import os

from ..repo_paths import REPO
from ..student import factor

AGREES, TREND, INCONCLUSIVE, DISAGREES, NO_DATA, UNTESTABLE = (
    "agrees", "agrees in trend only", "inconclusive", "disagrees", "no data", "not testable")
PAPER_INCONSISTENT, NOT_STEADY = "paper inconsistent", "not steady"
RUNNING, PENDING = "running", "pending"
# The version of the criteria a figure record was computed with (its "criteria"): 2 is the
# measured 2 T_c/P axis for every figure, the classes above and the per-point criteria of
# Figs. 5-8; 3 the steady-state criterion of steady.py (the two quarter means, the starts
# agreeing) and the values at earlier times over the averaging window ending there; 4 the
# statistics of Method: quarter errors from the window's autocorrelation time (steady.py),
# "inconclusive" trends, A_n's error from the gap A_t^max - A_t with replicate variances
# pooled and widened (points.py), errors of Fig. 7's onsets and of Fig. 8's mean difference,
# and Fig. 5 fitted as the master curve is; records without it are older (docs/validation.md
# says so under the figure).
CRITERIA = 4
# Every verdict, in the order of the page's counts.
VERDICTS = (AGREES, TREND, INCONCLUSIVE, DISAGREES, PAPER_INCONSISTENT, NOT_STEADY, NO_DATA,
            UNTESTABLE)

PAPER_FILE = os.path.join(REPO, "scripts", "validation_paper.json")


def paper():
    """The paper's statements, keyed by id (scripts/validation_paper.json)."""
    with open(PAPER_FILE) as f:
        return {s["id"]: s for s in json.load(f)["statements"]}


def finite(*values):
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)


def value_verdict(ours, err, p, tol, trend_holds=None, dof=None):
    """The verdict of a number against the paper's p +- tol; "2 errors" is student.factor(dof)
    errors for an error with dof degrees of freedom (2 without)."""
    if not finite(ours, p, tol):
        return NO_DATA
    e = err if finite(err) else 0.0
    if abs(ours - p) <= tol + factor(dof) * e:
        return AGREES
    return TREND if trend_holds else DISAGREES


def trend_verdict(d, e, dof=None):
    """The verdict of a difference the paper says is positive (2 errors: as value_verdict)."""
    if not finite(d):
        return NO_DATA
    k = factor(dof) * (e if finite(e) else 0.0)
    if d > k:
        return AGREES
    if d > 0:
        return TREND
    return INCONCLUSIVE if d >= -k else DISAGREES


def fmt(v, err=None, digits=3):
    """"0.52 +- 0.03" / "0.52" / "n/a"."""
    if not finite(v):
        return "n/a"
    text = "%.*g" % (digits, v)
    if err is not None and finite(err) and err > 0:
        text += " +- %.2g" % err
    return text


def fmt_temperature(x, err=None):
    """A temperature k_B T/(P sigma^3) given in the paper's convention (2 T_c) in both
    conventions: "2T_c/P = 0.3 (T_c/P = 0.15)"."""
    half = err / 2 if err is not None and finite(err) else None
    return "2T_c/P = %s (T_c/P = %s)" % (fmt(x, err), fmt(x / 2 if finite(x) else x, half))


def row(statement_id, ours, verdict, why, data=None, unsteady=None):
    """One row of the side-by-side table: the paper's statement (by id), ours as text, the
    verdict, the reason (with the criterion's numbers) and the raw numbers. `unsteady`: the
    names of the state points the row rests on that are not steady (then "not steady");
    a statement the paper contradicts itself on gets "paper inconsistent" (paper_verdict)."""
    s = paper()[statement_id]
    if unsteady:
        why += "; not steady: %s" % ", ".join(unsteady)
        verdict = NOT_STEADY
    verdict, why = paper_verdict(s, verdict, why)
    return {"id": statement_id, "figure": s["figure"], "paper": s["text"],
            "source": s["source"], "ours": ours, "verdict": verdict, "why": why,
            "data": data or {}}


def paper_verdict(statement, verdict, why):
    """(verdict, why) of a row by the statement's class: where the paper contradicts itself
    (`inconsistent`), a number's verdict becomes "paper inconsistent" and the reason keeps
    what it would have been. Idempotent, so that records written before a class existed read
    the same (docs/validation.md is regenerated from them)."""
    if statement.get("inconsistent") and verdict not in (NO_DATA, UNTESTABLE, NOT_STEADY,
                                                          PAPER_INCONSISTENT, RUNNING, PENDING):
        return PAPER_INCONSISTENT, "%s; against %s alone: %s" % (
            statement["inconsistent"], statement.get("compared", "the paper's value"), verdict)
    return verdict, why


def is_code_check(statement_id):
    """True for a statement that checks our code, not the paper (`"check": "code"`)."""
    return paper().get(statement_id, {}).get("check") == "code"


def all_of(verdicts):
    """One verdict for a statement that must hold at every point: no data if none has data;
    agrees if every point with data agrees; disagrees if one disagrees; else inconclusive if
    one is; else trend only."""
    vs = [v for v in verdicts if v != NO_DATA]
    if not vs:
        return NO_DATA
    if all(v == AGREES for v in vs):
        return AGREES
    for worst in (DISAGREES, INCONCLUSIVE):
        if worst in vs:
            return worst
    return TREND


def log_verdict(ours, err, p, within, trend_holds=None, dof=None):
    """The verdict of a positive number against the paper's p within a factor `within`
    (plus 2 errors, on a log scale; 2 errors as value_verdict)."""
    if not finite(ours, p, within) or ours <= 0 or p <= 0:
        return NO_DATA
    e = err / ours / math.log(10) if finite(err) else 0.0
    if abs(math.log10(ours / p)) <= math.log10(within) + factor(dof) * e:
        return AGREES
    return TREND if trend_holds else DISAGREES


def range_verdict(values, low, high):
    """All of `values` (value, error) within [low, high] up to 2 errors: agrees; some: trend
    only; none: disagrees."""
    vals = [(v, e if finite(e) else 0.0) for v, e in values if finite(v)]
    if not vals:
        return NO_DATA
    inside = [low - 2 * e <= v <= high + 2 * e for v, e in vals]
    return AGREES if all(inside) else (TREND if any(inside) else DISAGREES)
