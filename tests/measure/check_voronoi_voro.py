"""invasim's Voronoi measurement against voro++ (Debian voro++: its program and its library).

Usage: check_voronoi_voro.py INVASIM DUMP_LUA SCRATCH_DIR VORO_FACES

Runs DUMP_LUA (voronoi_dump.lua) through `INVASIM run`, which writes configurations and what
sys:voronoi{} measured on them. For each, writes the sites for voro++ with x clamped into the
walls as invasim's tessellation clamps it (docs/measurements.md, "What is tessellated"), runs
  voro++ -py -pz [-r] -c "%i %n %f" x_lo x_hi y_lo y_hi z_lo z_hi FILE
(walls at the box's x-walls, periodic y and z; -r for the radical tessellation, whose weights
(d/2)^2 are voro++'s squared radii) and VORO_FACES (voro_faces.cpp: the same container through
voro++'s library, printing the areas with 17 digits), and recomputes from each one's faces: A_t,
its two parts (cancer-adipocyte faces, cancer cells' wall faces), every adipocyte's surface
S_i and wall area, the adipocytes' wall total and A_t^max = 2 L_y L_z + sum S_i.

Tolerances, on |invasim - voro++| against the sum S of the absolute values of the areas added
(plus 1e-12 L_y L_z, for sums of no face):
- the program prints every area with "%g", 6 significant digits, within 5e-6 of it relative
  to it (half a unit in the sixth digit of a mantissa >= 1); a sum of printed areas is then
  within 5e-6 S of the exact sum. Bound 5e-6 S: the printing's, not a statistical one.
- the library's areas are doubles: both programs compute them to rounding of coordinates
  O(10) (CGAL's circumcentres in double precision, voro++'s plane cuts with its 1e-11
  tolerance), ~1e-13 of an area, so the sums agree to ~1e-13 S. Bound 1e-9 S, four orders
  above rounding and far below any real error: one face of 1e-6 sigma^2 missing or wrong in a
  sum of ~400 sigma^2 exceeds it.
Without voro++ (program or library): skipped (77), or a failure under
INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.py).
"""

import os
import shutil
import subprocess
import sys

from prerequisites import skip_test  # tests/support, on PYTHONPATH (tests/CMakeLists.txt)

PRINT_REL = 5e-6   # the voro++ program's "%g"
LIBRARY_REL = 1e-9  # voro++'s library at full precision
WALL_GAP = 1e-9    # invasim's clamp: x in [lo_x + 1e-9 L_x, hi_x - 1e-9 L_x]
LEFT_WALL, RIGHT_WALL = -1, -2  # voro++'s neighbour ids of the walls x = x_lo, x = x_hi

failures = []


def check(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def read_dump(path):
    config = {"scalar": {}, "list": {}, "sites": []}
    with open(path) as f:
        for line in f:
            w = line.split()
            if w[0] == "box":
                config["box"] = [float(x) for x in w[1:7]]
            elif w[0] == "scalar":
                config["scalar"][w[1]] = float(w[2])
            elif w[0] == "list":
                config["list"][w[1]] = [float(x) for x in w[2:]]
            elif w[0] == "site":
                config["sites"].append((int(w[1]), w[2], int(w[3]),
                                        float(w[4]), float(w[5]), float(w[6])))
                if len(w) > 7:
                    config.setdefault("radius", {})[int(w[1])] = float(w[7])
    return config


def write_sites(config, path):
    """The sites as voro++ reads them: "id x y z [r]", x clamped as invasim clamps it."""
    x_lo, x_hi = config["box"][0:2]
    gap = WALL_GAP * (x_hi - x_lo)
    radius = config.get("radius")
    with open(path, "w") as f:
        for i, _, _, x, y, z in config["sites"]:
            x = min(max(x, x_lo + gap), x_hi - gap)
            f.write("%d %.17g %.17g %.17g%s\n"
                    % (i, x, y, z, " %.17g" % radius[i] if radius else ""))


def parse_cells(lines):
    """Lines "id neighbours... areas..." -> {id: [(neighbour, area), ...]}."""
    faces = {}
    for line in lines:
        w = line.split()
        if not w:
            continue
        k = (len(w) - 1) // 2
        faces[int(w[0])] = list(zip([int(n) for n in w[1:1 + k]],
                                    [float(a) for a in w[1 + k:]]))
    return faces


def run_program(voro, config, path):
    args = ([voro, "-py", "-pz"] + (["-r"] if "radius" in config else []) + ["-c", "%i %n %f"]
            + ["%.17g" % v for v in config["box"]] + [path])
    subprocess.run(args, check=True)
    with open(path + ".vol") as f:
        return parse_cells(f)


def run_library(voro_faces, config, path):
    args = ([voro_faces] + ["%.17g" % v for v in config["box"]] + [path]
            + (["radical"] if "radius" in config else []))
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    return parse_cells(out.splitlines())


def recount(config, faces):
    """The measured quantities from voro++'s faces, each as (value, sum of |areas| added)."""
    kind = {i: k for i, k, _, _, _, _ in config["sites"]}
    body = {i: b for i, _, b, _, _, _ in config["sites"]}
    n_bodies = len(config["list"]["adipocyte_surface"])
    sums = {key: [0.0, 0.0] for key in ("cancer_adipocyte", "cancer_wall", "adipocyte_wall")}
    surface = [[0.0, 0.0] for _ in range(n_bodies)]
    wall = [[0.0, 0.0] for _ in range(n_bodies)]

    def add(acc, area):
        acc[0] += area
        acc[1] += abs(area)

    for i, cell in faces.items():
        for j, area in cell:
            wall_face = j in (LEFT_WALL, RIGHT_WALL)
            if not wall_face and j < 0:
                raise SystemExit("voro++ lists a face of site %d on wall %d" % (i, j))
            if kind[i] == "c":
                if wall_face:
                    add(sums["cancer_wall"], area)
                elif kind[j] == "v":  # cancer-adipocyte faces once, from the cancer side
                    add(sums["cancer_adipocyte"], area)
            elif wall_face:
                add(wall[body[i]], area)
                add(sums["adipocyte_wall"], area)
            elif kind[j] == "c" or body[j] != body[i]:
                add(surface[body[i]], area)
    out = dict(sums)
    out["A_t"] = [sums["cancer_adipocyte"][0] + sums["cancer_wall"][0],
                  sums["cancer_adipocyte"][1] + sums["cancer_wall"][1]]
    _, _, y_lo, y_hi, z_lo, z_hi = config["box"]
    out["A_t_max"] = [2 * (y_hi - y_lo) * (z_hi - z_lo) + sum(s[0] for s in surface),
                      sum(s[1] for s in surface)]
    out["adipocyte_surface"] = surface
    out["adipocyte_wall_area"] = wall
    return out


def compare(name, config, voro, rel):
    _, _, y_lo, y_hi, z_lo, z_hi = config["box"]
    floor = 1e-12 * (y_hi - y_lo) * (z_hi - z_lo)
    worst = 0.0
    for key in ("A_t", "cancer_adipocyte", "cancer_wall", "adipocyte_wall", "A_t_max"):
        ours = config["scalar"][key]
        value, size = voro[key]
        bound = rel * size + floor
        worst = max(worst, abs(ours - value) / bound)
        check(abs(ours - value) <= bound,
              "%s: %s = %.15g, voro++ %.15g (difference %.2e, bound %.2e)"
              % (name, key, ours, value, ours - value, bound))
    for key in ("adipocyte_surface", "adipocyte_wall_area"):
        ours = config["list"][key]
        bad = []
        for b, (mine, (value, size)) in enumerate(zip(ours, voro[key])):
            bound = rel * size + floor
            worst = max(worst, abs(mine - value) / bound)
            if abs(mine - value) > bound:
                bad.append("body %d: %.15g, voro++ %.15g" % (b, mine, value))
        check(len(ours) == len(voro[key]) and not bad,
              "%s: %s of %d adipocytes (sum %.6g) %s" % (name, key, len(ours), sum(ours),
                                                          "; ".join(bad) or "agree"))
    print("%s: largest difference %.3g of its bound" % (name, worst))


def main():
    if len(sys.argv) != 5:
        raise SystemExit(__doc__)
    invasim, dump_lua, scratch, voro_faces = sys.argv[1:5]
    voro = shutil.which("voro++")
    if not voro:
        skip_test("the voro++ program is not on the PATH", "voro++")
    if voro_faces == "none" or not os.access(voro_faces, os.X_OK):
        skip_test("voro_faces was not built: voro++'s library and headers were missing when "
                  "CMake configured the build", "voro++-dev")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    subprocess.run([invasim, "run", dump_lua, "--set", "dir=" + scratch], check=True)
    for name in ("tissue", "tissue_sizes", "near_walls", "near_walls_radical"):
        config = read_dump(os.path.join(scratch, name + ".txt"))
        x_lo, x_hi = config["box"][0:2]
        xs = [s[3] for s in config["sites"]]
        beyond = sum(1 for x in xs if x <= x_lo or x >= x_hi)
        near = sum(1 for x in xs if x_lo < x < x_lo + 0.5 or x_hi - 0.5 < x < x_hi)
        print("%s: %d sites, %d at or beyond a wall, %d within 0.5 of one"
              % (name, len(xs), beyond, near))
        if name.startswith("near_walls"):
            check(beyond >= 3, "%s: sites beyond the walls (clamped to them)" % name)
        path = os.path.join(scratch, name + ".voro")
        write_sites(config, path)
        for label, faces, rel in (
                ("voro++ program", run_program(voro, config, path), PRINT_REL),
                ("voro++ library", run_library(voro_faces, config, path), LIBRARY_REL)):
            what = "%s, %s" % (name, label)
            check(len(faces) == len(config["sites"]), "%s: every site has a cell" % what)
            compare(what, config, recount(config, faces), rel)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
