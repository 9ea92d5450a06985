#include "io/slice_outline.hpp"

#include <algorithm>
#include <cmath>

namespace invasim {

namespace {

// A boundary piece between two stored points (ids): a segment or a counter-clockwise arc.
struct Piece {
  int from, to;
  double radius;  // 0: segment
  Point2 centre;
  bool large;
};

double dist2(const Point2& a, const Point2& b) {
  const double du = a[0] - b[0], dw = a[1] - b[1];
  return du * du + dw * dw;
}

// Even-odd rule: whether p lies inside an odd number of the loops.
bool inside_loop(const std::vector<Point2>& loop, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Point2 &a = loop[i], &b = loop[j];
    if ((a[1] > p[1]) != (b[1] > p[1]) &&
        p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]))
      in = !in;
  }
  return in;
}

double signed_area(const std::vector<Point2>& loop) {
  double a = 0.0;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    a += loop[j][0] * loop[i][1] - loop[i][0] * loop[j][1];
  return 0.5 * a;
}

// The union's geometry and the point store shared by all pieces (a crossing point is computed
// once, so the pieces meeting there share its id).
class Outliner {
 public:
  Outliner(const std::vector<std::vector<Point2>>& polygons, const std::vector<SliceDisc>& discs)
      : polys_(polygons), discs_(discs), on_circle_(discs.size()) {
    for (const SliceDisc& d : discs_) scale_ = std::max(scale_, d.radius);
    for (const auto& loop : polys_)
      for (const Point2& p : loop) scale_ = std::max({scale_, std::abs(p[0]), std::abs(p[1])});
    for (const SliceDisc& d : discs_)
      scale_ = std::max({scale_, std::abs(d.centre[0]), std::abs(d.centre[1])});
  }

  std::vector<OutlineLoop> run() {
    circle_crossings();
    polygon_pieces();  // also records the polygon-circle crossings on the circles
    arc_pieces();
    return chain();
  }

 private:
  bool in_polygons(const Point2& p) const {
    bool in = false;
    for (const auto& loop : polys_)
      if (loop.size() >= 3 && inside_loop(loop, p)) in = !in;
    return in;
  }
  bool in_discs(const Point2& p, std::size_t skip) const {
    for (std::size_t j = 0; j < discs_.size(); ++j)
      if (j != skip && dist2(p, discs_[j].centre) < discs_[j].radius * discs_[j].radius)
        return true;
    return false;
  }
  int add_point(const Point2& p) {
    points_.push_back(p);
    return int(points_.size()) - 1;
  }

  // Crossings of every pair of circles, recorded on both.
  void circle_crossings() {
    for (std::size_t i = 0; i < discs_.size(); ++i)
      for (std::size_t j = i + 1; j < discs_.size(); ++j) {
        const Point2 &ci = discs_[i].centre, &cj = discs_[j].centre;
        const double ri = discs_[i].radius, rj = discs_[j].radius;
        const double d = std::sqrt(dist2(ci, cj));
        if (!(d > 0.0) || d >= ri + rj || d <= std::abs(ri - rj)) continue;
        const double a = (ri * ri - rj * rj + d * d) / (2.0 * d);
        const double h2 = ri * ri - a * a;
        if (!(h2 > 0.0)) continue;
        const double h = std::sqrt(h2), eu = (cj[0] - ci[0]) / d, ew = (cj[1] - ci[1]) / d;
        const Point2 m{ci[0] + a * eu, ci[1] + a * ew};
        for (double s : {1.0, -1.0}) {
          const int id = add_point({m[0] - s * h * ew, m[1] + s * h * eu});
          on_circle_[i].push_back(id);
          on_circle_[j].push_back(id);
        }
      }
  }

  // Each polygon edge split at its circle crossings; the parts outside every disc are boundary,
  // directed with the polygon region on their left.
  void polygon_pieces() {
    for (std::size_t k = 0; k < polys_.size(); ++k) {
      const auto& loop = polys_[k];
      if (loop.size() < 3) continue;
      int depth = 0;  // loops enclosing this one: an odd depth makes it a hole
      for (std::size_t o = 0; o < polys_.size(); ++o)
        if (o != k && polys_[o].size() >= 3 && inside_loop(polys_[o], loop[0])) ++depth;
      const bool forward = (signed_area(loop) > 0.0) == (depth % 2 == 0);
      const int first = int(points_.size());
      for (const Point2& p : loop) add_point(p);
      const std::size_t n = loop.size();
      for (std::size_t e = 0; e < n; ++e) {
        const Point2 a = loop[e], b = loop[(e + 1) % n];
        std::vector<std::pair<double, int>> cuts{{0.0, first + int(e)},
                                                 {1.0, first + int((e + 1) % n)}};
        const double du = b[0] - a[0], dw = b[1] - a[1], A = du * du + dw * dw;
        for (std::size_t i = 0; i < discs_.size() && A > 0.0; ++i) {
          const Point2& c = discs_[i].centre;
          const double r = discs_[i].radius;
          const double B = 2.0 * ((a[0] - c[0]) * du + (a[1] - c[1]) * dw);
          const double C = dist2(a, c) - r * r, disc = B * B - 4.0 * A * C;
          if (!(disc > 0.0)) continue;
          for (double s : {-1.0, 1.0}) {
            const double t = (-B + s * std::sqrt(disc)) / (2.0 * A);
            if (!(t > 0.0 && t < 1.0)) continue;
            const int id = add_point({a[0] + t * du, a[1] + t * dw});
            cuts.push_back({t, id});
            on_circle_[i].push_back(id);
          }
        }
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
          const double t = 0.5 * (cuts[c].first + cuts[c + 1].first);
          if (!(cuts[c + 1].first > cuts[c].first) ||
              in_discs({a[0] + t * du, a[1] + t * dw}, discs_.size()))
            continue;
          const int p = cuts[c].second, q = cuts[c + 1].second;
          pieces_.push_back({forward ? p : q, forward ? q : p, 0.0, {0.0, 0.0}, false});
        }
      }
    }
  }

  // Each circle split at its crossings; the arcs outside the other discs and the polygons are
  // boundary (counter-clockwise). A circle crossing nothing is a loop of its own if uncovered.
  void arc_pieces() {
    for (std::size_t i = 0; i < discs_.size(); ++i) {
      const Point2& c = discs_[i].centre;
      const double r = discs_[i].radius;
      if (!(r > 0.0)) continue;
      auto at = [&](double angle) {
        return Point2{c[0] + r * std::cos(angle), c[1] + r * std::sin(angle)};
      };
      if (on_circle_[i].empty()) {
        if (in_discs(at(0.0), i) || in_polygons(at(0.0))) continue;
        const int east = add_point(at(0.0)), west = add_point({c[0] - r, c[1]});
        pieces_.push_back({east, west, r, c, false});
        pieces_.push_back({west, east, r, c, false});
        continue;
      }
      std::vector<std::pair<double, int>> cuts;
      for (int id : on_circle_[i])
        cuts.push_back({std::atan2(points_[id][1] - c[1], points_[id][0] - c[0]), id});
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t k = 0; k < cuts.size(); ++k) {
        const double a0 = cuts[k].first;
        const double a1 = k + 1 < cuts.size() ? cuts[k + 1].first : cuts[0].first + 2.0 * M_PI;
        if (!(a1 - a0 > 1e-12)) continue;
        const Point2 mid = at(0.5 * (a0 + a1));
        if (in_discs(mid, i) || in_polygons(mid)) continue;
        const int to = k + 1 < cuts.size() ? cuts[k + 1].second : cuts[0].second;
        pieces_.push_back({cuts[k].second, to, r, c, a1 - a0 > M_PI});
      }
    }
  }

  // Follows the pieces from end to start into closed loops. Where no piece starts at a
  // piece's end point (degenerate crossings), the nearest free start within round-off is taken;
  // failing that the loop is closed there.
  std::vector<OutlineLoop> chain() {
    std::vector<std::vector<int>> starting(points_.size());
    for (std::size_t p = 0; p < pieces_.size(); ++p) starting[pieces_[p].from].push_back(int(p));
    std::vector<char> used(pieces_.size(), 0);
    const double tol2 = std::pow(1e-9 * std::max(scale_, 1.0), 2);
    auto next_after = [&](int point) {
      for (int p : starting[point])
        if (!used[p]) return p;
      int best = -1;
      double best_d2 = tol2;
      for (std::size_t p = 0; p < pieces_.size(); ++p)
        if (!used[p] && dist2(points_[pieces_[p].from], points_[point]) <= best_d2)
          best = int(p), best_d2 = dist2(points_[pieces_[p].from], points_[point]);
      return best;
    };
    std::vector<OutlineLoop> loops;
    for (std::size_t first = 0; first < pieces_.size(); ++first) {
      if (used[first]) continue;
      const int start = pieces_[first].from;
      OutlineLoop loop{points_[start], {}};
      for (int p = int(first); p >= 0;) {
        used[p] = 1;
        const Piece& q = pieces_[p];
        loop.steps.push_back({points_[q.to], q.radius, q.centre, q.large});
        if (q.to == start || dist2(points_[q.to], points_[start]) <= tol2) break;
        p = next_after(q.to);
      }
      loops.push_back(std::move(loop));
    }
    return loops;
  }

  const std::vector<std::vector<Point2>>& polys_;
  const std::vector<SliceDisc>& discs_;
  std::vector<std::vector<int>> on_circle_;  // per disc: ids of the crossings on its circle
  std::vector<Point2> points_;
  std::vector<Piece> pieces_;
  double scale_ = 0.0;
};

}  // namespace

std::vector<OutlineLoop> union_outline(const std::vector<std::vector<Point2>>& polygons,
                                       const std::vector<SliceDisc>& discs) {
  return Outliner(polygons, discs).run();
}

std::vector<BodyOutline> body_outlines(const Slice& s) {
  int n = 0;
  for (const SlicePolygon& p : s.polygons) n = std::max(n, p.body + 1);
  for (const SliceDisc& d : s.vertex_discs) n = std::max(n, d.body + 1);
  std::vector<std::vector<std::vector<Point2>>> polygons(n);
  std::vector<std::vector<SliceDisc>> discs(n);
  for (const SlicePolygon& p : s.polygons)
    if (p.closed && p.body >= 0) polygons[p.body].push_back(p.points);
  for (const SliceDisc& d : s.vertex_discs)
    if (d.body >= 0) discs[d.body].push_back(d);
  std::vector<BodyOutline> out;
  for (int b = 0; b < n; ++b)
    if (!polygons[b].empty() || !discs[b].empty())
      out.push_back({b, union_outline(polygons[b], discs[b])});
  return out;
}

}  // namespace invasim
