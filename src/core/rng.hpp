#pragma once
// Counter-based random numbers: Philox4x32-10 (Salmon et al., SC'11), written from the
// published description. Every draw is a pure function of (seed, step, site, stream), so
// trajectories do not depend on thread count, site processing order or restarts.
#include <array>
#include <cmath>
#include <cstdint>

#include "core/vec3.hpp"

namespace invasim {

// One Philox4x32-10 block: 4 counter words, 2 key words -> 4 random words.
inline std::array<std::uint32_t, 4> philox4x32_10(std::array<std::uint32_t, 4> ctr,
                                                  std::array<std::uint32_t, 2> key) {
  constexpr std::uint32_t kMul0 = 0xD2511F53u, kMul1 = 0xCD9E8D57u;
  constexpr std::uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    const std::uint64_t p0 = std::uint64_t(kMul0) * ctr[0];
    const std::uint64_t p1 = std::uint64_t(kMul1) * ctr[2];
    ctr = {std::uint32_t(p1 >> 32) ^ ctr[1] ^ key[0], std::uint32_t(p1),
           std::uint32_t(p0 >> 32) ^ ctr[3] ^ key[1], std::uint32_t(p0)};
    key[0] += kWeyl0;
    key[1] += kWeyl1;
  }
  return ctr;
}

// Named streams so that different uses of randomness never share a counter.
enum class RngStream : std::uint32_t {
  kThermal = 1,      // Langevin force on a site
  kOrientation = 2,  // rotational diffusion of an active cell
  kPlacement = 3,    // initial placement
  kVelocity = 4,     // initial velocities
  kPiston = 5,       // Langevin force on the pressure wall (site 0)
  kUser = 16         // first id free for later uses
};

// The random draws for one (seed, step, site, stream) key.
class RandomKey {
 public:
  RandomKey(std::uint64_t seed, std::uint64_t step, std::uint32_t site, RngStream stream,
            std::uint32_t sub = 0)
      : key_{std::uint32_t(seed), std::uint32_t(seed >> 32)},
        ctr_{std::uint32_t(step), std::uint32_t(step >> 32), site,
             (std::uint32_t(stream) << 16) ^ sub} {}

  // Four uniform numbers in (0, 1), 32-bit resolution, never 0 or 1.
  std::array<double, 4> uniform4() const {
    const auto w = philox4x32_10(ctr_, key_);
    std::array<double, 4> u;
    for (int i = 0; i < 4; ++i) u[i] = (double(w[i]) + 0.5) * 0x1p-32;
    return u;
  }
  // Four independent standard normal numbers (Box-Muller on uniform4()).
  std::array<double, 4> normal4() const {
    const auto u = uniform4();
    const double r0 = std::sqrt(-2.0 * std::log(u[0])), r1 = std::sqrt(-2.0 * std::log(u[2]));
    const double t0 = 2.0 * M_PI * u[1], t1 = 2.0 * M_PI * u[3];
    return {r0 * std::cos(t0), r0 * std::sin(t0), r1 * std::cos(t1), r1 * std::sin(t1)};
  }
  // A standard normal 3-vector (the fourth normal is discarded).
  Vec3 normal3() const {
    const auto g = normal4();
    return {g[0], g[1], g[2]};
  }

 private:
  std::array<std::uint32_t, 2> key_;
  std::array<std::uint32_t, 4> ctr_;
};

}  // namespace invasim
