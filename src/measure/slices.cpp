#include "measure/slices.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "mesh/geometry.hpp"
#include "mesh/plane_cut.hpp"

namespace invasim {

std::vector<double> body_shape_parameters(const System& sys) {
  std::vector<double> out(sys.bodies().size());
  std::vector<Vec3> x;
  for (std::size_t b = 0; b < out.size(); ++b) {
    const MeshTopology& topo = *sys.bodies()[b].topology;
    x.resize(std::size_t(topo.n_vertices()));
    sys.body_vertices(int(b), x.data());
    out[b] = shape_parameter(mesh_area(topo, x.data()), mesh_volume(topo, x.data()));
  }
  return out;
}

namespace {

// A closed boundary loop of the cross-section.
struct Loop {
  std::vector<Vec3> points;
  double signed_area = 0.0;  // > 0: outer boundary (counter-clockwise about the normal)
  double perimeter = 0.0;
};

// Even-odd test of whether p lies inside the loop, in the plane coordinates (e1, e2).
bool inside(const Loop& loop, const Vec3& p, const Vec3& e1, const Vec3& e2) {
  const double px = p.dot(e1), py = p.dot(e2);
  bool in = false;
  const std::size_t n = loop.points.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = loop.points[i].dot(e1), yi = loop.points[i].dot(e2);
    const double xj = loop.points[j].dot(e1), yj = loop.points[j].dot(e2);
    if ((yi > py) != (yj > py) && px < xj + (py - yj) * (xi - xj) / (yi - yj)) in = !in;
  }
  return in;
}

// Groups loops into profiles: every outer loop is a region; each hole belongs to the
// smallest outer loop that contains it.
std::vector<SliceProfile> profiles_from_loops(const std::vector<Loop>& loops, const Vec3& normal) {
  const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  std::vector<SliceProfile> profiles;
  std::vector<int> profile_of(loops.size(), -1);
  for (std::size_t i = 0; i < loops.size(); ++i)
    if (loops[i].signed_area > 0.0) {
      profile_of[i] = int(profiles.size());
      profiles.push_back(
          {loops[i].perimeter, loops[i].signed_area, 1, int(loops[i].points.size())});
    }
  if (profiles.empty()) fail_simulation("slice: cross-section has holes but no outer boundary");
  for (std::size_t h = 0; h < loops.size(); ++h) {
    if (loops[h].signed_area > 0.0) continue;
    int best = -1;
    for (std::size_t o = 0; o < loops.size(); ++o) {
      if (profile_of[o] < 0 || !inside(loops[o], loops[h].points[0], e1, e2)) continue;
      if (best < 0 || loops[o].signed_area < loops[best].signed_area) best = int(o);
    }
    if (best < 0)  // not inside any outer loop (round-off at a tangency): the largest one
      for (std::size_t o = 0; o < loops.size(); ++o)
        if (profile_of[o] >= 0 && (best < 0 || loops[o].signed_area > loops[best].signed_area))
          best = int(o);
    SliceProfile& p = profiles[profile_of[best]];
    p.perimeter += loops[h].perimeter;
    p.area += loops[h].signed_area;
    p.loops += 1;
    p.corners += int(loops[h].points.size());
  }
  return profiles;
}

}  // namespace

std::vector<SliceProfile> slice_mesh(const MeshTopology& topo, const Vec3* x, const Plane& plane) {
  std::vector<Loop> loops;
  for (CutLoop& cut : cut_by_plane(x, topo.faces(), plane)) {
    if (!cut.closed) fail_simulation("slice: mesh is not closed");
    Loop loop{std::move(cut.points)};
    const std::size_t n = loop.points.size();
    const Vec3& o = loop.points[0];
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& a = loop.points[i];
      const Vec3& b = loop.points[(i + 1) % n];
      loop.perimeter += (b - a).norm();
      loop.signed_area += 0.5 * (a - o).cross(b - o).dot(plane.normal);
    }
    loops.push_back(std::move(loop));
  }
  if (loops.empty()) return {};
  return profiles_from_loops(loops, plane.normal);
}

void SliceOptions::validate() const {
  if (per_body < 1 || per_body > 8192)
    fail_input("slices: per_body = ", per_body, " must be in [1, 8192]");
  if (!(offset_fraction > 0.0 && offset_fraction <= 1.0))
    fail_input("slices: offset_fraction = ", offset_fraction, " must be in (0, 1]");
}

namespace {
// Counter-based stream of the slice planes (the first user stream).
constexpr RngStream kSliceStream = RngStream(std::uint32_t(RngStream::kUser) + 1);
constexpr int kAttempts = 8;  // random keys reserved per slice (one used)
}  // namespace

std::vector<BodySlice> random_slices(const MeshTopology& topo, const Vec3* x,
                                     const SliceOptions& options, std::uint64_t step, int body) {
  options.validate();
  const int nv = topo.n_vertices();
  const Vec3 c = vertex_centroid(nv, x);
  std::vector<BodySlice> out;
  for (int m = 0; m < options.per_body; ++m) {
    // The plane of slice m uses the first of the kAttempts keys reserved for it (planes
    // through a vertex were redrawn before the on-plane rule of cut_by_plane existed).
    const auto u = RandomKey(options.seed, step, std::uint32_t(body), kSliceStream,
                             std::uint32_t(m * kAttempts))
                       .uniform4();
    const double z = 2.0 * u[0] - 1.0, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 n(rho * std::cos(2.0 * M_PI * u[1]), rho * std::sin(2.0 * M_PI * u[1]), z);
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < nv; ++i) {
      const double h = (x[i] - c).dot(n);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    const double offset = options.offset_fraction * (lo + u[2] * (hi - lo));
    const Plane plane{c + offset * n, n};
    for (const SliceProfile& p : slice_mesh(topo, x, plane))
      out.push_back({body, m, plane, p, p.shape()});
  }
  return out;
}

std::vector<BodySlice> random_slices(const System& sys, const SliceOptions& options) {
  options.validate();
  const int n = int(sys.bodies().size());
  std::vector<std::vector<BodySlice>> per_body(static_cast<std::size_t>(n));
  // An exception must not leave the parallel region: keep the first, rethrow after it.
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic)
  for (int b = 0; b < n; ++b) {
    try {
      const MeshTopology& topo = *sys.bodies()[b].topology;
      std::vector<Vec3> x(std::size_t(topo.n_vertices()));
      sys.body_vertices(b, x.data());
      per_body[b] = random_slices(topo, x.data(), options, sys.step, b);
    } catch (...) {
      failure[b] = std::current_exception();
    }
  }
  for (const auto& e : failure)
    if (e) std::rethrow_exception(e);
  std::vector<BodySlice> out;
  for (auto& v : per_body) out.insert(out.end(), v.begin(), v.end());
  return out;
}

Histogram histogram(std::span<const double> values, double lo, double hi, int bins) {
  if (bins < 1) fail_input("histogram: bins = ", bins, " must be >= 1");
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
    fail_input("histogram: range [", lo, ", ", hi, "] is empty or not finite");
  Histogram h;
  const double width = (hi - lo) / bins;
  for (int i = 0; i <= bins; ++i) h.edges.push_back(i == bins ? hi : lo + i * width);
  h.counts.assign(std::size_t(bins), 0);
  for (double v : values) {
    if (!std::isfinite(v)) {
      ++h.invalid;
    } else if (v < lo) {
      ++h.below;
    } else if (v > hi) {
      ++h.above;
    } else {
      // The bin whose reported edges hold v (the division may round across an edge).
      int k = std::min(bins - 1, int((v - lo) / width));
      if (k + 1 < bins && v >= h.edges[k + 1]) ++k;
      if (k > 0 && v < h.edges[k]) --k;
      ++h.counts[std::size_t(k)];
    }
  }
  std::uint64_t total = 0;
  for (auto c : h.counts) total += c;
  h.density.assign(std::size_t(bins), 0.0);
  if (total > 0)
    for (int i = 0; i < bins; ++i) h.density[i] = double(h.counts[i]) / (double(total) * width);
  return h;
}

}  // namespace invasim
