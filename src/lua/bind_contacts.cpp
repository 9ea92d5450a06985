// invasim.Contacts{alpha =, beta =, alpha_cv =, beta_cv =, eps_cc =, eps_cv =, eps_vv =,
// skin =}: contact springs of every pair kind with cancer-cancer cohesion and optional
// cancer-vertex adhesion (ContactForce); invasim.Contacts.check{...} applies its rules only.
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.Contacts{}, c:set{} and c:params(); defaults: ContactParams'.
const FieldTable<ContactParams>& contact_fields() {
  using P = ContactParams;
  static const FieldTable<P> table(
      "Contacts",
      {
          number<P>("alpha", &P::alpha, Range::non_negative(), "1",
                    "cohesion range: cells attract out to r_a = (1 + alpha) s"),
          number<P>("beta", &P::beta, Range::non_negative(), "1",
                    "cohesion depth: r_b = (1 + beta) s; 0 = purely repulsive"),
          number<P>("alpha_cv", &P::alpha_cv, Range::non_negative(), "1",
                    "adhesion range: cells and adipocyte vertices attract out to "
                    "r_a = (1 + alpha_cv) s"),
          number<P>("beta_cv", &P::beta_cv, Range::non_negative(), "1",
                    "adhesion depth: r_b = (1 + beta_cv) s; 0 = purely repulsive (the paper)"),
          number<P>("eps_cc", &P::eps_cc, Range::positive(), "eps_c",
                    "cancer-cancer contact energy"),
          number<P>("eps_cv", &P::eps_cv, Range::positive(), "eps_c",
                    "cancer-vertex contact energy"),
          number<P>("eps_vv", &P::eps_vv, Range::positive(), "eps_c",
                    "vertex-vertex contact energy (different adipocytes)"),
          number<P>("skin", &P::skin, Range::non_negative(), "sigma", "neighbour-list skin"),
      });
  return table;
}

}  // namespace

std::string LuaType<Contacts>::describe(const Contacts& c) {
  return contact_fields().describe(c.force->params());
}

// The contact keys present in kw into p (the others keep p's values), for the `contacts`
// key of compress and minimize (TemporaryContacts); checks kw for unknown keys.
void read_contact_params(Kwargs& kw, ContactParams& p) {
  contact_fields().set(kw, p);
}

namespace {

// c:set{alpha =, beta =, ...}: changes some parameters (the others keep their values), e.g.
// switching cohesion on after an athermal compression.
int l_set(lua_State* L) {
  Contacts& c = check<Contacts>(L, 1);
  Kwargs kw(L, 2, "Contacts:set");
  ContactParams p = c.force->params();
  contact_fields().set(kw, p);
  engine_call("Contacts:set", [&] { c.force->set_params(p); });
  if (auto sim = c.owner.lock()) sim->changed();
  return 0;
}

// c:params() -> {alpha =, beta =, alpha_cv =, beta_cv =, eps_cc =, eps_cv =, eps_vv =, skin =}
// invasim.Contacts.check{alpha =, beta =, ...} -> nil, or the message saying why invasim.Contacts
// would refuse these keys (their ranges and ContactParams::validate's rules such as beta <
// alpha): a protocol checks its parameters before any work with the engine's own rules.
int l_check(lua_State* L) {
  std::string problem;
  try {
    Kwargs kw(L, 1, "Contacts");
    contact_fields().make(kw).validate();
  } catch (const InputError& e) {
    problem = e.what();
  }
  if (problem.empty()) {
    lua_pushnil(L);
    return 1;
  }
  protected_call(L, 0, 1, [&problem](lua_State* S) noexcept {
    lua_pushstring(S, problem.c_str());
    return 1;
  });
  return 1;
}

}  // namespace

void open_contacts(lua_State* L) {
  define_params_type<Contacts, &contact_fields, [](const Contacts& c) { return c.force->params(); },
                     [](const ContactParams& p) {
                       return std::make_shared<Contacts>(std::make_shared<ContactForce>(p));
                     }>(L, {INVASIM_LUA_FN(set)});
  set_static_function(L, "Contacts", "check", &lua_wrap<&l_check>);
}

}  // namespace invasim::lua
