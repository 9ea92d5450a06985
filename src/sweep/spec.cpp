#include "sweep/spec.hpp"

#include <lua.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <variant>

#include "core/errors.hpp"
#include "core/names.hpp"
#include "io/regular_file.hpp"
#include "lua/lua_state.hpp"
#include "sweep/spec_sandbox.hpp"

namespace invasim::sweep {

namespace fs = std::filesystem;

const Param* find_param(const std::vector<Param>& declared, const std::string& name) {
  for (const auto& p : declared)
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<Param> protocol_params(const std::string& protocol) {
  lua::RunOptions options;
  options.script_path = protocol;
  options.list_params = true;
  lua::LuaState state(options);
  state.run_file(protocol);
  if (!state.context().params)
    fail_input(protocol,
               " declares no parameters (it never calls invasim.params{...}): a sweep "
               "has nothing to vary");
  return *state.context().params;
}

std::string set_text(const Json& value) {
  if (value.is_number_float()) return python_float_repr(value.get<double>());
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

Json to_json(const ParamValue& value) {
  return std::visit([](const auto& v) { return Json(v); }, value);
}

namespace {

// The spec file's lines, to tell the line of a key (a Lua table does not keep it).
class SourceLines {
 public:
  explicit SourceLines(const std::string& path) {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }
  // The first line at or after `from` (1-based) holding `key =` (not `==`), or `from`.
  int find(const std::string& key, int from) const {
    for (int n = std::max(from, 1); n <= static_cast<int>(lines_.size()); ++n) {
      const std::string& line = lines_[n - 1];
      for (auto at = line.find(key); at != std::string::npos; at = line.find(key, at + 1)) {
        const bool word_start =
            at == 0 ||
            !(std::isalnum(static_cast<unsigned char>(line[at - 1])) || line[at - 1] == '_');
        auto after = at + key.size();
        while (after < line.size() && (line[after] == ' ' || line[after] == '\t')) ++after;
        if (word_start && after < line.size() && line[after] == '=' &&
            (after + 1 >= line.size() || line[after + 1] != '='))
          return n;
      }
    }
    return std::max(from, 1);
  }

 private:
  std::vector<std::string> lines_;
};

// Reads and checks the table the spec returns; every error names file:line: key.
class SpecReader {
 public:
  SpecReader(lua_State* L, const std::string& path) : L_(L), path_(path), source_(path) {}

  [[noreturn]] void fail(int line, const std::string& key, const std::string& why) const {
    fail_input(path_, ":", line, ": ", key, ": ", why);
  }

  // The Lua type name of the value at `index`, "integer"/"float" for numbers.
  // "an integer", "a float", "a string", ... : the type of the value at `index` with its article.
  std::string type_at(int index) const {
    if (lua_type(L_, index) == LUA_TNUMBER)
      return lua_isinteger(L_, index) ? "an integer" : "a float";
    return std::string("a ") + luaL_typename(L_, index);
  }

  // String keys of the table at the top, sorted; a non-string key is an error.
  std::vector<std::string> keys(const std::string& where, int line) const {
    std::vector<std::string> names;
    lua_pushnil(L_);
    while (lua_next(L_, -2)) {
      lua_pop(L_, 1);
      if (lua_type(L_, -1) != LUA_TSTRING)
        fail(line, where,
             "expected a table of name = value entries; found a " + type_at(-1) + " key");
      names.emplace_back(lua_tostring(L_, -1));
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  // The value at the top converted to JSON and checked against the parameter `name`.
  Json value(const std::string& key, const std::string& name, int line) const {
    const Param* p = find_param(spec_.declared, name);
    if (!p) {
      std::vector<std::string> names;
      for (const auto& d : spec_.declared) names.push_back(d.name);
      fail(line, key,
           "'" + name + "' is not a parameter of " + spec_.protocol + did_you_mean(name, names) +
               "; declared parameters: " + join_names(names));
    }
    const std::string got = type_at(-1);
    const auto wrong = [&](const std::string& expected) {
      fail(line, key,
           "parameter '" + name + "' is " + expected + "; got " + got +
               (lua_type(L_, -1) == LUA_TNUMBER || lua_type(L_, -1) == LUA_TSTRING
                    ? std::string(" (") + luaL_tolstring(L_, -1, nullptr) + ")"
                    : ""));
    };
    Json out;
    ParamValue checked;
    switch (p->type) {
      case ParamType::kNumber:
        if (lua_type(L_, -1) != LUA_TNUMBER) wrong("a number");
        if (lua_isinteger(L_, -1)) {
          out = static_cast<std::int64_t>(lua_tointeger(L_, -1));
          checked = static_cast<double>(lua_tointeger(L_, -1));
        } else {
          const double d = lua_tonumber(L_, -1);
          if (!std::isfinite(d)) wrong("a finite number");
          out = d;
          checked = d;
        }
        break;
      case ParamType::kInteger:
        if (!lua_isinteger(L_, -1))
          wrong("an integer (write it without a decimal point or exponent)");
        out = static_cast<std::int64_t>(lua_tointeger(L_, -1));
        checked = static_cast<long long>(lua_tointeger(L_, -1));
        break;
      case ParamType::kBoolean:
        if (!lua_isboolean(L_, -1)) wrong("a boolean");
        out = static_cast<bool>(lua_toboolean(L_, -1));
        checked = out.get<bool>();
        break;
      case ParamType::kString:
        if (lua_type(L_, -1) != LUA_TSTRING) wrong("a string");
        out = std::string(lua_tostring(L_, -1));
        checked = out.get<std::string>();
        break;
    }
    if (const std::string why = value_violation(*p, checked); !why.empty())
      fail(line, key, "parameter '" + name + "' " + why);
    return out;
  }

  // A table of name = value (set = {...}) at the top into `out`.
  void parameters(const std::string& where, int line, Json& out) const {
    if (!lua_istable(L_, -1))
      fail(line, where, "expected a table of name = value; got " + type_at(-1));
    for (const auto& name : keys(where, line)) {
      const int at = source_.find(name, line);
      lua_getfield(L_, -1, name.c_str());
      out[name] = value(where + "." + name, name, at);
      lua_pop(L_, 1);
    }
  }

  // The list of values at the top for parameter `name`; with `unique` (a product axis, the
  // seeds) a value given twice is refused: it would be one point twice, merged without a word
  // (1 and 1.0 are two values, as they are two points). A zip column may repeat values.
  std::vector<Json> list(const std::string& key, const std::string& name, int line,
                         bool unique) const {
    if (!lua_istable(L_, -1))
      fail(line, key, "expected a list of values { v1, v2, ... }; got " + type_at(-1));
    const auto n = static_cast<lua_Integer>(lua_rawlen(L_, -1));
    std::size_t entries = 0;
    lua_pushnil(L_);
    while (lua_next(L_, -2)) {
      lua_pop(L_, 1);
      ++entries;
    }
    if (n == 0) fail(line, key, "the list of values is empty");
    if (entries != static_cast<std::size_t>(n))
      fail(line, key,
           "expected a list of values { v1, v2, ... } (no name = value entries, no holes)");
    std::vector<Json> values;
    std::map<std::string, lua_Integer> seen;
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L_, -1, i);
      values.push_back(value(key + "[" + std::to_string(i) + "]", name, line));
      lua_pop(L_, 1);
      const auto [at, fresh] = seen.emplace(values.back().dump(), i);
      if (unique && !fresh)
        fail(line, key, cat("lists ", at->first, " twice (entries ", at->second, " and ", i, ")"));
    }
    return values;
  }

  // name = { values } entries of the table at the top.
  std::vector<Axis> axes(const std::string& where, int line) const {
    if (!lua_istable(L_, -1))
      fail(line, where, "expected a table of name = { values }; got " + type_at(-1));
    std::vector<Axis> out;
    for (const auto& name : keys(where, line)) {
      const int at = source_.find(name, line);
      lua_getfield(L_, -1, name.c_str());
      out.emplace_back(name, list(where + "." + name, name, at, where == "product"));
      lua_pop(L_, 1);
    }
    if (out.empty()) fail(line, where, "names no parameter");
    return out;
  }

  // tiny = { set = { name = value }, take = N }: the CI size (sweep/overrides.hpp applies it).
  void read_tiny(int at) {
    lua_getfield(L_, -1, "tiny");
    if (!lua_istable(L_, -1))
      fail(at, "tiny", "expected { set = { ... }, take = N } (the CI size); got " + type_at(-1));
    for (const auto& key : keys("tiny", at))
      if (key != "set" && key != "take")
        fail(source_.find(key, at), "tiny." + key,
             "unknown key" + did_you_mean(key, {"set", "take"}) + "; tiny has: set, take");
    spec_.has_tiny = true;
    lua_getfield(L_, -1, "take");
    if (!lua_isnil(L_, -1)) {
      if (!lua_isinteger(L_, -1) || lua_tointeger(L_, -1) < 1) {
        const std::string got = type_at(-1);  // before luaL_tolstring pushes the text
        fail(source_.find("take", at), "tiny.take",
             "expected an integer >= 1 (values kept per axis); got " + got + " (" +
                 luaL_tolstring(L_, -1, nullptr) + ")");
      }
      spec_.tiny_take = static_cast<int>(lua_tointeger(L_, -1));
    }
    lua_pop(L_, 1);
    lua_getfield(L_, -1, "set");
    if (!lua_isnil(L_, -1)) parameters("tiny.set", at, spec_.tiny_set);
    lua_pop(L_, 2);
  }

  SweepSpec read() {
    if (!lua_istable(L_, -1))
      fail_input(path_,
                 ": a sweep spec must return a table { protocol = ..., set = ..., product = "
                 "..., zip = ..., seeds = ..., prep = ... }; it returned ",
                 type_at(-1));
    static const std::set<std::string> known = {"protocol", "set",  "product", "zip",
                                                "seeds",    "prep", "tiny"};
    std::map<std::string, int> line;
    for (const auto& key : keys("the spec", 1)) {
      line[key] = source_.find(key, 1);
      if (!known.count(key))
        fail(line[key], key,
             "unknown key" + did_you_mean(key, {known.begin(), known.end()}) +
                 "; a sweep spec has: protocol, set, product, zip, seeds, prep, tiny");
    }
    spec_.path = path_;
    if (!line.count("protocol")) fail_input(path_, ": missing protocol = \"PROTOCOL.lua\"");
    lua_getfield(L_, -1, "protocol");
    if (lua_type(L_, -1) != LUA_TSTRING)
      fail(line["protocol"], "protocol",
           "expected the path of a protocol file; got " + type_at(-1));
    fs::path protocol = lua_tostring(L_, -1);
    lua_pop(L_, 1);
    if (protocol.is_relative()) protocol = fs::absolute(path_).parent_path() / protocol;
    protocol = fs::weakly_canonical(protocol);
    if (!fs::is_regular_file(protocol))
      fail(line["protocol"], "protocol",
           "no file " + protocol.string() +
               " (a relative path is relative to the spec's directory)");
    spec_.protocol = protocol.string();
    spec_.declared = protocol_params(spec_.protocol);

    std::map<std::string, std::string> owner;  // parameter -> the key that gives it
    const auto claim = [&](const std::string& name, const std::string& key, int at) {
      if (auto it = owner.find(name); it != owner.end())
        fail(at, key, "parameter '" + name + "' is already given by " + it->second);
      owner[name] = key;
    };
    if (line.count("set")) {
      lua_getfield(L_, -1, "set");
      parameters("set", line["set"], spec_.fixed);
      lua_pop(L_, 1);
      for (const auto& item : spec_.fixed.items())
        claim(item.key(), "set." + item.key(), line["set"]);
    }
    if (line.count("product")) {
      lua_getfield(L_, -1, "product");
      spec_.product = axes("product", line["product"]);
      lua_pop(L_, 1);
      for (const auto& [name, values] : spec_.product)
        claim(name, "product." + name, source_.find(name, line["product"]));
    }
    if (line.count("zip")) {
      lua_getfield(L_, -1, "zip");
      const int at = line["zip"];
      if (!lua_istable(L_, -1))
        fail(at, "zip", "expected a list of groups { { a = {...}, b = {...} }, ... }");
      const auto n = static_cast<lua_Integer>(lua_rawlen(L_, -1));
      if (n == 0) fail(at, "zip", "expected a list of groups { { a = {...}, b = {...} }, ... }");
      for (lua_Integer g = 1; g <= n; ++g) {
        lua_rawgeti(L_, -1, g);
        const std::string where = "zip[" + std::to_string(g) + "]";
        auto group = axes(where, at);
        for (const auto& [name, values] : group) {
          claim(name, where + "." + name, source_.find(name, at));
          if (values.size() != group.front().second.size())
            fail(source_.find(name, at), where + "." + name,
                 "zipped lists must have equal lengths: " + group.front().first + " has " +
                     std::to_string(group.front().second.size()) + " values, " + name + " has " +
                     std::to_string(values.size()));
        }
        spec_.zips.push_back(std::move(group));
        lua_pop(L_, 1);
      }
      lua_pop(L_, 1);
    }
    if (line.count("seeds")) {
      if (!find_param(spec_.declared, "seed"))
        fail(line["seeds"], "seeds",
             spec_.protocol + " declares no parameter 'seed' to replicate over");
      claim("seed", "seeds", line["seeds"]);
      lua_getfield(L_, -1, "seeds");
      spec_.product.emplace_back("seed", list("seeds", "seed", line["seeds"], true));
      lua_pop(L_, 1);
    } else if (const Param* seed = find_param(spec_.declared, "seed");
               seed && !owner.count("seed")) {
      spec_.fixed["seed"] = to_json(seed->default_value);  // explicit in every point
    }
    if (line.count("prep")) {
      const int at = line["prep"];
      lua_getfield(L_, -1, "prep");
      if (!lua_istable(L_, -1))
        fail(at, "prep", "expected { set = { ... } } (the preparation's own parameters)");
      for (const auto& key : keys("prep", at))
        if (key != "set") fail(source_.find(key, at), "prep." + key, "unknown key; prep has: set");
      spec_.has_prep = true;
      spec_.prep_set = spec_.fixed;
      lua_getfield(L_, -1, "set");
      if (!lua_isnil(L_, -1)) {
        parameters("prep.set", at, spec_.prep_set);
        parameters("prep.set", at, spec_.prep_own);
      }
      lua_pop(L_, 2);
    }
    if (line.count("tiny")) read_tiny(line["tiny"]);
    return spec_;
  }

 private:
  lua_State* L_;
  std::string path_;
  SourceLines source_;
  SweepSpec spec_;
};

}  // namespace

std::vector<Json> SweepSpec::points() const {
  std::vector<std::vector<Axis>> groups;  // each group's axes move together
  for (const auto& axis : product) groups.push_back({axis});
  for (const auto& zip : zips) groups.push_back(zip);
  std::vector<Json> out = {fixed};
  for (const auto& group : groups) {
    std::vector<Json> next;
    for (const auto& point : out)
      for (std::size_t i = 0; i < group.front().second.size(); ++i) {
        Json p = point;
        for (const auto& [name, values] : group) p[name] = values[i];
        next.push_back(std::move(p));
      }
    out = std::move(next);
  }
  return out;
}

std::size_t SweepSpec::point_count() const {
  std::size_t count = 1;
  const auto times = [&count](std::size_t n) {
    if (n != 0 && count > std::numeric_limits<std::size_t>::max() / n)
      count = std::numeric_limits<std::size_t>::max();
    else
      count *= n;
  };
  for (const auto& axis : product) times(axis.second.size());
  for (const auto& zip : zips) times(zip.front().second.size());
  return count;
}

std::string SweepSpec::point_count_factors() const {
  std::string text;
  const auto factor = [&text](const std::string& name, std::size_t n) {
    text += (text.empty() ? "" : " x ") + name + ": " + std::to_string(n);
  };
  for (const auto& [name, values] : product) factor(name, values.size());
  for (const auto& zip : zips) {
    std::string names;
    for (const auto& axis : zip) names += (names.empty() ? "" : "+") + axis.first;
    factor(names, zip.front().second.size());
  }
  return text.empty() ? "no axes" : text;
}

SweepSpec load_spec(const std::string& path) {
  if (!fs::exists(path)) fail_input("sweep spec ", path, ": no such file");
  require_regular_file(path, "sweep spec");  // a FIFO would block the reader
  std::unique_ptr<lua_State, decltype(&lua_close)> state(luaL_newstate(), &lua_close);
  lua_State* L = state.get();
  luaL_openlibs(L);
  run_spec_chunk(L, path);  // data only: sweep/spec_sandbox.hpp
  return SpecReader(L, path).read();
}

}  // namespace invasim::sweep
