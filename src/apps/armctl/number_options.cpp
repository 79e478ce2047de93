#include "apps/armctl/number_options.hpp"

#include <charconv>
#include <cmath>

#include <fmt/core.h>

#include "core/error.hpp"
#include "core/must.hpp"
#include "core/printable.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "transport/serial_port.hpp"

namespace armctl::cli {

double percent_option(const std::string& text, const std::string& what, double otherwise) {
  if (text.empty()) return otherwise;
  return must(parse_percent(text, what, motion::kMinSpeedFraction, motion::kMaxSpeedFraction));
}

double seconds_option(const std::string& text, const std::string& option) {
  double v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const std::string unit(end, text.data() + text.size());
  if (ec != std::errc() || !std::isfinite(v) || v < 0 || (unit != "s" && unit != "ms" && !unit.empty()))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("{} '{}' is not allowed: a duration like 2s, 1.5s or 800ms (bare numbers are seconds)",
                                  option, text));
  return unit == "ms" ? v / 1000 : v;
}

double avoid_time_option(const std::string& text, double otherwise) {
  if (text.empty()) return otherwise;
  const double s = seconds_option(text, "--avoid-time");
  if (s < 0.01 || s > 60)
    throw ArmctlError(ErrorKind::invalid_argument, fmt::format("--avoid-time '{}' is not allowed: 10ms..60s", text));
  return s;
}

CLI::Validator whole_number_in(long long min, long long max) {
  const std::string range = fmt::format("{}..{}", min, max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        long long v = 0;
        const char* first = text.data();
        const char* last = first + text.size();
        if (text.size() > 1 && text[0] == '+' && text[1] != '-') ++first;  // "+5" is a number too
        const auto [end, ec] = std::from_chars(first, last, v);
        if (text.empty() || ec == std::errc::invalid_argument || end != last)
          return fmt::format("'{}' is not a whole number (allowed {})", printable(text), range);
        // A number too large for 64 bits is still a number outside the range.
        if (ec == std::errc::result_out_of_range || v < min || v > max)
          return fmt::format("{} is outside {}", printable(text), range);
        return "";
      },
      "INT in " + range);
}

CLI::Validator number_in(double min, double max, const std::string& unit, bool above_min) {
  const std::string range = fmt::format("{}..{}{}{}{}", min, max, unit.empty() ? "" : " ", unit,
                                        above_min ? fmt::format(", {} excluded", min) : std::string());
  return CLI::Validator(
      [min, max, above_min, range](std::string& text) -> std::string {
        double v = 0;
        const char* first = text.data();
        const char* last = first + text.size();
        if (text.size() > 1 && text[0] == '+' && text[1] != '-') ++first;
        const auto [end, ec] = std::from_chars(first, last, v);
        if (text.empty() || ec == std::errc::invalid_argument || end != last)
          return fmt::format("'{}' is not a number (allowed {})", printable(text), range);
        if (ec == std::errc::result_out_of_range || !std::isfinite(v) || v < min || v > max || (above_min && v == min))
          return fmt::format("{} is outside {}", printable(text), range);
        return "";
      },
      "NUMBER in " + range);
}

CLI::Validator standard_baud() {
  const std::string allowed = transport::standard_bauds_text();
  return CLI::Validator(
      [allowed](std::string& text) -> std::string {
        long long v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        const bool whole = !text.empty() && ec != std::errc::invalid_argument && end == text.data() + text.size();
        if (!whole || ec == std::errc::result_out_of_range || v <= 0 || v > transport::kMaxStandardBaud ||
            !transport::baud_constant(static_cast<std::uint32_t>(v)))
          return fmt::format("{} is not a standard rate (allowed: {})", printable(text), allowed);
        return "";
      },
      "BAUD (a standard rate)");
}

}  // namespace armctl::cli
