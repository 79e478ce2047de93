// Plays one action group (GroupRun): each action is one synchronized move whose time is
// scaled by the group's speed (200 % = half the time), the next action starting when the
// previous move ends; `count` passes, or until stopped when count is 0.
//
// Time-driven, no threads: the Board asks next_event() and calls step() at exactly that
// time, so a coarse poll (or one big SimClock jump) still plays every action at its own
// instant.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/clock.hpp"
#include "devices/rc_board/action_group.hpp"
#include "devices/rc_board/arm_backend.hpp"

namespace armctl::rc_board {

// Time of an action at `percent` speed (percent >= 1).
Duration scaled_time(std::uint16_t milliseconds, std::uint16_t percent);

class GroupPlayer {
 public:
  struct Finished {
    GroupNumber group;
    std::uint16_t count;
  };

  void start(GroupNumber group, ActionGroup actions, std::uint16_t count, TimePoint now);
  void stop() { running_ = false; }
  bool running() const { return running_; }
  std::optional<GroupNumber> group() const {
    return running_ ? std::optional<GroupNumber>(group_) : std::nullopt;
  }
  std::uint32_t passes_done() const { return passes_; }
  std::size_t actions_skipped() const { return skipped_; }  // no longer fit, or refused
  std::size_t moves_refused() const { return refused_; }    // the arm refused the move
  // Why the last refused move was refused, naming the group and action.
  const std::string& last_refusal() const { return last_refusal_; }

  // When step() must run next (nothing while stopped).
  std::optional<TimePoint> next_event() const {
    return running_ ? std::optional<TimePoint>(next_at_) : std::nullopt;
  }
  // Does what is due at next_event(): plays one action, or ends a pass. The backend must
  // have been advanced to next_event(). Returns the run's end if it ended now.
  std::optional<Finished> step(ArmBackend& arm, std::uint16_t speed_percent);

 private:
  bool running_ = false;
  GroupNumber group_ = 0;
  ActionGroup actions_;
  std::uint16_t count_ = 0;
  std::uint32_t passes_ = 0;
  std::size_t index_ = 0;
  std::size_t skipped_ = 0;
  std::size_t refused_ = 0;
  std::string last_refusal_;
  TimePoint next_at_{};
};

}  // namespace armctl::rc_board
