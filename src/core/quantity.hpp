// Physical quantities written with their unit, as users type them on the command line and
// in arm files: "30deg", "-0.5rad", "120mm", "0.12m", and rates of them: "90deg/s",
// "0.2m/s^2", "5000deg/s^3". Values come out in SI units (rad, m, per s^k).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace armctl {

enum class Dimension { angle, length };
const char* to_string(Dimension d);  // "angle", "length"

// The unit used to print a value of this dimension for people: deg or mm.
const char* display_unit(Dimension d);
double to_display(Dimension d, double si);    // rad -> deg, m -> mm
double from_display(Dimension d, double shown);  // deg -> rad, mm -> m

// Parses `text` as a quantity of dimension `dimension` divided by s^`per_second_power`
// (0 = position, 1 = velocity, 2 = acceleration, 3 = jerk). A bare number takes
// `default_unit` ("deg", "mm", ...) when one is given, else it is refused. Errors
// (invalid_argument) name `what`, the text, and the units allowed.
Result<double> parse_quantity(std::string_view text, Dimension dimension, std::string_view what,
                              int per_second_power = 0,
                              std::optional<std::string_view> default_unit = std::nullopt);

// parse_quantity, then the range [min_si, max_si] (SI), refused in the user's words and
// the display unit: "--speed: '1e-300mm/s' is too slow; allowed 0.1..500 mm/s".
Result<double> parse_quantity_in(std::string_view text, Dimension dimension, std::string_view what,
                                 int per_second_power, std::optional<std::string_view> default_unit, double min_si,
                                 double max_si);

// The same range check for a number given in SI already (Python's arguments, the HTTP
// API's fields): "speed: 1e-300 m/s is too slow; allowed 0.1..500 mm/s".
Status check_quantity_in(double si, Dimension dimension, std::string_view what, int per_second_power, double min_si,
                         double max_si);

// A percentage as people write it, "50%" or "12.5%", as a fraction (0.5) within
// [min_fraction, max_fraction]. A bare number is refused (is "0.5" half or 0.5 %?):
// "--override: '50' has no unit; write a percentage like 50%", and so is a value outside:
// "--override: '1e-300%' is too small; allowed 0.1..100 %".
Result<double> parse_percent(std::string_view text, std::string_view what, double min_fraction, double max_fraction);

// The same range check for a fraction given as a number (Python, HTTP): "speed_override:
// 1e-300 is too small; allowed 0.001..1 (0.1..100 %)".
Status check_fraction_in(double fraction, std::string_view what, double min_fraction, double max_fraction);

// "30 deg", "120.5 mm": for messages; `per_second_power` adds "/s", "/s^2", ...
std::string format_quantity(Dimension d, double si, int per_second_power = 0);

}  // namespace armctl
