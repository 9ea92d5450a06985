"""invasim's Voronoi measurement against voro++ (the Debian package's command-line program).

Usage: check_voronoi_voro.py INVASIM DUMP_LUA SCRATCH_DIR [VORO++]

Runs DUMP_LUA (voronoi_dump.lua) through `INVASIM run`, which writes configurations and what
sys:voronoi{} measured on them. For each, writes the sites for voro++ with x clamped into the
walls as invasim's tessellation clamps it (docs/measurements.md, "What is tessellated"), runs
  voro++ -py -pz -c "%i %n %f" x_lo x_hi y_lo y_hi z_lo z_hi FILE
(walls at the box's x-walls, periodic y and z) and recomputes from voro++'s faces: A_t, its
two parts (cancer-adipocyte faces, cancer cells' wall faces), every adipocyte's surface S_i
and wall area, the adipocytes' wall total and A_t^max = 2 L_y L_z + sum S_i.

Tolerance: voro++ prints every face area with "%g", 6 significant digits, so each printed area
is within 5e-6 of its value relative to it (half a unit in the sixth digit of a mantissa
>= 1); a sum of printed areas is then within 5e-6 of the exact sum, relative to the sum of the
areas' absolute values. Both programs compute the areas themselves to ~1e-13 relative, far
below that. A quantity passes if |invasim - voro++| <= 5e-6 sum |a| + 1e-12 L_y L_z (the
second term for sums of no face). This is the printing's bound, not a statistical one: a
single face of area 1e-3 sigma^2 missing or wrong in a sum of ~400 sigma^2 exceeds it.
Without voro++: skipped (77), or a failure under INVASIM_REQUIRE_ALL_TESTS=1
(tests/support/prerequisites.py).
"""

import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from prerequisites import skip_test  # noqa: E402

PRINT_REL = 5e-6   # relative rounding of voro++'s "%g"
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
    return config


def run_voro(voro, config, path):
    """voro++'s faces per site: {i: [(neighbour, area), ...]}. Sites are numbered by their
    invasim index."""
    x_lo, x_hi, y_lo, y_hi, z_lo, z_hi = config["box"]
    gap = WALL_GAP * (x_hi - x_lo)
    with open(path, "w") as f:
        for i, _, _, x, y, z in config["sites"]:
            x = min(max(x, x_lo + gap), x_hi - gap)
            f.write("%d %.17g %.17g %.17g\n" % (i, x, y, z))
    args = [voro, "-py", "-pz", "-c", "%i %n %f"] + ["%.17g" % v for v in config["box"]] + [path]
    subprocess.run(args, check=True)
    faces = {}
    with open(path + ".vol") as f:
        for line in f:
            w = line.split()
            i = int(w[0])
            k = (len(w) - 1) // 2
            faces[i] = list(zip([int(n) for n in w[1:1 + k]], [float(a) for a in w[1 + k:]]))
    return faces


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


def compare(name, config, voro):
    _, _, y_lo, y_hi, z_lo, z_hi = config["box"]
    floor = 1e-12 * (y_hi - y_lo) * (z_hi - z_lo)
    worst = 0.0
    for key in ("A_t", "cancer_adipocyte", "cancer_wall", "adipocyte_wall", "A_t_max"):
        ours = config["scalar"][key]
        value, size = voro[key]
        bound = PRINT_REL * size + floor
        worst = max(worst, abs(ours - value) / bound)
        check(abs(ours - value) <= bound,
              "%s: %s = %.12g, voro++ %.12g (difference %.2e, bound %.2e)"
              % (name, key, ours, value, ours - value, bound))
    for key in ("adipocyte_surface", "adipocyte_wall_area"):
        ours = config["list"][key]
        bad = []
        for b, (mine, (value, size)) in enumerate(zip(ours, voro[key])):
            bound = PRINT_REL * size + floor
            worst = max(worst, abs(mine - value) / bound)
            if abs(mine - value) > bound:
                bad.append("body %d: %.12g, voro++ %.12g" % (b, mine, value))
        check(len(ours) == len(voro[key]) and not bad,
              "%s: %s of %d adipocytes (sum %.6g) %s" % (name, key, len(ours), sum(ours),
                                                          "; ".join(bad) or "agree"))
    print("%s: largest difference %.2f of its bound" % (name, worst))


def main():
    if len(sys.argv) not in (4, 5):
        raise SystemExit(__doc__)
    invasim, dump_lua, scratch = sys.argv[1:4]
    voro = sys.argv[4] if len(sys.argv) == 5 else shutil.which("voro++")
    if not voro or not os.access(voro, os.X_OK):
        skip_test("voro++ not found", "voro++")
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    subprocess.run([invasim, "run", dump_lua, "--set", "dir=" + scratch], check=True)
    for name in ("tissue", "near_walls"):
        config = read_dump(os.path.join(scratch, name + ".txt"))
        x_lo, x_hi = config["box"][0:2]
        xs = [s[3] for s in config["sites"]]
        beyond = sum(1 for x in xs if x <= x_lo or x >= x_hi)
        near = sum(1 for x in xs if x_lo < x < x_lo + 0.5 or x_hi - 0.5 < x < x_hi)
        print("%s: %d sites, %d at or beyond a wall, %d within 0.5 of one"
              % (name, len(xs), beyond, near))
        if name == "near_walls":
            check(beyond >= 3, "near_walls: sites beyond the walls (clamped to them)")
        faces = run_voro(voro, config, os.path.join(scratch, name + ".voro"))
        check(len(faces) == len(config["sites"]), "%s: voro++ gives every site a cell" % name)
        compare(name, config, recount(config, faces))
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
