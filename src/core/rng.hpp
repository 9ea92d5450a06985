#pragma once
// Counter-based random numbers: Philox4x32-10 (Salmon et al., SC'11), written from the
// published description; normal numbers by Box-Muller (normal4) or the ziggurat (normal3). Every
// draw is a pure function of (seed, step, site, stream), so trajectories do not depend on thread
// count, site processing order or restarts.
#include <array>
#include <cmath>
#include <cstdint>

#include "core/vec3.hpp"

namespace invasim {

// One Philox4x32-10 block on plain words (counter c0..c3, key k0, k1 -> w0..w3), so that a
// loop over sites drawing one block each vectorises (`#pragma omp simd`).
[[gnu::always_inline]] inline void philox4x32_10_words(std::uint32_t c0, std::uint32_t c1,
                                                       std::uint32_t c2, std::uint32_t c3,
                                                       std::uint32_t k0, std::uint32_t k1,
                                                       std::uint32_t& w0, std::uint32_t& w1,
                                                       std::uint32_t& w2, std::uint32_t& w3) {
  constexpr std::uint32_t kMul0 = 0xD2511F53u, kMul1 = 0xCD9E8D57u;
  constexpr std::uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    const std::uint64_t p0 = std::uint64_t(kMul0) * c0;
    const std::uint64_t p1 = std::uint64_t(kMul1) * c2;
    const std::uint32_t n0 = std::uint32_t(p1 >> 32) ^ c1 ^ k0, n1 = std::uint32_t(p1);
    const std::uint32_t n2 = std::uint32_t(p0 >> 32) ^ c3 ^ k1, n3 = std::uint32_t(p0);
    c0 = n0, c1 = n1, c2 = n2, c3 = n3;
    k0 += kWeyl0;
    k1 += kWeyl1;
  }
  w0 = c0, w1 = c1, w2 = c2, w3 = c3;
}

// One Philox4x32-10 block: 4 counter words, 2 key words -> 4 random words.
inline std::array<std::uint32_t, 4> philox4x32_10(std::array<std::uint32_t, 4> ctr,
                                                  std::array<std::uint32_t, 2> key) {
  std::array<std::uint32_t, 4> w;
  philox4x32_10_words(ctr[0], ctr[1], ctr[2], ctr[3], key[0], key[1], w[0], w[1], w[2], w[3]);
  return w;
}

// Named streams so that different uses of randomness never share a counter.
enum class RngStream : std::uint32_t {
  kThermal = 1,        // Langevin force on a site
  kOrientation = 2,    // rotational diffusion of an active cell
  kPlacement = 3,      // initial placement
  kVelocity = 4,       // initial velocities
  kPiston = 5,         // Langevin force on the pressure wall (site 0)
  kProliferation = 6,  // division and death of cancer cells (integrate/proliferation.hpp)
  kUser = 16           // first id free for later uses
};

// The 128-layer ziggurat for the standard normal (Marsaglia and Tsang 2000, in the form of
// Doornik 2005 with the layer index and the uniform taken from separate bits): x[0] = v/f(r),
// x[1] = r = 3.442619855899, x[128] = 0, layers of equal area v = 9.91256303526217e-3 under
// f(x) = exp(-x^2/2); ratio[i] = x[i+1]/x[i].
struct ZigguratTables {
  static constexpr int kLayers = 128;
  static constexpr double kR = 3.442619855899, kV = 9.91256303526217e-3;
  double x[kLayers + 1];
  double ratio[kLayers];
  ZigguratTables() {
    double f = std::exp(-0.5 * kR * kR);
    x[0] = kV / f;
    x[1] = kR;
    x[kLayers] = 0.0;
    for (int i = 2; i < kLayers; ++i) {
      x[i] = std::sqrt(-2.0 * std::log(kV / x[i - 1] + f));
      f = std::exp(-0.5 * x[i] * x[i]);
    }
    for (int i = 0; i < kLayers; ++i) ratio[i] = x[i + 1] / x[i];
  }
};
inline const ZigguratTables& ziggurat_tables() {
  static const ZigguratTables t;
  return t;
}

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
    for (int i = 0; i < 4; ++i) u[i] = uniform(w[i]);
    return u;
  }
  // The uniform in (0, 1) of one random word, as uniform4 makes it.
  static double uniform(std::uint32_t w) { return (double(w) + 0.5) * 0x1p-32; }
  // The Philox block of key (seed, step, site, stream) on plain words: the words uniform4()
  // and normal3() start from, for loops over sites that vectorise (the counter laid out as
  // the constructor lays it out, sub-stream 0).
  [[gnu::always_inline]] static void block_words(std::uint64_t seed, std::uint64_t step,
                                                 std::uint32_t site, RngStream stream,
                                                 std::uint32_t& w0, std::uint32_t& w1,
                                                 std::uint32_t& w2, std::uint32_t& w3) {
    philox4x32_10_words(std::uint32_t(step), std::uint32_t(step >> 32), site,
                        std::uint32_t(stream) << 16, std::uint32_t(seed), std::uint32_t(seed >> 32),
                        w0, w1, w2, w3);
  }
  // Four independent standard normal numbers (Box-Muller on uniform4()).
  std::array<double, 4> normal4() const {
    const auto u = uniform4();
    const double r0 = std::sqrt(-2.0 * std::log(u[0])), r1 = std::sqrt(-2.0 * std::log(u[2]));
    const double t0 = 2.0 * M_PI * u[1], t1 = 2.0 * M_PI * u[3];
    return {r0 * std::cos(t0), r0 * std::sin(t0), r1 * std::cos(t1), r1 * std::sin(t1)};
  }
  // A standard normal 3-vector by the ziggurat: the three components take their uniforms
  // from words 0-2 of one Philox block and their layers from 7-bit fields of word 3; with
  // probability ~0.988 each is accepted at once (no log, no trigonometry). A rejected one
  // (a wedge or the tail beyond r) continues with further blocks of the same key, told apart
  // by a retry count in bits 24-31 of the stream word (which the streams and sub-streams
  // leave free), so the result stays a pure function of the key.
  Vec3 normal3() const {
    const auto w = philox4x32_10(ctr_, key_);
    const ZigguratTables& z = ziggurat_tables();
    Vec3 g;
    Retry retry{*this};
    for (int c = 0; c < 3; ++c) {
      const double u = signed_uniform(w[c]);
      const int layer = int(w[3] >> (7 * c)) & (ZigguratTables::kLayers - 1);
      g[c] = std::abs(u) < z.ratio[layer] ? u * z.x[layer] : ziggurat_slow(u, layer, retry);
    }
    return g;
  }
  // normal3() of the keys (seed, step, sites[q], stream) for q < m (m <= kBatch), the same
  // numbers bit for bit, as structure of arrays g[0..2][q]: the Philox blocks and the
  // ziggurat's fast test in loops the compiler vectorises, then the rare rejections (a few %
  // of the components) one by one, in normal3's order.
  static constexpr int kBatch = 128;
  static void normal3_batch(std::uint64_t seed, std::uint64_t step, const int* sites, int m,
                            RngStream stream, double (*g)[kBatch]) {
    const ZigguratTables& z = ziggurat_tables();
    std::uint32_t w[4][kBatch];
    bool slow[kBatch];
#pragma omp simd
    for (int q = 0; q < m; ++q) {
      block_words(seed, step, std::uint32_t(sites[q]), stream, w[0][q], w[1][q], w[2][q], w[3][q]);
      bool any_slow = false;
      for (int c = 0; c < 3; ++c) {
        const double u = signed_uniform(w[c][q]);
        const int layer = int(w[3][q] >> (7 * c)) & (ZigguratTables::kLayers - 1);
        const bool fast = std::abs(u) < z.ratio[layer];
        g[c][q] = u * z.x[layer];
        any_slow |= !fast;
      }
      slow[q] = any_slow;
    }
    for (int q = 0; q < m; ++q) {
      if (!slow[q]) continue;
      const RandomKey key(seed, step, std::uint32_t(sites[q]), stream);
      Retry retry{key};
      for (int c = 0; c < 3; ++c) {
        const double u = signed_uniform(w[c][q]);
        const int layer = int(w[3][q] >> (7 * c)) & (ZigguratTables::kLayers - 1);
        if (!(std::abs(u) < z.ratio[layer])) g[c][q] = ziggurat_slow(u, layer, retry);
      }
    }
  }

 private:
  // Uniform in (-1, 1) from a 32-bit word, never 0.
  static double signed_uniform(std::uint32_t w) {
    return (double(std::int32_t(w)) + 0.5) * 0x1p-31;
  }
  // Further words of this key for the ziggurat's rare rejections: blocks 1, 2, ... in the
  // retry field of the stream word.
  struct Retry {
    const RandomKey& key;
    std::uint32_t block = 0;
    std::array<std::uint32_t, 4> words{};
    int used = 4;
    std::uint32_t next() {
      if (used == 4) {
        ++block;
        auto ctr = key.ctr_;
        ctr[3] ^= (block & 0xFFu) << 24;
        words = philox4x32_10(ctr, key.key_);
        used = 0;
      }
      return words[used++];
    }
  };
  // The ziggurat after the fast test failed for uniform u in layer `layer`: the tail beyond
  // r for the base layer, the wedge test otherwise; a rejection draws a new (u, layer).
  static double ziggurat_slow(double u, int layer, Retry& retry) {
    const ZigguratTables& z = ziggurat_tables();
    for (;;) {
      if (layer == 0) {  // tail: Marsaglia's method
        double x, y;
        do {
          x = std::log(uniform(retry.next())) / ZigguratTables::kR;
          y = std::log(uniform(retry.next()));
        } while (-2.0 * y < x * x);
        return u < 0.0 ? x - ZigguratTables::kR : ZigguratTables::kR - x;
      }
      const double x = u * z.x[layer];
      const double f0 = std::exp(-0.5 * (z.x[layer] * z.x[layer] - x * x));
      const double f1 = std::exp(-0.5 * (z.x[layer + 1] * z.x[layer + 1] - x * x));
      if (f1 + uniform(retry.next()) * (f0 - f1) < 1.0) return x;
      u = signed_uniform(retry.next());
      layer = int(retry.next() & (ZigguratTables::kLayers - 1));
      if (std::abs(u) < z.ratio[layer]) return u * z.x[layer];
    }
  }

  std::array<std::uint32_t, 2> key_;
  std::array<std::uint32_t, 4> ctr_;
};

}  // namespace invasim
