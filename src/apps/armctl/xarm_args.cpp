#include "apps/armctl/xarm_args.hpp"

#include <charconv>
#include <cmath>

#include <fmt/core.h>

#include "core/error.hpp"
#include "protocol/robot_commands/units.hpp"

namespace armctl::cli::xarm_args {
namespace {

[[noreturn]] void bad(const std::string& message) {
  throw ArmctlError(ErrorKind::invalid_argument, message);
}

}  // namespace

long parse_int(const std::string& text, long min, long max, const std::string& what) {
  long v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size()) {
    bad(fmt::format("{} \"{}\" is not a whole number (allowed {}..{})", what, text, min, max));
  }
  if (v < min || v > max) bad(fmt::format("{} {} is out of range (allowed {}..{})", what, v, min, max));
  return v;
}

std::uint8_t parse_servo(const std::string& text, int servo_count) {
  return static_cast<std::uint8_t>(parse_int(text, 1, servo_count, "servo"));
}

std::vector<std::uint8_t> parse_servos(const std::vector<std::string>& texts, int servo_count) {
  std::vector<std::uint8_t> out;
  if (texts.empty()) {
    for (int s = 1; s <= servo_count; ++s) out.push_back(static_cast<std::uint8_t>(s));
    return out;
  }
  for (const auto& t : texts) out.push_back(parse_servo(t, servo_count));
  return out;
}

robot_commands::ServoTarget parse_target(const std::string& text, int servo_count) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) {
    bad(fmt::format("move target \"{}\" is not SERVO=POSITION (e.g. 1=500, 2=30deg, 3=keep)",
                    text));
  }
  robot_commands::ServoTarget t;
  t.servo = parse_servo(text.substr(0, eq), servo_count);
  std::string value = text.substr(eq + 1);
  if (value == "keep") return t;
  if (value.size() > 3 && value.compare(value.size() - 3, 3, "deg") == 0) {
    const std::string number = value.substr(0, value.size() - 3);
    double deg = 0;
    auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), deg);
    if (ec != std::errc{} || end != number.data() + number.size() || !std::isfinite(deg) ||
        deg < -120.0 || deg > 120.0) {
      bad(fmt::format("servo {}: angle \"{}\" is not allowed (-120deg..120deg from centre)",
                      t.servo, value));
    }
    t.position = static_cast<std::uint16_t>(rc::degrees_to_position(deg));
    return t;
  }
  t.position = static_cast<std::uint16_t>(
      parse_int(value, 0, 1000, fmt::format("servo {} position", t.servo)));
  return t;
}

std::uint8_t parse_group(const std::string& text, bool all_allowed) {
  // "all" is the word for every group; its wire value 255 is not a group number, so typing
  // 255 is refused like any other number outside 0..254 (help, message and code agree).
  if (all_allowed && text == "all") return 255;
  return static_cast<std::uint8_t>(parse_int(text, 0, 254, all_allowed ? "group (0..254 or all)" : "group"));
}

}  // namespace armctl::cli::xarm_args
