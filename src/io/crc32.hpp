#pragma once
// CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial value and final xor
// 0xFFFFFFFF), the checksum of zlib, PNG and gzip, so a checkpoint can be checked by
// independent tools (Python's zlib.crc32). It detects every single-bit and every burst error
// up to 32 bits. Written from the published definition (table-driven, one byte at a time).
#include <cstdint>
#include <string_view>

namespace invasim {

// CRC-32 of `data`, continuing from `crc` (pass the previous result to checksum in pieces).
std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0);

}  // namespace invasim
