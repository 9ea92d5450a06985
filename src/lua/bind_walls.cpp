// invasim.Walls{eps = 1, left = true, right = true}: the flat walls normal to x (WallForce).
#include <lua.hpp>

#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"

namespace invasim::lua {

std::string LuaType<Walls>::describe(const Walls& w) {
  return cat("Walls(eps=", w.force->eps(), ", left=", w.left ? "true" : "false",
             ", right=", w.right ? "true" : "false", ")");
}

namespace {

int l_new(lua_State* L) {
  Kwargs kw(L, 1, "Walls");
  const double eps = kw.number("eps", 1.0, Range::positive());
  const bool left = kw.boolean("left", true);
  const bool right = kw.boolean("right", true);
  kw.finish();
  auto force = engine_call("Walls", [&] { return std::make_shared<WallForce>(eps, left, right); });
  push(L, std::make_shared<Walls>(std::move(force), left, right));
  return 1;
}

// w:reaction() -> left, right: x force the sites exert on each wall at the last evaluation.
int l_reaction(lua_State* L) {
  const WallForce& w = *check<Walls>(L, 1).force;
  lua_pushnumber(L, w.left_wall_force());
  lua_pushnumber(L, w.right_wall_force());
  return 2;
}

const luaL_Reg kMethods[] = {
    {"reaction", &lua_wrap<&l_reaction>},
    {nullptr, nullptr},
};

}  // namespace

void open_walls(lua_State* L) {
  define_type<Walls>(L, kMethods);
  lua_pushcfunction(L, &lua_wrap<&l_new>);
  lua_setfield(L, -2, "Walls");
}

}  // namespace invasim::lua
