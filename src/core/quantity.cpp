#include "core/quantity.hpp"
#include "core/units.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

namespace armctl {

namespace {

constexpr QuantityUnit kUnits[] = {
    {"deg", Dimension::angle, std::numbers::pi / 180.0},
    {"rad", Dimension::angle, 1.0},
    {"mm", Dimension::length, 1e-3},
    {"m", Dimension::length, 1.0},
};

std::string rate_suffix(int power) {
  if (power <= 0) return "";
  if (power == 1) return "/s";
  return fmt::format("/s^{}", power);
}

std::string allowed_units(Dimension d, int power) {
  std::string out;
  for (const QuantityUnit& u : kUnits) {
    if (u.dimension != d) continue;
    out += (out.empty() ? "" : ", ") + std::string(u.name) + rate_suffix(power);
  }
  return out;
}

}  // namespace

const QuantityUnit* find_unit(std::string_view name) {
  for (const QuantityUnit& u : kUnits)
    if (name == u.name) return &u;
  return nullptr;
}
const QuantityUnit& display_unit_of(Dimension d) { return d == Dimension::angle ? kUnits[0] : kUnits[2]; }

const char* to_string(Dimension d) { return d == Dimension::angle ? "angle" : "length"; }
const char* display_unit(Dimension d) { return display_unit_of(d).name; }
double to_display(Dimension d, double si) {
  const double shown = d == Dimension::angle ? si * 180.0 / std::numbers::pi : si * 1e3;
  return std::abs(shown) < 5e-7 ? 0.0 : shown;  // no "-0.000"
}
double from_display(Dimension d, double shown) {
  return d == Dimension::angle ? shown * std::numbers::pi / 180.0 : shown * 1e-3;
}

Result<double> parse_quantity(std::string_view text, Dimension dimension, std::string_view what,
                              int per_second_power, std::optional<std::string_view> default_unit) {
  auto refuse = [&](const std::string& why) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{}: '{}' {}; write a number with one of the units {}", what, text,
                             why, allowed_units(dimension, per_second_power))};
  };
  // std::from_chars accepts no leading '+', and "nan"/"inf" would parse: refused below.
  std::string_view body = text;
  if (!body.empty() && body.front() == '+') body.remove_prefix(1);
  double value = 0;
  auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (ec != std::errc() || end == body.data()) return refuse("is not a number");
  if (!std::isfinite(value)) return refuse("is not a finite number");
  std::string_view unit(end, static_cast<std::size_t>(body.data() + body.size() - end));
  if (unit.empty()) {
    if (!default_unit) return refuse("has no unit");
    unit = *default_unit;
  }
  const std::string suffix = rate_suffix(per_second_power);
  for (const QuantityUnit& u : kUnits) {
    if (unit != std::string(u.name) + suffix) continue;
    if (u.dimension != dimension)
      return refuse(fmt::format("is {}, but this is {}", u.dimension == Dimension::angle ? "an angle" : "a length",
                                dimension == Dimension::angle ? "an angle" : "a length"));
    return value * u.to_si;
  }
  return refuse(fmt::format("has the unknown unit '{}'", unit));
}

namespace {

// "too slow" / "too fast" for speeds, "too small" / "too large" for anything else.
const char* too(bool low, int per_second_power) {
  if (per_second_power == 1) return low ? "too slow" : "too fast";
  return low ? "too small" : "too large";
}

// "0.1..500 mm/s"
std::string display_range(Dimension d, int power, double min_si, double max_si) {
  return fmt::format("{:g}..{:g} {}{}", to_display(d, min_si), to_display(d, max_si), display_unit(d),
                     rate_suffix(power));
}

}  // namespace

Result<double> parse_quantity_in(std::string_view text, Dimension dimension, std::string_view what,
                                 int per_second_power, std::optional<std::string_view> default_unit, double min_si,
                                 double max_si) {
  auto v = parse_quantity(text, dimension, what, per_second_power, default_unit);
  if (!v) return v;
  if (*v >= min_si && *v <= max_si) return v;
  return Error{ErrorKind::invalid_argument,
               fmt::format("{}: '{}' is {}; allowed {}", what, text, too(*v < min_si, per_second_power),
                           display_range(dimension, per_second_power, min_si, max_si))};
}

Status check_quantity_in(double si, Dimension dimension, std::string_view what, int per_second_power, double min_si,
                         double max_si) {
  if (si >= min_si && si <= max_si) return Ok{};
  const std::string si_unit = std::string(dimension == Dimension::angle ? "rad" : "m") + rate_suffix(per_second_power);
  return Error{ErrorKind::invalid_argument,
               fmt::format("{}: {:g} {} is {}; allowed {}", what, si, si_unit,
                           std::isnan(si) ? "not a number" : too(si < min_si, per_second_power),
                           display_range(dimension, per_second_power, min_si, max_si))};
}

Result<double> parse_percent(std::string_view text, std::string_view what, double min_fraction, double max_fraction) {
  const std::string range = fmt::format("{:g}..{:g} %", min_fraction * 100, max_fraction * 100);
  std::string_view body = text;
  if (!body.empty() && body.front() == '+') body.remove_prefix(1);
  const bool has_unit = !body.empty() && body.back() == '%';
  if (has_unit) body.remove_suffix(1);
  double value = 0;
  auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (ec == std::errc::result_out_of_range && end == body.data() + body.size())
    return Error{ErrorKind::invalid_argument, fmt::format("{}: '{}' is outside {}", what, text, range)};
  if (ec != std::errc() || end != body.data() + body.size() || body.empty() || !std::isfinite(value))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{}: '{}' is not a percentage; write a number and %, within {} (e.g. 50%)", what, text, range)};
  if (!has_unit)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{}: '{}' has no unit; write a percentage like {:g}%, within {}", what, text, value, range)};
  const double fraction = value / 100;
  if (fraction >= min_fraction && fraction <= max_fraction) return fraction;
  return Error{ErrorKind::invalid_argument,
               fmt::format("{}: '{}' is {}; allowed {}", what, text, fraction < min_fraction ? "too small" : "too large",
                           range)};
}

Status check_fraction_in(double fraction, std::string_view what, double min_fraction, double max_fraction) {
  if (fraction >= min_fraction && fraction <= max_fraction) return Ok{};
  return Error{ErrorKind::invalid_argument,
               fmt::format("{}: {:g} is {}; allowed {:g}..{:g} ({:g}..{:g} %)", what, fraction,
                           std::isnan(fraction) ? "not a number" : fraction < min_fraction ? "too small" : "too large",
                           min_fraction, max_fraction, min_fraction * 100, max_fraction * 100)};
}

std::string format_quantity(Dimension d, double si, int per_second_power) {
  // + 0.0 turns -0 into 0: "-0.000 deg" reads as a sign error.
  return fmt::format("{:.3f} {}{}", to_display(d, si) + 0.0, display_unit(d), rate_suffix(per_second_power));
}

}  // namespace armctl
