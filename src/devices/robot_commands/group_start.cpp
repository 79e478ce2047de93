#include "devices/robot_commands/group_start.hpp"

#include <chrono>

#include <fmt/core.h>

namespace armctl::robot_commands {

Status run_group_started(Client& client, std::uint8_t group, std::uint16_t times) {
  if (auto st = client.run_group(group, times); !st) return st;
  const Duration waited = client.options().reply_timeout;
  const TimePoint deadline = client.clock().now() + waited;
  for (;;) {
    auto e = client.wait_event(deadline);
    if (!e) {
      if (e.error().kind != ErrorKind::timeout) return e.error();
      return Error{ErrorKind::device,
                   fmt::format("group {} did not start: the board sent no 'started' notification within {} ms "
                               "(is group {} empty on this board? download it first)",
                               group, std::chrono::duration_cast<std::chrono::milliseconds>(waited).count(), group),
                   GroupNotStarted{group, waited}};
    }
    if (e->kind == GroupEventKind::started) return Ok{};
  }
}

}  // namespace armctl::robot_commands
