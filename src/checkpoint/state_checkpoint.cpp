#include "checkpoint/state_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace invasim {

namespace {

// Section names "<prefix>.<field>".
struct Keys {
  std::string prefix;
  std::string operator()(const char* field) const { return prefix + "." + field; }
};

bool same_topology(const MeshTopology& a, const MeshTopology& b) {
  return &a == &b || (a.n_vertices() == b.n_vertices() && a.faces() == b.faces());
}

// A vec3 section that must hold exactly one vector.
Vec3 get_one_vec3(const CheckpointReader& in, const std::string& name) {
  const std::vector<Vec3> v = in.get_vec3s(name);
  if (v.size() != 1) in.fail("section '", name, "' holds ", v.size(), " vectors, expected 1");
  return v[0];
}

// Checks that a per-site or per-body array has `n` entries.
template <typename T>
const std::vector<T>& sized(const CheckpointReader& in, const std::string& name,
                            const std::vector<T>& v, std::size_t n, const char* what) {
  if (v.size() != n) in.fail("section '", name, "' has ", v.size(), " entries for ", n, " ", what);
  return v;
}

// The stored bodies, checked against the stored sites before anything is rebuilt.
struct StoredBodies {
  std::vector<std::shared_ptr<const MeshTopology>> topologies;
  std::vector<int> topology, first_site;
  std::vector<double> ref_area, ref_volume, outer_volume, ref_volume_initial;
  std::vector<std::size_t> area_offset;  // first reference area of each body
};

StoredBodies read_bodies(const CheckpointReader& in, const Keys& key, const Sites& s) {
  StoredBodies b;
  const std::vector<int> nv = in.get_i32s(key("topologies.n_vertices"));
  const std::vector<int> nf =
      sized(in, key("topologies.n_faces"), in.get_i32s(key("topologies.n_faces")), nv.size(),
            "topologies");
  const std::vector<int> faces = in.get_i32s(key("topologies.faces"));
  std::size_t at = 0;
  for (std::size_t t = 0; t < nv.size(); ++t) {
    // A topology sizes per-vertex arrays: its vertices must be sites of this checkpoint.
    if (nv[t] < 0 || std::size_t(nv[t]) > s.size())
      in.fail("section '", key("topologies.n_vertices"), "': topology ", t, " has ", nv[t],
              " vertices, outside [0, ", s.size(), "] (the number of stored sites)");
    if (nf[t] < 0 || faces.size() - at < 3 * std::size_t(nf[t]))
      in.fail("section '", key("topologies.faces"), "' is too short for topology ", t);
    std::vector<MeshTopology::Face> f(nf[t]);
    for (auto& face : f)
      for (int& v : face) v = faces[at++];
    try {
      b.topologies.push_back(std::make_shared<const MeshTopology>(nv[t], std::move(f)));
    } catch (const InputError& e) {
      in.fail("topology ", t, ": ", e.what());
    }
  }
  if (at != faces.size()) in.fail("section '", key("topologies.faces"), "' is too long");

  b.topology = in.get_i32s(key("bodies.topology"));
  const std::size_t n_bodies = b.topology.size();
  b.first_site = sized(in, key("bodies.first_site"), in.get_i32s(key("bodies.first_site")),
                       n_bodies, "bodies");
  b.ref_volume = sized(in, key("bodies.ref_volume"), in.get_f64s(key("bodies.ref_volume")),
                       n_bodies, "bodies");
  b.outer_volume = sized(in, key("bodies.outer_volume"), in.get_f64s(key("bodies.outer_volume")),
                         n_bodies, "bodies");
  b.ref_area = in.get_f64s(key("bodies.ref_area"));
  // (Absent from checkpoints written before lipolysis existed: v_0 had never changed.)
  b.ref_volume_initial =
      in.has(key("bodies.ref_volume_initial"))
          ? sized(in, key("bodies.ref_volume_initial"),
                  in.get_f64s(key("bodies.ref_volume_initial")), n_bodies, "bodies")
          : b.ref_volume;
  for (std::size_t k = 0; k < n_bodies; ++k)
    if (!(b.ref_volume_initial[k] > 0.0) || !std::isfinite(b.ref_volume_initial[k]))
      in.fail("section '", key("bodies.ref_volume_initial"), "': body ", k,
              " has initial reference volume ", b.ref_volume_initial[k], " (must be > 0)");

  // Every body is a contiguous block of vertex sites, in increasing site order (as add_mesh
  // builds them); every other site is a cancer cell.
  std::size_t areas = 0;
  int next_site = 0;
  std::vector<int> owner(s.size(), -1);
  for (std::size_t k = 0; k < n_bodies; ++k) {
    const int t = b.topology[k];
    if (t < 0 || std::size_t(t) >= b.topologies.size())
      in.fail("body ", k, ": topology index ", t, " out of range");
    const int first = b.first_site[k], n = b.topologies[t]->n_vertices();
    if (first < next_site || std::size_t(first) + n > s.size())
      in.fail("body ", k, ": sites [", first, ", ", std::size_t(first) + std::size_t(n),
              ") overlap another body or lie ", "outside the ", s.size(), " sites");
    for (int i = first; i < first + n; ++i) owner[i] = int(k);
    next_site = first + n;
    b.area_offset.push_back(areas);
    areas += b.topologies[t]->n_faces();
  }
  if (b.ref_area.size() != areas)
    in.fail("section '", key("bodies.ref_area"), "' has ", b.ref_area.size(),
            " reference areas for ", areas, " faces");
  for (std::size_t i = 0; i < s.size(); ++i) {
    const bool vertex = s.kind[i] == SiteKind::kVertex;
    if (s.body[i] != owner[i] || vertex != (owner[i] >= 0))
      in.fail("site ", i, ": kind ", int(s.kind[i]), " and body ", s.body[i],
              " do not match the body blocks");
  }
  return b;
}

// Adds every site and body to sys in stored order through the public API (which validates
// them), with the walls temporarily widened so that sites slightly beyond a wall (allowed
// during a run) are accepted. Values are overwritten exactly afterwards.
void rebuild_sites(const CheckpointReader& in, System& sys, const Sites& s, const StoredBodies& b) {
  Box& box = sys.box();
  const Vec3 lo = box.lo(), hi = box.hi();
  for (int a = 0; a < 3; ++a) {
    if (box.periodic(a)) continue;
    double min = lo[a], max = hi[a];
    for (const Vec3& r : s.pos) min = std::min(min, r[a]), max = std::max(max, r[a]);
    box.set_wall(a, false, min - 1.0);
    box.set_wall(a, true, max + 1.0);
  }
  std::size_t next_body = 0;
  std::vector<Vec3> x;
  try {
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] == SiteKind::kCancer) {
        sys.add_sphere(box.unwrap(s.pos[i], s.image[i]), s.diameter[i], s.mass[i]);
        continue;
      }
      const auto& topo = b.topologies[b.topology[next_body]];
      x.resize(topo->n_vertices());
      for (int v = 0; v < topo->n_vertices(); ++v) x[v] = box.unwrap(s.pos[i + v], s.image[i + v]);
      const std::size_t a0 = b.area_offset[next_body];
      std::vector<double> area(b.ref_area.begin() + a0, b.ref_area.begin() + a0 + topo->n_faces());
      sys.add_mesh(topo, x, s.diameter[i], std::move(area), b.ref_volume[next_body], s.mass[i]);
      i += topo->n_vertices() - 1;
      ++next_body;
    }
  } catch (const InputError& e) {
    in.fail("cannot rebuild the system: ", e.what());
  }
  for (int a = 0; a < 3; ++a)
    if (!box.periodic(a)) {
      box.set_wall(a, false, lo[a]);
      box.set_wall(a, true, hi[a]);
    }
}

}  // namespace

void write_system(CheckpointWriter& out, const System& sys, const std::string& prefix) {
  if (sys.engine_layout())
    throw std::logic_error("write_system: the sites are in the engine layout (inside a step)");
  const Keys key{prefix};
  const Box& box = sys.box();
  out.put_vec3s(key("box.lo"), {box.lo()});
  out.put_vec3s(key("box.hi"), {box.hi()});
  out.put_i32s(key("box.periodic"), {box.periodic(0), box.periodic(1), box.periodic(2)});
  out.put_u64(key("box.version"), box.version());
  out.put_u64(key("seed"), sys.seed());
  out.put_u64(key("step"), sys.step);
  out.put_f64(key("time"), sys.time);
  // Only once cells were born or died (Proliferation), so that other checkpoints stay as they
  // were: the epoch and the sites' identities (System::site_ids).
  if (sys.site_epoch() > 0) {
    out.put_u64(key("site_epoch"), sys.site_epoch());
    out.put_u64s(key("sites.id"), sys.site_ids());
    out.put_u64(key("next_site_id"), sys.next_site_id());
  }

  const Sites& s = sys.sites();
  out.put_vec3s(key("sites.pos"), s.pos);
  out.put_vec3s(key("sites.vel"), s.vel);
  out.put_vec3s(key("sites.force"), s.force);
  out.put_vec3s(key("sites.orient"), s.orient);
  out.put_vec3is(key("sites.image"), s.image);
  out.put_f64s(key("sites.diameter"), s.diameter);
  out.put_f64s(key("sites.mass"), s.mass);
  out.put_i32s(key("sites.body"), s.body);
  std::vector<int> kind(s.kind.size());
  std::transform(s.kind.begin(), s.kind.end(), kind.begin(), [](SiteKind k) { return int(k); });
  out.put_i32s(key("sites.kind"), kind);
  // The engine order of the sites (Dynamics' storage order during its steps): a restored run
  // then sums its forces in the same order as the run that wrote the checkpoint.
  if (!sys.engine_order().empty()) out.put_i32s(key("sites.engine_order"), sys.engine_order());

  // Distinct topologies (by content), then each body's index into them.
  std::vector<const MeshTopology*> topologies;
  std::vector<int> topology, first_site;
  std::vector<double> ref_area, ref_volume, outer_volume, ref_volume_initial;
  for (const MeshBody& b : sys.bodies()) {
    auto it = std::find_if(topologies.begin(), topologies.end(),
                           [&](const MeshTopology* t) { return same_topology(*t, *b.topology); });
    if (it == topologies.end()) it = topologies.insert(topologies.end(), b.topology.get());
    topology.push_back(int(it - topologies.begin()));
    first_site.push_back(b.first_site);
    ref_area.insert(ref_area.end(), b.ref_area.begin(), b.ref_area.end());
    ref_volume.push_back(b.ref_volume);
    outer_volume.push_back(b.outer_volume);
    ref_volume_initial.push_back(b.ref_volume_initial);
  }
  std::vector<int> n_vertices, n_faces, faces;
  for (const MeshTopology* t : topologies) {
    n_vertices.push_back(t->n_vertices());
    n_faces.push_back(t->n_faces());
    for (const auto& f : t->faces()) faces.insert(faces.end(), f.begin(), f.end());
  }
  out.put_i32s(key("topologies.n_vertices"), n_vertices);
  out.put_i32s(key("topologies.n_faces"), n_faces);
  out.put_i32s(key("topologies.faces"), faces);
  out.put_i32s(key("bodies.topology"), topology);
  out.put_i32s(key("bodies.first_site"), first_site);
  out.put_f64s(key("bodies.ref_area"), ref_area);
  out.put_f64s(key("bodies.ref_volume"), ref_volume);
  out.put_f64s(key("bodies.outer_volume"), outer_volume);
  out.put_f64s(key("bodies.ref_volume_initial"), ref_volume_initial);
}

System read_system(const CheckpointReader& in, const std::string& prefix) {
  const Keys key{prefix};
  const Vec3 lo = get_one_vec3(in, key("box.lo")), hi = get_one_vec3(in, key("box.hi"));
  const std::vector<int> per = in.get_i32s(key("box.periodic"));
  if (per.size() != 3) in.fail("section '", key("box.periodic"), "' must hold 3 flags");
  Box box;
  try {
    box = Box(lo, hi, {per[0] != 0, per[1] != 0, per[2] != 0});
  } catch (const InputError& e) {
    in.fail("box: ", e.what());
  }
  System sys(box, in.get_u64(key("seed")));

  Sites s;
  s.pos = in.get_vec3s(key("sites.pos"));
  const std::size_t n = s.pos.size();
  auto vec3s = [&](const char* f) { return sized(in, key(f), in.get_vec3s(key(f)), n, "sites"); };
  auto f64s = [&](const char* f) { return sized(in, key(f), in.get_f64s(key(f)), n, "sites"); };
  auto i32s = [&](const char* f) { return sized(in, key(f), in.get_i32s(key(f)), n, "sites"); };
  s.vel = vec3s("sites.vel");
  s.force = vec3s("sites.force");
  s.orient = vec3s("sites.orient");
  s.image = sized(in, key("sites.image"), in.get_vec3is(key("sites.image")), n, "sites");
  s.diameter = f64s("sites.diameter");
  s.mass = f64s("sites.mass");
  s.body = i32s("sites.body");
  for (int k : i32s("sites.kind")) {
    if (k != int(SiteKind::kCancer) && k != int(SiteKind::kVertex))
      in.fail("section '", key("sites.kind"), "' holds an unknown site kind ", k);
    s.kind.push_back(SiteKind(k));
  }
  const StoredBodies bodies = read_bodies(in, key, s);
  rebuild_sites(in, sys, s, bodies);

  // Exact values: every array as stored, the reference state, the counters.
  for (std::size_t k = 0; k < bodies.topology.size(); ++k) {
    MeshBody& b = sys.bodies()[k];
    if (b.first_site != bodies.first_site[k]) in.fail("body ", k, " was rebuilt at another site");
    b.outer_volume = bodies.outer_volume[k];
    b.ref_volume_initial = bodies.ref_volume_initial[k];
  }
  sys.sites() = std::move(s);
  // (Absent from checkpoints written before the engine order existed: the next run chooses one.)
  if (in.has(key("sites.engine_order"))) {
    try {
      sys.set_engine_order(in.get_i32s(key("sites.engine_order")));
    } catch (const InputError& e) {
      in.fail("section '", key("sites.engine_order"), "': ", e.what());
    }
  }
  // Box::version counts set_bounds calls: restored as stored (any value is a valid count, and
  // the System rebuilt above has not yet counted any change).
  const std::uint64_t version = in.get_u64(key("box.version"));
  if (version < sys.box().version())
    in.fail("section '", key("box.version"), "' holds ", version, ", below the ",
            sys.box().version(), " of a freshly built box");
  sys.box().restore_version(version);
  sys.step = in.get_u64(key("step"));
  sys.time = in.get_f64(key("time"));
  if (in.has(key("site_epoch"))) sys.set_site_epoch(in.get_u64(key("site_epoch")));
  if (in.has(key("sites.id"))) {
    try {
      sys.set_site_ids(in.get_u64s(key("sites.id")), in.get_u64(key("next_site_id")));
    } catch (const InputError& e) {
      in.fail("section '", key("sites.id"), "': ", e.what());
    }
  }
  return sys;
}

void write_tethers(CheckpointWriter& out, const TetherForce& tethers, const std::string& prefix) {
  const Keys key{prefix};
  std::vector<int> a, b, periods;
  std::vector<double> rest;
  for (const Tether& t : tethers.tethers()) {
    a.push_back(t.a);
    b.push_back(t.b);
    rest.push_back(t.rest_length);
    periods.insert(periods.end(), t.periods.begin(), t.periods.end());
  }
  out.put_f64(key("stiffness"), tethers.stiffness());
  out.put_i32s(key("a"), a);
  out.put_i32s(key("b"), b);
  out.put_f64s(key("rest_length"), rest);
  out.put_i32s(key("periods"), periods);
}

void read_tethers(const CheckpointReader& in, const System& sys, TetherForce& tethers,
                  const std::string& prefix) {
  if (!tethers.tethers().empty())
    fail_input("read_tethers: the tether force already holds ", tethers.tethers().size(),
               " tethers");
  const Keys key{prefix};
  const std::vector<int> a = in.get_i32s(key("a"));
  const std::vector<int> b = sized(in, key("b"), in.get_i32s(key("b")), a.size(), "tethers");
  const std::vector<double> rest =
      sized(in, key("rest_length"), in.get_f64s(key("rest_length")), a.size(), "tethers");
  // A checkpoint written before tethers kept their image has no `periods`: its tethers take
  // the nearest image as the bodies stand (what they used at every step then).
  const bool has_periods = in.has(key("periods"));
  const std::vector<int> periods = has_periods
                                       ? sized(in, key("periods"), in.get_i32s(key("periods")),
                                               3 * a.size(), "tether periods (3 per tether)")
                                       : std::vector<int>();
  try {
    tethers.set_stiffness(in.get_f64(key("stiffness")));
    for (std::size_t k = 0; k < a.size(); ++k)
      if (has_periods)
        tethers.add(sys, a[k], b[k], rest[k],
                    Vec3i(periods[3 * k], periods[3 * k + 1], periods[3 * k + 2]));
      else
        tethers.add(sys, a[k], b[k], rest[k]);
  } catch (const IoError&) {
    throw;
  } catch (const InputError& e) {
    in.fail("section '", prefix, "': ", e.what());
  }
}

namespace {

// The pressure wall's state, in the order of its sections.
constexpr std::pair<const char*, double PressureWall::*> kWallFields[] = {
    {"pressure", &PressureWall::pressure}, {"mass", &PressureWall::mass},
    {"gamma", &PressureWall::gamma},       {"kT", &PressureWall::kT},
    {"velocity", &PressureWall::velocity}, {"force", &PressureWall::force}};

}  // namespace

void write_pressure_wall(CheckpointWriter& out, const PressureWall& wall,
                         const std::string& prefix) {
  const Keys key{prefix};
  for (const auto& [name, field] : kWallFields) out.put_f64(key(name), wall.*field);
}

void read_pressure_wall(const CheckpointReader& in, PressureWall& wall, const std::string& prefix) {
  const Keys key{prefix};
  for (const auto& [name, field] : kWallFields)
    // Checkpoints written before the piston had a bath have no kT: 0 (no noise), as they ran.
    wall.*field = field == &PressureWall::kT && !in.has(key(name)) ? 0.0 : in.get_f64(key(name));
}

}  // namespace invasim
