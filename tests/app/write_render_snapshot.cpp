// Writes one snapshot frame whose slices are known by construction, for the `invasim render`
// tests (tests/app/CMakeLists.txt): box [0,20]^3 with walls in x, step 500, t = 25.
//   cells (diameter 1): five within 0.5 of z = 10.05, one within 0.5 of x = 5, one within 0.5
//     of y = 15, two cut by none of these planes;
//   adipocytes (radius 2, 42 vertices): A at (5, 5, 10), B at (15, 15, 10), C at (10, 10, 3).
// So z = 10.05 cuts 5 cells and 2 meshes (A, B), x = 5 cuts 1 cell and 1 mesh (A), y = 15 cuts
// 1 cell and 1 mesh (B). Nothing lies near an in-plane periodic edge, so each shape is drawn
// once. Also writes DIR/bad/cells_000000001.xyz, which is not an XYZ file.
// Usage: app_write_snapshot DIR (writes DIR/snaps/... and DIR/bad/...).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/snapshot_writer.hpp"
#include "mesh/topology.hpp"
#include "state/system.hpp"

using namespace invasim;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::remove_all(dir / "snaps");
    System sys(Box(Vec3::Zero(), Vec3::Constant(20.0), {false, true, true}), 7);
    const Vec3 cells[] = {{2.0, 2.0, 10.0},  {8.0, 4.0, 9.8},
                          {12.0, 8.0, 10.2},                      // cut by z = 10.05
                          {16.0, 6.0, 10.0}, {10.0, 16.0, 10.3},  // cut by z = 10.05
                          {14.0, 2.0, 10.6},                      // 0.55 above z = 10.05
                          {5.2, 17.0, 3.0},                       // cut by x = 5
                          {3.0, 15.3, 14.0},                      // cut by y = 15
                          {17.0, 12.0, 16.0}};                    // cut by none
    for (const Vec3& r : cells) sys.add_sphere(r, 1.0);
    const MeshShape shape = icosphere(1);
    for (const Vec3& c : {Vec3(5, 5, 10), Vec3(15, 15, 10), Vec3(10, 10, 3)})
      sys.add_mesh_scaled(shape, c, 2.0, 1.0, 1.1);
    sys.step = 500;
    sys.time = 25.0;
    SnapshotWriter(dir / "snaps").write(sys);
    ensure_directory(dir / "bad");
    write_file_atomically(dir / "bad" / "cells_000000001.xyz", "not a snapshot\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "app_write_snapshot: %s\n", e.what());
    return 1;
  }
  return 0;
}
