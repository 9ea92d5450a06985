// No C++ memory is lost when Lua runs out of memory inside a binding. Lua
// (Debian's, built as C) raises errors with longjmp, which skips the destructors of C++
// objects in the frames it leaves; the bindings therefore make every allocating Lua call in a
// protected block (binding.hpp). These tests run scripts under a Lua memory limit placed at
// many points of a big-table binding (histogram, positions, correlator results, ...), so that
// the allocation fails midway, and count the C++ heap blocks (this executable replaces the
// global operator new/delete) before the LuaState is created and after it is closed: any
// block left over is a leak.
#include <lua.hpp>

#include <atomic>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <new>
#include <string>

#include "lua/lua_state.hpp"

namespace {
std::atomic<long> live_blocks{0};  // C++ heap blocks allocated and not yet freed
}  // namespace

// Global allocation functions of this test executable: malloc/free plus a count.
void* operator new(std::size_t size) {
  void* p = std::malloc(size ? size : 1);
  if (!p) throw std::bad_alloc();
  ++live_blocks;
  return p;
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  void* p = std::malloc(size ? size : 1);
  if (p) ++live_blocks;
  return p;
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* p) noexcept {
  if (!p) return;
  --live_blocks;
  std::free(p);
}
void operator delete[](void* p) noexcept {
  operator delete(p);
}
void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  operator delete(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  operator delete(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  operator delete(p);
}

using invasim::lua::LuaState;
using invasim::lua::ScriptError;

namespace {

// One run: `prelude` without a limit, then `call` with the Lua memory capped at what the
// prelude left plus `extra` bytes (no cap when extra < 0).
struct Run {
  bool failed = false;         // `call` raised an error
  bool out_of_memory = false;  // ... "not enough memory"
  bool located = false;        // ... with the script location "mem.lua:N:"
  long leaked_blocks = 0;      // C++ heap blocks alive after the state closed, minus before
};

Run run_limited(const char* prelude, const char* call, long extra) {
  Run r;
  const long before = live_blocks.load();
  {
    LuaState state;
    state.run_string(prelude, "@prelude.lua");
    if (extra >= 0) state.set_memory_limit(state.memory_used() + std::size_t(extra));
    try {
      state.run_string(call, "@mem.lua");
    } catch (const ScriptError& e) {
      const std::string message = e.what();
      r.failed = true;
      r.out_of_memory = message.find("not enough memory") != std::string::npos;
      r.located = message.rfind("mem.lua:", 0) == 0;
    }
  }
  r.leaked_blocks = live_blocks.load() - before;
  return r;
}

// Runs `call` under limits of extra = 0, step, 2 step, ... until it completes; checks that no
// run leaked, that the limits made it fail with a memory error midway at least `min_failures`
// times (with `located`: some of them with the script location, i.e. raised by a binding and
// reported by lua_wrap; when memory is very short even that message cannot be built), and
// returns the number of failed runs.
int scan_limits(const char* prelude, const char* call, long step, int min_failures,
                bool located_too) {
  run_limited(prelude, call, -1);  // warm-up: lazily built static data, thread pools
  run_limited(prelude, call, 0);
  const Run full = run_limited(prelude, call, -1);
  INFO("without a limit: " << (full.failed ? "failed" : "ok") << ", leaked " << full.leaked_blocks);
  REQUIRE_FALSE(full.failed);
  REQUIRE(full.leaked_blocks == 0);
  int failures = 0, located = 0;
  long extra = 0;
  for (int k = 0; k < 400; ++k, extra += step) {
    const Run r = run_limited(prelude, call, extra);
    INFO("limit: memory after the prelude + " << extra << " bytes");
    CHECK(r.leaked_blocks == 0);
    if (!r.failed) break;
    CHECK(r.out_of_memory);
    ++failures;
    located += r.located;
  }
  CHECK(failures >= min_failures);
  if (located_too) CHECK(located > 0);  // a failure inside a binding names the script line
  return failures;
}

}  // namespace

TEST_CASE("Lua out of memory inside histogram leaks no C++ memory", "[lua][memory]") {
  const char* prelude =
      "iv = require('invasim'); values = {}; "
      "for i = 1, 20000 do values[i] = (i * 7919) % 1000 / 10 end";
  const char* call =
      "local h = iv.histogram(values, {lo = 0, hi = 100, bins = 20000})\n"
      "assert(#h.edges == 20001 and #h.counts == 20000)";
  scan_limits(prelude, call, 40000, 10, true);
}

TEST_CASE("Lua out of memory in System queries and placement leaks no C++ memory",
          "[lua][memory]") {
  const char* prelude =
      "iv = require('invasim'); sys = iv.System{box = {40, 40, 40}, seed = 3}; "
      "placed = sys:place{cells = {n = 500, x = {1, 39}}, adipocytes = {n = 2, diameter = 6, "
      "vertex_diameter = 2, subdivisions = 1, volume_grid = 0.5, x = {10, 30}}}";
  const char* call =
      "local p = sys:positions(); local a = sys:adipocytes(); local b = sys:box()\n"
      "local g = sys:group('cancer'); local s = g:sites(); local v = sys:shape_parameters()\n"
      "local q = sys:place{cells = {n = 20, x = {1, 39}}}\n"
      "assert(#p > 500 and #a == 2 and #s == 500 and q.cells:size() == 20)";
  scan_limits(prelude, call, 4000, 10, false);
}

TEST_CASE("Lua out of memory in constructors, keyword tables and results leaks no C++ memory",
          "[lua][memory]") {
  const char* prelude =
      "iv = require('invasim'); sys = iv.System{box = {20, 20, 20}, seed = 3}; "
      "cells = sys:place{cells = {n = 100, x = {1, 19}}}.cells";
  const char* call =
      "local p = iv.params{a = 1, b = {2.5, help = 'x'}, name = 'abc'}\n"
      "local c = iv.Correlator{group = cells, interval = 0.05, lags = 1000}\n"
      "local r = c:result()\n"
      "local t = {}; for i = 1, 30 do t[i] = iv.System{box = {10, 10, 10}, seed = i} end\n"
      "local x = {}; for i = 1, 5000 do x[i] = i % 17 end\n"
      "local b = iv.mean_error(x, {fraction = 1})\n"
      "local s = tostring(t[1]) .. tostring(c)\n"
      "assert(#r.names > 0 and b.n == 5000)";
  scan_limits(prelude, call, 3000, 10, false);
}
