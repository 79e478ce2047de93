// Values of the program language: a number and its kind of quantity. Literals carry their
// unit ("40mm", "90deg", "0.5s", "50%", "40mm/s") and are kept in SI units; arithmetic
// checks the kinds (a length plus an angle is an error), so that a bare 200 is never
// taken for 200 m.
#pragma once

#include <string>
#include <string_view>

#include "core/error.hpp"

namespace armctl::program {

enum class Unit { number, length, angle, time, percent, speed, angular_speed, acceleration, angular_acceleration };
// "a number", "a length", "a percentage", ... for messages.
const char* describe(Unit u);
// An example literal: "40mm", "90deg", "0.5s", "50%", "40mm/s", ...
const char* example(Unit u);

struct Value {
  double si = 0;  // percent: the fraction (50% = 0.5)
  Unit unit = Unit::number;
};

// A unit suffix as written after a number ("mm", "deg/s", "%", ...): the unit and the factor
// to SI, or an error listing the suffixes allowed.
struct UnitSuffix {
  Unit unit;
  double factor;
};
Result<UnitSuffix> unit_suffix(std::string_view text);
std::string_view allowed_suffixes();

// For PRINT and messages: "40 mm", "90 deg", "0.5 s", "50 %", "3".
std::string format_value(const Value& v);

}  // namespace armctl::program
