#include "app/resume_options.hpp"

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "io/regular_file.hpp"

namespace invasim::app {

lua::RunOptions read_resume_options(const std::string& dir) {
  const std::string path = dir + "/resume.txt";
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) require_regular_file(path, "run description");
  std::ifstream in(path);
  if (!in)
    fail_input("--resume ", dir, ": cannot read ", path,
               " (is it the run directory of an invasim protocol?)");
  lua::RunOptions options;
  if (!std::getline(in, options.script_path) || options.script_path.empty())
    fail_input("--resume ", dir, ": ", path, " has no protocol path on its first line");
  std::string line;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;  // # run_id=...: for the reader
    if (line.rfind("--from=", 0) == 0) {
      options.from_dir = line.substr(7);
      if (options.from_dir.empty())
        fail_input("--resume ", dir, ": ", path, ":", number, ": --from= names no run directory");
      continue;
    }
    if (line.find('=') == std::string::npos)
      fail_input("--resume ", dir, ": ", path, ":", number, ": expected key=value, got '", line,
                 "'");
    options.overrides.push_back(parse_override(line));
  }
  options.out_dir = dir;
  options.resume = true;
  return options;
}

}  // namespace invasim::app
