// `armctl jog --gamepad` and `--gamepad-replay` (docs/gamepad.md): a gamepad's events
// (jog/gamepad_source.hpp) through the mapping (jog/gamepad_jog.hpp) into a jog session.
#pragma once

#include <memory>
#include <string>

#include "apps/armctl/jog_session.hpp"
#include "arm/arm_model.hpp"

namespace armctl::cli {

// `device`: "auto" or /dev/input/eventN; `replay`: a recording's path. Exactly one is
// non-empty. `record`: where to write what the pad did (empty: nowhere), checked writable
// now and written when the session is over. Throws ArmctlError when the device, the
// recording or the file to record to cannot be used.
std::unique_ptr<JogDriver> gamepad_driver(const arm::ArmModel& model, const std::string& device,
                                          const std::string& replay, const std::string& record);

}  // namespace armctl::cli
