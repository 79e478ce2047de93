// The arm controller's view of the arm (the "arm_controller" section of config/scara.arm.json,
// core/arm_file_sections.hpp; a file of the old form, as config/scara-arm.json was, is still
// read; each joint's name, number and velocity/acceleration are the arm file's joint
// entry's): which joints exist, how a
// Robot Commands position (0..1000) maps to joint clicks, the soft limits, and what the
// joints can do (velocity at set_speed 100 %, acceleration), which the synchronized-move
// planner needs. Format: docs/arm-controller.md. Every key is validated: an unknown key, a
// wrong type or a value out of range is an ArmctlError(invalid_config) naming the key and
// what is allowed; nothing is half-loaded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace armctl::arm_controller {

// A straight line through two points: Robot Commands position `rc` <-> joint `clicks`.
struct LinearMap {
  double rc_a = 0, clicks_a = 0;
  double rc_b = 1000, clicks_b = 1000;

  double clicks_per_unit() const { return (clicks_b - clicks_a) / (rc_b - rc_a); }
  // Rounded to the nearest click / unit.
  std::int32_t to_clicks(double rc) const;
  std::int32_t to_rc(double clicks) const;
};

struct ControllerJointConfig {
  std::string name;
  std::uint8_t number = 0;        // 1..7: servo ID upstream = joint number on the bus
  LinearMap map;
  std::int16_t soft_min = 0;      // clicks; targets outside are refused
  std::int16_t soft_max = 0;
  double max_speed_cps = 0;       // the joint's velocity at set_speed 100 %
  double max_accel_cps2 = 0;      // the joint's setpoint acceleration limit
  std::int16_t zone_clicks = 10;  // "arrived" band, also sent to the joint (set_zone)
};

struct ControllerConfig {
  std::vector<ControllerJointConfig> joints;  // sorted by number
  std::uint16_t supply_millivolts = 24000;    // GetBatteryVoltage when no supply is measured

  const ControllerJointConfig* joint(int number) const;  // nullptr if absent
};

ControllerConfig parse_controller_config(std::string_view json_text,
                                         const std::string& source = "<string>");
ControllerConfig load_controller_config(const std::filesystem::path& path);
// config/scara.arm.json: $ARMCTL_CONFIG_DIR, the installed copy, or the source tree. Asked for
// the old name config/scara-arm.json, load_controller_config reads it, with a warning.
std::filesystem::path default_controller_config_path();

}  // namespace armctl::arm_controller
