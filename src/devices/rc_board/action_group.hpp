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

inline constexpr std::uint16_t kLeaveAlone = 0xFF00;  // position: servo keeps its place
inline constexpr std::size_t kMaxActions = 1020;      // 4 blocks of 255
inline constexpr std::size_t kActionsPerBlock = 255;
inline constexpr std::size_t kMaxBlocks = 4;
inline constexpr GroupNumber kAllGroups = 255;   // GroupErase / GroupSpeed: every group
inline constexpr std::size_t kGroupCount = 255;  // groups 0..254 exist
inline constexpr std::uint16_t kMaxMoveMilliseconds = 30000;

struct Action {
  std::uint16_t milliseconds = 0;
  std::vector<ServoTarget> positions;  // position may be kLeaveAlone
  bool operator==(const Action&) const = default;
};

struct ActionGroup {
  std::uint8_t servo_count = 0;  // servos in every action (GroupDownload sub 2)
  std::vector<Action> actions;   // 1..kMaxActions
  bool operator==(const ActionGroup&) const = default;
};

// Blocks of 255 needed for `actions` actions (GroupDownload sub 3).
constexpr std::size_t blocks_for(std::size_t actions) {
  return (actions + kActionsPerBlock - 1) / kActionsPerBlock;
}

}  // namespace armctl::rc_board
