// invasim.Contacts{alpha =, beta =, eps_cc =, eps_cv =, eps_vv =, skin =}: contact springs of
// every pair kind with cancer-cancer cohesion (ContactForce).
#include <lua.hpp>

#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"

namespace invasim::lua {

std::string LuaType<Contacts>::describe(const Contacts& c) {
  const ContactParams& p = c.force->params();
  return cat("Contacts(alpha=", p.alpha, ", beta=", p.beta, ", eps_cc=", p.eps_cc,
             ", eps_cv=", p.eps_cv, ", eps_vv=", p.eps_vv, ", skin=", p.skin, ")");
}

void read_contact_params(Kwargs& kw, ContactParams& p) {
  p.alpha = kw.number("alpha", p.alpha, Range::non_negative());
  p.beta = kw.number("beta", p.beta, Range::non_negative());
  p.eps_cc = kw.number("eps_cc", p.eps_cc, Range::positive());
  p.eps_cv = kw.number("eps_cv", p.eps_cv, Range::positive());
  p.eps_vv = kw.number("eps_vv", p.eps_vv, Range::positive());
  p.skin = kw.number("skin", p.skin, Range::non_negative());
}

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Contacts");
  ContactParams p;
  read_contact_params(kw, p);
  kw.finish();
  auto force = engine_call("Contacts", [&] { return std::make_shared<ContactForce>(p); });
  push(L, std::make_shared<Contacts>(std::move(force)));
  return 1;
}

// c:set{alpha =, beta =, ...}: changes some parameters (the others keep their values), e.g.
// switching cohesion on after an athermal compression.
int l_set(lua_State* L) {
  Contacts& c = check<Contacts>(L, 1);
  Kwargs kw(L, 2, "Contacts:set");
  ContactParams p = c.force->params();
  read_contact_params(kw, p);
  kw.finish();
  engine_call("Contacts:set", [&] { c.force->set_params(p); });
  if (auto sim = c.owner.lock()) sim->changed();
  return 0;
}

// c:params() -> {alpha =, beta =, eps_cc =, eps_cv =, eps_vv =, skin =}
int l_params(lua_State* L) {
  const ContactParams& p = check<Contacts>(L, 1).force->params();
  lua_createtable(L, 0, 6);
  set_number(L, "alpha", p.alpha);
  set_number(L, "beta", p.beta);
  set_number(L, "eps_cc", p.eps_cc);
  set_number(L, "eps_cv", p.eps_cv);
  set_number(L, "eps_vv", p.eps_vv);
  set_number(L, "skin", p.skin);
  return 1;
}

const luaL_Reg kMethods[] = {
    {"params", &lua_wrap<&l_params>},
    {"set", &lua_wrap<&l_set>},
    {nullptr, nullptr},
};

}  // namespace

void open_contacts(lua_State* L) {
  define_type<Contacts>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_new>);
  lua_setfield(L, -2, "Contacts");
}

}  // namespace invasim::lua
