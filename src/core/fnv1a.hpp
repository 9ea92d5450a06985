#pragma once
// FNV-1a, 64-bit (Fowler-Noll-Vo; offset basis 0xcbf29ce484222325, prime 0x100000001b3): a
// small, portable, deterministic hash of a byte string. Used for a run's identity (the hash
// of its protocol, resolved parameters and --from source: protocols/lib/run_identity.lua),
// which every checkpoint of the run carries. Not a cryptographic hash.
#include <cstdint>
#include <string>
#include <string_view>

namespace invasim {

constexpr std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    hash ^= std::uint64_t(static_cast<unsigned char>(c));
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

// The hash as 16 lowercase hexadecimal digits.
inline std::string fnv1a64_hex(std::string_view bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::uint64_t hash = fnv1a64(bytes);
  std::string text(16, '0');
  for (int i = 15; i >= 0; --i, hash >>= 4) text[std::size_t(i)] = kDigits[hash & 0xf];
  return text;
}

}  // namespace invasim
