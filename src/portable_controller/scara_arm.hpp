// The retrofitted SCARA's seven joints as the Mega controller firmware knows them: the same
// values as the arm_controller section of config/scara.arm.json (a host test keeps the two equal).
#pragma once

#include "portable_controller/controller_core.hpp"

namespace armctl {
namespace controller {

const uint8_t scara_joint_count = 7;
extern const JointSetup scara_joints[scara_joint_count];
// GetBatteryVoltage when the board measures no supply (config supply_millivolts).
const uint16_t scara_supply_millivolts = 24000;

}  // namespace controller
}  // namespace armctl
