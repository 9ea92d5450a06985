#pragma once
// Error type of the output layer. A file that cannot be written (disk full, missing or
// unwritable directory) or read back (missing, truncated, corrupt, wrong format) is reported
// as an IoError whose message names the file and the problem. It derives from InputError so
// that every handler of user-facing errors (Lua layer, command line) reports it the same way,
// while callers that care can still tell file problems apart.
#include <filesystem>
#include <string>

#include "core/errors.hpp"

namespace invasim {

class IoError : public InputError {
 public:
  using InputError::InputError;
};

// Builds a message from streamable parts and throws it as an IoError.
template <typename... Parts>
[[noreturn]] void fail_io(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  throw IoError(out.str());
}

// A path quoted for messages: 'dir/file.xyz'.
inline std::string quoted(const std::filesystem::path& path) {
  std::string out(1, '\'');
  out += path.string();
  out += '\'';
  return out;
}

}  // namespace invasim
