// invasim.Walls{eps = 1, left = true, right = true}: the flat walls normal to x (WallForce).
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.Walls{}; defaults: WallForce's constructor's.
struct WallKeys {
  double eps;
  bool left, right;
};

const FieldTable<WallKeys>& wall_fields() {
  using P = WallKeys;
  static const WallForce engine_default;
  static const FieldTable<P> table(
      "Walls",
      {
          number<P>("eps", &P::eps, Range::positive(), "eps_c",
                    "wall stiffness: F = (eps/s)(1 - d/s) into the box"),
          boolean<P>("left", &P::left, "a wall at the lower x bound"),
          boolean<P>("right", &P::right, "a wall at the upper x bound"),
      },
      P{engine_default.eps(), engine_default.left(), engine_default.right()});
  return table;
}

WallKeys keys_of(const Walls& w) {
  return {w.force->eps(), w.left, w.right};
}

}  // namespace

std::string LuaType<Walls>::describe(const Walls& w) {
  return wall_fields().describe(keys_of(w));
}

namespace {

// w:params() -> {eps =, left =, right =}
// w:reaction() -> left, right: x force the sites exert on each wall at the last evaluation.
int l_reaction(lua_State* L) {
  const WallForce& w = *check<Walls>(L, 1).force;
  no_arguments_after(L, 1);
  lua_pushnumber(L, w.left_wall_force());
  lua_pushnumber(L, w.right_wall_force());
  return 2;
}

}  // namespace

void open_walls(lua_State* L) {
  define_params_type<Walls, &wall_fields, &keys_of, [](const WallKeys& k) {
    return std::make_shared<Walls>(std::make_shared<WallForce>(k.eps, k.left, k.right), k.left,
                                   k.right);
  }>(L, {INVASIM_LUA_FN(reaction)});
}

}  // namespace invasim::lua
