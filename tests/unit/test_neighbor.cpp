// VerletList against a brute-force O(N^2) pair search: every pair with minimum-image distance
// below cutoff(i, j) + skin, both directions, vertices of one adipocyte excluded.
#include <omp.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "mesh/geometry.hpp"
#include "neighbor/cell_stencil.hpp"
#include "neighbor/verlet_list.hpp"
#include "test_support.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

namespace {

using PairSet = std::set<std::pair<int, int>>;

// Minimum-image distance computed independently of Box: the smallest |d + k L| over the
// images k in {-1, 0, 1} of every periodic axis (positions are wrapped, so this is exact).
double brute_distance(const System& sys, int i, int j) {
  const Box& box = sys.box();
  const Vec3 d0 = sys.sites().pos[i] - sys.sites().pos[j];
  double best = INFINITY;
  for (int kx = -1; kx <= 1; ++kx)
    for (int ky = -1; ky <= 1; ++ky)
      for (int kz = -1; kz <= 1; ++kz) {
        const int k[3] = {kx, ky, kz};
        Vec3 d = d0;
        bool skip = false;
        for (int a = 0; a < 3; ++a) {
          if (!box.periodic(a) && k[a] != 0) skip = true;
          d[a] += k[a] * box.length(a);
        }
        if (!skip) best = std::min(best, d.norm());
      }
  return best;
}

// Ordered pairs (i, j), i != j, closer than rule.of(...) + skin, excluding same-body vertices.
PairSet brute_pairs(const System& sys, const CutoffRule& rule, double skin) {
  const Sites& s = sys.sites();
  PairSet out;
  const int n = int(s.size());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      if (s.body[i] >= 0 && s.body[i] == s.body[j]) continue;
      const double rc = rule.of(s.kind[i], s.kind[j], s.diameter[i], s.diameter[j]) + skin;
      if (brute_distance(sys, i, j) < rc) out.insert({i, j});
    }
  return out;
}

// The list as a set of ordered pairs; fails if any row holds a duplicate or the site itself.
PairSet list_pairs(const VerletList& list, std::size_t n) {
  PairSet out;
  std::size_t total = 0, duplicates = 0, self = 0, out_of_range = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int* nb = list.neighbors(i);
    const std::set<int> row(nb, nb + list.count(i));
    duplicates += std::size_t(list.count(i)) - row.size();  // cell deduplication
    self += row.count(int(i));
    for (int j : row) {
      if (j < 0 || j >= int(n)) ++out_of_range;
      out.insert({int(i), j});
    }
    total += std::size_t(list.count(i));
  }
  CHECK(duplicates == 0);
  CHECK(self == 0);
  CHECK(out_of_range == 0);
  CHECK(total == out.size());
  return out;
}

bool symmetric(const PairSet& p) {
  for (const auto& [i, j] : p)
    if (!p.count({j, i})) return false;
  return true;
}

// Builds (or updates) the list and requires it to equal the brute-force set exactly.
void require_exact(const System& sys, const VerletList& list, const CutoffRule& rule) {
  const PairSet expected = brute_pairs(sys, rule, list.skin());
  const PairSet got = list_pairs(list, sys.n_sites());
  REQUIRE(!expected.empty());
  // Report the first few differences in either direction before failing.
  std::vector<std::pair<int, int>> missing, extra;
  std::set_difference(expected.begin(), expected.end(), got.begin(), got.end(),
                      std::back_inserter(missing));
  std::set_difference(got.begin(), got.end(), expected.begin(), expected.end(),
                      std::back_inserter(extra));
  INFO("pairs expected " << expected.size() << ", listed " << got.size() << ", missing "
                         << missing.size() << ", extra " << extra.size());
  if (!missing.empty())
    INFO("first missing (" << missing[0].first << ", " << missing[0].second << ")");
  if (!extra.empty()) INFO("first extra (" << extra[0].first << ", " << extra[0].second << ")");
  CHECK(missing.empty());
  CHECK(extra.empty());
  CHECK(symmetric(got));
}

CutoffRule rule_of(double cc, double cv, double vv) {
  CutoffRule r;
  r.factor = {{{cc, cv}, {cv, vv}}};
  return r;
}

// Random displacement of length exactly `len` (reproducible per site and round).
Vec3 random_step(std::uint64_t seed, int site, int round, double len) {
  const auto g = RandomKey(seed, round, std::uint32_t(site), RngStream::kUser).normal4();
  return len * Vec3(g[0], g[1], g[2]).normalized();
}

// Polydisperse spheres (diameters in [0.5, 1.5]) at random in a box of side L.
System polydisperse(int n, double L, std::array<bool, 3> periodic, std::uint64_t seed) {
  System sys(Box(Vec3::Zero(), Vec3::Constant(L), periodic), seed);
  for (int i = 0; i < n; ++i)
    sys.add_sphere(
        L * Vec3(test::uniform(seed, i, 0), test::uniform(seed, i, 1), test::uniform(seed, i, 2)),
        0.5 + test::uniform(seed, i, 3));
  return sys;
}

}  // namespace

TEST_CASE("Verlet list equals the brute-force pair set in a fully periodic box") {
  System sys = test::random_spheres(400, 0.5, false, 11);
  const CutoffRule rule = rule_of(1.2, 1.0, 1.0);  // cohesive cancer-cancer range
  VerletList list(0.3);
  list.set_cutoff_rule(rule);
  CHECK(list.update(sys));
  CHECK(list.builds() == 1);
  require_exact(sys, list, rule);
  // A second update with nothing moved does not rebuild.
  CHECK_FALSE(list.update(sys));
  CHECK(list.builds() == 1);
}

TEST_CASE(
    "Verlet list with polydisperse sites, a large cutoff factor and more than 64 neighbours") {
  // Cutoff factor 2.5 gives ~90 neighbours per site, beyond the initial row stride of 64.
  System sys = polydisperse(700, 10.0, {true, true, true}, 5);
  const CutoffRule rule = rule_of(2.5, 1.0, 1.0);
  VerletList list(0.3);
  list.set_cutoff_rule(rule);
  list.build(sys);
  int max_count = 0;
  for (std::size_t i = 0; i < sys.n_sites(); ++i) max_count = std::max(max_count, list.count(i));
  CHECK(max_count > 64);
  require_exact(sys, list, rule);
}

TEST_CASE("Verlet list equals the brute-force pair set with walls in x, periodic y and z") {
  System sys = test::random_spheres(400, 0.5, true, 12);
  const CutoffRule rule = rule_of(1.2, 1.0, 1.0);
  VerletList list(0.4);
  list.set_cutoff_rule(rule);
  list.update(sys);
  require_exact(sys, list, rule);
  // No pair is found through the x walls: sites at opposite walls are not neighbours.
  const Sites& s = sys.sites();
  const double Lx = sys.box().length(0);
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < list.count(i); ++k) {
      const int j = list.neighbors(i)[k];
      CHECK(std::abs(s.pos[i][0] - s.pos[j][0]) < 0.5 * Lx);
    }
}

TEST_CASE(
    "Verlet list: moves below skin/2 keep the list valid without a rebuild, larger moves rebuild") {
  const double skin = 0.3;
  for (bool walls : {false, true}) {
    DYNAMIC_SECTION("walls in x: " << walls) {
      System sys = test::random_spheres(400, 0.55, walls, 21 + walls);
      const CutoffRule rule = rule_of(1.2, 1.0, 1.0);
      VerletList list(skin);
      list.set_cutoff_rule(rule);
      list.update(sys);
      const auto builds = list.builds();
      const PairSet at_build = list_pairs(list, sys.n_sites());
      const PairSet bare_before = brute_pairs(sys, rule, 0.0);
      const Vec3 start_mover = sys.unwrapped(17);
      // Every site moves by 0.49 skin (just under skin/2) in a random direction.
      Sites& s = sys.sites();
      for (std::size_t i = 0; i < s.size(); ++i) {
        s.pos[i] += random_step(3, int(i), 0, 0.49 * skin);
        sys.box().wrap(s.pos[i], s.image[i]);
      }
      CHECK_FALSE(list.update(sys));
      CHECK(list.builds() == builds);
      const PairSet now = list_pairs(list, sys.n_sites());
      CHECK(now == at_build);
      // The list still holds every pair within the bare cutoff at the new positions.
      const PairSet bare = brute_pairs(sys, rule, 0.0);
      CHECK(bare != bare_before);  // the moves created new contacts: the check is not vacuous
      std::size_t unlisted = 0;
      for (const auto& p : bare) unlisted += now.count(p) == 0;
      CHECK(unlisted == 0);  // pairs within the bare cutoff missing from the stale list
      // One site now moves further along the same direction, to 0.69 skin from its build
      // position (past skin/2, short of a full skin): the list must rebuild and be exact again.
      const int mover = 17;
      s.pos[mover] += random_step(3, mover, 0, 0.2 * skin);
      sys.box().wrap(s.pos[mover], s.image[mover]);
      const double moved = (sys.unwrapped(mover) - start_mover).norm();
      REQUIRE(moved > 0.6 * skin);
      REQUIRE(moved < 0.8 * skin);
      CHECK(list.update(sys));
      CHECK(list.builds() == builds + 1);
      require_exact(sys, list, rule);
      // Large random moves of everything (several skins), then exact again after rebuild.
      for (std::size_t i = 0; i < s.size(); ++i) {
        s.pos[i] += random_step(4, int(i), 2, 1.5);
        if (walls) s.pos[i][0] = std::clamp(s.pos[i][0], 0.0, sys.box().length(0));
        sys.box().wrap(s.pos[i], s.image[i]);
      }
      CHECK(list.update(sys));
      CHECK(list.builds() == builds + 2);
      require_exact(sys, list, rule);
    }
  }
}

TEST_CASE("Verlet list rebuilds after a box change (System::scale) and matches brute force") {
  System sys = test::mixed_system(2, 150, 7.5, 0.2, 31);
  const CutoffRule rule = rule_of(1.2, 1.0, 1.0);
  VerletList list(0.3);
  list.set_cutoff_rule(rule);
  list.update(sys);
  require_exact(sys, list, rule);
  const auto b0 = list.builds();
  // A tiny change moves no site by skin/2, but the periodic lengths changed: must rebuild.
  sys.scale(Vec3(1.0, 0.9999, 1.0), true);
  CHECK(list.update(sys));
  CHECK(list.builds() == b0 + 1);
  require_exact(sys, list, rule);
  // Compress anisotropically: sites near the far edges move by far more than the skin.
  sys.scale(Vec3(0.93, 0.9, 0.95), true);
  CHECK(list.update(sys));
  CHECK(list.builds() == b0 + 2);
  require_exact(sys, list, rule);
  sys.scale(Vec3(1.0, 1.12, 1.05), false);  // affine, bodies deform
  CHECK(list.update(sys));
  require_exact(sys, list, rule);
}

TEST_CASE("Verlet list with adipocytes excludes same-body vertex pairs and nothing else") {
  System sys = test::mixed_system(2, 200, 7.0, 0.3, 41);
  // Different factors per kind pair exercise the CutoffRule lookup.
  const CutoffRule rule = rule_of(1.2, 1.05, 0.95);
  VerletList list(0.3);
  list.set_cutoff_rule(rule);
  list.update(sys);
  require_exact(sys, list, rule);
  const Sites& s = sys.sites();
  // Same-body vertex pairs well within the cutoff exist (so the exclusion is tested) ...
  int same_body_close = 0;
  for (const MeshBody& b : sys.bodies())
    for (int u = 0; u < b.n_vertices(); ++u)
      for (int v = u + 1; v < b.n_vertices(); ++v)
        same_body_close +=
            brute_distance(sys, b.first_site + u, b.first_site + v) < 0.95 * 2.0 + 0.3;
  CHECK(same_body_close > 100);
  // ... and none is listed; vertex-vertex pairs of different bodies and vertex-cell pairs are.
  int same_body_listed = 0, cv = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < list.count(i); ++k) {
      const int j = list.neighbors(i)[k];
      same_body_listed += s.body[i] >= 0 && s.body[j] == s.body[i];
      cv += (s.body[i] >= 0) != (s.body[j] >= 0);
    }
  CHECK(same_body_listed == 0);
  CHECK(cv > 0);
  // Bring two bodies into contact so different-body vertex pairs exist, then rebuild.
  const MeshBody& b1 = sys.bodies()[1];
  const Vec3 c0 = TetherForce::body_centres(sys)[0];
  const Vec3 c1 = TetherForce::body_centres(sys)[1];
  const Vec3 shift = sys.box().minimum_image(c0 - c1) * 0.4;
  Sites& sm = sys.sites();
  for (int v = 0; v < b1.n_vertices(); ++v) {
    sm.pos[b1.first_site + v] += shift;
    sys.box().wrap(sm.pos[b1.first_site + v], sm.image[b1.first_site + v]);
  }
  CHECK(list.update(sys));
  require_exact(sys, list, rule);
  int vv_other = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < list.count(i); ++k) {
      const int j = list.neighbors(i)[k];
      vv_other += s.body[i] >= 0 && s.body[j] >= 0;
    }
  CHECK(vv_other > 0);
}

TEST_CASE("Verlet list in small periodic boxes with 2 or 3 cells per axis (cell deduplication)") {
  // Reach = 1.0 * 1.1 + 0.3 = 1.4: L = 3.0 gives 2 cells, L = 4.5 gives 3 cells per axis.
  const CutoffRule rule = rule_of(1.0, 1.0, 1.0);
  for (double L : {2.85, 3.0, 4.5}) {
    DYNAMIC_SECTION("fully periodic cube L = " << L) {
      System sys(Box(Vec3::Zero(), Vec3::Constant(L), {true, true, true}), 3);
      const int n = int(0.6 * L * L * L);
      for (int i = 0; i < n; ++i)
        sys.add_sphere(
            L * Vec3(test::uniform(7, i, 0), test::uniform(7, i, 1), test::uniform(7, i, 2)),
            i % 2 ? 1.1 : 0.9);
      VerletList list(0.3);
      list.set_cutoff_rule(rule);
      list.update(sys);
      require_exact(sys, list, rule);
    }
  }
  SECTION("mixed: 1 walled cell in x, 2 cells in y, 3 in z") {
    System sys(Box(Vec3::Zero(), Vec3(1.3, 3.0, 4.5), {false, true, true}), 3);
    for (int i = 0; i < 20; ++i)
      sys.add_sphere(Vec3(1.3 * test::uniform(8, i, 0), 3.0 * test::uniform(8, i, 1),
                          4.5 * test::uniform(8, i, 2)),
                     i % 2 ? 1.1 : 0.9);
    VerletList list(0.3);
    list.set_cutoff_rule(rule);
    list.update(sys);
    require_exact(sys, list, rule);
  }
}

TEST_CASE("Verlet list with sites slightly outside a wall") {
  System sys = test::random_spheres(300, 0.5, true, 51);
  Sites& s = sys.sites();
  const double Lx = sys.box().length(0);
  // Push a few sites just beyond each wall (as the dynamics can do under wall overlap), and
  // put partners next to them inside so that they have neighbours.
  for (int k = 0; k < 10; ++k) {
    s.pos[k][0] = -0.05 - 0.03 * k;
    s.pos[k + 10] = s.pos[k] + Vec3(0.8, 0.1, 0.0);
    s.pos[k + 20][0] = Lx + 0.05 + 0.03 * k;
    s.pos[k + 30] = s.pos[k + 20] - Vec3(0.8, 0.1, 0.0);
  }
  sys.wrap_all();
  const CutoffRule rule = rule_of(1.2, 1.0, 1.0);
  VerletList list(0.3);
  list.set_cutoff_rule(rule);
  list.update(sys);
  for (int k = 0; k < 10; ++k) {
    CHECK(list.count(k) > 0);
    CHECK(list.count(k + 20) > 0);
  }
  require_exact(sys, list, rule);
}

TEST_CASE("Verlet list refuses a periodic box shorter than twice the cutoff + skin, naming it") {
  // Reach = 1.1 + 0.3 = 1.4; L_y = 2.5 < 2.8.
  System sys(Box(Vec3::Zero(), Vec3(5.0, 2.5, 5.0), {true, true, true}), 1);
  sys.add_sphere(Vec3(1, 1, 1), 1.1);
  sys.add_sphere(Vec3(2, 1, 1), 0.9);
  VerletList list(0.3);
  CHECK_THROWS_AS(list.update(sys), InputError);
  CHECK_THROWS_WITH(list.update(sys), Contains("box length along y = 2.5"));
  // A cohesive cutoff rule counts: L = 3.0 passes with factor 1 but not with factor 1.2.
  System ok(Box(Vec3::Zero(), Vec3::Constant(3.0), {true, true, true}), 1);
  ok.add_sphere(Vec3(1, 1, 1), 1.1);
  CHECK_NOTHROW(list.update(ok));
  list.set_cutoff_rule(rule_of(1.2, 1.0, 1.0));
  CHECK_THROWS_WITH(list.update(ok), Contains("box length along x = 3"));
  // A short walled axis is fine: walls do not wrap.
  System walled(Box(Vec3::Zero(), Vec3(1.0, 5.0, 5.0), {false, true, true}), 1);
  walled.add_sphere(Vec3(0.5, 1, 1), 1.1);
  CHECK_NOTHROW(list.update(walled));
  // The shrinking box is caught when it becomes too short, by a rebuild after scale().
  System shrink = test::random_spheres(30, 0.3, false, 2);
  VerletList l2(0.3);
  l2.update(shrink);
  const double L = shrink.box().length(0);
  shrink.scale(Vec3::Constant(2.7 / L), false);
  CHECK_THROWS_AS(l2.update(shrink), InputError);
}

TEST_CASE(
    "Verlet list: per-class-pair stencils scan about the reach's volume, rows exact, in mixed "
    "systems") {
  // Cancer cells (cohesive: list radius 1.2 s + skin) next to adipocyte vertices (diameter 2):
  // the largest reach is the vertex-vertex one (2.3), the cells' own is 1.62. Cells as wide as
  // the smallest reach and stencils per class pair scan ~10 candidates per listed pair here,
  // and testing each pair once (from the site first in the binned order) halves that (5.1;
  // cells of half the smallest reach scanned 2.9 but cost more per site to find their runs,
  // verlet_list.cpp); cells as wide as the largest reach, every pair tested from both sides,
  // scan ~29.
  const CutoffRule rule = rule_of(1.2, 1.0, 1.0);
  SECTION("slab of 2 x 2 x 2 adipocytes and 1500 cells") {
    System sys = test::slab_system(2, 2, 1500, 5.2, 0.6, 11);
    VerletList list(0.3);
    list.set_cutoff_rule(rule);
    list.update(sys);
    require_exact(sys, list, rule);
    double entries = 0.0;
    for (std::size_t i = 0; i < sys.n_sites(); ++i) entries += list.count(i);
    const double per_entry = double(list.candidates()) / entries;
    INFO("candidates per listed pair " << per_entry);
    CHECK(per_entry < 6.0);
  }
  auto build_and_require_exact = [&](const System& sys) {
    VerletList list(0.3);
    list.set_cutoff_rule(rule);
    list.update(sys);
    require_exact(sys, list, rule);
  };
  SECTION("one adipocyte in a small box: the vertex stencils wrap onto themselves") {
    // L = 6: 7 cells per axis of width 0.86, the vertex-vertex stencil spans 7 offsets.
    build_and_require_exact(test::mixed_system(1, 40, 6.0, 0.3, 5));
  }
  SECTION("8 adipocytes and 100 cells in a box of side 10") {
    build_and_require_exact(test::mixed_system(2, 100, 5.0, 0.5, 6));
  }
}

TEST_CASE("Verlet list refuses an asymmetric cutoff rule, naming both factors") {
  // Each pair is tested once for both rows, which needs cutoff(i, j) = cutoff(j, i).
  VerletList list(0.3);
  CHECK_NOTHROW(list.set_cutoff_rule(rule_of(1.2, 1.05, 0.95)));
  CutoffRule rule = rule_of(1.2, 1.0, 1.0);
  rule.factor[1][0] = 1.1;
  CHECK_THROWS_AS(list.set_cutoff_rule(rule), InputError);
  CHECK_THROWS_WITH(list.set_cutoff_rule(rule),
                    Contains("cancer-vertex = 1") && Contains("vertex-cancer = 1.1"));
}

TEST_CASE(
    "Cell stencils stay within the grid when the reach is many cell lengths (squeezed axis)") {
  // A blown-up tissue can squeeze the walls' axis to a sliver: the reach is then ~1e9 cell
  // lengths along x. The stencil must still hold only offsets the grid has (it used to loop
  // over every offset up to the reach: minutes per list build).
  for (const bool periodic_x : {false, true}) {
    const Box box(Vec3(0.0, 0.0, 0.0), Vec3(1e-9, 8.0, 8.0), {periodic_x, true, true});
    CellStencils grid;
    grid.setup(box, 1e-10, {1.7, 1.7, 1.7, 2.3}, 2, 4096);
    const auto& nc = grid.cells_per_axis();
    INFO("periodic x " << periodic_x << ", cells " << nc[0] << " x " << nc[1] << " x " << nc[2]);
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        CHECK(grid.strips(a, b) <= std::size_t((2 * nc[0] + 1) * (2 * nc[1] + 1)));
        std::vector<int> seen(std::size_t(grid.n_cells()), 0);
        grid.for_each_run(0, a, b, [&](int c0, int c1) {
          for (int c = c0; c <= c1; ++c) ++seen[std::size_t(c)];
        });
        CHECK(*std::max_element(seen.begin(), seen.end()) == 1);  // every cell once
      }
  }
}

TEST_CASE(
    "Verlet list at 1 and 2 threads: a row overflowing the stride in the mirror pass is rebuilt "
    "exactly") {
  // 1500 spheres of diameter 1 (~14 neighbours each) and one of diameter 4 in the corner cell,
  // added last: it comes last in the binned order, so all its ~140 neighbours reach its row
  // through the mirror pass (its own upper part is empty) while no upper part exceeds the
  // initial stride of 64. The mirror pass overflows, the build is repeated with a wider
  // stride (max_count + 16), and the rows are exact whatever thread placed which entry.
  const int saved = omp_get_max_threads();
  const double L = 10.0;
  System sys(Box(Vec3::Zero(), Vec3::Constant(L), {true, true, true}), 7);
  for (int i = 0; i < 1500; ++i)
    sys.add_sphere(L * Vec3(test::uniform(7, i, 0), test::uniform(7, i, 1), test::uniform(7, i, 2)),
                   1.0);
  sys.add_sphere(Vec3::Constant(L - 0.01), 4.0);
  const CutoffRule rule = rule_of(1.0, 1.0, 1.0);
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    omp_set_num_threads(threads);
    VerletList list(0.3);
    list.set_cutoff_rule(rule);
    REQUIRE(list.stride() == 64);
    list.update(sys);
    CHECK(list.count(1500) > 64);
    CHECK(list.max_count() == std::size_t(list.count(1500)));
    CHECK(list.stride() == list.max_count() + 16);  // grown by the mirror pass's overflow
    require_exact(sys, list, rule);
    list.build(sys);  // the wider stride holds it at once
    CHECK(list.stride() == list.max_count() + 16);
    require_exact(sys, list, rule);
  }
  omp_set_num_threads(saved);
}
