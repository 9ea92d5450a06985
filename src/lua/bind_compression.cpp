// The setup stages that reshape the box (setup/compression.hpp):
//   invasim.compress(sys, {to_phi =, step = 0.03, ftol =, dt =, dt_max =, max_steps =,
//                          max_compressions = 1e5, progress = p, callback = f,
//                          continue_from = {steps =, fire_steps =, converged =, max_force =,
//                                           fire_state =},
//                          contacts = {beta = 0, ...}})
//   -> report {steps, fire_steps, converged, phi, max_force, box, stopped [, fire_state]}
//   (f(report) is called after every compression step with the report so far. A stop signal
//   (SIGINT/SIGTERM, invasim.interrupted()) stops the compression at the next FIRE iteration
//   with stopped = true and fire_state = {dt, alpha, n_positive, steps, wall_velocity}, the
//   minimiser's state (or at a step boundary, without fire_state); continue_from = such a
//   report continues it on the same tissue, bit for bit; contacts changes the System's
//   Contacts parameters for this call only: run/wiring.hpp's TemporaryContacts)
//   invasim.rescale(sys, {phi_a =, ftol =, dt =, dt_max =, max_steps =}) -> FIRE result
// ftol, dt, dt_max and max_steps set the FIRE minimisation after each box change.
#include <lua.hpp>

#include "core/progress.hpp"
#include "core/stop_request.hpp"
#include "lua/engine_fields.hpp"
#include "lua/module.hpp"
#include "setup/compression.hpp"
#include "setup/test_hooks.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.compress (to_phi required: the target is the stage's choice); defaults:
// CompressionParams' and FireParams'.
const FieldTable<CompressionParams>& compress_fields() {
  using P = CompressionParams;
  static const FieldTable<P> table("compress", [] {
    std::vector<Field<P>> f = {
        required(number<P>("to_phi", &P::target_phi, Range::inside(0, 1), "1",
                           "total packing fraction to reach")),
        number<P>("step", &P::step, Range::inside(0, 1), "1",
                  "relative change of phi per compression step"),
    };
    for (auto& fire : fire_fields<P>(&P::fire)) f.push_back(std::move(fire));
    f.push_back(integer<P>("max_compressions", &P::max_steps, Range::at_least(1), "1",
                           "compression steps before giving up"));
    return f;
  }());
  return table;
}

// The keys of invasim.rescale; FIRE defaults: FireParams'.
struct RescaleKeys {
  double phi_a = 0.0;
  FireParams fire;
  bool stop_on_signal = false;  // SIGINT/SIGTERM ends the FIRE before its next iteration
};

const FieldTable<RescaleKeys>& rescale_fields() {
  using P = RescaleKeys;
  static const FieldTable<P> table("rescale", [] {
    std::vector<Field<P>> f = {required(number<P>("phi_a", &P::phi_a, Range::inside(0, 1), "1",
                                                  "adipocyte packing fraction to reach"))};
    for (auto& fire : fire_fields<P>(&P::fire)) f.push_back(std::move(fire));
    f.push_back(boolean<P>("stop_on_signal", &P::stop_on_signal,
                           "a SIGINT/SIGTERM ends the FIRE before its next iteration (stopped = "
                           "true in the result)"));
    return f;
  }());
  return table;
}

// Pushes the compression report {stopped, steps, fire_steps, converged, phi, max_force, box
// [, fire_state]}.
void push_compression_report(lua_State* L, const CompressionReport& r) {
  Record record{{"stopped", r.stopped},     {"steps", r.steps}, {"fire_steps", r.fire_steps},
                {"converged", r.converged}, {"phi", r.phi},     {"max_force", r.max_force},
                {"box", r.box_lengths}};
  if (r.fire_state) record.push_back({"fire_state", fire_state_record(*r.fire_state)});
  push_record(L, record);
}

int l_compress(lua_State* L) {
  const std::shared_ptr<SystemHandle> sim = check_shared<SystemHandle>(L, 1);
  Kwargs kw(L, 2, "compress");
  const CompressionParams p = compress_fields().read(kw);
  const std::shared_ptr<Progress> progress = kw_object<Progress>(kw, "progress");
  const int callback = kw_function(kw, "callback");  // stack index of the Lua callback, or 0
  CompressionReport so_far;
  if (kw.push("continue_from") != LUA_TNIL) {
    if (!lua_istable(L, -1))
      fail_input("compress: key 'continue_from' must be a table, got ", type_name_at(L, -1));
    Kwargs from(L, lua_gettop(L), "compress: continue_from");
    so_far.steps = from.integer<std::size_t>("steps", Range::at_least(0));
    so_far.fire_steps = from.integer<std::uint64_t>("fire_steps", Range::at_least(0));
    so_far.converged = from.boolean("converged");
    so_far.max_force = from.number("max_force", Range::at_least(0));
    so_far.fire_state = read_fire_state(from);
    from.finish();
  } else {
    lua_pop(L, 1);
  }
  std::optional<TemporaryContacts> contacts;  // undone on every exit path
  temporary_contacts(kw, *sim, contacts);
  kw.finish();
  CompressionCallback on_step = [&](const CompressionReport& r) {
    if (progress) progress->update(static_cast<long long>(r.steps));
    if (callback) {
      lua_pushvalue(L, callback);
      push_compression_report(L, r);
      call_lua(L, 1, 0);
    }
    return stop_requested() == 0;  // the caller checks invasim.interrupted()
  };
  sim->changed();
  const CompressionReport r = engine_call("compress", [&] {
    return compress_to_phi(sim->system, sim->forces, p, on_step, so_far,
                           [] { return stop_requested() != 0; });
  });
  push_compression_report(L, r);
  return 1;
}

int l_rescale(lua_State* L) {
  const std::shared_ptr<SystemHandle> sim = check_shared<SystemHandle>(L, 1);
  Kwargs kw(L, 2, "rescale");
  const RescaleKeys k = rescale_fields().make(kw);
  const double phi_a = k.phi_a;
  const FireParams& fire = k.fire;
  sim->changed();
  FireControl control;
  // Polled before every FIRE iteration; the test hook (off by default) pauses there whether
  // or not a signal may stop the FIRE.
  control.stop = [polls = std::uint64_t(0), on_signal = k.stop_on_signal]() mutable {
    pause_in_rescale_fire(polls++);
    return on_signal && stop_requested() != 0;
  };
  const FireResult r = engine_call(
      "rescale", [&] { return rescale_to_phi_a(sim->system, sim->forces, phi_a, fire, &control); });
  push_fire_result(L, r);
  return 1;
}

}  // namespace

void open_compression(lua_State* L) {
  static const std::vector<Declaration> compress_keys = with_options(
      compress_fields().infos(),
      {option_key("progress", "Progress", "shows the compression's progress"),
       option_key("callback", "function", "f(report) after each compression step"),
       option_key("continue_from", "table",
                  "the report of a stopped compression: continues it bit for bit"),
       option_key("contacts", "table",
                  "Contacts keys for the compression only (given back on every exit)")});
  set_constructor(L, "compress", &lua_wrap<&l_compress>, compress_keys);
  set_constructor(L, "rescale", &lua_wrap<&l_rescale>, rescale_fields().infos());
}

}  // namespace invasim::lua
