// invasim.Progress{total = N, every_seconds = 10, label = "...", live = bool, start = 0}
// with :update(step [, time]) and :finish(). Reports to stderr (live line on a terminal).
#include <unistd.h>
#include <lua.hpp>

#include <cstdio>
#include <iostream>
#include <limits>

#include "lua/binding.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"
#include "lua/progress.hpp"

namespace invasim::lua {

template <>
struct LuaType<Progress> {
  static constexpr const char* name = "Progress";
  static constexpr const char* metatable = "invasim.Progress";
  static std::string describe(const Progress& p) {
    return cat("Progress(step ", p.step(), p.total() > 0 ? cat("/", p.total()) : "",
               p.finished() ? ", finished)" : ")");
  }
};

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Progress");
  ProgressOptions options;
  options.total = kw.integer<long long>("total", 0, Range::non_negative());
  options.start_step = kw.integer<long long>("start", 0, Range::non_negative());
  options.every_seconds = kw.number("every_seconds", 10.0, Range::non_negative());
  options.label = kw.string("label", "");
  const bool live = kw.boolean("live", isatty(STDERR_FILENO) != 0);
  kw.finish();
  push(L, std::make_shared<Progress>(options, std::cerr, live));
  return 1;
}

int l_update(lua_State* L) {
  Progress& progress = check<Progress>(L, 1);
  const long long step = arg_integer(L, 2, 0, std::numeric_limits<long long>::max());
  progress.update(step, opt_number(L, 3));
  return 0;
}

int l_finish(lua_State* L) {
  check<Progress>(L, 1).finish();
  return 0;
}

const luaL_Reg kMethods[] = {
    {"update", &lua_wrap<&l_update>},
    {"finish", &lua_wrap<&l_finish>},
    {nullptr, nullptr},
};

}  // namespace

void open_progress(lua_State* L) {
  define_type<Progress>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_new>);
  lua_setfield(L, -2, "Progress");
}

}  // namespace invasim::lua
