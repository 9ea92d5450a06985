// Files from Lua (src/io), for the run directory that protocols fill:
//   invasim.write_file(path, text)   -- atomically (temp file + rename)
//   invasim.make_dirs(path)          -- like mkdir -p
//   invasim.exists(path)             -- true if a file or directory is there
//   invasim.resolve_path(path)       -- absolute, with symbolic links and . / .. resolved
//   invasim.remove_path(path)        -- like rm -rf; returns the number of entries removed
//   local snap = invasim.Snapshots{dir =, cells_xyz = true, spheres_vtp = true,
//                                  adipocytes_vtp = true, trajectory = false, ids = false}
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

std::string LuaType<SnapshotWriter>::describe(const SnapshotWriter& w) {
  return cat("Snapshots(", w.directory().string(), ")");
}

namespace {

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
          boolean<P>("trajectory", &P::trajectory,
                     "trajectory.xyz: every frame appended (from its first frame on, a new writer "
                     "replaces the frames it will write again)"),
          boolean<P>("ids", &P::ids,
                     "an id column: each cell's identity, kept across divisions and deaths"),
      });
  return table;
}

int l_snapshots(lua_State* L) {
  Kwargs kw(L, 1, "Snapshots");
  const SnapshotKeys k = snapshot_fields().make(kw);
  require_no_nul(k.dir, "Snapshots: key 'dir'");
  const SnapshotOptions& o = k;
  push(L, engine_call("Snapshots", [&] { return std::make_shared<SnapshotWriter>(k.dir, o); }));
  return 1;
}

}  // namespace

void open_io(lua_State* L) {
  add_functions(
      L, {method<"write_file",
                 [](Path path, std::string text) { write_file_atomically(path.value, text); }>(),
          method<"make_dirs", [](Path path) { ensure_directory(path.value); }>(),
          method<"exists",
                 [](Path path) {
                   std::error_code error;
                   return std::filesystem::exists(path.value, error);
                 }>(),
          // absolute, with symbolic links and . / .. resolved
          method<"resolve_path",
                 [](Path path) {
                   std::error_code error;
                   const auto p = std::filesystem::weakly_canonical(
                       std::filesystem::absolute(path.value), error);
                   if (error) fail_input("cannot resolve '", path.value, "': ", error.message());
                   return p.string();
                 }>(),
          // like rm -rf; returns the number of entries removed
          method<"remove_path", [](Path path) {
            std::error_code error;
            const auto n = std::filesystem::remove_all(path.value, error);
            if (error) fail_input("cannot remove '", path.value, "': ", error.message());
            return n;
          }>()});
  define_type<SnapshotWriter>(
      L,
      {method<"write", [](SnapshotWriter& w, const SystemHandle& sim) { w.write(sim.system); }>(),
       // drop .pvd entries of later steps (a resumed run)
       method<"forget_after",
              [](SnapshotWriter& w, std::uint64_t step) { w.forget_after(step); }>()});
  set_constructor(L, "Snapshots", &lua_wrap<&l_snapshots>, snapshot_fields().infos());
}

}  // namespace invasim::lua
