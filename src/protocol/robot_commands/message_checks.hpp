// Value checks shared by the encoders (refuse to send) and decoders (refuse to accept).
// Each returns a message naming the command, the field and what is allowed.
#pragma once

#include <optional>
#include <string>

#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc::checks {

using Problem = std::optional<std::string>;  // nothing = fine

Problem check(const MultiServoMove& m, const ServoRange& servos);
Problem check(const GroupDownloadBegin& m);
Problem check(const GroupDownloadServoCount& m, const ServoRange& servos);
Problem check(const GroupDownloadBlocks& m);
Problem check(const GroupDownloadAction& m, const ServoRange& servos);
Problem check(const GroupDownloadEnd& m);
Problem check(const GroupRun& m);
Problem check(const GroupErase& m);
Problem check(const GroupSpeed& m);
Problem check_servo_list(const char* command, const std::vector<std::uint8_t>& list,
                         const ServoRange& servos);
Problem check(const ServoOffsetAdjust& m, const ServoRange& servos);
Problem check(const ServoSpeed& m, const ServoRange& servos);
Problem check(const BusServoInfoWrite& m, const ServoRange& servos);
Problem check(const GroupDownloadAck& m);
Problem check(const ServoPositionReply& m);
Problem check(const ServoOffsetReply& m);

}  // namespace armctl::rc::checks
