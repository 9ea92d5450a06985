// invasim.Progress{total = N, every_seconds = 10, label = "...", live = bool, start = 0}
// with :update(step [, time]), :finish() and :stop() (a run cut short). Reports to stderr (live
// line on a terminal).
#include <unistd.h>
#include <lua.hpp>

#include <cstdio>
#include <iostream>
#include <limits>

#include "core/names.hpp"
#include "core/progress.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

std::string LuaType<Progress>::describe(const Progress& p) {
  return cat("Progress(step ", p.step(), p.total() > 0 ? cat("/", p.total()) : "",
             p.finished() ? ", finished)" : ")");
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

}  // namespace

void open_progress(lua_State* L) {
  define_type<Progress>(L, {method<"update",
                                   [](Progress& p, std::uint64_t step, std::optional<double> time) {
                                     // A step before the last one would make the rate and ETA
                                     // negative.
                                     if (static_cast<long long>(step) < p.step())
                                       fail_input("update: step ", step,
                                                  " is before the last one, ", p.step());
                                     p.update(static_cast<long long>(step), time);
                                   }>(),
                            method<"finish", [](Progress& p) { p.finish(); }>(),
                            method<"stop", [](Progress& p) { p.stop(); }>()});
  static const std::vector<Declaration> progress_keys = with_options(
      progress_fields().infos(),
      {option_key("live", "boolean",
                  "redraw one line on the terminal (default: when stderr is a terminal)")});
  set_constructor(L, "Progress", &lua_wrap<&l_new>, progress_keys);
}

}  // namespace invasim::lua
