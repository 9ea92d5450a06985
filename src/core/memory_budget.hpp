#pragma once
// Checks of parameters that size memory: before a histogram's bins, a correlator's
// lags or a placement's sites are allocated, the bytes they need are compared with the memory
// this process may still use, and a request beyond it is an InputError naming the parameter,
// its value, the bytes it needs and the limit (instead of std::bad_alloc after a minute, or
// the kernel's OOM killer).
#include <cstdint>
#include <string>
#include <string_view>

namespace invasim {

// Throws InputError "<owner>: <parameter> = <value> needs about <X> of memory (<per_item>
// bytes each); the limit is <Y> (<source>)" if count * bytes_each exceeds the memory this
// process may still allocate: MemAvailable of /proc/meminfo, lowered to the cgroup's
// memory.max - memory.current when that is set; the environment variable
// INVASIM_MEMORY_LIMIT (bytes) overrides both (tests use it). Falls back to the physical
// memory (sysconf) when /proc is unreadable.
void check_memory(std::string_view owner, std::string_view parameter, double count,
                  double bytes_each);

// "1.5 GiB", "640 KiB", "12 B".
std::string_view format_bytes(double bytes, char (&buffer)[32]);

}  // namespace invasim
