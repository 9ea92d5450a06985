#pragma once
// The rules that tie a protocol's objects (run/objects.hpp) together, checked where they are
// used: a group and a method act on their own System only; a force joins one System; before
// a Dynamics steps or minimises a System, its pressure wall is connected to the System's
// Walls and it re-prepares if the System changed since its last run (run/model.hpp's
// RunRecord); a run goes through one function (run_steps) whatever started it. A function that
// takes `what` starts its messages with it: the call that asked ("run", "minimize", "sample").
#include <memory>
#include <string>
#include <string_view>

#include "run/objects.hpp"
#include "run/simulation.hpp"

namespace invasim {

class Progress;  // core/progress.hpp

// The SystemHandle a weak owner points to; throws "<what>: its System no longer exists" when
// it expired, or "<what>: not in a System; <hint>" when it was never set.
SystemHandle& owner_of(const std::weak_ptr<SystemHandle>& owner, const std::string& what,
                       const std::string& hint);

// Throws unless `group` belongs to `sim`: "<what>: group 'cancer' belongs to another System".
void require_same_system(const Group& group, const SystemHandle& sim, const std::string& what);
// Throws when cells were born or died since `group` was made (its indices name other cells
// now), "<what>: group 'cancer' was made before cells divided or died; make it again", or when
// it names a site the System no longer has (a checkpoint of fewer sites loaded since).
void require_current(const Group& group, const std::string& what);

// Adds the force of `handle` to `sim` (sys:add); `name` ("Contacts") names it in the error
// when it already is in a System.
template <typename H>
void attach_force(const std::shared_ptr<SystemHandle>& sim, const std::shared_ptr<H>& handle,
                  const char* name) {
  if (auto other = handle->owner.lock())
    fail_input("add: this ", name, " is already in ", other == sim ? "the" : "another", " System");
  handle->owner = sim;
  sim->forces.add(handle->force);
  sim->handles.emplace_back(handle);
  sim->changed();
}

// Before stepping or minimising `sim` with `d`: checks that every method's group belongs to
// sim, connects the pressure wall to its Walls (the given ones, else the System's only Walls),
// and invalidates the Dynamics when the System changed since its last run. Returns the
// pressure wall or nullptr.
PressureWall* prepare_dynamics(DynamicsHandle& d, const std::shared_ptr<SystemHandle>& sim,
                               const std::string& what);

// A Simulation stepping `system`'s System and ForceField with `d`'s Dynamics; its pointers
// share ownership of the two objects (aliasing shared_ptrs).
Simulation make_simulation(const std::shared_ptr<SystemHandle>& system,
                           const std::shared_ptr<DynamicsHandle>& d);

// Runs n steps of `run` (made by make_simulation from `system` and `d`), the one path of
// dyn:run and sim:run: `progress` (may be null) hears of every chunk; the Dynamics is prepared
// first, and afterwards the System is marked changed and the Dynamics as having run on it.
// Refuses n > 0 steps of a Dynamics with no method and no pressure wall (nothing would move).
RunResult run_steps(Simulation& run, const std::shared_ptr<SystemHandle>& system, DynamicsHandle& d,
                    long long n, const std::shared_ptr<Progress>& progress);

// After a checkpoint was read into `sim` (and `d`, if given): the forces' caches are stale, the
// System changed, and the Dynamics continues as if it had just run on it (pressure wall linked,
// no re-preparation: the checkpoint holds the forces of its step).
void restored_from_checkpoint(const std::shared_ptr<SystemHandle>& sim, DynamicsHandle* d);

// The System's one Contacts force; throws "<what>: the System has no Contacts force ..." or
// "... has several Contacts forces ...".
std::shared_ptr<ContactForce> only_contacts(const SystemHandle& sim, std::string_view what);

// A change of a Contacts force's parameters for the lifetime of the guard (the compress
// stage's "cohesion off" during one engine call): applied by the constructor (which throws,
// changing nothing, if `changed` is invalid) and undone by the destructor, so the contacts get
// their own parameters back on every exit path (a return, a stop signal, an engine error, an
// error raised by a Lua callback).
class TemporaryContacts {
 public:
  TemporaryContacts(SystemHandle& sim, std::shared_ptr<ContactForce> force,
                    const ContactParams& changed);
  ~TemporaryContacts();
  TemporaryContacts(const TemporaryContacts&) = delete;
  TemporaryContacts& operator=(const TemporaryContacts&) = delete;

 private:
  SystemHandle& sim_;
  std::shared_ptr<ContactForce> force_;
  ContactParams saved_;
};

}  // namespace invasim
