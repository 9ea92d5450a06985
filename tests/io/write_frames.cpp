// Writes sample output files for the independent Python check (check_snapshots.py):
//   <dir>/snaps/...   two frames through SnapshotWriter (with the trajectory option)
//   <dir>/state.ckpt  a checkpoint of the System, its tethers and a barostat wall
//   <dir>/slice.svg   a slice picture of the last frame
//   <dir>/expected.txt  key = value facts the check compares the files against
// Usage: io_write_frames DIR (DIR is emptied first).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "checkpoint/state_checkpoint.hpp"
#include "core/range.hpp"
#include "integrate/dynamics.hpp"
#include "io/atomic_file.hpp"
#include "io/render_slice.hpp"
#include "io/snapshot_writer.hpp"
#include "io/text_format.hpp"
#include "io_test_support.hpp"

using namespace invasim;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::remove_all(dir);
    ensure_directory(dir);
    System sys = iotest::sample_system(20);
    SnapshotOptions opt;
    opt.trajectory = true;
    SnapshotWriter writer(dir / "snaps", opt);
    std::string expected;
    auto fact = [&](const std::string& key, const std::string& value) {
      expected += key + " = " + value + "\n";
    };
    std::string steps, times;
    for (int frame = 0; frame < 2; ++frame) {
      sys.step = 1200 + 1000 * std::uint64_t(frame);
      sys.time = 0.05 * double(sys.step);
      for (Vec3& v : sys.sites().vel) v *= -1.0;  // frames differ
      writer.write(sys);
      steps += (frame ? " " : "") + std::to_string(sys.step);
      times += (frame ? " " : "") + format_number(sys.time);
    }
    fact("steps", steps);
    fact("times", times);
    fact("n_cells", "20");
    fact("n_bodies", std::to_string(sys.bodies().size()));
    fact("vertices_per_body", "42");
    fact("faces_per_body", "80");
    const Box& box = sys.box();
    fact("box_lo", format_number(box.lo()[0]) + " " + format_number(box.lo()[1]) + " " +
                       format_number(box.lo()[2]));
    fact("box_hi", format_number(box.hi()[0]) + " " + format_number(box.hi()[1]) + " " +
                       format_number(box.hi()[2]));

    TetherForce tethers(0.7);
    iotest::sample_tethers(sys, tethers);
    PressureWall wall;
    wall.pressure = 1.3e-3;
    CheckpointWriter ckpt;
    write_system(ckpt, sys);
    write_tethers(ckpt, tethers);
    write_pressure_wall(ckpt, wall);
    ckpt.write(dir / "state.ckpt");
    fact("n_sites", std::to_string(sys.n_sites()));

    const RenderCounts c =
        render_snapshot(dir / "snaps" / SnapshotWriter::frame_file_name("cells", sys.step, "xyz"),
                        parse_slice_plane("z=5"), dir / "slice.svg");
    fact("svg_discs", std::to_string(c.discs));
    fact("svg_polygons", std::to_string(c.polygons));
    write_file_atomically(dir / "expected.txt", expected);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "io_write_frames: %s\n", e.what());
    return 1;
  }
  return 0;
}
