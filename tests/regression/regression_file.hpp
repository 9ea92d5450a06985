#pragma once
// A force regression file (tests/regression/*.force): a configuration, the parameters of one
// force term, and the reference energy, virial and per-site forces computed independently by
// tests/regression/generate.py. Line-based text, one record per line:
//   description <text> | term contact|wall|shape|tether | box_lo x y z | box_hi x y z |
//   periodic px py pz | param <name> <value> | sphere d x y z |
//   body n_vertices n_faces vertex_diameter ref_volume, then n_vertices `vertex x y z` and
//   n_faces `face a b c ref_area` lines | tether a b rest_length |
//   energy E | virial Wx Wy Wz | force i fx fy fz
// '#' starts a comment line. Unknown keywords and malformed lines are errors naming file:line.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "forces/force.hpp"
#include "state/system.hpp"

namespace invasim::regression {

struct SphereSpec {
  double diameter;
  Vec3 pos;
};

struct BodySpec {
  double vertex_diameter = 0.0, ref_volume = 0.0;
  std::vector<Vec3> vertices;
  std::vector<MeshTopology::Face> faces;
  std::vector<double> ref_area;
};

struct TetherSpec {
  int a, b;
  double rest_length;
};

struct RegressionCase {
  std::string path, description, term;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  std::array<bool, 3> periodic{false, true, true};
  std::map<std::string, double> params;
  std::vector<SphereSpec> spheres;
  std::vector<BodySpec> bodies;
  std::vector<TetherSpec> tethers;
  double energy = 0.0;
  Vec3 virial = Vec3::Zero();
  std::vector<Vec3> forces;  // one per site, in site order (spheres, then body vertices)
};

// Reads and checks a file; throws InputError naming file:line and the problem.
RegressionCase read_regression_file(const std::string& path);

// The System of a case: spheres first, then the bodies (sites in file order).
System build_system(const RegressionCase& c);

// The force term of a case with its parameters (tethers added to `sys`'s bodies). Unknown or
// missing parameters are errors.
std::shared_ptr<Force> build_force(const RegressionCase& c, const System& sys);

}  // namespace invasim::regression
