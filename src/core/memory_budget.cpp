#include "core/memory_budget.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace invasim {

namespace {

// The first number in `path` (cgroup files), or 0 if absent or "max".
std::uint64_t read_number(const char* path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return 0;
  return std::strtoull(text.c_str(), nullptr, 10);
}

// MemAvailable of /proc/meminfo in bytes, or 0.
std::uint64_t mem_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

// An integral value in full ("2147483647"), else as printed by std::to_string.
std::string number_text(double x) {
  return x == std::floor(x) && std::abs(x) < 9e18 ? std::to_string(static_cast<long long>(x))
                                                  : std::to_string(x);
}

// The limit and where it came from.
std::uint64_t limit_and_source(const char*& source) {
  if (const char* env = std::getenv("INVASIM_MEMORY_LIMIT"); env && *env) {
    source = "INVASIM_MEMORY_LIMIT";
    char* end = nullptr;
    errno = 0;
    const unsigned long long bytes = std::strtoull(env, &end, 10);
    if (*env == '-' || end == env || *end != '\0' || errno == ERANGE)
      fail_input("INVASIM_MEMORY_LIMIT = '", env, "' is not a number of bytes");
    return bytes;
  }
  std::uint64_t limit = mem_available();
  source = "the memory available now, MemAvailable in /proc/meminfo";
  if (limit == 0) {
    limit = std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
    source = "the physical memory";
  }
  const std::uint64_t cgroup_max = read_number("/sys/fs/cgroup/memory.max");
  if (cgroup_max > 0) {
    const std::uint64_t used = read_number("/sys/fs/cgroup/memory.current");
    const std::uint64_t left = cgroup_max > used ? cgroup_max - used : 0;
    if (left < limit) {
      limit = left;
      source = "the cgroup's memory.max less memory.current";
    }
  }
  return limit;
}

}  // namespace

std::string_view format_bytes(double bytes, char (&buffer)[32]) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int u = 0;
  while (bytes >= 1024.0 && u < 6) {
    bytes /= 1024.0;
    ++u;
  }
  std::snprintf(buffer, sizeof buffer, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return buffer;
}

void check_memory(std::string_view owner, std::string_view parameter, double count,
                  double bytes_each) {
  const char* source = nullptr;
  const double limit = double(limit_and_source(source));
  const double need = count * bytes_each;
  if (need <= limit) return;
  char need_text[32], limit_text[32];
  fail_input(owner, ": ", parameter, " = ", number_text(count), " needs about ",
             format_bytes(need, need_text), " of memory (", number_text(bytes_each),
             " bytes each); the limit is ", format_bytes(limit, limit_text), " (", source, ")");
}

}  // namespace invasim
