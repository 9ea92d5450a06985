// Files from Lua (src/io), for the run directory that protocols fill:
//   invasim.write_file(path, text)   -- atomically (temp file + rename)
//   invasim.make_dirs(path)          -- like mkdir -p
//   invasim.exists(path)             -- true if a file or directory is there
//   invasim.resolve_path(path)       -- absolute, with symbolic links and . / .. resolved
//   invasim.remove_path(path)        -- like rm -rf; returns the number of entries removed
//   local snap = invasim.Snapshots{dir =, cells_xyz = true, spheres_vtp = true,
//                                  adipocytes_vtp = true, ids = false}
//   snap:write(sys)                  -- one frame: extended XYZ + VTK .vtp + .pvd indexes
//   snap:forget_after(step)          -- drop .pvd entries of later steps (a resumed run)
#include <lua.hpp>

#include <filesystem>
#include <system_error>

#include "core/names.hpp"
#include "io/atomic_file.hpp"
#include "io/snapshot_writer.hpp"
#include "lua/engine_types.hpp"
#include "lua/fields.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

INVASIM_LUA_TYPE(SnapshotWriter, "Snapshots");
std::string LuaType<SnapshotWriter>::describe(const SnapshotWriter& w) {
  return cat("Snapshots(", w.directory().string(), ")");
}

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

int l_exists(lua_State* L) {
  const std::string path = arg_string(L, 1);
  std::error_code error;
  lua_pushboolean(L, std::filesystem::exists(path, error));
  return 1;
}

int l_resolve_path(lua_State* L) {
  const std::string path = arg_string(L, 1);
  const std::string resolved = engine_call("resolve_path", [&] {
    std::error_code error;
    const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path), error);
    if (error) fail_input("resolve_path: cannot resolve '", path, "': ", error.message());
    return p.string();
  });
  lua_pushstring(L, resolved.c_str());
  return 1;
}

int l_remove_path(lua_State* L) {
  const std::string path = arg_string(L, 1);
  const auto removed = engine_call("remove_path", [&] {
    std::error_code error;
    const auto n = std::filesystem::remove_all(path, error);
    if (error) fail_input("remove_path: cannot remove '", path, "': ", error.message());
    return n;
  });
  lua_pushinteger(L, lua_Integer(removed));
  return 1;
}

// The keys of invasim.Snapshots{}; defaults: SnapshotOptions'.
struct SnapshotKeys : SnapshotOptions {
  std::string dir;
};

const FieldTable<SnapshotKeys>& snapshot_fields() {
  using P = SnapshotKeys;
  static const FieldTable<P> table(
      "Snapshots",
      {
          required(string<P>("dir", &P::dir, "path", "directory the files are written to")),
          boolean<P>("cells_xyz", &P::cells_xyz, "cells_<step>.xyz"),
          boolean<P>("spheres_vtp", &P::spheres_vtp, "spheres_<step>.vtp and spheres.pvd"),
          boolean<P>("adipocytes_vtp", &P::adipocytes_vtp,
                     "adipocytes_<step>.vtp and adipocytes.pvd"),
          boolean<P>("ids", &P::ids,
                     "an id column: each cell's identity, kept across divisions and deaths"),
      });
  return table;
}

int l_snapshots(lua_State* L) {
  Kwargs kw(L, 1, "Snapshots");
  const SnapshotKeys k = snapshot_fields().make(kw);
  const SnapshotOptions& o = k;
  push(L, engine_call("Snapshots", [&] { return std::make_shared<SnapshotWriter>(k.dir, o); }));
  return 1;
}

int l_snapshot_write(lua_State* L) {
  SnapshotWriter& w = check<SnapshotWriter>(L, 1);
  const SystemHandle& sim = check<SystemHandle>(L, 2);
  engine_call("write", [&] { w.write(sim.system); });
  return 0;
}

int l_snapshot_forget_after(lua_State* L) {
  SnapshotWriter& w = check<SnapshotWriter>(L, 1);
  const auto step = std::uint64_t(arg_integer(L, 2, 0, LUA_MAXINTEGER));
  engine_call("forget_after", [&] { w.forget_after(step); });
  return 0;
}

}  // namespace

std::shared_ptr<SnapshotWriter> shared_snapshots(lua_State* L, int index) {
  auto* slot = test<SnapshotWriter>(L, index);
  return slot ? *slot : nullptr;
}

namespace {

const luaL_Reg kSnapshotMethods[] = {
    {"write", &lua_wrap<&l_snapshot_write>},
    {"forget_after", &lua_wrap<&l_snapshot_forget_after>},
    {nullptr, nullptr},
};

}  // namespace

void open_io(lua_State* L) {
  add_functions(L, {INVASIM_LUA_FN(write_file), INVASIM_LUA_FN(make_dirs), INVASIM_LUA_FN(exists),
                    INVASIM_LUA_FN(resolve_path), INVASIM_LUA_FN(remove_path)});
  define_type<SnapshotWriter>(L, kSnapshotMethods);
  set_constructor(L, "Snapshots", &lua_wrap<&l_snapshots>, snapshot_fields().infos());
}

}  // namespace invasim::lua
