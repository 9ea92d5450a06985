#pragma once
// Orthorhombic simulation box [lo, hi) per axis. Periodic axes wrap; a non-periodic axis is
// bounded by walls at lo and hi (x in invasim: the left wall lo.x moves under the barostat).
// `version` changes whenever a periodic length changes, so neighbour lists know to rebuild.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/errors.hpp"
#include "core/vec3.hpp"

namespace invasim {

class Box {
 public:
  Box() = default;
  // Box from corners; throws InputError if any length is not positive.
  Box(const Vec3& lo, const Vec3& hi, std::array<bool, 3> periodic);

  const Vec3& lo() const { return lo_; }
  const Vec3& hi() const { return hi_; }
  Vec3 lengths() const { return hi_ - lo_; }
  double length(int axis) const { return hi_[axis] - lo_[axis]; }
  bool periodic(int axis) const { return periodic_[axis]; }
  const std::array<bool, 3>& periodic() const { return periodic_; }
  double volume() const { return lengths().prod(); }
  // Area of a wall normal to x (the barostat's piston area).
  double wall_area() const { return length(1) * length(2); }
  std::uint64_t version() const { return version_; }

  // Minimum-image separation along periodic axes (valid for any |d|).
  Vec3 minimum_image(Vec3 d) const {
    for (int a = 0; a < 3; ++a)
      if (periodic_[a]) {
        const double len = hi_[a] - lo_[a];
        d[a] -= len * std::round(d[a] / len);
      }
    return d;
  }
  // The number of box lengths to take off d along each periodic axis to reach its minimum
  // image (0 on walled axes): minimum_image(d) == minus_periods(d, nearest_periods(d)).
  // Refuses a separation of kMaxImage box lengths or more, or not finite (no int says it).
  Vec3i nearest_periods(const Vec3& d) const {
    Vec3i n = Vec3i::Zero();
    for (int a = 0; a < 3; ++a)
      if (periodic_[a]) {
        const double k = std::round(d[a] / (hi_[a] - lo_[a]));
        if (!(std::abs(k) < kMaxImage))
          fail_input("separation ", d[a], " along axis ", a, " is not a countable number of ",
                     "box lengths");
        n[a] = static_cast<int>(k);
      }
    return n;
  }
  // d minus n box lengths along each periodic axis (a fixed image, whatever |d|).
  Vec3 minus_periods(Vec3 d, const Vec3i& n) const {
    for (int a = 0; a < 3; ++a)
      if (periodic_[a]) d[a] -= (hi_[a] - lo_[a]) * double(n[a]);
    return d;
  }
  // Wraps r into the primary cell on periodic axes and counts the crossings in image.
  // Image counts are ints; a site more than this many box lengths away has blown up.
  static constexpr double kMaxImage = 1e9;
  void wrap(Vec3& r, Vec3i& image) const {
    for (int a = 0; a < 3; ++a)
      if (periodic_[a]) {
        const double len = hi_[a] - lo_[a];
        if (r[a] >= hi_[a] || r[a] < lo_[a]) {
          const double shift = std::floor((r[a] - lo_[a]) / len);
          if (!(std::abs(double(image[a]) + shift) < kMaxImage)) {
            // Flung further than any int image count can say (a blow-up; converting the
            // shift would be undefined): the coordinate becomes infinite, a non-finite
            // position the blow-up guard reports.
            r[a] = std::copysign(std::numeric_limits<double>::infinity(), shift);
            continue;
          }
          r[a] -= shift * len;
          image[a] += static_cast<int>(shift);
          // Round-off at the upper edge (r just below lo, r + len rounding to hi; or a floor one
          // short): the site is one more period up, at lo. The image count must follow, or the
          // unwrapped position would lose a whole period (and again at every step it stays there).
          if (r[a] >= hi_[a]) {
            r[a] = lo_[a];
            ++image[a];
          }
        }
      }
  }
  // The first walled axis on which r lies outside [lo, hi] (a site must lie between the walls),
  // or -1.
  int axis_outside_walls(const Vec3& r) const {
    for (int a = 0; a < 3; ++a)
      if (!periodic_[a] && (r[a] < lo_[a] || r[a] > hi_[a])) return a;
    return -1;
  }
  // Position with the periodic images undone.
  Vec3 unwrap(const Vec3& r, const Vec3i& image) const {
    Vec3 u = r;
    for (int a = 0; a < 3; ++a)
      if (periodic_[a]) u[a] += image[a] * (hi_[a] - lo_[a]);
    return u;
  }

  // Moves the wall bound of a non-periodic axis (barostat, compression); no version change.
  void set_wall(int axis, bool upper, double value);
  // Replaces both corners (compression, rescaling); bumps the version.
  void set_bounds(const Vec3& lo, const Vec3& hi);
  // Sets the version counter (a checkpoint restores it exactly, in O(1): replaying
  // set_bounds calls would loop as often as a crafted file says).
  void restore_version(std::uint64_t version) { version_ = version; }

 private:
  Vec3 lo_ = Vec3::Zero();
  Vec3 hi_ = Vec3::Ones();
  std::array<bool, 3> periodic_{false, true, true};
  std::uint64_t version_ = 0;
};

// Branch-based minimum image for separations of two wrapped positions (|d| < L on periodic
// axes): cheaper than a rounding division in the pair loops.
class MinimumImage {
 public:
  explicit MinimumImage(const Box& box) {
    for (int a = 0; a < 3; ++a) {
      len_[a] = box.periodic(a) ? box.length(a) : 0.0;
      half_[a] = box.periodic(a) ? 0.5 * box.length(a) : std::numeric_limits<double>::infinity();
    }
  }
  double axis(int a, double d) const { return wrap(d, half_[a], len_[a]); }
  // The same with an axis's half period and period passed in (kept in registers by the
  // vectorised pair loops: contact kernel, neighbour-list build).
  static double wrap(double d, double half, double len) {
    return d > half ? d - len : (d < -half ? d + len : d);
  }
  double x(double d) const { return axis(0, d); }
  double y(double d) const { return axis(1, d); }
  double z(double d) const { return axis(2, d); }
  // Half the period along axis a (infinite on a walled axis) and the period (0 there).
  double half(int a) const { return half_[a]; }
  double length(int a) const { return len_[a]; }

 private:
  double len_[3], half_[3];
};

}  // namespace invasim
