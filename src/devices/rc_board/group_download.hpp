// GroupDownload (CMD 5, sub 1..5) as a board receives it, per the decisions in
// spec/robot-commands.md and docs/action-groups.md:
//
//   sub 1 begin(group, count)      count 1..1020; starts a new download (any download in
//                                  progress is abandoned)
//   sub 2 servo count n            1..servos of the arm, once, after sub 1
//   sub 3 blocks 0..k-1            k == rc::blocks_for_actions(count), once, after sub 2
//   sub 4 action (block, index)    after sub 3; block < k, index 0..254 and
//                                  block*255+index < count; n servos, each present, at most
//                                  once, position in its range or 0xFF00; time 0..30000.
//                                  A slot sent twice is overwritten (host retransmission).
//   sub 5 end                      every slot 0..count-1 received
//
// Every sub names the group; a different group than the download in progress is
// inconsistent. Any inconsistent request abandons the download: the stored group keeps
// its previous content, and the host must start again at sub 1.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "devices/rc_board/action_group.hpp"
#include "devices/rc_board/arm_backend.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::rc_board {

class GroupDownload {
 public:
  Status begin(const rc::GroupDownloadBegin& m);
  Status servo_count(const rc::GroupDownloadServoCount& m, const ArmBackend& arm);
  Status blocks(const rc::GroupDownloadBlocks& m);
  Status action(const rc::GroupDownloadAction& m, const ArmBackend& arm);
  // The complete group, ready to store; the download is over either way.
  Result<ActionGroup> end(const rc::GroupDownloadEnd& m);

  bool in_progress() const { return state_ != State::idle; }
  std::optional<GroupNumber> group() const {
    return in_progress() ? std::optional<GroupNumber>(group_) : std::nullopt;
  }
  void abandon() { state_ = State::idle; }

 private:
  enum class State { idle, begun, servo_count_known, blocks_known };
  Status fail(std::string message);
  Status check_group(const char* sub, std::uint8_t group, State wanted);

  State state_ = State::idle;
  GroupNumber group_ = 0;
  std::size_t count_ = 0;
  std::uint8_t servo_count_ = 0;
  std::size_t received_ = 0;
  std::vector<std::optional<Action>> slots_;
};

}  // namespace armctl::rc_board
