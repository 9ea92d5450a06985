#pragma once
// The engine objects as Lua sees them, shared by the bind_<type>.cpp files that expose the
// engine (System, Group, Contacts, Walls, Shape, Tethers, Method, Dynamics, Fire). Each
// LuaType specialisation lives here because several bindings check each other's types
// (dyn:run(sys, ...) checks a System); its describe() is defined in the type's binding file.
//
// Ownership: a System userdata holds a SystemHandle (the engine System plus its ForceField and
// the Lua handles of the forces added to it). Forces, groups and methods remember the
// SystemHandle they belong to through a weak_ptr, so a force cannot be added to two systems
// and a method cannot move a group of another system; nothing holds a SystemHandle strongly
// except the System userdata, so Lua's collection order never matters. (Simulation is only
// the run layer's: run/simulation.hpp, and its Lua object invasim.Simulation.)
#include <lua.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "forces/contact_force.hpp"
#include "forces/shape_force.hpp"
#include "forces/tether_force.hpp"
#include "forces/wall_force.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/fire.hpp"
#include "integrate/lipolysis.hpp"
#include "integrate/proliferation.hpp"
#include "lua/adapters.hpp"
#include "run/model.hpp"

namespace invasim {
class Progress;        // core/progress.hpp
class SnapshotWriter;  // io/snapshot_writer.hpp
}  // namespace invasim

namespace invasim::lua {

struct SystemHandle;

// A force term as a Lua object: the engine term and the System it was added to (if any).
template <typename F>
struct BoundForce {
  explicit BoundForce(std::shared_ptr<F> f) : force(std::move(f)) {}
  std::shared_ptr<F> force;
  std::weak_ptr<SystemHandle> owner;
};
using Contacts = BoundForce<ContactForce>;
using Shape = BoundForce<ShapeForce>;
using Tethers = BoundForce<TetherForce>;
struct Walls : BoundForce<WallForce> {
  Walls(std::shared_ptr<WallForce> f, bool l, bool r)
      : BoundForce(std::move(f)), left(l), right(r) {}
  bool left, right;
};
using ForceHandle = std::variant<std::shared_ptr<Contacts>, std::shared_ptr<Walls>,
                                 std::shared_ptr<Shape>, std::shared_ptr<Tethers>>;

// The System userdata: the engine's Model (state, force field, revision: run/model.hpp) and
// the Lua handles of its forces. Every binding call that changes the state, the forces or the
// site forces outside a Dynamics run calls changed().
struct SystemHandle : Model {
  SystemHandle(const Box& box, std::uint64_t seed) : Model(box, seed) {}
  std::vector<ForceHandle> handles;  // in the order added (same as forces.terms())
};

// A set of sites of one System (a snapshot of indices, taken when the group is made).
struct Group {
  std::string name;
  std::vector<int> sites;  // engine site indices (0-based)
  std::weak_ptr<SystemHandle> owner;
  std::uint64_t epoch = 0;  // the System's site_epoch() when the group was made
};

// An integration method (Damped, Langevin, Active) and the group it moves.
struct MethodHandle {
  std::string kind;  // "Damped", "Langevin", "Active"
  std::shared_ptr<Method> method;
  std::shared_ptr<Group> group;
};

// A Dynamics with its methods' handles and the Walls of its pressure wall.
struct DynamicsHandle {
  explicit DynamicsHandle(double dt) : dynamics(dt) {}
  Dynamics dynamics;
  std::vector<std::shared_ptr<MethodHandle>> methods;
  std::shared_ptr<Walls> walls;  // walls = given to pressure_wall{}, else resolved at run
  RunRecord record;              // the System of the last run and its revision after it
};

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

// The SystemHandle a weak owner points to; throws "<what>: its System no longer exists" when it
// expired, or "<what>: not in a System; <hint>" when it was never set.
SystemHandle& owner_of(const std::weak_ptr<SystemHandle>& owner, const std::string& what,
                       const std::string& hint);

// Throws unless `group` belongs to `sim`: "<what>: group 'cancer' belongs to another System".
void require_same_system(const Group& group, const SystemHandle& sim, const std::string& what);
// Throws when cells were born or died since `group` was made (its indices name other cells
// now), "<what>: group 'cancer' was made before cells divided or died; make it again".
void require_current(const Group& group, const std::string& what);

// Pushes {x, y, z} (inside a protected_call block: binding.hpp).
void push_vec3(lua_State* L, const Vec3& v) noexcept;

// Pushes the Lua object of a force handle (a new userdata sharing the handle).
void push_force(lua_State* L, const ForceHandle& handle);

// Before stepping or minimising `sim` with `d` (bind_dynamics.cpp): checks that every method's
// group belongs to sim, connects the pressure wall to its Walls (the given ones, else the
// System's only Walls), and invalidates the Dynamics when the System changed since its last
// run. Returns the pressure wall or nullptr. Errors start with `what`.
PressureWall* prepare_dynamics(DynamicsHandle& d, const std::shared_ptr<SystemHandle>& sim,
                               const std::string& what);

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
