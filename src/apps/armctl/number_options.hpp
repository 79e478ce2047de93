// The one check for armctl's numeric options. CLI11 alone answers "-1" for an unsigned option
// or 99999999999 for a 32-bit one with "Could not convert", naming no range; with these
// checks, which run on the text before CLI11 converts it, every numeric option answers
// "--baud: 99999999999 is outside 1..4000000" (CLI11 puts the option's name first).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace armctl::cli {

// A whole number within min..max (the range also shows in --help).
CLI::Validator whole_number_in(long long min, long long max);
// A finite number within min..max (no nan, no inf), `unit` is shown after it ("s", "ms").
// With `above_min`, min itself is refused too (a timeout of 0 s).
CLI::Validator number_in(double min, double max, const std::string& unit, bool above_min = false);
// A percentage option as a fraction: --speed of the joints' velocity limits (arm, replay),
// --override of the programmed speeds (arm, program): "50%", within 0.1..100 % (the motion
// layer's limits); a bare number is refused (half, or 0.5 %?). Empty: `otherwise`. The one
// parser of them all (core/quantity.hpp's parse_percent); errors throw invalid_argument.
double percent_option(const std::string& text, const std::string& what, double otherwise);

// A duration option: 2s, 1.5s, 800ms or a bare number of seconds, 0 or more; errors throw
// invalid_argument naming `option`.
double seconds_option(const std::string& text, const std::string& option);
// --avoid-time (arm move-to, program check/run): how long the search around obstacles may
// take, 10 ms..60 s; empty: `otherwise` s.
double avoid_time_option(const std::string& text, double otherwise);

// A standard serial line rate (0, 12345 and 99999999999 all get the one message listing them).
CLI::Validator standard_baud();

}  // namespace armctl::cli
