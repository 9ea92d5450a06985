#pragma once
// `invasim render SNAPSHOT --slice z=VALUE -o FILE.svg [--size PIXELS]`: a slice picture of
// one snapshot frame (docs/output_formats.md, "Slice pictures").
#include <ostream>

#include "app/cli.hpp"

namespace invasim::app {

// Loads the frame of options.snapshot (and its sibling files), cuts it by the plane, writes
// the SVG atomically and prints "render: N discs, M polygons -> FILE.svg" on `out`. Errors
// (unreadable snapshot, plane outside the walls, unwritable output) throw, naming the file.
int run_render(const RenderOptions& options, std::ostream& out);

}  // namespace invasim::app
