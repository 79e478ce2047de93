#include "devices/joint_bus/status_dialect.hpp"

#include "portable/joint_bus_codes.hpp"

namespace armctl::joint_bus {


const char* to_string(Dialect dialect) {
  return dialect == Dialect::legacy ? "legacy" : "standard";
}

std::optional<Dialect> dialect_from_string(std::string_view name) {
  if (name == "standard") return Dialect::standard;
  if (name == "legacy") return Dialect::legacy;
  return std::nullopt;
}

std::optional<std::int16_t> success_status(Dialect dialect, std::int16_t command) {
  if (!command_shape(command).known) return std::nullopt;
  if (dialect == Dialect::legacy) return command;
  return joint_bus::success_status(command);
}

StatusMeaning interpret_status(Dialect dialect, std::int16_t command, std::int16_t status) {
  // Success first only for a known command: otherwise legacy command 93 answered with its
  // "unknown" 93 would read as success.
  if (status == success_status(dialect, command)) return StatusMeaning::success;
  const std::int16_t unknown =
      dialect == Dialect::legacy ? legacy_status_unknown_command : std::int16_t{status_unknown_command};
  const std::int16_t bad = dialect == Dialect::legacy ? legacy_status_bad_data : std::int16_t{status_bad_data};
  if (status == unknown) return StatusMeaning::unknown_command;
  if (status == bad) return StatusMeaning::bad_data;
  return StatusMeaning::unexpected;
}

int max_speed_value(Dialect dialect) { return dialect == Dialect::legacy ? 255 : 100; }

}  // namespace armctl::joint_bus
