#pragma once
// Shared by the output-layer tests (tests/unit/test_io*.cpp) and the frame writer of the
// independent Python check (tests/io/write_frames.cpp): a small but complete System and a
// scratch directory.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/rng.hpp"
#include "forces/tether_force.hpp"
#include "state/system.hpp"

namespace invasim::iotest {

// A fresh, empty directory under the system temp dir, removed with its contents at scope exit.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("invasim_io_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Uniform number in [0, 1) keyed by (i, k): reproducible test data.
inline double u01(std::uint32_t i, std::uint32_t k) {
  return RandomKey(99, k / 4, i, RngStream::kUser).uniform4()[k % 4];
}
inline Vec3 random_vec(std::uint32_t i, std::uint32_t k, double scale) {
  return scale * Vec3(u01(i, k) - 0.5, u01(i, k + 1) - 0.5, u01(i, k + 2) - 0.5);
}

// Box [0,12] x [0,10] x [0,10] with walls in x; `n_cells` bidisperse cells in 0.6 < x < 4
// with random velocities, orientations and forces, and non-zero image counters; adipocyte 0 at
// the centre, adipocyte 1 straddling the periodic y and z edges (so its mesh wraps) and one
// period away in y and z (its unwrapped centroid (7.5, 19.5, -9.7) lies outside the box); the box
// version bumped twice; step and time set; outer volumes set.
inline System sample_system(int n_cells = 20) {
  System sys(Box(Vec3::Zero(), Vec3(12.0, 10.0, 10.0), {false, true, true}), 1234567);
  for (int i = 0; i < n_cells; ++i) {
    const Vec3 r(0.6 + 3.4 * u01(i, 0), 10.0 * u01(i, 1) + 10.0 * (i % 3 - 1),
                 10.0 * u01(i, 2) - 10.0 * (i % 2));
    sys.add_sphere(r, i % 2 ? 1.1 : 0.9, 1.0, random_vec(i, 4, 2.0));
  }
  const MeshShape shape = icosphere(1);
  sys.add_mesh_scaled(shape, Vec3(7.5, 5.0, 5.0), 2.0, 2.0, 1.1);
  sys.add_mesh_scaled(shape, Vec3(7.5, 19.5, -9.7), 2.0, 2.0, 1.1);
  Sites& s = sys.sites();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] == SiteKind::kVertex) s.pos[i] += random_vec(1000 + i, 0, 0.2);
    s.vel[i] = random_vec(2000 + i, 0, 0.4);
    s.force[i] = random_vec(3000 + i, 0, 1e-3);
  }
  sys.wrap_all();
  sys.bodies()[0].outer_volume = 61.25;
  sys.bodies()[1].outer_volume = 62.5;
  sys.box().set_bounds(sys.box().lo(), sys.box().hi());
  sys.box().set_bounds(sys.box().lo(), sys.box().hi());
  sys.step = 1200;
  sys.time = 60.000000000000007;
  return sys;
}

// Two tethers between the sample system's adipocytes.
inline void sample_tethers(const System& sys, TetherForce& tethers) {
  tethers.add(sys, 0, 1, 4.25);
  tethers.add(sys, 1, 0, 5.0 / 3.0);
}

}  // namespace invasim::iotest
