// The debug log: lines for whoever debugs armctl, never part of normal output. On when the
// environment has ARMCTL_DEBUG set to anything but "" or "0"; then each line goes to stderr as
// "armctl: debug: LINE". Used where a value must stay hidden from normal output, e.g. the
// truth of a mis-assembled simulator (core/miscalibration.hpp), which a test reads through
// the simulator's API and a user must find out with the calibration wizard.
#pragma once

#include <string_view>

namespace armctl {

bool debug_log_enabled();
void debug_log(std::string_view line);  // nothing unless debug_log_enabled()

}  // namespace armctl
