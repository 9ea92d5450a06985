#!/usr/bin/env python3
"""Generates the force regression files tests/regression/*.force.

The references are computed here, independently of the engine's C++ code, straight from the
formulas of the model (docs/model.md: bodies, pair forces, walls, ECM tethers), including
its rule for coincident sites: pair sums over all pairs with the minimum image, wall terms,
mesh volume/area energies with their analytic gradient (checked here against central finite
differences), tethers between vertex centroids. Sums use math.fsum (correctly rounded).
Plain python3, no numpy.

Run once after a deliberate physics change:  python3 tests/regression/generate.py
The runner (tests/regression/runner.cpp) compares the engine against these files.
"""
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


# ---------------------------------------------------------------- vectors
def add(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def mul(k, a):
    return [k * a[0], k * a[1], k * a[2]]


def dot(a, b):
    return math.fsum([a[0] * b[0], a[1] * b[1], a[2] * b[2]])


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


# ---------------------------------------------------------------- box
class Box:
    def __init__(self, lo, hi, periodic):
        self.lo, self.hi, self.periodic = lo, hi, periodic

    def length(self, a):
        return self.hi[a] - self.lo[a]

    def wrap(self, r):
        """Position folded into [lo, hi) on periodic axes."""
        out = list(r)
        for a in range(3):
            if self.periodic[a] and (out[a] < self.lo[a] or out[a] >= self.hi[a]):
                out[a] -= math.floor((out[a] - self.lo[a]) / self.length(a)) * self.length(a)
        return out

    def minimum_image(self, d):
        out = list(d)
        for a in range(3):
            if self.periodic[a]:
                L = self.length(a)
                out[a] -= L * math.floor(out[a] / L + 0.5)
        return out


# ---------------------------------------------------------------- icosphere(1), independent
def icosphere1():
    """Unit icosahedron with every edge split once, midpoints projected on the sphere:
    42 vertices, 80 outward-oriented faces."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    raw = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
           [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    verts = [mul(1.0 / norm(v), v) for v in raw]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
             [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
             [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    mid = {}

    def midpoint(i, j):
        key = (min(i, j), max(i, j))
        if key not in mid:
            m = mul(0.5, add(verts[i], verts[j]))
            verts.append(mul(1.0 / norm(m), m))
            mid[key] = len(verts) - 1
        return mid[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
    assert len(verts) == 42 and len(out) == 80
    return verts, out


def face_area(x, f):
    return 0.5 * norm(cross(sub(x[f[1]], x[f[0]]), sub(x[f[2]], x[f[0]])))


def mesh_volume(x, faces):
    return math.fsum(dot(x[a], cross(x[b], x[c])) for a, b, c in faces) / 6.0


class Body:
    """An adipocyte: unwrapped vertex positions, faces, reference areas and volume."""

    def __init__(self, center, radius, vdiam, shape_param, jitter, rng):
        unit, self.faces = icosphere1()
        x0 = [add(center, mul(radius, v)) for v in unit]
        self.ref_volume = mesh_volume(x0, self.faces)
        areas = [face_area(x0, f) for f in self.faces]
        # docs/model.md, reference state: one common factor so that A_0 = shape_param exactly.
        total = shape_param * 6.0 * math.sqrt(math.pi) * self.ref_volume
        k = total ** (2.0 / 3.0) / math.fsum(areas)
        self.ref_area = [k * a for a in areas]
        self.x = [add(v, [jitter * (2 * rng.random() - 1) for _ in range(3)]) for v in x0]
        self.vdiam = vdiam

    def centroid(self):
        n = len(self.x)
        return [math.fsum(v[a] for v in self.x) / n for a in range(3)]


def shape_energy_grad(body, x, eps_v, eps_a):
    """U = eps_v/2 (1 - v/v0)^2 + eps_a/2 sum_k (1 - a_k/a_k0)^2 and its analytic gradient."""
    n = len(x)
    terms = [[[] for _ in range(3)] for _ in range(n)]
    dv = 1.0 - mesh_volume(x, body.faces) / body.ref_volume
    energy = [0.5 * eps_v * dv * dv]
    cv = -eps_v * dv / body.ref_volume / 6.0  # dU/dv * dv/dx, dv/dx_a = (x_b x x_c)/6 cyclic
    for k, (a, b, c) in enumerate(body.faces):
        for i, j, l in ((a, b, c), (b, c, a), (c, a, b)):
            g = cross(x[j], x[l])
            for d in range(3):
                terms[i][d].append(cv * g[d])
        nrm = cross(sub(x[b], x[a]), sub(x[c], x[a]))
        twice = norm(nrm)
        da = 1.0 - 0.5 * twice / body.ref_area[k]
        energy.append(0.5 * eps_a * da * da)
        nh = mul(1.0 / twice, nrm)
        ca = -eps_a * da / body.ref_area[k] * 0.5  # dU/da_k * d(a_k)/d|n|
        for i, j, l in ((a, b, c), (b, c, a), (c, a, b)):
            g = cross(sub(x[j], x[l]), nh)  # d|n|/dx_i = (x_j - x_l) x n_hat
            for d in range(3):
                terms[i][d].append(ca * g[d])
    grad = [[math.fsum(terms[i][d]) for d in range(3)] for i in range(n)]
    return math.fsum(energy), grad


def check_gradient(body, eps_v, eps_a):
    """Central finite differences of the shape energy against the analytic gradient."""
    _, grad = shape_energy_grad(body, body.x, eps_v, eps_a)
    h, worst, scale = 1e-6, 0.0, max(abs(g) for row in grad for g in row)
    for i in range(len(body.x)):
        for d in range(3):
            xp = [list(v) for v in body.x]
            xm = [list(v) for v in body.x]
            xp[i][d] += h
            xm[i][d] -= h
            fd = (shape_energy_grad(body, xp, eps_v, eps_a)[0] -
                  shape_energy_grad(body, xm, eps_v, eps_a)[0]) / (2 * h)
            worst = max(worst, abs(fd - grad[i][d]))
    assert worst < 1e-6 * scale, (worst, scale)
    return worst / scale


# ---------------------------------------------------------------- the configuration
class Config:
    def __init__(self, name, term, description, box):
        self.name, self.term, self.description, self.box = name, term, description, box
        self.spheres = []  # (diameter, position) in site order before the bodies
        self.bodies = []
        self.params = {}
        self.tethers = []  # (body a, body b, rest length)

    def sites(self):
        """Site list in the engine's order: (kind, diameter, body, position as given)."""
        out = [("cancer", d, -1, r) for d, r in self.spheres]
        for b, body in enumerate(self.bodies):
            out += [("vertex", body.vdiam, b, v) for v in body.x]
        return out


COVERAGE = {}


def branch(ki, kj, r, s, alpha, beta):
    """Name of the contact kind / cohesion branch of one interacting pair (coverage report)."""
    if ki != kj:
        return "cell-vertex"
    if ki == "vertex":
        return "vertex-vertex"
    if r < 1e-12 * s:
        return "cell-cell coincident"
    if r <= s:
        return "cell-cell overlap"
    return "cell-cell s<r<=r_b" if r <= (1 + beta) * s else "cell-cell r_b<r<=r_a"


def contact_forces(cfg):
    """All pairs (i < j), minimum image, of wrapped positions; the pair forms of docs/model.md."""
    p, box = cfg.params, cfg.box
    COVERAGE[cfg.name] = __import__("collections").Counter()
    sites = cfg.sites()
    pos = [box.wrap(r) for _, _, _, r in sites]
    n = len(sites)
    fterms = [[[] for _ in range(3)] for _ in range(n)]
    energy, virial = [], [[], [], []]
    eps = {("cancer", "cancer"): p["eps_cc"], ("cancer", "vertex"): p["eps_cv"],
           ("vertex", "cancer"): p["eps_cv"], ("vertex", "vertex"): p["eps_vv"]}
    alpha, beta = p["alpha"], p["beta"]
    for i in range(n):
        for j in range(i + 1, n):
            ki, di, bi, _ = sites[i]
            kj, dj, bj, _ = sites[j]
            if bi >= 0 and bi == bj:
                continue  # no contacts within one adipocyte
            d = box.minimum_image(sub(pos[i], pos[j]))
            r = norm(d)
            s = 0.5 * (di + dj)
            e = eps[(ki, kj)]
            if ki == "cancer" and kj == "cancer" and beta > 0:
                ra, rb = (1 + alpha) * s, (1 + beta) * s
                if r <= rb:
                    f = e / s * (1 - r / s)
                    # U(r) = integral_r^{r_a} F: linear part + the attractive tail's area
                    u_rb = -0.5 * (e / s) * (rb - s) / (ra - rb) / s * (ra - rb) ** 2
                    u = u_rb + 0.5 * e * ((1 - r / s) ** 2 - (1 - rb / s) ** 2)
                elif r <= ra:
                    f = e / s * (rb - s) / (ra - rb) * (r - ra) / s
                    u = -0.5 * (e / s) * (rb - s) / (ra - rb) / s * (ra - r) ** 2
                else:
                    continue
            else:
                if r > s:
                    continue
                f, u = e / s * (1 - r / s), 0.5 * e * (1 - r / s) ** 2
            COVERAGE[cfg.name][branch(ki, kj, r, s, alpha, beta)] += 1
            if r < 1e-12 * s:  # docs/model.md: +x on the lower-index site, no virial
                uvec, dvec = [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]
            else:
                uvec, dvec = mul(1.0 / r, d), d
            energy.append(u)
            for a in range(3):
                fterms[i][a].append(f * uvec[a])
                fterms[j][a].append(-f * uvec[a])
                virial[a].append(dvec[a] * f * uvec[a])
    forces = [[math.fsum(fterms[i][a]) for a in range(3)] for i in range(n)]
    return math.fsum(energy), [math.fsum(v) for v in virial], forces


def wall_forces(cfg):
    """F = (eps/s)(1 - d/s) into the box for d <= s, s the site's own diameter; the virial
    is -dU/d(ln L_x) = d * F_into_box per wall contact."""
    p, box = cfg.params, cfg.box
    sites = cfg.sites()
    energy, wx, forces = [], [], []
    for _, s, _, r in sites:
        fx = []
        for on, d, sign in ((p["left"], r[0] - box.lo[0], 1.0), (p["right"], box.hi[0] - r[0], -1.0)):
            if on and d <= s:
                f = p["eps"] / s * (1 - d / s)
                fx.append(sign * f)
                energy.append(0.5 * p["eps"] * (1 - d / s) ** 2)
                wx.append(d * f)
        forces.append([math.fsum(fx), 0.0, 0.0])
    return math.fsum(energy), [math.fsum(wx), 0.0, 0.0], forces


def shape_forces(cfg):
    """Shape energy of every body; virial -sum_v (x_v - c) * dU/dx_v (c = vertex centroid:
    the shape energy is invariant under translation, so any origin gives the same sum)."""
    p = cfg.params
    forces = [[0.0, 0.0, 0.0] for _ in cfg.spheres]
    energy, virial = [], [[], [], []]
    for body in cfg.bodies:
        u, grad = shape_energy_grad(body, body.x, p["eps_v"], p["eps_a"])
        energy.append(u)
        c = body.centroid()
        for v, g in zip(body.x, grad):
            forces.append([-g[0], -g[1], -g[2]])
            for a in range(3):
                virial[a].append(-(v[a] - c[a]) * g[a])
    return math.fsum(energy), [math.fsum(v) for v in virial], forces


def tether_forces(cfg):
    """U = K/2 (R_ab - l0)^2 between vertex centroids (minimum image); the force on a centre
    is shared equally by the body's vertices. Virial: d_ab * F_a."""
    K, box = cfg.params["K"], cfg.box
    cen = [b.centroid() for b in cfg.bodies]
    bf = [[[] for _ in range(3)] for _ in cfg.bodies]
    energy, virial = [], [[], [], []]
    for a, b, l0 in cfg.tethers:
        d = box.minimum_image(sub(cen[a], cen[b]))
        r = norm(d)
        f = mul(-K * (r - l0) / r, d)
        energy.append(0.5 * K * (r - l0) ** 2)
        for k in range(3):
            bf[a][k].append(f[k])
            bf[b][k].append(-f[k])
            virial[k].append(d[k] * f[k])
    forces = [[0.0, 0.0, 0.0] for _ in cfg.spheres]
    for b, body in enumerate(cfg.bodies):
        share = [math.fsum(bf[b][k]) / len(body.x) for k in range(3)]
        forces += [list(share) for _ in body.x]
    return math.fsum(energy), [math.fsum(v) for v in virial], forces


TERMS = {"contact": contact_forces, "wall": wall_forces, "shape": shape_forces,
         "tether": tether_forces}


# ---------------------------------------------------------------- output
def g17(x):
    return "%.17g" % x


def render(cfg):
    """The text of cfg's regression file."""
    energy, virial, forces = TERMS[cfg.term](cfg)
    lines = ["# invasim force regression file, generated by tests/regression/generate.py.",
             "# Regenerate only after a deliberate physics change (docs/architecture.md).",
             "description " + cfg.description,
             "term " + cfg.term,
             "box_lo " + " ".join(map(g17, cfg.box.lo)),
             "box_hi " + " ".join(map(g17, cfg.box.hi)),
             "periodic " + " ".join("1" if p else "0" for p in cfg.box.periodic)]
    for k in sorted(cfg.params):
        lines.append("param %s %s" % (k, g17(float(cfg.params[k]))))
    lines.append("# sphere diameter x y z   (cancer cells, site indices 0..)")
    for d, r in cfg.spheres:
        lines.append("sphere %s %s" % (g17(d), " ".join(map(g17, r))))
    for body in cfg.bodies:
        lines.append("# body n_vertices n_faces vertex_diameter ref_volume; then its vertices"
                     " (unwrapped x y z) and faces (a b c ref_area)")
        lines.append("body %d %d %s %s" % (len(body.x), len(body.faces), g17(body.vdiam),
                                           g17(body.ref_volume)))
        for v in body.x:
            lines.append("vertex " + " ".join(map(g17, v)))
        for f, a0 in zip(body.faces, body.ref_area):
            lines.append("face %d %d %d %s" % (f[0], f[1], f[2], g17(a0)))
    for a, b, l0 in cfg.tethers:
        lines.append("tether %d %d %s" % (a, b, g17(l0)))
    lines.append("# references")
    lines.append("energy " + g17(energy))
    lines.append("virial " + " ".join(map(g17, virial)))
    for i, f in enumerate(forces):
        lines.append("force %d %s" % (i, " ".join(map(g17, f))))
    print("%-24s %4d sites  E = %.6g" % (cfg.name + ".force", len(forces), energy))
    return "\n".join(lines) + "\n"


def same_numbers(a, b):
    """Token-wise equality, numbers up to 1e-12 relative (another libm may round pow or
    sqrt differently in the last bit; the C++ runner's tolerance is 1e-12 too)."""
    ta, tb = a.split(), b.split()
    if len(ta) != len(tb):
        return False
    for x, y in zip(ta, tb):
        if x == y:
            continue
        try:
            fx, fy = float(x), float(y)
        except ValueError:
            return False
        if abs(fx - fy) > 1e-12 * max(abs(fx), abs(fy)) + 1e-15:
            return False
    return True


def contact_params(beta, eps_cc=1.0, eps_cv=1.0, eps_vv=1.0):
    return {"eps_cc": eps_cc, "eps_cv": eps_cv, "eps_vv": eps_vv, "alpha": 0.2, "beta": beta,
            "skin": 0.3}


def configs():
    rng = random.Random(20261202)
    box = Box([0.0, 0.0, 0.0], [14.0, 12.0, 12.0], [False, True, True])
    out = []

    # Contacts without cohesion: the three kinds with distinct eps, overlaps across y and z.
    c = Config("contact_repulsive", "contact",
               "linear springs: cell-cell, cell-vertex, vertex-vertex (different adipocytes), "
               "periodic images in y and z, distinct eps per kind", box)
    c.params = contact_params(0.0, eps_cc=1.0, eps_cv=0.7, eps_vv=1.3)
    c.spheres = [(0.9, [1.0, 0.3, 6.0]), (1.1, [1.5, 11.6, 6.2]),  # cc across y
                 (0.9, [2.0, 5.0, 0.2]), (1.1, [2.3, 5.4, 11.5]),  # cc across z
                 (1.1, [3.0, 3.0, 3.0]), (0.9, [3.6, 3.4, 3.3]),  # cc plain
                 (1.1, [6.4, 6.0, 3.1]),  # near the bottom of body 0 (cell-vertex)
                 (0.9, [7.2, 9.3, 6.4])]  # between the bodies
    c.bodies = [Body([6.5, 6.0, 6.0], 2.0, 2.0, 1.1, 0.15, rng),
                Body([9.0, 10.8, 7.0], 2.0, 2.0, 1.1, 0.15, rng)]  # overlaps body 0, wraps y
    out.append(c)

    # Cohesion: every branch, images, and the coincident-site rule.
    c = Config("contact_cohesive", "contact",
               "cancer-cell cohesion alpha = 0.2, beta = 0.05: overlaps, s < r <= r_b, "
               "r_b < r <= r_a, beyond r_a, coincident sites, periodic images; plus "
               "cell-vertex and vertex-vertex contacts", box)
    c.params = contact_params(0.05)
    s = 1.0
    c.spheres = [(0.9, [2.0, 2.0, 2.0]), (1.1, [2.0 + 0.8 * s, 2.0, 2.0]),  # overlap
                 (0.9, [2.0, 6.0, 2.0]), (1.1, [2.0, 6.0 + 1.03 * s, 2.0]),  # s<r<=r_b
                 (0.9, [4.0, 1.0, 9.0]), (1.1, [4.0 + 0.5, 1.0, 9.0 + 1.05]),  # r_b<r<=r_a
                 (1.1, [1.0, 11.7, 11.7]), (0.9, [1.2, 0.4, 0.42]),  # s<r<=r_b across y, z
                 (1.0, [5.0, 4.0, 5.0]), (1.0, [5.0, 4.0, 5.0]),  # coincident
                 (0.9, [12.0, 3.0, 3.0]), (1.1, [12.0, 3.0, 3.0 + 1.25]),  # beyond r_a
                 (1.1, [9.9, 6.0, 6.1])]  # touching body 0
    c.bodies = [Body([8.0, 6.0, 7.5], 2.0, 2.0, 1.1, 0.2, rng),
                Body([8.3, 6.5, 2.4], 2.0, 2.0, 1.1, 0.2, rng)]
    out.append(c)

    # Walls: sites touching the left, the right and (narrow box) both walls.
    wbox = Box([-0.5, 0.0, 0.0], [1.0, 8.0, 8.0], [False, True, True])
    c = Config("wall", "wall", "walls in x with s = the site's own diameter: left, right, "
               "both walls at once (narrow box), out of reach, exactly at a wall", wbox)
    c.params = {"eps": 1.7, "left": 1, "right": 1}
    c.spheres = [(1.1, [0.25, 1.0, 1.0]),  # both walls (d = 0.75 each)
                 (0.9, [-0.4, 2.0, 2.0]), (1.1, [0.9, 3.0, 3.0]), (0.9, [-0.5, 4.0, 4.0]),
                 (0.2, [0.25, 5.0, 5.0]),  # out of reach of both
                 (1.0, [1.0, 6.0, 6.0])]  # on the right wall
    out.append(c)
    c = Config("wall_right_only", "wall", "only the right wall (left = 0): sites within reach "
               "of the absent left wall feel nothing", wbox)
    c.params = {"eps": 0.9, "left": 0, "right": 1}
    c.spheres = [(1.1, [0.25, 1.0, 1.0]), (0.9, [-0.4, 2.0, 2.0]), (1.1, [0.6, 3.0, 3.0])]
    out.append(c)

    # Shape: two deformed adipocytes, one straddling the periodic boundary in y and z.
    c = Config("shape", "shape", "adipocyte volume and face-area energies, two randomly "
               "deformed icosphere(1) bodies (one straddling the y and z boundaries), "
               "A_0 = 1.1", box)
    c.params = {"eps_v": 100.0, "eps_a": 1.3}
    c.spheres = [(1.0, [1.0, 1.0, 1.0])]
    c.bodies = [Body([5.0, 6.0, 6.0], 2.0, 2.0, 1.1, 0.3, rng),
                Body([10.0, 11.5, 0.4], 2.2, 1.8, 1.05, 0.3, rng)]
    out.append(c)
    for b in c.bodies:
        print("shape gradient vs finite differences: max |diff| / max |grad| = %.2e"
              % check_gradient(b, c.params["eps_v"], c.params["eps_a"]))

    # Tethers: stretched, compressed, across the periodic boundary, zero rest length.
    c = Config("tether", "tether", "ECM tethers between vertex centroids: stretched, "
               "compressed, across the y and z boundaries, zero rest length", box)
    c.params = {"K": 0.8}
    c.spheres = [(1.0, [1.0, 1.0, 1.0])]
    c.bodies = [Body([3.5, 2.5, 2.5], 2.0, 2.0, 1.1, 0.2, rng),
                Body([3.5, 9.0, 2.0], 2.0, 2.0, 1.1, 0.2, rng),  # 5.5 away across y
                Body([9.5, 2.0, 10.5], 2.0, 2.0, 1.1, 0.2, rng),  # across z
                Body([9.0, 7.0, 6.0], 2.0, 2.0, 1.1, 0.2, rng)]
    c.tethers = [(0, 1, 6.5), (0, 2, 6.0), (1, 3, 5.0), (2, 3, 0.0), (0, 3, 8.2)]
    out.append(c)
    return out


if __name__ == "__main__":
    # --check: regenerate in memory and compare with the committed files (CTest
    # "regression: generator reproduces the files"); otherwise (re)write the files.
    check = "--check" in sys.argv[1:]
    bad = [a for a in sys.argv[1:] if a != "--check"]
    if bad:
        sys.exit("generate.py: unknown argument %r (allowed: --check)" % bad[0])
    stale = []
    for cfg in configs():
        path = os.path.join(HERE, cfg.name + ".force")
        text = render(cfg)
        if check:
            if not os.path.exists(path) or not same_numbers(open(path).read(), text):
                stale.append(path)
        else:
            with open(path, "w") as out:
                out.write(text)
    for name, counts in COVERAGE.items():
        print(name, dict(sorted(counts.items())))
    if stale:
        sys.exit("generate.py --check: these files differ from what the generator computes: "
                 + ", ".join(stale))
