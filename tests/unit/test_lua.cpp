// Tests of the Lua layer foundation: keyword tables, parameters and overrides, the progress
// reporter, and the binding pattern (lua_wrap, check<T>, __gc).
#include <lua.hpp>

#include <catch2/catch.hpp>
#include <limits>
#include <memory>
#include <regex>
#include <sstream>

#include "core/errors.hpp"
#include "core/params.hpp"
#include "core/progress.hpp"
#include "lua/binding.hpp"
#include "lua/declaration.hpp"
#include "lua/fields.hpp"
#include "lua/kwargs.hpp"
#include "lua/lua_state.hpp"

using namespace invasim;
using namespace invasim::lua;

namespace {

// Evaluates `return <expression>` and leaves the value on top of the stack.
void eval(lua_State* L, const std::string& expression) {
  const std::string code = "return " + expression;
  REQUIRE(luaL_dostring(L, code.c_str()) == LUA_OK);
}

// Reads the invasim.params entry `entry` (Lua source) of parameter `name` as invasim.params does.
Param declare(lua_State* L, const std::string& name, const std::string& entry) {
  eval(L, entry);
  const Declaration d =
      read_declaration(L, -1, "params: parameter '" + name + "'", name, DeclarationUse::kParameter);
  lua_pop(L, 1);
  return d.to_param();
}

// A small bound type for the binding tests.
struct Widget {
  static inline int alive = 0;
  int size;
  explicit Widget(int s) : size(s) { ++alive; }
  ~Widget() { --alive; }
};

// Counts destructions of objects alive in a throwing binding function.
struct Guard {
  static inline int destroyed = 0;
  ~Guard() { ++destroyed; }
};

}  // namespace

namespace invasim::lua {
template <>
struct LuaType<Widget> {
  static constexpr const char* name = "Widget";
  static constexpr const char* metatable = "invasim.test.Widget";
  static std::string describe(const Widget& w) { return "Widget(" + std::to_string(w.size) + ")"; }
};
}  // namespace invasim::lua

namespace {

int l_widget(lua_State* L) {
  Kwargs kw(L, 1, "Widget");
  const int size = kw.integer<int>("size", Range::positive());
  kw.finish();
  push(L, std::make_shared<Widget>(size));
  return 1;
}

int l_widget_size(lua_State* L) {
  lua_pushinteger(L, check<Widget>(L, 1).size);
  return 1;
}

int l_throw_input(lua_State*) {
  Guard guard;
  std::string alive = "a C++ object with a destructor";
  throw InputError("boom");
}

int l_throw_other(lua_State*) {
  throw 42;
}

int l_throw_raised(lua_State*) {
  throw LuaRaised("elsewhere.lua:7: callback failed");
}

// A state with the test functions as globals.
void install_test_functions(lua_State* L) {
  const luaL_Reg methods[] = {{"size", &lua_wrap<&l_widget_size>}, {nullptr, nullptr}};
  define_type<Widget>(L, methods);
  lua_register(L, "Widget", &lua_wrap<&l_widget>);
  lua_register(L, "throw_input", &lua_wrap<&l_throw_input>);
  lua_register(L, "throw_other", &lua_wrap<&l_throw_other>);
  lua_register(L, "throw_raised", &lua_wrap<&l_throw_raised>);
}

std::string script_error(LuaState& state, const std::string& code) {
  try {
    state.run_string(code, "@test.lua");
  } catch (const ScriptError& e) {
    return e.what();
  }
  return "(no error)";
}

// A declared parameter with its default as value (no range, no choices).
Param declared(const std::string& name, ParamType type, const ParamValue& value,
               const std::string& unit, const std::string& help) {
  Param p;
  p.name = name;
  p.type = type;
  p.default_value = value;
  p.value = value;
  p.unit = unit;
  p.help = help;
  return p;
}

}  // namespace

TEST_CASE("Kwargs reads typed keys with defaults", "[lua][kwargs]") {
  LuaState state;
  lua_State* L = state.get();
  eval(L,
       "{box = {70, 60, 50}, periodic = {false, true, true}, seed = 2e5, dt = 0.5, "
       "name = 'x', on = true, mode = 'fast'}");
  Kwargs kw(L, -1, "System");
  CHECK(kw.number_list("box", 3) == std::vector<double>{70, 60, 50});
  CHECK(*kw.maybe_boolean_list("periodic", 3) == std::vector<bool>{false, true, true});
  CHECK(kw.integer<long long>("seed", Range{}) == 200000);  // integral floats are integers
  CHECK(kw.number("dt", Range::positive()) == 0.5);
  CHECK(kw.string("name") == "x");
  CHECK(kw.boolean("on"));
  CHECK(std::get<std::string>(*kw.declared(
            field_declaration("mode", {"string"}, std::nullopt, "", "", {"fast", "slow"}), true)) ==
        "fast");
  CHECK(kw.number("absent", 3.0) == 3.0);
  CHECK(kw.integer<int>("absent_int", 4, Range{}) == 4);
  CHECK_FALSE(kw.maybe_string("nothing"));
  CHECK_NOTHROW(kw.finish());
  CHECK(lua_gettop(L) == 1);  // getters leave the stack as they found it
}

TEST_CASE("Kwargs errors name the owner, the key and the valid keys", "[lua][kwargs]") {
  LuaState state;
  lua_State* L = state.get();

  SECTION("unknown key") {
    eval(L, "{bxo = {1, 2, 3}, seed = 1}");
    Kwargs kw(L, -1, "System");
    kw.maybe_number_list("box", 3);
    kw.maybe_boolean_list("periodic", 3);
    kw.integer<long long>("seed", Range{});
    CHECK_THROWS_WITH(kw.finish(),
                      "System: unknown key 'bxo' (did you mean 'box'?); valid "
                      "keys: box, periodic, seed");
  }
  SECTION("several unknown keys") {
    eval(L, "{zz = 1, aa = 2}");
    Kwargs kw(L, -1, "System");
    kw.maybe_integer<long long>("seed", Range{});
    CHECK_THROWS_WITH(kw.finish(), "System: unknown keys 'aa', 'zz'; valid keys: seed");
  }
  SECTION("wrong type") {
    eval(L, "{seed = 'x'}");
    Kwargs kw(L, -1, "System");
    CHECK_THROWS_WITH(kw.integer<long long>("seed", Range{}),
                      "System: key 'seed' must be an integer, got string");
  }
  SECTION("fractional integer") {
    eval(L, "{n = 1.5}");
    Kwargs kw(L, -1, "Spheres");
    CHECK_THROWS_WITH(kw.integer<int>("n", Range::non_negative()),
                      "Spheres: key 'n' must be an integer, got 1.5 (allowed: in [0, 2147483647])");
  }
  SECTION("out of range") {
    eval(L, "{dt = -1, phi = 2}");
    Kwargs kw(L, -1, "Langevin");
    CHECK_THROWS_WITH(kw.number("dt", Range::positive()),
                      "Langevin: key 'dt' = -1 is out of range (must be > 0)");
    CHECK_THROWS_WITH(kw.number("phi", Range::between(0, 1)),
                      "Langevin: key 'phi' = 2 is out of range (must be in [0, 1])");
  }
  SECTION("missing required key") {
    eval(L, "{}");
    Kwargs kw(L, -1, "Langevin");
    CHECK_THROWS_WITH(kw.number("T"), "Langevin: missing required key 'T' (a number)");
  }
  SECTION("not a table") {
    eval(L, "5");
    CHECK_THROWS_WITH(Kwargs(L, -1, "System"),
                      "System: expected a keyword table, as in "
                      "System{key = value, ...}; got number");
  }
  SECTION("positional value") {
    eval(L, "{3, seed = 1}");
    Kwargs kw(L, -1, "System");
    kw.integer<long long>("seed", Range{});
    CHECK_THROWS_WITH(kw.finish(),
                      "System: unexpected positional value [1]; write key = value "
                      "(valid keys: seed)");
  }
  SECTION("list of the wrong length or element type") {
    eval(L, "{box = {1, 2}, box2 = {1, 'a', 3}}");
    Kwargs kw(L, -1, "System");
    CHECK_THROWS_WITH(kw.number_list("box", 3),
                      "System: key 'box' must be a list of 3 numbers, got a table of length 2");
    CHECK_THROWS_WITH(kw.number_list("box2", 3),
                      "System: key 'box2[2]' must be a number, got "
                      "string");
  }
  SECTION("choice") {
    eval(L, "{mode = 'fsat'}");
    Kwargs kw(L, -1, "Dynamics");
    CHECK_THROWS_WITH(
        kw.declared(field_declaration("mode", {"string"}, std::nullopt, "", "", {"fast", "slow"}),
                    true),
        "Dynamics: key 'mode' must be one of: fast, slow; got 'fsat' (did you "
        "mean 'fast'?)");
  }
  SECTION("nested table") {
    eval(L, "{cohesion = {beta = 0.1, alfa = 0.2}}");
    Kwargs kw(L, -1, "contacts");
    auto sub = kw.maybe_table("cohesion");
    REQUIRE(sub);
    CHECK(sub->number("beta") == 0.1);
    sub->maybe_number("alpha");
    CHECK_THROWS_WITH(sub->finish(),
                      "contacts.cohesion: unknown key 'alfa' (did you mean "
                      "'alpha'?); valid keys: alpha, beta");
  }
  SECTION("non-finite numbers") {
    eval(L, "{x = math.huge}");
    Kwargs kw(L, -1, "System");
    CHECK_THROWS_WITH(kw.number("x"), "System: key 'x' must be a finite number, got inf");
  }
}

// Integers are checked on the lua_Integer (or the float) before they are
// narrowed to the C++ type: 2^32 + 5 used to become 5 in an int, 1e12 a negative int.
TEST_CASE("Kwargs integers are range-checked before narrowing", "[lua][kwargs]") {
  LuaState state;
  lua_State* L = state.get();
  eval(L,
       "{big = 2^32 + 5, bigi = 4294967301, tera = 1e12, huge = 1e300, neg = -3, half = 2.5, "
       "inf = 1/0, ok = 7.0, max_int = 2147483647}");
  Kwargs kw(L, -1, "place.cells");
  CHECK_THROWS_WITH(kw.integer<int>("big", Range::non_negative()),
                    "place.cells: key 'big' = 4294967301 is out of range (must be in [0, "
                    "2147483647])");
  CHECK_THROWS_WITH(kw.integer<int>("bigi", Range::non_negative()),
                    "place.cells: key 'bigi' = 4294967301 is out of range (must be in [0, "
                    "2147483647])");
  CHECK_THROWS_WITH(kw.integer<int>("tera", Range::non_negative()),
                    "place.cells: key 'tera' = 1e+12 is out of range (must be in [0, "
                    "2147483647])");
  CHECK(kw.integer<long long>("tera", Range::non_negative()) == 1000000000000LL);
  CHECK_THROWS_WITH(kw.integer<std::size_t>("huge", Range::at_least(1)),
                    "place.cells: key 'huge' = 1e+300 is out of range (must be >= 1)");
  CHECK_THROWS_WITH(kw.integer<std::size_t>("neg", Range{}),
                    "place.cells: key 'neg' = -3 is out of range (must be >= 0)");
  CHECK_THROWS_WITH(kw.integer<std::uint64_t>("half", Range::at_least(1)),
                    "place.cells: key 'half' must be an integer, got 2.5 (allowed: >= 1)");
  CHECK_THROWS_WITH(kw.integer<int>("inf", Range::at_least(1)),
                    Catch::Matchers::StartsWith("place.cells: key 'inf' must be an integer, got "));
  CHECK(kw.integer<int>("ok", Range::at_least(1)) == 7);
  CHECK(kw.integer<int>("max_int", Range::non_negative()) == 2147483647);
  CHECK(kw.maybe_integer<int>("absent", Range::non_negative()) == std::nullopt);
  // Open and fractional bounds of a Range become the integers inside them.
  CHECK(IntegerBounds::of<int>(Range::positive()).lo == 1);
  CHECK(IntegerBounds::of<int>(Range::between(0.5, 4.5)).describe() == "in [1, 4]");
  CHECK(IntegerBounds::of<std::uint64_t>(Range{}).describe() == ">= 0");
  CHECK(IntegerBounds::of<long long>(Range{}).describe() == "any integer");
}

TEST_CASE("parse_value converts override text to the declared type", "[lua][params]") {
  CHECK(std::get<double>(parse_value(ParamType::kNumber, "x", "2.5")) == 2.5);
  CHECK(std::get<double>(parse_value(ParamType::kNumber, "x", "1e-3")) == 1e-3);
  CHECK(std::get<long long>(parse_value(ParamType::kInteger, "n", "42")) == 42);
  CHECK(std::get<long long>(parse_value(ParamType::kInteger, "n", "2e5")) == 200000);
  CHECK(std::get<long long>(parse_value(ParamType::kInteger, "n", "-3")) == -3);
  CHECK(std::get<bool>(parse_value(ParamType::kBoolean, "b", "yes")));
  CHECK_FALSE(std::get<bool>(parse_value(ParamType::kBoolean, "b", "False")));
  CHECK(std::get<std::string>(parse_value(ParamType::kString, "s", "a b")) == "a b");
  CHECK_THROWS_WITH(parse_value(ParamType::kNumber, "phi", "abc"),
                    "parameter 'phi' is a number; cannot parse 'abc'");
  CHECK_THROWS_WITH(parse_value(ParamType::kNumber, "phi", "nan"),
                    "parameter 'phi' is a number; cannot parse 'nan'");
  // Infinities are numbers (the declared range decides whether they are allowed).
  CHECK(std::get<double>(parse_value(ParamType::kNumber, "tau_p", "inf")) ==
        std::numeric_limits<double>::infinity());
  CHECK(std::get<double>(parse_value(ParamType::kNumber, "x", "-inf")) ==
        -std::numeric_limits<double>::infinity());
  CHECK(std::get<double>(parse_value(ParamType::kNumber, "x", "+inf")) ==
        std::numeric_limits<double>::infinity());
  CHECK_THROWS_AS(parse_value(ParamType::kInteger, "n", "1.5"), InputError);
  CHECK_THROWS_AS(parse_value(ParamType::kBoolean, "b", "maybe"), InputError);
  CHECK_THROWS_AS(parse_value(ParamType::kNumber, "x", ""), InputError);
}

TEST_CASE("error messages show a value's control characters escaped", "[lua][params]") {
  // A NUL byte does not end the message; an escape sequence does not reach the terminal.
  CHECK_THROWS_WITH(parse_value(ParamType::kNumber, "phi", std::string("1\0 2", 4)),
                    "parameter 'phi' is a number; cannot parse '1\\x00 2'");
  CHECK_THROWS_WITH(parse_value(ParamType::kNumber, "phi", "\x1b[31m\x7f"),
                    "parameter 'phi' is a number; cannot parse '\\x1b[31m\\x7f'");
  CHECK(printable_message("two\nlines\tand a tab") == "two\nlines\tand a tab");
}

TEST_CASE("apply_overrides: undeclared keys, duplicates and --seed", "[lua][params]") {
  std::vector<Param> params = {
      declared("n", ParamType::kInteger, 5LL, "cells", "number"),
      declared("phi", ParamType::kNumber, 0.5, "", "fraction"),
  };
  SECTION("applied") {
    apply_overrides(params, {parse_override("phi=0.75"), parse_override("n=8")});
    CHECK(std::get<double>(params[1].value) == 0.75);
    CHECK(std::get<long long>(params[0].value) == 8);
    CHECK(params[0].overridden);
  }
  SECTION("undeclared") {
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("ph=1")}),
                      "--set ph=1: 'ph' is not a parameter of this protocol (did you mean "
                      "'phi'?); declared parameters: n, phi");
  }
  SECTION("unparsable") {
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("phi=x")}),
                      "--set phi=x: parameter 'phi' is a number; cannot parse 'x'");
  }
  SECTION("numbers the parameter's type cannot hold, each with its own hint") {
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("n=2.5")}),
                      Catch::Contains("cannot parse '2.5' (to accept fractions, write its default "
                                      "with a decimal point in the protocol: 5.0)"));
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("n=9223372036854775808")}),
                      Catch::Contains("(beyond the 64-bit integers"));
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("phi=1e-400")}),
                      Catch::Contains("'1e-400' is beyond the range of a double"));
  }
  SECTION("twice") {
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("n=1"), parse_override("n=2")}),
                      "parameter 'n' is set twice on the command line (--set n=1 and --set n=2)");
  }
  SECTION("--seed without a seed parameter") {
    CHECK_THROWS_WITH(apply_overrides(params, {Override{"seed", "3", true}}),
                      "--seed: the protocol declares no parameter 'seed'; declared parameters: "
                      "n, phi");
  }
  SECTION("malformed --set") {
    CHECK_THROWS_WITH(parse_override("phi"), "--set expects key=value, got 'phi'");
  }
}

TEST_CASE("invasim.params declares, overrides and protects parameters", "[lua][params]") {
  RunOptions options;
  options.overrides = {parse_override("n=7"), parse_override("x=0.25"), parse_override("flag=true"),
                       parse_override("name=hello")};
  options.seed = "11";
  LuaState state(options);
  state.run_string(R"lua(
    local iv = require("invasim")
    local p = iv.params{ n = {5, unit = "cells", help = "count"}, x = 0.5, flag = false,
                         name = "abc", seed = 1, steps = {2e5, type = "integer"} }
    assert(p.n == 7 and math.type(p.n) == "integer")
    assert(p.x == 0.25 and math.type(p.x) == "float")
    assert(p.flag == true and p.name == "hello" and p.seed == 11)
    assert(p.steps == 200000 and math.type(p.steps) == "integer")
    local ok, err = pcall(function() return p.nn end)
    assert(not ok and err:find("no parameter 'nn'", 1, true), err)
    ok, err = pcall(function() p.n = 1 end)
    assert(not ok and err:find("read-only", 1, true), err)
    local count = 0
    for k, v in pairs(p) do count = count + 1 end
    assert(count == 6)
  )lua");
  const auto& params = *state.context().params;
  REQUIRE(params.size() == 6);
  CHECK(params[1].name == "n");
  CHECK(params[1].unit == "cells");
  CHECK(params[1].help == "count");
  const std::string table = format_param_table(params);
  CHECK(std::regex_search(table, std::regex("\n  n +integer +5 +7 +cells +count\n")));
}

TEST_CASE("invasim.params errors", "[lua][params]") {
  LuaState state;
  CHECK(script_error(state, "local iv = require('invasim')\niv.params{x = {unit = 'm'}}") ==
        "test.lua:2: params: parameter 'x' has no default; write name = default or name = "
        "{default, unit = ..., help = ...}");
  CHECK(script_error(state, "require('invasim').params{x = {1, unti = 'm'}}") ==
        "test.lua:1: params: parameter 'x': unknown key 'unti' (did you mean 'unit'?); valid "
        "keys: choices, help, range, type, unit");
  CHECK(script_error(state, "require('invasim').params{x = {1.5, type = 'integer'}}") ==
        "test.lua:1: params: parameter 'x' is declared an integer but its default 1.5 is not");
}

TEST_CASE("parse_range reads interval notation", "[lua][params]") {
  const Range half_open = parse_range("x", "[0, 1)");
  CHECK(half_open.contains(0.0));
  CHECK(half_open.contains(0.999));
  CHECK_FALSE(half_open.contains(1.0));
  CHECK_FALSE(half_open.contains(-1e-12));
  CHECK(half_open.notation() == "[0, 1)");
  const Range positive = parse_range("dt", " ( 0 ,inf ) ");
  CHECK_FALSE(positive.contains(0.0));
  CHECK(positive.contains(1e-300));
  CHECK(positive.contains(1e300));
  CHECK(positive.notation() == "(0, inf)");
  CHECK(parse_range("x", "(-inf, 2.5e-3]").notation() == "(-inf, 0.0025]");
  CHECK(parse_range("x", "(-inf, +inf)").contains(-1e300));
  CHECK(parse_range("n", "[1, 1]").contains(1.0));
  const std::string form =
      "is not in interval notation: write \"[lo, hi]\" with [ ] inclusive, ( ) exclusive and inf "
      "for no bound, e.g. \"(0, inf)\"";
  CHECK_THROWS_WITH(parse_range("x", "0, 1"), "params: parameter 'x': range '0, 1' " + form);
  CHECK_THROWS_WITH(parse_range("x", "[0; 1]"), "params: parameter 'x': range '[0; 1]' " + form);
  CHECK_THROWS_WITH(parse_range("x", "[0, 1, 2]"), Catch::Contains("interval notation"));
  CHECK_THROWS_WITH(parse_range("x", "[a, 1]"), Catch::Contains("interval notation"));
  CHECK_THROWS_WITH(parse_range("x", "[0, nan]"), Catch::Contains("interval notation"));
  CHECK_THROWS_WITH(parse_range("x", "[0,]"), Catch::Contains("interval notation"));
  CHECK_THROWS_WITH(parse_range("x", ""), Catch::Contains("interval notation"));
  CHECK_THROWS_WITH(parse_range("x", "[1, 0]"),
                    "params: parameter 'x': range '[1, 0]' is empty: no value lies in it");
  CHECK_THROWS_WITH(parse_range("x", "(1, 1]"), Catch::Contains("is empty"));
  CHECK_THROWS_WITH(parse_range("x", "[inf, inf]"), Catch::Contains("is empty"));
}

TEST_CASE("ranges and choices refuse overrides and defaults outside them", "[lua][params]") {
  LuaState state;
  lua_State* L = state.get();
  const Param dt =
      declare(L, "dt", R"lua({0.05, range = "(0, inf)", unit = "tau", help = "time step"})lua");
  const Param every = declare(L, "every", R"lua({1000, range = "[1, inf)", help = "sampling"})lua");
  const Param seed = declare(L, "seed", R"lua({1, range = "[0, inf)", help = "seed"})lua");
  const Param system =
      declare(L, "system",
              R"lua({"reduced", choices = {"reduced", "paper", "large"}, help = "preset"})lua");
  std::vector<Param> params = {dt, every, seed, system};

  SECTION("inside") {
    apply_overrides(params, {parse_override("dt=1e-3"), parse_override("every=1"),
                             parse_override("system=paper"), Override{"seed", "0", true}});
    CHECK(std::get<double>(params[0].value) == 1e-3);
    CHECK(std::get<std::string>(params[3].value) == "paper");
  }
  SECTION("outside, naming the override, the parameter, the range and the value") {
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("dt=0")}),
                      "--set dt=0: parameter 'dt' must be in (0, inf); got 0");
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("dt=-1e-3")}),
                      "--set dt=-1e-3: parameter 'dt' must be in (0, inf); got -0.001");
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("every=0")}),
                      "--set every=0: parameter 'every' must be in [1, inf); got 0");
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("every=-1")}),
                      "--set every=-1: parameter 'every' must be in [1, inf); got -1");
    CHECK_THROWS_WITH(apply_overrides(params, {Override{"seed", "-2", true}}),
                      "--seed -2: parameter 'seed' must be in [0, inf); got -2");
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("system=huge")}),
                      "--set system=huge: parameter 'system' must be one of large, paper, "
                      "reduced; got 'huge'");
    CHECK_THROWS_WITH(apply_overrides(params, {parse_override("system=paer")}),
                      "--set system=paer: parameter 'system' must be one of large, paper, "
                      "reduced; got 'paer' (did you mean 'paper'?)");
  }
  SECTION("a default outside its own range") {
    CHECK_THROWS_WITH(declare(L, "dt", R"lua({0.0, range = "(0, inf)"})lua"),
                      "params: parameter 'dt' must be in (0, inf); its default is 0");
    CHECK_THROWS_WITH(
        declare(L, "system", R"lua({"medium", choices = {"reduced", "paper", "large"}})lua"),
        "params: parameter 'system' must be one of large, paper, reduced; its "
        "default is 'medium'");
  }
  SECTION("a parameter's type is one of the four plain ones, and only those are suggested") {
    CHECK_THROWS_WITH(declare(L, "x", R"lua({1, type = "tabel"})lua"),
                      "params: parameter 'x': unknown type 'tabel'; a type is one of boolean, "
                      "integer, number, string");
    CHECK_THROWS_WITH(declare(L, "x", R"lua({1, type = "nubmer"})lua"),
                      "params: parameter 'x': unknown type 'nubmer' (did you mean 'number'?); a "
                      "type is one of boolean, integer, number, string");
  }
  SECTION("a range on a string, choices on a number") {
    CHECK_THROWS_WITH(declare(L, "system", R"lua({"reduced", range = "[0, 1]"})lua"),
                      "params: parameter 'system' is a string: a range applies to number and "
                      "integer parameters only");
    CHECK_THROWS_WITH(declare(L, "dt", R"lua({0.05, choices = {"a"}})lua"),
                      "params: parameter 'dt' is a number: choices apply to string parameters "
                      "only");
  }
  SECTION("the listing shows the range or the choices") {
    params.push_back(declared("flag", ParamType::kBoolean, false, "", "a switch"));
    const std::string table = format_param_table(params);
    CHECK(std::regex_search(table,
                            std::regex("\n  dt +number +0.05 +\\(0, inf\\) +tau +time step\n")));
    CHECK(std::regex_search(table,
                            std::regex("\n  every +integer +1000 +\\[1, inf\\) +- +sampling\n")));
    CHECK(std::regex_search(
        table,
        std::regex("\n  system +string +\"reduced\" +\\{large, paper, reduced\\} +- +preset\n")));
    CHECK(std::regex_search(table, std::regex("\n  flag +boolean +false +- +- +a switch\n")));
    CHECK(table.find("  name ") == 0);
    CHECK(table.find(" range ") != std::string::npos);
  }
}

TEST_CASE("invasim.params reads range and choices and checks them first", "[lua][params]") {
  SECTION("declaration errors") {
    LuaState state;
    CHECK(script_error(state,
                       "local iv = require('invasim')\n"
                       "iv.params{dt = {0.0, range = '(0, inf)'}}") ==
          "test.lua:2: params: parameter 'dt' must be in (0, inf); its default is 0");
    CHECK(script_error(state, "require('invasim').params{n = {-1, range = '[0, inf)'}}") ==
          "test.lua:1: params: parameter 'n' must be in [0, inf); its default is -1");
    CHECK(script_error(state, "require('invasim').params{s = {'x', choices = {'a', 'b'}}}") ==
          "test.lua:1: params: parameter 's' must be one of a, b; its default is 'x'");
    CHECK(script_error(state, "require('invasim').params{b = {true, range = '[0, 1]'}}") ==
          "test.lua:1: params: parameter 'b' is a boolean: a range applies to number and "
          "integer parameters only");
    CHECK(script_error(state, "require('invasim').params{x = {1.0, range = 5}}") ==
          "test.lua:1: params: parameter 'x': key 'range' must be a string, got 5");
    CHECK(script_error(state, "require('invasim').params{x = {1.0, range = '0 < x'}}") ==
          "test.lua:1: params: parameter 'x': range '0 < x' is not in interval notation: write "
          "\"[lo, hi]\" with [ ] inclusive, ( ) exclusive and inf for no bound, e.g. \"(0, "
          "inf)\"");
    const std::string list_error =
        "test.lua:1: params: parameter 's': key 'choices' must be a list of strings, as in "
        "choices = {\"a\", \"b\"}";
    CHECK(script_error(state, "require('invasim').params{s = {'a', choices = 'a'}}") == list_error);
    CHECK(script_error(state, "require('invasim').params{s = {'a', choices = {'a', 2}}}") ==
          list_error);
    CHECK(script_error(state, "require('invasim').params{s = {'a', choices = {}}}") == list_error);
    CHECK(script_error(state, "require('invasim').params{s = {'a', choices = {'a', x = 'b'}}}") ==
          list_error);
  }
  SECTION("an override out of range stops the script at invasim.params") {
    RunOptions options;
    options.overrides = {parse_override("dt=0")};
    LuaState state(options);
    CHECK(script_error(state,
                       "ran_before = true\n"
                       "local p = require('invasim').params{\n"
                       "  dt = {0.05, range = '(0, inf)'}}\n"
                       "ran_after = true") ==
          "test.lua:2: --set dt=0: parameter 'dt' must be in (0, inf); got 0");
    lua_getglobal(state.get(), "ran_after");
    CHECK(lua_isnil(state.get(), -1));
  }
  SECTION("values inside reach the script") {
    RunOptions options;
    options.overrides = {parse_override("mode=b"), parse_override("n=0")};
    LuaState state(options);
    state.run_string(R"lua(
      local p = require("invasim").params{ mode = {"a", choices = {"a", "b"}},
                                           n = {3, range = "[0, 10]"} }
      assert(p.mode == "b" and p.n == 0)
    )lua");
    const auto& params = *state.context().params;
    REQUIRE(params.size() == 2);
    CHECK(params[0].choices == std::vector<std::string>{"a", "b"});
    REQUIRE(params[1].range);
    CHECK(params[1].range->notation() == "[0, 10]");
  }
}

TEST_CASE("invasim.params in list mode stops the script after recording", "[lua][params]") {
  RunOptions options;
  options.list_params = true;
  LuaState state(options);
  const auto outcome = state.run_string(R"lua(
    ran_before = true
    require("invasim").params{ a = 1 }
    ran_after = true
  )lua");
  CHECK(outcome == LuaState::Outcome::kStopped);
  REQUIRE(state.context().params);
  CHECK(state.context().params->size() == 1);
  lua_getglobal(state.get(), "ran_before");
  lua_getglobal(state.get(), "ran_after");
  CHECK(lua_toboolean(state.get(), -2));
  CHECK_FALSE(lua_toboolean(state.get(), -1));
}

TEST_CASE("Progress formats the line", "[lua][progress]") {
  double now = 0.0;
  std::ostringstream out;
  ProgressOptions options;
  options.total = 10000;
  Progress progress(options, out, false, [&] { return now; });
  CHECK(progress.line(1200, 60.0, 0.8, false) ==
        "step 1200/10000 (12.0%)  t = 60  1500 steps/s  ETA 0:06");
  CHECK(progress.line(0, std::nullopt, 0.0, false) == "step 0/10000 (0.0%)");
  CHECK(progress.line(10000, 500.0, 4.0, true) ==
        "step 10000/10000 (100.0%)  t = 500  2500 steps/s  done in 0:04");
  CHECK(Progress::format_duration(5) == "0:05");
  CHECK(Progress::format_duration(754) == "12:34");
  CHECK(Progress::format_duration(3723) == "1:02:03");

  ProgressOptions unknown_total;
  unknown_total.label = "quench";
  Progress open_ended(unknown_total, out, false, [&] { return now; });
  CHECK(open_ended.line(30, std::nullopt, 2.0, false) == "quench: step 30  15 steps/s");
}

TEST_CASE("Progress warns once when the ETA exceeds a year", "[lua][progress]") {
  double now = 0.0;
  std::ostringstream out;
  ProgressOptions options;
  options.total = 9223372036854775807LL;  // --set steps=9223372036854775807
  options.label = "production";
  Progress progress(options, out, false, [&] { return now; });
  now = 1.0;
  progress.update(1000);
  now = 20.0;
  progress.update(20000);
  const std::string text = out.str();
  CHECK(text.find("production: warning: at 1000 steps/s the remaining 9.22337e+18 steps take "
                  "2.92e+08 years, more than a year; check the number of steps\n") == 0);
  CHECK(text.find("warning", 20) == std::string::npos);  // once
  CHECK(text.find("ETA 2.92e+08 years") != std::string::npos);

  std::ostringstream quiet;
  options.total = 1000000;  // 1000 s at 1000 steps/s: no warning
  Progress short_run(options, quiet, false, [&] { return now; });
  now = 21.0;
  short_run.update(1000);
  CHECK(quiet.str().find("warning") == std::string::npos);
}

TEST_CASE("Progress prints plain lines every N seconds plus first and last", "[lua][progress]") {
  double now = 0.0;
  std::ostringstream out;
  ProgressOptions options;
  options.total = 100;
  options.every_seconds = 10.0;
  {
    Progress progress(options, out, false, [&] { return now; });
    now = 1.0;
    progress.update(10, 1.0);  // first: printed
    now = 5.0;
    progress.update(20, 2.0);  // 4 s later: skipped
    now = 11.5;
    progress.update(50, 5.0);  // 10.5 s after the first: printed
    now = 12.0;
    progress.update(60, 6.0);  // skipped
    now = 20.0;
    progress.finish();    // last: printed
    progress.update(70);  // after finish: ignored
  }
  CHECK(out.str() ==
        "step 10/100 (10.0%)  t = 1  10 steps/s  ETA 0:09\n"
        "step 50/100 (50.0%)  t = 5  4.35 steps/s  ETA 0:12\n"
        "step 60/100 (60.0%)  t = 6  3 steps/s  done in 0:20\n");
}

TEST_CASE("Progress of a run stopped by a signal ends with 'stopped after'", "[lua][progress]") {
  double now = 0.0;
  std::ostringstream out;
  ProgressOptions options;
  options.total = 100;
  Progress progress(options, out, false, [&] { return now; });
  now = 2.0;
  progress.update(40);
  now = 4.0;
  progress.stop();
  progress.finish();  // after stop: ignored
  CHECK(out.str() ==
        "step 40/100 (40.0%)  20 steps/s  ETA 0:03\n"
        "step 40/100 (40.0%)  10 steps/s  stopped after 0:04\n");
  CHECK(progress.finished());
}

TEST_CASE("Progress live line rewrites itself with carriage returns", "[lua][progress]") {
  double now = 0.0;
  std::ostringstream out;
  ProgressOptions options;
  options.total = 1000;
  {
    Progress progress(options, out, true, [&] { return now; });
    now = 1.0;
    progress.update(100);
    now = 1.1;
    progress.update(110);  // within live_interval: skipped
    now = 2.0;
    progress.update(1000);
    progress.finish();
  }
  CHECK(out.str() ==
        "\rstep 100/1000 (10.0%)  100 steps/s  ETA 0:09"
        "\rstep 1000/1000 (100.0%)  500 steps/s  ETA 0:00"
        "\rstep 1000/1000 (100.0%)  500 steps/s  done in 0:02\n");
}

TEST_CASE("Progress live line pads over a longer previous line", "[lua][progress]") {
  double now = 1.0;
  std::ostringstream out;
  ProgressOptions options;
  options.live_interval = 0.0;
  Progress progress(options, out, true, [&] { return now; });
  progress.update(1000000, 123456.0);
  progress.update(5);
  const std::string text = out.str();
  const auto second = text.rfind('\r');
  CHECK(text.substr(0, second).size() == text.substr(second).size());
}

TEST_CASE("lua_wrap turns C++ exceptions into Lua errors with file:line", "[lua][binding]") {
  LuaState state;
  install_test_functions(state.get());
  Guard::destroyed = 0;
  CHECK(script_error(state, "local x = 1\n\nthrow_input()") == "test.lua:3: boom");
  CHECK(Guard::destroyed == 1);  // the throwing frame was unwound by C++, not skipped
  CHECK(script_error(state, "throw_other()") == "test.lua:1: unknown C++ exception");
  CHECK(script_error(state, "throw_raised()") == "elsewhere.lua:7: callback failed");
  // Through pcall (a C function) the location is still the script line.
  CHECK_NOTHROW(state.run_string(R"lua(
    local ok, err = pcall(throw_input)
    assert(not ok and err == "t.lua:2: boom", err)
  )lua",
                                 "@t.lua"));
}

TEST_CASE("Bound types: constructor, methods, type errors and __gc", "[lua][binding]") {
  LuaState state;
  install_test_functions(state.get());
  Widget::alive = 0;
  state.run_string(R"lua(
    local w = Widget{size = 3}
    assert(w:size() == 3)
    assert(tostring(w) == "Widget(3)")
    assert(getmetatable(w) == false)
    local ok, err = pcall(function() return w.size(5) end)
    assert(err == "t.lua:6: bad argument #1 to 'size' (Widget expected, got number; for a method call write obj:method(...))", err)
    ok, err = pcall(function() return w:sise() end)
    assert(err == "t.lua:8: Widget has no method or field 'sise' (did you mean 'size'?); methods: size", err)
    ok, err = pcall(function() return Widget{size = 0} end)
    assert(err == "t.lua:10: Widget: key 'size' = 0 is out of range (must be in [1, 2147483647])", err)
    kept = Widget{size = 4}
  )lua",
                   "@t.lua");
  lua_gc(state.get(), LUA_GCCOLLECT);
  CHECK(Widget::alive == 1);  // only the global `kept`
  state.run_string("kept = nil");
  lua_gc(state.get(), LUA_GCCOLLECT);
  CHECK(Widget::alive == 0);
}

TEST_CASE("LuaState reports missing files, syntax errors and odd error values", "[lua][state]") {
  LuaState state;
  CHECK_THROWS_WITH(state.run_file("/nonexistent/protocol.lua"),
                    "cannot open protocol file '/nonexistent/protocol.lua': no such file");
  CHECK(script_error(state, "x = = 1") == "test.lua:1: unexpected symbol near '='");
  CHECK(script_error(state, "error({})") ==
        "test.lua:1: error object is a table value (no message)");
  CHECK(script_error(state, "error(setmetatable({}, {__tostring = function() return 'T' end}))") ==
        "test.lua:1: error object is a table value: T");
  CHECK(script_error(state, "\nerror(nil)") ==
        "test.lua:2: error object is a nil value (no message)");
  CHECK(script_error(state, "error(false)") ==
        "test.lua:1: error object is a boolean value: false");
  CHECK(
      script_error(state, "error(setmetatable({}, {__tostring = function() error('x', 0) end}))") ==
      "test.lua:1: error object is a table value (its __tostring failed: x)");
  CHECK(script_error(state, "error('plain', 0)") == "plain");  // strings are kept as they are
  CHECK(script_error(state, "local function f() return f() + 1 end f()").find("stack overflow") !=
        std::string::npos);
  try {
    state.run_string("local function g() error('deep') end\ng()", "@tb.lua");
    FAIL("no error");
  } catch (const ScriptError& e) {
    CHECK(std::string(e.what()) == "tb.lua:1: deep");
    CHECK(e.traceback().find("tb.lua:2") != std::string::npos);
  }
}

namespace {

enum class Mode { kSlow, kFast };

// A parameter struct with one member of each kind a FieldTable field stores.
struct Knobs {
  double rate = 0.5;
  double tau = 1.0;
  std::uint8_t level = 3;
  bool on = true;
  std::string label = "x";
  Mode mode = Mode::kSlow;
};

const FieldTable<Knobs>& knobs_table() {
  static const FieldTable<Knobs> table(
      "Knobs", {number<Knobs>("rate", &Knobs::rate, Range::positive(), "1", "a rate"),
                number<Knobs>("tau", &Knobs::tau, Range::positive(), "tau", "a time", true),
                integer<Knobs>("level", &Knobs::level, Range::non_negative(), "1", "a level"),
                boolean<Knobs>("on", &Knobs::on, "a switch"),
                string<Knobs>("label", &Knobs::label, "", "a name"),
                choice<Knobs>("mode", &Knobs::mode, {{"slow", Mode::kSlow}, {"fast", Mode::kFast}},
                              "a mode")});
  return table;
}

// Knobs read from the Lua table `expression`, or the error's text.
std::string read_knobs(lua_State* L, const std::string& expression, Knobs* out = nullptr) {
  eval(L, expression);
  try {
    Kwargs kw(L, -1, "Knobs");
    const Knobs k = knobs_table().make(kw);
    if (out) *out = k;
  } catch (const InputError& e) {
    lua_settop(L, 0);
    return e.what();
  }
  lua_settop(L, 0);
  return "";
}

}  // namespace

TEST_CASE("FieldTable fields check each value through Kwargs::declared", "[lua][fields]") {
  LuaState state;
  lua_State* L = state.get();
  Knobs k;
  REQUIRE(read_knobs(L,
                     "{rate = 2, tau = math.huge, level = 255, on = false, label = 'y', "
                     "mode = 'fast'}",
                     &k) == "");
  CHECK(k.rate == 2.0);
  CHECK(k.tau == std::numeric_limits<double>::infinity());
  CHECK(k.level == 255);
  CHECK_FALSE(k.on);
  CHECK(k.label == "y");
  CHECK(k.mode == Mode::kFast);
  REQUIRE(read_knobs(L, "{}", &k) == "");  // the struct's own defaults
  CHECK((k.rate == 0.5 && k.tau == 1.0 && k.level == 3 && k.on && k.label == "x" &&
         k.mode == Mode::kSlow));
  // math.huge only where the field allows it; the member's type bounds the integers.
  CHECK(read_knobs(L, "{rate = math.huge}") ==
        "Knobs: key 'rate' must be a finite number, got inf");
  CHECK(read_knobs(L, "{level = 256}") ==
        "Knobs: key 'level' = 256 is out of range (must be in [0, 255])");
  CHECK(read_knobs(L, "{on = 1}") == "Knobs: key 'on' must be a boolean (true or false), got 1");
  CHECK(read_knobs(L, "{mode = 'fats'}") ==
        "Knobs: key 'mode' must be one of: fast, slow; got 'fats' (did you mean 'fast'?)");
  // The listing shows tau's closed end at inf and rate's open one.
  const auto& fields = knobs_table().fields();
  CHECK(fields[0].info.range->notation() == "(0, inf)");
  CHECK(fields[1].info.range->notation() == "(0, inf]");
  // params() reads the values back, the enum as its name.
  const auto values = knobs_table().values(Knobs{});
  REQUIRE(values.size() == 6);
  CHECK(std::get<long long>(values[2].second) == 3);
  CHECK(std::get<std::string>(values[5].second) == "slow");
}
