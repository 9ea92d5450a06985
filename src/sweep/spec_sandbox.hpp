#pragma once
// A sweep spec runs as data, not as a program: the table it returns (protocol, set, product,
// ...) is all invasim reads, so its chunk gets an environment with the basic functions that
// compute values (pairs, ipairs, select, tonumber, tostring, type, error, assert, pcall, ...)
// and the string, table, math and utf8 libraries, and nothing that reaches outside the
// process or changes the interpreter: no io, os (os.exit, os.execute), require/package,
// load/loadfile/dofile, debug, collectgarbage, setmetatable/getmetatable. Reading one of
// those is an error naming it ("spec.lua:3: 'os' is not available in a sweep spec ...").
// Specs load as text only, under the stop hook (lua/stop_hook.hpp) and with non-string error
// objects described (lua/error_object.hpp). docs/sweeps.md, "What a spec may do".
#include <string>

struct lua_State;

namespace invasim::sweep {

// Runs the spec file `path` in L (a fresh state with the standard libraries open) in the
// restricted environment and leaves the value it returns on the stack. Any error (syntax,
// runtime, a refused name) is an InputError whose message starts with "spec.lua:LINE: ".
void run_spec_chunk(lua_State* L, const std::string& path);

}  // namespace invasim::sweep
