#include "app/resume_options.hpp"

#include <fstream>

#include "core/errors.hpp"

namespace invasim::app {

lua::RunOptions read_resume_options(const std::string& dir) {
  const std::string path = dir + "/resume.txt";
  std::ifstream in(path);
  if (!in)
    fail_input("--resume ", dir, ": cannot read ", path,
               " (is it the run directory of an invasim protocol?)");
  lua::RunOptions options;
  if (!std::getline(in, options.script_path) || options.script_path.empty())
    fail_input("--resume ", dir, ": ", path, " has no protocol path on its first line");
  std::string line;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    if (line.find('=') == std::string::npos)
      fail_input("--resume ", dir, ": ", path, ":", number, ": expected key=value, got '", line,
                 "'");
    options.overrides.push_back(lua::parse_override(line));
  }
  options.out_dir = dir;
  options.resume = true;
  return options;
}

}  // namespace invasim::app
