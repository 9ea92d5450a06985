// Checkpoints of a protocol's state (checkpoint/protocol_checkpoint.hpp):
//   invasim.save_checkpoint(path, {system =, dynamics =, tethers =, correlator =, contacts =,
//                                  extra = "", run_id = "", run_parameters = ""})
//   local extra = invasim.load_checkpoint(path, {system =, dynamics =, tethers =, correlator =,
//                                                contacts =, seed =})  -- seed: a new one
//   local id, parameters = invasim.checkpoint_run(path)  -- the run that wrote it (nil, nil if
//                                                          -- it was written outside a run)
//   invasim.interrupted()   -> "SIGINT" / "SIGTERM" once a stop was requested, else nil
//   invasim.decode_state(text [, origin]) -> the plain Lua data of a checkpoint's `extra`
//                                            (checkpoint/lua_data.hpp: parsed as data, never run)
// save writes the System (every site array, bit for bit), the Dynamics (time step, method
// parameters and ramp anchors, the pressure wall), the tethers, a correlator's accumulators,
// the contacts' parameters (which a protocol may change while it runs) and a string of the
// protocol's own (`extra`), atomically. load restores them into objects
// built the same way (same protocol, same parameters) and marks the Dynamics prepared, so the
// run continues bit for bit as if it had never stopped. run_id / run_parameters identify the
// run that writes the checkpoint (protocols/lib/run_identity.lua): they go into the sections
// "run.id" and "run.parameters", which --resume compares with the run it continues.
#include <lua.hpp>

#include <optional>

#include "checkpoint/lua_data.hpp"
#include "checkpoint/protocol_checkpoint.hpp"
#include "core/names.hpp"
#include "core/stop_request.hpp"
#include "lua/checkpoint_parts.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

CheckpointParts read_checkpoint_parts(Kwargs& kw, bool need_system) {
  lua_State* L = kw.state();
  CheckpointParts p;
  if (need_system) {
    p.sim = kw_object<SystemHandle>(kw, "system", true);
    p.dyn = kw_object<DynamicsHandle>(kw, "dynamics");
  }
  p.tethers = kw_object<Tethers>(kw, "tethers");
  p.contacts = kw_object<Contacts>(kw, "contacts");
  if (kw.push("correlator") != LUA_TNIL) {
    p.correlator = shared_correlator(L, -1);
    if (!p.correlator)
      fail_input(kw.owner(), ": key 'correlator' must be a Correlator, got ", type_name_at(L, -1));
  }
  lua_pop(L, 1);
  if (need_system) check_checkpoint_parts(p);
  return p;
}

void check_checkpoint_parts(const CheckpointParts& p) {
  if (p.contacts && p.contacts->owner.lock() != p.sim)
    fail_input("checkpoint: key 'contacts' must be the Contacts force of its System");
}

namespace {

// The engine objects of the parts (checkpoint/protocol_checkpoint.hpp).
ProtocolObjects engine_objects(const CheckpointParts& p) {
  return {&p.sim->system, p.dyn ? &p.dyn->dynamics : nullptr,
          p.tethers ? p.tethers->force.get() : nullptr, p.correlator.get(),
          p.contacts ? p.contacts->force.get() : nullptr};
}

}  // namespace

void write_checkpoint_parts(CheckpointWriter& w, const CheckpointParts& p, std::string_view extra,
                            const std::optional<std::string>& run_id,
                            const std::optional<std::string>& run_parameters) {
  write_protocol_checkpoint(w, engine_objects(p), {std::string(extra), run_id, run_parameters});
}

namespace {

int l_save(lua_State* L) {
  const std::string path = arg_path(L, 1);
  Kwargs kw(L, 2, "save_checkpoint");
  const CheckpointParts p = read_checkpoint_parts(kw);
  const std::string extra = kw.string("extra", "");
  const auto run_id = kw.maybe_string("run_id");
  const auto run_parameters = kw.maybe_string("run_parameters");
  kw.finish();
  if (run_parameters && !run_id)
    fail_input("save_checkpoint: run_parameters without run_id (give the run's identity too)");
  engine_call("save_checkpoint", [&] {
    CheckpointWriter w;
    write_checkpoint_parts(w, p, extra, run_id, run_parameters);
    w.write(path);
  });
  return 0;
}

int l_load(lua_State* L) {
  const std::string path = arg_path(L, 1);
  Kwargs kw(L, 2, "load_checkpoint");
  const CheckpointParts p = read_checkpoint_parts(kw);
  const auto seed = kw.maybe_integer<std::uint64_t>("seed", Range::at_least(0));
  kw.finish();
  std::string extra;
  engine_call("load_checkpoint", [&] {
    extra = read_protocol_checkpoint(CheckpointReader::read(path), path, engine_objects(p), seed);
    restored_from_checkpoint(p.sim, p.dyn.get());
  });
  push_value(L, extra);
  return 1;
}

// invasim.checkpoint_run(path) -> run id, run parameters (strings; nil where not stored).
int l_checkpoint_run(lua_State* L) {
  const std::string path = arg_path(L, 1);
  ProtocolRecord record;
  engine_call("checkpoint_run", [&] { record = checkpoint_run(CheckpointReader::read(path)); });
  return push_results(L, 2, [&record](lua_State* S) noexcept {
    for (const std::optional<std::string>* value : {&record.run_id, &record.run_parameters}) {
      if (*value)
        lua_pushlstring(S, (*value)->data(), (*value)->size());
      else
        lua_pushnil(S);
    }
    return 2;
  });
}

// Pushes a parsed datum (depth <= kMaxLuaDataDepth); runs inside push_results' protected
// call, so a Lua memory error unwinds to it (no C++ object of this frame needs destroying).
void push_datum(lua_State* L, const LuaDatum& d) noexcept {
  switch (d.kind) {
    case LuaDatum::Kind::kNil:
      lua_pushnil(L);
      return;
    case LuaDatum::Kind::kBoolean:
      lua_pushboolean(L, d.boolean);
      return;
    case LuaDatum::Kind::kInteger:
      lua_pushinteger(L, lua_Integer(d.integer));
      return;
    case LuaDatum::Kind::kNumber:
      lua_pushnumber(L, d.number);
      return;
    case LuaDatum::Kind::kString:
      lua_pushlstring(L, d.string.data(), d.string.size());
      return;
    case LuaDatum::Kind::kTable:
      luaL_checkstack(L, 4, "checkpoint state");
      // As Lua's constructor {[k]=v, ...} builds it: a hash part of that size, keys in order.
      lua_createtable(L, 0, int(std::min<std::size_t>(d.entries.size(), 1u << 26)));
      for (const auto& [key, value] : d.entries) {
        push_datum(L, key);
        push_datum(L, value);
        lua_rawset(L, -3);
      }
      return;
  }
}

// invasim.decode_state(text [, origin]): resume.lua's serialized state back as Lua data.
int l_decode_state(lua_State* L) {
  const std::string text = arg_string(L, 1);
  const std::string origin = lua_isnoneornil(L, 2) ? "checkpoint state" : arg_string(L, 2);
  LuaDatum datum;
  engine_call("decode_state", [&] { datum = parse_lua_data(text, origin); });
  return push_results(L, 1, [&datum](lua_State* S) noexcept {
    push_datum(S, datum);
    return 1;
  });
}

}  // namespace

void open_checkpoint(lua_State* L) {
  install_stop_handlers();
  add_functions(L, {{"save_checkpoint", &lua_wrap<&l_save>},
                    {"load_checkpoint", &lua_wrap<&l_load>},
                    INVASIM_LUA_FN(load),  // invasim.load(path, {...}): the same, shorter
                    INVASIM_LUA_FN(checkpoint_run),
                    INVASIM_LUA_FN(decode_state),
                    method<"interrupted", []() -> std::optional<std::string> {
                      if (const int signal = stop_requested()) return stop_signal_name(signal);
                      return std::nullopt;
                    }>()});
}

}  // namespace invasim::lua
