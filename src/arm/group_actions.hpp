// The one conversion of joint targets (SI) into a Robot Commands board's servo action: an
// action group's step, whether the dashboard's frames (web/group_frames) or a compiled
// program (program/group_compiler). Each joint with a target goes to its servo by the arm's
// Robot Commands map (couplings applied), rounded to whole servo units.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "arm/arm_model.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::arm {

// `targets`: one entry per joint of `model`, empty = the servo keeps where it is (left out of
// the action; a coupled joint's partner is then taken at 0). Refused: unsupported when a
// joint has no Robot Commands servo; invalid_argument naming the joint when its servo
// position falls outside 0..1000.
Result<robot_commands::GroupAction> servo_action(const ArmModel& model, const std::vector<std::optional<double>>& targets,
                                                 std::uint16_t time_ms);

}  // namespace armctl::arm
