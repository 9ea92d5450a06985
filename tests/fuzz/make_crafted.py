#!/usr/bin/env python3
"""Writes the crafted hostile files into tests/fuzz/regression/<target>/ from the
seed corpus that `invasim_fuzz seeds <target> DIR` writes (the project's own writers):

  make_crafted.py SEED_CHECKPOINT SEED_SPHERES_VTP OUT_DIR

Checkpoints are rebuilt section by section, with the file length and CRC-32 recomputed, as an
attacker would (the reader's checksum does not protect against a crafted file)."""
import struct
import sys
import zlib
from pathlib import Path

MAGIC = b"INVASIMCKPT"


def sections(data):
    count = struct.unpack_from("<I", data, 23)[0]
    at, out = 27, []
    for _ in range(count):
        (n,) = struct.unpack_from("<I", data, at)
        name = data[at + 4:at + 4 + n].decode()
        at += 4 + n
        kind = data[at]
        (length,) = struct.unpack_from("<Q", data, at + 1)
        at += 9
        out.append([name, kind, data[at:at + length]])
        at += length
    return out


def build(secs, version=3):
    body = b"".join(struct.pack("<I", len(n)) + n.encode() + bytes([k]) + struct.pack("<Q", len(p)) + p
                    for n, k, p in secs)
    total = 11 + 4 + 8 + 4 + len(body) + 4
    head = MAGIC + struct.pack("<IQI", version, total, len(secs))
    data = head + body
    return data + struct.pack("<I", zlib.crc32(data) & 0xFFFFFFFF)


def payload(secs, name):
    return next(s[2] for s in secs if s[0] == name)


def replaced(secs, name, payload):
    out = [list(s) for s in secs]
    for s in out:
        if s[0] == name:
            s[2] = payload
            return out
    raise KeyError(name)


def main():
    ckpt = Path(sys.argv[1]).read_bytes()
    vtp = Path(sys.argv[2]).read_text()
    out = Path(sys.argv[3])
    (out / "checkpoint").mkdir(parents=True, exist_ok=True)
    (out / "vtk").mkdir(parents=True, exist_ok=True)
    (out / "set").mkdir(parents=True, exist_ok=True)
    secs = sections(ckpt)
    files = {
        "checkpoint/box-version-2^63-1.ckpt":
            build(replaced(secs, "system.box.version", struct.pack("<Q", 2**63 - 1))),
        "checkpoint/topology-vertices-2^31-1.ckpt":
            build(replaced(secs, "system.topologies.n_vertices",
                           struct.pack("<i", 2**31 - 1) + payload(secs, "system.topologies.n_vertices")[4:])),
        "checkpoint/state-endless-loop.ckpt":
            build(replaced(secs, "extra", b"(function() while true do end end)()")),
        "checkpoint/state-string-rep-2^40.ckpt":
            build(replaced(secs, "extra", b"{[1]=('x'):rep(1 << 40)}")),
        "checkpoint/state-nested-100000.ckpt":
            build(replaced(secs, "extra", b"{[1]=" * 100000 + b"1" + b"}" * 100000)),
    }
    n = 5000
    files["vtk/nested-5000.vtp"] = ('<?xml version="1.0"?>\n<VTKFile type="PolyData">' + "<a>" * n +
                                    "</a>" * n + "</VTKFile>\n").encode()
    files["vtk/nested-5000.pvd"] = ('<?xml version="1.0"?>\n<VTKFile type="Collection"><Collection>' +
                                    "<a>" * n + "</a>" * n + "</Collection></VTKFile>\n").encode()
    # A Points DataArray with no values stating NumberOfTuples="0" in a Piece of 50000000 points:
    # the reader believed the array and read 50000000 points past its end (SIGSEGV).
    start = vtp.index("<DataArray", vtp.index("<Points>"))
    data = vtp.index(">", start) + 1
    crafted = vtp[:start + 10] + ' NumberOfTuples="0"' + vtp[start + 10:data] + vtp[vtp.index("</DataArray>", data):]
    p = crafted.index('NumberOfPoints="')
    crafted = crafted[:p] + 'NumberOfPoints="50000000"' + crafted[crafted.index('"', p + 16) + 1:]
    files["vtk/points-tuples-0-of-50000000.vtp"] = crafted.encode()
    files["set/steps-int64-max.txt"] = b"steps=9223372036854775807\nseed=18446744073709551616\ndt=1e309"
    for name, data in files.items():
        (out / name).write_bytes(data)
        print(out / name, len(data), "bytes")


main()
