// Groups of sites, made by sys:group(name) and sys:place{...}: g:size(), g:name(), g:sites().
#include <lua.hpp>

#include "core/names.hpp"
#include "lua/adapters.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

std::string LuaType<Group>::describe(const Group& g) {
  return cat("Group('", g.name, "', ", g.sites.size(), " sites",
             g.owner.expired() ? ", no System" : "", ")");
}

void open_group(lua_State* L) {
  define_type<Group>(L, {getter<Group, [](const Group& g) { return g.sites.size(); }>("size"),
                         getter<Group, [](const Group& g) { return g.name; }>("name"),
                         // the engine's site indices, which start at 0
                         getter<Group, [](const Group& g) { return g.sites; }>("sites")});
}

}  // namespace invasim::lua
