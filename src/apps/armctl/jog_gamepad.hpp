// `armctl jog --gamepad` and `--gamepad-replay` (docs/gamepad.md): a gamepad's events
// (jog/gamepad_source.hpp) through the mapping (jog/gamepad_jog.hpp) into a jog session.
#pragma once

#include <memory>
#include <string>

#include "apps/armctl/jog_session.hpp"
#include "arm/arm_model.hpp"

namespace armctl::cli {

// `device`: "auto" or /dev/input/eventN; `replay`: a recording's path. Exactly one is
// non-empty. Throws ArmctlError when the device or the recording cannot be used.
std::unique_ptr<JogDriver> gamepad_driver(const arm::ArmModel& model, const std::string& device,
                                          const std::string& replay);

}  // namespace armctl::cli
