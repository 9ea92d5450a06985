#pragma once
// `invasim run --resume DIR`: the protocol and parameters of the run in DIR, read from the
// DIR/resume.txt its run directory wrote (protocols/lib/run_dir.lua): the protocol path on the
// first line, then `--from=RUN_DIR` if the run started from another run's compressed tissue,
// then one `key=value` per parameter in --set syntax; lines starting with '#' (the run's
// identity, for the reader) are skipped.
#include <string>

#include "lua/context.hpp"

namespace invasim::app {

// Options that start the same protocol again in DIR with resume set; InputError if DIR holds
// no readable resume.txt (naming the file) or a line is malformed (naming the line).
lua::RunOptions read_resume_options(const std::string& dir);

}  // namespace invasim::app
