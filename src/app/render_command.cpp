#include "app/render_command.hpp"

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/render_slice.hpp"

namespace invasim::app {

int run_render(const RenderOptions& options, std::ostream& out) {
  // render_snapshot with a picture size: load_snapshot_frame + cut_frame + slice_svg.
  const Frame frame = load_snapshot_frame(options.snapshot);
  Slice slice;
  try {
    slice = cut_frame(frame, options.plane);
  } catch (const InputError& e) {  // e.g. a plane outside the walls: name the snapshot too
    fail_input("'", options.snapshot, "': ", e.what());
  }
  write_file_atomically(options.output, slice_svg(slice, options.size_px));
  const RenderCounts counts = count_shapes(slice);
  out << "render: " << counts.discs << " discs, " << counts.polygons << " polygons -> "
      << options.output << '\n';
  return 0;
}

}  // namespace invasim::app
