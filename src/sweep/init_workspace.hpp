#pragma once
// `invasim sweep init`: creating a sweep workspace (sweep/workspace.hpp describes its files),
// or growing one with the new points of the same sweep. What it refuses, before writing
// anything (docs/sweeps.md, "The workspace"):
//   - more points than the limit (kDefaultMaxPoints unless --max-points), counted from the
//     spec's axes without making the points;
//   - a directory that is not a workspace: a run directory (resume.txt or params.json) or any
//     other non-empty directory;
//   - a workspace of another sweep: another protocol, another preparation, points that give
//     other parameters, or other values of the spec's fixed parameters (a grown spec, with
//     more values on its axes or more seeds, is the same sweep).
// The writing is atomic: a new workspace is built in a temporary sibling directory
// (.NAME.init.PID) renamed into place; the new points of a grown one are built in WS/.init.PID
// and renamed one by one into WS/workspace/ before the configuration that lists them is
// replaced. A killed init leaves only its temporary directory, which the next init removes.
#include <cstddef>
#include <filesystem>

#include "sweep/spec.hpp"

namespace invasim::sweep {

// The largest number of points `sweep init` writes unless --max-points raises it.
inline constexpr std::size_t kDefaultMaxPoints = 10000;

// What `sweep init` did.
struct InitReport {
  int added = 0;
  int kept = 0;
};

// Creates the workspace `root` for `spec` (or adds the spec's new points to it); InputError
// on any of the refusals above. Existing jobs and their results are kept.
InitReport init_workspace(const SweepSpec& spec, const std::filesystem::path& root,
                          std::size_t max_points = kDefaultMaxPoints);

}  // namespace invasim::sweep
