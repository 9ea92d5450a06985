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
#include <array>
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

// Per-cell data: the (weighted) circumcentre, computed once when the cell is verified.
struct CellInfo {
  Vec3 center = Vec3::Zero();
  // 0: new; 1: in the current verification pass (centre known); 2: verified.
  int state = 0;
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

// What a triangulated point is: the image of `site` shifted by (sy, sz) periods in y and z
// (the real site has no shift), or a dummy point beyond a wall (site -1).
struct Tag {
  int site = 0;
  int sy = 0, sz = 0;
  bool real() const { return site >= 0 && sy == 0 && sz == 0; }
  bool dummy() const { return site < 0; }
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

// Fraction of L_x by which a site at or beyond a wall is kept inside it: every site lies
// strictly inside the slab whose cells are clipped.
constexpr double kWallGap = 1e-9;
// Faces smaller than this times spacing^2 are degenerate (zero-area duals of Delaunay edges
// in cospherical configurations, e.g. lattices) and are not listed.
constexpr double kTinyArea = 1e-12;
// Automatic image margin in y and z, in mean site spacings (see docs/measurements.md).
constexpr double kAutoMargin = 1.5;
// Refinement passes allowed (each inserts at least one point; a handful is usual).
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

// The walls by clipping. The walled box's cells are those of the mirror construction: the
// sites and their mirror images across the walls, repeated (x = p_x or 2 lo_x - p_x, plus
// multiples of 2 L_x). For a point r of the slab lo_x <= x <= hi_x and a site p in it, no such
// image of p is nearer to r than p itself (|r_x - x| >= |r_x - p_x|), nor of lower power (same
// weight). So the cells of the walled box are the cells of the sites and their periodic
// images in y and z alone clipped to the slab: a face between two sites is clipped to the
// slab, and the cross-section of a cell with a wall plane is its wall face (the mirror
// construction's face between a site and its mirror image). Without the mirror images there
// are none of their exact degeneracies (a site and its mirror image are cospherical with every
// other such pair).

// The sites and their periodic images in y and z: point (i, k) is site i shifted by k periods
// (k.x = 0). A grid over the box finds the points in any axis-aligned box.
class Images {
 public:
  explicit Images(const PreparedSites& s) : s_(s) {
    for (std::size_t i = 0; i < s.pos.size(); ++i)
      if (s.used[i]) fund_.push_back({int(i), s.pos[i]});
    build_grid();
  }

  const PreparedSites& sites() const { return s_; }
  // Every point r of the slab has a site within this distance (an image of any one site
  // with |dx| <= L_x, |dy| <= L_y / 2, |dz| <= L_z / 2), so its nearest site has power at most
  // reach^2 (weights are >= 0).
  double reach() const {
    return std::sqrt(s_.len.x() * s_.len.x() +
                     0.25 * (s_.len.y() * s_.len.y() + s_.len.z() * s_.len.z()));
  }
  // A margin in y and z that always suffices. A point r of a real site's clipped cell lies
  // within L_y / 2 of the site in y (the site's images at -+L_y, inside any margin >= L_y,
  // bound the cell) and has power at most reach^2 to the site (above); an image farther
  // than m from the box in y is more than m - L_y / 2 from r in y, so it cannot be nearer once
  // (m - L_y / 2)^2 - w_max >= reach^2 (and likewise in z). No point beyond this margin
  // changes a real cell.
  double max_margin() const {
    return 1.1 * (0.5 * std::max(s_.len.y(), s_.len.z()) + std::sqrt(reach() * reach() + s_.w_max));
  }
  // Image of a site shifted by k periods (computed the same way everywhere, so region tests
  // on it are reproducible).
  Vec3 image(const Vec3& base, const Vec3i& k) const {
    return Vec3(base.x(), base.y() + k.y() * s_.len.y(), base.z() + k.z() * s_.len.z());
  }
  // Whether r lies within m of the box in y and z: every image there was inserted at the
  // start, whatever its x.
  bool in_region(const Vec3& r, double m) const {
    for (int a = 1; a < 3; ++a)
      if (!(r[a] >= s_.lo[a] - m && r[a] <= s_.hi[a] + m)) return false;
    return true;
  }
  // Key identifying point (i, k) (|k| < 512 in y and z).
  static std::uint64_t key(int i, const Vec3i& k) {
    std::uint64_t u = std::uint64_t(i);
    for (int a = 1; a < 3; ++a) u = u * 1024 + std::uint64_t(k[a] + 512);
    return u;
  }
  // Calls fn(i, k, r) for every image r with a <= r <= b.
  template <class Fn>
  void for_each_in(const Vec3& a, const Vec3& b, Fn&& fn) const {
    Vec3i lo_cell, hi_cell;
    for (int d = 0; d < 3; ++d) {
      lo_cell[d] = int(std::floor((a[d] - s_.lo[d]) / cell_[d]));
      hi_cell[d] = int(std::floor((b[d] - s_.lo[d]) / cell_[d]));
    }
    // Not periodic in x: the sites' x lie in the box.
    lo_cell.x() = std::max(lo_cell.x(), 0);
    hi_cell.x() = std::min(hi_cell.x(), n_.x() - 1);
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
              fn(fund_[p].i, k, r);
          }
        }
  }

 private:
  struct Fundamental {
    int i;
    Vec3 pos;
  };
  static int floor_div(int a, int n) { return a >= 0 ? a / n : -((-a + n - 1) / n); }

  // Cells of about 2 mean spacings (at most 64 per axis), points sorted by cell.
  void build_grid() {
    for (int d = 0; d < 3; ++d) {
      n_[d] = std::clamp(int(s_.len[d] / (2.0 * s_.spacing)), 1, 64);
      cell_[d] = s_.len[d] / n_[d];
    }
    auto cell_of = [&](const Vec3& r) {
      int c[3];
      for (int d = 0; d < 3; ++d)
        c[d] = std::clamp(int((r[d] - s_.lo[d]) / cell_[d]), 0, n_[d] - 1);
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
  Vec3 cell_;
  Vec3i n_;
  std::vector<Fundamental> fund_;
  std::vector<int> start_;
};

// The dummy points: eight, of weight 0, at x = lo_x - D and hi_x + D and at the corners of
// the inserted images' y-z region grown by a spacing. Every point of the slab has a site
// within power Images::reach()^2, and a dummy is farther than D > reach from every point of
// the slab, so no dummy owns any point of the slab: they change no clipped cell. They put
// every real site strictly inside the convex hull of the triangulated points, so every real
// cell is bounded (all the cells around its edges are finite).
std::array<Vec3, 8> dummy_points(const Images& u, double m) {
  const PreparedSites& s = u.sites();
  const double d = u.reach() + s.spacing;
  const double g = m + s.spacing;
  std::array<Vec3, 8> out;
  for (int c = 0; c < 8; ++c)
    out[std::size_t(c)] =
        Vec3(c & 1 ? s.hi.x() + d : s.lo.x() - d, c & 2 ? s.hi.y() + g : s.lo.y() - g,
             c & 4 ? s.hi.z() + g : s.lo.z() - g);
  return out;
}

// The wall planes: side -1 is x = lo_x (beyond it: x < lo_x), +1 is x = hi_x (x > hi_x).
struct Walls {
  double lo, hi;
  double x(int side) const { return side < 0 ? lo : hi; }
  bool beyond(const Vec3& r, int side) const { return side < 0 ? r.x() < lo : r.x() > hi; }
  bool inside(const Vec3& r) const { return r.x() >= lo && r.x() <= hi; }
  // Where the segment from a to b crosses wall `side`, given that exactly one end is beyond
  // it; computed from the end beyond, so the same point whichever end comes first.
  Vec3 crossing(const Vec3& a, const Vec3& b, int side) const {
    const bool a_out = beyond(a, side);
    const Vec3& o = a_out ? a : b;
    const Vec3& in = a_out ? b : a;
    const double w = x(side);
    Vec3 r = o + (w - o.x()) / (in.x() - o.x()) * (in - o);
    r.x() = w;
    return r;
  }
};

// Points to insert into a triangulation, with their tags (vertex info = index into tags).
template <class Tr>
struct Batch {
  std::vector<std::pair<typename Tr::Point, int>> points;
  void add(const Tr& tr, std::vector<Tag>& tags, const Vec3& r, double weight, const Tag& t) {
    points.emplace_back(make_point(tr, r, weight), int(tags.size()));
    tags.push_back(t);
  }
};

// What a verification needs: the images, the margin inserted at the start, the tags of the
// triangulated points, the images inserted since, and the points queued for the next insertion.
template <class Tr>
struct Verifier {
  const Tr& tr;
  const Images& u;
  double m;
  Walls walls;
  std::vector<Tag>& tags;
  std::unordered_set<std::uint64_t>& added;
  Batch<Tr>& batch;

  bool real(typename Tr::Vertex_handle v) const { return tags[v->info()].real(); }

  // Looks for images not yet triangulated with power below r2 about `center` (inside the
  // sphere) and queues the one closest to a real vertex of cell c (of its facet opposite
  // vertex `skip`, or all four: skip = -1), whose cells the sphere bounds: the likeliest true
  // neighbour. One point per sphere and pass keeps the insertions local when a flat cell has
  // a huge sphere.
  void add_closest_inside(const Vec3& center, double r2, const Vec3& reach,
                          typename Tr::Cell_handle c, int skip) {
    Vec3 near[4];
    int n_near = 0;
    for (int k = 0; k < 4; ++k)
      if (k != skip && real(c->vertex(k))) near[n_near++] = to_vec(c->vertex(k)->point());
    double best = std::numeric_limits<double>::infinity();
    int best_i = -1;
    Vec3i best_k = Vec3i::Zero();
    Vec3 best_r = Vec3::Zero();
    // Only images within the always-sufficient margin matter; this bounds the search for
    // huge spheres.
    const Vec3 cap = Vec3::Constant(u.max_margin());
    const Vec3 a = (center - reach).cwiseMax(u.sites().lo - cap);
    const Vec3 b = (center + reach).cwiseMin(u.sites().hi + cap);
    u.for_each_in(a, b, [&](int i, const Vec3i& k, const Vec3& r) {
      if (u.in_region(r, m)) return;  // inserted at the start
      if ((r - center).squaredNorm() - u.sites().weight[i] >= r2) return;
      if (added.count(Images::key(i, k))) return;
      for (int j = 0; j < n_near; ++j)
        if ((r - near[j]).squaredNorm() < best) {
          best = (r - near[j]).squaredNorm();
          best_i = i;
          best_k = k;
          best_r = r;
        }
    });
    if (best_i < 0) return;
    added.insert(Images::key(best_i, best_k));
    batch.add(tr, tags, best_r, u.sites().weight[best_i], Tag{best_i, best_k.y(), best_k.z()});
  }

  // Checks the empty sphere (power r2 about center) of a vertex of real cells: only images
  // inside it by more than a tolerance (1e-9 spacing^2 in power) count, so that an insertion
  // surely changes the triangulation; one closer to the sphere moves the cells' faces by
  // O(tolerance) at most. A sphere within the region inserted at the start needs no search.
  // (c, skip) as for add_closest_inside.
  void check_sphere(const Vec3& center, double r2, typename Tr::Cell_handle c, int skip) {
    const PreparedSites& s = u.sites();
    const double tol = 1e-9 * s.spacing * s.spacing;
    const Vec3 reach = Vec3::Constant(std::sqrt(std::max(r2 + s.w_max + tol, 0.0)));
    if (!u.in_region(center - reach, m) || !u.in_region(center + reach, m))
      add_closest_inside(center, r2 - tol, reach, c, skip);
  }

  // Verifies cell c (touching a real site; its centre and its neighbours' are known). The
  // clipped cell of a real site i is exact if no image is nearer (in power) than i to any
  // vertex of it: the difference of two powers is affine along the cell, so if an image is
  // nearer somewhere in it, it is nearer at a vertex. Those vertices are the centres of the
  // cells around i inside the slab (the sphere of c) and the points where the Voronoi edges
  // of i's cell cross a wall (the facets of c whose dual edge crosses one, each checked from
  // one of its two cells).
  void verify_cell(typename Tr::Cell_handle c) {
    const Vec3& center = c->info().center;
    if (walls.inside(center)) {
      const auto& p0 = c->vertex(0)->point();
      check_sphere(center, (to_vec(p0) - center).squaredNorm() - weight_of(p0), c, -1);
    }
    for (int k = 0; k < 4; ++k) {
      const auto n = c->neighbor(k);
      // A neighbour touching no real site (new, or infinite) means a facet without one.
      if (n->info().state == 0) continue;
      const Vec3& other = n->info().center;
      const bool left = walls.beyond(center, -1) != walls.beyond(other, -1);
      const bool right = walls.beyond(center, 1) != walls.beyond(other, 1);
      if (!left && !right) continue;
      bool facet_real = false;
      for (int j = 1; j < 4; ++j) facet_real = facet_real || real(c->vertex((k + j) & 3));
      if (!facet_real) continue;
      // A facet between two cells of this pass is checked from the one whose opposite vertex
      // comes first.
      if (n->info().state == 1 && tr.mirror_vertex(c, k)->info() < c->vertex(k)->info()) continue;
      const auto& p = c->vertex((k + 1) & 3)->point();
      for (int side : {-1, 1}) {
        if (!(side < 0 ? left : right)) continue;
        const Vec3 x = walls.crossing(center, other, side);
        check_sphere(x, (to_vec(p) - x).squaredNorm() - weight_of(p), c, k);
      }
    }
  }
};

// Whether the cell has a real site among its vertices.
template <class Tr>
bool touches_real(typename Tr::Cell_handle c, const std::vector<Tag>& tags) {
  for (int k = 0; k < 4; ++k)
    if (tags[c->vertex(k)->info()].real()) return true;
  return false;
}

// One verification pass over the cells touching real sites: all of them (first_new == 0), or
// only the new cells, those incident to the vertices inserted by the previous pass (tags from
// first_new on). Inserts the points found and returns true (check again), or returns false.
template <class Tr>
bool refine(Tr& tr, const Images& u, double m, std::vector<Tag>& tags,
            std::unordered_set<std::uint64_t>& added, std::size_t first_new) {
  std::vector<typename Tr::Cell_handle> cells, around;
  auto take = [&](typename Tr::Cell_handle c) {
    if (c->info().state != 0 || !touches_real<Tr>(c, tags)) return;
    c->info().state = 1;
    c->info().center = cell_center(tr, c);
    cells.push_back(c);
  };
  if (first_new == 0) {
    for (auto c = tr.finite_cells_begin(); c != tr.finite_cells_end(); ++c) take(c);
  } else {
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
      if (std::size_t(v->info()) < first_new) continue;
      around.clear();
      tr.finite_incident_cells(v, std::back_inserter(around));
      for (const auto& c : around) take(c);
    }
  }
  Batch<Tr> batch;
  Verifier<Tr> check{tr, u, m, {u.sites().lo.x(), u.sites().hi.x()}, tags, added, batch};
  for (const auto& c : cells) check.verify_cell(c);
  for (const auto& c : cells) c->info().state = 2;
  if (batch.points.empty()) return false;
  tr.insert(batch.points.begin(), batch.points.end());
  return true;
}

// Whether the triangulation is 3D with no real site on its convex hull (the dummy points
// guarantee it).
template <class Tr>
bool encloses_real_sites(const Tr& tr, const std::vector<Tag>& tags) {
  if (tr.dimension() < 3) return false;
  std::vector<typename Tr::Vertex_handle> hull;
  tr.finite_adjacent_vertices(tr.infinite_vertex(), std::back_inserter(hull));
  for (const auto& v : hull)
    if (tags[v->info()].real()) return false;
  return true;
}

// Twice the signed area, projected onto the unit vector u, of triangle (r, a, b) clipped to the
// slab. Summed over the consecutive corners a, b of a polygon around any point r, it gives
// twice the signed area of the polygon clipped to the slab (the triangles' winding numbers add
// up to the polygon's, and clipping to a convex region keeps that). `poly` and `cut` are
// scratch space.
double clipped_twice_area(const Vec3& r, const Vec3& a, const Vec3& b, const Vec3& u,
                          const Walls& walls, std::vector<Vec3>& poly, std::vector<Vec3>& cut) {
  if (walls.inside(r) && walls.inside(a) && walls.inside(b)) return (a - r).cross(b - r).dot(u);
  poly.assign({r, a, b});
  for (int side : {-1, 1}) {
    cut.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec3& p = poly[k];
      const Vec3& q = poly[(k + 1) % poly.size()];
      if (!walls.beyond(p, side)) cut.push_back(p);
      if (walls.beyond(p, side) != walls.beyond(q, side)) cut.push_back(walls.crossing(p, q, side));
    }
    poly.swap(cut);
  }
  double twice = 0.0;
  for (std::size_t k = 2; k < poly.size(); ++k)
    twice += (poly[k - 1] - poly[0]).cross(poly[k] - poly[0]).dot(u);
  return twice;
}

// Distance from a site of weight wa to its face with a site (or image) of weight wb at
// distance d (the power plane; d / 2 for the plain Voronoi tessellation).
double height(double d, double wa, double wb) {
  return (d * d + wa - wb) / (2.0 * d);
}

// Whether the face between real site a and image t of another site is listed from a's side
// (so that a face seen from both of its cells is listed once).
bool lists_face(int a, const Tag& t) {
  if (a != t.site) return a < t.site;
  return t.sy > 0 || (t.sy == 0 && t.sz > 0);
}

// A face of a real site's cell being summed: the one with vertex w (a site's image), normal
// u, in the plane through r; twice its signed clipped area so far.
template <class Tr>
struct OpenFace {
  typename Tr::Vertex_handle w;
  Vec3 offset, u, r;
  double twice = 0.0;
};

// Adds a face whose area is summed (from real vertex va) to the volumes and the face list.
template <class Tr>
void add_face(const OpenFace<Tr>& f, const Tag& ta, const Tag& tb, const PreparedSites& s,
              VoronoiTessellation& out) {
  const double area = 0.5 * std::abs(f.twice);
  const double d = f.offset.norm();
  const double wa = s.weight[ta.site], wb = s.weight[tb.site];
  out.volume[ta.site] += area * height(d, wa, wb) / 3.0;
  if (tb.real()) out.volume[tb.site] += area * height(d, wb, wa) / 3.0;
  if (area <= kTinyArea * s.spacing * s.spacing) return;
  if (tb.real() || lists_face(ta.site, tb)) out.faces.push_back({ta.site, tb.site, area, f.offset});
}

// Area of a convex polygon in a wall plane from its vertices in any order (y, z; repeated
// points allowed): sorted by angle about their mean, which lies inside.
double convex_area(std::vector<std::array<double, 2>>& p) {
  if (p.size() < 3) return 0.0;
  double cy = 0.0, cz = 0.0;
  for (const auto& q : p) {
    cy += q[0];
    cz += q[1];
  }
  cy /= double(p.size());
  cz /= double(p.size());
  for (auto& q : p) {
    q[0] -= cy;
    q[1] -= cz;
  }
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) {
    return std::atan2(a[1], a[0]) < std::atan2(b[1], b[0]);
  });
  double twice = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto& a = p[k];
    const auto& b = p[(k + 1) % p.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * std::abs(twice);
}

// Wall faces of real site `site` (vertex v, its cells `cells`): the cross-sections of its cell
// with the wall planes, whose corners are the points where the cell's Voronoi edges cross a
// plane. Each such edge is dual to a facet at v whose one cell lies beyond the wall, where
// the crossing is taken. Adds the faces to the list and their pyramids to the volume.
template <class Tr>
void add_wall_faces(typename Tr::Vertex_handle v, int site,
                    const std::vector<typename Tr::Cell_handle>& cells, const PreparedSites& s,
                    const Walls& walls, std::vector<std::array<double, 2>>& corners,
                    VoronoiTessellation& out) {
  for (int side : {-1, 1}) {
    corners.clear();
    for (const auto& c : cells) {
      const Vec3& center = c->info().center;
      if (!walls.beyond(center, side)) continue;
      const int i = c->index(v);
      for (int k = 0; k < 4; ++k) {
        if (k == i) continue;
        const Vec3& other = c->neighbor(k)->info().center;  // touches v: centre known
        if (walls.beyond(other, side)) continue;
        const Vec3 x = walls.crossing(center, other, side);
        corners.push_back({x.y(), x.z()});
      }
    }
    const double area = convex_area(corners);
    const double h = side > 0 ? s.hi.x() - s.pos[site].x() : s.pos[site].x() - s.lo.x();
    out.volume[site] += area * h / 3.0;
    if (area > kTinyArea * s.spacing * s.spacing)
      out.faces.push_back({site, side > 0 ? kRightWall : kLeftWall, area,
                           Vec3(side > 0 ? 2.0 * h : -2.0 * h, 0.0, 0.0)});
  }
}

// Faces and volumes of the real cells from the verified triangulation. For each real vertex v,
// the face with each neighbour w is the polygon of the centres of the cells around edge vw in
// their order around it: each cell around v adds, for each of its edges vw, the triangle from
// a point r of the face's plane to its centre and the centre of the next cell around vw (the
// edge circulator's step), clipped to the slab. Edges to a dummy point (their faces lie
// beyond the walls) are left out, an edge between two real vertices is summed once (from its
// lower site); then v's wall faces. Edges between two sites marked in `skip` (or a marked site
// and an image of one) are left out, and the volumes of the marked sites are NaN (incomplete).
template <class Tr>
void collect(const Tr& tr, const std::vector<Tag>& tags, const PreparedSites& s,
             const std::vector<char>& skip, VoronoiTessellation& out) {
  out.volume.assign(s.pos.size(), 0.0);
  out.faces.clear();
  const Walls walls{s.lo.x(), s.hi.x()};
  auto skipped = [&](int site) { return !skip.empty() && skip[std::size_t(site)]; };
  constexpr int kNone = -1, kLeftOut = -2;
  std::vector<int> slot(tags.size(), kNone);  // per vertex: index into `open`, or kLeftOut
  std::vector<int> left_out;
  std::vector<OpenFace<Tr>> open;
  std::vector<typename Tr::Cell_handle> cells;
  std::vector<Vec3> poly, cut;
  std::vector<std::array<double, 2>> corners;
  for (auto it = tr.finite_vertices_begin(); it != tr.finite_vertices_end(); ++it) {
    const typename Tr::Vertex_handle v = it;
    const Tag& ta = tags[v->info()];
    if (!ta.real()) continue;
    const bool skip_a = skipped(ta.site);
    const Vec3 pv = to_vec(v->point());
    const double wa = weight_of(v->point());
    cells.clear();
    open.clear();
    tr.incident_cells(v, std::back_inserter(cells));
    for (const auto& c : cells) {
      const int i = c->index(v);
      const Vec3& center = c->info().center;
      for (int j = 0; j < 4; ++j) {
        if (j == i) continue;
        const auto w = c->vertex(j);
        int& k = slot[std::size_t(w->info())];
        if (k == kLeftOut) continue;
        if (k == kNone) {
          const Tag& tb = tags[w->info()];
          if (tb.dummy() || (tb.real() && tb.site < ta.site) || (skip_a && skipped(tb.site))) {
            k = kLeftOut;
            left_out.push_back(w->info());
            continue;
          }
          k = int(open.size());
          OpenFace<Tr> f;
          f.w = w;
          f.offset = to_vec(w->point()) - pv;
          const double d = f.offset.norm();
          f.u = f.offset / d;
          f.r = pv + height(d, wa, weight_of(w->point())) * f.u;
          open.push_back(f);
        }
        OpenFace<Tr>& f = open[std::size_t(k)];
        const Vec3& next = c->neighbor(Tr::next_around_edge(i, j))->info().center;
        f.twice += clipped_twice_area(f.r, center, next, f.u, walls, poly, cut);
      }
    }
    for (const OpenFace<Tr>& f : open) {
      add_face(f, ta, tags[f.w->info()], s, out);
      slot[std::size_t(f.w->info())] = kNone;
    }
    for (int x : left_out) slot[std::size_t(x)] = kNone;
    left_out.clear();
    add_wall_faces<Tr>(v, ta.site, cells, s, walls, corners, out);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < skip.size(); ++i)
    if (skip[i]) out.volume[i] = nan;
}

// Triangulates the images within margin m of the box in y and z and the dummy points, refines
// until every real cell is verified, and collects the clipped cells.
template <class Tr>
VoronoiTessellation run(const PreparedSites& s, const VoronoiOptions& opt,
                        const std::vector<char>& skip) {
  VoronoiTessellation out;
  const Images u(s);
  const double m =
      std::min(opt.margin > 0.0 ? opt.margin : kAutoMargin * s.spacing, u.max_margin());
  Tr tr;
  std::vector<Tag> tags;
  std::unordered_set<std::uint64_t> added;
  Batch<Tr> start;
  const Vec3 grow(0.0, m, m);
  u.for_each_in(s.lo - grow, s.hi + grow, [&](int i, const Vec3i& k, const Vec3& r) {
    start.add(tr, tags, r, s.weight[i], Tag{i, k.y(), k.z()});
  });
  for (const Vec3& r : dummy_points(u, m)) start.add(tr, tags, r, 0.0, Tag{-1, 0, 0});
  tr.insert(start.points.begin(), start.points.end());
  if (!encloses_real_sites(tr, tags))
    fail_simulation("Voronoi: a real site lies on the convex hull of the triangulated points");
  std::size_t first_new = 0;  // first pass: every cell
  for (out.refinements = 0;; ++out.refinements) {
    if (out.refinements > kMaxRefinements)
      fail_simulation("Voronoi: cells not verified after ", kMaxRefinements, " refinements");
    const std::size_t before = tags.size();
    if (!refine(tr, u, m, tags, added, first_new)) break;
    first_new = before;
  }
  out.margin = m;
  out.n_points = tags.size();
  out.n_added = added.size();
  collect(tr, tags, s, skip, out);
  return out;
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
