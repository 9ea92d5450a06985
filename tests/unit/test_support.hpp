#pragma once
// Builders of small test systems shared by the unit tests and the benchmarks.
#include <cmath>
#include <memory>

#include "core/rng.hpp"
#include "forces/contact_force.hpp"
#include "forces/shape_force.hpp"
#include "forces/tether_force.hpp"
#include "forces/wall_force.hpp"
#include "state/system.hpp"

namespace invasim::test {

// Uniform random number in [0, 1) keyed by (seed, i, k): reproducible test configurations.
inline double uniform(std::uint64_t seed, std::uint32_t i, std::uint32_t k) {
  return RandomKey(seed, k / 4, i, RngStream::kPlacement).uniform4()[k % 4];
}

// The unit cube [0, 1]^3 as an outward-oriented triangle mesh (two triangles per side);
// vertex i = (i&1, i>>1&1, i>>2&1): a mesh whose plane cuts are known by hand.
inline MeshShape unit_cube_mesh() {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  std::vector<MeshTopology::Face> f = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                       {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                       {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return {std::make_shared<const MeshTopology>(8, std::move(f)), std::move(v)};
}

// A box [0,L)^3 periodic in y,z (and x too when !walls).
inline Box cube(double L, bool walls) {
  return Box(Vec3::Zero(), Vec3::Constant(L), {!walls, true, true});
}

// n bidisperse spheres (half 0.9, half 1.1) at random positions (overlaps allowed) in a cube
// sized for packing fraction phi.
inline System random_spheres(int n, double phi, bool walls, std::uint64_t seed) {
  const double vol = n * M_PI / 6.0 * 0.5 * (0.9 * 0.9 * 0.9 + 1.1 * 1.1 * 1.1);
  const double L = std::cbrt(vol / phi);
  System sys(cube(L, walls), seed);
  for (int i = 0; i < n; ++i) {
    const Vec3 r(uniform(seed, i, 0) * L, uniform(seed, i, 1) * L, uniform(seed, i, 2) * L);
    sys.add_sphere(r, i % 2 ? 1.1 : 0.9);
  }
  return sys;
}

// Adipocytes (radius 2, vertex diameter 2, A0 = 1.1) on a loose cubic grid of spacing
// `spacing`, each randomly displaced and with randomly perturbed vertices, plus n_cells
// random cancer cells, in a walled box periodic in y and z.
inline System mixed_system(int grid, int n_cells, double spacing, double jitter,
                           std::uint64_t seed) {
  const double L = grid * spacing;
  System sys(cube(L, true), seed);
  for (int i = 0; i < n_cells; ++i) {
    const Vec3 r(0.6 + uniform(seed, i, 0) * (L - 1.2), uniform(seed, i, 1) * L,
                 uniform(seed, i, 2) * L);
    sys.add_sphere(r, i % 2 ? 1.1 : 0.9);
  }
  const MeshShape shape = icosphere(1);
  int b = 0;
  for (int gx = 0; gx < grid; ++gx)
    for (int gy = 0; gy < grid; ++gy)
      for (int gz = 0; gz < grid; ++gz, ++b) {
        const Vec3 c = spacing * Vec3(gx + 0.5, gy + 0.5, gz + 0.5);
        sys.add_mesh_scaled(shape, c, 2.0, 2.0, 1.1);
        const MeshBody& body = sys.bodies().back();
        for (int v = 0; v < body.n_vertices(); ++v) {
          const std::uint32_t id = 100000 + b * 64 + v;
          sys.sites().pos[body.first_site + v] +=
              jitter * Vec3(uniform(seed, id, 0) - 0.5, uniform(seed, id, 1) - 0.5,
                            uniform(seed, id, 2) - 0.5);
        }
      }
  sys.wrap_all();
  return sys;
}

// Contacts (with cohesion beta), walls, shape (eps_v, eps_a) and no tethers.
inline ForceField standard_forces(double beta = 1e-2, double eps_v = 100.0, double eps_a = 1.0) {
  ForceField ff;
  ContactParams cp;
  cp.beta = beta;
  ff.add(std::make_shared<ContactForce>(cp));
  ff.add(std::make_shared<WallForce>());
  ff.add(std::make_shared<ShapeForce>(eps_v, eps_a));
  return ff;
}

}  // namespace invasim::test

namespace invasim::test {

// De-mixed slab like the paper's start: n_yz x n_yz columns of adipocytes, nx deep, at
// centre spacing `spacing` in the right part of a walled box, and n_cells cancer cells at
// random in a left region sized for cell packing fraction phi_c. Overlaps are allowed (a
// minimiser or the dynamics resolves them).
inline System slab_system(int nx, int n_yz, int n_cells, double spacing, double phi_c,
                          std::uint64_t seed) {
  const double Lyz = n_yz * spacing;
  const double cell_volume = n_cells * M_PI / 6.0 * 0.5 * (0.9 * 0.9 * 0.9 + 1.1 * 1.1 * 1.1);
  const double Lc = cell_volume / phi_c / (Lyz * Lyz);
  const double Lx = Lc + nx * spacing;
  System sys(Box(Vec3::Zero(), Vec3(Lx, Lyz, Lyz), {false, true, true}), seed);
  for (int i = 0; i < n_cells; ++i)
    sys.add_sphere(Vec3(0.5 + uniform(seed, i, 0) * (Lc - 0.5), uniform(seed, i, 1) * Lyz,
                        uniform(seed, i, 2) * Lyz),
                   i % 2 ? 1.1 : 0.9);
  const MeshShape shape = icosphere(1);
  for (int gx = 0; gx < nx; ++gx)
    for (int gy = 0; gy < n_yz; ++gy)
      for (int gz = 0; gz < n_yz; ++gz)
        sys.add_mesh_scaled(
            shape, Vec3(Lc + spacing * (gx + 0.5), spacing * (gy + 0.5), spacing * (gz + 0.5)), 2.0,
            2.0, 1.1);
  sys.wrap_all();
  return sys;
}

// Every site index of a system (a group of all sites).
inline std::vector<int> all_sites(const System& sys) {
  std::vector<int> g(sys.n_sites());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = int(i);
  return g;
}

// n non-interacting spheres of mass m at random positions in a fully periodic box.
inline System free_particles(int n, double mass, std::uint64_t seed) {
  const double L = 40.0;
  System sys(cube(L, false), seed);
  for (int i = 0; i < n; ++i)
    sys.add_sphere(L * Vec3(uniform(seed, i, 0), uniform(seed, i, 1), uniform(seed, i, 2)), 1.0,
                   mass);
  return sys;
}

// Mean and standard error of a set of independent estimates.
struct Estimate {
  double mean = 0.0, error = 0.0;
};
inline Estimate estimate(const std::vector<double>& x) {
  Estimate e;
  for (double v : x) e.mean += v;
  e.mean /= double(x.size());
  double var = 0.0;
  for (double v : x) var += (v - e.mean) * (v - e.mean);
  e.error = std::sqrt(var / double(x.size() - 1) / double(x.size()));
  return e;
}

}  // namespace invasim::test
