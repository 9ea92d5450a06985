// JSON (io/json.hpp): the number rule and the layout of every JSON file invasim writes
// (params.json, summary.json), byte for byte as the Lua encoder that preceded it wrote them;
// reading back; errors naming the file.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "io/io_error.hpp"
#include "io/json.hpp"

using namespace invasim;
using Catch::Matchers::Contains;

TEST_CASE("json_float: shortest round-trip digits in %g layout") {
  CHECK(json_float(0.1) == "0.1");
  CHECK(json_float(1.0) == "1");
  CHECK(json_float(100.0) == "100");
  CHECK(json_float(-0.0) == "-0");
  CHECK(json_float(1.0 / 3.0) == "0.3333333333333333");   // 16 digits
  CHECK(json_float(0.1 + 0.2) == "0.30000000000000004");  // 17 digits
  CHECK(json_float(123456.789) == "123456.789");
  CHECK(json_float(1e-5) == "1e-05");  // exponent below 1e-4
  CHECK(json_float(0.0001) == "0.0001");
  CHECK(json_float(1e15) == "1e+15");                           // exponent from 10^15
  CHECK(json_float(1234567890123456.0) == "1234567890123456");  // 16 digits: 10^16
  CHECK(json_float(9007199254740992.0) == "9007199254740992");
  CHECK(json_float(1e16) == "1e+16");
  CHECK(json_float(6.02214076e23) == "6.02214076e+23");
  CHECK(json_float(5e-324) == "4.94065645841247e-324");  // denormal: 15 digits do
  CHECK(json_float(std::numeric_limits<double>::max()) == "1.7976931348623157e+308");
  CHECK(json_float(std::nan("")) == "null");
  CHECK(json_float(-std::numeric_limits<double>::infinity()) == "null");
  // Every text reads back to the same double.
  for (double v : {0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 12345.678901234567, 0.1 + 0.7, 1e22})
    CHECK(std::strtod(json_float(v).c_str(), nullptr) == v);
}

namespace {

// A document with every kind of value (the Lua encoder's output for the same table is below).
Json sample_document() {
  Json doc = Json::object();
  doc["1.5"] = "float key";
  doc["empty"] = Json::array();
  doc["floats"] = {0.1, 1.0, 1e-5, 1e15, -0.0, std::nan("")};
  doc["ints"] = {0, -1, std::numeric_limits<std::int64_t>::max(),
                 std::numeric_limits<std::int64_t>::min()};
  doc["text"] = "tab\there \"q\" back\\ nl\n cr\r bell\a del\x7f \xc3\xa9";
  doc["nested"] = {{"3", "three"},
                   {"off", false},
                   {"flag", true},
                   {"list_of_objects", {{{"b", 2}, {"a", 1}}, Json::array()}}};
  return doc;
}

// Written by protocols/lib/json.lua (the Lua encoder json_dump replaced) for the same values.
const char* const kSampleText = R"({
  "1.5": "float key",
  "empty": [],
  "floats": [0.1, 1, 1e-05, 1e+15, -0, null],
  "ints": [0, -1, 9223372036854775807, -9223372036854775808],
  "nested": {
    "3": "three",
    "flag": true,
    "list_of_objects": [{
        "a": 1,
        "b": 2
      }, []],
    "off": false
  },
  "text": "tab\there \"q\" back\\ nl\n cr\r bell\u0007 del\u007f é"
}
)";

}  // namespace

TEST_CASE("json_dump: sorted keys, objects one entry per line, arrays on one line") {
  CHECK(json_dump(sample_document()) == kSampleText);
  CHECK(json_dump(Json::object()) == "{}\n");
  CHECK(json_dump(Json::array()) == "[]\n");
  CHECK(json_dump(Json(7u)) == "7\n");
  CHECK(json_dump({{"b", {1, 2.5}}, {"a", {{"x", nullptr}}}}, 0) ==
        "{\"a\": {\"x\": null}, \"b\": [1, 2.5]}\n");
  CHECK(json_dump({{"a", {{"x", 1}}}}, 4) == "{\n    \"a\": {\n        \"x\": 1\n    }\n}\n");
  CHECK_THROWS_WITH(json_dump(Json(1), -1), Contains("indent = -1 must be >= 0"));
}

TEST_CASE("parse_json reads back what json_dump wrote, malformed JSON names the file") {
  const Json back = parse_json(kSampleText, "sample");
  std::string same = kSampleText;  // all but -0, which reads back as the integer 0
  same.replace(same.find("-0,"), 3, "0,");
  CHECK(json_dump(back) == same);
  CHECK(back["floats"][0].get<double>() == 0.1);
  CHECK(back["floats"][1].get<double>() == 1.0);  // an integral float comes back as 1
  CHECK(back["ints"][3].get<std::int64_t>() == std::numeric_limits<std::int64_t>::min());
  CHECK(back["text"].get<std::string>() == sample_document()["text"].get<std::string>());
  CHECK_THROWS_AS(parse_json("{\"a\": 1,\n  \"b\": }", "'x.json'"), IoError);
  CHECK_THROWS_WITH(parse_json("{\"a\": 1,\n  \"b\": }", "'x.json'"),
                    Contains("'x.json': malformed JSON: parse error at line 2, column 8"));
  CHECK_THROWS_WITH(read_json("/nonexistent/x.json"), Contains("'/nonexistent/x.json'"));
  CHECK_THROWS_WITH(parse_json("[1e999]", "'big.json'"),
                    Contains("'big.json': malformed JSON: number overflow parsing '1e999'"));
}

TEST_CASE("json_dump writes UTF-8 strings as they are and refuses the others, naming the byte") {
  const std::string text = "\xc3\xa9t\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80";  // été € and U+1F600
  const std::string dumped = json_dump(Json{{"s", text}}, 0);
  CHECK(dumped == "{\"s\": \"" + text + "\"}\n");
  CHECK(parse_json(dumped, "utf8")["s"].get<std::string>() == text);
  const struct {
    const char* bytes;
    const char* what;
  } bad[] = {{"a\xff", "byte 0xff at position 2"},             // never in UTF-8
             {"\xc0\xaf", "byte 0xc0 at position 1"},          // overlong '/'
             {"\xed\xa0\x80", "byte 0xed at position 1"},      // a surrogate
             {"\xf4\x90\x80\x80", "byte 0xf4 at position 1"},  // above U+10FFFF
             {"ab\xe2\x82", "byte 0xe2 at position 3"},        // cut short
             {"\x80", "byte 0x80 at position 1"}};             // a lone continuation
  for (const auto& b : bad) {
    CAPTURE(b.what);
    CHECK_THROWS_WITH(json_dump(Json{{"s", b.bytes}}), Contains(b.what) && Contains("not UTF-8"));
    // nlohmann's parser refuses what it would have written: the refusal is the writer's.
    CHECK_THROWS(Json::parse(std::string("\"") + b.bytes + "\""));
  }
}
