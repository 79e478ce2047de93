// The simulated SCARA arm's configuration (config/scara.json): bus baud, physics step, and
// per joint its hardware (motor, gearbox, encoder, load, end stops) and controller tuning.
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
// config/scara.json: $ARMCTL_CONFIG_DIR, the installed copy, or the source tree.
std::filesystem::path default_arm_config_path();

}  // namespace armctl::joint_sim
