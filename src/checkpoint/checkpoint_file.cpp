#include "checkpoint/checkpoint_file.hpp"

#include <bit>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/crc32.hpp"

namespace invasim {

namespace {

// Little-endian encoding of unsigned integers of 1..8 bytes.
void put_uint(std::string& out, std::uint64_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out += char((v >> (8 * k)) & 0xFFu);
}
std::uint64_t get_uint(std::string_view s, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int k = 0; k < bytes; ++k)
    v |= std::uint64_t(static_cast<unsigned char>(s[at + k])) << (8 * k);
  return v;
}
void put_f64_bits(std::string& out, double v) {
  put_uint(out, std::bit_cast<std::uint64_t>(v), 8);
}
double get_f64_bits(std::string_view s, std::size_t at) {
  return std::bit_cast<double>(get_uint(s, at, 8));
}

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", v);
  return buf;
}

constexpr std::uint8_t kLastType = std::uint8_t(SectionType::kVec3iArray);

const char* section_type_name(SectionType type) {
  static constexpr const char* kNames[] = {"bytes",      "f64",        "u64",       "i64",
                                           "string",     "f64 array",  "i32 array", "u64 array",
                                           "vec3 array", "vec3i array"};
  const auto k = static_cast<std::uint8_t>(type);
  return k <= kLastType ? kNames[k] : "unknown";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Writer

void CheckpointWriter::add(const std::string& name, SectionType type, std::string payload) {
  if (name.empty()) fail_input("checkpoint: a section needs a name");
  if (has(name)) fail_input("checkpoint: section '", name, "' is written twice");
  sections_.push_back({name, type, std::move(payload)});
}

bool CheckpointWriter::has(const std::string& name) const {
  for (const Section& s : sections_)
    if (s.name == name) return true;
  return false;
}

void CheckpointWriter::put_bytes(const std::string& name, std::string_view bytes) {
  add(name, SectionType::kBytes, std::string(bytes));
}
void CheckpointWriter::put_string(const std::string& name, std::string_view value) {
  add(name, SectionType::kString, std::string(value));
}
void CheckpointWriter::put_f64(const std::string& name, double value) {
  std::string p;
  put_f64_bits(p, value);
  add(name, SectionType::kF64, std::move(p));
}
void CheckpointWriter::put_u64(const std::string& name, std::uint64_t value) {
  std::string p;
  put_uint(p, value, 8);
  add(name, SectionType::kU64, std::move(p));
}
void CheckpointWriter::put_i64(const std::string& name, std::int64_t value) {
  std::string p;
  put_uint(p, std::uint64_t(value), 8);
  add(name, SectionType::kI64, std::move(p));
}
void CheckpointWriter::put_f64s(const std::string& name, const std::vector<double>& values) {
  std::string p;
  p.reserve(8 * values.size());
  for (double v : values) put_f64_bits(p, v);
  add(name, SectionType::kF64Array, std::move(p));
}
void CheckpointWriter::put_i32s(const std::string& name, const std::vector<int>& values) {
  std::string p;
  p.reserve(4 * values.size());
  for (int v : values) put_uint(p, std::uint32_t(v), 4);
  add(name, SectionType::kI32Array, std::move(p));
}
void CheckpointWriter::put_u64s(const std::string& name, const std::vector<std::uint64_t>& values) {
  std::string p;
  p.reserve(8 * values.size());
  for (std::uint64_t v : values) put_uint(p, v, 8);
  add(name, SectionType::kU64Array, std::move(p));
}
void CheckpointWriter::put_vec3s(const std::string& name, const std::vector<Vec3>& values) {
  std::string p;
  p.reserve(24 * values.size());
  for (const Vec3& v : values)
    for (int a = 0; a < 3; ++a) put_f64_bits(p, v[a]);
  add(name, SectionType::kVec3Array, std::move(p));
}
void CheckpointWriter::put_vec3is(const std::string& name, const std::vector<Vec3i>& values) {
  std::string p;
  p.reserve(12 * values.size());
  for (const Vec3i& v : values)
    for (int a = 0; a < 3; ++a) put_uint(p, std::uint32_t(v[a]), 4);
  add(name, SectionType::kVec3iArray, std::move(p));
}

std::string CheckpointWriter::bytes() const {
  std::size_t total = kCheckpointHeaderSize + 4;
  for (const Section& s : sections_) total += 4 + s.name.size() + 1 + 8 + s.payload.size();
  std::string out;
  out.reserve(total);
  out += kCheckpointMagic;
  put_uint(out, kCheckpointVersion, 4);
  put_uint(out, total, 8);
  put_uint(out, sections_.size(), 4);
  for (const Section& s : sections_) {
    put_uint(out, s.name.size(), 4);
    out += s.name;
    put_uint(out, std::uint8_t(s.type), 1);
    put_uint(out, s.payload.size(), 8);
    out += s.payload;
  }
  put_uint(out, crc32(out), 4);
  return out;
}

void CheckpointWriter::write(const std::filesystem::path& path) const {
  write_file_atomically(path, bytes());
}

// ---------------------------------------------------------------------------------------------
// Reader

CheckpointReader CheckpointReader::read(const std::filesystem::path& path) {
  return parse(read_file(path), quoted(path));
}

CheckpointReader CheckpointReader::parse(std::string bytes, std::string origin) {
  CheckpointReader r;
  r.data_ = std::move(bytes);
  r.origin_ = std::move(origin);
  const std::string_view d = r.data_;
  const std::size_t size = d.size();
  if (size == 0) r.fail("the file is empty");
  const std::size_t magic_len = std::min(size, kCheckpointMagic.size());
  if (d.substr(0, magic_len) != kCheckpointMagic.substr(0, magic_len))
    r.fail("not an invasim checkpoint (wrong magic: it does not start with \"", kCheckpointMagic,
           "\")");
  if (size < kCheckpointHeaderSize)
    r.fail("truncated: ", size, " bytes, shorter than the ", kCheckpointHeaderSize, "-byte header");
  r.version_ = std::uint32_t(get_uint(d, 11, 4));
  if (r.version_ == 2)
    r.fail("format version 2 is not supported (this build reads version ", kCheckpointVersion,
           "; version 2 stored the Dynamics as positional arrays: continue it with an invasim "
           "that reads version 2, or start that run again)");
  if (r.version_ < kCheckpointVersion)
    r.fail("format version ", r.version_, " is not supported (this build reads version ",
           kCheckpointVersion,
           "; older checkpoints do not record the run that wrote them, so they cannot be "
           "continued: start that run again)");
  if (r.version_ != kCheckpointVersion)
    r.fail("format version ", r.version_, " is not supported (this build reads version ",
           kCheckpointVersion, ")");
  const std::uint64_t total = get_uint(d, 15, 8);
  if (total < kCheckpointHeaderSize + 4) r.fail("corrupt header (file length field ", total, ")");
  if (size < total) r.fail("truncated: ", size, " of ", total, " bytes");
  if (size > total) r.fail("corrupt: ", size, " bytes where the header says ", total);
  const std::uint32_t stored = std::uint32_t(get_uint(d, total - 4, 4));
  const std::uint32_t computed = crc32(d.substr(0, total - 4));
  if (stored != computed)
    r.fail("checksum mismatch (stored ", hex32(stored), ", computed ", hex32(computed),
           "): the file is corrupt");

  // The checksum holds, so a malformed section table means a writer bug: still bounds-checked.
  const std::size_t end = total - 4;
  const std::uint64_t count = get_uint(d, 23, 4);
  std::size_t at = kCheckpointHeaderSize;
  auto need = [&](std::uint64_t n, std::uint64_t k) {
    if (n > end - at) r.fail("corrupt section table at section ", k);
  };
  for (std::uint64_t k = 0; k < count; ++k) {
    need(4, k);
    const std::uint64_t name_len = get_uint(d, at, 4);
    at += 4;
    need(name_len + 1 + 8, k);
    std::string name(d.substr(at, name_len));
    at += name_len;
    const std::uint8_t type = std::uint8_t(get_uint(d, at, 1));
    at += 1;
    const std::uint64_t len = get_uint(d, at, 8);
    at += 8;
    need(len, k);
    if (type > kLastType) r.fail("section '", name, "' has unknown type ", int(type));
    if (r.index_.count(name)) r.fail("section '", name, "' appears twice");
    r.index_[name] = Section{SectionType(type), at, std::size_t(len)};
    r.names_.push_back(std::move(name));
    at += len;
  }
  if (at != end) r.fail("corrupt section table (", end - at, " unread bytes)");
  return r;
}

SectionType CheckpointReader::type(const std::string& name) const {
  const auto it = index_.find(name);
  if (it == index_.end()) fail("no section '", name, "'");
  return it->second.type;
}

std::string_view CheckpointReader::payload(const std::string& name, SectionType type,
                                           std::size_t element_size) const {
  const auto it = index_.find(name);
  if (it == index_.end()) fail("no section '", name, "'");
  const Section& s = it->second;
  if (s.type != type)
    fail("section '", name, "' holds ", section_type_name(s.type), ", not ",
         section_type_name(type));
  if (s.length % element_size != 0)
    fail("section '", name, "' has ", s.length, " bytes, not a whole number of elements");
  return std::string_view(data_).substr(s.offset, s.length);
}

std::string CheckpointReader::get_bytes(const std::string& name) const {
  return std::string(payload(name, SectionType::kBytes, 1));
}
std::string CheckpointReader::get_string(const std::string& name) const {
  return std::string(payload(name, SectionType::kString, 1));
}
double CheckpointReader::get_f64(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kF64, 8);
  if (p.size() != 8) fail("section '", name, "' does not hold one f64");
  return get_f64_bits(p, 0);
}
std::uint64_t CheckpointReader::get_u64(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kU64, 8);
  if (p.size() != 8) fail("section '", name, "' does not hold one u64");
  return get_uint(p, 0, 8);
}
std::int64_t CheckpointReader::get_i64(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kI64, 8);
  if (p.size() != 8) fail("section '", name, "' does not hold one i64");
  return std::int64_t(get_uint(p, 0, 8));
}
std::vector<double> CheckpointReader::get_f64s(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kF64Array, 8);
  std::vector<double> out(p.size() / 8);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = get_f64_bits(p, 8 * i);
  return out;
}
std::vector<int> CheckpointReader::get_i32s(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kI32Array, 4);
  std::vector<int> out(p.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = std::int32_t(std::uint32_t(get_uint(p, 4 * i, 4)));
  return out;
}
std::vector<std::uint64_t> CheckpointReader::get_u64s(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kU64Array, 8);
  std::vector<std::uint64_t> out(p.size() / 8);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = get_uint(p, 8 * i, 8);
  return out;
}
std::vector<Vec3> CheckpointReader::get_vec3s(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kVec3Array, 24);
  std::vector<Vec3> out(p.size() / 24);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int a = 0; a < 3; ++a) out[i][a] = get_f64_bits(p, 24 * i + 8 * a);
  return out;
}
std::vector<Vec3i> CheckpointReader::get_vec3is(const std::string& name) const {
  const std::string_view p = payload(name, SectionType::kVec3iArray, 12);
  std::vector<Vec3i> out(p.size() / 12);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int a = 0; a < 3; ++a)
      out[i][a] = std::int32_t(std::uint32_t(get_uint(p, 12 * i + 4 * a, 4)));
  return out;
}

}  // namespace invasim
