#include "targets.hpp"

#include <lua.hpp>

#include <cstdio>
#include <stdexcept>

#include "../io/io_test_support.hpp"
#include "checkpoint/checkpoint_file.hpp"
#include "checkpoint/correlator_sections.hpp"
#include "checkpoint/lua_data.hpp"
#include "checkpoint/state_checkpoint.hpp"
#include "core/params.hpp"
#include "io/crc32.hpp"
#include "io/vtk_format.hpp"
#include "lua/fields.hpp"
#include "lua/lua_state.hpp"
#include "measure/time_correlator.hpp"

namespace invasim::fuzz {

namespace {

// A real protocol state as protocols/lib/resume.lua's serialize writes it.
const char* const kState =
    "{[\"compression\"]={[\"phi\"]=0x1.a3d70a3d70a3dp-1,[\"steps\"]=12},[\"end_step\"]=2400,"
    "[\"rows\"]={[1]={[\"T\"]=0x1.0624dd2f1a9fcp-10,[\"step\"]=1200,[\"ok\"]=true,"
    "[\"name\"]=\"a\\\"b\\\n\\0011\"},[2]={[\"nan\"]=0/0,[\"inf\"]=-math.huge}}}";

// The correlator parameters of the checkpoint seeds (the reader is given the same ones).
TimeCorrelatorParams correlator_params() {
  TimeCorrelatorParams p;
  p.lags = 4;
  p.origin_every = 1;
  return p;
}

std::vector<int> cancer_sites(const System& sys) {
  return sys.sites_of_kind(SiteKind::kCancer);
}

// ---------------------------------------------------------------------------------------------
// checkpoint

std::string checkpoint_bytes(bool tethers, bool correlator, const std::string& extra) {
  const System sys = iotest::sample_system(6);
  CheckpointWriter w;
  write_system(w, sys);
  if (tethers) {
    TetherForce t(0.05);
    iotest::sample_tethers(sys, t);
    write_tethers(w, t);
  }
  if (correlator) {
    TimeCorrelator c(cancer_sites(sys), correlator_params());
    std::vector<Vec3> v(cancer_sites(sys).size(), Vec3(0.1, 0.2, 0.3));
    for (int k = 0; k < 6; ++k) c.add_sample(v.data(), v.data(), v.data());
    write_correlator(w, c);
  }
  w.put_string("extra", extra);
  w.put_string("run.id", "0123456789abcdef");
  return w.bytes();
}

// Sets the length field and the CRC to match the (mutated) bytes.
void fix_checkpoint(std::string& s) {
  if (s.size() < kCheckpointHeaderSize + 4) return;
  const std::uint64_t total = s.size();
  for (int k = 0; k < 8; ++k) s[15 + k] = char((total >> (8 * k)) & 0xFF);
  const std::uint32_t crc = crc32(std::string_view(s).substr(0, s.size() - 4));
  for (int k = 0; k < 4; ++k) s[s.size() - 4 + k] = char((crc >> (8 * k)) & 0xFF);
}

void run_checkpoint(const std::string& input) {
  const CheckpointReader r = CheckpointReader::parse(input, "'fuzz.ckpt'");
  const System sys = read_system(r);
  if (r.has("tethers.a")) {
    TetherForce t(0.05);
    read_tethers(r, sys, t);
  }
  if (r.has("correlator.samples") && !cancer_sites(sys).empty()) {
    TimeCorrelator c(cancer_sites(sys), correlator_params());
    read_correlator(r, c);
    std::vector<Vec3> v(cancer_sites(sys).size(), Vec3(0.1, 0.2, 0.3));
    c.add_sample(v.data(), v.data(), v.data());  // uses the restored state
  }
  if (r.has("extra")) parse_lua_data(r.get_string("extra"), "checkpoint 'fuzz.ckpt': 'extra'");
}

Target checkpoint_target() {
  Target t;
  t.name = "checkpoint";
  t.seeds = {checkpoint_bytes(true, true, kState), checkpoint_bytes(false, false, "{}"),
             checkpoint_bytes(true, false, "{[1]={[1]={[1]={}}}}")};
  t.dictionary = {"system.box.version",
                  "system.topologies.n_vertices",
                  "extra",
                  "{[",
                  "]=",
                  "0x1p+0",
                  "0/0",
                  "math.huge",
                  "\\255",
                  "\\x41"};
  t.fixup = fix_checkpoint;
  t.run = run_checkpoint;
  return t;
}

// ---------------------------------------------------------------------------------------------
// vtk

void run_vtk(const std::string& input) {
  // The same text through each reader: most inputs are one kind, splices mix them.
  try {
    parse_pvd(input, "'fuzz.pvd'");
  } catch (const InputError&) {
  }
  const VtpData vtp = parse_vtp(input, "'fuzz.vtp'");
  try {
    mesh_frame_from_vtp(vtp, "'fuzz.vtp'");
  } catch (const InputError&) {
  }
  cell_frame_from_vtp(vtp, "'fuzz.vtp'");
}

Target vtk_target() {
  Target t;
  t.name = "vtk";
  const Frame frame = frame_from_system(iotest::sample_system(6));
  t.seeds = {adipocytes_vtp_text(frame), spheres_vtp_text(frame),
             pvd_text({{0.0, "snapshots/a_0.vtp"}, {1.5, "snapshots/a_100.vtp"}})};
  t.dictionary = {"<a>",
                  "</a>",
                  "<DataArray ",
                  "</DataArray>",
                  "NumberOfTuples=\"",
                  "NumberOfComponents=\"",
                  "NumberOfPoints=\"",
                  "format=\"ascii\"",
                  "<![CDATA[",
                  "]]>",
                  "&amp;",
                  "<!--",
                  "-->",
                  "<Piece>"};
  t.run = run_vtk;
  return t;
}

// ---------------------------------------------------------------------------------------------
// set

std::vector<Param> declared_params() {
  std::vector<Param> p(6);
  p[0] = {"dt",  ParamType::kNumber,       0.05, 0.05, "tau", "time step",
          false, Range{0, 1, true, false}, {}};
  p[1] = {"steps", ParamType::kInteger,          100LL, 100LL, "", "steps",
          false,   Range{0, 1e18, false, false}, {}};
  p[2] = {"seed", ParamType::kInteger, 1LL, 1LL, "", "seed", false, std::nullopt, {}};
  p[3] = {"flag", ParamType::kBoolean, false, false, "", "a switch", false, std::nullopt, {}};
  p[4] = {"bath", ParamType::kString, std::string("langevin"), std::string("langevin"), "", "bath",
          false,  std::nullopt,       {"langevin", "damped"}};
  p[5] = {"label", ParamType::kString, std::string(""), std::string(""),
          "",      "a name",           false,           std::nullopt,
          {}};
  return p;
}

// One `--set` argument per line, then all of them applied to the declared parameters.
void run_set(const std::string& input) {
  std::vector<Override> overrides;
  std::size_t at = 0;
  while (at <= input.size()) {
    const std::size_t end = std::min(input.find('\n', at), input.size());
    const std::string line = input.substr(at, end - at);
    at = end + 1;
    try {
      overrides.push_back(parse_override(line));
      for (auto type :
           {ParamType::kNumber, ParamType::kInteger, ParamType::kBoolean, ParamType::kString})
        try {
          format_value(parse_value(type, overrides.back().key, overrides.back().text));
        } catch (const InputError&) {
        }
    } catch (const InputError&) {
    }
  }
  std::vector<Param> params = declared_params();
  apply_overrides(params, overrides);
  format_param_table(params);
}

Target set_target() {
  Target t;
  t.name = "set";
  t.seeds = {"dt=0.01\nsteps=200\nseed=7\nflag=yes\nbath=damped\nlabel=run one",
             "steps=9223372036854775807",
             "dt=1e-3",
             "steps=2e5\nflag=off",
             "bath=langevn",
             "seed=-1",
             "label= spaced =value",
             "dt=inf\nsteps=nan"};
  t.dictionary = {"dt=", "steps=", "seed=", "flag=", "bath=", "label=", "\n", "=",
                  " ",   "e308",   "0x10",  "true",  "nan",   "-0",     "+"};
  t.run = run_set;
  return t;
}

// ---------------------------------------------------------------------------------------------
// keywords

// Runs each input as "<Name>\n<keyword table as plain Lua data>": invasim.keywords (Name
// "keywords", the data {spec, opts}) or a constructor of the field tables with the table as its
// keywords. Strings "@System" and "@Group" become a small System and its cancer cells. The
// table is decoded as data (invasim.decode_state), so no input runs code of its own.
const char* const kKeywordDriver = R"lua(
local iv = require("invasim")
local sys = iv.System{ box = { 8, 8, 8 }, seed = 3 }
local placed = sys:place{ cells = { n = 4, diameters = { 0.9, 1.1 }, x = { 1, 7 } } }
local objects = { ["@System"] = sys, ["@Group"] = placed.cells }
local function resolve(t, depth)
  if depth > 20 then return end
  for k, v in pairs(t) do
    if type(v) == "string" and objects[v] then t[k] = objects[v]
    elseif type(v) == "table" then resolve(v, depth + 1) end
  end
end
function __fuzz_keywords(text)
  local name, data = text:match("^([%w_:]+)\n(.*)$")
  if not name then return true end
  local ok, args = pcall(iv.decode_state, data)
  if not ok or type(args) ~= "table" then return true end
  resolve(args, 0)
  local f
  if name == "keywords" then
    if type(args[1]) ~= "table" or type(args[2]) ~= "table" then return true end
    f = function() return iv.keywords("fuzz", args[2], args[1]) end
  elseif name == "Tethers:connect" or name == "Dynamics:pressure_wall" then
    return true
  else
    local ctor = iv[name]
    if type(ctor) ~= "function" then return true end
    f = function() return ctor(args) end
  end
  local ok2, err = pcall(f)
  collectgarbage()
  if ok2 then return true end
  return tostring(err)
end
)lua";

// A Lua error message that a non-project C++ exception produced (lua_wrap copies what()).
bool foreign_exception(const std::string& message) {
  for (const char* p : {"std::", "bad_alloc", "vector::", "basic_string", "unknown C++ exception",
                        "bad_variant_access", "bad_optional_access", "out_of_range"})
    if (message.find(p) != std::string::npos) return true;
  return false;
}

std::string datum_text(const lua::Declaration& f) {
  const std::string type = f.type_text();
  if (type.find("list of 3") != std::string::npos)
    return type.find("boolean") != std::string::npos ? "{[1]=true,[2]=false,[3]=true}"
                                                     : "{[1]=8,[2]=8,[3]=8}";
  if (type.find("Group") != std::string::npos) return "\"@Group\"";
  if (type == "System") return "\"@System\"";
  if (f.default_value) {
    const ParamValue& v = *f.default_value;
    if (const auto* s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
    if (const auto* d = std::get_if<double>(&v)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%a", *d);
      return buf;
    }
    return format_value(v);
  }
  if (!f.choices.empty()) return "\"" + f.choices[0] + "\"";
  if (type == "integer") return "1";
  if (type == "boolean") return "true";
  if (type == "string") return "\"x\"";
  return "0x1p-1";
}

Target keywords_target() {
  Target t;
  t.name = "keywords";
  auto state = std::make_shared<lua::LuaState>();
  state->set_memory_limit(std::size_t(512) << 20);
  state->run_string(kKeywordDriver, "=fuzz_keywords");
  for (const auto& [name, fields] : lua::registered_field_tables()) {
    std::string table = "{";
    for (const auto& f : fields) {
      table += "[\"" + f.name + "\"]=" + datum_text(f) + ",";
      t.dictionary.push_back("[\"" + f.name + "\"]=");
    }
    t.seeds.push_back(name + "\n" + table + "}");
  }
  t.seeds.push_back(
      "keywords\n{[1]={[\"steps\"]={[1]=\"integer\",[\"default\"]=100,[\"range\"]=\"[0, inf)\"},"
      "[\"bath\"]={[1]=\"string\",[\"choices\"]={[1]=\"a\",[2]=\"b\"}},[\"label\"]=\"x\"},"
      "[2]={[\"steps\"]=5,[\"bath\"]=\"a\"}}");
  t.dictionary.insert(t.dictionary.end(), {"{[", "]=", "\"@Group\"", "\"@System\"", "1e308", "-1",
                                           "0/0", "math.huge", "\"(0, inf)\""});
  t.run = [state](const std::string& input) {
    lua_State* L = state->get();
    lua_settop(L, 0);
    lua_getglobal(L, "__fuzz_keywords");
    lua_pushlstring(L, input.data(), input.size());
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
      const std::string message = lua_isstring(L, -1) ? lua_tostring(L, -1) : "?";
      lua_settop(L, 0);
      if (message.find("not enough memory") != std::string::npos) return;  // the Lua limit
      throw std::logic_error("the keyword driver failed: " + message);
    }
    if (lua_type(L, -1) == LUA_TSTRING) {
      const std::string message = lua_tostring(L, -1);
      lua_settop(L, 0);
      if (foreign_exception(message)) throw std::logic_error("not a project error: " + message);
      throw InputError(message);  // a project error, raised in Lua: its kind feeds the corpus
    }
    lua_settop(L, 0);
  };
  return t;
}

}  // namespace

Target make_target(const std::string& name) {
  if (name == "checkpoint") return checkpoint_target();
  if (name == "vtk") return vtk_target();
  if (name == "set") return set_target();
  if (name == "keywords") return keywords_target();
  throw std::invalid_argument("unknown fuzz target '" + name +
                              "' (checkpoint, vtk, set or keywords)");
}

}  // namespace invasim::fuzz
