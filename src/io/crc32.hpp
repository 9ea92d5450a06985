#pragma once
// CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial value and final xor
// 0xFFFFFFFF) from zlib (Debian's zlib1g-dev), the checksum of zlib, PNG and gzip, so that a
// checkpoint can be checked by independent tools (Python's zlib.crc32). It detects every
// single-bit error and every burst error up to 32 bits.
#include <zlib.h>

#include <cstdint>
#include <string_view>

namespace invasim {

// CRC-32 of `data`, continuing from `crc` (pass the previous result to checksum in pieces).
inline std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0) {
  return std::uint32_t(
      ::crc32_z(crc, reinterpret_cast<const Bytef*>(data.data()), z_size_t(data.size())));
}

}  // namespace invasim
