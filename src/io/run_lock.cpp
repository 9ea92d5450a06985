#include "io/run_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <map>
#include <mutex>

#include "io/io_error.hpp"

namespace invasim {

namespace {

// The lock files this process holds, by resolved directory, with their descriptors (kept
// open: closing one would release its lock).
std::map<std::string, int>& held_locks() {
  static std::map<std::string, int> locks;
  return locks;
}

std::mutex& held_locks_mutex() {
  static std::mutex m;
  return m;
}

// "pid 123 on host h, started 2026-01-02T03:04:05Z": what the lock file records.
std::string holder_text() {
  return "pid " + std::to_string(::getpid()) + " on host " + host_name() + ", started " + utc_now();
}

// The holder recorded in an open lock file (its first line), or a note that it recorded none.
std::string read_holder(int fd) {
  char buffer[512];
  const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
  std::string text = n > 0 ? std::string(buffer, std::size_t(n)) : std::string();
  if (const auto end = text.find('\n'); end != std::string::npos) text.resize(end);
  return text.empty() ? "a process that has not recorded itself yet" : text;
}

// The lock file of a run directory: DIR/.lock.
std::filesystem::path run_lock_path(const std::filesystem::path& dir) {
  return dir / ".lock";
}

// The key of a directory in held_locks.
std::string lock_key(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(std::filesystem::absolute(dir), ec).string();
}

}  // namespace

std::optional<std::string> lock_run_directory(const std::filesystem::path& dir) {
  const std::string key = lock_key(dir);
  const std::lock_guard<std::mutex> guard(held_locks_mutex());
  if (held_locks().count(key)) return std::nullopt;
  const std::filesystem::path path = run_lock_path(dir);
  // O_CLOEXEC: a program the protocol starts must not keep the lock alive after the run ends.
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    fail_io("cannot open the run directory's lock file ", quoted(path), ": ", std::strerror(err));
  }
  int rc;
  do rc = ::flock(fd, LOCK_EX | LOCK_NB);
  while (rc != 0 && errno == EINTR);
  if (rc != 0) {
    const int err = errno;
    if (err == EWOULDBLOCK) {
      std::string holder = read_holder(fd);
      ::close(fd);
      return holder;
    }
    ::close(fd);
    fail_io("cannot lock ", quoted(path), ": ", std::strerror(err),
            " (the file system may not support flock)");
  }
  held_locks()[key] = fd;
  return std::nullopt;
}

void record_run_lock_holder(const std::filesystem::path& dir) {
  const std::lock_guard<std::mutex> guard(held_locks_mutex());
  const auto it = held_locks().find(lock_key(dir));
  if (it == held_locks().end())
    fail_io("cannot record the holder of ", quoted(run_lock_path(dir)),
            ": this process does not hold that lock");
  const std::string text = holder_text() + "\n";
  if (::ftruncate(it->second, 0) != 0 ||
      ::pwrite(it->second, text.data(), text.size(), 0) != ssize_t(text.size())) {
    const int err = errno;
    fail_io("cannot write the run directory's lock file ", quoted(run_lock_path(dir)), ": ",
            std::strerror(err));
  }
}

std::string utc_now() {
  char when[32] = "unknown";
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  if (::gmtime_r(&now, &utc)) std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return when;
}

std::string host_name() {
  char host[256] = "unknown";
  if (::gethostname(host, sizeof host - 1) != 0) std::strcpy(host, "unknown");
  host[sizeof host - 1] = '\0';
  return host;
}

}  // namespace invasim
