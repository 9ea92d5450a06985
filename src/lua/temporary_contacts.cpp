#include "lua/temporary_contacts.hpp"

#include <lua.hpp>

#include "core/names.hpp"

namespace invasim::lua {

namespace {

// The System's one Contacts force; throws naming the call when it has none or several.
std::shared_ptr<ContactForce> only_contacts(const SystemHandle& sim, std::string_view owner) {
  std::shared_ptr<ContactForce> found;
  for (const ForceHandle& h : sim.handles) {
    if (const auto* c = std::get_if<std::shared_ptr<Contacts>>(&h)) {
      if (found)
        fail_input(owner,
                   ": key 'contacts': the System has several Contacts forces; change "
                   "their parameters with c:set{} instead");
      found = (*c)->force;
    }
  }
  if (!found)
    fail_input(owner,
               ": key 'contacts': the System has no Contacts force (add one with "
               "sys:add(invasim.Contacts{...}))");
  return found;
}

}  // namespace

TemporaryContacts::TemporaryContacts(Kwargs& kw, SystemHandle& sim, std::string_view owner) {
  std::optional<Kwargs> keys = kw.maybe_table("contacts");
  if (!keys) return;
  std::shared_ptr<ContactForce> force = only_contacts(sim, owner);
  ContactParams changed = force->params();
  read_contact_params(*keys, changed);
  keys->finish();
  saved_ = force->params();
  engine_call(kw.owner(), [&] { force->set_params(changed); });
  sim_ = &sim;
  force_ = std::move(force);
  sim.changed();
}

TemporaryContacts::~TemporaryContacts() {
  if (!force_) return;
  try {
    force_->set_params(saved_);  // the contacts' own parameters: valid, never throws here
  } catch (...) {
  }
  sim_->changed();
}

}  // namespace invasim::lua
