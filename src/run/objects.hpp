#pragma once
// The objects a protocol builds and runs (the Lua layer's System, Group, force, Method and
// Dynamics objects are these; lua/engine_types.hpp names them for Lua).
//
// Ownership: a SystemHandle is the Model (the engine System, its ForceField, the revision:
// run/model.hpp) plus the handles of the forces added to it. Forces, groups and methods
// remember the SystemHandle they belong to through a weak_ptr, so a force cannot be added to
// two systems, a method cannot move a group of another system, and no handle keeps its System
// alive or forms a cycle with it (only what runs it holds it strongly: the Lua System object,
// a Simulation, a checkpoint writer). The rules that tie them together are run/wiring.hpp.
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "forces/contact_force.hpp"
#include "forces/shape_force.hpp"
#include "forces/tether_force.hpp"
#include "forces/wall_force.hpp"
#include "integrate/dynamics.hpp"
#include "run/model.hpp"

namespace invasim {

struct SystemHandle;

// A force term and the System it was added to (if any).
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

// A Model with the handles of its forces. Every change made to the state, the forces or the
// site forces outside a Dynamics run calls changed().
struct SystemHandle : Model {
  SystemHandle(const Box& box, std::uint64_t seed) : Model(box, seed) {}
  std::vector<ForceHandle> handles;  // in the order added (same as forces.terms())
  bool running = false;  // inside run_steps: a callback of the run may not start another
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
  bool running = false;          // inside run_steps: its methods and pressure wall stay fixed
};

}  // namespace invasim
