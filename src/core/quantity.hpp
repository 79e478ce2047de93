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

// "30 deg", "120.5 mm": for messages; `per_second_power` adds "/s", "/s^2", ...
std::string format_quantity(Dimension d, double si, int per_second_power = 0);

}  // namespace armctl
