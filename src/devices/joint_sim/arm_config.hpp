// The simulated SCARA arm's configuration (the "simulator" section of config/scara.arm.json,
// core/arm_file_sections.hpp): bus baud, physics step, and per joint its hardware (motor,
// gearbox, encoder, load, end stops) and controller tuning; each joint's name, bus number and
// max_speed_cps/max_accel_cps2 are the arm file's joint entry's. A config file of the old
// form (a whole file of its own, as config/scara.json was) is still read.
// Format and defaults: docs/simulator.md. Every key is validated: an unknown key, a wrong
// type or a value out of range is an ArmctlError(invalid_config) naming the key and what is
// allowed; nothing is half-loaded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "devices/joint_sim/joint_hardware.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::joint_sim {

struct JointConfig {
  std::string name;
  std::uint8_t number = 0;  // 1..7, the joint's select line and its READY word
  JointHardwareParams hardware;
  joint_bus::JointTuning tuning{};
};

struct ArmConfig {
  std::uint32_t baud = 9600;
  std::vector<JointConfig> joints;  // sorted by number

  const JointConfig& joint(int number) const;  // throws invalid_argument if absent
};

// `source` names the input in error messages (a path, "<string>").
ArmConfig parse_arm_config(std::string_view json_text, const std::string& source = "<string>");
ArmConfig load_arm_config(const std::filesystem::path& path);
// config/scara.arm.json: $ARMCTL_CONFIG_DIR, the installed copy, or the source tree. Asked for
// the old name config/scara.json, load_arm_config reads it, with a warning.
std::filesystem::path default_arm_config_path();

}  // namespace armctl::joint_sim
