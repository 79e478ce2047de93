// An action group as the board keeps it: a numbered sequence of actions, each one
// MultiServoMove (time + servo positions). Shared by the download state machine, the store
// and playback.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "devices/rc_board/arm_backend.hpp"

namespace armctl::rc_board {

using GroupNumber = std::uint8_t;

// Groups 0..rc::kGroupMax exist; rc::kAllGroups (255) names every group.
inline constexpr std::size_t kGroupCount = std::size_t{rc::kGroupMax} + 1;

struct Action {
  std::uint16_t milliseconds = 0;
  std::vector<ServoTarget> positions;  // a target without a position: leave that servo alone
  bool operator==(const Action&) const = default;
};

struct ActionGroup {
  std::uint8_t servo_count = 0;  // servos in every action (GroupDownload sub 2)
  std::vector<Action> actions;   // 1..rc::kActionsMax
  bool operator==(const ActionGroup&) const = default;
};

}  // namespace armctl::rc_board
