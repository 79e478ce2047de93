// Action-group notifications as the SDK delivers them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/clock.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace armctl::robot_commands {

// The protocol's kinds; the SDK tells a board's "finished" CMD 7 from the answer to our
// GroupStop (see Client), so `stopped` here means a stop this host asked for.
using rc::GroupEventKind;
using rc::to_string;

struct GroupEvent {
  GroupEventKind kind = GroupEventKind::started;
  std::optional<std::uint8_t> group;   // absent in the real-board no-DATA variants
  std::optional<std::uint16_t> count;  // absent in the real-board no-DATA variants
  // True for the real-board variants: CMD 6/7 without DATA, and CMD 7 meaning "finished"
  // (a CMD 7 that arrives when no GroupStop was sent since the group started).
  bool variant = false;
  TimePoint received{};
  bool operator==(const GroupEvent&) const = default;
};

// "group 2 finished (3 times)", "group stopped", ...
std::string describe(const GroupEvent& event);

}  // namespace armctl::robot_commands
