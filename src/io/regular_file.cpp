#include "io/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/io_error.hpp"

namespace invasim {

namespace {

// What kind of non-regular file `mode` (st_mode) describes: "a directory", "a FIFO (named
// pipe)", "a character device", ...; "" for a regular file.
std::string non_regular_kind(unsigned mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse(const std::filesystem::path& path, std::string_view what,
                         const std::string& kind) {
  fail_io("cannot read ", what, what.empty() ? "" : " ", quoted(path), ": it is ", kind,
          ", not a regular file (invasim reads only regular files)");
}

[[noreturn]] void fail_errno(const std::filesystem::path& path, std::string_view what, int err) {
  fail_io("cannot read ", what, what.empty() ? "" : " ", quoted(path), ": ", std::strerror(err));
}

}  // namespace

void require_regular_file(const std::filesystem::path& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail_errno(path, what, errno);
  if (const std::string kind = non_regular_kind(st.st_mode); !kind.empty())
    refuse(path, what, kind);
}

int open_regular_file(const std::filesystem::path& path, std::string_view what) {
  require_regular_file(path, what);  // before open: never opens a device
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) fail_errno(path, what, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    fail_errno(path, what, err);
  }
  if (const std::string kind = non_regular_kind(st.st_mode); !kind.empty()) {
    ::close(fd);
    refuse(path, what, kind);
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

}  // namespace invasim
