#include "core/box.hpp"

#include "core/errors.hpp"

namespace invasim {

namespace {
void check_corners(const Vec3& lo, const Vec3& hi) {
  for (int a = 0; a < 3; ++a)
    if (!(hi[a] > lo[a]) || !std::isfinite(lo[a]) || !std::isfinite(hi[a]))
      fail_input("box: length along axis ", "xyz"[a], " is ", hi[a] - lo[a], " (lo = ", lo[a],
                 ", hi = ", hi[a], "); it must be finite and > 0");
}
}  // namespace

Box::Box(const Vec3& lo, const Vec3& hi, std::array<bool, 3> periodic)
    : lo_(lo), hi_(hi), periodic_(periodic) {
  check_corners(lo, hi);
}

void Box::set_wall(int axis, bool upper, double value) {
  if (periodic_[axis]) fail_input("box: axis ", "xyz"[axis], " is periodic and has no wall");
  Vec3 lo = lo_, hi = hi_;
  (upper ? hi : lo)[axis] = value;
  check_corners(lo, hi);
  lo_ = lo;
  hi_ = hi;
}

void Box::set_bounds(const Vec3& lo, const Vec3& hi) {
  check_corners(lo, hi);
  lo_ = lo;
  hi_ = hi;
  ++version_;
}

}  // namespace invasim
