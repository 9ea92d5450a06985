// The one interval type (core/range.hpp): the same Range states the allowed values of a
// keyword (lua/kwargs), of a declared parameter (core/params) and the x range of a random
// placement (setup/placement).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/params.hpp"
#include "core/range.hpp"
#include "lua/kwargs.hpp"
#include "setup/placement.hpp"

using namespace invasim;

// One type everywhere: a second interval type in any of these places fails to compile here.
static_assert(std::is_same_v<decltype(MeshPlacement::x), Range>);
static_assert(std::is_same_v<decltype(SpherePlacement::x), Range>);
static_assert(std::is_same_v<decltype(Param::range), std::optional<Range>>);
static_assert(std::is_same_v<decltype(parse_range("", "")), Range>);
static_assert(std::is_same_v<decltype(lua::IntegerBounds::of(std::declval<const Range&>(), 0, 1)),
                             lua::IntegerBounds>);

TEST_CASE("Range: one interval type for kwargs, params and placement x ranges") {
  // A placement's {lo, hi}: closed at both ends.
  const Range x{1.0, 2.5};
  CHECK(x.contains(1.0));
  CHECK(x.contains(2.5));
  CHECK_FALSE(x.contains(std::nextafter(2.5, 3.0)));
  CHECK(x.describe() == "in [1, 2.5]");
  CHECK(x.notation() == "[1, 2.5]");
  // A keyword's range, in words and in the parameters' interval notation.
  CHECK(Range::positive().describe() == "> 0");
  CHECK(parse_range("dt", "(0, inf)").notation() == "(0, inf)");  // brackets as declared
  CHECK(parse_range("dt", "(0, inf)").describe() == "> 0");
  CHECK_FALSE(Range::positive().contains(0.0));
  CHECK(Range::at_least(1).describe() == ">= 1");
  CHECK(Range{}.describe() == "finite");
  CHECK(Range{}.notation() == "[-inf, inf]");
  const Range p = parse_range("x", "(-inf, 2.5e-3]");
  CHECK(p.notation() == "(-inf, 0.0025]");
  CHECK(p.describe() == "<= 0.0025");
  CHECK(p.contains(-1e300));
  CHECK(format_number(0.1) == "0.1");
  // NaN is "nan" whatever its sign bit (0.0 / 0.0 has it set on x86).
  CHECK(format_number(std::numeric_limits<double>::quiet_NaN()) == "nan");
  CHECK(format_number(-std::numeric_limits<double>::quiet_NaN()) == "nan");
}
