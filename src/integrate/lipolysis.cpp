#include "integrate/lipolysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

void LipolysisParams::validate() const {
  if (!(rate >= 0.0) || !std::isfinite(rate))
    fail_input("lipolysis: rate = ", rate, " must be >= 0 and finite");
  if (!(floor > 0.0 && floor <= 1.0))
    fail_input("lipolysis: floor = ", floor, " must be in (0, 1] (a fraction of the initial ",
               "reference volume)");
}

Lipolysis::Lipolysis(const LipolysisParams& params) : params_(params) {
  params_.validate();
}

void set_reference_volume(MeshBody& body, double v) {
  if (!(v > 0.0)) fail_input("lipolysis: reference volume ", v, " must be > 0");
  const double area_factor = std::cbrt((v / body.ref_volume) * (v / body.ref_volume));
  for (double& a : body.ref_area) a *= area_factor;
  body.ref_volume = v;
}

std::vector<char> Lipolysis::touched(const System& sys) const {
  if (sys.engine_layout()) throw std::logic_error("Lipolysis::touched in the engine layout");
  const Sites& s = sys.sites();
  const Box& box = sys.box();
  std::vector<int> cells;
  double max_cell = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.kind[i] == SiteKind::kCancer) {
      cells.push_back(int(i));
      max_cell = std::max(max_cell, s.diameter[i]);
    }
  const auto& bodies = sys.bodies();
  std::vector<char> out(bodies.size(), 0);
  std::vector<Vec3> x;
  std::vector<int> near;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const MeshBody& body = bodies[b];
    const int n = body.n_vertices();
    x.resize(n);
    sys.body_vertices(int(b), x.data());
    // Candidates: the cells within the body's bounding sphere plus a contact distance.
    const Vec3 c = vertex_centroid(n, x.data());
    double radius = 0.0, max_vertex = 0.0;
    for (int v = 0; v < n; ++v) {
      radius = std::max(radius, (x[v] - c).norm());
      max_vertex = std::max(max_vertex, s.diameter[body.first_site + v]);
    }
    const double reach = radius + 0.5 * (max_cell + max_vertex);
    near.clear();
    for (int i : cells)
      if (box.minimum_image(s.pos[i] - c).squaredNorm() < reach * reach) near.push_back(i);
    for (int i : near) {
      for (int v = 0; v < n && !out[b]; ++v) {
        const double contact = 0.5 * (s.diameter[i] + s.diameter[body.first_site + v]);
        if (box.minimum_image(s.pos[i] - x[v]).squaredNorm() < contact * contact) out[b] = 1;
      }
      if (out[b]) break;
    }
  }
  return out;
}

namespace {

// Grid spacing of the union volumes lipolysis recomputes: on the adipocyte (outer diameter 6,
// vertex diameter 2) h = 0.2 is within 8e-4 of h = 0.02 and takes ~1 ms.
constexpr double kUnionVolumeH = 0.2;

// V_i's factor when body b's reference volume goes from v_old to v_new: the union volumes of
// its vertices now, scaled about their centroid so that the mesh encloses v_new and v_old
// (the vertices read, and their centroid and mesh volume computed, once).
double union_volume_ratio(const System& sys, int b, double v_new, double v_old) {
  const MeshBody& body = sys.bodies()[b];
  const int n = body.n_vertices();
  std::vector<Vec3> x(n), y(n);
  sys.body_vertices(b, x.data());
  const Vec3 c = vertex_centroid(n, x.data());
  const double v_mesh = mesh_volume(*body.topology, x.data());
  const double d = sys.sites().diameter[body.first_site];
  auto at = [&](double v) {
    const double scale = std::cbrt(v / v_mesh);
    for (int k = 0; k < n; ++k) y[k] = c + scale * (x[k] - c);
    return union_volume(*body.topology, y.data(), d, kUnionVolumeH);
  };
  return at(v_new) / at(v_old);
}

}  // namespace

int Lipolysis::apply(System& sys, double elapsed) const {
  if (!(elapsed >= 0.0)) fail_input("lipolysis: elapsed time ", elapsed, " must be >= 0");
  const std::vector<char> touch = touched(sys);
  int count = 0;
  for (std::size_t b = 0; b < touch.size(); ++b) {
    if (!touch[b]) continue;
    ++count;
    MeshBody& body = sys.bodies()[b];
    const double lowest = params_.floor * body.ref_volume_initial;
    const double v =
        std::max(lowest, body.ref_volume - params_.rate * body.ref_volume_initial * elapsed);
    if (!(v < body.ref_volume)) continue;
    // V_i (packing fractions) follows: scaled by the union volumes of the body's shape now at
    // the old and the new reference volume.
    if (body.outer_volume > 0.0)
      body.outer_volume *= union_volume_ratio(sys, int(b), v, body.ref_volume);
    set_reference_volume(body, v);
  }
  return count;
}

}  // namespace invasim
