#include "mutate.hpp"

#include <algorithm>
#include <limits>

namespace invasim::fuzz {

namespace {

// Boundary values of the integer types counts are stored in.
const std::uint64_t kBoundary[] = {0,
                                   1,
                                   2,
                                   3,
                                   0x7F,
                                   0xFF,
                                   0x7FFF,
                                   0xFFFF,
                                   0x7FFFFFFF,
                                   0x80000000,
                                   0xFFFFFFFF,
                                   0x100000000,
                                   0x7FFFFFFFFFFFFFFF,
                                   0x8000000000000000,
                                   0xFFFFFFFFFFFFFFFF,
                                   0xFFFFFFFFFFFFFFFE};

const char* const kBoundaryText[] = {"0",
                                     "-1",
                                     "1",
                                     "2147483647",
                                     "2147483648",
                                     "-2147483649",
                                     "4294967296",
                                     "9223372036854775807",
                                     "-9223372036854775808",
                                     "9223372036854775808",
                                     "18446744073709551616",
                                     "1e308",
                                     "1e309",
                                     "-1e308",
                                     "4.9e-324",
                                     "nan",
                                     "inf",
                                     "-inf",
                                     "0x7fffffffffffffff",
                                     "1e18",
                                     "1e-300"};

}  // namespace

std::string Mutator::mutate(std::string input, const std::vector<std::string>& corpus,
                            const std::vector<std::string>& dictionary) {
  const int n = 1 + int(pick(8));
  for (int k = 0; k < n; ++k) mutate_once(input, corpus, dictionary);
  if (input.size() > (1u << 22)) input.resize(1u << 22);  // keep inputs small
  return input;
}

void Mutator::mutate_once(std::string& s, const std::vector<std::string>& corpus,
                          const std::vector<std::string>& dictionary) {
  switch (pick(10)) {
    case 0:  // bit flip
      if (!s.empty()) s[pick(s.size())] ^= char(1u << pick(8));
      return;
    case 1:  // random byte
      if (!s.empty()) s[pick(s.size())] = char(rng_());
      return;
    case 2:  // insert bytes
      s.insert(pick(s.size() + 1), std::string(1 + pick(4), char(rng_())));
      return;
    case 3: {  // delete a range
      if (s.empty()) return;
      const std::size_t at = pick(s.size());
      s.erase(at, 1 + pick(std::min<std::size_t>(s.size() - at, 64)));
      return;
    }
    case 4: {  // duplicate a chunk (deeper nesting, repeated entries)
      if (s.empty()) return;
      const std::size_t at = pick(s.size());
      const std::size_t len = 1 + pick(std::min<std::size_t>(s.size() - at, 256));
      const std::string chunk = s.substr(at, len);
      std::string rep;
      for (std::size_t r = 1 + pick(std::size_t(1) << pick(12)); r > 0; --r) rep += chunk;
      s.insert(at, rep);
      return;
    }
    case 5: {  // splice: a prefix of s with a suffix of another input
      if (corpus.empty()) return;
      const std::string& other = corpus[pick(corpus.size())];
      s = s.substr(0, pick(s.size() + 1)) + other.substr(pick(other.size() + 1));
      return;
    }
    case 6: {  // binary boundary value, 1, 2, 4 or 8 bytes little-endian
      const int bytes = 1 << pick(4);
      if (s.size() < std::size_t(bytes)) return;
      std::uint64_t v = kBoundary[pick(std::size(kBoundary))];
      if (pick(4) == 0) v = std::uint64_t(s.size() - pick(64));  // near the file's size
      const std::size_t at = pick(s.size() - bytes + 1) & ~std::size_t(pick(2) ? 3 : 0);
      for (int k = 0; k < bytes && at + k < s.size(); ++k) s[at + k] = char((v >> (8 * k)) & 0xFF);
      return;
    }
    case 7: {  // replace a decimal number by a boundary value
      if (s.empty()) return;
      std::size_t at = pick(s.size());
      while (at < s.size() && !(s[at] >= '0' && s[at] <= '9')) ++at;
      if (at == s.size()) return;
      std::size_t end = at;
      while (end < s.size() && ((s[end] >= '0' && s[end] <= '9') || s[end] == '.' ||
                                s[end] == 'e' || s[end] == '-' || s[end] == '+'))
        ++end;
      s.replace(at, end - at, kBoundaryText[pick(std::size(kBoundaryText))]);
      return;
    }
    case 8:  // a dictionary word
      if (!dictionary.empty()) s.insert(pick(s.size() + 1), dictionary[pick(dictionary.size())]);
      return;
    default: {  // copy a chunk over another place
      if (s.size() < 2) return;
      const std::size_t from = pick(s.size()), to = pick(s.size());
      const std::size_t len = std::min({1 + pick(64), s.size() - from, s.size() - to});
      s.replace(to, len, s.substr(from, len));
      return;
    }
  }
}

}  // namespace invasim::fuzz
