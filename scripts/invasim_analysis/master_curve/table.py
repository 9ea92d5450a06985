"""Reads the results table written by `invasim sweep collect` (results.csv).

One row per job: job_id, status, wall_seconds, the state-point keys (bare names), then the
summary averages `<name> [unit]` with `<name>_error [unit]`, `<name>_error_converged`,
`<name>_drift [unit]` and `<name>_drift_error [unit]`, then tau_d, tau_r, tau_d_unresolved.
Columns are addressed by their bare name (the ` [unit]` suffix stripped)."""

import math

from ..errors import InputError
from ..csv_header import header_entry, read_rows

BOOKKEEPING = ("job_id", "status", "wall_seconds")
# Measured columns that carry no `_error` companion and may come without a unit.
MEASURED_WITHOUT_ERROR = ("tau_d", "tau_r", "tau_d_standard", "tau_d_free", "tau_d_unresolved")


def as_number(text):
    """The float value of a state-point or measured field, None if it is not a number."""
    try:
        return float(text)
    except ValueError:
        return None


class Table:
    """The rows of results.csv as dicts {bare name: text}, with their line numbers."""

    def __init__(self, path):
        self.path = path
        lines = read_rows(path, InputError)
        self.names, self.units = [], {}
        for k, entry in enumerate(lines[0]):
            parsed = header_entry(entry)
            if parsed is None:
                raise InputError("%s: line 1, column %d: bad header entry '%s' (expected "
                                 "'name [unit]' or 'name')" % (path, k + 1, entry))
            if parsed[0] in self.units:
                raise InputError("%s: line 1: column '%s' appears twice (a state-point key "
                                 "and a measurement of the same name cannot be told apart)"
                                 % (path, parsed[0]))
            self.names.append(parsed[0])
            self.units[parsed[0]] = parsed[1]
        self.require("status", "to select the finished jobs")
        self.rows = []
        for number, fields in enumerate(lines[1:], start=2):
            if not any(x.strip() for x in fields):
                continue
            if len(fields) != len(self.names):
                raise InputError("%s: line %d has %d fields, the header has %d"
                                 % (path, number, len(fields), len(self.names)))
            row = {n: x.strip() for n, x in zip(self.names, fields)}
            row["_line"] = number
            self.rows.append(row)

    def require(self, name, why):
        """Raises InputError unless column `name` is present."""
        if name not in self.units:
            raise InputError("%s: no column '%s' (needed %s); its columns are: %s"
                             % (self.path, name, why, ", ".join(self.names)))

    def has(self, name):
        return name in self.units

    def done_rows(self):
        """The rows with status == done; InputError if there are none."""
        done = [r for r in self.rows if r["status"] == "done"]
        if not done:
            counts = {}
            for r in self.rows:
                counts[r["status"]] = counts.get(r["status"], 0) + 1
            seen = ", ".join("%d %s" % (n, s or "(empty)") for s, n in sorted(counts.items()))
            raise InputError("%s: no job has status 'done' (%s): nothing to analyse"
                             % (self.path, seen or "no rows at all"))
        return done

    def state_keys(self):
        """The state-point columns: unitless columns that are neither bookkeeping nor a
        measurement (a measurement has an `_error` companion, is one, its `_drift` or its
        `_error_converged`, or is a tau_*)."""
        names = set(self.names)
        keys = []
        for n in self.names:
            if n in BOOKKEEPING or n in MEASURED_WITHOUT_ERROR or self.units[n]:
                continue
            if n.endswith("_error") or n + "_error" in names:
                continue
            if n.endswith("_drift") and n[:-len("_drift")] + "_error" in names:
                continue
            if n.endswith("_error_converged") and n[:-len("_converged")] in names:
                continue
            keys.append(n)
        return keys

    def where(self, row):
        job = row.get("job_id", "")
        return "%s line %d%s" % (self.path, row["_line"], " (job %s)" % job if job else "")

    def number(self, row, name, why, allow_missing=False):
        """The float in `row[name]`; InputError naming file, line and column if it is not a
        finite number (an empty field gives nan when allow_missing)."""
        self.require(name, why)
        text = row[name]
        if text == "" and allow_missing:
            return math.nan
        value = as_number(text)
        if value is None or (not allow_missing and not math.isfinite(value)):
            raise InputError("%s: column '%s' = '%s' is not a finite number (needed %s)"
                             % (self.where(row), name, text, why))
        return value
