#include "devices/rc_board/group_download.hpp"

#include <fmt/core.h>

namespace armctl::rc_board {
namespace {

const char* state_name(int s) {
  static const char* names[] = {"no download in progress", "after sub 1", "after sub 2",
                                "after sub 3"};
  return names[s];
}

}  // namespace

Status GroupDownload::fail(std::string message) {
  state_ = State::idle;
  slots_.clear();
  return Error{ErrorKind::protocol, "GroupDownload: " + std::move(message) +
                                        " (download abandoned; stored group unchanged)"};
}

Status GroupDownload::check_group(const char* sub, std::uint8_t group, State wanted) {
  if (state_ == State::idle)
    return fail(fmt::format("{} for group {} without a sub 1", sub, group));
  if (group != group_)
    return fail(
        fmt::format("{} names group {} but group {} is being downloaded", sub, group, group_));
  if (state_ != wanted)
    return fail(fmt::format("{} arrived {}; allowed only {}", sub,
                            state_name(static_cast<int>(state_)),
                            state_name(static_cast<int>(wanted))));
  return Ok{};
}

Status GroupDownload::begin(const rc::GroupDownloadBegin& m) {
  state_ = State::idle;
  if (m.group >= kGroupCount) return fail(fmt::format("sub 1: group {} not in 0..254", m.group));
  if (m.action_count < 1 || m.action_count > rc::kActionsMax)
    return fail(fmt::format("sub 1: action count {} not in 1..{}", m.action_count, rc::kActionsMax));
  group_ = m.group;
  count_ = m.action_count;
  servo_count_ = 0;
  received_ = 0;
  slots_.assign(count_, std::nullopt);
  state_ = State::begun;
  return Ok{};
}

Status GroupDownload::servo_count(const rc::GroupDownloadServoCount& m, const ArmBackend& arm) {
  if (auto s = check_group("sub 2", m.group, State::begun); !s) return s;
  if (m.servo_count < 1 || m.servo_count > arm.servos().size())
    return fail(fmt::format("sub 2: {} servos per action; this arm has 1..{}", m.servo_count,
                            arm.servos().size()));
  servo_count_ = m.servo_count;
  state_ = State::servo_count_known;
  return Ok{};
}

Status GroupDownload::blocks(const rc::GroupDownloadBlocks& m) {
  if (auto s = check_group("sub 3", m.group, State::servo_count_known); !s) return s;
  if (m.block_count != rc::blocks_for_actions(count_))
    return fail(fmt::format("sub 3: {} blocks listed but {} actions need {}", m.block_count, count_,
                            rc::blocks_for_actions(count_)));
  state_ = State::blocks_known;
  return Ok{};
}

Status GroupDownload::action(const rc::GroupDownloadAction& m, const ArmBackend& arm) {
  if (auto s = check_group("sub 4", m.group, State::blocks_known); !s) return s;
  std::size_t slot = std::size_t{m.block} * rc::kActionsPerBlock + m.index;
  if (m.block >= rc::blocks_for_actions(count_) || m.index >= rc::kActionsPerBlock || slot >= count_)
    return fail(fmt::format("sub 4: block {} index {} is outside the {} actions announced", m.block,
                            m.index, count_));
  if (m.targets.size() != servo_count_)
    return fail(fmt::format("sub 4: action has {} servos but sub 2 announced {}", m.targets.size(),
                            servo_count_));
  if (m.time_ms > rc::kMoveTimeMaxMs)
    return fail(fmt::format("sub 4: time {} ms not in 0..30000", m.time_ms));
  Action action{m.time_ms, {}};
  for (const rc::ServoTarget& t : m.targets) {
    if (!arm.has_servo(t.servo))
      return fail(fmt::format("sub 4: servo {} is not present", t.servo));
    for (const ServoTarget& seen : action.positions)
      if (seen.servo == t.servo)
        return fail(fmt::format("sub 4: servo {} appears twice in one action", t.servo));
    if (t.position) {  // none: leave this servo alone
      PositionRange range = arm.position_range(t.servo);
      if (!range.contains(*t.position))
        return fail(fmt::format("sub 4: servo {} position {} outside its range {}..{}", t.servo,
                                *t.position, range.min, range.max));
    }
    action.positions.push_back(t);
  }
  if (!slots_[slot]) ++received_;
  slots_[slot] = std::move(action);
  return Ok{};
}

Result<ActionGroup> GroupDownload::end(const rc::GroupDownloadEnd& m) {
  if (auto s = check_group("sub 5", m.group, State::blocks_known); !s) return s.error();
  if (received_ != count_) {
    std::size_t missing = 0;
    while (slots_[missing]) ++missing;
    return fail(fmt::format("sub 5: {} of {} actions received (first missing: block {} index {})",
                            received_, count_, missing / rc::kActionsPerBlock,
                            missing % rc::kActionsPerBlock))
        .error();
  }
  ActionGroup group{servo_count_, {}};
  group.actions.reserve(count_);
  for (auto& slot : slots_) group.actions.push_back(std::move(*slot));
  state_ = State::idle;
  slots_.clear();
  return group;
}

}  // namespace armctl::rc_board
