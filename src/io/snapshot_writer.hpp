#pragma once
// Writes snapshot frames into one directory (docs/output_formats.md, "Snapshot directory"):
//   cells_<step>.xyz        extended XYZ of the cancer cells (OVITO: open cells_*.xyz)
//   spheres_<step>.vtp      the same cells as VTK vertices (ParaView)
//   adipocytes_<step>.vtp   all adipocyte meshes (ParaView)
//   spheres.pvd, adipocytes.pvd   time-series indexes, rewritten atomically at each frame
//   trajectory.xyz          optional: every frame appended to one multi-frame XYZ file
// <step> is the step zero-padded to 9 digits (more if needed). Every file but trajectory.xyz
// is written atomically. A writer opened on a directory that already holds a series (a
// restarted run) continues it: entries that do not name an existing frame file of the series
// in this directory are dropped at once, and at its first frame, index entries and trajectory
// frames whose step is not below the new frame's step (the abandoned part of the old run) are
// dropped.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/frame.hpp"
#include "io/vtk_format.hpp"

namespace invasim {

struct SnapshotOptions {
  bool cells_xyz = true;       // cells_<step>.xyz
  bool spheres_vtp = true;     // spheres_<step>.vtp + spheres.pvd
  bool adipocytes_vtp = true;  // adipocytes_<step>.vtp + adipocytes.pvd
  bool trajectory = false;     // trajectory.xyz (multi-frame, appended)
  bool ids = false;            // an id column: each cell's System::site_ids (proliferation)
};

// The files one frame produced.
struct SnapshotFiles {
  std::vector<std::filesystem::path> written;
};

class SnapshotWriter {
 public:
  // Creates `dir` if needed and loads existing .pvd indexes (to continue a series).
  explicit SnapshotWriter(std::filesystem::path dir, SnapshotOptions options = {});

  // Writes the frame of the current state of sys (frame_from_system).
  SnapshotFiles write(const System& sys);
  // Writes a frame.
  SnapshotFiles write(const Frame& frame);

  // Drops the .pvd index entries of steps after `step` and rewrites the indexes (a run
  // continued from a checkpoint of that step will write those frames again).
  void forget_after(std::uint64_t step);

  const std::filesystem::path& directory() const { return dir_; }
  // Frame file name for a kind ("cells", "spheres", "adipocytes") and step.
  static std::string frame_file_name(const std::string& kind, std::uint64_t step,
                                     const std::string& extension);
  // The step encoded in a frame file name "<kind>_<digits>.<ext>", or -1.
  static std::int64_t step_of_file_name(const std::string& name);

 private:
  // A .pvd index kept in memory and rewritten atomically after every frame.
  struct Series {
    std::string kind;  // "spheres" or "adipocytes"
    std::vector<PvdEntry> entries;
  };
  // Loads an existing .pvd index, keeping only entries of is_own_frame (rewrites it if any
  // entry was dropped).
  void load_series(Series& s);
  // Whether a .pvd entry names a frame file of this series: "<kind>_<step>.vtp", a regular
  // file (not a link) in this directory.
  bool is_own_frame(const std::string& kind, const std::string& file) const;
  // Drops the entries of steps >= first (entries whose file name encodes no step are kept);
  // returns whether any was dropped.
  static bool drop_steps_from(Series& s, std::uint64_t first);
  void add_to_series(Series& s, const Frame& frame, const std::string& file);
  void append_trajectory(const Frame& frame);

  std::filesystem::path dir_;
  SnapshotOptions options_;
  Series spheres_{"spheres", {}}, adipocytes_{"adipocytes", {}};
  bool first_frame_ = true;
};

// Drops every frame whose Step is >= `step` (and any incomplete frame at the end) from a
// multi-frame XYZ file, so that a restarted run can append to it. No-op if it does not exist.
void truncate_xyz_trajectory(const std::filesystem::path& path, std::uint64_t step);

}  // namespace invasim
