"""Atomic file writes: every file the analysis writes goes through here, so that an
interrupted run (Ctrl-C, a killed job, a full disk, an exception halfway through a table)
never leaves a truncated or half-written file in place of a good one.

A write goes to "<path>.tmp.<pid>" in the target's directory (the name the C++ side uses,
src/io/atomic_file.cpp, so `invasim.remove_temporaries` finds one a killed process left),
which is flushed, fsynced and then renamed over the target with os.replace (atomic on one
file system); the directory is fsynced after the rename. On any failure, KeyboardInterrupt
included, the temporary file is removed and the target keeps its previous contents. A
process killed by a signal (SIGTERM, SIGKILL) or a power loss can leave a temporary file
behind, never a half-written target.

  write_text(path, text)            a whole text at once (UTF-8, written as given)
  open_text(path) / open_binary(path)
                                    a context manager for writers (csv.writer, json.dump):
                                    the target is replaced when the block ends normally
  copy_file(src, path)              a copy of src's contents
  save_figure(fig, path, **kw)      a matplotlib figure, its format from path's extension

Needs the standard library only (save_figure: the figure's own matplotlib)."""

import contextlib
import errno
import os
import shutil

TEMPORARY_MARK = ".tmp."


def temporary_path(path):
    """The temporary file of this process for `path`: "<path>.tmp.<pid>", same directory."""
    return "%s%s%d" % (path, TEMPORARY_MARK, os.getpid())


def _target(path):
    """The file to replace: `path` with symbolic links resolved, so that writing to a link
    replaces the file it points at (as writing in place did) and keeps the link."""
    return os.path.realpath(os.fspath(path))


def _sync_directory(directory):
    """Makes the rename durable. Some file systems refuse fsync on a directory (EINVAL,
    EROFS); the rename has happened all the same, so that is not an error."""
    try:
        fd = os.open(directory or ".", os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError as e:
        if e.errno not in (errno.EINVAL, errno.EROFS):
            raise
    finally:
        os.close(fd)


@contextlib.contextmanager
def _replacing(path, mode, **open_kwargs):
    """Yields a file object (os.fdopen(fd, mode, **open_kwargs)) writing the temporary file
    of `path`; when the block ends normally it is flushed, fsynced, closed and renamed over
    `path`. If the block raises, or any step fails, the temporary file is removed, `path` is
    left as it was and the error propagates."""
    target = _target(path)
    tmp = temporary_path(target)
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_CLOEXEC", 0),
                 0o644)
    try:
        with os.fdopen(fd, mode, **open_kwargs) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise
    _sync_directory(os.path.dirname(target))


def open_binary(path):
    """A context manager yielding a binary file whose contents replace `path` atomically
    when the block ends normally; if it raises, `path` is left as it was."""
    return _replacing(path, "wb")


def open_text(path, encoding="utf-8", newline=""):
    """open_binary as text, for writers that stream into a file (csv.writer, json.dump).
    UTF-8; newline="": "\\n" is written as "\\n" (csv.writer with lineterminator="\\n")."""
    return _replacing(path, "w", encoding=encoding, newline=newline)


def write_text(path, text, encoding="utf-8"):
    """Replaces `path` by `text` atomically (see the module's docstring)."""
    with open_text(path, encoding=encoding) as f:
        f.write(text)


def copy_file(src, path):
    """Replaces `path` by a copy of the contents of `src` atomically (not its mode or times,
    as shutil.copyfile)."""
    with open(src, "rb") as source, open_binary(path) as f:
        shutil.copyfileobj(source, f)


def save_figure(fig, path, **savefig_kwargs):
    """fig.savefig to `path` atomically, in the format of path's extension (.png, .svg,
    .pdf, ...; matplotlib's savefig.format without one) unless format= is given: the
    temporary file's name ends in .tmp.<pid>, from which matplotlib cannot tell it."""
    if "format" not in savefig_kwargs:
        ext = os.path.splitext(os.fspath(path))[1]
        if ext:
            savefig_kwargs["format"] = ext[1:].lower()
        else:
            import matplotlib
            savefig_kwargs["format"] = matplotlib.rcParams["savefig.format"]
    with open_binary(path) as f:
        fig.savefig(f, **savefig_kwargs)
