"""Atomic writes of the analysis (scripts/invasim_analysis/atomic.py).

Usage: check_atomic.py REPO WORKDIR. Checks that
  - write_text replaces the file (a new inode; a hard link to the old file keeps the old
    bytes), through "<path>.tmp.<pid>" in the same directory, fsynced before the rename, and
    leaves no temporary file;
  - a failure while writing (text that cannot be encoded, an exception or Ctrl-C inside a
    writer's block, fsync or os.replace failing, a directory that is not writable) leaves the
    previous file byte for byte intact and no temporary file;
  - a write through a symbolic link replaces the file it points at; copy_file copies;
  - save_figure writes a valid PNG, SVG and PDF (format from the extension) and a failing
    savefig leaves the previous figure intact;
  - master_curve's tables interrupted halfway keep their previous contents;
  - no file under scripts/ writes a file other than through atomic.py (open for writing,
    savefig, savetxt, shutil.copy*, os.rename/replace), but for bath_table.py's log of a
    child process and its temporary Lua script.
Without matplotlib the figure checks are skipped (77), or fail under
INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.py)."""

import ast
import errno
import os
import shutil
import stat
import sys
import xml.etree.ElementTree as ET

from prerequisites import skip_test  # tests/support, on PYTHONPATH (tests/CMakeLists.txt)

from invasim_analysis import atomic

failures = []

OLD = b"previous,contents\n1,2\n\xc3\xa9\n"  # what a failed write must leave, byte for byte


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def fresh(name):
    """An empty directory WORK/name holding target.csv with OLD; returns (dir, target)."""
    d = os.path.join(WORK, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    target = os.path.join(d, "target.csv")
    with open(target, "wb") as f:
        f.write(OLD)
    return d, target


def read(path):
    with open(path, "rb") as f:
        return f.read()


def intact(d, target, what, names=("target.csv",)):
    """The failed write left the previous bytes and no temporary file."""
    check(read(target) == OLD, "%s: the previous file is intact byte for byte" % what)
    left = sorted(set(os.listdir(d)) - set(names))
    check(not left, "%s: no temporary file left (%s)" % (what, left or "none"))


def raises(kind, call):
    try:
        call()
    except kind:
        return True
    except BaseException as e:  # the wrong error is a failure, not a crash of the test
        print("   raised %r, expected %s" % (e, kind.__name__))
        return False
    return False


class Patched:
    """Replaces os.<name> by `function` for a with-block (atomic.py calls os.<name>)."""

    def __init__(self, name, function):
        self.name, self.function = name, function

    def __enter__(self):
        self.saved = getattr(os, self.name)
        setattr(os, self.name, self.function)

    def __exit__(self, *exc):
        setattr(os, self.name, self.saved)


def replacing():
    d, target = fresh("replace")
    new = "curve,a\nc1,0.5\n\u00e9\n"
    # A second name of the old file: writing in place would change what it shows too.
    os.link(target, os.path.join(d, "old_link.csv"))
    inode = os.stat(target).st_ino
    seen = {}
    real_fsync, real_replace = os.fsync, os.replace

    def spy_fsync(fd):
        # The first fsync is the temporary file's: the target still holds the old bytes.
        if "fsync" not in seen:
            seen["fsync"] = (read(target), sorted(os.listdir(d)))
        real_fsync(fd)

    def spy_replace(src, dst):
        seen["replace"] = (src, dst, read(src), read(target))
        real_replace(src, dst)

    with Patched("fsync", spy_fsync), Patched("replace", spy_replace):
        atomic.write_text(target, new)
    check(read(target) == new.encode("utf-8"), "write_text writes the text (UTF-8, as given)")
    check(os.stat(target).st_ino != inode and read(os.path.join(d, "old_link.csv")) == OLD,
          "write_text replaces the file (a new inode; a hard link keeps the old bytes)")
    check(sorted(os.listdir(d)) == ["old_link.csv", "target.csv"],
          "write_text leaves no temporary file: %s" % sorted(os.listdir(d)))
    tmp = target + ".tmp.%d" % os.getpid()
    check(seen.get("fsync") == (OLD, ["old_link.csv", "target.csv", os.path.basename(tmp)]),
          "the temporary file <path>.tmp.<pid> is fsynced while the target is untouched")
    src, dst, src_bytes, old_bytes = seen.get("replace", (None,) * 4)
    check(src == tmp and dst == target and src_bytes == new.encode("utf-8")
          and old_bytes == OLD,
          "the whole temporary file, in the target's directory, is renamed over the target "
          "by os.replace: %r -> %r" % (src, dst))
    # A new file, and text that is not ASCII.
    other = os.path.join(d, "new.json")
    atomic.write_text(other, "{\"\u03b2\": 1}\n")
    check(read(other) == "{\"\u03b2\": 1}\n".encode("utf-8"), "write_text creates a new file")


def failures_keep_the_old_file():
    d, target = fresh("encode")
    check(raises(UnicodeEncodeError, lambda: atomic.write_text(target, "half\udcffwritten")),
          "text that cannot be encoded raises")
    intact(d, target, "text that cannot be encoded")

    d, target = fresh("block")

    def half_a_table():
        with atomic.open_text(target) as f:
            f.write("curve,a\n" * 1000)
            f.flush()
            raise KeyError("a curve without a name")
    check(raises(KeyError, half_a_table), "an exception inside open_text's block propagates")
    intact(d, target, "an exception halfway through a table")

    d, target = fresh("interrupt")

    def interrupted():
        with atomic.open_binary(target) as f:
            f.write(b"\x89PNG half")
            raise KeyboardInterrupt
    check(raises(KeyboardInterrupt, interrupted), "Ctrl-C inside open_binary's block propagates")
    intact(d, target, "Ctrl-C halfway through a figure")

    def broken(*args):
        raise OSError(errno.EIO, "injected failure")

    d, target = fresh("fsync")
    with Patched("fsync", broken):
        check(raises(OSError, lambda: atomic.write_text(target, "new\n")),
              "a failing fsync raises")
    intact(d, target, "a failing fsync")

    d, target = fresh("rename")
    with Patched("replace", broken):
        check(raises(OSError, lambda: atomic.write_text(target, "new\n")),
              "a failing os.replace raises")
    intact(d, target, "a failing os.replace")

    d, target = fresh("copy")
    check(raises(OSError, lambda: atomic.copy_file(os.path.join(d, "missing"), target)),
          "copy_file of a missing file raises")
    intact(d, target, "copy_file of a missing file")

    # A writable file in a directory that is not: writing in place would succeed.
    if os.geteuid() == 0:
        print("ok: (not checked as root: a directory that is not writable)")
        return
    d, target = fresh("read_only_dir")
    os.chmod(d, stat.S_IRUSR | stat.S_IXUSR)
    try:
        check(raises(PermissionError, lambda: atomic.write_text(target, "new\n")),
              "write_text refuses a directory it cannot create the temporary file in")
    finally:
        os.chmod(d, stat.S_IRWXU)
    intact(d, target, "a directory that is not writable")


def links_and_copies():
    d, target = fresh("symlink")
    link = os.path.join(d, "link.csv")
    os.symlink("target.csv", link)
    atomic.write_text(link, "through the link\n")
    check(os.path.islink(link) and read(target) == b"through the link\n",
          "a write through a symbolic link replaces the file it points at, keeping the link")
    check(sorted(os.listdir(d)) == ["link.csv", "target.csv"], "no temporary file left")

    d, target = fresh("copy_ok")
    src = os.path.join(d, "source.json")
    with open(src, "wb") as f:
        f.write(b"{\"status\": \"done\"}\n" * 500)
    atomic.copy_file(src, target)
    check(read(target) == read(src), "copy_file copies the contents")
    check(sorted(os.listdir(d)) == ["source.json", "target.csv"], "no temporary file left")


def master_curve_tables():
    """write_tables failing at the second curve of fits.csv keeps the previous fits.csv."""
    from invasim_analysis.master_curve import output
    d = os.path.join(WORK, "master_curve")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    fits = os.path.join(d, "fits.csv")
    with open(fits, "wb") as f:
        f.write(OLD)
    good = {"name": "c1", "group": {"beta": 0.01}, "points": [], "varying": [],
            "tau_d_dropped": False, "plateaus": (0.0, 1.0)}
    check(raises(KeyError, lambda: output.write_tables(d, {"curves": [good, {}]}, {})),
          "master_curve's write_tables fails on a curve without a name")
    check(read(fits) == OLD and os.listdir(d) == ["fits.csv"],
          "the interrupted fits.csv keeps its previous contents, no temporary file left")


def figures():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as missing:
        skip_test("%s cannot import %s" % (sys.executable, missing.name), "python3-matplotlib")
    d = os.path.join(WORK, "figures")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([1, 2, 3], [1, 4, 9], label="$A_n$")
    ax.legend()
    png, svg, pdf = (os.path.join(d, "f." + e) for e in ("png", "svg", "pdf"))
    atomic.save_figure(fig, png, dpi=50)
    data = read(png)
    check(data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
          and int.from_bytes(data[16:20], "big") == 150
          and int.from_bytes(data[20:24], "big") == 100 and data.endswith(b"IEND\xaeB`\x82"),
          "save_figure writes a whole PNG of 150 x 100 pixels (3 x 2 in at dpi=50)")
    atomic.save_figure(fig, svg)
    root = ET.fromstring(read(svg))
    check(root.tag == "{http://www.w3.org/2000/svg}svg", "save_figure writes an SVG (.svg)")
    atomic.save_figure(fig, pdf)
    check(read(pdf).startswith(b"%PDF") and b"%%EOF" in read(pdf)[-32:],
          "save_figure writes a PDF (.pdf)")
    check(sorted(os.listdir(d)) == ["f.pdf", "f.png", "f.svg"], "no temporary file left")

    # A figure whose drawing fails halfway (the SVG backend has written its header by then).
    from matplotlib.artist import Artist

    class Broken(Artist):
        def draw(self, renderer):
            raise RuntimeError("drawing failed")

    fig.add_artist(Broken())
    before = {p: read(p) for p in (png, svg)}
    for p in (png, svg):
        check(raises(RuntimeError, lambda: atomic.save_figure(fig, p)),
              "a failing savefig raises (%s)" % os.path.basename(p))
    check(all(read(p) == b for p, b in before.items())
          and sorted(os.listdir(d)) == ["f.pdf", "f.png", "f.svg"],
          "a failing savefig leaves the previous PNG and SVG intact and no temporary file")
    plt.close(fig)


# The writers allowed outside atomic.py: (file under scripts/, enclosing function).
NOT_ATOMIC = {
    ("invasim_analysis/bath_table.py", "run"),  # a child process's log, written as it runs
    ("invasim_analysis/bath_table.py", "active_temperatures"),  # a temporary Lua script
}


def writes(node):
    """What a call writes, if it writes a file: "open(..., 'w')", "savefig", ..."""
    f = node.func
    name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
    owner = f.value.id if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) else ""
    if name in ("open", "fdopen"):
        mode = node.args[1] if len(node.args) > 1 else next(
            (k.value for k in node.keywords if k.arg == "mode"), None)
        if isinstance(mode, ast.Constant) and isinstance(mode.value, str) \
                and set(mode.value) & set("wax+"):
            return "%s(..., %r)" % (name, mode.value)
        return None
    if name in ("savefig", "savetxt", "write_bytes") or (name == "write_text" and owner != "atomic"):
        return name
    if owner == "shutil" and name.startswith("copy") or owner == "os" and name in (
            "rename", "replace"):
        return "%s.%s" % (owner, name)
    return None


def only_atomic_writes():
    scripts = os.path.join(REPO, "scripts")
    found = []
    for d, dirs, files in os.walk(scripts):
        dirs[:] = [x for x in dirs if x != "__pycache__"]
        for name in sorted(files):
            if not name.endswith(".py"):
                continue
            path = os.path.join(d, name)
            rel = os.path.relpath(path, scripts)
            if rel == "invasim_analysis/atomic.py":
                continue
            with open(path) as f:
                tree = ast.parse(f.read(), path)
            for node in ast.walk(tree):
                if isinstance(node, ast.Call) and writes(node):
                    fn = _innermost(tree, node)
                    if (rel, fn.name if fn else "") not in NOT_ATOMIC:
                        found.append("scripts/%s:%d: %s" % (rel, node.lineno, writes(node)))
    check(not found, "every file under scripts/ writes through invasim_analysis/atomic.py: %s"
          % (found or "yes"))


def _innermost(tree, target):
    """The innermost function definition holding `target` (None: module level)."""
    best = None
    for n in ast.walk(tree):
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and any(
                c is target for c in ast.walk(n)):
            if best is None or any(c is n for c in ast.walk(best)):
                best = n
    return best


def main():
    global REPO, WORK
    REPO, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(WORK, exist_ok=True)
    replacing()
    failures_keep_the_old_file()
    links_and_copies()
    master_curve_tables()
    only_atomic_writes()
    figures()
    if failures:
        print("%d check(s) FAILED" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
