// Files from Lua (src/io), for the run directory that protocols fill:
//   invasim.write_file(path, text)   -- atomically (temp file + rename)
//   invasim.make_dirs(path)          -- like mkdir -p
//   local snap = invasim.Snapshots{dir =, cells_xyz = true, spheres_vtp = true,
//                                  adipocytes_vtp = true}
//   snap:write(sys)                  -- one frame: extended XYZ + VTK .vtp + .pvd indexes
#include <lua.hpp>

#include "io/atomic_file.hpp"
#include "io/snapshot_writer.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"
#include "lua/names.hpp"

namespace invasim::lua {

template <>
struct LuaType<SnapshotWriter> {
  static constexpr const char* name = "Snapshots";
  static constexpr const char* metatable = "invasim.Snapshots";
  static std::string describe(const SnapshotWriter& w) {
    return cat("Snapshots(", w.directory().string(), ")");
  }
};

namespace {

int l_write_file(lua_State* L) {
  const std::string path = arg_string(L, 1);
  const std::string text = arg_string(L, 2);
  engine_call("write_file", [&] { write_file_atomically(path, text); });
  return 0;
}

int l_make_dirs(lua_State* L) {
  const std::string path = arg_string(L, 1);
  engine_call("make_dirs", [&] { ensure_directory(path); });
  return 0;
}

int l_snapshots(lua_State* L) {
  Kwargs kw(L, 1, "Snapshots");
  const std::string dir = kw.string("dir");
  SnapshotOptions o;
  o.cells_xyz = kw.boolean("cells_xyz", o.cells_xyz);
  o.spheres_vtp = kw.boolean("spheres_vtp", o.spheres_vtp);
  o.adipocytes_vtp = kw.boolean("adipocytes_vtp", o.adipocytes_vtp);
  kw.finish();
  push(L, engine_call("Snapshots", [&] { return std::make_shared<SnapshotWriter>(dir, o); }));
  return 1;
}

int l_snapshot_write(lua_State* L) {
  SnapshotWriter& w = check<SnapshotWriter>(L, 1);
  const Simulation& sim = check<Simulation>(L, 2);
  engine_call("write", [&] { w.write(sim.system); });
  return 0;
}

const luaL_Reg kSnapshotMethods[] = {
    {"write", &lua_wrap<&l_snapshot_write>},
    {nullptr, nullptr},
};

}  // namespace

void open_io(lua_State* L) {
  lua_pushcfunction(L, &lua_wrap<&l_write_file>);
  lua_setfield(L, -2, "write_file");
  lua_pushcfunction(L, &lua_wrap<&l_make_dirs>);
  lua_setfield(L, -2, "make_dirs");
  define_type<SnapshotWriter>(L, kSnapshotMethods);
  lua_pushcfunction(L, &lua_wrap<&l_snapshots>);
  lua_setfield(L, -2, "Snapshots");
}

}  // namespace invasim::lua
