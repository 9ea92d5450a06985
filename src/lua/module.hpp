#pragma once
// The `invasim` module table. open_invasim is the package.preload loader; it calls one
// open_<part> per binding file, each adding its functions and types to the table on top of
// the stack. A new binding file adds its open_<part> here and in module.cpp.
struct lua_State;

namespace invasim::lua {

// Loader for require("invasim"): pushes the module table (wrap with lua_wrap).
int open_invasim(lua_State* L);

void open_params(lua_State* L);    // invasim.params{...}        (bind_params.cpp)
void open_progress(lua_State* L);  // invasim.Progress{...}      (bind_progress.cpp)
// The engine (types in engine_types.hpp).
void open_system(lua_State* L);      // invasim.System{...}        (bind_system.cpp)
void open_group(lua_State* L);       // Group objects              (bind_group.cpp)
void open_contacts(lua_State* L);    // invasim.Contacts{...}      (bind_contacts.cpp)
void open_walls(lua_State* L);       // invasim.Walls{...}         (bind_walls.cpp)
void open_shape(lua_State* L);       // invasim.Shape{...}         (bind_shape.cpp)
void open_tethers(lua_State* L);     // invasim.Tethers{...}       (bind_tethers.cpp)
void open_method(lua_State* L);      // invasim.Damped/Langevin/Active{...} (bind_method.cpp)
void open_simulation(lua_State* L);  // invasim.Simulation{...}    (bind_simulation.cpp)
void open_dynamics(lua_State* L);    // invasim.Dynamics{...}      (bind_dynamics.cpp)
void open_fire(lua_State* L);        // invasim.Fire{...}          (bind_fire.cpp)
void open_measure(lua_State* L);     // invasim.histogram, block_average (bind_measure.cpp)
void open_correlator(lua_State* L);  // invasim.Correlator{...}    (bind_correlator.cpp)
void open_io(lua_State* L);          // invasim.write_file, make_dirs, Snapshots (bind_io.cpp)
void open_json(lua_State* L);        // invasim.json_encode, read_json (bind_json.cpp)
void open_run_dir(lua_State* L);     // invasim.lock_run_dir, ...  (bind_run_dir.cpp)
void open_checkpoint(
    lua_State* L);  // invasim.save/load_checkpoint, interrupted (bind_checkpoint.cpp)
void open_lipolysis(lua_State* L);    // invasim.Lipolysis{...}  (bind_lipolysis.cpp)
void open_ramp(lua_State* L);         // invasim.ramp{...}          (bind_ramp.cpp)
void open_compression(lua_State* L);  // invasim.compress, rescale  (bind_compression.cpp)
void open_keywords(lua_State* L);     // invasim.keywords(...)      (bind_keywords.cpp)

}  // namespace invasim::lua
