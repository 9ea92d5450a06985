#include "state/system.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"
#include "mesh/geometry.hpp"

namespace invasim {

System::System(const Box& box, std::uint64_t seed) : box_(box), seed_(seed) {}

namespace {

// v[k] becomes v[from[k]] for every k, through `spare` (its storage reused from call to call:
// the layouts change twice per run of steps).
template <typename T>
void gather(std::vector<T>& v, std::vector<T>& spare, const std::vector<int>& from) {
  spare.resize(from.size());
  for (std::size_t k = 0; k < from.size(); ++k) spare[k] = v[std::size_t(from[k])];
  v.swap(spare);
}

void gather_sites(Sites& s, Sites& spare, const std::vector<int>& from) {
  gather(s.pos, spare.pos, from);
  gather(s.vel, spare.vel, from);
  gather(s.force, spare.force, from);
  gather(s.orient, spare.orient, from);
  gather(s.image, spare.image, from);
  gather(s.diameter, spare.diameter, from);
  gather(s.mass, spare.mass, from);
  gather(s.body, spare.body, from);
  gather(s.kind, spare.kind, from);
}

// Numbers of the engine orders, unique in the process (never 0, the user layout's id).
std::uint64_t next_engine_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

}  // namespace

void System::require_user_layout(const char* what) const {
  if (engine_layout_)
    throw std::logic_error(std::string(what) +
                           ": the sites are in the engine layout (only a "
                           "Dynamics step stores them so)");
}

void System::set_engine_order(std::vector<int> order) {
  const std::size_t n = sites_.size();
  if (order.size() != n) fail_input("engine order: ", order.size(), " entries for ", n, " sites");
  std::vector<int> slot(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const int i = order[k];
    if (i < 0 || std::size_t(i) >= n || slot[std::size_t(i)] >= 0)
      fail_input("engine order: entry ", k, " = ", i,
                 " is outside [0, n_sites) or repeats a site; it must be a permutation");
    slot[std::size_t(i)] = int(k);
  }
  if (order == order_) return;
  if (engine_layout_) {
    // The site of new slot k is at old slot slot_[order[k]].
    std::vector<int> from(n);
    for (std::size_t k = 0; k < n; ++k) from[k] = slot_[std::size_t(order[k])];
    gather_sites(sites_, spare_, from);
  }
  order_ = std::move(order);
  slot_ = std::move(slot);
  engine_id_ = next_engine_id();
}

void System::to_engine() {
  if (engine_layout_) return;
  if (order_.size() != sites_.size())
    throw std::logic_error("System::to_engine: no engine order for the current sites");
  gather_sites(sites_, spare_, order_);
  engine_layout_ = true;
}

void System::to_user() {
  if (!engine_layout_) return;
  gather_sites(sites_, spare_, slot_);
  engine_layout_ = false;
}

int System::push_site(const Vec3& r, double diameter, double mass, int body, SiteKind kind,
                      const Vec3& orientation) {
  require_user_layout("adding a site");
  const std::size_t id = sites_.size();
  if (!(diameter > 0.0) || !std::isfinite(diameter))
    fail_input("site ", id, ": diameter = ", diameter, " must be finite and > 0");
  if (!(mass > 0.0) || !std::isfinite(mass))
    fail_input("site ", id, ": mass = ", mass, " must be finite and > 0");
  if (!r.allFinite()) fail_input("site ", id, ": position is not finite");
  if (const int a = box_.axis_outside_walls(r); a >= 0)
    fail_input("site ", id, ": ", "xyz"[a], " = ", r[a], " is outside the walls [", box_.lo()[a],
               ", ", box_.hi()[a], "]");
  Vec3 wrapped = r;
  Vec3i image = Vec3i::Zero();
  box_.wrap(wrapped, image);
  const double n = orientation.norm();
  sites_.pos.push_back(wrapped);
  sites_.image.push_back(image);
  sites_.vel.push_back(Vec3::Zero());
  sites_.force.push_back(Vec3::Zero());
  sites_.orient.push_back(n > 0 ? Vec3(orientation / n) : Vec3::Zero());
  sites_.diameter.push_back(diameter);
  sites_.mass.push_back(mass);
  sites_.body.push_back(body);
  sites_.kind.push_back(kind);
  ids_.push_back(next_id_++);
  // A new site: the engine order is chosen again (by Dynamics) for the new set of sites.
  order_.clear();
  slot_.clear();
  return int(id);
}

std::vector<int> System::remove_sites(const std::vector<int>& sites) {
  require_user_layout("removing sites");
  const std::size_t n = sites_.size();
  std::vector<int> new_index(n, 0);
  for (int i : sites) {
    if (i < 0 || std::size_t(i) >= n) fail_input("remove_sites: no site ", i);
    if (sites_.body[i] >= 0)
      fail_input("remove_sites: site ", i, " is a vertex of adipocyte ", sites_.body[i]);
    new_index[i] = -1;
  }
  std::vector<int> kept;  // the old index of each new site
  for (std::size_t i = 0; i < n; ++i)
    if (new_index[i] >= 0) {
      new_index[i] = int(kept.size());
      kept.push_back(int(i));
    }
  gather_sites(sites_, spare_, kept);
  std::vector<std::uint64_t> spare_ids;
  gather(ids_, spare_ids, kept);
  for (MeshBody& b : bodies_) b.first_site = new_index[b.first_site];
  order_.clear();
  slot_.clear();
  ++site_epoch_;
  return new_index;
}

void System::set_site_ids(std::vector<std::uint64_t> ids, std::uint64_t next) {
  if (ids.size() != sites_.size())
    fail_input("site ids: ", ids.size(), " for ", sites_.size(), " sites");
  for (std::uint64_t id : ids)
    if (id >= next) fail_input("site ids: id ", id, " is not below the next id ", next);
  ids_ = std::move(ids);
  next_id_ = next;
}

int System::add_sphere(const Vec3& r, double diameter, double mass, const Vec3& orientation) {
  return push_site(r, diameter, mass, -1, SiteKind::kCancer, orientation);
}

int System::add_mesh(std::shared_ptr<const MeshTopology> topology,
                     const std::vector<Vec3>& vertices, double vertex_diameter,
                     std::vector<double> ref_area, double ref_volume, double mass) {
  require_user_layout("adding an adipocyte");
  if (!topology) fail_input("add_mesh: no mesh topology given");
  const int body = int(bodies_.size());
  if (int(vertices.size()) != topology->n_vertices())
    fail_input("adipocyte ", body, ": ", vertices.size(), " vertex positions for a mesh of ",
               topology->n_vertices(), " vertices");
  if (int(ref_area.size()) != topology->n_faces())
    fail_input("adipocyte ", body, ": ", ref_area.size(), " reference areas for ",
               topology->n_faces(), " faces");
  for (std::size_t k = 0; k < ref_area.size(); ++k)
    if (!(ref_area[k] > 0.0))
      fail_input("adipocyte ", body, ": reference area of face ", k, " = ", ref_area[k],
                 " must be > 0");
  if (!(ref_volume > 0.0))
    fail_input("adipocyte ", body, ": reference volume = ", ref_volume, " must be > 0");
  const double volume = mesh_volume(*topology, vertices.data());
  if (!(volume > 0.0))
    fail_input("adipocyte ", body, ": mesh volume = ", volume,
               " is not positive; faces must be oriented outward");
  // Validate every vertex before adding any, so a failure leaves the system unchanged.
  for (std::size_t v = 0; v < vertices.size(); ++v)
    if (const int a = box_.axis_outside_walls(vertices[v]); a >= 0)
      fail_input("adipocyte ", body, ": vertex ", v, " has ", "xyz"[a], " = ", vertices[v][a],
                 " outside the walls [", box_.lo()[a], ", ", box_.hi()[a], "]");
  if (!(vertex_diameter > 0.0))
    fail_input("adipocyte ", body, ": vertex diameter = ", vertex_diameter, " must be > 0");
  MeshBody mb{topology, int(sites_.size()), std::move(ref_area), ref_volume};
  mb.ref_volume_initial = ref_volume;
  for (const Vec3& x : vertices)
    push_site(x, vertex_diameter, mass, body, SiteKind::kVertex, Vec3::Zero());
  bodies_.push_back(std::move(mb));
  return body;
}

int System::add_mesh_scaled(const MeshShape& shape, const Vec3& center, double radius,
                            double vertex_diameter, double shape_param, double mass) {
  require_positive("radius", radius);
  if (!(shape_param >= 1.0))
    fail_input("shape_param = ", shape_param, " must be >= 1 (1 is a sphere)");
  std::vector<Vec3> x;
  for (const Vec3& v : shape.vertices) x.push_back(center + radius * v);
  const MeshTopology& topo = *shape.topology;
  const double volume = mesh_volume(topo, x.data());
  std::vector<double> area(topo.n_faces());
  double total = 0.0;
  for (int k = 0; k < topo.n_faces(); ++k) total += area[k] = face_area(topo, x.data(), k);
  // (c S)^(3/2) = A0 6 sqrt(pi) V  =>  c = (A0 6 sqrt(pi) V)^(2/3) / S.
  const double c = std::pow(shape_param * 6.0 * std::sqrt(M_PI) * volume, 2.0 / 3.0) / total;
  for (double& a : area) a *= c;
  return add_mesh(shape.topology, x, vertex_diameter, std::move(area), volume, mass);
}

void System::body_vertices(int b, Vec3* out) const {
  const MeshBody& body = bodies_[b];
  for (int v = 0; v < body.n_vertices(); ++v) out[v] = unwrapped(slot_of(body.first_site + v));
}

void System::wrap_all() {
  for (std::size_t i = 0; i < sites_.size(); ++i) box_.wrap(sites_.pos[i], sites_.image[i]);
}

std::vector<int> System::sites_of_kind(SiteKind kind) const {
  std::vector<int> out;
  for (std::size_t i = 0; i < sites_.size(); ++i)
    if (sites_.kind[i] == kind) out.push_back(site_of_slot(int(i)));
  std::sort(out.begin(), out.end());
  return out;
}

void System::scale(const Vec3& s, bool rigid_bodies) {
  const Vec3 lo = box_.lo();
  auto map = [&](const Vec3& r) -> Vec3 { return lo + s.cwiseProduct(r - lo); };
  // Work on unwrapped positions so bodies that straddle a periodic edge stay whole.
  std::vector<Vec3> u(sites_.size());
  for (std::size_t i = 0; i < sites_.size(); ++i) u[i] = unwrapped(i);
  for (std::size_t i = 0; i < sites_.size(); ++i)
    if (sites_.body[i] < 0 || !rigid_bodies) u[i] = map(u[i]);
  if (rigid_bodies)
    for (const MeshBody& b : bodies_) {
      std::vector<Vec3> x(std::size_t(b.n_vertices()));
      for (int v = 0; v < b.n_vertices(); ++v) x[v] = u[slot_of(b.first_site + v)];
      const Vec3 c = vertex_centroid(b.n_vertices(), x.data());
      const Vec3 shift = map(c) - c;
      for (int v = 0; v < b.n_vertices(); ++v) u[slot_of(b.first_site + v)] += shift;
    }
  box_.set_bounds(lo, map(box_.hi()));
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    sites_.pos[i] = u[i];
    sites_.image[i] = Vec3i::Zero();
    box_.wrap(sites_.pos[i], sites_.image[i]);
  }
}

void System::validate() const {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (!sites_.pos[i].allFinite() || !sites_.vel[i].allFinite())
      fail_simulation("site ", site_of_slot(int(i)), ": position or velocity is not finite");
    for (int a = 0; a < 3; ++a)
      if (!box_.periodic(a) && (sites_.pos[i][a] < box_.lo()[a] - sites_.diameter[i] ||
                                sites_.pos[i][a] > box_.hi()[a] + sites_.diameter[i]))
        fail_simulation("site ", site_of_slot(int(i)), " escaped through the wall: ", "xyz"[a],
                        " = ", sites_.pos[i][a], ", walls at [", box_.lo()[a], ", ", box_.hi()[a],
                        "]");
  }
}

}  // namespace invasim
