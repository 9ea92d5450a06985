#include "integrate/blowup_guard.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace invasim {

namespace {

// "cancer cell" or "vertex 5 of adipocyte 3", for the site in storage slot i.
std::string site_kind(const System& sys, std::size_t i) {
  const Sites& s = sys.sites();
  const int b = s.body[i];
  if (s.kind[i] == SiteKind::kCancer || b < 0 || std::size_t(b) >= sys.bodies().size())
    return "cancer cell";
  return "vertex " + std::to_string(sys.site_of_slot(int(i)) - sys.bodies()[b].first_site) +
         " of adipocyte " + std::to_string(b);
}

std::string triple(const Vec3& v) {
  std::ostringstream out;
  out << '(' << v[0] << ", " << v[1] << ", " << v[2] << ')';
  return out.str();
}

bool finite(const Vec3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

[[noreturn]] void fail_site(const System& sys, std::size_t i, const std::string& what) {
  fail_simulation("blow-up at step ", sys.step, ": site ", sys.site_of_slot(int(i)), " (",
                  site_kind(sys, i), ") ", what);
}

}  // namespace

void check_blowup(const System& sys) {
  const Box& box = sys.box();  // always finite: Box refuses non-finite bounds
  const Sites& s = sys.sites();
  // In permanent-index order (the first blown-up site is the same in either storage layout).
  for (std::size_t site = 0; site < s.size(); ++site) {
    const std::size_t i = std::size_t(sys.slot_of(int(site)));
    const Vec3& r = s.pos[i];
    if (!finite(r)) fail_site(sys, i, "has a non-finite position " + triple(r));
    if (!finite(s.vel[i])) fail_site(sys, i, "has a non-finite velocity " + triple(s.vel[i]));
    const double d = s.diameter[i];
    for (int a = 0; a < 3; ++a) {
      if (box.periodic(a)) continue;
      const double lo = box.lo()[a] - d, hi = box.hi()[a] + d;  // one diameter beyond
      const bool below = r[a] < lo;
      if (!below && !(r[a] > hi)) continue;
      const char axis = "xyz"[a];
      std::ostringstream what;
      what << "has left the box through the " << (below ? "lower " : "upper ") << axis
           << " wall: " << axis << " = " << r[a] << (below ? " < lo." : " > hi.") << axis
           << (below ? " - diameter = " : " + diameter = ") << (below ? lo : hi) << ", position "
           << triple(r);
      fail_site(sys, i, what.str());
    }
  }
}

void BlowupGuard::set_every(std::uint64_t every) {
  if (every < 1) fail_input("blow-up check interval check_every = ", every, " must be >= 1");
  every_ = every;
}

}  // namespace invasim
