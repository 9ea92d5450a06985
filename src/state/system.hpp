#pragma once
// The simulated state: box, point sites and deformable bodies. Cancer cells and adipocyte
// vertices are all "sites" in one structure-of-arrays store so a single neighbour list serves
// every contact; an adipocyte is a contiguous block of sites plus its reference geometry.
// Positions are kept wrapped on periodic axes, with image counters to unwrap them.
//
// Two storage layouts (docs/performance.md, "Sites in cell order"): the user layout, in which a
// site's storage index is its permanent index (the order of creation, which every interface,
// group, body block, output and checkpoint uses), and the engine layout, in which the sites are
// stored in the engine order (by kind, then spatially, set by Dynamics), so that neighbours are
// near in memory and index ranges are slabs. Dynamics switches to the engine layout for its
// steps (to_engine) and back at their end (to_user); everything else sees the user layout.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/box.hpp"
#include "mesh/topology.hpp"

namespace invasim {

enum class SiteKind : std::uint8_t { kCancer = 0, kVertex = 1 };

// Structure-of-arrays store of all point sites.
struct Sites {
  std::vector<Vec3> pos, vel, force, orient;
  std::vector<Vec3i> image;
  std::vector<double> diameter, mass;
  std::vector<int> body;  // adipocyte index, -1 for a cancer cell
  std::vector<SiteKind> kind;
  std::size_t size() const { return pos.size(); }
};

// One adipocyte: its block of sites and the reference state of its shape energy.
struct MeshBody {
  std::shared_ptr<const MeshTopology> topology;
  int first_site = 0;
  std::vector<double> ref_area;  // a_k0, one per face
  double ref_volume = 0.0;       // v_0
  // Volume of the union of the mesh and its vertex spheres (the paper's V_i), used for
  // packing fractions; set when the body is created (0 if unknown).
  double outer_volume = 0.0;
  // v_0 when the body was made: lipolysis (integrate/lipolysis.hpp) shrinks v_0 by fractions
  // of it and down to a floor given as a fraction of it.
  double ref_volume_initial = 0.0;
  int n_vertices() const { return topology->n_vertices(); }
};

class System {
 public:
  System(const Box& box, std::uint64_t seed);

  Box& box() { return box_; }
  const Box& box() const { return box_; }
  Sites& sites() { return sites_; }
  const Sites& sites() const { return sites_; }
  std::size_t n_sites() const { return sites_.size(); }
  const std::vector<MeshBody>& bodies() const { return bodies_; }
  std::vector<MeshBody>& bodies() { return bodies_; }
  std::uint64_t seed() const { return seed_; }
  // A new random seed (a run started from another run's saved state draws its own noise).
  void set_seed(std::uint64_t seed) { seed_ = seed; }
  std::uint64_t step = 0;  // completed time steps
  double time = 0.0;       // simulated time

  // The storage layouts (see the header comment). In the engine layout, slot k holds the site of
  // permanent index engine_order()[k]; layout_id() is 0 in the user layout and, in the engine
  // layout, a number unique to the current engine order (process-wide), so that a cache keyed
  // by site slots (neighbour lists, groups) knows when to rebuild.
  bool engine_layout() const { return engine_layout_; }
  std::uint64_t layout_id() const { return engine_layout_ ? engine_id_ : 0; }
  // The engine order (permanent index of every slot), empty until set_engine_order.
  const std::vector<int>& engine_order() const { return order_; }
  // Sets the engine order: a permutation of [0, n_sites) (throws InputError otherwise). In the
  // engine layout the sites move to their new slots at once; an equal order changes nothing.
  void set_engine_order(std::vector<int> order);
  // Moves the sites into the engine order (set_engine_order first) / back to the user order.
  // No-ops when already there.
  void to_engine();
  void to_user();
  // Permanent index of the site in storage slot `slot`, and the slot of permanent index `site`.
  int site_of_slot(int slot) const { return engine_layout_ ? order_[slot] : slot; }
  int slot_of(int site) const { return engine_layout_ ? slot_[site] : site; }
  // Storage slot of vertex v of body b.
  int body_slot(int b, int v) const { return slot_of(bodies_[b].first_site + v); }

  // Adds a cancer cell (or any free sphere); returns its site index. Diameter and mass must
  // be > 0, and the position inside the walls. orientation (if non-zero) is normalised.
  int add_sphere(const Vec3& r, double diameter, double mass = 1.0,
                 const Vec3& orientation = Vec3::Zero());
  // Adds a deformable body with the given vertex positions (unwrapped, any location) and
  // reference state; returns the body index. Every vertex must be inside the walls.
  int add_mesh(std::shared_ptr<const MeshTopology> topology, const std::vector<Vec3>& vertices,
               double vertex_diameter, std::vector<double> ref_area, double ref_volume,
               double mass = 1.0);
  // Adds `shape` scaled by `radius` at `center`, with reference areas scaled by one common
  // factor so that the reference shape parameter is `shape_param` (docs/model.md, "Bodies")
  // and reference volume the initial one.
  int add_mesh_scaled(const MeshShape& shape, const Vec3& center, double radius,
                      double vertex_diameter, double shape_param, double mass = 1.0);

  // Removes free spheres (sites in no body, e.g. cancer cells that die), given by permanent
  // index; the others keep their order. Returns the new index of every old site (-1: removed)
  // and moves the site epoch on. User layout only.
  std::vector<int> remove_sites(const std::vector<int>& sites);
  // Changes whenever a site was removed or born (Proliferation): a list of permanent indices
  // taken at another epoch (a group) no longer names the same cells. 0 for a System whose
  // number of sites changed only by its setup.
  std::uint64_t site_epoch() const { return site_epoch_; }
  void set_site_epoch(std::uint64_t epoch) { site_epoch_ = epoch; }
  // Each site's identity, by permanent index: the number it got when it was created (0, 1, ...
  // in creation order), kept when earlier sites are removed, so that a cell can be followed
  // across deaths (snapshots' id column); next_site_id() is the number the next site gets.
  const std::vector<std::uint64_t>& site_ids() const { return ids_; }
  std::uint64_t next_site_id() const { return next_id_; }
  // Restores the identities (a checkpoint): one per site, each below next.
  void set_site_ids(std::vector<std::uint64_t> ids, std::uint64_t next);

  // Unwrapped position of the site in storage slot i.
  Vec3 unwrapped(std::size_t i) const { return box_.unwrap(sites_.pos[i], sites_.image[i]); }
  // Unwrapped vertex positions of body b, written to out (size n_vertices).
  void body_vertices(int b, Vec3* out) const;
  // Wraps every site into the box on periodic axes.
  void wrap_all();
  // Permanent indices of all sites of a kind (e.g. the cancer-cell group).
  std::vector<int> sites_of_kind(SiteKind kind) const;

  // Scales the box about its lower corner by factors s (per axis) and moves every cancer
  // cell and every body's centroid affinely; bodies move rigidly (shape kept) when
  // rigid_bodies, else every vertex scales too. Velocities are left unchanged.
  void scale(const Vec3& s, bool rigid_bodies);

  // Throws InputError naming the first site outside the walls or with invalid data.
  void validate() const;

 private:
  int push_site(const Vec3& r, double diameter, double mass, int body, SiteKind kind,
                const Vec3& orientation);
  // Throws std::logic_error naming `what` in the engine layout (for the functions that take
  // permanent indices as storage indices).
  void require_user_layout(const char* what) const;
  Box box_;
  Sites sites_;
  std::vector<MeshBody> bodies_;
  std::uint64_t seed_;
  std::uint64_t site_epoch_ = 0;
  std::vector<std::uint64_t> ids_;  // by permanent index
  std::uint64_t next_id_ = 0;
  // The engine order (slot -> permanent index) and its inverse, the layout in use, and the
  // engine order's process-wide number.
  std::vector<int> order_, slot_;
  bool engine_layout_ = false;
  std::uint64_t engine_id_ = 0;
  Sites spare_;  // storage reused by the changes of layout (no state)
};

}  // namespace invasim
