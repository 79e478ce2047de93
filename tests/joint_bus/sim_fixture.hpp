// The simulated SCARA arm (config/scara.arm.json) at a chosen baud, for master tests.
#pragma once

#include <memory>

#include "devices/joint_sim/sim_arm.hpp"

namespace armctl::test {

inline std::unique_ptr<joint_sim::SimArm> make_arm(std::uint32_t baud = 9600) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  config.baud = baud;
  return std::make_unique<joint_sim::SimArm>(std::move(config));
}

}  // namespace armctl::test
