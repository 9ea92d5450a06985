"""Paths as the validation page and plans show them: inside this repository, never a path
of the machine that ran the campaign (scripts/check_citations.sh refuses those)."""
import os

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def repo_path(path, outside=None):
    """`path` relative to the repository when it lies inside it. A file under another
    checkout's protocols/ (a campaign's own clone) is shown as the same file of this
    repository when that exists. Any other path is shown as `outside` (a name for it on the
    page, e.g. "ROOT"), or as given when `outside` is None."""
    if not os.path.isabs(path) and not os.path.exists(path):
        return path  # already as recorded (a plan made elsewhere)
    full = os.path.abspath(path)
    rel = os.path.relpath(full, REPO)
    if not rel.startswith(os.pardir):
        return rel
    parts = os.path.normpath(full).split(os.sep)
    if "protocols" in parts:
        k = len(parts) - 1 - parts[::-1].index("protocols")
        inside = os.path.join(*parts[k:])
        if os.path.exists(os.path.join(REPO, inside)):
            return inside
    return outside if outside is not None else path
