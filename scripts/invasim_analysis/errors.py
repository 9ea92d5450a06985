"""The one error of the analysis: bad or missing input, named in the message (the entry
points print it and exit 1)."""


class InputError(Exception):
    """Bad or missing input: the message names the file, the line or column, and the
    problem."""
