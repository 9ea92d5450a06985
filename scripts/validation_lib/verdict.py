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
  disagrees            d <= 0
A row whose numbers are missing or not finite (too few points, e.g. at the CI size) gets
"no data" with the reason; a statement that needs data we do not have gets "not testable"."""

import json
import math
import os

AGREES, TREND, DISAGREES, NO_DATA, UNTESTABLE = (
    "agrees", "agrees in trend only", "disagrees", "no data", "not testable")

PAPER_FILE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                          "validation_paper.json")


def paper():
    """The paper's statements, keyed by id (scripts/validation_paper.json)."""
    with open(PAPER_FILE) as f:
        return {s["id"]: s for s in json.load(f)["statements"]}


def finite(*values):
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values)


def value_verdict(ours, err, p, tol, trend_holds=None):
    """The verdict of a number against the paper's p +- tol."""
    if not finite(ours, p, tol):
        return NO_DATA
    e = err if finite(err) else 0.0
    if abs(ours - p) <= tol + 2 * e:
        return AGREES
    return TREND if trend_holds else DISAGREES


def trend_verdict(d, e):
    """The verdict of a difference the paper says is positive."""
    if not finite(d):
        return NO_DATA
    e = e if finite(e) else 0.0
    if d > 2 * e:
        return AGREES
    return TREND if d > 0 else DISAGREES


def fmt(v, err=None, digits=3):
    """"0.52 +- 0.03" / "0.52" / "n/a"."""
    if not finite(v):
        return "n/a"
    text = "%.*g" % (digits, v)
    if err is not None and finite(err) and err > 0:
        text += " +- %.2g" % err
    return text


def row(statement_id, ours, verdict, why, data=None):
    """One row of the side-by-side table: the paper's statement (by id), ours as text, the
    verdict, the reason (with the criterion's numbers) and the raw numbers."""
    s = paper()[statement_id]
    return {"id": statement_id, "figure": s["figure"], "paper": s["text"],
            "source": s["source"], "ours": ours, "verdict": verdict, "why": why,
            "data": data or {}}


def log_verdict(ours, err, p, factor, trend_holds=None):
    """The verdict of a positive number against the paper's p within a factor `factor`
    (plus 2 errors, on a log scale)."""
    if not finite(ours, p, factor) or ours <= 0 or p <= 0:
        return NO_DATA
    e = err / ours / math.log(10) if finite(err) else 0.0
    if abs(math.log10(ours / p)) <= math.log10(factor) + 2 * e:
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
