#pragma once
// Atomic file replacement and directory creation for every writer of the output layer.
// A reader (another process, a restarted run) never sees a partially written file: the new
// contents go to a temporary file in the same directory, which is flushed to disk and then
// renamed over the target in one step. A crash or an error leaves either the old file or the
// new one, never a mix, and no temporary file behind when the error is reported.
#include <filesystem>
#include <string_view>
#include <vector>

namespace invasim {

// Replaces `path` by `contents` atomically: writes "<path>.tmp.<pid>", fsyncs it, renames it
// over `path` and fsyncs the directory. On any failure the temporary file is removed and an
// IoError naming the path, the failed operation and strerror(errno) is thrown; the target is
// then unchanged.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Appends `contents` to `path` (created if missing) and fsyncs it. Not atomic: a crash can
// leave a partial last record, which readers of append-only files must tolerate (see
// truncate_xyz_trajectory). Throws IoError naming the path and strerror(errno).
void append_file_synced(const std::filesystem::path& path, std::string_view contents);

// The temporary file name used by write_file_atomically for `path` in this process.
std::filesystem::path atomic_temp_path(const std::filesystem::path& path);

// Removes the temporary files of write_file_atomically ("<name>.tmp.<digits>") that a killed
// process left in `dir` and its subdirectories (symbolic links are not followed), and returns
// their paths relative to `dir`. Only for a directory no other process writes (a run
// directory whose lock this process holds: io/run_lock.hpp). Throws IoError naming a file
// that cannot be removed.
std::vector<std::filesystem::path> remove_atomic_temporaries(const std::filesystem::path& dir);

// Creates `dir` and its missing parents (no-op if it exists). Throws IoError naming the
// directory if it cannot be created or if the path exists and is not a directory.
void ensure_directory(const std::filesystem::path& dir);

// Writes all of `bytes` to the open file `fd`, retrying short writes and EINTR; returns false
// with errno set on an error.
bool write_all(int fd, std::string_view bytes);

// Reads a whole file into a string. Throws IoError naming the file if it cannot be read or is
// not a regular file (a FIFO, directory or device: io/regular_file.hpp), without blocking.
std::string read_file(const std::filesystem::path& path);

}  // namespace invasim
