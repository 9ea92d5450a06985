// invasim.Shape{eps_v =, eps_a =}: the adipocytes' volume and face-area energy (ShapeForce).
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_fields.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

// The keys of invasim.Shape{} (both required: ShapeForce has no defaults).
struct ShapeKeys {
  double eps_v = 0.0, eps_a = 0.0;
};

const FieldTable<ShapeKeys>& shape_fields() {
  using P = ShapeKeys;
  static const FieldTable<P> table(
      "Shape", {
                   required(number<P>("eps_v", &P::eps_v, Range::non_negative(), "eps_c",
                                      "adipocyte volume stiffness")),
                   required(number<P>("eps_a", &P::eps_a, Range::non_negative(), "eps_c",
                                      "adipocyte face-area stiffness")),
               });
  return table;
}

ShapeKeys keys_of(const Shape& s) {
  return {s.force->eps_v(), s.force->eps_a()};
}

}  // namespace

std::string LuaType<Shape>::describe(const Shape& s) {
  return shape_fields().describe(keys_of(s));
}

// s:params() -> {eps_v =, eps_a =}
void open_shape(lua_State* L) {
  define_params_type<Shape, &shape_fields, &keys_of, [](const ShapeKeys& k) {
    return std::make_shared<Shape>(std::make_shared<ShapeForce>(k.eps_v, k.eps_a));
  }>(L, {});
}

}  // namespace invasim::lua
