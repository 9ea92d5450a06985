#pragma once
// The one interval type of invasim: a real interval with either end closed, open or infinite.
// It states the allowed values of a keyword (lua/kwargs), of a declared parameter
// (core/params, written "(0, inf)") and the x range of a random placement (setup/placement,
// closed: Range{lo, hi}).
#include <limits>
#include <string>

namespace invasim {

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range positive() { return {0.0, inf(), true, false}; }       // > 0
  static Range non_negative() { return {0.0, inf(), false, false}; }  // >= 0
  static Range at_least(double lo) { return {lo, inf(), false, false}; }
  static Range greater_than(double lo) { return {lo, inf(), true, false}; }
  static Range between(double lo, double hi) { return {lo, hi, false, false}; }  // [lo, hi]
  static Range inside(double lo, double hi) { return {lo, hi, true, true}; }     // (lo, hi)

  bool contains(double x) const;
  std::string describe() const;  // in words: "> 0", ">= 1", "in [0, 1]", "finite"
  std::string notation() const;  // interval notation: "(0, inf)", "[0, 1)"

 private:
  static double inf() { return std::numeric_limits<double>::infinity(); }
};

// The shortest text that reads back as x ("0.0025", "1e+300").
std::string format_number(double x);

}  // namespace invasim
