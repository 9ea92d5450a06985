"""The CSV files of a run and of a sweep (series.csv, results.csv): their rows, and a header
entry `name [unit]` split into its name and unit. Python standard library only."""

import csv
import re


def header_entry(entry):
    """`name [unit]` -> (name, unit); `name` -> (name, ""); None when it has no name."""
    m = re.fullmatch(r"\s*([^\[\]]*?)\s*(?:\[([^\]]*)\])?\s*", entry)
    if not m or not m.group(1):
        return None
    return m.group(1), (m.group(2) or "").strip()


def read_rows(path, error):
    """The rows of the CSV file `path` (lists of fields), the header first; raises `error`
    (an exception class) naming the file when it cannot be read or has no header row."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise error("cannot read %s: %s" % (path, e.strerror or e))
    if not rows or not any(field.strip() for field in rows[0]):
        raise error("%s is empty (no header row)" % path)
    return rows
