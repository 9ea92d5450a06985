#pragma once
// Seeded random mutations for the fuzz driver (no libFuzzer needed): bit flips, byte
// insertion and deletion, chunk duplication, splices with another corpus input, and integer
// boundary values written over counts, both as little-endian binary (checkpoint section
// tables and payloads) and as decimal text (XML attributes, --set values, Lua numbers).
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace invasim::fuzz {

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}
  // One to eight random mutations of `input`; `corpus` supplies splice partners and
  // dictionary words (tokens of the target's format).
  std::string mutate(std::string input, const std::vector<std::string>& corpus,
                     const std::vector<std::string>& dictionary);
  std::mt19937_64& rng() { return rng_; }

 private:
  std::size_t pick(std::size_t n) { return n ? std::size_t(rng_() % n) : 0; }
  void mutate_once(std::string& s, const std::vector<std::string>& corpus,
                   const std::vector<std::string>& dictionary);
  std::mt19937_64 rng_;
};

}  // namespace invasim::fuzz
