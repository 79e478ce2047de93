// Running an action group and knowing that it runs: a board answers nothing to a run it
// refuses (an empty or erased group), so only its 'started' notification says the group
// runs. run_group_started waits for it as long as a reply may take.
#pragma once

#include <cstdint>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"

namespace armctl::robot_commands {

// The detail of the error run_group_started returns when the board sent no 'started'
// notification in time (kind device): the group did not start. Apps map it to their own
// form (the HTTP API's 409).
struct GroupNotStarted {
  std::uint8_t group = 0;
  Duration waited{};  // how long the notification was waited for
};
inline const GroupNotStarted* group_not_started(const Error& error) { return error.detail_as<GroupNotStarted>(); }

// Runs `group` `times` times (0 = continuous) and waits for the board's 'started'.
Status run_group_started(Client& client, std::uint8_t group, std::uint16_t times);

}  // namespace armctl::robot_commands
