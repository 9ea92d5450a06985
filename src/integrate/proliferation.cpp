#include "integrate/proliferation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/rng.hpp"

namespace invasim {

void ProliferationParams::validate() const {
  if (!(division_rate >= 0.0) || !std::isfinite(division_rate))
    fail_input("proliferation: division_rate = ", division_rate, " must be >= 0 and finite");
  if (!(death_rate >= 0.0) || !std::isfinite(death_rate))
    fail_input("proliferation: death_rate = ", death_rate, " must be >= 0 and finite");
  if (inhibition_contacts < 0)
    fail_input("proliferation: inhibition_contacts = ", inhibition_contacts, " must be >= 0");
  if (!(separation > 0.0 && separation <= 1.0))
    fail_input("proliferation: separation = ", separation,
               " must be in (0, 1] (a fraction of the cell's diameter)");
}

std::vector<int> SiteChange::follow(const std::vector<int>& old_sites) const {
  std::vector<char> member;
  std::vector<int> out;
  for (int i : old_sites) {
    const int j = new_index.at(std::size_t(i));
    if (j < 0) continue;
    out.push_back(j);
    if (member.size() <= std::size_t(j)) member.resize(std::size_t(j) + 1, 0);
    member[j] = 1;
  }
  for (const auto& [daughter, parent] : born)
    if (std::size_t(parent) < member.size() && member[parent]) out.push_back(daughter);
  return out;
}

Proliferation::Proliferation(const ProliferationParams& params) : params_(params) {
  params_.validate();
}

std::vector<int> Proliferation::contacts(const System& sys) const {
  if (sys.engine_layout()) throw std::logic_error("Proliferation::contacts in the engine layout");
  const Sites& s = sys.sites();
  const Box& box = sys.box();
  const std::size_t n = s.size();
  double reach = 0.0;  // the largest contact distance
  for (std::size_t i = 0; i < n; ++i) reach = std::max(reach, s.diameter[i]);
  // Cells of the grid at least `reach` wide, so that contacts are in neighbouring cells, and
  // not many more than the sites (the counts do not depend on the grid; tiny diameters or no
  // sites would otherwise ask for an int-overflowing number of cells).
  const double max_cells = 2.0 * std::cbrt(double(n)) + 2.0;
  Vec3i dims;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::floor(box.lengths()[a] / reach);  // +inf or NaN when reach is 0
    dims[a] = cells >= 1.0 ? int(std::min(cells, max_cells)) : 1;
  }
  auto cell_of = [&](const Vec3& r) {
    Vec3i c;
    for (int a = 0; a < 3; ++a) {
      const double f = (r[a] - box.lo()[a]) / box.lengths()[a];
      const double x = std::floor(f * dims[a]);  // clamped before the conversion (NaN: 0)
      c[a] = x >= 0.0 ? int(std::min(x, double(dims[a] - 1))) : 0;
    }
    return c;
  };
  auto flat = [&](const Vec3i& c) { return (c[0] * dims[1] + c[1]) * dims[2] + c[2]; };
  std::vector<std::vector<int>> grid(std::size_t(dims[0]) * dims[1] * dims[2]);
  for (std::size_t j = 0; j < n; ++j) grid[flat(cell_of(s.pos[j]))].push_back(int(j));
  std::vector<int> out;
  std::vector<int> seen;  // neighbouring cells already visited (small grids repeat them)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != SiteKind::kCancer) continue;
    const Vec3i c = cell_of(s.pos[i]);
    int count = 0;
    seen.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          Vec3i d(c[0] + dx, c[1] + dy, c[2] + dz);
          bool outside = false;
          for (int a = 0; a < 3; ++a) {
            if (d[a] >= 0 && d[a] < dims[a]) continue;
            if (!box.periodic(a)) outside = true;
            d[a] = (d[a] + dims[a]) % dims[a];
          }
          if (outside) continue;
          const int k = flat(d);
          if (std::find(seen.begin(), seen.end(), k) != seen.end()) continue;
          seen.push_back(k);
          for (int j : grid[k]) {
            if (std::size_t(j) == i) continue;
            const double contact = 0.5 * (s.diameter[i] + s.diameter[j]);
            if (box.minimum_image(s.pos[j] - s.pos[i]).squaredNorm() < contact * contact) ++count;
          }
        }
    out.push_back(count);
  }
  return out;
}

SiteChange Proliferation::apply(System& sys, double elapsed) const {
  if (sys.engine_layout()) throw std::logic_error("Proliferation::apply in the engine layout");
  if (!(elapsed >= 0.0)) fail_input("proliferation: elapsed time ", elapsed, " must be >= 0");
  const double p_death = -std::expm1(-params_.death_rate * elapsed);
  const double p_division = -std::expm1(-params_.division_rate * elapsed);
  const std::size_t n = sys.n_sites();
  std::vector<int> touching;
  if (params_.inhibition_contacts > 0 && p_division > 0.0) touching = contacts(sys);
  // The draws, in index order: death, division, the division axis.
  std::vector<int> dead;
  std::vector<std::pair<int, Vec3>> dividing;  // (cell, unit axis)
  std::size_t cell = 0;                        // rank among the cancer cells
  for (std::size_t i = 0; i < n; ++i) {
    if (sys.sites().kind[i] != SiteKind::kCancer) continue;
    const std::size_t rank = cell++;
    const auto u =
        RandomKey(sys.seed(), sys.step, std::uint32_t(i), RngStream::kProliferation).uniform4();
    if (u[0] < p_death) {
      dead.push_back(int(i));
      continue;
    }
    if (!(u[1] < p_division)) continue;
    if (!touching.empty() && touching[rank] >= params_.inhibition_contacts) continue;
    const double cos_theta = 2.0 * u[2] - 1.0;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * M_PI * u[3];
    dividing.emplace_back(int(i),
                          Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
  }
  SiteChange change;
  // Divisions: the daughters are appended in their parents' order.
  std::vector<std::pair<int, int>> born_old;  // (daughter, parent) before the deaths
  const Box& box = sys.box();
  auto inside_walls = [&box](Vec3 r) {
    for (int a = 0; a < 3; ++a)
      if (!box.periodic(a)) r[a] = std::clamp(r[a], box.lo()[a], box.hi()[a]);
    return r;
  };
  for (const auto& [i, axis] : dividing) {
    Sites& s = sys.sites();
    const Vec3 centre = sys.unwrapped(std::size_t(i));
    const Vec3 offset = 0.5 * params_.separation * s.diameter[i] * axis;
    const Vec3 velocity = 0.5 * s.vel[i];
    const Vec3 orientation = s.orient[i];
    const double diameter = s.diameter[i], mass = s.mass[i];
    Vec3 parent = inside_walls(centre - offset);
    Vec3i image = Vec3i::Zero();
    box.wrap(parent, image);
    s.pos[i] = parent;
    s.image[i] = image;
    s.vel[i] = velocity;
    const int daughter = sys.add_sphere(inside_walls(centre + offset), diameter, mass, orientation);
    sys.sites().vel[daughter] = velocity;
    born_old.emplace_back(daughter, i);
  }
  // Then the deaths (remove_sites moves the site epoch on; births alone move it here).
  std::vector<int> map(sys.n_sites());
  std::iota(map.begin(), map.end(), 0);
  if (!dead.empty())
    map = sys.remove_sites(dead);
  else if (!born_old.empty())
    sys.set_site_epoch(sys.site_epoch() + 1);
  change.new_index.assign(map.begin(), map.begin() + std::ptrdiff_t(n));
  for (const auto& [d, p] : born_old) change.born.emplace_back(map[d], map[p]);
  change.deaths = int(dead.size());
  return change;
}

}  // namespace invasim
