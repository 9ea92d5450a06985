#pragma once
// The checkpoint container (docs/output_formats.md, "Checkpoint"): a versioned, checksummed
// binary file of named, typed sections, written atomically. Layout, all integers
// little-endian:
//   "INVASIMCKPT" (11 bytes) | u32 format version | u64 file length | u32 section count
//   sections: u32 name length | name (UTF-8) | u8 type | u64 payload length | payload
//   u32 CRC-32 of every preceding byte
// Doubles are stored as their IEEE-754 bits, so a round trip is bit-for-bit. The reader
// refuses a file with a wrong magic, another format version, a length that does not match
// (truncated or extended) or a checksum mismatch, each with a message naming the file.
// What goes into the sections (System, forces, integrator, observers) is up to the callers:
// see checkpoint/state_checkpoint.hpp for the System and force sections.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec3.hpp"
#include "io/io_error.hpp"

namespace invasim {

inline constexpr std::string_view kCheckpointMagic = "INVASIMCKPT";
// Version 2: checkpoints of a protocol run carry the run's identity (sections "run.id" and
// "run.parameters"); version 1 files, which cannot be told apart from another run's, are
// refused. Version 3: each object writes its own named sections (checkpoint/*_sections.hpp:
// "dynamics.method1.gamma", ... instead of positional arrays); version 2 files are refused
// with the version needed to read them.
inline constexpr std::uint32_t kCheckpointVersion = 3;
// Bytes before the first section: magic, version, file length, section count.
inline constexpr std::size_t kCheckpointHeaderSize = 11 + 4 + 8 + 4;

// What a section's payload holds; the reader checks it against the getter used.
enum class SectionType : std::uint8_t {
  kBytes = 0,
  kF64 = 1,
  kU64 = 2,
  kI64 = 3,
  kString = 4,
  kF64Array = 5,
  kI32Array = 6,
  kU64Array = 7,
  kVec3Array = 8,   // x y z doubles per element
  kVec3iArray = 9,  // x y z int32 per element
};

// Collects sections in memory, then serialises them in insertion order.
class CheckpointWriter {
 public:
  void put_bytes(const std::string& name, std::string_view bytes);
  void put_string(const std::string& name, std::string_view value);
  void put_f64(const std::string& name, double value);
  void put_u64(const std::string& name, std::uint64_t value);
  void put_i64(const std::string& name, std::int64_t value);
  void put_f64s(const std::string& name, const std::vector<double>& values);
  void put_i32s(const std::string& name, const std::vector<int>& values);
  void put_u64s(const std::string& name, const std::vector<std::uint64_t>& values);
  void put_vec3s(const std::string& name, const std::vector<Vec3>& values);
  void put_vec3is(const std::string& name, const std::vector<Vec3i>& values);

  bool has(const std::string& name) const;
  std::size_t n_sections() const { return sections_.size(); }
  // The complete file contents.
  std::string bytes() const;
  // Writes the file atomically (write_file_atomically).
  void write(const std::filesystem::path& path) const;

 private:
  struct Section {
    std::string name;
    SectionType type;
    std::string payload;
  };
  // Adds a section; a name used twice is a programming error (InputError).
  void add(const std::string& name, SectionType type, std::string payload);
  std::vector<Section> sections_;
};

// A validated checkpoint held in memory; sections are read by name and type.
class CheckpointReader {
 public:
  // Reads and validates a file (IoError naming it and the problem if it is not valid).
  static CheckpointReader read(const std::filesystem::path& path);
  // Validates bytes; `origin` names their source in messages (e.g. a quoted path).
  static CheckpointReader parse(std::string bytes, std::string origin);

  std::uint32_t version() const { return version_; }
  bool has(const std::string& name) const { return index_.count(name) != 0; }
  // Section names in file order.
  const std::vector<std::string>& names() const { return names_; }
  SectionType type(const std::string& name) const;

  // Getters: a missing section or a section of another type is an IoError naming both.
  std::string get_bytes(const std::string& name) const;
  std::string get_string(const std::string& name) const;
  double get_f64(const std::string& name) const;
  std::uint64_t get_u64(const std::string& name) const;
  std::int64_t get_i64(const std::string& name) const;
  std::vector<double> get_f64s(const std::string& name) const;
  std::vector<int> get_i32s(const std::string& name) const;
  std::vector<std::uint64_t> get_u64s(const std::string& name) const;
  std::vector<Vec3> get_vec3s(const std::string& name) const;
  std::vector<Vec3i> get_vec3is(const std::string& name) const;

  // Throws IoError "checkpoint <origin>: <parts>" (for callers that find inconsistent data).
  template <typename... Parts>
  [[noreturn]] void fail(const Parts&... parts) const {
    fail_io("checkpoint ", origin_, ": ", parts...);
  }

 private:
  struct Section {
    SectionType type;
    std::size_t offset, length;  // payload position in data_
  };
  CheckpointReader() = default;
  // The payload of a section of the expected type, checked to hold whole elements.
  std::string_view payload(const std::string& name, SectionType type,
                           std::size_t element_size) const;

  std::string data_;
  std::string origin_;
  std::uint32_t version_ = 0;
  std::map<std::string, Section> index_;
  std::vector<std::string> names_;
};

}  // namespace invasim
