#include "app/render_command.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/render_slice.hpp"

namespace invasim::app {

namespace {

// Lower-case extension of a path (".svg", ".png", ...).
std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Single-quotes a string for /bin/sh.
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// PNG through Debian's rsvg-convert (librsvg2-bin): SVG to a temporary file next to the
// output, converted into a second temporary file, renamed over the output at the end.
void write_png(const std::string& svg, const std::string& output) {
  if (std::system("command -v rsvg-convert > /dev/null 2>&1") != 0)
    fail_input("PNG output needs rsvg-convert: apt-get install librsvg2-bin (or write .svg)");
  const std::string svg_tmp = output + ".tmp.svg", png_tmp = output + ".tmp.png";
  write_file_atomically(svg_tmp, svg);
  const int status =
      std::system(("rsvg-convert " + shell_quote(svg_tmp) + " -o " + shell_quote(png_tmp)).c_str());
  std::filesystem::remove(svg_tmp);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::filesystem::remove(png_tmp);
    fail_input("rsvg-convert could not write '", output, "'");
  }
  std::filesystem::rename(png_tmp, output);
}

}  // namespace

int run_render(const RenderOptions& options, std::ostream& out) {
  const std::string ext = extension_of(options.output);
  if (ext != ".svg" && ext != ".png")
    fail_input("-o ", options.output, ": the picture must be a .svg or .png file");
  // render_snapshot with a picture size: load_snapshot_frame + cut_frame + slice_svg.
  const Frame frame = load_snapshot_frame(options.snapshot);
  Slice slice;
  try {
    slice = cut_frame(frame, options.plane);
  } catch (const InputError& e) {  // e.g. a plane outside the walls: name the snapshot too
    fail_input("'", options.snapshot, "': ", e.what());
  }
  const std::string svg = slice_svg(slice, options.size_px);
  if (ext == ".png")
    write_png(svg, options.output);
  else
    write_file_atomically(options.output, svg);
  const RenderCounts counts = count_shapes(slice);
  out << "render: " << counts.discs << " discs, " << counts.polygons << " polygons -> "
      << options.output << '\n';
  return 0;
}

}  // namespace invasim::app
