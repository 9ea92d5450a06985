#pragma once
// The one check every reader of a user-named file runs before it reads (protocols, configs,
// sweep specs, checkpoints, snapshots, JSON): the path must be a regular file. A FIFO would
// block the reader until some writer appears, a directory or a device would be read as
// garbage or forever (/dev/zero), so they are refused with a message that says what the path
// is, instead of hanging.
#include <filesystem>
#include <string>
#include <string_view>

namespace invasim {

// Throws IoError "cannot read <what> '<path>': it is a FIFO (named pipe), not a regular file
// ..." (or strerror(errno) if it cannot be stat'ed) unless `path` (symlinks followed) is a
// regular file. `what` ("protocol", "checkpoint", ...) may be empty. Never opens the path, so
// it cannot block.
void require_regular_file(const std::filesystem::path& path, std::string_view what = "");

// Opens `path` for reading without blocking (O_NONBLOCK, so a FIFO does not wait for a
// writer), checks with fstat that the opened file is regular (so a path swapped after a
// require_regular_file cannot slip through), then clears O_NONBLOCK. Returns the file
// descriptor (the caller closes it); throws IoError as require_regular_file.
int open_regular_file(const std::filesystem::path& path, std::string_view what = "");

}  // namespace invasim
