"""State-point bookkeeping: the values of keys in a row (or supplied with --fixed), the
selector of the normalisation group (`K_ecm=0,lambda=0`) and grouping of rows by keys."""

from ..errors import InputError
from .table import as_number


def parse_assignments(text, option):
    """`K=V,K2=V2` -> [(K, V), ...]; InputError naming the option on a malformed entry."""
    pairs = []
    for item in (text or "").split(","):
        if not item.strip():
            continue
        key, sep, value = item.partition("=")
        if not sep or not key.strip() or not value.strip():
            raise InputError("%s: '%s' is not KEY=VALUE (e.g. %s K_ecm=0)"
                             % (option, item.strip(), option))
        pairs.append((key.strip(), value.strip()))
    return pairs


def parse_limits(text, option):
    """`L_x=0.05,A_t=0.1` -> [("L_x", 0.05), ...]; `none` -> []; InputError naming the option
    if a limit is not a number >= 0."""
    if (text or "").strip().lower() == "none":
        return []
    limits = []
    for key, value in parse_assignments(text, option):
        limit = as_number(value)
        if limit is None or not limit >= 0 or limit == float("inf"):
            raise InputError("%s: %s=%s: the limit must be a finite number >= 0 (a fraction "
                             "of the mean, e.g. %s %s=0.05)" % (option, key, value, option, key))
        limits.append((key, limit))
    return limits


def parse_keys(text):
    """`beta,tau_p` -> ['beta', 'tau_p'] (empty text: [])."""
    return [k.strip() for k in (text or "").split(",") if k.strip()]


def same_value(a, b):
    """Two state-point values are equal as numbers if both are numbers, else as text."""
    x, y = as_number(a), as_number(b)
    if x is not None and y is not None:
        return x == y
    return a == b


def canonical(text):
    """A value as a grouping label: numbers in Python's shortest repr (1 and 1.0 are equal),
    other text as is."""
    x = as_number(text)
    if x is None:
        return text
    return repr(int(x)) if x.is_integer() and abs(x) < 1e15 else repr(x)


class Keys:
    """Looks up state-point values in a row, falling back on the --fixed values."""

    def __init__(self, table, state_keys, fixed):
        self.table, self.state_keys, self.fixed = table, list(state_keys), dict(fixed)

    def known(self, key):
        return key in self.state_keys or key in self.fixed

    def check(self, keys, option):
        """InputError unless every key is a state-point column of the table."""
        for k in keys:
            if k not in self.state_keys:
                what = ("a measured column, not a state-point key" if self.table.has(k)
                        else "not a column of %s" % self.table.path)
                raise InputError("%s: '%s' is %s; the state-point keys are: %s"
                                 % (option, k, what, ", ".join(self.state_keys) or "(none)"))

    def text(self, row, key):
        return row[key] if key in self.state_keys else self.fixed[key]

    def number(self, row, key, why):
        """The value of `key` (column or --fixed) as a float, InputError if it is absent or
        not a number."""
        if not self.known(key):
            raise InputError("%s has no state-point column '%s' (needed %s); give it with "
                             "--fixed %s=VALUE" % (self.table.path, key, why, key))
        value = as_number(self.text(row, key))
        if value is None:
            where = self.table.where(row) if key in self.state_keys else "--fixed"
            raise InputError("%s: '%s' = '%s' is not a number (needed %s)"
                             % (where, key, self.text(row, key), why))
        return value

    def label(self, row, keys):
        """A tuple of canonical values of `keys` in `row` (grouping key)."""
        return tuple(canonical(self.text(row, k)) for k in keys)


def matches(keys, row, selector):
    """True if the row has every key = value of the selector."""
    return all(same_value(keys.text(row, k), v) for k, v in selector)


def group_indices(labels):
    """{label: [row indices]} in order of first appearance."""
    groups = {}
    for i, lab in enumerate(labels):
        groups.setdefault(lab, []).append(i)
    return groups
