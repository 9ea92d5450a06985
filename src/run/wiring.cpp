#include "run/wiring.hpp"

#include "core/names.hpp"
#include "core/progress.hpp"

namespace invasim {

namespace {

// The System's one force of handle type H; `several` and `none` end the two refusals.
template <typename H>
std::shared_ptr<H> the_one(const SystemHandle& sim, std::string_view what, const char* several,
                           const char* none) {
  std::shared_ptr<H> found;
  for (const ForceHandle& h : sim.handles)
    if (const auto* x = std::get_if<std::shared_ptr<H>>(&h)) {
      if (found) fail_input(what, several);
      found = *x;
    }
  if (!found) fail_input(what, none);
  return found;
}

}  // namespace

SystemHandle& owner_of(const std::weak_ptr<SystemHandle>& owner, const std::string& what,
                       const std::string& hint) {
  if (auto sim = owner.lock()) return *sim;
  if (!owner.owner_before(std::weak_ptr<SystemHandle>{}) &&
      !std::weak_ptr<SystemHandle>{}.owner_before(owner))
    fail_input(what, ": not in a System; ", hint);
  fail_input(what, ": its System no longer exists");
}

void require_same_system(const Group& group, const SystemHandle& sim, const std::string& what) {
  if (group.owner.lock().get() != &sim)
    fail_input(what, ": group '", group.name, "' belongs to another System");
}

void require_current(const Group& group, const std::string& what) {
  const auto sim = group.owner.lock();
  if (!sim) return;
  if (sim->system.site_epoch() != group.epoch)
    fail_input(what, ": group '", group.name,
               "' was made before cells divided or died, and its site indices name other cells "
               "now; make it again (sys:group('",
               group.name, "'))");
  // The same epoch with fewer sites: a checkpoint of another System was loaded since.
  const std::size_t n = sim->system.n_sites();
  for (int i : group.sites)
    if (i < 0 || std::size_t(i) >= n)
      fail_input(what, ": group '", group.name, "' names site index ", i, " but the System has ", n,
                 " sites now (a checkpoint of other sites was loaded since it was made); make "
                 "it again (sys:group('",
                 group.name, "'))");
}

PressureWall* prepare_dynamics(DynamicsHandle& d, const std::shared_ptr<SystemHandle>& sim,
                               const std::string& what) {
  for (const auto& m : d.methods) require_same_system(*m->group, *sim, what + ": " + m->kind);
  PressureWall* wall = d.dynamics.pressure_wall().get();
  if (wall) {
    std::shared_ptr<Walls> walls = d.walls;
    if (walls) {
      if (walls->owner.lock() != sim)
        fail_input(what,
                   ": the pressure wall's Walls are not a force of this System; add them "
                   "with sys:add(walls)");
    } else {
      walls = the_one<Walls>(*sim, what,
                             ": the System has several Walls; name the pressure wall's with "
                             "dyn:pressure_wall{walls = w, ...}",
                             ": the pressure wall needs a Walls force in the System "
                             "(sys:add(iv.Walls{}))");
    }
    if (!walls->left)
      fail_input(what, ": the pressure wall moves the left wall, but its Walls have left = false");
    wall->walls = walls->force;
  }
  d.record.check(d.dynamics, sim);
  return wall;
}

Simulation make_simulation(const std::shared_ptr<SystemHandle>& system,
                           const std::shared_ptr<DynamicsHandle>& d) {
  return Simulation(std::shared_ptr<System>(system, &system->system),
                    std::shared_ptr<ForceField>(system, &system->forces),
                    std::shared_ptr<Dynamics>(d, &d->dynamics));
}

RunResult run_steps(Simulation& run, const std::shared_ptr<SystemHandle>& system, DynamicsHandle& d,
                    long long n, const std::shared_ptr<Progress>& progress) {
  // Steps that move nothing are a forgotten dyn:add, not a run.
  if (n > 0 && d.dynamics.methods().empty() && !d.dynamics.pressure_wall())
    fail_input(
        "run: the Dynamics has no methods, so nothing would move: add one first, e.g. "
        "dyn:add(iv.Langevin{group = sys:group(\"cancer\"), gamma =, kT =})");
  // A run started from a callback of a run of the same System would advance it behind the
  // outer run, whose step count and schedule would no longer be the System's.
  if (system->running)
    fail_input(
        "run: the System is running already (this call comes from a callback of its "
        "run); return from the callback, and run after the run returns");
  if (progress)
    run.set_progress([progress](std::uint64_t done, double time) {
      progress->update(static_cast<long long>(done), time);
    });
  RunResult result;
  system->running = true;
  d.running = true;
  try {
    prepare_dynamics(d, system, "run");
    result = run.run(static_cast<std::uint64_t>(n));
  } catch (...) {
    system->running = false;
    d.running = false;
    run.set_progress({});
    throw;
  }
  system->running = false;
  d.running = false;
  run.set_progress({});
  system->changed();
  d.record.ran_on(system);
  return result;
}

void restored_from_checkpoint(const std::shared_ptr<SystemHandle>& sim, DynamicsHandle* d) {
  for (const auto& term : sim->forces.terms()) term->invalidate_caches();
  sim->changed();
  if (d) {
    prepare_dynamics(*d, sim, "load_checkpoint");  // links the pressure wall
    d->dynamics.mark_prepared();
    d->record.ran_on(sim);
  }
}

std::shared_ptr<ContactForce> only_contacts(const SystemHandle& sim, std::string_view what) {
  return the_one<Contacts>(sim, what,
                           ": the System has several Contacts forces; change their parameters "
                           "with c:set{} instead",
                           ": the System has no Contacts force (add one with "
                           "sys:add(invasim.Contacts{...}))")
      ->force;
}

TemporaryContacts::TemporaryContacts(SystemHandle& sim, std::shared_ptr<ContactForce> force,
                                     const ContactParams& changed)
    : sim_(sim), force_(std::move(force)), saved_(force_->params()) {
  force_->set_params(changed);
  sim_.changed();
}

TemporaryContacts::~TemporaryContacts() {
  try {
    force_->set_params(saved_);  // the contacts' own parameters: valid, never throws here
  } catch (...) {
  }
  sim_.changed();
}

}  // namespace invasim
