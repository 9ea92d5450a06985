// Voronoi tessellation with CGAL (the only translation unit that includes CGAL headers) and
// the measurements built on it. See voronoi.hpp and docs/measurements.md.
#include "measure/voronoi.hpp"

// CGAL's containers keep their freed blocks for the next call (recycling_allocator.hpp): every
// call builds a fresh triangulation of about the same size. Must precede the CGAL headers.
#include "measure/recycling_allocator.hpp"
#define CGAL_ALLOCATOR(T) invasim::RecyclingAllocator<T>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>
#include <unordered_set>
#include <utility>

#include "core/errors.hpp"

namespace invasim {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// Per-cell data: the (weighted) circumcentre, computed once while the cell is verified.
struct CellInfo {
  Vec3 center = Vec3::Zero();
  bool verified = false;  // no point of the unfolded set is inside its sphere
};

// Plain Voronoi: Delaunay triangulation; vertex info = index of the point's Tag.
using DelaunayVb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using DelaunayCb =
    CGAL::Triangulation_cell_base_with_info_3<CellInfo, K,
                                              CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Delaunay =
    CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<DelaunayVb, DelaunayCb>>;

// Radical (power) tessellation: regular triangulation of weighted points.
using RegularVb =
    CGAL::Triangulation_vertex_base_with_info_3<int, K,
                                                CGAL::Regular_triangulation_vertex_base_3<K>>;
using RegularCb =
    CGAL::Triangulation_cell_base_with_info_3<CellInfo, K,
                                              CGAL::Regular_triangulation_cell_base_3<K>>;
using Regular =
    CGAL::Regular_triangulation_3<K, CGAL::Triangulation_data_structure_3<RegularVb, RegularCb>>;

Vec3 to_vec(const K::Point_3& p) {
  return Vec3(p.x(), p.y(), p.z());
}
Vec3 to_vec(const K::Weighted_point_3& p) {
  return to_vec(p.point());
}
double weight_of(const K::Point_3&) {
  return 0.0;
}
double weight_of(const K::Weighted_point_3& p) {
  return p.weight();
}
K::Point_3 make_point(const Delaunay&, const Vec3& r, double) {
  return {r.x(), r.y(), r.z()};
}
K::Weighted_point_3 make_point(const Regular&, const Vec3& r, double w) {
  return {K::Point_3(r.x(), r.y(), r.z()), w};
}

// Circumcentre of a Delaunay cell; power (weighted circum-) centre of a regular cell.
Vec3 cell_center(const Delaunay&, Delaunay::Cell_handle c) {
  return to_vec(CGAL::circumcenter(c->vertex(0)->point(), c->vertex(1)->point(),
                                   c->vertex(2)->point(), c->vertex(3)->point()));
}
Vec3 cell_center(const Regular& tr, Regular::Cell_handle c) {
  return to_vec(tr.geom_traits().construct_weighted_circumcenter_3_object()(
      c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point()));
}

// What a triangulated point is: an image of `site` on side -1 (beyond the left wall: mirror
// images and their copies), 0 (inside the slab) or +1 (beyond the right wall), shifted by
// (sy, sz) periods in y and z. The real site is side 0 with no shift.
struct Tag {
  int site = 0;
  int side = 0;
  int sy = 0, sz = 0;
  bool real() const { return side == 0 && sy == 0 && sz == 0; }
};

// The sites as triangulated: x clamped inside the walls, y and z wrapped, coincident sites
// reduced to one (`used`), and the box geometry.
struct PreparedSites {
  Vec3 lo, hi, len;
  std::vector<Vec3> pos;
  std::vector<double> weight;
  std::vector<char> used;
  double w_max = 0.0;
  double spacing = 1.0;  // (V / N)^(1/3): scale for the automatic margin and tolerances
};

// Fraction of L_x by which a site at or beyond a wall is kept inside it, so that the site and
// its mirror image stay distinct points.
constexpr double kWallGap = 1e-9;
// Faces smaller than this times spacing^2 are degenerate (zero-area duals of Delaunay edges
// in cospherical configurations, e.g. lattices) and are not listed.
constexpr double kTinyArea = 1e-12;
// Automatic initial image margin, in mean site spacings (see docs/measurements.md).
constexpr double kAutoMargin = 2.0;
// Refinement passes allowed in one build (each inserts at least one point; a handful is usual).
constexpr int kMaxRefinements = 1000;

double wrap_into(double v, double lo, double len) {
  double t = std::fmod(v - lo, len);
  if (t < 0.0) t += len;
  if (t >= len) t = 0.0;
  return lo + t;
}

// Marks all but one of each group of exactly coincident sites as unused (keeps the largest
// weight, then the lowest index): a triangulation keeps only one vertex per position.
void drop_coincident(PreparedSites& s) {
  std::vector<int> order(s.pos.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) { return std::make_tuple(s.pos[i].x(), s.pos[i].y(), s.pos[i].z()); };
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    if (key(i) != key(j)) return key(i) < key(j);
    if (s.weight[i] != s.weight[j]) return s.weight[i] > s.weight[j];
    return i < j;
  });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (key(order[k]) == key(order[k - 1])) s.used[order[k]] = 0;
}

PreparedSites prepare(const Box& box, const std::vector<Vec3>& points,
                      const std::vector<double>& w) {
  PreparedSites s;
  s.lo = box.lo();
  s.hi = box.hi();
  s.len = box.lengths();
  const double gap = kWallGap * s.len.x();
  s.pos.resize(points.size());
  s.weight = w.empty() ? std::vector<double>(points.size(), 0.0) : w;
  s.used.assign(points.size(), 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) fail_simulation("Voronoi: site ", i, " is not finite");
    s.pos[i].x() = std::clamp(points[i].x(), s.lo.x() + gap, s.hi.x() - gap);
    for (int a = 1; a < 3; ++a) s.pos[i][a] = wrap_into(points[i][a], s.lo[a], s.len[a]);
  }
  drop_coincident(s);
  for (double x : s.weight) s.w_max = std::max(s.w_max, x);
  s.spacing = std::cbrt(box.volume() / std::max<std::size_t>(points.size(), 1));
  return s;
}

// The unfolded point set: the sites and their mirror images across x = lo form a pattern
// periodic with period (2 L_x, L_y, L_z); mirroring it across x = lo or x = hi leaves it
// unchanged, so a site's Voronoi cell in it is the site's cell in the walled box. Point
// (f, k) is fundamental point f (2 i: site i; 2 i + 1: its mirror 2 lo - x) shifted by k
// periods. A grid over the fundamental domain finds the points in any axis-aligned box.
class Unfolded {
 public:
  explicit Unfolded(const PreparedSites& s) : s_(s) {
    origin_ = Vec3(s.lo.x() - s.len.x(), s.lo.y(), s.lo.z());
    period_ = Vec3(2.0 * s.len.x(), s.len.y(), s.len.z());
    for (std::size_t i = 0; i < s.pos.size(); ++i) {
      if (!s.used[i]) continue;
      fund_.push_back({int(2 * i), s.pos[i]});
      fund_.push_back(
          {int(2 * i + 1), Vec3(2.0 * s.lo.x() - s.pos[i].x(), s.pos[i].y(), s.pos[i].z())});
    }
    build_grid();
  }

  const PreparedSites& sites() const { return s_; }
  // A margin that always suffices: an empty sphere is smaller than the period cell
  // (2 L_x, L_y, L_z), as it cannot hold a whole period of points (weights add at most their
  // root to a reach). No point beyond it can be a neighbour of a real site.
  double max_margin() const { return 1.1 * (period_.norm() + 2.0 * std::sqrt(s_.w_max)); }
  // Image of fundamental point f shifted by k periods (computed the same way everywhere, so
  // region tests on it are reproducible).
  Vec3 image(const Vec3& base, const Vec3i& k) const {
    return Vec3(base.x() + k.x() * period_.x(), base.y() + k.y() * period_.y(),
                base.z() + k.z() * period_.z());
  }
  // Whether r lies in the box grown by m on every side.
  bool in_region(const Vec3& r, double m) const {
    for (int a = 0; a < 3; ++a)
      if (!(r[a] >= s_.lo[a] - m && r[a] <= s_.hi[a] + m)) return false;
    return true;
  }
  // Tag of point (f, k) at r.
  Tag tag(int f, const Vec3i& k, const Vec3& r) const {
    const int side = r.x() < s_.lo.x() ? -1 : (r.x() > s_.hi.x() ? 1 : 0);
    return {f / 2, side, k.y(), k.z()};
  }
  // Key identifying point (f, k) (|k| < 512 on every axis).
  static std::uint64_t key(int f, const Vec3i& k) {
    std::uint64_t u = std::uint64_t(f);
    for (int a = 0; a < 3; ++a) u = u * 1024 + std::uint64_t(k[a] + 512);
    return u;
  }
  // Calls fn(f, k, r) for every point r of the unfolded set with a <= r <= b.
  template <class Fn>
  void for_each_in(const Vec3& a, const Vec3& b, Fn&& fn) const {
    Vec3i lo_cell, hi_cell;
    for (int d = 0; d < 3; ++d) {
      lo_cell[d] = int(std::floor((a[d] - origin_[d]) / cell_[d]));
      hi_cell[d] = int(std::floor((b[d] - origin_[d]) / cell_[d]));
    }
    for (int u = lo_cell.x(); u <= hi_cell.x(); ++u)
      for (int v = lo_cell.y(); v <= hi_cell.y(); ++v)
        for (int w = lo_cell.z(); w <= hi_cell.z(); ++w) {
          const Vec3i cell(u, v, w);
          Vec3i wrapped, k;
          for (int d = 0; d < 3; ++d) {
            k[d] = floor_div(cell[d], n_[d]);
            wrapped[d] = cell[d] - k[d] * n_[d];
          }
          const int c = (wrapped.x() * n_.y() + wrapped.y()) * n_.z() + wrapped.z();
          for (int p = start_[c]; p < start_[c + 1]; ++p) {
            const Vec3 r = image(fund_[p].pos, k);
            if ((r.array() >= a.array()).all() && (r.array() <= b.array()).all())
              fn(fund_[p].f, k, r);
          }
        }
  }

 private:
  struct Fundamental {
    int f;
    Vec3 pos;
  };
  static int floor_div(int a, int n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }

  // Cells of about 2 mean spacings (at most 64 per axis), points sorted by cell.
  void build_grid() {
    for (int d = 0; d < 3; ++d) {
      n_[d] = std::clamp(int(period_[d] / (2.0 * s_.spacing)), 1, 64);
      cell_[d] = period_[d] / n_[d];
    }
    auto cell_of = [&](const Vec3& r) {
      int c[3];
      for (int d = 0; d < 3; ++d)
        c[d] = std::clamp(int((r[d] - origin_[d]) / cell_[d]), 0, n_[d] - 1);
      return (c[0] * n_.y() + c[1]) * n_.z() + c[2];
    };
    start_.assign(n_.prod() + 1, 0);
    for (const Fundamental& p : fund_) ++start_[cell_of(p.pos) + 1];
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    std::vector<Fundamental> sorted(fund_.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (const Fundamental& p : fund_) sorted[fill[cell_of(p.pos)]++] = p;
    fund_ = std::move(sorted);
  }

  const PreparedSites& s_;
  Vec3 origin_, period_, cell_;
  Vec3i n_;
  std::vector<Fundamental> fund_;
  std::vector<int> start_;
};

// Points to insert into a triangulation, with their tags (vertex info = index into tags).
template <class Tr>
struct Batch {
  std::vector<std::pair<typename Tr::Point, int>> points;
  void add(const Tr& tr, const Unfolded& u, std::vector<Tag>& tags, int f, const Vec3i& k,
           const Vec3& r) {
    points.emplace_back(make_point(tr, r, u.sites().weight[f / 2]), int(tags.size()));
    tags.push_back(u.tag(f, k, r));
  }
};

// Looks for uninserted points of the unfolded set inside the sphere (power below r2 about
// center) of cell c and queues the one closest to a real vertex of c: the likeliest true
// neighbour. One point per cell and pass keeps the insertions local when a flat cell near the
// hull has a huge sphere.
template <class Tr>
void add_closest_inside(const Tr& tr, typename Tr::Cell_handle c, const Vec3& center, double r2,
                        const Vec3& reach, const Unfolded& u, double m, std::vector<Tag>& tags,
                        std::unordered_set<std::uint64_t>& added, Batch<Tr>& batch) {
  std::vector<Vec3> real;
  for (int k = 0; k < 4; ++k)
    if (tags[c->vertex(k)->info()].real()) real.push_back(to_vec(c->vertex(k)->point()));
  double best = std::numeric_limits<double>::infinity();
  int best_f = -1;
  Vec3i best_k = Vec3i::Zero();
  Vec3 best_r = Vec3::Zero();
  // Only points within the always-sufficient margin matter (if a cell of the triangulation of
  // those points is empty of them, it is a cell of the full set); this bounds the search for
  // huge, nearly flat cells.
  const Vec3 cap = Vec3::Constant(u.max_margin());
  const Vec3 a = (center - reach).cwiseMax(u.sites().lo - cap);
  const Vec3 b = (center + reach).cwiseMin(u.sites().hi + cap);
  u.for_each_in(a, b, [&](int f, const Vec3i& k, const Vec3& r) {
    if (u.in_region(r, m)) return;  // inserted at the start
    if ((r - center).squaredNorm() - u.sites().weight[f / 2] >= r2) return;
    if (added.count(Unfolded::key(f, k))) return;
    for (const Vec3& p : real)
      if ((r - p).squaredNorm() < best) {
        best = (r - p).squaredNorm();
        best_f = f;
        best_k = k;
        best_r = r;
      }
  });
  if (best_f < 0) return;
  added.insert(Unfolded::key(best_f, best_k));
  batch.add(tr, u, tags, best_f, best_k, best_r);
}

// Outcome of one verification pass.
enum class Check { kVerified, kRefined, kRebuild };

// Whether the triangulation is 3D with no real site on its convex hull (else every real
// cell would be unbounded however many images are added nearby: the margin must grow).
template <class Tr>
bool encloses_real_sites(const Tr& tr, const std::vector<Tag>& tags) {
  if (tr.dimension() < 3) return false;
  std::vector<typename Tr::Vertex_handle> hull;
  tr.finite_adjacent_vertices(tr.infinite_vertex(), std::back_inserter(hull));
  for (const auto& v : hull)
    if (tags[v->info()].real()) return false;
  return true;
}

// Verifies one cell if it touches a real site: no point of the unfolded set (inserted or
// not) may lie inside its circumsphere (regular: have negative power to its orthogonal
// sphere). A sphere inside the region covered by the first insertion needs no search; for
// the others an uninserted point inside is queued. Only points inside by more than a
// tolerance (1e-9 spacing^2 in power) count, so the insertion surely replaces the cell; a
// point closer to the sphere moves the cell's faces by O(tolerance) at most. Stores the
// cell's centre.
template <class Tr>
void verify_cell(const Tr& tr, typename Tr::Cell_handle c, const Unfolded& u, double m,
                 std::vector<Tag>& tags, std::unordered_set<std::uint64_t>& added,
                 Batch<Tr>& batch) {
  if (c->info().verified) return;
  bool touches_real = false;
  for (int k = 0; k < 4; ++k) touches_real |= tags[c->vertex(k)->info()].real();
  if (!touches_real) return;
  const PreparedSites& s = u.sites();
  const double tol = 1e-9 * s.spacing * s.spacing;
  const Vec3 center = cell_center(tr, c);
  c->info().center = center;
  const auto& p0 = c->vertex(0)->point();
  const double r2 = (to_vec(p0) - center).squaredNorm() - weight_of(p0);  // power radius^2
  const Vec3 reach = Vec3::Constant(std::sqrt(std::max(r2 + s.w_max + tol, 0.0)));
  if (!u.in_region(center - reach, m) || !u.in_region(center + reach, m))
    add_closest_inside(tr, c, center, r2 - tol, reach, u, m, tags, added, batch);
  c->info().verified = true;
}

// One verification pass over the cells touching real sites: all of them (first_new == 0), or
// only the new cells, those incident to the vertices inserted by the previous pass (tags from
// first_new on). Inserts the points found (kRefined: check again) or returns kVerified.
template <class Tr>
Check verify(Tr& tr, const Unfolded& u, double m, std::vector<Tag>& tags,
             std::unordered_set<std::uint64_t>& added, std::size_t first_new) {
  Batch<Tr> batch;
  if (first_new == 0) {
    if (!encloses_real_sites(tr, tags)) return Check::kRebuild;
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c)
      verify_cell(tr, c, u, m, tags, added, batch);
  } else {
    std::vector<typename Tr::Cell_handle> cells;
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v)
      if (std::size_t(v->info()) >= first_new)
        tr.finite_incident_cells(v, std::back_inserter(cells));
    for (const auto& c : cells) verify_cell(tr, c, u, m, tags, added, batch);
  }
  if (batch.points.empty()) return Check::kVerified;
  tr.insert(batch.points.begin(), batch.points.end());
  return Check::kRefined;
}

// Area of the dual face of edge e: the polygon of the centres of the cells around e, whose
// plane is normal to the unit edge direction u (signed projected area, so repeated centres of
// degenerate configurations add nothing).
template <class Tr>
double dual_area(const Tr& tr, const typename Tr::Edge& e, const Vec3& u) {
  auto cc = tr.incident_cells(e);
  const auto done = cc;
  const Vec3 c0 = cc->info().center;
  Vec3 prev = c0;
  double twice = 0.0;
  for (++cc; cc != done; ++cc) {
    const Vec3 c = cc->info().center;
    twice += (prev - c0).cross(c - c0).dot(u);
    prev = c;
  }
  return 0.5 * std::abs(twice);
}

// Distance from a site of weight wa to its face with a site (or image) of weight wb at
// distance d (the power plane; d / 2 for the plain Voronoi tessellation).
double height(double d, double wa, double wb) {
  return (d * d + wa - wb) / (2.0 * d);
}

// Whether the face between real site a and image t of another site is listed from a's side
// (so that a face seen from both of its cells is listed once).
bool lists_face(int a, const Tag& t) {
  if (t.side != 0) return true;  // wall face, a's own
  if (a != t.site) return a < t.site;
  return t.sy > 0 || (t.sy == 0 && t.sz > 0);
}

// Adds the face dual to edge e (from real vertex va to vb) to the volumes and the face list.
template <class Tr>
void add_face(const Tr& tr, const typename Tr::Edge& e, typename Tr::Vertex_handle va,
              typename Tr::Vertex_handle vb, const std::vector<Tag>& tags, const PreparedSites& s,
              VoronoiTessellation& out) {
  const Tag& ta = tags[va->info()];
  const Tag& tb = tags[vb->info()];
  const Vec3 offset = to_vec(vb->point()) - to_vec(va->point());
  const double d = offset.norm();
  const double area = dual_area(tr, e, offset / d);
  const double wa = s.weight[ta.site], wb = s.weight[tb.site];
  out.volume[ta.site] += area * height(d, wa, wb) / 3.0;
  if (tb.real()) out.volume[tb.site] += area * height(d, wb, wa) / 3.0;
  if (area <= kTinyArea * s.spacing * s.spacing) return;
  if (tb.side != 0)
    out.faces.push_back({ta.site, tb.side < 0 ? kLeftWall : kRightWall, area, offset});
  else if (tb.real() || lists_face(ta.site, tb))
    out.faces.push_back({ta.site, tb.site, area, offset});
}

// Faces and volumes of the real cells from the verified triangulation: every edge at a real
// vertex, an edge between two real vertices once (from its lower site). Edges between two
// sites marked in `skip` (or a marked site and an image of one) are left out, and the
// volumes of the marked sites are NaN (incomplete).
template <class Tr>
void collect(const Tr& tr, const std::vector<Tag>& tags, const PreparedSites& s,
             const std::vector<char>& skip, VoronoiTessellation& out) {
  out.volume.assign(s.pos.size(), 0.0);
  out.faces.clear();
  auto skipped = [&](int site) { return !skip.empty() && skip[std::size_t(site)]; };
  std::vector<typename Tr::Edge> edges;
  for (auto it = tr.finite_vertices_begin(); it != tr.finite_vertices_end(); ++it) {
    const typename Tr::Vertex_handle v = it;
    const Tag& ta = tags[v->info()];
    if (!ta.real()) continue;
    const bool skip_a = skipped(ta.site);
    edges.clear();
    tr.finite_incident_edges(v, std::back_inserter(edges));
    for (const auto& e : edges) {
      auto w = e.first->vertex(e.second);
      if (w == v) w = e.first->vertex(e.third);
      const Tag& tb = tags[w->info()];
      if (tb.real() && tb.site < ta.site) continue;
      if (skip_a && tb.side == 0 && skipped(tb.site)) continue;
      add_face(tr, e, v, w, tags, s, out);
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < skip.size(); ++i)
    if (skip[i]) out.volume[i] = nan;
}

// Builds the triangulation of the unfolded points within margin m of the box and refines it
// until verified; widens the margin (rebuild) when real sites reach the convex hull.
template <class Tr>
VoronoiTessellation run(const PreparedSites& s, const VoronoiOptions& opt,
                        const std::vector<char>& skip) {
  VoronoiTessellation out;
  const Unfolded u(s);
  const double m_cap = u.max_margin();
  double m = std::min(opt.margin > 0.0 ? opt.margin : kAutoMargin * s.spacing, m_cap);
  for (out.builds = 1;; ++out.builds) {
    Tr tr;
    std::vector<Tag> tags;
    std::unordered_set<std::uint64_t> added;
    Batch<Tr> start;
    u.for_each_in(s.lo - Vec3::Constant(m), s.hi + Vec3::Constant(m),
                  [&](int f, const Vec3i& k, const Vec3& r) { start.add(tr, u, tags, f, k, r); });
    tr.insert(start.points.begin(), start.points.end());
    Check check = Check::kRefined;
    std::size_t first_new = 0;  // first pass: every cell
    for (out.refinements = 0; check == Check::kRefined; ++out.refinements) {
      if (out.refinements > kMaxRefinements)
        fail_simulation("Voronoi: cells not verified after ", kMaxRefinements, " refinements");
      const std::size_t before = tags.size();
      check = verify(tr, u, m, tags, added, first_new);
      first_new = before;
    }
    --out.refinements;  // the last pass found nothing to add
    if (check == Check::kVerified) {
      out.margin = m;
      out.n_points = tags.size();
      out.n_added = added.size();
      collect(tr, tags, s, skip, out);
      return out;
    }
    if (out.builds >= opt.max_builds || m >= m_cap)
      fail_simulation("Voronoi: real sites still on the convex hull after ", out.builds,
                      " builds (image margin ", m, ")");
    m = std::min(2.0 * m, m_cap);
  }
}

void check_box(const Box& box) {
  if (box.periodic(0) || !box.periodic(1) || !box.periodic(2))
    fail_input("Voronoi: the box must have walls in x and be periodic in y and z");
}

// Adds face f to the surface of the union of the vertex cells of each body it separates
// from something else: to S_i (`surface`) if the other side is a cancer cell or another body,
// to i's wall area (`wall`) if it is a wall. Faces between two vertices of i are inside.
void add_surfaces(const Sites& sites, const VoronoiFace& f, std::vector<double>& surface,
                  std::vector<double>& wall) {
  const int body_a = sites.body[f.a];
  if (f.b < 0) {
    if (body_a >= 0) wall[body_a] += f.area;
    return;
  }
  const int body_b = sites.body[f.b];
  if (body_a == body_b) return;
  if (body_a >= 0) surface[body_a] += f.area;
  if (body_b >= 0) surface[body_b] += f.area;
}

// A_t's two parts from one face.
void add_interface(const Sites& sites, const VoronoiFace& f, VoronoiMeasurement& m) {
  const bool cancer_a = sites.kind[f.a] == SiteKind::kCancer;
  if (f.b < 0) {
    if (cancer_a) m.cancer_wall_area += f.area;
    return;
  }
  const bool cancer_b = sites.kind[f.b] == SiteKind::kCancer;
  if (cancer_a != cancer_b) m.cancer_adipocyte_area += f.area;
}

// Adipocyte Voronoi volumes W_i, the local packing fractions V_i / W_i, their mean and
// population standard deviation over the bodies with known V_i.
void local_packing(const System& sys, VoronoiMeasurement& m) {
  const auto& bodies = sys.bodies();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  m.adipocyte_volume.assign(bodies.size(), 0.0);
  m.local_phi_a.assign(bodies.size(), nan);
  std::vector<double> known;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int v = 0; v < bodies[b].n_vertices(); ++v)
      m.adipocyte_volume[b] += m.tessellation.volume[bodies[b].first_site + v];
    if (!(bodies[b].outer_volume > 0.0)) continue;
    m.local_phi_a[b] = bodies[b].outer_volume / m.adipocyte_volume[b];
    known.push_back(m.local_phi_a[b]);
  }
  m.mean_local_phi_a = m.std_local_phi_a = nan;
  if (known.empty()) return;
  double sum = 0.0, sum2 = 0.0;
  for (double phi : known) sum += phi;
  m.mean_local_phi_a = sum / double(known.size());
  for (double phi : known) sum2 += (phi - m.mean_local_phi_a) * (phi - m.mean_local_phi_a);
  m.std_local_phi_a = std::sqrt(sum2 / double(known.size()));
}

}  // namespace

VoronoiTessellation tessellate(const Box& box, const std::vector<Vec3>& points,
                               const VoronoiOptions& opt, const std::vector<double>& weights,
                               const std::vector<char>& skip_faces_between) {
  check_box(box);
  if (opt.radical && weights.size() != points.size())
    fail_input("Voronoi: the radical tessellation needs one weight per point (", weights.size(),
               " for ", points.size(), " points)");
  if (opt.max_builds < 1) fail_input("Voronoi: max_builds = ", opt.max_builds, " must be >= 1");
  if (points.empty()) return {};
  const PreparedSites s = prepare(box, points, opt.radical ? weights : std::vector<double>{});
  if (!skip_faces_between.empty() && skip_faces_between.size() != points.size())
    fail_input("Voronoi: ", skip_faces_between.size(), " skip flags for ", points.size(),
               " points");
  return opt.radical ? run<Regular>(s, opt, skip_faces_between)
                     : run<Delaunay>(s, opt, skip_faces_between);
}

VoronoiMeasurement measure_voronoi(const System& sys, const VoronoiOptions& opt) {
  const Sites& sites = sys.sites();
  std::vector<double> weights;
  if (opt.radical)
    for (double d : sites.diameter) weights.push_back(0.25 * d * d);
  VoronoiMeasurement m;
  std::vector<char> cancer;
  if (opt.interface_only)
    for (SiteKind k : sites.kind) cancer.push_back(k == SiteKind::kCancer);
  m.tessellation = tessellate(sys.box(), sites.pos, opt, weights, cancer);
  m.adipocyte_surface.assign(sys.bodies().size(), 0.0);
  m.adipocyte_wall_area.assign(sys.bodies().size(), 0.0);
  for (const VoronoiFace& f : m.tessellation.faces) {
    add_interface(sites, f, m);
    add_surfaces(sites, f, m.adipocyte_surface, m.adipocyte_wall_area);
  }
  for (double w : m.adipocyte_wall_area) m.adipocyte_wall_total += w;
  m.interface_area = m.cancer_adipocyte_area + m.cancer_wall_area;
  m.max_interface_area = 2.0 * sys.box().wall_area();
  for (double s : m.adipocyte_surface) m.max_interface_area += s;
  m.interface_ratio = m.interface_area / m.max_interface_area;
  local_packing(sys, m);
  return m;
}

}  // namespace invasim
