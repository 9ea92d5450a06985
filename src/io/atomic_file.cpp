#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "io/io_error.hpp"
#include "io/regular_file.hpp"
#include "io/test_hooks.hpp"

namespace invasim {

namespace {

// What write_file_atomically puts between a file's name and its pid: "<name>.tmp.<pid>".
const std::string kTemporaryMark = ".tmp.";

// Closes a file descriptor when it goes out of scope (error paths).
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Closes now and reports close()'s result (write-back errors may surface here).
  int close() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

// Flushes a directory entry change (the rename) to disk. Some file systems refuse fsync on a
// directory (EINVAL); the rename itself has already happened, so that is not an error.
void sync_directory(const std::filesystem::path& dir, const std::filesystem::path& target) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  FileDescriptor guard(fd);
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
    const int error = errno;  // (read before the message's strings allocate)
    fail_io("cannot write ", quoted(target),
            ": fsync of its directory failed: ", std::strerror(error));
  }
}

}  // namespace

bool write_all(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= std::size_t(n);
  }
  return true;
}

std::filesystem::path atomic_temp_path(const std::filesystem::path& path) {
  return std::filesystem::path(path.string() + kTemporaryMark + std::to_string(::getpid()));
}

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  const std::filesystem::path tmp = atomic_temp_path(path);
  // Any failure: remember errno, remove the temporary file, throw.
  auto fail = [&](const char* what) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail_io("cannot write ", quoted(path), ": ", what, ": ", std::strerror(err));
  };
  FileDescriptor fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) {
    const int err = errno;
    fail_io("cannot write ", quoted(path), ": cannot create temporary file ", quoted(tmp), ": ",
            std::strerror(err));
  }
  // Fault injection for the reliability tests (io/test_hooks.hpp): stop halfway through.
  std::string_view rest = contents;
  if (const WriteFault fault = checkpoint_write_fault(path); fault != WriteFault::kNone) {
    const std::string_view half = contents.substr(0, contents.size() / 2);
    if (!write_all(fd.get(), half)) fail("write failed");
    if (fault == WriteFault::kNoSpace) {
      errno = ENOSPC;
      fail("write failed");
    }
    ::fsync(fd.get());
    pause_inside_write(path);
    rest = contents.substr(half.size());
  }
  if (!write_all(fd.get(), rest)) fail("write failed");
  if (::fsync(fd.get()) != 0) fail("fsync failed");
  if (fd.close() != 0) fail("close failed");
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("rename of the temporary file failed");
  sync_directory(path.parent_path(), path);
}

namespace {

// Whether a file name is that of a temporary file of write_file_atomically: "<name>.tmp.<pid>".
bool is_atomic_temporary(const std::string& name) {
  const std::size_t mark = name.rfind(kTemporaryMark);
  const std::size_t digits = mark + kTemporaryMark.size();
  if (mark == std::string::npos || mark == 0 || digits == name.size()) return false;
  for (std::size_t i = digits; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

}  // namespace

std::vector<std::filesystem::path> remove_atomic_temporaries(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (it->is_regular_file(ec) && !it->is_symlink(ec) &&
        is_atomic_temporary(it->path().filename().string()))
      found.push_back(it->path());
  }
  if (ec) fail_io("cannot list ", quoted(dir), ": ", ec.message());
  std::vector<fs::path> removed;
  for (const fs::path& path : found) {
    if (!fs::remove(path, ec) && ec) fail_io("cannot remove ", quoted(path), ": ", ec.message());
    removed.push_back(path.lexically_relative(dir));
  }
  return removed;
}

void append_file_synced(const std::filesystem::path& path, std::string_view contents) {
  FileDescriptor fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644));
  auto fail = [&](const char* what) {
    const int err = errno;
    fail_io("cannot append to ", quoted(path), ": ", what, ": ", std::strerror(err));
  };
  if (fd.get() < 0) fail("open failed");
  if (!write_all(fd.get(), contents)) fail("write failed");
  if (::fsync(fd.get()) != 0) fail("fsync failed");
  if (fd.close() != 0) fail("close failed");
}

void ensure_directory(const std::filesystem::path& dir) {
  if (dir.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) fail_io("cannot create directory ", quoted(dir), ": ", ec.message());
  if (!std::filesystem::is_directory(dir, ec))
    fail_io("cannot create directory ", quoted(dir), ": the path exists and is not a directory");
}

std::string read_file(const std::filesystem::path& path) {
  FileDescriptor fd(open_regular_file(path));
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      fail_io("cannot read ", quoted(path), ": read error: ", std::strerror(err));
    }
    out.append(buffer, std::size_t(n));
  }
  return out;
}

}  // namespace invasim
