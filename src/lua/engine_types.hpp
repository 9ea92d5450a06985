#pragma once
// The engine objects as Lua sees them, shared by the bind_<type>.cpp files that expose the
// engine (System, Group, Contacts, Walls, Shape, Tethers, Method, Dynamics, Fire). Each
// LuaType specialisation lives here because several bindings check each other's types
// (dyn:run(sys, ...) checks a System); its describe() is defined in the type's binding file.
//
// The objects themselves and the rules between them are the run layer's (run/objects.hpp,
// run/wiring.hpp).
#include <lua.hpp>

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "integrate/fire.hpp"
#include "integrate/lipolysis.hpp"
#include "integrate/proliferation.hpp"
#include "lua/adapters.hpp"
#include "run/objects.hpp"
#include "run/wiring.hpp"

namespace invasim {
class Progress;        // core/progress.hpp
class SnapshotWriter;  // io/snapshot_writer.hpp
}  // namespace invasim

namespace invasim::lua {

INVASIM_LUA_TYPE(SystemHandle, "System");
INVASIM_LUA_TYPE(Group, "Group");
INVASIM_LUA_TYPE(Contacts, "Contacts");
INVASIM_LUA_TYPE(Walls, "Walls");
INVASIM_LUA_TYPE(Shape, "Shape");
INVASIM_LUA_TYPE(Tethers, "Tethers");
INVASIM_LUA_TYPE(MethodHandle, "Method");
INVASIM_LUA_TYPE(DynamicsHandle, "Dynamics");
INVASIM_LUA_TYPE(Fire, "Fire");
INVASIM_LUA_TYPE(Ramp, "Ramp");
INVASIM_LUA_TYPE(Lipolysis, "Lipolysis");
INVASIM_LUA_TYPE(Proliferation, "Proliferation");
INVASIM_LUA_TYPE(Progress, "Progress");
INVASIM_LUA_TYPE(SnapshotWriter, "Snapshots");

// --- helpers shared by the engine bindings (engine_glue.cpp) ---

// The Group of key `key` (required unless `required` is false: nullptr when absent).
std::shared_ptr<Group> kw_group(Kwargs& kw, std::string_view key, bool required = true);

// A number or an invasim.ramp{} (a copy: each use anchors its own start). Range applies to
// the number and to both ends of a ramp. Required unless a fallback is given.
struct NumberOrRamp {
  double value = 0.0;  // the number, or the ramp's `from`
  std::optional<Ramp> ramp;
};
NumberOrRamp kw_number_or_ramp(Kwargs& kw, std::string_view key, Range range,
                               std::optional<double> fallback = std::nullopt);

// Contact keys alpha, beta, eps_cc, eps_cv, eps_vv, skin present in kw into p (the others
// keep p's values; unknown keys are refused); defined in bind_contacts.cpp.
void read_contact_params(Kwargs& kw, ContactParams& p);

// Key `contacts = {beta = 0, ...}` of kw (absent or nil: no change): the System's one Contacts
// force gets these parameters until `out` is destroyed (run/wiring.hpp's TemporaryContacts).
void temporary_contacts(Kwargs& kw, SystemHandle& sim, std::optional<TemporaryContacts>& out);

// Pushes {x, y, z} (inside a protected_call block: binding.hpp).
void push_vec3(lua_State* L, const Vec3& v) noexcept;

// Pushes the Lua object of a force handle (a new userdata sharing the handle).
void push_force(lua_State* L, const ForceHandle& handle);

// System methods defined in bind_measure.cpp (voronoi, shape_parameters, slices).
extern const luaL_Reg kSystemMeasureMethods[];

// Pushes a FIRE result table {converged, steps, max_force, energy [, stopped, fire_state]}
// (protected: may be called anywhere; a Lua error comes back as a C++ exception).
void push_fire_result(lua_State* L, const FireResult& r);

// {dt, alpha, n_positive, steps, wall_velocity}: the state of a stopped minimisation, to
// continue it bit for bit.
Record fire_state_record(const FireState& st);

// Key `fire_state` of kw (such a table), if present.
std::optional<FireState> read_fire_state(Kwargs& kw);

}  // namespace invasim::lua
