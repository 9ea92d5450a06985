#include "checkpoint/protocol_checkpoint.hpp"

#include <utility>

#include "checkpoint/correlator_sections.hpp"
#include "checkpoint/dynamics_sections.hpp"
#include "checkpoint/state_checkpoint.hpp"
#include "core/errors.hpp"

namespace invasim {

namespace {

// The contact parameters as the sections "contacts.<field>" hold them.
constexpr std::pair<const char*, double ContactParams::*> kContactFields[] = {
    {"eps_cc", &ContactParams::eps_cc},   {"eps_cv", &ContactParams::eps_cv},
    {"eps_vv", &ContactParams::eps_vv},   {"alpha", &ContactParams::alpha},
    {"beta", &ContactParams::beta},       {"alpha_cv", &ContactParams::alpha_cv},
    {"beta_cv", &ContactParams::beta_cv}, {"skin", &ContactParams::skin}};

void write_contacts(CheckpointWriter& out, const ContactForce& contacts) {
  for (const auto& [name, field] : kContactFields)
    out.put_f64(std::string("contacts.") + name, contacts.params().*field);
}

// The checkpoint's contact parameters (checked), or none where they equal the contacts' own
// or the checkpoint was written without them (by an older invasim): the contacts stay as
// they are.
std::optional<ContactParams> stored_contacts(const CheckpointReader& in,
                                             const ContactForce& contacts) {
  if (!in.has("contacts.beta")) return std::nullopt;
  ContactParams stored = contacts.params();
  bool differ = false;
  for (const auto& [name, field] : kContactFields) {
    const double value = in.get_f64(std::string("contacts.") + name);
    differ = differ || value != stored.*field;
    stored.*field = value;
  }
  if (!differ) return std::nullopt;
  stored.validate();
  return stored;
}

}  // namespace

void write_protocol_checkpoint(CheckpointWriter& out, const ProtocolObjects& objects,
                               const ProtocolRecord& record) {
  write_system(out, *objects.system);
  if (objects.dynamics) write_dynamics(out, *objects.dynamics);
  if (objects.tethers) write_tethers(out, *objects.tethers);
  if (objects.correlator) write_correlator(out, *objects.correlator);
  if (objects.contacts) write_contacts(out, *objects.contacts);
  out.put_string("extra", record.extra);
  if (record.run_id) out.put_string("run.id", *record.run_id);
  if (record.run_parameters) out.put_string("run.parameters", *record.run_parameters);
}

std::string read_protocol_checkpoint(const CheckpointReader& in, const std::string& path,
                                     const ProtocolObjects& objects,
                                     std::optional<std::uint64_t> seed) {
  System restored = read_system(in);
  System& sys = *objects.system;
  // The number of sites may differ only when cells were born or died (System::site_epoch).
  const bool same_sites = restored.n_sites() == sys.n_sites() || restored.site_epoch() > 0;
  if (!same_sites || restored.bodies().size() != sys.bodies().size())
    fail_input("the checkpoint '", path, "' holds ", restored.n_sites(), " sites and ",
               restored.bodies().size(), " adipocytes, this System ", sys.n_sites(), " sites and ",
               sys.bodies().size(), " adipocytes (load into a System built with the same sizes)");
  // Every part is read and checked before any object changes, so that a refused checkpoint
  // leaves them all as they were. The correlator's restore checks its sizes before it changes
  // anything: the one step that can still refuse, it goes first.
  std::optional<TetherForce> tethers;
  if (objects.tethers) {
    tethers.emplace(*objects.tethers);
    tethers->clear();
    read_tethers(in, restored, *tethers);
  }
  std::optional<CorrelatorState> correlator;
  if (objects.correlator) correlator = read_correlator_state(in);
  if (objects.dynamics) check_dynamics(in, *objects.dynamics);
  std::optional<ContactParams> contacts;
  if (objects.contacts) contacts = stored_contacts(in, *objects.contacts);
  std::string extra = in.get_string("extra");
  if (correlator) objects.correlator->restore(std::move(*correlator));
  sys = std::move(restored);
  if (seed) sys.set_seed(*seed);
  if (tethers) *objects.tethers = std::move(*tethers);
  if (objects.dynamics) read_dynamics(in, *objects.dynamics);
  if (contacts) objects.contacts->set_params(*contacts);
  return extra;
}

ProtocolRecord checkpoint_run(const CheckpointReader& in) {
  ProtocolRecord record;
  if (in.has("run.id")) record.run_id = in.get_string("run.id");
  if (in.has("run.parameters")) record.run_parameters = in.get_string("run.parameters");
  return record;
}

}  // namespace invasim
