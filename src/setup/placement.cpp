#include "setup/placement.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/memory_budget.hpp"
#include "core/rng.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

namespace {

struct Ball {
  Vec3 centre;
  double radius;
};

// Brute-force overlap test against every ball placed so far (minimum image).
bool overlaps(const Box& box, const std::vector<Ball>& balls, const Ball& b) {
  for (const Ball& o : balls) {
    const double reach = o.radius + b.radius;
    if (box.minimum_image(o.centre - b.centre).squaredNorm() < reach * reach) return true;
  }
  return false;
}

// The centres' x range must lie inside the box; with walls in x, the bodies too.
void check_range(const Box& box, const Range& x, double radius, const char* what) {
  if (!(x.hi >= x.lo)) fail_input(what, ": x range [", x.lo, ", ", x.hi, "] is empty");
  if (box.periodic(0)) {
    if (x.lo < box.lo()[0] || x.hi > box.hi()[0])
      fail_input(what, ": x range [", x.lo, ", ", x.hi, "] is outside the periodic box [",
                 box.lo()[0], ", ", box.hi()[0], "]");
    return;
  }
  if (x.lo - radius < box.lo()[0] || x.hi + radius > box.hi()[0])
    fail_input(what, ": x range [", x.lo, ", ", x.hi, "] with body radius ", radius,
               " does not fit between the walls [", box.lo()[0], ", ", box.hi()[0], "]");
}

// A random point with x in the range and y, z anywhere in the box.
Vec3 random_point(const System& sys, const Range& x, std::uint64_t attempt, std::uint32_t id,
                  std::uint32_t sub) {
  const auto u = RandomKey(sys.seed(), attempt, id, RngStream::kPlacement, sub).uniform4();
  const Box& box = sys.box();
  return {x.lo + u[0] * (x.hi - x.lo), box.lo()[1] + u[1] * box.length(1),
          box.lo()[2] + u[2] * box.length(2)};
}

// A uniformly random rotation (unit quaternion from four normals).
Eigen::Matrix3d random_rotation(const System& sys, std::uint32_t id) {
  const auto g = RandomKey(sys.seed(), 0, id, RngStream::kPlacement, 7).normal4();
  Eigen::Quaterniond q(g[0], g[1], g[2], g[3]);
  q.normalize();
  return q.toRotationMatrix();
}

// The outer diameter of adipocyte `id` (MeshPlacement: one size, a list, or log-normal).
double adipocyte_diameter(const System& sys, const MeshPlacement& m, int k, std::uint32_t id) {
  if (!m.diameters.empty()) return m.diameters[std::size_t(k) % m.diameters.size()];
  if (m.spread <= 0.0) return m.diameter;
  const double z = RandomKey(sys.seed(), 0, id, RngStream::kPlacement, 9).normal4()[0];
  return m.diameter * std::exp(m.spread * z - 0.5 * m.spread * m.spread);
}

// The x range of adipocyte k's centre. One size: the given range (check_range has refused a
// range whose bodies would cross a wall). Many sizes: the given range narrowed so that this
// body stays between the walls, refused only when no centre would.
Range body_range(const Box& box, const MeshPlacement& m, double outer, int k) {
  if (m.diameters.empty() && m.spread <= 0.0) return m.x;
  if (!(m.x.hi >= m.x.lo))
    fail_input("adipocyte placement: x range [", m.x.lo, ", ", m.x.hi, "] is empty");
  if (box.periodic(0)) return m.x;
  const Range x{std::max(m.x.lo, box.lo()[0] + outer), std::min(m.x.hi, box.hi()[0] - outer)};
  if (!(x.hi >= x.lo))
    fail_input("adipocyte placement: adipocyte ", k, " of diameter ", 2 * outer,
               " does not fit between the walls [", box.lo()[0], ", ", box.hi()[0],
               "] with its centre in the x range [", m.x.lo, ", ", m.x.hi, "]");
  return x;
}

// place_random on `sys` itself (a failure may leave some of the bodies placed).
PlacementResult place_into(System& sys, const MeshPlacement& meshes,
                           const SpherePlacement& spheres) {
  if (meshes.n < 0 || spheres.n < 0) fail_input("placement: negative number of bodies");
  if (spheres.n > 0 && spheres.diameters.empty())
    fail_input("placement: no cancer-cell diameters given");
  for (double d : spheres.diameters) require_positive("cancer-cell diameter", d);
  // Memory of the new sites, checked before any is added.
  const double vertices = 10.0 * std::pow(4.0, std::clamp(meshes.subdivisions, 0, 30)) + 2.0;
  check_memory("placement", "cells.n", double(spheres.n), kBytesPerSite);
  check_memory("placement", "adipocytes.n", double(meshes.n), kBytesPerSite * vertices);
  check_memory("placement", "cells.n + adipocytes.n x vertices",
               double(sys.n_sites()) + double(spheres.n) + double(meshes.n) * vertices,
               kBytesPerSite);
  PlacementResult out;
  std::vector<Ball> balls;
  for (std::size_t i = 0; i < sys.n_sites(); ++i)
    balls.push_back({sys.sites().pos[i], 0.5 * sys.sites().diameter[i]});

  if (meshes.n > 0) {
    require_positive("adipocyte diameter", meshes.diameter);
    require_positive("vertex diameter", meshes.vertex_diameter);
    for (double d : meshes.diameters) require_positive("adipocyte diameter", d);
    require_non_negative("adipocyte diameter spread", meshes.spread);
    if (!meshes.diameters.empty() && meshes.spread > 0.0)
      fail_input(
          "adipocyte placement: give the diameters as a list or as a spread, not both "
          "(spread = ",
          meshes.spread, " with ", meshes.diameters.size(), " diameters)");
    const MeshShape shape = icosphere(meshes.subdivisions);
    // Each size's mesh radius and outer (union) volume; computed once per distinct diameter.
    double known_diameter = -1.0, radius = 0.0, v_outer = 0.0;
    auto size_for = [&](double d, int k) {
      if (d == known_diameter) return;
      radius = 0.5 * (d - meshes.vertex_diameter);
      if (!(radius > 0.0))
        fail_input("adipocyte ", k, ": diameter = ", d,
                   " must exceed the vertex diameter = ", meshes.vertex_diameter,
                   meshes.spread > 0.0 ? " (drawn from the spread: lower the spread)" : "");
      if (meshes.diameters.empty() && meshes.spread <= 0.0)
        check_range(sys.box(), meshes.x, 0.5 * d, "adipocyte placement");
      std::vector<Vec3> scaled;
      for (const Vec3& v : shape.vertices) scaled.push_back(radius * v);
      v_outer =
          union_volume(*shape.topology, scaled.data(), meshes.vertex_diameter, meshes.volume_grid);
      known_diameter = d;
    };
    for (int k = 0; k < meshes.n; ++k) {
      const std::uint32_t id = std::uint32_t(sys.bodies().size());
      const double diameter = adipocyte_diameter(sys, meshes, k, id);
      size_for(diameter, k);
      const double outer = 0.5 * diameter;
      const Range x = body_range(sys.box(), meshes, outer, k);
      bool placed = false;
      for (std::uint64_t attempt = 0; attempt < meshes.max_attempts_per_body && !placed;
           ++attempt) {
        const Ball b{random_point(sys, x, attempt, id, 1), outer};
        if (overlaps(sys.box(), balls, b)) continue;
        MeshShape rotated = shape;
        if (meshes.random_rotation) {
          const Eigen::Matrix3d rot = random_rotation(sys, id);
          for (Vec3& v : rotated.vertices) v = rot * v;
        }
        const int body = sys.add_mesh_scaled(rotated, b.centre, radius, meshes.vertex_diameter,
                                             meshes.shape_param);
        sys.bodies()[body].outer_volume = v_outer;
        balls.push_back(b);
        out.bodies.push_back(body);
        placed = true;
      }
      if (!placed)
        fail_input("adipocyte placement: only ", k, " of ", meshes.n,
                   " adipocytes fit in x range [", meshes.x.lo, ", ", meshes.x.hi,
                   "] without overlaps; widen the range or enlarge the box");
    }
  }

  if (!spheres.positions.empty()) {
    if (spheres.n != int(spheres.positions.size()))
      fail_input("cancer-cell placement: n = ", spheres.n, " for ", spheres.positions.size(),
                 " given positions");
    // All checked first, so that the message names the given position (not the site added).
    for (std::size_t k = 0; k < spheres.positions.size(); ++k) {
      const Vec3& r = spheres.positions[k];
      if (!r.allFinite()) fail_input("cancer-cell placement: position ", k + 1, " is not finite");
      if (const int a = sys.box().axis_outside_walls(r); a >= 0)
        fail_input("cancer-cell placement: position ", k + 1, " has ", "xyz"[a], " = ", r[a],
                   ", outside the walls [", sys.box().lo()[a], ", ", sys.box().hi()[a], "]");
    }
    for (std::size_t k = 0; k < spheres.positions.size(); ++k)
      out.cells.push_back(
          sys.add_sphere(spheres.positions[k], spheres.diameters[k % spheres.diameters.size()]));
  } else if (spheres.n > 0) {
    double d_max = 0.0;
    for (double d : spheres.diameters) d_max = std::max(d_max, d);
    check_range(sys.box(), spheres.x, 0.5 * d_max, "cancer-cell placement");
    for (int k = 0; k < spheres.n; ++k) {
      const double d = spheres.diameters[k % spheres.diameters.size()];
      const std::uint32_t id = std::uint32_t(k);
      bool placed = false;
      for (std::uint64_t attempt = 0; attempt < spheres.max_attempts_per_cell && !placed;
           ++attempt) {
        const Ball b{random_point(sys, spheres.x, attempt, id, 2), 0.5 * d};
        if (overlaps(sys.box(), balls, b)) continue;
        out.cells.push_back(sys.add_sphere(b.centre, d));
        balls.push_back(b);
        placed = true;
      }
      if (!placed)
        fail_input("cancer-cell placement: only ", k, " of ", spheres.n, " cells fit in x range [",
                   spheres.x.lo, ", ", spheres.x.hi,
                   "] without overlaps; widen the range or enlarge the box");
    }
  }
  return out;
}

}  // namespace

PlacementResult place_random(System& sys, const MeshPlacement& meshes,
                             const SpherePlacement& spheres) {
  System trial = sys;  // a refused placement leaves the System as it was
  PlacementResult out = place_into(trial, meshes, spheres);
  sys = std::move(trial);
  return out;
}

}  // namespace invasim
