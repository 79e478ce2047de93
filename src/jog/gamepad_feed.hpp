// One servo cycle of gamepad jogging (docs/gamepad.md): what the source has by now, through
// the mapping, into the servo mode's mailbox. The one place this happens, for `armctl jog`
// and the tests alike.
#pragma once

#include <string>
#include <vector>

#include "arm/servo_commands.hpp"
#include "jog/gamepad_jog.hpp"
#include "jog/gamepad_source.hpp"

namespace armctl::jog {

// Sends this cycle's command, or finishes `input` when the pad asks to quit (START held) or
// a replay has ended. Returns the lines for the user (a pad found or lost, a setting
// changed), in order.
std::vector<std::string> feed_gamepad(GamepadSource& source, GamepadJog& pad, arm::ServoInput& input,
                                      TimePoint now);

}  // namespace armctl::jog
