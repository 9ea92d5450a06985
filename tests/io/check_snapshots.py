#!/usr/bin/env python3
"""Independent check of the output layer's files (docs/output_formats.md).

Parses, with the Python standard library only, what tests/io/write_frames.cpp wrote into DIR
and checks every documented field: the extended XYZ header (Lattice, Origin, Properties, pbc,
Time, Step) and rows, the trajectory file, the adipocyte and sphere .vtp files (counts,
connectivity, offsets, array names and types, closed outward meshes, shape parameters), the
.pvd indexes, the checkpoint container (magic, version, length, CRC-32 via zlib, sections)
and the slice SVG.  Usage: check_snapshots.py DIR
"""
import math
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

PROPERTIES = "species:S:1:pos:R:3:radius:R:1:velo:R:3:orient:R:3"
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def read_expected(path):
    facts = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.partition("=")
            facts[key.strip()] = value.strip()
    return facts


def comment_pairs(line):
    """key=value and key="value with spaces" pairs of an extended XYZ comment line."""
    return {m.group(1): (m.group(3) if m.group(3) is not None else m.group(4))
            for m in re.finditer(r'(\w+)=("([^"]*)"|(\S+))', line)}


def check_xyz_frame(lines, where, exp, step, time):
    """Checks one frame starting at lines[0]; returns (rows, number of lines used)."""
    lo = [float(v) for v in exp["box_lo"].split()]
    hi = [float(v) for v in exp["box_hi"].split()]
    n = int(lines[0])
    check(n == int(exp["n_cells"]), f"{where}: {n} particles")
    kv = comment_pairs(lines[1])
    lattice = [float(v) for v in kv.get("Lattice", "").split()]
    want = [hi[0] - lo[0], 0, 0, 0, hi[1] - lo[1], 0, 0, 0, hi[2] - lo[2]]
    check(lattice == want, f"{where}: Lattice {lattice} != {want}")
    check([float(v) for v in kv.get("Origin", "").split()] == lo, f"{where}: Origin")
    check(kv.get("Properties") == PROPERTIES, f"{where}: Properties={kv.get('Properties')}")
    check(kv.get("pbc") == "F T T", f"{where}: pbc={kv.get('pbc')}")
    check(kv.get("Step") == str(step), f"{where}: Step={kv.get('Step')}, expected {step}")
    check(float(kv.get("Time", "nan")) == time, f"{where}: Time={kv.get('Time')}")
    rows = []
    for k, line in enumerate(lines[2:2 + n]):
        cols = line.split()
        if not check(len(cols) == 11, f"{where}: row {k} has {len(cols)} columns"):
            continue
        check(cols[0] == "C", f"{where}: row {k} species {cols[0]}")
        x = [float(v) for v in cols[1:]]
        pos, radius, orient = x[0:3], x[3], x[7:10]
        check(radius in (0.45, 0.55), f"{where}: row {k} radius {radius}")
        for a in (1, 2):
            check(lo[a] <= pos[a] < hi[a], f"{where}: row {k} not wrapped on axis {a}")
        norm = math.sqrt(sum(c * c for c in orient))
        check(abs(norm - 1) < 1e-12 or norm == 0, f"{where}: row {k} orientation norm {norm}")
        rows.append(cols)
    return rows, n + 2


def data_array(parent, name):
    for a in parent.findall("DataArray"):
        if a.get("Name") == name:
            return a
    failures.append(f"no DataArray {name}")
    return None


def values(array, cast=float):
    return [cast(v) for v in array.text.split()] if array is not None and array.text else []


def check_field_data(poly, where, exp, step, time):
    fd = poly.find("FieldData")
    if not check(fd is not None, f"{where}: no FieldData"):
        return
    check(values(data_array(fd, "TimeValue")) == [time], f"{where}: TimeValue")
    check(values(data_array(fd, "step"), int) == [step], f"{where}: step")
    check(values(data_array(fd, "box_lo")) == [float(v) for v in exp["box_lo"].split()],
          f"{where}: box_lo")
    check(values(data_array(fd, "box_hi")) == [float(v) for v in exp["box_hi"].split()],
          f"{where}: box_hi")
    check(values(data_array(fd, "periodic"), int) == [0, 1, 1], f"{where}: periodic")


def piece_of(path, where):
    root = ET.parse(path).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "PolyData", f"{where}: not PolyData")
    poly = root.find("PolyData")
    pieces = poly.findall("Piece")
    check(len(pieces) == 1, f"{where}: {len(pieces)} pieces")
    return poly, pieces[0]


def check_array(array, where, vtk_type, components, count):
    check(array.get("type") == vtk_type, f"{where}: {array.get('Name')} type {array.get('type')}")
    check(array.get("format") == "ascii", f"{where}: {array.get('Name')} not ascii")
    check(int(array.get("NumberOfComponents", "1")) == components,
          f"{where}: {array.get('Name')} components")
    v = values(array)
    check(len(v) == count * components, f"{where}: {array.get('Name')} has {len(v)} values")
    return v


def mesh_volume_area(points, tris):
    vol = area = 0.0
    c = [sum(p[a] for p in points) / len(points) for a in range(3)]
    for t in tris:
        a, b, d = ([points[i][k] - c[k] for k in range(3)] for i in t)
        cross = [b[1] * d[2] - b[2] * d[1], b[2] * d[0] - b[0] * d[2], b[0] * d[1] - b[1] * d[0]]
        vol += sum(a[k] * cross[k] for k in range(3)) / 6
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [d[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0]]
        area += 0.5 * math.sqrt(sum(x * x for x in n))
    return vol, area


def check_adipocytes(path, exp, step, time):
    where = os.path.basename(path)
    nb, nv, nf = int(exp["n_bodies"]), int(exp["vertices_per_body"]), int(exp["faces_per_body"])
    poly, piece = piece_of(path, where)
    check_field_data(poly, where, exp, step, time)
    n_points, n_polys = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfPolys"))
    check(n_points == nb * nv, f"{where}: NumberOfPoints {n_points}")
    check(n_polys == nb * nf, f"{where}: NumberOfPolys {n_polys}")
    check(int(piece.get("NumberOfVerts", "0")) == 0, f"{where}: NumberOfVerts")
    pts = check_array(piece.find("Points").find("DataArray"), where, "Float64", 3, n_points)
    points = [pts[3 * i:3 * i + 3] for i in range(n_points)]
    radius = check_array(data_array(piece.find("PointData"), "radius"), where, "Float64", 1,
                         n_points)
    check(all(r == 1.0 for r in radius), f"{where}: vertex radii must be 1 (diameter 2)")
    polys = piece.find("Polys")
    conn = values(data_array(polys, "connectivity"), int)
    offsets = values(data_array(polys, "offsets"), int)
    check(offsets == [3 * (k + 1) for k in range(n_polys)], f"{where}: offsets")
    check(len(conn) == 3 * n_polys, f"{where}: connectivity length {len(conn)}")
    check(all(0 <= i < n_points for i in conn), f"{where}: connectivity out of range")
    cd = piece.find("CellData")
    body = [int(v) for v in check_array(data_array(cd, "adipocyte"), where, "Int32", 1, n_polys)]
    shape = check_array(data_array(cd, "shape_parameter"), where, "Float64", 1, n_polys)
    lo = [float(v) for v in exp["box_lo"].split()]
    hi = [float(v) for v in exp["box_hi"].split()]
    for b in range(nb):
        tris = [tuple(conn[3 * k:3 * k + 3]) for k in range(n_polys) if body[k] == b]
        check(len(tris) == nf, f"{where}: body {b} has {len(tris)} triangles")
        check(all(nv * b <= i < nv * (b + 1) for t in tris for i in t),
              f"{where}: body {b} uses points of another body")
        # Closed and consistently oriented: every directed edge once, its reverse once.
        directed = [(t[k], t[(k + 1) % 3]) for t in tris for k in range(3)]
        check(len(set(directed)) == len(directed) and
              all((q, p) in set(directed) for p, q in directed), f"{where}: body {b} not closed")
        vol, area = mesh_volume_area(points, tris)
        check(vol > 0, f"{where}: body {b} volume {vol} (faces must point outward)")
        a0 = area ** 1.5 / (6 * math.sqrt(math.pi) * vol)
        s = {shape[k] for k in range(n_polys) if body[k] == b}
        check(len(s) == 1 and abs(s.pop() - a0) < 1e-9 * a0, f"{where}: body {b} shape parameter")
        c = [sum(points[i][a] for i in range(nv * b, nv * (b + 1))) / nv for a in range(3)]
        check(all(lo[a] <= c[a] < hi[a] for a in (1, 2)), f"{where}: body {b} centroid {c}")
        span = max(points[i][1] for i in range(nv * b, nv * (b + 1))) - \
            min(points[i][1] for i in range(nv * b, nv * (b + 1)))
        check(span < 0.5 * (hi[1] - lo[1]), f"{where}: body {b} is not whole (y span {span})")


def check_spheres(path, exp, step, time, xyz_rows):
    where = os.path.basename(path)
    poly, piece = piece_of(path, where)
    check_field_data(poly, where, exp, step, time)
    n = int(exp["n_cells"])
    check(int(piece.get("NumberOfPoints")) == n, f"{where}: NumberOfPoints")
    check(int(piece.get("NumberOfVerts")) == n, f"{where}: NumberOfVerts")
    check(int(piece.get("NumberOfPolys", "0")) == 0, f"{where}: NumberOfPolys")
    verts = piece.find("Verts")
    check(values(data_array(verts, "connectivity"), int) == list(range(n)), f"{where}: verts")
    check(values(data_array(verts, "offsets"), int) == list(range(1, n + 1)), f"{where}: offsets")
    pd = piece.find("PointData")
    radius = check_array(data_array(pd, "radius"), where, "Float64", 1, n)
    vel = check_array(data_array(pd, "velocity"), where, "Float64", 3, n)
    orient = check_array(data_array(pd, "orientation"), where, "Float64", 3, n)
    pts = check_array(piece.find("Points").find("DataArray"), where, "Float64", 3, n)
    for i, row in enumerate(xyz_rows):  # the same values as the XYZ file, exactly
        x = [float(v) for v in row[1:]]
        check(pts[3 * i:3 * i + 3] == x[0:3] and radius[i] == x[3] and
              vel[3 * i:3 * i + 3] == x[4:7] and orient[3 * i:3 * i + 3] == x[7:10],
              f"{where}: cell {i} differs from the XYZ file")


def check_pvd(path, kind, steps, times, snaps):
    where = os.path.basename(path)
    root = ET.parse(path).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "Collection", f"{where}: not a Collection")
    sets = root.find("Collection").findall("DataSet")
    check([float(d.get("timestep")) for d in sets] == times, f"{where}: timesteps")
    check([d.get("file") for d in sets] == [f"{kind}_{s:09d}.vtp" for s in steps],
          f"{where}: files")
    for d in sets:
        check(os.path.isfile(os.path.join(snaps, d.get("file"))), f"{where}: {d.get('file')}")
        check(d.get("part") == "0", f"{where}: part")


def check_checkpoint(path, exp):
    where = os.path.basename(path)
    data = open(path, "rb").read()
    check(data[:11] == b"INVASIMCKPT", f"{where}: magic")
    version, total, count = struct.unpack_from("<IQI", data, 11)
    check(version == 3, f"{where}: version {version}")
    check(total == len(data), f"{where}: length field {total} for {len(data)} bytes")
    crc, = struct.unpack_from("<I", data, len(data) - 4)
    check(crc == zlib.crc32(data[:-4]), f"{where}: CRC-32")
    sections, at = {}, 27
    for _ in range(count):
        nlen, = struct.unpack_from("<I", data, at)
        name = data[at + 4:at + 4 + nlen].decode()
        at += 4 + nlen
        kind, length = struct.unpack_from("<BQ", data, at)
        at += 9
        sections[name] = (kind, data[at:at + length])
        at += length
    check(at == len(data) - 4, f"{where}: section table does not end at the checksum")
    n = int(exp["n_sites"])
    for name, kind, size in [("system.sites.pos", 8, 24 * n), ("system.sites.image", 9, 12 * n),
                             ("system.sites.kind", 6, 4 * n), ("system.time", 1, 8),
                             ("system.step", 2, 8), ("tethers.a", 6, 8),
                             ("tethers.rest_length", 5, 16), ("pressure_wall.pressure", 1, 8)]:
        if check(name in sections, f"{where}: no section {name}"):
            check(sections[name][0] == kind and len(sections[name][1]) == size,
                  f"{where}: section {name} type {sections[name][0]} size {len(sections[name][1])}")
    if "pressure_wall.pressure" in sections:
        check(struct.unpack("<d", sections["pressure_wall.pressure"][1])[0] == 1.3e-3,
              f"{where}: pressure")
    if "system.step" in sections:
        check(struct.unpack("<Q", sections["system.step"][1])[0] == int(exp["steps"].split()[-1]),
              f"{where}: step")


def expected_discs(rows, exp, plane_z):
    """The discs a slice at z = plane_z must show, computed here from the XYZ rows: every cell
    the plane cuts (|z - plane_z| < r, minimum image along the periodic z axis) gives a disc of
    radius sqrt(r^2 - d^2) centred at its (x, y), plus its periodic copy along y (periodic; x
    has walls) where the disc sticks out of the box. Returns (cell, x, y, radius) tuples."""
    lo = [float(v) for v in exp["box_lo"].split()]
    hi = [float(v) for v in exp["box_hi"].split()]
    length_y, length_z = hi[1] - lo[1], hi[2] - lo[2]
    discs = []
    for k, cols in enumerate(rows):
        x, y, z, r = (float(v) for v in cols[1:5])
        d = z - plane_z
        d -= length_z * round(d / length_z)
        if abs(d) >= r:
            continue
        rho = math.sqrt(r * r - d * d)
        discs.append((k, x, y, rho))
        if y - rho < lo[1]:
            discs.append((k, x, y + length_y, rho))
        if y + rho > hi[1]:
            discs.append((k, x, y - length_y, rho))
    return discs


def check_svg(path, exp, rows):
    ns = "{http://www.w3.org/2000/svg}"
    root = ET.parse(path).getroot()
    check(root.tag == ns + "svg", "slice.svg: root is not <svg>")
    circles = [c for c in root.iter(ns + "circle") if c.get("data-cell") is not None]
    polygons = list(root.iter(ns + "polygon"))
    fills = [p for p in root.iter(ns + "path") if p.get("data-body") is not None]
    outlines = [p for p in root.iter(ns + "path") if p.get("data-outline") is not None]
    # Each adipocyte's envelope: filled in cyan, then outlined by closed loops of its own.
    check(len(outlines) >= int(exp["svg_polygons"]) > 0, f"slice.svg: {len(outlines)} outlines")
    check([p.get("data-body") for p in fills] == [p.get("data-outline") for p in outlines],
          "slice.svg: one fill per outline, same bodies")
    check(all(p.get("fill") == "#9ee9f2" for p in fills), "slice.svg: envelopes must be cyan")
    for p in outlines:
        d = p.get("d").split()
        check(d[0] == "M" and d[-1] == "Z" and d.count("M") == d.count("Z")
              and p.get("fill") == "none" and p.get("stroke") == "#00424a",
              "slice.svg: outline of body %s: closed dark loops" % p.get("data-outline"))
    check(len(circles) >= int(exp["svg_discs"]) > 0, f"slice.svg: {len(circles)} circles")
    check(len(polygons) >= int(exp["svg_polygons"]) > 0, f"slice.svg: {len(polygons)} polygons")
    check(len({c.get("data-cell") for c in circles}) == int(exp["svg_discs"]), "slice.svg: cells")
    # Every circle against the discs computed from the frame (positions in pixels: the canvas
    # maps x to 72 + (x - lo_x) s and y to 44 + (hi_y - y) s, s from the picture's width; the
    # SVG numbers have 2 decimals).
    lo = [float(v) for v in exp["box_lo"].split()]
    hi = [float(v) for v in exp["box_hi"].split()]
    scale = (float(root.get("width")) - 72.0 - 24.0) / (hi[0] - lo[0])
    want = sorted((k, round(72.0 + (x - lo[0]) * scale, 2), round(44.0 + (hi[1] - y) * scale, 2),
                   round(rho * scale, 2)) for k, x, y, rho in expected_discs(rows, exp, 5.0))
    got = sorted((int(c.get("data-cell")), float(c.get("cx")), float(c.get("cy")),
                  float(c.get("r"))) for c in circles)
    check(len({k for k, *_ in want}) == int(exp["svg_discs"]),
          "slice.svg: the renderer reports %s discs; the plane cuts %d cells"
          % (exp["svg_discs"], len({k for k, *_ in want})))
    check(len(got) == len(want) and all(
        g[0] == w[0] and max(abs(a - b) for a, b in zip(g[1:], w[1:])) < 0.015
        for g, w in zip(got, want)),
        "slice.svg: circles (cell, cx, cy, r) %s differ from the discs the plane cuts %s"
        % (got, want))
    check(all(c.get("fill") in ("#e3221c", "#fd9a4b") for c in circles),
          "slice.svg: circles must be red (active) or orange (passive)")
    check(all(p.get("fill") == "none" for p in polygons), "slice.svg: mesh sections are lines")
    texts = ["".join(t.itertext()) for t in root.iter(ns + "text")]
    check(any(t.startswith("z = 5 \u03c3, step ") and t.endswith(" \u03c4") for t in texts),
          "slice.svg: caption with the plane in sigma and the time in tau")
    check(any(g.get("id") == "legend" for g in root.iter(ns + "g")), "slice.svg: legend")
    check(any(g.get("id") == "axes" for g in root.iter(ns + "g")), "slice.svg: axes")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    exp = read_expected(os.path.join(d, "expected.txt"))
    snaps = os.path.join(d, "snaps")
    steps = [int(s) for s in exp["steps"].split()]
    times = [float(t) for t in exp["times"].split()]
    traj = open(os.path.join(snaps, "trajectory.xyz")).read().splitlines()
    rows = []
    for step, time in zip(steps, times):
        name = f"cells_{step:09d}.xyz"
        lines = open(os.path.join(snaps, name)).read().splitlines()
        rows, used = check_xyz_frame(lines, name, exp, step, time)
        check(used == len(lines), f"{name}: {len(lines) - used} extra lines")
        check(traj[:used] == lines, f"trajectory.xyz: frame of step {step} differs from {name}")
        traj = traj[used:]
        check_adipocytes(os.path.join(snaps, f"adipocytes_{step:09d}.vtp"), exp, step, time)
        check_spheres(os.path.join(snaps, f"spheres_{step:09d}.vtp"), exp, step, time, rows)
    check(traj == [], "trajectory.xyz: extra lines after the last frame")
    for kind in ("adipocytes", "spheres"):
        check_pvd(os.path.join(snaps, kind + ".pvd"), kind, steps, times, snaps)
    check(not [f for f in os.listdir(snaps) if ".tmp." in f], "temporary files left behind")
    check_checkpoint(os.path.join(d, "state.ckpt"), exp)
    check_svg(os.path.join(d, "slice.svg"), exp, rows)  # the last frame's rows
    if failures:
        print("\n".join(failures))
        sys.exit(f"{len(failures)} check(s) failed")
    print("all output files match docs/output_formats.md")


if __name__ == "__main__":
    main()
