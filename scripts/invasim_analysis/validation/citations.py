"""What docs/validation.md may cite (docs/validation.md, "Method"): a statement's source is its
place in the paper (section, figure, equation), never a file outside the repository; statement
ids, figure names and section headings use the paper's own figure numbers. scripts/validation.py
document refuses a page that breaks either rule, and the CI-size pipeline test checks the page
it made, so that a figure renumbered or a source copied from notes outside the repository
cannot reach the page unnoticed."""

import json
import re

from .verdict import PAPER_FILE

# A path outside the repository: a parent directory, the machine's work tree, the shared notes.
OUTSIDE = re.compile(r"\.\./|/work/|\bshared/|MODEL\.md")
# A place in the paper: one of these must be in every source.
PAPER_PLACE = re.compile(r"\bFig\. \d+|\bEq\. \(\d+\)|\bAppendix [A-C]\b|\bMethods\b|\bResults\b")
FIG_PROSE = re.compile(r"\bFigs?\. (\d+)")
FIG_NAME = re.compile(r"^(fig\d+[a-z]?)(?:_|$)")
HEADING = re.compile(r"^## Fig\. (\d+[a-z]?)\b")


def paper_figures(path=PAPER_FILE):
    """(the paper's figure count, the figure names a statement may compare with) from
    scripts/validation_paper.json."""
    with open(path) as f:
        data = json.load(f)
    return data["paper_figures"], set(data["figures"])


def _prose_numbers(text, count, where):
    """'Fig. N' with N beyond the paper's count."""
    return ["%s: 'Fig. %s' (the paper has Figs. 1-%d)" % (where, n, count)
            for n in FIG_PROSE.findall(text) if not 1 <= int(n) <= count]


def statement_problems(statements, count, figures):
    """Every problem of the statements (dicts with id, figure, source, and text or paper):
    an id or figure that is not one of the paper's compared figures, an id whose figure is
    not its `figure`, a source outside the repository or naming no place in the paper."""
    problems = []
    for s in statements:
        sid, fig, source = s.get("id", "?"), s.get("figure"), s.get("source") or ""
        where = "statement %s" % sid
        m = FIG_NAME.match(sid)
        if m and m.group(1) not in figures:
            problems.append("%s: id names %s, not a figure of the paper's (%s)"
                            % (where, m.group(1), ", ".join(sorted(figures))))
        elif m and m.group(1) != fig:
            problems.append("%s: id names %s but its figure is %s" % (where, m.group(1), fig))
        if fig not in figures:
            problems.append("%s: figure %r is not a figure of the paper's (%s)"
                            % (where, fig, ", ".join(sorted(figures))))
        hit = OUTSIDE.search(source)
        if hit:
            problems.append("%s: source %r cites %r, outside the repository; cite the paper "
                            "(section, figure, equation)" % (where, source, hit.group(0)))
        if not PAPER_PLACE.search(source):
            problems.append("%s: source %r names no place in the paper (Fig. N, Eq. (N), "
                            "Appendix, Methods or Results)" % (where, source))
        for key in ("source", "text", "paper"):
            problems += _prose_numbers(s.get(key) or "", count, "%s %s" % (where, key))
    return problems


def page_problems(text, count, figures):
    """Every problem of a generated page: a path outside the repository anywhere in it, a
    section heading 'Fig. N' that is not a compared figure, a 'Fig. N' beyond the paper's."""
    problems = []
    for k, line in enumerate(text.split("\n"), 1):
        where = "page line %d" % k
        hit = OUTSIDE.search(line)
        if hit:
            problems.append("%s cites %r, outside the repository: %s" % (where, hit.group(0), line[:120]))
        m = HEADING.match(line)
        if m and "fig" + m.group(1) not in figures:
            problems.append("%s: section 'Fig. %s' is not a figure of the paper's (%s)"
                            % (where, m.group(1), ", ".join(sorted(figures))))
        problems += _prose_numbers(line, count, where)
    return problems
