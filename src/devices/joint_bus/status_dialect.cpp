#include "devices/joint_bus/status_dialect.hpp"

#include "portable/joint_bus_codes.hpp"

namespace armctl::joint_bus {

namespace {
constexpr std::int16_t legacy_unknown_command = 93;
constexpr std::int16_t legacy_bad_data = 94;
}  // namespace

const char* to_string(Dialect dialect) {
  return dialect == Dialect::legacy ? "legacy" : "standard";
}

std::optional<Dialect> dialect_from_string(std::string_view name) {
  if (name == "standard") return Dialect::standard;
  if (name == "legacy") return Dialect::legacy;
  return std::nullopt;
}

std::int16_t success_status(Dialect dialect, std::int16_t command) {
  if (dialect == Dialect::legacy) return command;
  return joint_bus::success_status(command);
}

StatusMeaning interpret_status(Dialect dialect, std::int16_t command, std::int16_t status) {
  if (status == success_status(dialect, command)) return StatusMeaning::success;
  const std::int16_t unknown =
      dialect == Dialect::legacy ? legacy_unknown_command : std::int16_t{status_unknown_command};
  const std::int16_t bad = dialect == Dialect::legacy ? legacy_bad_data : std::int16_t{status_bad_data};
  if (status == unknown) return StatusMeaning::unknown_command;
  if (status == bad) return StatusMeaning::bad_data;
  return StatusMeaning::unexpected;
}

int max_speed_value(Dialect dialect) { return dialect == Dialect::legacy ? 255 : 100; }

}  // namespace armctl::joint_bus
