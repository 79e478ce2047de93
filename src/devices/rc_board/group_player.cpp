#include "devices/rc_board/group_player.hpp"

#include <algorithm>
#include <vector>

namespace armctl::rc_board {

// A pass over actions that all take 0 ms must still let time pass, or a continuous run
// would spin forever inside one step; 1 ms is well below any servo's reaction time.
constexpr Duration kMinimumActionTime = std::chrono::milliseconds(1);

Duration scaled_time(std::uint16_t milliseconds, std::uint16_t percent) {
  auto ns = std::chrono::nanoseconds(std::chrono::milliseconds(milliseconds)).count();
  return Duration{ns * 100 / std::max<std::uint16_t>(percent, 1)};
}

void GroupPlayer::start(GroupNumber group, ActionGroup actions, std::uint16_t count,
                        TimePoint now) {
  running_ = true;
  group_ = group;
  actions_ = std::move(actions);
  count_ = count;
  passes_ = 0;
  index_ = 0;
  next_at_ = now;
}

std::optional<GroupPlayer::Finished> GroupPlayer::step(ArmBackend& arm,
                                                       std::uint16_t speed_percent) {
  if (!running_) return std::nullopt;
  if (index_ == actions_.actions.size()) {  // the last move of a pass has ended
    ++passes_;
    index_ = 0;
    if (count_ != 0 && passes_ >= count_) {
      running_ = false;
      return Finished{group_, count_};
    }
  }
  const Action& action = actions_.actions[index_++];
  // Limits may have changed since the download: an action that no longer fits is skipped
  // whole (no partial move), like a refused MultiServoMove.
  std::vector<ServoTarget> targets;
  bool valid = true;
  for (const ServoTarget& t : action.positions) {
    if (!t.position) continue;  // leave this servo alone
    if (!arm.has_servo(t.servo) || !arm.position_range(t.servo).contains(*t.position)) valid = false;
    targets.push_back(t);
  }
  Duration wanted = scaled_time(action.milliseconds, speed_percent);
  Duration took = wanted;
  if (!valid) {
    ++skipped_;
  } else if (!targets.empty()) {
    auto moved = arm.move(targets, wanted, next_at_);
    if (moved) {
      took = *moved;
    } else {  // the arm refused (e.g. a joint not answering): nothing moved, the group goes on
      ++skipped_;
      ++refused_;
      last_refusal_ = "group " + std::to_string(group_) + " action " + std::to_string(index_) +
                      ": move refused: " + moved.error().message;
    }
  }
  next_at_ += std::max(took, kMinimumActionTime);
  return std::nullopt;
}

}  // namespace armctl::rc_board
