// invasim.Progress{total = N, every_seconds = 10, label = "...", live = bool, start = 0}
// with :update(step [, time]) and :finish(). Reports to stderr (live line on a terminal).
#include <unistd.h>
#include <lua.hpp>

#include <cstdio>
#include <iostream>
#include <limits>

#include "core/names.hpp"
#include "core/progress.hpp"
#include "lua/binding.hpp"
#include "lua/fields.hpp"
#include "lua/kwargs.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

INVASIM_LUA_TYPE(Progress, "Progress");
std::string LuaType<Progress>::describe(const Progress& p) {
  return cat("Progress(step ", p.step(), p.total() > 0 ? cat("/", p.total()) : "",
             p.finished() ? ", finished)" : ")");
}

// Declared in engine_types.hpp: the Progress at `index`, or nullptr if it is none.
Progress* test_progress(lua_State* L, int index) {
  auto* slot = test<Progress>(L, index);
  if (slot == nullptr) return nullptr;
  if (!*slot) throw InputError("Progress object is no longer valid");
  return slot->get();
}

namespace {

// The keys of invasim.Progress{} besides `live` (default: whether stderr is a terminal, known
// only at run time); defaults: ProgressOptions'.
const FieldTable<ProgressOptions>& progress_fields() {
  using P = ProgressOptions;
  static const FieldTable<P> table(
      "Progress", {
                      integer<P>("total", &P::total, Range::non_negative(), "steps",
                                 "steps in the run (0: unknown, no percentage or ETA)"),
                      integer<P>("start", &P::start_step, Range::non_negative(), "steps",
                                 "step at construction (for the rate of a continued run)"),
                      number<P>("every_seconds", &P::every_seconds, Range::non_negative(), "s",
                                "seconds between plain-mode lines (0: every update)"),
                      string<P>("label", &P::label, "", "prefix of each line"),
                  });
  return table;
}

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Progress");
  const ProgressOptions options = progress_fields().read(kw);
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

}  // namespace

void open_progress(lua_State* L) {
  define_type<Progress>(L, {INVASIM_LUA_FN(update), INVASIM_LUA_FN(finish)});
  set_constructor(L, "Progress", &lua_wrap<&l_new>, progress_fields().infos());
}

}  // namespace invasim::lua
