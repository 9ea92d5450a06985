#pragma once
// A temporary change of a System's contact parameters for the duration of one engine call:
// key `contacts = {beta = 0, ...}` of invasim.compress and of fire:minimize (the compress
// stage's "cohesion off"). The change is applied when the guard is made and undone by its
// destructor, so the contacts get their own parameters back on every exit path: a normal
// return, a stop signal (SIGINT/SIGTERM), an engine error, an error raised by a Lua callback.
#include <memory>
#include <optional>
#include <string_view>

#include "lua/engine_types.hpp"

namespace invasim::lua {

class TemporaryContacts {
 public:
  // Reads key "contacts" of kw (absent or nil: no change) and applies it to the System's
  // Contacts force (an error if the System has none or several). `owner` names the call in
  // messages: "compress: key 'contacts': the System has no Contacts force".
  TemporaryContacts(Kwargs& kw, SystemHandle& sim, std::string_view owner);
  ~TemporaryContacts();
  TemporaryContacts(const TemporaryContacts&) = delete;
  TemporaryContacts& operator=(const TemporaryContacts&) = delete;

 private:
  SystemHandle* sim_ = nullptr;
  std::shared_ptr<ContactForce> force_;  // null when nothing was changed
  ContactParams saved_;
};

}  // namespace invasim::lua
