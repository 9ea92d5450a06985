// signac job ids: python_json.hpp must write exactly what Python's
// json.dumps(statepoint, sort_keys=True) writes, so that the MD5 (the job id) is signac's.
// The expected text and ids come from /usr/bin/python3's json and hashlib, run by the test on
// awkward values: tiny, huge and negative-zero floats, 1 against 1.0, unicode (also outside
// the BMP), control characters, nested objects and lists, booleans and null, and a few
// thousand random doubles.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "sweep/md5.hpp"
#include "sweep/python_json.hpp"

using invasim::sweep::Json;
using invasim::sweep::python_dumps;
using invasim::sweep::python_float_repr;
using invasim::sweep::signac_id;

namespace {

// Python's json.dumps(v, sort_keys=True) and the MD5 of it for each line of JSON in `lines`
// (read by Python's json.loads): pairs of output lines.
std::vector<std::string> python_dumps_of(const std::vector<std::string>& lines) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("sweep_ids_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream in(dir / "in.jsonl");
    for (const auto& l : lines) in << l << '\n';
    std::ofstream py(dir / "dumps.py");
    py << "import hashlib, json, sys\n"
          "for line in open(sys.argv[1], encoding='utf-8'):\n"
          "    text = json.dumps(json.loads(line), sort_keys=True)\n"
          "    print(text)\n"
          "    print(hashlib.md5(text.encode()).hexdigest())\n";
  }
  const std::string command = std::string(INVASIM_PYTHON3) + " " + (dir / "dumps.py").string() +
                              " " + (dir / "in.jsonl").string();
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  std::string text;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
  REQUIRE(::pclose(pipe) == 0);
  std::filesystem::remove_all(dir);
  std::vector<std::string> out;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) out.push_back(line);
  return out;
}

// Compares python_dumps and signac_id with Python on each value.
void check_against_python(const std::vector<Json>& values) {
  std::vector<std::string> lines;
  for (const auto& v : values) lines.push_back(v.dump());  // nlohmann round-trips doubles
  const auto expected = python_dumps_of(lines);
  REQUIRE(expected.size() == 2 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    INFO("value " << lines[i]);
    CHECK(python_dumps(values[i]) == expected[2 * i]);
    CHECK(signac_id(values[i]) == expected[2 * i + 1]);
  }
}

}  // namespace

TEST_CASE("MD5 matches RFC 1321's test suite") {
  CHECK(invasim::sweep::md5_hex("") == "d41d8cd98f00b204e9800998ecf8427e");
  CHECK(invasim::sweep::md5_hex("abc") == "900150983cd24fb0d6963f7d28e17f72");
  CHECK(invasim::sweep::md5_hex(
            "12345678901234567890123456789012345678901234567890123456789012345678901234567890") ==
        "57edf4a22be3c955ac49da2e2107b67a");
}

TEST_CASE("floats are written as Python's repr") {
  CHECK(python_float_repr(1e-05) == "1e-05");
  CHECK(python_float_repr(0.0001) == "0.0001");
  CHECK(python_float_repr(1e16) == "1e+16");
  CHECK(python_float_repr(1e15) == "1000000000000000.0");
  CHECK(python_float_repr(1.0) == "1.0");
  CHECK(python_float_repr(-0.0) == "-0.0");
  CHECK(python_float_repr(0.1) == "0.1");
  CHECK(python_float_repr(1.3e-3) == "0.0013");
  CHECK(python_float_repr(123456789.125) == "123456789.125");
  CHECK(python_float_repr(5e-324) == "5e-324");
  CHECK(python_float_repr(1.7976931348623157e308) == "1.7976931348623157e+308");
}

TEST_CASE("state point ids equal Python's json.dumps + hashlib.md5 on awkward values") {
  std::vector<Json> values;
  values.push_back(Json::object());
  values.push_back({{"a", 1}, {"b", 1.0}});
  values.push_back({{"kT", 1e-5}, {"P", 0.0001}, {"big", 1e16}, {"edge", 1e15}, {"negzero", -0.0}});
  values.push_back({{"tiny", 5e-324},
                    {"max", 1.7976931348623157e308},
                    {"third", 1.0 / 3.0},
                    {"neg", -2.5e-7},
                    {"int_min", std::numeric_limits<std::int64_t>::min()},
                    {"uint_max", std::numeric_limits<std::uint64_t>::max()}});
  values.push_back(
      {{"flag", true}, {"off", false}, {"none", nullptr}, {"list", {1, 2.0, "x", false}}});
  values.push_back({{"nested", {{"z", {{"y", {1e-300, -1e300}}}}, {"a", Json::array()}}}});
  values.push_back({{"caf\xc3\xa9", "\xe2\x82\xac and \xf0\x9f\x98\x80"},
                    {"ctrl", std::string("tab\tnl\ncr\rbs\bff\f\x01\x1f\x7f quote\" slash\\ /")},
                    {"\xc3\xa9", 1},
                    {"z", 2},
                    {"Z", 3},
                    {"\xf0\x9f\x98\x80", 4}});
  values.push_back(Json::array({Json::object(), Json::array(), 0, 0.0, "", -1}));
  check_against_python(values);
}

TEST_CASE("random doubles are written as Python's repr") {
  std::mt19937_64 random(12345);
  std::vector<Json> values;
  Json list = Json::array();
  for (int i = 0; i < 4000; ++i) {
    std::uint64_t bits = random();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    if (!std::isfinite(d)) continue;
    list.push_back(d);
    // Values near the switch between fixed and exponent notation, and short decimals.
    list.push_back(
        std::ldexp(static_cast<double>(random() % 1000000), static_cast<int>(random() % 120) - 60));
    list.push_back(static_cast<double>(random() % 100000) *
                   std::pow(10.0, static_cast<int>(random() % 40) - 20));
  }
  values.push_back(list);
  check_against_python(values);
}
