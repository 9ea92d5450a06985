// invasim.Shape{eps_v =, eps_a =}: the adipocytes' volume and face-area energy (ShapeForce).
#include <lua.hpp>

#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"

namespace invasim::lua {

std::string LuaType<Shape>::describe(const Shape& s) {
  return cat("Shape(eps_v=", s.force->eps_v(), ", eps_a=", s.force->eps_a(), ")");
}

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Shape");
  const double eps_v = kw.number("eps_v", Range::non_negative());
  const double eps_a = kw.number("eps_a", Range::non_negative());
  kw.finish();
  auto force = engine_call("Shape", [&] { return std::make_shared<ShapeForce>(eps_v, eps_a); });
  push(L, std::make_shared<Shape>(std::move(force)));
  return 1;
}

// s:params() -> {eps_v =, eps_a =}
int l_params(lua_State* L) {
  const ShapeForce& f = *check<Shape>(L, 1).force;
  lua_createtable(L, 0, 2);
  set_number(L, "eps_v", f.eps_v());
  set_number(L, "eps_a", f.eps_a());
  return 1;
}

const luaL_Reg kMethods[] = {
    {"params", &lua_wrap<&l_params>},
    {nullptr, nullptr},
};

}  // namespace

void open_shape(lua_State* L) {
  define_type<Shape>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_new>);
  lua_setfield(L, -2, "Shape");
}

}  // namespace invasim::lua
