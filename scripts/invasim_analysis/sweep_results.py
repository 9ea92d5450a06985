"""Keeps a sweep's finished points small enough to commit, and puts them back.

Usage:
  sweep_results.py save WS DEST      copy every done point of workspace WS (its statepoint,
                                     job document and result files; no checkpoints, snapshots
                                     or locks) to DEST/<job id>/, replacing what DEST held for
                                     those points
  sweep_results.py restore DEST WS   copy the points kept in DEST into workspace WS (made by
                                     `invasim sweep init` from the same sweep file), so that
                                     `invasim sweep run WS` skips them and the analysis reads
                                     them as done

A campaign that spans machines (a session's machine may be replaced, taking the workspace
with it) saves after each sweep run and restores into a fresh workspace before running again;
only the points still unfinished are then redone. A restored point whose statepoint differs
from the workspace's point of the same id is refused: the sweep file changed.
"""

import os
import sys

from . import atomic, workspace

KEPT_SUFFIXES = (".json", ".csv", ".txt", ".log")
SKIPPED_NAMES = {"run.lock", ".lock", "resume.txt"}


class UsageError(Exception):
    pass


def job_status(job_dir):
    return workspace.document(job_dir).get("status")


def read_statepoint(job_dir):
    return workspace.statepoint(job_dir)


def workspace_jobs(ws):
    root = os.path.join(ws, "workspace")
    if not os.path.isfile(os.path.join(ws, "invasim_sweep.json")) or not os.path.isdir(root):
        raise UsageError("%s is not a sweep workspace (no invasim_sweep.json and workspace/): "
                         "make it with `invasim sweep init SPEC --workspace %s`" % (ws, ws))
    return root, sorted(os.listdir(root))


def kept_files(job_dir):
    """The small regular files of a job directory that carry its results."""
    for name in sorted(os.listdir(job_dir)):
        path = os.path.join(job_dir, name)
        if name in SKIPPED_NAMES or not os.path.isfile(path) or os.path.islink(path):
            continue
        if name.endswith(KEPT_SUFFIXES):
            yield name, path


def copy_atomically(src, dest_dir, name):
    """Copies src to dest_dir/name through a temporary file renamed into place (atomic.py):
    an interrupted save or restore leaves each file whole, old or new."""
    atomic.copy_file(src, os.path.join(dest_dir, name))


def save(ws, dest):
    root, ids = workspace_jobs(ws)
    os.makedirs(dest, exist_ok=True)
    saved = 0
    for job_id in ids:
        job_dir = os.path.join(root, job_id)
        if job_status(job_dir) != "done":
            continue
        target = os.path.join(dest, job_id)
        os.makedirs(target, exist_ok=True)
        for name, path in kept_files(job_dir):
            copy_atomically(path, target, name)
        saved += 1
    print("sweep_results: saved %d done point(s) of %s to %s" % (saved, ws, dest))
    return saved


def restore(dest, ws):
    root, ids = workspace_jobs(ws)
    if not os.path.isdir(dest):
        raise UsageError("%s: no such directory of saved points" % dest)
    known = set(ids)
    restored = 0
    for job_id in sorted(os.listdir(dest)):
        kept = os.path.join(dest, job_id)
        if not os.path.isdir(kept):
            continue
        if job_id not in known:
            raise UsageError("%s: point %s is not in workspace %s (another sweep file, or its "
                             "axes changed)" % (dest, job_id, ws))
        job_dir = os.path.join(root, job_id)
        if read_statepoint(kept) != read_statepoint(job_dir):
            raise UsageError("%s: point %s has another statepoint than in %s" %
                             (dest, job_id, ws))
        if job_status(job_dir) == "done":
            continue
        if job_status(kept) != "done":
            raise UsageError("%s: point %s was not saved as done" % (dest, job_id))
        for name, path in kept_files(kept):
            copy_atomically(path, job_dir, name)
        restored += 1
    print("sweep_results: restored %d done point(s) from %s into %s" % (restored, dest, ws))
    return restored


def main(argv):
    if len(argv) != 4 or argv[1] not in ("save", "restore"):
        sys.stderr.write(__doc__)
        return 2
    try:
        if argv[1] == "save":
            save(argv[2], argv[3])
        else:
            restore(argv[2], argv[3])
    except (UsageError, OSError, ValueError) as e:
        sys.stderr.write("sweep_results: error: %s\n" % e)
        return 1
    return 0
